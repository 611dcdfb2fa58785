//! Coverage of several fields on 3D terrain (seed 001 §2): swaths at the best heading per
//! field, draped on the terrain, with edge passes around every boundary and hole.

pub mod drape;
pub mod edge_corners;
pub mod edge_cut;
mod edge_passes;
pub mod heading;
pub mod measure;
pub mod region;
pub mod scan_lines;
pub mod sliver;

use geo::{Area, MapCoords, MultiPolygon};
use serde::Serialize;

use crate::error::Fault;
use crate::limits::{DRAPE_SPACING_RANGE_M, MAX_PLAN_AREA_M2, MAX_PLAN_SWATHS, MAX_SCAN_LINES};
use crate::model::{Farm, Vehicle};
use crate::terrain::Terrain;
use drape::{drape, draped_length, path_length_3d, GroundPoint};
pub use edge_cut::EdgeCut;
use edge_passes::{edge_passes, EdgeLayout};
use heading::{
    choose_heading, near_best_headings, HeadingChoice, HeadingObjective, HeadingSample,
    DOSE_CANDIDATES, DOSE_TOLERANCE,
};
use measure::{edge_strip, measure, swath_strip, CoverageMeasure};
use region::{edge_pass_regions, rings, sprayable_region};
use scan_lines::{scan_segments, Frame, RotatedRings, Segment};

/// How coverage is laid out.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct CoverageSettings {
    /// Edge passes around each boundary and hole (`--headland`); 0 is seed 001's layout.
    pub headland_passes: usize,
    /// Distance kept from the field boundary, metres.
    pub boundary_margin_m: f64,
    /// Distance kept from obstacles, metres.
    pub obstacle_margin_m: f64,
    /// Seed 001's a: spacing of the perpendicular lines that sample the terrain, metres.
    pub drape_spacing_m: f64,
    /// What the swath heading is chosen for.
    pub heading: HeadingObjective,
    /// Refine the best 1° heading to 0.1° where that lowers the objective.
    pub refine_heading: bool,
    /// Where swaths' spray on/off points sit against the edge-pass band (`--edge-cut`).
    pub edge_cut: EdgeCut,
}

impl Default for CoverageSettings {
    fn default() -> Self {
        Self {
            headland_passes: 1,
            boundary_margin_m: 0.0,
            obstacle_margin_m: 0.0,
            drape_spacing_m: 20.0,
            heading: HeadingObjective::default(),
            refine_heading: true,
            edge_cut: EdgeCut::default(),
        }
    }
}

impl CoverageSettings {
    /// Checks every setting is finite and within range; errs with the first one that is not.
    pub fn validate(&self) -> Result<(), Fault> {
        let check = |what: &str, value: f64, positive: bool| {
            let ok = value.is_finite() && if positive { value > 0.0 } else { value >= 0.0 };
            if ok {
                Ok(())
            } else {
                Err(Fault::InvalidValue {
                    what: what.into(),
                    value: value.to_string(),
                    why: if positive {
                        "must be a number above 0"
                    } else {
                        "must be 0 or more"
                    }
                    .into(),
                })
            }
        };
        check("drape spacing (a)", self.drape_spacing_m, true)?;
        let (finest, coarsest) = DRAPE_SPACING_RANGE_M;
        if !(finest..=coarsest).contains(&self.drape_spacing_m) {
            return Err(Fault::InvalidValue {
                what: "drape spacing (a)".into(),
                value: crate::error::figure(self.drape_spacing_m),
                why: format!("lies in {finest}..={coarsest} m (docs/limits.md)"),
            });
        }
        check("boundary margin", self.boundary_margin_m, false)?;
        check("obstacle margin", self.obstacle_margin_m, false)?;
        if self.headland_passes > 20 {
            return Err(Fault::InvalidValue {
                what: "headland".into(),
                value: self.headland_passes.to_string(),
                why: "at most 20 edge passes".into(),
            });
        }
        match self.heading {
            HeadingObjective::Fixed {
                heading_deg: degrees,
            }
            | HeadingObjective::Bearing {
                bearing_deg: degrees,
            } if !degrees.is_finite() => Err(Fault::NonFinite),
            HeadingObjective::Seed {
                count_weight,
                length_weight,
            }
            | HeadingObjective::LeastDose {
                count_weight,
                length_weight,
            } if !(count_weight >= 0.0
                && length_weight >= 0.0
                && count_weight + length_weight > 0.0) =>
            {
                Err(Fault::InvalidValue {
                    what: "heading weights".into(),
                    value: format!("{count_weight}/{length_weight}"),
                    why: "must be 0 or more and not both 0".into(),
                })
            }
            _ => Ok(()),
        }
    }
}

