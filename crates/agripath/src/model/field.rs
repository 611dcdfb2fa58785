//! Fields, obstacles and the farm they make, in a local metric frame.

use std::path::PathBuf;

use geo::{Area, BoundingRect, Coord, Polygon, Rect};

use crate::geometry::{from_utm, UtmZone};
use crate::terrain::TerrainSpec;

/// The frame the plan is computed in, and the one outputs go back to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CoordinateSystem {
    /// Metres in the input's own local frame (x east, y north); outputs stay in it.
    Local,
    /// The input was WGS84 longitude/latitude; it is planned in this UTM zone and outputs are
    /// projected back to longitude/latitude.
    Utm(UtmZone),
}

impl CoordinateSystem {
    /// A planning-frame position back in the input's coordinate system ([lon, lat] or [x, y]).
    pub fn to_input(self, x: f64, y: f64) -> (f64, f64) {
        match self {
            Self::Local => (x, y),
            Self::Utm(zone) => from_utm(x, y, zone),
        }
    }

    /// A position given in the input's coordinate system, in the planning frame.
    pub fn to_plan(self, a: f64, b: f64) -> (f64, f64) {
        match self {
            Self::Local => (a, b),
            Self::Utm(zone) => crate::geometry::to_utm(a, b, zone),
        }
    }

    pub fn describe(self) -> String {
        match self {
            Self::Local => "local metres".to_string(),
            Self::Utm(zone) => format!(
                "WGS84 lon/lat, planned in UTM zone {}{} (EPSG:{})",
                zone.number,
                if zone.south { "S" } else { "N" },
                zone.epsg()
            ),
        }
    }
}

/// One field to spray: an outer boundary with holes (not sprayed), in planning metres.
#[derive(Debug, Clone, PartialEq)]
pub struct Field {
    pub name: String,
    /// Boundary and holes; rings closed, simple, holes strictly inside.
    pub polygon: Polygon<f64>,
}

impl Field {
    /// Area inside the boundary less the holes, m².
    pub fn area_m2(&self) -> f64 {
        self.polygon.unsigned_area()
    }

    pub fn holes(&self) -> usize {
        self.polygon.interiors().len()
    }

    pub fn vertices(&self) -> usize {
        std::iter::once(self.polygon.exterior())
            .chain(self.polygon.interiors())
            .map(|ring| ring.0.len() - 1)
            .sum()
    }
}

/// A no-spray zone (a `kind: obstacle` feature): not sprayed, not crossed at spray height.
#[derive(Debug, Clone, PartialEq)]
pub struct Obstacle {
    pub name: String,
    pub polygon: Polygon<f64>,
}

/// A named point of the input (`kind`: `launch`, `supply`, … or anything the operator uses).
#[derive(Debug, Clone, PartialEq)]
pub struct Marker {
    pub kind: String,
    pub name: String,
    pub position: Coord<f64>,
}

/// Words that mark where the drone takes off, refills and swaps batteries, as operators name
/// or type a point in Google Earth or a GeoJSON editor (case-insensitive).
pub const LAUNCH_WORDS: [&str; 6] = ["launch", "home", "takeoff", "supply", "base", "start"];

impl Marker {
    /// Whether the point is a launch/supply point: by its `kind`/`type` or by its name.
    pub fn is_launch(&self) -> bool {
        let word = |text: &str| {
            let text = text.trim().to_ascii_lowercase();
            LAUNCH_WORDS
                .iter()
                .any(|w| text == *w || text.replace(['-', '_', ' '], "") == *w)
        };
        word(&self.kind) || word(&self.name)
    }
}

/// Everything read from one field file, validated.
#[derive(Debug, Clone)]
pub struct Farm {
    pub source: PathBuf,
    pub coordinate_system: CoordinateSystem,
    pub fields: Vec<Field>,
    pub obstacles: Vec<Obstacle>,
    pub markers: Vec<Marker>,
    /// A terrain described inside the field file itself (the `terrain` member of the data
    /// files), used when no other terrain is given.
    pub embedded_terrain: Option<TerrainSpec>,
}

impl Farm {
    /// Bounding rectangle of all fields and obstacles, metres.
    pub fn bounds(&self) -> Rect<f64> {
        let mut rects = self
            .fields
            .iter()
            .map(|field| &field.polygon)
            .chain(self.obstacles.iter().map(|obstacle| &obstacle.polygon))
            .filter_map(|polygon| polygon.bounding_rect());
        let first = rects.next().expect("a farm has at least one field");
        rects.fold(first, |acc, rect| {
            Rect::new(
                Coord {
                    x: acc.min().x.min(rect.min().x),
                    y: acc.min().y.min(rect.min().y),
                },
                Coord {
                    x: acc.max().x.max(rect.max().x),
                    y: acc.max().y.max(rect.max().y),
                },
            )
        })
    }

    pub fn total_area_m2(&self) -> f64 {
        self.fields.iter().map(Field::area_m2).sum()
    }
}
