//! The validated inputs of a plan: the farm (fields, obstacles), the vehicle, the scenario.

pub mod field;
pub mod limits;
pub mod scenario;
pub mod vehicle;

pub use field::{CoordinateSystem, Farm, Field, Marker, Obstacle};
pub use scenario::Scenario;
pub use vehicle::Vehicle;
