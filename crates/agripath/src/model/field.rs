//! Fields, obstacles and the farm they make, in a local metric frame.

use std::path::PathBuf;

use geo::{Area, BoundingRect, Coord, Polygon, Rect};

use super::terrain_spec::TerrainSpec;
use crate::geometry::{from_utm, UtmZone};
use crate::limits::{MAX_OVERLAP_CANDIDATES, MAX_OVERLAP_PAIRS};

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

    /// The true bearing of the planning frame's north (its +y) at `(x, y)`, degrees clockwise
    /// from true north: the UTM grid convergence, about (λ − λ₀)·sin φ, up to ±3° at a zone's
    /// edge; 0 for local metres, whose north is the frame's. A compass bearing is the grid
    /// bearing plus it. Measured, not from the series: the frame's north 100 m on, back in
    /// lon/lat, and the azimuth between the two on the sphere (exact to 0.001° over 100 m).
    pub fn grid_north_bearing_deg(self, x: f64, y: f64) -> f64 {
        match self {
            Self::Local => 0.0,
            Self::Utm(_) => {
                let (lon_a, lat_a) = self.to_input(x, y);
                let (lon_b, lat_b) = self.to_input(x, y + 100.0);
                let (phi_a, phi_b) = (lat_a.to_radians(), lat_b.to_radians());
                let delta_lon = (lon_b - lon_a).to_radians();
                let east = delta_lon.sin() * phi_b.cos();
                let north = phi_a.cos() * phi_b.sin() - phi_a.sin() * phi_b.cos() * delta_lon.cos();
                east.atan2(north).to_degrees()
            }
        }
    }

    /// A position given in the input's coordinate system, in the planning frame.
    pub fn to_plan(self, a: f64, b: f64) -> (f64, f64) {
        match self {
            Self::Local => (a, b),
            Self::Utm(zone) => crate::geometry::to_utm(a, b, zone),
        }
    }

    /// A one-line description for reports, e.g. "local metres" or the UTM zone and its EPSG code.
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

/// Shared area below which two fields count as touching, not overlapping, m²: digitising
/// noise along a common boundary, not a double dose.
pub const OVERLAP_TOLERANCE_M2: f64 = 1.0;

/// One field to spray: an outer boundary with holes (not sprayed), in planning metres.
#[derive(Debug, Clone, PartialEq)]
pub struct Field {
    /// The field's name from the file, or "field N" when it has none (parts of a multipolygon get ".1", ".2", …).
    pub name: String,
    /// Boundary and holes; rings closed, simple, holes strictly inside.
    pub polygon: Polygon<f64>,
    /// Parts of earlier fields that overlap this one (kept with `--allow-overlap`): sprayed
    /// with those fields, so left out of this one's sprayable region, and sprayed once.
    pub sprayed_with_others: Vec<Polygon<f64>>,
}

impl Field {
    /// A field with no overlapping earlier fields.
    pub fn new(name: impl Into<String>, polygon: Polygon<f64>) -> Self {
        Self {
            name: name.into(),
            polygon,
            sprayed_with_others: Vec::new(),
        }
    }

    /// The earlier fields this one overlaps, as one region: their union (a list of
    /// overlapping polygons read even-odd would count a part in two of them as outside both).
    pub fn sprayed_by_others(&self) -> geo::MultiPolygon<f64> {
        use geo::BooleanOps;
        self.sprayed_with_others
            .iter()
            .fold(geo::MultiPolygon::new(vec![]), |union, polygon| {
                union.union(&geo::MultiPolygon::new(vec![polygon.clone()]))
            })
    }

    /// The field less the parts sprayed with earlier, overlapping fields.
    pub fn own_ground(&self) -> geo::MultiPolygon<f64> {
        use geo::BooleanOps;
        let whole = geo::MultiPolygon::new(vec![self.polygon.clone()]);
        if self.sprayed_with_others.is_empty() {
            whole
        } else {
            whole.difference(&self.sprayed_by_others())
        }
    }