/// One interior swath, draped, in scan order (its direction of flight is set by the route).
#[derive(Debug, Clone, PartialEq)]
pub struct Swath {
    /// Index of the field in the farm's fields.
    pub field: usize,
    /// Scan line index within the field (0 at the low side of the rotated frame).
    pub line: usize,
    /// The draped path, in order along the scan line.
    pub points: Vec<GroundPoint>,
    /// Draped length, metres.
    pub length_m: f64,
}

/// One closed edge pass around a boundary or a hole.
#[derive(Debug, Clone, PartialEq)]
pub struct EdgePass {
    /// Index of the field in the farm's fields.
    pub field: usize,
    /// 0 for the outermost pass.
    pub pass: usize,
    /// The draped path of the pass.
    pub points: Vec<GroundPoint>,
    /// Draped length, metres.
    pub length_m: f64,
}

/// The coverage of one field.
#[derive(Debug, Clone)]
pub struct FieldCoverage {
    /// The field's name.
    pub name: String,
    /// The chosen swath heading.
    pub heading: HeadingChoice,
    /// Interior swaths, in scan order.
    pub swaths: Vec<Swath>,
    /// Edge passes around the rings of the sprayable region, outermost pass first.
    pub edges: Vec<EdgePass>,
    /// How well the swaths and edge passes cover the sprayable region.
    pub measure: CoverageMeasure,
    /// The heading scan (0..179°), for plots.
    pub heading_samples: Vec<HeadingSample>,
    /// Corners of edge passes where the pass stops spraying and starts again rather than
    /// spray the corner's wedge twice ([`edge_corners`]).
    pub edge_corners_cut: usize,
    /// Double dose those corners save by the corner model, m².
    pub edge_corners_saved_m2: f64,
    /// The true bearing of the planning frame's north at the field's middle, degrees: the UTM
    /// grid convergence for lon/lat input, 0 in local metres (and for a field laid out alone).
    pub grid_north_bearing_deg: f64,
}

impl FieldCoverage {
    /// The swaths' bearing as the operator reads it, 0..180°: true for lon/lat input, from the
    /// frame's y axis in local metres.
    pub fn swath_bearing_deg(&self) -> f64 {
        crate::geometry::true_swath_bearing_deg(
            self.heading.heading_deg,
            self.grid_north_bearing_deg,
        )
    }

    /// Interior swath length, metres (seed 001's L).
    pub fn spray_length_m(&self) -> f64 {
        self.swaths.iter().map(|swath| swath.length_m).sum()
    }

    /// Edge pass length, metres.
    pub fn edge_length_m(&self) -> f64 {
        self.edges.iter().map(|edge| edge.length_m).sum()
    }
}

/// The coverage of a farm.
#[derive(Debug, Clone)]
pub struct CoveragePlan {
    /// The settings the plan was laid out with.
    pub settings: CoverageSettings,
    /// Swath width of the vehicle, metres.
    pub swath_width_m: f64,
    /// The coverage of each field, in the farm's order.
    pub fields: Vec<FieldCoverage>,
}

/// The true bearing of the planning frame's north at the middle of `field` (the UTM grid
/// convergence there; 0 in local metres).
fn field_grid_north_bearing_deg(farm: &Farm, field: &crate::model::Field) -> f64 {
    let (low, high) = crate::geometry::bounds(&field.polygon.exterior().0);
    farm.coordinate_system
        .grid_north_bearing_deg(0.5 * (low.x + high.x), 0.5 * (low.y + high.y))
}

