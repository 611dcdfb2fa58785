//! Level ground with circular plateaus: seed 001's S4 holds a 3 m plateau of radius 35 m that
//! is sprayed over. The edge rises linearly over `edge_ramp_m` (our choice; the paper's DEM
//! has 20 m spacing and does not say how steep the edge is).

use super::{Extent, Terrain};
use crate::error::{Fault, TerrainError};

pub use crate::model::terrain_spec::Plateau;

/// Level ground at `base_m` with circular plateaus standing on it.
#[derive(Debug, Clone, PartialEq)]
pub struct Plateaus {
    base_m: f64,
    plateaus: Vec<Plateau>,
}

impl Plateaus {
    /// The terrain; errs when a number is not finite, a radius is not above 0 or a ramp is negative.
    pub fn new(base_m: f64, plateaus: Vec<Plateau>) -> Result<Self, Fault> {
        if !base_m.is_finite() {
            return Err(Fault::NonFinite);
        }
        for plateau in &plateaus {
            let numbers = [
                plateau.center[0],
                plateau.center[1],
                plateau.radius_m,
                plateau.height_m,
                plateau.edge_ramp_m,
            ];
            if numbers.iter().any(|number| !number.is_finite()) {
                return Err(Fault::NonFinite);
            }
            if plateau.radius_m <= 0.0 || plateau.edge_ramp_m < 0.0 {
                return Err(Fault::InvalidValue {
                    what: "plateau radius_m / edge_ramp_m".into(),
                    value: format!("{} / {}", plateau.radius_m, plateau.edge_ramp_m),
                    why: "the radius must be above 0 and the ramp 0 or more".into(),
                });
            }
        }
        Ok(Self { base_m, plateaus })
    }
}

impl Terrain for Plateaus {
    fn height_m(&self, x: f64, y: f64) -> Result<f64, TerrainError> {
        let rise = self
            .plateaus
            .iter()
            .map(|plateau| {
                let (dx, dy) = (x - plateau.center[0], y - plateau.center[1]);
                // Most samples lie well inside a plateau's top or well beyond its ramp: there
                // the squared distance decides, without `hypot` (5 % of a demo run's samples,
                // 1.4 points of them in planning, the battery reserve's terrain sampling). Near either edge, within
                // a relative 1e-9 that rounding cannot cross, the distance decides as before,
                // so every height is the same to the bit.
                let squared = dx * dx + dy * dy;
                let outer = plateau.radius_m + plateau.edge_ramp_m;
                if squared > (outer * (1.0 + 1e-9)).powi(2) {
                    return 0.0;
                }
                if squared < (plateau.radius_m * (1.0 - 1e-9)).powi(2) {
                    return plateau.height_m;
                }
                let distance = dx.hypot(dy);
                if distance <= plateau.radius_m {
                    plateau.height_m
                } else if distance < plateau.radius_m + plateau.edge_ramp_m {
                    plateau.height_m * (1.0 - (distance - plateau.radius_m) / plateau.edge_ramp_m)
                } else {
                    0.0
                }
            })
            .fold(0.0, f64::max);
        Ok(self.base_m + rise)
    }

    fn extent(&self) -> Option<Extent> {
        None
    }

    /// Where the segment crosses each plateau's top edge and foot (the ramp bends there) and
    /// where it passes closest to the centre (the highest point of a crossing of the ramp).
    fn bends_along(&self, from: (f64, f64), to: (f64, f64)) -> Vec<f64> {
        let (dx, dy) = (to.0 - from.0, to.1 - from.1);
        let length_squared = dx * dx + dy * dy;
        if length_squared <= 0.0 {
            return Vec::new();
        }
        let mut bends = Vec::new();
        for plateau in &self.plateaus {
            let (cx, cy) = (from.0 - plateau.center[0], from.1 - plateau.center[1]);
            // |from + t·d − centre|² = r²: t² L + 2 t (c·d) + |c|² − r² = 0.
            let half_b = cx * dx + cy * dy;
            let mut crosses = false;
            for radius in [plateau.radius_m, plateau.radius_m + plateau.edge_ramp_m] {
                let discriminant =
                    half_b * half_b - length_squared * (cx * cx + cy * cy - radius * radius);
                if discriminant > 0.0 {
                    let root = discriminant.sqrt();
                    bends.push((-half_b - root) / length_squared);
                    bends.push((-half_b + root) / length_squared);
                    crosses = true;
                }
            }
            // The closest approach, only where the line meets the plateau at all.
            if crosses {
                bends.push(-half_b / length_squared);
            }
        }
        bends.retain(|t| *t > 0.0 && *t < 1.0);
        bends.sort_by(f64::total_cmp);
        bends.dedup();
        bends
    }

