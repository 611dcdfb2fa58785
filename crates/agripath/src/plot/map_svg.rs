//! `plan.svg` (and `plan.png`): a map of the plan people can look at — the terrain's
//! hillshade, fields, holes and obstacles, the strips each pass sprays (swath-wide,
//! translucent, so gaps and overlaps show) coloured by sortie, flight lines, transfers
//! (climbing ones in red), return legs and points, the supply point, labels, legend, scale bar
//! and north arrow.

use std::fmt::Write;

use geo::Polygon;

use super::line_chart::escape;
use super::map_labels::{label_places, PixelLine};
use crate::coverage::drape::GroundPoint;
use crate::coverage::CoveragePlan;
use crate::model::{AccessShape, Farm};
use crate::sequence::{Pass, Route};
use crate::sortie::PlannedSorties;

/// Sortie colours (Okabe and Ito, then darker tones), repeating after ten.
pub const SORTIE_COLOURS: [&str; 10] = [
    "#0072B2", "#E69F00", "#009E73", "#CC79A7", "#D55E00", "#56B4E9", "#332288", "#999933",
    "#882255", "#117733",
];

/// The colour of sortie `sortie` of `count`: the palette's ten while they suffice; past
/// ten, hues spread by the golden angle at three lightnesses, so that no two sorties of a
/// plan share a colour and neighbours differ.
pub fn sortie_colour(sortie: usize, count: usize) -> String {
    if count <= SORTIE_COLOURS.len() {
        return SORTIE_COLOURS[sortie].to_string();
    }
    let hue = (sortie as f64 * 137.507_764).rem_euclid(360.0);
    let lightness = [38.0, 50.0, 30.0][sortie % 3];
    format!("hsl({hue:.1},70%,{lightness:.0}%)")
}

/// A picture under the map: PNG bytes and the plan-metre box it covers.
pub struct Underlay<'a> {
    /// The picture, PNG bytes.
    pub png: &'a [u8],
    /// West edge of the box, plan metres.
    pub min_x: f64,
    /// South edge of the box, plan metres.
    pub min_y: f64,
    /// East edge of the box, plan metres.
    pub max_x: f64,
    /// North edge of the box, plan metres.
    pub max_y: f64,
}

const WIDTH_PX: f64 = 1200.0;
/// Tallest the map's drawing of the farm gets, pixels (the frame widens beyond).
const MOST_MAP_HEIGHT_PX: f64 = 1600.0;
const PAD_PX: f64 = 40.0;
const LEGEND_PX: f64 = 95.0;
/// Sortie swatches per legend row: the row and the words after it fit the width.
const LEGEND_PER_ROW: usize = 25;
/// Most sortie swatches the legend draws (two rows, within the legend's band): above, their
/// colours repeat and a grid of them overran the map and pushed its words off the picture (a
/// tenth trial's 201 sorties), so only the count and the numbering are said.
const LEGEND_MOST_SWATCHES: usize = 2 * LEGEND_PER_ROW;

struct Canvas {
    min_x: f64,
    max_y: f64,
    scale: f64,
}

impl Canvas {
    fn x(&self, x: f64) -> f64 {
        PAD_PX + (x - self.min_x) * self.scale
    }

    fn y(&self, y: f64) -> f64 {
        PAD_PX + (self.max_y - y) * self.scale
    }

    fn path(&self, points: impl Iterator<Item = (f64, f64)>, close: bool) -> String {
        let mut data = String::new();
        for (index, (x, y)) in points.enumerate() {
            let _ = write!(
                data,
                "{}{:.2},{:.2}",
                if index == 0 { "M" } else { " L" },
                self.x(x),
                self.y(y)
            );
        }
        if close {
            data.push_str(" Z");
        }
        data
    }

    fn polygon(&self, polygon: &Polygon<f64>) -> String {
        std::iter::once(polygon.exterior())
            .chain(polygon.interiors())
            .map(|ring| self.path(ring.0.iter().map(|p| (p.x, p.y)), true))
            .collect::<Vec<_>>()
            .join(" ")
    }

    fn line(&self, points: &[GroundPoint]) -> String {
        self.path(points.iter().map(|p| (p.x, p.y)), false)
    }
}

/// Fill of ground narrower than a swath (unreachable): slate, apart from every sortie hue.
const UNREACHABLE_COLOUR: &str = "#37474f";