/// Lays out every field of the farm.
pub fn plan_coverage(
    farm: &Farm,
    terrain: &dyn Terrain,
    vehicle: &Vehicle,
    settings: &CoverageSettings,
) -> Result<CoveragePlan, Fault> {
    settings.validate()?;
    check_work_size(farm, vehicle.swath_width_m)?;
    // A camera has no dose to double: its images want the overlap, so surveys keep the swaths
    // whole whatever `--edge-cut` says (decision 0019).
    let surveying = CoverageSettings {
        edge_cut: EdgeCut::Overlap,
        ..*settings
    };
    let settings = if vehicle.is_survey() {
        &surveying
    } else {
        settings
    };
    // Fields are laid out independently, on every core (the demo's five fields took 0.1 s of
    // its 0.5 s plan on one core with `--heading dose` and the corner cuts): the results in
    // the fields' order, and the first fault by field is the one reported (decision 0025).
    let laid_out = crate::progress::Counter::new("laying out the fields", farm.fields.len());
    let fields = crate::parallel::try_map_in_order(&farm.fields, |index, field| {
        let sprayable = sprayable_region(
            field,
            &farm.obstacles,
            settings.boundary_margin_m,
            settings.obstacle_margin_m,
        );
        check_something_to_spray(field, &sprayable, vehicle.swath_width_m)?;
        let grid_north_bearing_deg = field_grid_north_bearing_deg(farm, field);
        let in_its_frame = CoverageSettings {
            heading: settings.heading.for_field(grid_north_bearing_deg),
            ..*settings
        };
        let mut coverage = cover_field(
            index,
            &field.name,
            &sprayable,
            terrain,
            vehicle.swath_width_m,
            &in_its_frame,
        )?;
        coverage.grid_north_bearing_deg = grid_north_bearing_deg;
        // A strip narrower than a swath has area but no line to fly.
        if coverage.swaths.is_empty()
            && coverage.edges.is_empty()
            && sprayable.unsigned_area() >= vehicle.swath_width_m.powi(2)
        {
            return Err(narrower_than_a_swath(&field.name, vehicle.swath_width_m));
        }
        laid_out.one_done();
        Ok(coverage)
    })?;
    Ok(CoveragePlan {
        settings: *settings,
        swath_width_m: vehicle.swath_width_m,
        fields,
    })
}

/// What `validate` can tell of the layout without laying it out: every field has ground to
/// spray at the default margins, and a line one swath in from its edges (the eleventh
/// trial's 3 m strip read `valid`, then `plan` refused the farm for it). The faults are
/// `plan`'s own, word for word.
pub fn check_fields_can_be_laid_out(farm: &Farm, vehicle: &Vehicle) -> Result<(), Fault> {
    let settings = CoverageSettings::default();
    let width_m = vehicle.swath_width_m;
    check_work_size(farm, width_m)?;
    for field in &farm.fields {
        let sprayable = sprayable_region(
            field,
            &farm.obstacles,
            settings.boundary_margin_m,
            settings.obstacle_margin_m,
        );
        check_something_to_spray(field, &sprayable, width_m)?;
        if sprayable.unsigned_area() >= width_m.powi(2)
            && edge_pass_regions(&sprayable, 1, width_m).is_empty()
        {
            return Err(narrower_than_a_swath(&field.name, width_m));
        }
    }
    Ok(())
}

fn narrower_than_a_swath(name: &str, width_m: f64) -> Fault {
    Fault::Structure(format!(
        "field '{name}' is narrower than one swath ({width_m} m) everywhere: no swath fits inside it, and every footprint is kept inside its field (decision 0023)"
    ))
}

/// Refuses, before any layout, a farm whose coverage would not finish in bounded time and
/// memory: more sprayable area than [`MAX_PLAN_AREA_M2`], or more swaths (estimated as each
/// field's diagonal over the swath width, an upper bound) than [`MAX_PLAN_SWATHS`].
fn check_work_size(farm: &Farm, width_m: f64) -> Result<(), Fault> {
    use geo::BoundingRect;
    let area_m2: f64 = farm.fields.iter().map(|field| field.area_m2()).sum();
    if area_m2 > MAX_PLAN_AREA_M2 {
        return Err(Fault::TooLarge(format!(
            "the fields cover {:.0} ha (limit {:.0} ha in one plan): plan the farm in parts",
            area_m2 / 1e4,
            MAX_PLAN_AREA_M2 / 1e4
        )));
    }
    let swaths: f64 = farm
        .fields
        .iter()
        .filter_map(|field| field.polygon.bounding_rect())
        .map(|bounds| bounds.width().hypot(bounds.height()) / width_m)
        .sum();
    if swaths > MAX_PLAN_SWATHS as f64 {
        return Err(Fault::TooLarge(format!(
            "about {swaths:.0} swaths of {width_m} m (limit {MAX_PLAN_SWATHS} in one plan): use a wider swath or plan the farm in parts"
        )));
    }
    Ok(())
}