    fn describe(&self) -> String {
        format!(
            "ground at {} m with {} plateau(s) up to {} m",
            self.base_m,
            self.plateaus.len(),
            self.plateaus
                .iter()
                .map(|plateau| plateau.height_m)
                .fold(0.0, f64::max)
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn top_ramp_and_base() {
        let terrain = Plateaus::new(
            1.0,
            vec![Plateau {
                center: [0.0, 0.0],
                radius_m: 10.0,
                height_m: 3.0,
                edge_ramp_m: 4.0,
            }],
        )
        .unwrap();
        assert_eq!(terrain.height_m(5.0, 0.0), Ok(4.0));
        assert_eq!(terrain.height_m(12.0, 0.0), Ok(2.5));
        assert_eq!(terrain.height_m(20.0, 0.0), Ok(1.0));
    }

    #[test]
    fn the_squared_shortcut_gives_the_distance_rules_heights_to_the_bit() {
        let plateaus = vec![
            Plateau {
                center: [3.0, -7.0],
                radius_m: 10.0,
                height_m: 3.0,
                edge_ramp_m: 4.0,
            },
            Plateau {
                center: [30.0, 11.0],
                radius_m: 2.0,
                height_m: 5.0,
                edge_ramp_m: 1.0,
            },
        ];
        let terrain = Plateaus::new(0.5, plateaus.clone()).unwrap();
        let by_distance = |x: f64, y: f64| {
            let rise = plateaus
                .iter()
                .map(|plateau| {
                    let distance = (x - plateau.center[0]).hypot(y - plateau.center[1]);
                    if distance <= plateau.radius_m {
                        plateau.height_m
                    } else if distance < plateau.radius_m + plateau.edge_ramp_m {
                        plateau.height_m
                            * (1.0 - (distance - plateau.radius_m) / plateau.edge_ramp_m)
                    } else {
                        0.0
                    }
                })
                .fold(0.0, f64::max);
            0.5 + rise
        };
        // A lattice through both plateaus, their edges and their centres, and points on the
        // circles themselves.
        let mut points = Vec::new();
        for i in -200..=200 {
            for j in -200..=200 {
                points.push((f64::from(i) * 0.237, f64::from(j) * 0.193));
                points.push((30.0 + f64::from(i) * 0.0171, 11.0 + f64::from(j) * 0.0163));
            }
        }
        for k in 0..3600 {
            let angle = f64::from(k).to_radians() / 10.0;
            for radius in [10.0, 14.0, 10.0 + 1e-12, 14.0 - 1e-12] {
                points.push((3.0 + radius * angle.cos(), -7.0 + radius * angle.sin()));
            }
            for radius in [2.0, 3.0, 2.0 + 1e-12, 3.0 - 1e-12] {
                points.push((30.0 + radius * angle.cos(), 11.0 + radius * angle.sin()));
            }
        }
        assert_eq!(points.len(), 2 * 401 * 401 + 2 * 4 * 3600);
        points.push((30.0, 11.0));
        for (x, y) in points {
            assert_eq!(
                terrain.height_m(x, y).unwrap().to_bits(),
                by_distance(x, y).to_bits(),
                "at ({x}, {y})"
            );
        }
    }
}
