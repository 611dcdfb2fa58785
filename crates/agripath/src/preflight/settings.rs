//! What a plan is held to by the preflight: the mission settings it was written with and the
//! coverage and spray-outside limits drawn from its own measure (decision 0012).

use super::MAX_OUTSIDE_FRACTION;
use crate::mission::flight::{AltitudeReference, MissionSettings, SprayerCommand};

/// What the plan promised.
#[derive(Debug, Clone, PartialEq)]
pub struct PreflightSettings {
    /// How the files write altitudes.
    pub altitude: AltitudeReference,
    /// How the files switch the sprayer.
    pub sprayer: SprayerCommand,
    /// Largest gap allowed between the spray altitude flown and terrain + spray height, metres.
    pub terrain_tolerance_m: f64,
    /// Where a plan in local metres lies on Earth (lon, lat of its origin, degrees).
    pub local_origin: (f64, f64),
    /// Distance the plan kept from field boundaries, metres (it shapes the sprayable region).
    pub boundary_margin_m: f64,
    /// Distance the plan kept from obstacles, metres (no spraying within it).
    pub obstacle_margin_m: f64,
    /// Least share of each field's sprayable area to cover, 0..1, by field.
    pub required_coverage: Vec<f64>,
    /// Most sprayed area outside the fields, as a share of the sprayed area.
    pub max_outside_fraction: f64,
}

/// What a plan promised by its own measure, which the coverage and spray-outside limits are
/// drawn from.
#[derive(Debug, Clone, PartialEq)]
pub struct Promise {
    /// Edge passes around each boundary and hole; 0 is the seed's layout.
    pub headland_passes: usize,
    /// Whether the edge passes end where the core first ends (`--edge-cut gap`), leaving the
    /// sliver between them unsprayed by choice.
    pub edge_gaps: bool,
    /// Per field, the share of its sprayable area the plan's measure covers.
    pub covered_fraction: Vec<f64>,
    /// Strip area the plan's measure puts outside the sprayable region, m².
    pub outside_m2: f64,
    /// Swath and edge-pass metres × swath width, m².
    pub sprayed_m2: f64,
}

impl PreflightSettings {
    /// The settings a plan is held to (decision 0012). With edge passes: 99 % of each field
    /// and at most [`MAX_OUTSIDE_FRACTION`] outside. The seed's layout (`--headland 0`)
    /// leaves 2-4 % at oblique swath ends and runs swaths to the boundary, half a swath
    /// overhanging it: it is held to its own coverage less ½ point and its own overhang plus
    /// 0.1 point. `--edge-cut gap` leaves its gaps by the operator's choice: it is held to
    /// its own coverage less ½ point where that is under 99 % (trial 7: a plain rectangle
    /// planned with it covered 98.93 % and failed).
    pub fn new(
        mission: &MissionSettings,
        boundary_margin_m: f64,
        obstacle_margin_m: f64,
        promise: &Promise,
    ) -> Self {
        let seed_layout = promise.headland_passes == 0;
        Self {
            altitude: mission.altitude,
            sprayer: mission.sprayer,
            terrain_tolerance_m: mission.terrain_tolerance_m,
            local_origin: mission.local_origin,
            boundary_margin_m,
            obstacle_margin_m,
            required_coverage: promise
                .covered_fraction
                .iter()
                .map(|&covered| {
                    if seed_layout {
                        (covered - 0.005).max(0.0)
                    } else if promise.edge_gaps {
                        (covered - 0.005).clamp(0.0, 0.99)
                    } else {
                        0.99
                    }
                })
                .collect(),
            max_outside_fraction: if seed_layout && promise.sprayed_m2 > 0.0 {
                MAX_OUTSIDE_FRACTION.max(promise.outside_m2 / promise.sprayed_m2 + 0.001)
            } else {
                MAX_OUTSIDE_FRACTION
            },
        }
    }
}

/// What the flight is flown against.
pub struct World<'a> {
    /// The farm: its fields, obstacles and coordinate system.
    pub farm: &'a crate::model::Farm,
    /// The terrain the flight is flown over.
    pub terrain: &'a dyn crate::terrain::Terrain,
    /// The drone: heights, speeds, swath width, tank and battery.
    pub vehicle: &'a crate::model::Vehicle,
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Edge passes hold a field to 99 %; `--edge-cut gap`, whose gaps are the operator's
    /// choice, to its own coverage − ½ point (never more than 99 %); the seed's layout too.
    #[test]
    fn the_coverage_required_follows_the_layout_chosen() {
        let required = |headland_passes: usize, edge_gaps: bool, covered: f64| {
            let promise = Promise {
                headland_passes,
                edge_gaps,
                covered_fraction: vec![covered],
                outside_m2: 0.0,
                sprayed_m2: 1.0,
            };
            PreflightSettings::new(&MissionSettings::default(), 0.0, 0.0, &promise)
                .required_coverage[0]
        };
        assert_eq!(required(1, false, 0.9893), 0.99);
        assert!((required(1, true, 0.9893) - 0.9843).abs() < 1e-12);
        assert_eq!(required(1, true, 0.9999), 0.99);
        assert!((required(0, false, 0.97) - 0.965).abs() < 1e-12);
    }
}