/// Fill of reachable ground the flight missed: signal red.
const MISSED_COLOUR: &str = "#d50000";
/// The rings where a preflight check failed: colour, and radius in px (also the least gap
/// between two rings).
const FAILURE_COLOUR: &str = "#d50000";
const FAILURE_RING_PX: f64 = 9.0;

/// A round scale-bar length near a fifth of the map width.
pub(super) fn scale_bar_m(width_m: f64) -> f64 {
    let target = width_m / 5.0;
    let magnitude = 10f64.powf(target.log10().floor());
    [1.0, 2.0, 5.0, 10.0]
        .iter()
        .map(|step| step * magnitude)
        .rfind(|length| *length <= target)
        .unwrap_or(magnitude)
}

/// What the plan's map draws.
pub struct PlanMap<'a> {
    /// The fields, holes, obstacles and access features.
    pub farm: &'a Farm,
    /// The swaths and edge passes.
    pub plan: &'a CoveragePlan,
    /// The order flown, with its transfers.
    pub route: &'a Route,
    /// The sorties: passes coloured by sortie, the returns and the supply point.
    pub sorties: Option<&'a PlannedSorties>,
    /// The hillshade, beneath everything.
    pub underlay: Option<&'a Underlay<'a>>,
    /// The map's heading.
    pub title: &'a str,
    /// Ground no swath reaches, and ground the preflight found missed.
    pub ground: &'a crate::coverage::region::GroundPatches,
    /// With `--supply auto:N`: the other places listed, in their order (the 2nd best first).
    pub other_supply_points: &'a [geo::Coord<f64>],
}