    /// Area inside the boundary less the holes, m².
    pub fn area_m2(&self) -> f64 {
        self.polygon.unsigned_area()
    }

    /// Number of holes.
    pub fn holes(&self) -> usize {
        self.polygon.interiors().len()
    }

    /// Number of distinct vertices over all rings (the closing repeat not counted).
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
    /// The obstacle's name from the file, or "obstacle N".
    pub name: String,
    /// Its outline in planning metres.
    pub polygon: Polygon<f64>,
}

/// A named point of the input (`kind`: `launch`, `supply`, … or anything the operator uses).
#[derive(Debug, Clone, PartialEq)]
pub struct Marker {
    /// The point's kind (`properties.kind`, "field" when absent).
    pub kind: String,
    /// The point's name, or its kind when it has none.
    pub name: String,
    /// Position in the planning frame, metres.
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
    /// The field file read.
    pub source: PathBuf,
    /// The frame the farm is planned in.
    pub coordinate_system: CoordinateSystem,
    /// The fields to spray, in file order.
    pub fields: Vec<Field>,
    /// The no-spray zones, in file order.
    pub obstacles: Vec<Obstacle>,
    /// The named points, in file order.
    pub markers: Vec<Marker>,
    /// Roads, tracks and yards where a vehicle can stand (kind `access`), in file order.
    pub access: Vec<super::Access>,
    /// A terrain described inside the field file itself (the `terrain` member of the data
    /// files), used when no other terrain is given.
    pub embedded_terrain: Option<TerrainSpec>,
    /// A swath width the field file states (the top-level `swath_width_m` of seed 004's
    /// files), for commands that plan without a vehicle.
    pub stated_swath_width_m: Option<f64>,
    /// What the reader skipped or repaired, one line each, naming the feature (a drawn path
    /// that is not a road, a ring it closed): printed as `note:` lines, never silent.
    pub notes: Vec<String>,
}

impl Farm {
    /// A farm of `fields` in local metres and nothing else (no obstacles, markers, access
    /// features or terrain): what benchmarks and tests build.
    pub fn local(source: impl Into<PathBuf>, fields: Vec<Field>) -> Self {
        Self {
            source: source.into(),
            coordinate_system: CoordinateSystem::Local,
            fields,
            obstacles: vec![],
            markers: vec![],
            access: vec![],
            embedded_terrain: None,
            stated_swath_width_m: None,
            notes: Vec::new(),
        }
    }

    /// Pairs of fields that overlap by more than [`OVERLAP_TOLERANCE_M2`]: (earlier, later,
    /// shared area m²), at most `most` of them (the search stops there). Bounding boxes are
    /// swept in x first, so a farm of thousands of fields is checked in milliseconds; a farm
    /// with more than [`MAX_OVERLAP_CANDIDATES`] pairs of overlapping boxes (thousands of
    /// copies of one field, fields nested in each other's holes) is refused instead of
    /// intersected pair by pair.
    pub fn overlaps(&self, most: usize) -> Result<Vec<(usize, usize, f64)>, crate::Fault> {
        use geo::BooleanOps;
        let boxes: Vec<Option<Rect<f64>>> = self
            .fields
            .iter()
            .map(|field| field.polygon.bounding_rect())
            .collect();
        let mut order: Vec<usize> = (0..self.fields.len())
            .filter(|&i| boxes[i].is_some())
            .collect();
        order.sort_by(|&a, &b| {
            let (a, b) = (boxes[a].map(|r| r.min().x), boxes[b].map(|r| r.min().x));
            a.partial_cmp(&b).unwrap_or(std::cmp::Ordering::Equal)
        });
        let mut pairs = Vec::new();
        let mut candidates = 0usize;
        for (position, &first) in order.iter().enumerate() {
            let Some(first_box) = boxes[first] else {
                continue;
            };
            for &second in &order[position + 1..] {
                let Some(second_box) = boxes[second] else {
                    continue;
                };
                if second_box.min().x > first_box.max().x {
                    break;
                }
                if second_box.min().y > first_box.max().y || second_box.max().y < first_box.min().y
                {
                    continue;
                }
                candidates += 1;
                if candidates > MAX_OVERLAP_CANDIDATES {
                    return Err(crate::Fault::TooLarge(format!(
                        "more than {MAX_OVERLAP_CANDIDATES} pairs of fields lie over each other's boxes: are fields repeated?"
                    )));
                }
                let shared = self.fields[first]
                    .polygon
                    .intersection(&self.fields[second].polygon)
                    .unsigned_area();
                if shared > OVERLAP_TOLERANCE_M2 {
                    pairs.push((first.min(second), first.max(second), shared));
                    if pairs.len() >= most {
                        pairs.sort_by_key(|&(first, second, _)| (first, second));
                        return Ok(pairs);
                    }
                }
            }
        }
        pairs.sort_by_key(|&(first, second, _)| (first, second));
        Ok(pairs)
    }

