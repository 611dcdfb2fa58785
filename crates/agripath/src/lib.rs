//! agripath: mission planning for agricultural UAVs over real terrain.
//!
//! The data flows one way (see `docs/architecture.md`): inputs ([`input`], [`terrain`]) become
//! validated models ([`model`]), which the planning stages turn into missions.

pub mod demo;
pub mod error;
pub mod geometry;
pub mod input;
pub mod model;
pub mod output;
pub mod summary;
pub mod terrain;

pub use error::{Fault, InputError, TerrainError};