/// Draws the plan.
pub fn plan_svg(map: &PlanMap) -> String {
    let PlanMap {
        farm,
        plan,
        route,
        sorties,
        underlay,
        title,
        ground,
        other_supply_points,
    } = *map;
    // The farm, the supply point where it stands off the fields (it may be 200 m out) and
    // the other places listed.
    let mut bounds = farm.bounds();
    let supply = route.launch.map(|leg| geo::Coord {
        x: leg.from.x,
        y: leg.from.y,
    });
    for point in supply.iter().chain(other_supply_points) {
        bounds = geo::Rect::new(
            geo::Coord {
                x: bounds.min().x.min(point.x),
                y: bounds.min().y.min(point.y),
            },
            geo::Coord {
                x: bounds.max().x.max(point.x),
                y: bounds.max().y.max(point.y),
            },
        );
    }
    let span_y = bounds.height().max(1.0);
    // A farm much taller than wide (a strip, a row of terraces) is drawn at most
    // `MOST_MAP_HEIGHT_PX` tall, centred in a wider frame (the eleventh trial's 400 m strip
    // drew 1,600 × 20,143 px).
    let span_x = bounds
        .width()
        .max(1.0)
        .max(span_y * (WIDTH_PX - 2.0 * PAD_PX) / MOST_MAP_HEIGHT_PX);
    let min_x = bounds.center().x - span_x / 2.0;
    let scale = (WIDTH_PX - 2.0 * PAD_PX) / span_x;
    let height_px = span_y * scale + 2.0 * PAD_PX + LEGEND_PX;
    let canvas = Canvas {
        min_x,
        max_y: bounds.max().y,
        scale,
    };
    let strip_px = plan.swath_width_m * scale;
    let mut svg = String::new();
    let _ = writeln!(
        svg,
        r##"<svg xmlns="http://www.w3.org/2000/svg" width="{WIDTH_PX:.0}" height="{height_px:.0}" viewBox="0 0 {WIDTH_PX:.0} {height_px:.0}" font-family="Helvetica, Arial, sans-serif">"##
    );
    let _ = writeln!(
        svg,
        r##"<rect width="100%" height="100%" fill="#fbfbf8"/>"##
    );
    let _ = writeln!(
        svg,
        r##"<text x="{PAD_PX}" y="24" font-size="16" fill="#222">{}</text>"##,
        escape(title)
    );
    let map_height = span_y * scale + 2.0 * PAD_PX - 30.0;
    let _ = writeln!(
        svg,
        r##"<clipPath id="map-area"><rect x="0" y="30" width="{WIDTH_PX:.0}" height="{map_height:.0}"/></clipPath>"##
    );
    if let Some(underlay) = underlay {
        let _ = writeln!(
            svg,
            r##"<image clip-path="url(#map-area)" x="{:.2}" y="{:.2}" width="{:.2}" height="{:.2}" preserveAspectRatio="none" opacity="0.55" href="data:image/png;base64,{}"/>"##,
            canvas.x(underlay.min_x),
            canvas.y(underlay.max_y),
            (underlay.max_x - underlay.min_x) * scale,
            (underlay.max_y - underlay.min_y) * scale,
            super::plan_html::base64(underlay.png)
        );
    }
    // The sortie flying each pass (0 when the route is not split).
    let sortie_of =
        |index: usize| sorties.map_or(0, |split| split.sortie_at(split.visit_offsets[index]));
    let _ = writeln!(svg, r##"<g id="fields">"##);
    for field in &farm.fields {
        let _ = writeln!(
            svg,
            r##"<path d="{}" fill="#e3efcf" fill-opacity="0.55" fill-rule="evenodd" stroke="#4a7a2a" stroke-width="1.2"/>"##,
            canvas.polygon(&field.polygon)
        );
    }
    for obstacle in &farm.obstacles {
        let _ = writeln!(
            svg,
            r##"<path d="{}" fill="#c62828" fill-opacity="0.35" stroke="#8e0000" stroke-width="1"/>"##,
            canvas.polygon(&obstacle.polygon)
        );
    }
    // Ground narrower than a swath, which no pass reaches without spraying outside.
    let any_unreachable = ground.unreachable.iter().any(|field| !field.0.is_empty());
    for piece in ground.unreachable.iter().flat_map(|field| &field.0) {
        let _ = writeln!(
            svg,
            r##"<path class="unreachable" d="{}" fill="{UNREACHABLE_COLOUR}" fill-opacity="0.8" fill-rule="evenodd" stroke="none"/>"##,
            canvas.polygon(piece)
        );
    }
    // Reachable ground the flight missed, as the preflight measured it.
    let any_missed = ground.missed.iter().any(|field| !field.0.is_empty());
    for piece in ground.missed.iter().flat_map(|field| &field.0) {
        let _ = writeln!(
            svg,
            r##"<path class="missed" d="{}" fill="{MISSED_COLOUR}" fill-opacity="0.9" stroke="{MISSED_COLOUR}" stroke-width="0.6"/>"##,
            canvas.polygon(piece)
        );
    }
    // Roads and yards where the supply point may stand, in road grey.
    for access in &farm.access {
        let _ = match &access.shape {
            AccessShape::Line(line) => writeln!(
                svg,
                r##"<path d="{}" fill="none" stroke="#8d8d8d" stroke-width="3" stroke-linecap="round"/>"##,
                canvas.path(line.0.iter().map(|p| (p.x, p.y)), false)
            ),
            AccessShape::Area(polygon) => writeln!(
                svg,
                r##"<path d="{}" fill="#b0b0b0" fill-opacity="0.5" fill-rule="evenodd" stroke="#8d8d8d" stroke-width="1"/>"##,
                canvas.polygon(polygon)
            ),
        };
    }
    let _ = writeln!(svg, "</g>");
    // One layer per sortie (`sortie-NN`, numbered as the mission files): its strips, then its
    // passes over them, in the sortie's own colour.
    let sortie_count = sorties.map_or(1, |split| split.plan.sorties.len());
    for sortie in 0..sortie_count {
        let colour = sortie_colour(sortie, sortie_count);
        let visits: Vec<(usize, &crate::sequence::Visit)> = route
            .visits
            .iter()
            .enumerate()
            .filter(|&(index, _)| sortie_of(index) == sortie)
            .collect();
        let _ = writeln!(
            svg,
            r##"<g id="sortie-{:02}" class="sortie" stroke="{colour}" fill="none">"##,
            sortie + 1
        );
        let _ = writeln!(
            svg,
            r##"<g stroke-linecap="butt" stroke-linejoin="miter" stroke-opacity="0.22" stroke-width="{strip_px:.2}">"##
        );
        for (_, visit) in &visits {
            let _ = writeln!(svg, r##"<path d="{}"/>"##, canvas.line(&visit.points));
        }
        let _ = writeln!(svg, r##"</g><g stroke-width="1">"##);
        for (_, visit) in &visits {
            // Edge passes dashed, so they read apart from the swaths of the same sortie.
            let dash = match visit.pass {
                Pass::Swath { .. } => "",
                Pass::Edge { .. } => r#" stroke-dasharray="6 2""#,
            };
            let _ = writeln!(svg, r##"<path d="{}"{dash}/>"##, canvas.line(&visit.points));
        }
        let _ = writeln!(svg, "</g></g>");
    }
    let _ = writeln!(
        svg,
        r##"<g id="transfers" fill="none" stroke-width="1.1" stroke-dasharray="4 3">"##
    );
    for transfer in route.legs() {
        let colour = if transfer.climbs {
            "#d32f2f"
        } else {
            "#ef6c00"
        };
        let _ = writeln!(
            svg,
            r##"<path d="{}" stroke="{colour}"/>"##,
            canvas.line(&[transfer.from, transfer.to])
        );
    }
    let _ = writeln!(svg, "</g>");
    if let Some(split) = sorties {
        let supply = split.supply;
        let _ = writeln!(
            svg,
            r##"<g id="returns" fill="none" stroke="#6a1b9a" stroke-width="1.2" stroke-dasharray="7 4">"##
        );
        for (&at, &resume) in split.plan.breaks.iter().zip(&split.plan.resumes) {
            let point = split.work_route.points()[at];
            let again = split.work_route.points()[resume];
            let _ = writeln!(
                svg,
                r##"<path d="{}"/><circle cx="{:.2}" cy="{:.2}" r="4" fill="#6a1b9a" stroke="white" stroke-dasharray="none"/>"##,
                canvas.path(
                    [(point.x, point.y), (supply.x, supply.y), (again.x, again.y)].into_iter(),
                    false
                ),
                canvas.x(point.x),
                canvas.y(point.y)
            );
        }
        let _ = writeln!(
            svg,
            r##"</g><g id="supply"><circle cx="{x:.2}" cy="{y:.2}" r="7" fill="#ffeb3b" stroke="#222" stroke-width="2"/><text x="{x:.2}" y="{:.2}" font-size="12" text-anchor="middle" fill="#222" stroke="#fbfbf8" stroke-width="3" paint-order="stroke">supply</text></g>"##,
            canvas.y(supply.y) - 11.0,
            x = canvas.x(supply.x),
            y = canvas.y(supply.y)
        );
    }
    // The other places `auto:N` listed: hollow, named by rank as `report.json` lists them
    // (the supply point is the first), in words, so they do not read as sortie numbers.
    if !other_supply_points.is_empty() {
        let _ = writeln!(
            svg,
            r##"<g id="other-supply-points" font-size="11" text-anchor="middle">"##
        );
        for (index, point) in other_supply_points.iter().enumerate() {
            let (x, y) = (canvas.x(point.x), canvas.y(point.y));
            let _ = writeln!(
                svg,
                r##"<circle cx="{x:.2}" cy="{y:.2}" r="5" fill="#ffeb3b" fill-opacity="0.35" stroke="#222" stroke-width="1.5" stroke-dasharray="3 2"/><text x="{x:.2}" y="{:.2}" fill="#222" stroke="#fbfbf8" stroke-width="3" paint-order="stroke">option {}</text>"##,
                y - 9.0,
                index + 2
            );
        }
        let _ = writeln!(svg, "</g>");
    }
    // The sortie numbers, at the first pass each sortie begins, over every line and return.
    if sortie_count > 1 {
        let _ = writeln!(
            svg,
            r##"<g id="sortie-numbers" font-size="11" font-weight="bold" text-anchor="middle">"##
        );
        // Each sortie's passes in pixels, in flying order.
        let sortie_passes: Vec<(usize, Vec<PixelLine>)> = (0..sortie_count)
            .map(|sortie| {
                let passes = (0..route.visits.len())
                    .filter(|&index| sortie_of(index) == sortie)
                    .map(|index| {
                        route.visits[index]
                            .points
                            .iter()
                            .map(|point| (canvas.x(point.x), canvas.y(point.y)))
                            .collect()
                    })
                    .collect();
                (sortie, passes)
            })
            .filter(|(_, passes): &(usize, Vec<PixelLine>)| !passes.is_empty())
            .collect();
        // Clear of the supply point's disc and its word above it.
        let supply_marks: Vec<(f64, f64)> = sorties
            .map(|split| {
                let (x, y) = (canvas.x(split.supply.x), canvas.y(split.supply.y));
                vec![
                    (x, y),
                    (x - 14.0, y - 15.0),
                    (x, y - 15.0),
                    (x + 14.0, y - 15.0),
                ]
            })
            .unwrap_or_default();
        let places = label_places(
            &supply_marks,
            sortie_passes.iter().map(|(_, passes)| passes.as_slice()),
        );
        for ((sortie, _), (x, y)) in sortie_passes.iter().zip(places) {
            let sortie = *sortie;
            let _ = writeln!(
                svg,
                r##"<circle cx="{x:.2}" cy="{y:.2}" r="8" fill="white" stroke="{}" stroke-width="2"/><text x="{x:.2}" y="{:.2}" fill="#111">{}</text>"##,
                sortie_colour(sortie, sortie_count),
                y + 4.0,
                sortie + 1
            );
        }
        let _ = writeln!(svg, "</g>");
    }
    // Where the preflight's checks failed (an unsafe plan's map): a ring each, one per
    // marker's width, so a leg failing at every sample reads as a row of rings.
    if !ground.failures.is_empty() {
        let _ = writeln!(svg, r##"<g id="failures" fill="none">"##);
        let mut drawn: Vec<(f64, f64)> = Vec::new();
        for &[x, y] in &ground.failures {
            let (x, y) = (canvas.x(x), canvas.y(y));
            if drawn
                .iter()
                .any(|&(a, b)| (a - x).hypot(b - y) < FAILURE_RING_PX)
            {
                continue;
            }
            drawn.push((x, y));
            let _ = writeln!(
                svg,
                r##"<circle cx="{x:.2}" cy="{y:.2}" r="{FAILURE_RING_PX}" stroke="white" stroke-width="5"/><circle cx="{x:.2}" cy="{y:.2}" r="{FAILURE_RING_PX}" stroke="{FAILURE_COLOUR}" stroke-width="2.5"/>"##
            );
        }
        let _ = writeln!(svg, "</g>");
    }
    let _ = writeln!(
        svg,
        r##"<g id="labels" font-size="13" fill="#111" text-anchor="middle">"##
    );
    // Inside each field, off its edges (a concave field's centroid can lie in its notch).
    let labels: Vec<super::map_labels::Labelled> = farm
        .fields
        .iter()
        .zip(&plan.fields)
        .filter_map(|(field, coverage)| {
            let centre = geo::InteriorPoint::interior_point(&field.polygon)?;
            let size = geo::BoundingRect::bounding_rect(&field.polygon)?;
            let text = format!("{} {:.1}°", field.name, coverage.swath_bearing_deg());
            let at = (canvas.x(centre.x()), canvas.y(centre.y()));
            Some((text, at, (size.width() * scale, size.height() * scale)))
        })
        .collect();
    let places = super::map_labels::field_label_places(&labels);
    for ((text, ..), place) in labels.iter().zip(places) {
        let _ = writeln!(
            svg,
            r##"<text transform="{}" stroke="#fbfbf8" stroke-width="3" paint-order="stroke">{}</text>"##,
            place.transform(),
            escape(text)
        );
    }
    let _ = writeln!(svg, "</g>");
    // Legend, scale bar, north arrow along the bottom.
    let base = height_px - LEGEND_PX + 55.0;
    // One numbered swatch per sortie, in rows of LEGEND_PER_ROW (so 35 sorties read as 35).
    let listed = if sortie_count <= LEGEND_MOST_SWATCHES {
        sortie_count
    } else {
        0
    };
    let rows = listed.div_ceil(LEGEND_PER_ROW).max(1);
    for sortie in 0..listed {
        let (row, column) = (sortie / LEGEND_PER_ROW, sortie % LEGEND_PER_ROW);
        let x = PAD_PX + 60.0 + column as f64 * 18.0;
        let y = base - 36.0 - (rows - 1 - row) as f64 * 13.0;
        let _ = writeln!(
            svg,
            r##"<rect x="{x:.0}" y="{y:.0}" width="16" height="11" fill="{}"/><text x="{:.0}" y="{:.0}" font-size="8" text-anchor="middle" fill="white">{}</text>"##,
            sortie_colour(sortie, sortie_count),
            x + 8.0,
            y + 8.5,
            sortie + 1
        );
    }
    let count_words = if listed == sortie_count {
        format!("{sortie_count} (numbered at each sortie's first pass; swaths solid, edge passes dashed)")
    } else {
        format!("{sortie_count}, each numbered at its first pass (too many to list by colour); swaths solid, edge passes dashed")
    };
    let _ = writeln!(
        svg,
        r##"<text x="{PAD_PX}" y="{:.0}" font-size="12" fill="#222">sorties</text><text x="{:.0}" y="{:.0}" font-size="12" fill="#222">{count_words}</text>"##,
        base - 27.0,
        PAD_PX + 66.0 + listed.min(LEGEND_PER_ROW) as f64 * 18.0,
        base - 27.0,
    );
    // The bottom row: each entry's swatch (a dashed line or a filled box), then its words;
    // entries sit one after another by the length of their words, so the row stays clear
    // of the scale bar.
    let mut swatches: Vec<(String, &str)> = [
        ("#ef6c00", "transfer", "4 3"),
        ("#d32f2f", "transfer climbing h", "4 3"),
        ("#6a1b9a", "return to supply", "7 4"),
    ]
    .into_iter()
    .map(|(colour, label, dash)| {
        (
            format!(
                r##"<line x1="0" y1="0" x2="28" y2="0" stroke="{colour}" stroke-width="3" stroke-dasharray="{dash}"/>"##
            ),
            label,
        )
    })
    .collect();
    let boxed = |style: &str| format!(r##"<rect x="0" y="-4.5" width="28" height="9" {style}/>"##);
    if any_unreachable {
        swatches.push((
            boxed(&format!(
                r##"fill="{UNREACHABLE_COLOUR}" fill-opacity="0.8""##
            )),
            "no swath reaches",
        ));
    }
    if !other_supply_points.is_empty() {
        swatches.push((
            r##"<circle cx="14" cy="0" r="5" fill="#ffeb3b" fill-opacity="0.35" stroke="#222" stroke-width="1.5" stroke-dasharray="3 2"/>"##.to_string(),
            "other supply places (option N of report.json)",
        ));
    }
    if any_missed {
        swatches.push((
            boxed(&format!(r##"fill="{MISSED_COLOUR}""##)),
            "missed as flown",
        ));
    }
    if !ground.failures.is_empty() {
        swatches.push((
            format!(
                r##"<circle cx="14" cy="0" r="6" fill="none" stroke="{FAILURE_COLOUR}" stroke-width="2.5"/>"##
            ),
            "a check failed here",
        ));
    }
    if !farm.obstacles.is_empty() {
        swatches.push((
            boxed(r##"fill="#c62828" fill-opacity="0.35" stroke="#8e0000" stroke-width="1""##),
            "obstacle, not sprayed",
        ));
    }
    let bar_m = scale_bar_m(span_x);
    let bar_x = WIDTH_PX - PAD_PX - bar_m * scale - 60.0;
    // An entry that would run into the scale bar starts a second row below the first.
    let (mut x, mut y) = (PAD_PX, base);
    for (swatch, label) in swatches {
        let width = 34.0 + LEGEND_CHARACTER_PX * label.chars().count() as f64;
        if x + width > bar_x - LEGEND_GAP_PX && x > PAD_PX {
            (x, y) = (PAD_PX, base + 20.0);
        }
        let _ = writeln!(
            svg,
            r##"<g transform="translate({x:.0},{y:.0})">{swatch}<text x="34" y="4" font-size="12" fill="#222">{label}</text></g>"##
        );
        x += width + LEGEND_GAP_PX;
    }
    let _ = writeln!(
        svg,
        r##"<g id="scale"><rect x="{bar_x:.2}" y="{:.0}" width="{:.2}" height="5" fill="#222"/><text x="{:.2}" y="{:.0}" font-size="12" text-anchor="middle" fill="#222">{bar_m} m</text></g>"##,
        base - 3.0,
        bar_m * scale,
        bar_x + bar_m * scale / 2.0,
        base + 18.0
    );
    let north_x = WIDTH_PX - PAD_PX - 15.0;
    let _ = writeln!(
        svg,
        r##"<g id="north"><path d="M{north_x:.0},{:.0} l8,22 l-8,-6 l-8,6 Z" fill="#222"/><text x="{north_x:.0}" y="{:.0}" font-size="12" text-anchor="middle">N</text></g>"##,
        base - 20.0,
        base + 18.0
    );
    svg.push_str("</svg>\n");
    svg
}

/// The legend's words at 12 px: a generous mean width of a character, px, and the gap
/// after each entry's words.
const LEGEND_CHARACTER_PX: f64 = 6.8;
const LEGEND_GAP_PX: f64 = 22.0;
