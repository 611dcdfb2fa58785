//! The composite mountain terrain of seed 000 (eq. 16) and seed 002 (eq. 1).
//!
//! z1(x, y) = sin(y + a) + b·sin(x) + c·cos(d·√(x² + y²)) + e·cos(y) + f·sin(g·√(x² + y²))
//! z2(x, y) = Σᵢ hᵢ · exp(−((x − xᵢ)/x_sᵢ)² − ((y − yᵢ)/y_sᵢ)²)
//! z(x, y)  = max(z1, z2)
//!
//! Deviations from the paper (contract decision 6, docs/contract.md): z1 follows seed 002's eq. (1), since
//! seed 000's eq. (16) misprints the f and g terms; the seventh y_s, missing in print, is 200.
//! Seed 002 gives no coefficients: its 1000 × 1000 × 60 m space uses seed 000's terrain with
//! heights scaled by 0.5 (documented in `docs/decisions/0003-terrain.md`).

use super::{Extent, Terrain};
use crate::error::TerrainError;

/// One Gaussian hill of z2.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Hill {
    /// hᵢ: height of the peak, metres.
    pub height_m: f64,
    /// xᵢ: x of the peak, metres.
    pub x_m: f64,
    /// yᵢ: y of the peak, metres.
    pub y_m: f64,
    /// x_sᵢ: spread along x, metres.
    pub spread_x_m: f64,
    /// y_sᵢ: spread along y, metres.
    pub spread_y_m: f64,
}

/// The composite terrain z = max(z1, z2), scaled.
#[derive(Debug, Clone, PartialEq)]
pub struct Composite {
    /// Coefficients a..g of z1.
    pub coefficients: [f64; 7],
    /// The Gaussian hills of z2.
    pub hills: Vec<Hill>,
    /// Factor applied to every height (1 for seed 000, 0.5 for seed 002).
    pub height_scale: f64,
    /// Where the terrain is defined; queries outside it fail.
    pub extent: Extent,
}

impl Composite {
    /// Seed 000's orchard: coefficients and hills of `data/seed000_orchard.json`, 1000 × 1000 m.
    pub fn seed000() -> Self {
        let heights = [40.0, 50.0, 40.0, 40.0, 50.0, 40.0, 40.0];
        let xs = [100.0, 600.0, 430.0, 160.0, 400.0, 300.0, 500.0];
        let ys = [1000.0, 110.0, 300.0, 850.0, 600.0, 700.0, 500.0];
        let spread_x = [300.0, 200.0, 200.0, 400.0, 300.0, 200.0, 400.0];
        let spread_y = [200.0, 200.0, 200.0, 200.0, 200.0, 200.0, 300.0];
        let hills = (0..7)
            .map(|index| Hill {
                height_m: heights[index],
                x_m: xs[index],
                y_m: ys[index],
                spread_x_m: spread_x[index],
                spread_y_m: spread_y[index],
            })
            .collect();
        Self {
            coefficients: [10.0, 0.2, 0.1, 0.6, 1.0, 0.1, 0.1],
            hills,
            height_scale: 1.0,
            extent: Extent {
                min_x: 0.0,
                min_y: 0.0,
                max_x: 1000.0,
                max_y: 1000.0,
            },
        }
    }

    /// Seed 002's survey space: seed 000's terrain with heights × 0.5 (peaks near 61 m, above its 60 m ceiling).
    pub fn seed002() -> Self {
        Self {
            height_scale: 0.5,
            ..Self::seed000()
        }
    }

    /// z = max(z1, z2), unscaled, at any (x, y).
    fn raw_height(&self, x: f64, y: f64) -> f64 {
        let [a, b, c, d, e, f, g] = self.coefficients;
        let radius = (x * x + y * y).sqrt();
        let z1 = (y + a).sin()
            + b * x.sin()
            + c * (d * radius).cos()
            + e * y.cos()
            + f * (g * radius).sin();
        let z2: f64 = self
            .hills
            .iter()
            .map(|hill| {
                let dx = (x - hill.x_m) / hill.spread_x_m;
                let dy = (y - hill.y_m) / hill.spread_y_m;
                hill.height_m * (-dx * dx - dy * dy).exp()
            })
            .sum();
        z1.max(z2)
    }
}

impl Terrain for Composite {
    fn height_m(&self, x: f64, y: f64) -> Result<f64, TerrainError> {
        if !self.extent.contains(x, y) {
            return Err(TerrainError::Outside { x, y });
        }
        Ok(self.height_scale * self.raw_height(x, y))
    }

    fn extent(&self) -> Option<Extent> {
        Some(self.extent)
    }

    fn describe(&self) -> String {
        format!(
            "composite terrain of seed 000 (7 hills, heights × {}) over {} × {} m",
            self.height_scale,
            self.extent.width(),
            self.extent.height()
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn peaks_and_formula() {
        let terrain = Composite::seed000();
        // At the centre of the 50 m hill at (600, 110) the neighbouring hills (430, 300) and
        // (500, 500) add their flanks.
        let peak = terrain.height_m(600.0, 110.0).unwrap();
        assert!((50.0..70.0).contains(&peak), "{peak}");
        // Far from every hill z1 wins; check it by hand at the origin corner (x = y = 0):
        // z1 = sin(10) + 0 + 0.1·cos(0) + 1·cos(0) + 0 = sin(10) + 1.1.
        let hills_at_origin: f64 = terrain
            .hills
            .iter()
            .map(|hill| {
                let dx = hill.x_m / hill.spread_x_m;
                let dy = hill.y_m / hill.spread_y_m;
                hill.height_m * (-dx * dx - dy * dy).exp()
            })
            .sum();
        let expected = (10.0f64.sin() + 1.1).max(hills_at_origin);
        assert!((terrain.height_m(0.0, 0.0).unwrap() - expected).abs() < 1e-12);
        assert!(terrain.height_m(-1.0, 0.0).is_err());
        let scaled = Composite::seed002().height_m(600.0, 110.0).unwrap();
        assert!((scaled - 0.5 * peak).abs() < 1e-9);
    }
}
