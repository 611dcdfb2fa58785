//! Plan metres ↔ longitude, latitude, for writing mission files and reading them back.

use crate::geometry::{from_utm, to_utm, UtmZone};
use crate::model::CoordinateSystem;

/// Plan metres → longitude, latitude.
#[derive(Debug, Clone, Copy)]
pub struct GeoFrame {
    system: CoordinateSystem,
    /// For local plans: the zone and UTM position of the origin.
    local: Option<(UtmZone, f64, f64)>,
}

impl GeoFrame {
    /// The frame of a plan in `system`; `local_origin` (lon, lat, degrees) places a local
    /// plan's origin on Earth and is ignored otherwise.
    pub fn new(system: CoordinateSystem, local_origin: (f64, f64)) -> Self {
        let local = (system == CoordinateSystem::Local).then(|| {
            let zone = UtmZone::containing(local_origin.0, local_origin.1);
            let (easting, northing) = to_utm(local_origin.0, local_origin.1, zone);
            (zone, easting, northing)
        });
        Self { system, local }
    }

    /// Plan metres (x, y) → longitude, latitude, degrees.
    pub fn lon_lat(&self, x: f64, y: f64) -> (f64, f64) {
        match self.local {
            Some((zone, easting, northing)) => from_utm(easting + x, northing + y, zone),
            None => self.system.to_input(x, y),
        }
    }

    /// Longitude, latitude → plan metres: the inverse of [`GeoFrame::lon_lat`], for reading
    /// mission files back.
    pub fn plan_xy(&self, lon: f64, lat: f64) -> (f64, f64) {
        match self.local {
            Some((zone, easting, northing)) => {
                let (x, y) = to_utm(lon, lat, zone);
                (x - easting, y - northing)
            }
            None => self.system.to_plan(lon, lat),
        }
    }

    /// A place as the user's input gives it: lon/lat for lon/lat input, metres for local.
    pub fn describe(&self, x: f64, y: f64) -> String {
        match self.system {
            CoordinateSystem::Local => format!("({x:.1}, {y:.1})"),
            CoordinateSystem::Utm(_) => {
                let (lon, lat) = self.lon_lat(x, y);
                format!("({lon:.6}, {lat:.6})")
            }
        }
    }
}