    /// Refuses overlapping fields (a field drawn twice, or two drawn across each other, would
    /// be sprayed twice where they meet), or with `allow` keeps them and has each shared part
    /// sprayed once, with the field that comes first in the file.
    pub fn resolve_overlaps(&mut self, allow: bool) -> Result<(), crate::Fault> {
        let pairs = self.overlaps(if allow { MAX_OVERLAP_PAIRS + 1 } else { 1 })?;
        if let (false, Some(&(first, second, shared))) = (allow, pairs.first()) {
            return Err(crate::Fault::Structure(format!(
                "fields '{}' and '{}' overlap by {shared:.1} m²: if one is a no-spray zone, mark it \
                 as an obstacle (kind 'obstacle', or a KML Folder named 'obstacles'); else correct \
                 the boundaries, or plan with --allow-overlap to spray each overlap once",
                self.fields[first].name, self.fields[second].name,
            )));
        }
        if pairs.len() > MAX_OVERLAP_PAIRS {
            return Err(crate::Fault::TooLarge(format!(
                "more than {MAX_OVERLAP_PAIRS} pairs of overlapping fields: are fields repeated?"
            )));
        }
        for (first, second, _) in pairs {
            let earlier = self.fields[first].polygon.clone();
            self.fields[second].sprayed_with_others.push(earlier);
        }
        Ok(())
    }

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

    /// How far the planning-frame point (x, y) lies outside [`Farm::bounds`], metres (0
    /// inside; NaN for a point that is not finite).
    pub fn distance_outside_bounds_m(&self, x: f64, y: f64) -> f64 {
        let bounds = self.bounds();
        (bounds.min().x - x)
            .max(x - bounds.max().x)
            .max(0.0)
            .hypot((bounds.min().y - y).max(y - bounds.max().y).max(0.0))
    }

    /// Total area of the fields less their holes, m².
    pub fn total_area_m2(&self) -> f64 {
        self.fields.iter().map(Field::area_m2).sum()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn grid_north_lies_by_the_convergence_of_the_zone() {
        // Snyder (1987) eq. 8-16's first term: γ = atan(tan(λ − λ₀)·sin φ), east of the
        // central meridian grid north lies east of true north (north), west of it west, and
        // south of the equator the other way; within 0.01° of the full series up to 3° off.
        for (lon, lat) in [
            (5.7, 52.5),
            (0.5, 52.5),
            (-93.6, 42.0),
            (147.5, -42.9),
            (3.0, 10.0),
        ] {
            let zone = UtmZone::containing(lon, lat);
            let system = CoordinateSystem::Utm(zone);
            let (x, y) = system.to_plan(lon, lat);
            let central = f64::from(zone.number) * 6.0 - 183.0;
            let expected = ((lon - central).to_radians().tan() * lat.to_radians().sin())
                .atan()
                .to_degrees();
            let measured = system.grid_north_bearing_deg(x, y);
            assert!(
                (measured - expected).abs() < 0.01,
                "({lon}, {lat}): {measured} against {expected}"
            );
        }
        assert_eq!(
            CoordinateSystem::Local.grid_north_bearing_deg(5.0, 7.0),
            0.0
        );
    }
}
