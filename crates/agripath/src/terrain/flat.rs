//! Level ground.

use super::{Extent, Terrain};
use crate::error::TerrainError;

/// Level ground at one height everywhere.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Flat {
    height_m: f64,
}

impl Flat {
    /// Level ground at `height_m` above sea level, metres.
    pub fn new(height_m: f64) -> Self {
        Self { height_m }
    }
}

impl Terrain for Flat {
    fn height_m(&self, _x: f64, _y: f64) -> Result<f64, TerrainError> {
        Ok(self.height_m)
    }

    fn extent(&self) -> Option<Extent> {
        None
    }

    fn describe(&self) -> String {
        format!("flat ground at {} m", self.height_m)
    }
}