/// Refuses a field with nothing a swath could spray: smaller than one swath square, or
/// covered by obstacles and margins. A field wholly sprayed with overlapping ones
/// (`--allow-overlap`) is not refused: it is done.
fn check_something_to_spray(
    field: &crate::model::Field,
    sprayable: &MultiPolygon<f64>,
    width_m: f64,
) -> Result<(), Fault> {
    let least = width_m * width_m;
    let (field_area, sprayable_area) = (field.area_m2(), sprayable.unsigned_area());
    if sprayable_area >= least {
        return Ok(());
    }
    // Done with the earlier fields it overlaps: its own ground is (nearly) nothing.
    if !field.sprayed_with_others.is_empty() && field.own_ground().unsigned_area() < least {
        return Ok(());
    }
    let name = &field.name;
    Err(Fault::Structure(if field_area < least {
        format!(
            "field '{name}' is {field_area:.2} m², smaller than one swath square ({width_m} × {width_m} m): nothing to plan"
        )
    } else {
        format!(
            "field '{name}' has {sprayable_area:.2} m² left to spray after its obstacles and margins (less than one swath square, {least} m²): are the obstacles right?"
        )
    }))
}

/// Lays out one field's sprayable region.
pub fn cover_field(
    index: usize,
    name: &str,
    sprayable: &MultiPolygon<f64>,
    terrain: &dyn Terrain,
    width_m: f64,
    settings: &CoverageSettings,
) -> Result<FieldCoverage, Fault> {
    let pass_regions = edge_pass_regions(sprayable, settings.headland_passes, width_m);
    // Seed layout: scan the sprayable region from y_min + w/2. With edge passes: scan the
    // region inside the innermost pass line from y_min + w, so the first swath's strip starts
    // where the pass's strip ends.
    let (interior, first_offset) = match pass_regions.last() {
        Some(innermost) => (innermost.clone(), width_m),
        None if settings.headland_passes == 0 => (sprayable.clone(), width_m / 2.0),
        // The field is narrower than its headland: edge passes only, nothing inside.
        None => (MultiPolygon::new(vec![]), width_m),
    };
    let interior_rings = rings(&interior);
    let span = interior_rings.iter().flatten().fold(
        (
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
        ),
        |b, p| (b.0.min(p.x), b.1.max(p.x), b.2.min(p.y), b.3.max(p.y)),
    );
    let diagonal = (span.1 - span.0).hypot(span.3 - span.2);
    if diagonal.is_finite() && diagonal / width_m > MAX_SCAN_LINES as f64 {
        return Err(Fault::TooLarge(format!(
            "field '{name}' is {diagonal:.0} m across: {:.0} swaths of {width_m} m (limit {MAX_SCAN_LINES})",
            diagonal / width_m
        )));
    }

    let layout_at = |heading_deg: f64| {
        let frame = Frame::new(heading_deg);
        let rotated = RotatedRings::new(interior_rings.iter().map(Vec::as_slice), frame);
        let segments = scan_segments(&rotated, width_m, first_offset);
        (frame, rotated.min_x, segments)
    };
    let evaluate = |heading_deg: f64| -> Result<HeadingSample, Fault> {
        let (frame, x_origin, segments) = layout_at(heading_deg);
        let mut length_m = 0.0;
        for segment in &segments {
            length_m += draped_length(segment, frame, terrain, x_origin, settings.drape_spacing_m)?;
        }
        Ok(HeadingSample {
            heading_deg,
            swaths: segments.len(),
            length_m,
        })
    };
    let (heading, heading_samples) = if interior_rings.is_empty() {
        let empty = HeadingSample {
            heading_deg: 0.0,
            swaths: 0,
            length_m: 0.0,
        };
        (
            HeadingChoice {
                heading_deg: 0.0,
                integer_heading_deg: 0.0,
                integer_objective: 0.0,
                objective: 0.0,
                swaths: 0,
                length_m: 0.0,
            },
            vec![empty],
        )
    } else {
        choose_heading(settings.heading, settings.refine_heading, evaluate)?
    };

    // The heading is chosen on the uncut swaths (seed 001's E over the interior); the cut
    // then moves their spray on/off points against the band (decision 0019), and `dose`
    // measures it at E's best few headings to keep the one that sprays least twice.
    let cut_against = match pass_regions.last() {
        Some(innermost) if settings.edge_cut != EdgeCut::Overlap => {
            Some(edge_cut::Core::new(innermost, width_m))
        }
        _ => None,
    };
    let budget_m2 = edge_cut::MISSED_BUDGET_SHARE * sprayable.unsigned_area();
    let cut_at = |choice: &HeadingChoice, core: &edge_cut::Core| {
        let (frame, x_origin, segments) = layout_at(choice.heading_deg);
        let cut = edge_cut::cut_swath_ends(
            &segments,
            core,
            frame,
            width_m,
            settings.edge_cut,
            budget_m2,
        );
        (frame, x_origin, cut)
    };
    let (heading, frame, x_origin, segments) = match &cut_against {
        Some(core) => {
            let candidates = match settings.heading {
                HeadingObjective::LeastDose { .. } => near_best_headings(
                    settings.heading,
                    &heading,
                    &heading_samples,
                    DOSE_TOLERANCE,
                    DOSE_CANDIDATES,
                ),
                _ => vec![heading],
            };
            let (choice, (frame, x_origin, cut)) = candidates
                .into_iter()
                .map(|candidate| {
                    let cut = cut_at(&candidate, core);
                    (candidate, cut)
                })
                // Strictly less: ties keep the better E.
                .reduce(|kept, next| {
                    if next.1 .2.double_m2 < kept.1 .2.double_m2 {
                        next
                    } else {
                        kept
                    }
                })
                .expect("E's own heading is always a candidate");
            (choice, frame, x_origin, cut.segments)
        }
        None => {
            let (frame, x_origin, segments) = layout_at(heading.heading_deg);
            (heading, frame, x_origin, segments)
        }
    };
    let swaths = segments
        .iter()
        .map(|segment| {
            let points = drape(segment, frame, terrain, x_origin, settings.drape_spacing_m)?;
            Ok(Swath {
                field: index,
                line: segment.line,
                length_m: path_length_3d(&points),
                points,
            })
        })
        .collect::<Result<Vec<_>, Fault>>()?;
    // `--edge-cut overlap` is the layout before decision 0019: passes round their corners.
    let corner_width_m = (settings.edge_cut != EdgeCut::Overlap).then_some(width_m);
    let (edges, corner_cuts) = edge_passes(
        &EdgeLayout {
            field: index,
            sprayable,
            pass_regions: &pass_regions,
            width_m,
        },
        terrain,
        settings.drape_spacing_m,
        corner_width_m,
    )?;

    // Measured in the rotated frame, where swath strips are axis-parallel rectangles whose
    // shared edges are exactly equal: tilted in the plan frame, their nearly collinear edges
    // cost the polygon overlay minutes on a 50,000-vertex boundary (docs/limits.md).
    let rotate = |region: &MultiPolygon<f64>| region.map_coords(|c| frame.to_rotated(c));
    let mut strips: Vec<MultiPolygon<f64>> = segments
        .iter()
        .map(|segment: &Segment| MultiPolygon::new(vec![swath_strip(segment, width_m)]))
        .collect();
    strips.extend(
        pass_regions
            .iter()
            .map(|region| rotate(&edge_strip(region, width_m))),
    );
    let measure = measure(&rotate(sprayable), &strips);

    Ok(FieldCoverage {
        name: name.to_string(),
        heading,
        swaths,
        edges,
        measure,
        heading_samples,
        edge_corners_cut: corner_cuts.corners,
        edge_corners_saved_m2: corner_cuts.double_saved_m2,
        grid_north_bearing_deg: 0.0,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::Field;
    use crate::terrain::Flat;
    use geo::Coord;
    use geo::{LineString, Polygon};
    use proptest::prelude::*;

    fn star(centre: (f64, f64), radii: &[f64], phase: f64) -> LineString<f64> {
        let count = radii.len() as f64;
        let mut points: Vec<Coord<f64>> = radii
            .iter()
            .enumerate()
            .map(|(index, radius)| {
                let angle = phase + index as f64 / count * std::f64::consts::TAU;
                Coord {
                    x: centre.0 + radius * angle.cos(),
                    y: centre.1 + radius * angle.sin(),
                }
            })
            .collect();
        points.push(points[0]);
        LineString::new(points)
    }

    /// A random star-shaped field (radii 80-150 m) with up to three star-shaped holes.
    fn random_field() -> impl Strategy<Value = Field> {
        (
            proptest::collection::vec(80.0f64..150.0, 5..14),
            proptest::collection::vec(proptest::collection::vec(4.0f64..12.0, 3..7), 0..4),
            0.0f64..1.0,
        )
            .prop_map(|(shell, holes, phase)| {
                let holes = holes
                    .iter()
                    .enumerate()
                    .map(|(index, radii)| {
                        let angle = phase + index as f64 * std::f64::consts::TAU / 3.0;
                        star((40.0 * angle.cos(), 40.0 * angle.sin()), radii, phase)
                    })
                    .collect();
                Field::new(
                    "random",
                    Polygon::new(star((0.0, 0.0), &shell, phase), holes),
                )
            })
    }

    proptest! {
        #![proptest_config(ProptestConfig { cases: 64, ..ProptestConfig::default() })]

        /// Default settings: the strips cover ≥ 99 % of the sprayable area and no pass sprays
        /// outside it; the seed's layout is measured beside (and covers less).
        #[test]
        fn edge_passes_and_swaths_cover_random_fields(field in random_field()) {
            let sprayable = MultiPolygon::new(vec![field.polygon.clone()]);
            let ours = cover_field(0, "random", &sprayable, &Flat::new(0.0), 5.0, &CoverageSettings::default()).unwrap();
            let seed_settings = CoverageSettings { headland_passes: 0, ..CoverageSettings::default() };
            let seed = cover_field(0, "random", &sprayable, &Flat::new(0.0), 5.0, &seed_settings).unwrap();
            let area = ours.measure.sprayable_area_m2;
            prop_assert!(ours.measure.covered_fraction >= 0.99, "ours {:?}", ours.measure);
            prop_assert!(ours.measure.outside_m2 <= 1e-4 * area, "ours {:?}", ours.measure);
            prop_assert!(seed.measure.covered_fraction <= ours.measure.covered_fraction + 1e-9,
                "seed {:?} ours {:?}", seed.measure, ours.measure);
            // Every swath point lies in the field (holes excluded), up to offset rounding.
            for swath in &ours.swaths {
                for point in &swath.points {
                    let inside = crate::geometry::validate::point_in_ring(Coord { x: point.x, y: point.y }, &field.polygon.exterior().0)
                        && field.polygon.interiors().iter().all(|hole| !crate::geometry::validate::point_in_ring(Coord { x: point.x, y: point.y }, &hole.0));
                    prop_assert!(inside, "swath point ({}, {}) outside the sprayable area", point.x, point.y);
                }
            }
        }
    }

    /// Seed 001 Table 7 on the flat fields, seed layout (docs/contract.md, data: 98°/16/1781,
    /// 3°/32/7164, 92°/22/4220, 90°/13/928 with this convention).
    #[test]
    fn table_7_flat_fields() {
        let scenario = crate::demo::scenario().unwrap();
        let settings = CoverageSettings {
            headland_passes: 0,
            refine_heading: false,
            ..CoverageSettings::default()
        };
        let plan = plan_coverage(
            &scenario.farm,
            scenario.terrain.as_ref(),
            &scenario.vehicle,
            &settings,
        )
        .unwrap();
        let expected = [
            ("S1", 98.0, 16, 1781.0),
            ("S2", 3.0, 32, 7164.0),
            ("S3", 92.0, 22, 4220.0),
            ("S5", 90.0, 13, 928.0),
        ];
        for (name, heading, swaths, length) in expected {
            let field = plan.fields.iter().find(|field| field.name == name).unwrap();
            eprintln!(
                "{name}: {} {} {}",
                field.heading.heading_deg,
                field.swaths.len(),
                field.spray_length_m()
            );
            assert_eq!(field.heading.heading_deg, heading, "{name}");
            assert_eq!(field.swaths.len(), swaths, "{name}");
            assert!(
                (field.spray_length_m() - length).abs() / length < 0.001,
                "{name}: {}",
                field.spray_length_m()
            );
        }
    }
}
