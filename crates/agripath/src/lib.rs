//! agripath: mission planning for agricultural UAVs over real terrain.
//!
//! The data flows one way (see `docs/architecture.md`): inputs ([`input`], [`terrain`]) become
//! validated models ([`model`]), which the planning stages turn into missions.

#![warn(missing_docs)]

pub mod bench;
pub mod coverage;
pub mod demo;
pub mod error;
pub mod files;
pub mod geometry;
pub mod grid_cover;
pub mod input;
pub mod limits;
pub mod mission;
pub mod model;
pub mod numbers;
pub mod output;
pub mod parallel;
pub mod pipeline;
pub mod plot;
pub mod preflight;
pub mod progress;
pub mod report;
pub mod repro;
pub mod request;
pub mod scenario;
pub mod sequence;
pub mod settings;
pub mod sheet;
pub mod sortie;
pub mod summary;
pub mod supply;
pub mod terrain;
pub mod track;
pub mod view;

pub use error::{Fault, InputError, TerrainError};
