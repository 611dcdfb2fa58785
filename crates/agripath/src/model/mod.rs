//! The validated inputs of a plan as data: the farm (fields, obstacles, access features), the
//! vehicle, the terrain as described. Reading them is `input`'s and `terrain`'s; `scenario` puts
//! them together.

pub mod access;
pub mod field;
pub mod terrain_spec;
pub mod vehicle;

pub use access::{Access, AccessShape};
pub use field::{CoordinateSystem, Farm, Field, Marker, Obstacle};
pub use vehicle::Vehicle;
