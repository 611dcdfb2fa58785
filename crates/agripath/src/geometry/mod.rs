//! Planar geometry in a local metric frame: projection to and from UTM, polygon validity.

pub mod detour;
pub mod projection;
pub mod validate;

pub use projection::{from_utm, to_utm, UtmZone};
