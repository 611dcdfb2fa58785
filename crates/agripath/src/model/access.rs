//! Access features: where a vehicle (the crew's truck, the mixing trailer, the battery
//! charger) can drive and stand: roads and tracks drawn as lines, yards drawn as areas
//! (`properties.kind = "access"` in GeoJSON, the same ExtendedData `kind` or a Folder named
//! "access" in KML). They are not sprayed; the supply point is chosen on them when the field
//! file has any (docs/decisions/0016-supply-point.md).

use geo::{Coord, LineString, Polygon};

/// The shape of an access feature, in planning metres.
#[derive(Debug, Clone, PartialEq)]
pub enum AccessShape {
    /// A road or track: at least two distinct points.
    Line(LineString<f64>),
    /// A yard or a parking area: a valid polygon (holes allowed).
    Area(Polygon<f64>),
}

/// One access feature of the field file.
#[derive(Debug, Clone, PartialEq)]
pub struct Access {
    /// The feature's name from the file, or "access N".
    pub name: String,
    /// Its line or area.
    pub shape: AccessShape,
}

impl Access {
    /// Every point of the feature's outline (a line's points; an area's rings), metres.
    pub fn points(&self) -> Box<dyn Iterator<Item = Coord<f64>> + '_> {
        match &self.shape {
            AccessShape::Line(line) => Box::new(line.0.iter().copied()),
            AccessShape::Area(polygon) => {
                Box::new(crate::geometry::rings(polygon).flatten().copied())
            }
        }
    }
}
