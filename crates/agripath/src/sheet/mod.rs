//! `sheet.html`: the mission sheet an operator prints and takes to the field (issue 21).
//!
//! One self-contained A4 page set (print CSS, no network): the farm, the vehicle, the altitude
//! reference and what it assumes, the supply point in the input's coordinates, one row per
//! sortie (fields and passes, sprayed area, litres, flight time, battery, distance, return
//! point), the totals, the preflight verdict of the mission files as read back, and the map.
//! `sheet.pdf` is the same page printed by headless Chromium ([`pdf`]), when one is found.
//!
//! Figures come from the plan's report (litres: seed 003 Table 5's per-sortie figures; flight
//! time and battery as the preflight flew each file, else as planned), the route (which passes
//! each sortie begins), and the mission items
//! (distance over the ground, item to item). The sprayed area of a sortie is its spray
//! length times the swath width. For a survey vehicle (decision 0022) the sheet says survey:
//! the camera's trigger distance and photos (survey metres / trigger distance) where a
//! sprayer has litres.

mod pdf;

pub use pdf::{find_browser, pdf, BROWSER_VARIABLE};

use std::fmt::Write;

use crate::mission::flight::{Action, SortieMission};
use crate::model::Farm;
use crate::plot::line_chart::escape;
use crate::report::Report;
use crate::sequence::{Pass, Route};
use crate::sortie::PlannedSorties;

/// One sortie as the sheet lists it.
#[derive(Debug, Clone, PartialEq)]
pub struct SortieRow {
    /// The sortie's number, from 1 (as in `sortie_NN.plan`).
    pub sortie: usize,
    /// The fields it works in, with the passes it begins in each, in flying order.
    pub fields: Vec<(String, usize)>,
    /// Spray length times swath width, hectares: horizontal, as the file flies with the pump
    /// on (as planned when the files were not flown); overlaps between strips counted.
    pub sprayed_area_ha: f64,
    /// Litres sprayed, on the same length (`None`: the application rate is not known).
    pub litres: Option<f64>,
    /// A survey's photos to expect (`None` for a sprayer).
    pub photos: Option<u64>,
    /// Out from the supply point, along the route and back, seconds.
    pub flight_time_s: f64,
    /// Share of the battery endurance used, percent (`None` for one flight without sorties).
    pub battery_percent: Option<f64>,
    /// Horizontal distance from takeoff to landing along the mission items, metres.
    pub distance_m: f64,
    /// Where it leaves the route to return (`None` for the last), in the input's coordinates.
    pub return_point: Option<[f64; 3]>,
}

/// The sortie rows of a plan: one per mission file, in order.
pub fn sortie_rows(
    farm: &Farm,
    route: &Route,
    sorties: Option<&PlannedSorties>,
    report: &Report,
    missions: &[SortieMission],
) -> Vec<SortieRow> {
    missions
        .iter()
        .map(|mission| {
            let index = mission.sortie;
            let detail = report.sortie_details.get(index);
            // The file as the preflight flew it: what the remote will show.
            let flown = report.preflight.as_ref().and_then(|verdict| {
                verdict
                    .sorties
                    .iter()
                    .find(|sortie| sortie.sortie == index + 1)
            });
            let mut fields: Vec<(String, usize)> = Vec::new();
            for (visit_index, visit) in route.visits.iter().enumerate() {
                let begun_in =
                    sorties.map_or(0, |split| split.sortie_at(split.visit_offsets[visit_index]));
                if begun_in != index {
                    continue;
                }
                let field = match visit.pass {
                    Pass::Swath { field, .. } | Pass::Edge { field, .. } => field,
                };
                let name = &farm.fields[field].name;
                match fields.last_mut() {
                    Some((last, count)) if last == name => *count += 1,
                    _ => fields.push((name.clone(), 1)),
                }
            }
            let planned_m =
                detail.map_or(report.spray_length_m + report.edge_length_m, |d| d.spray_m);
            // As the file flies: horizontal metres with the pump on, the distance ArduPilot's
            // sprayer doses by (the plan counts along the slope: 29.1 km against 27.3 km over
            // a third trial's hills), less where the pump stops on ground too steep.
            let sprayed_m = flown
                .filter(|_| detail.is_some())
                .map_or(planned_m, |sortie| sortie.spray_m - sortie.pump_stopped_m);
            SortieRow {
                sortie: index + 1,
                fields,
                sprayed_area_ha: sprayed_m * report.swath_width_m / 10_000.0,
                litres: detail.and_then(|d| d.litres).map(|litres| {
                    if planned_m > 0.0 {
                        litres * sprayed_m / planned_m
                    } else {
                        litres
                    }
                }),
                photos: match detail {
                    Some(detail) => detail.photos_estimate,
                    None => report.survey.as_ref().map(|survey| survey.photos_estimate),
                },
                flight_time_s: flown.map_or_else(
                    || detail.map_or(report.total_time_s, |d| d.flight_time_s),
                    |sortie| sortie.flight_time_s,
                ),
                battery_percent: flown
                    .filter(|_| detail.is_some())
                    .map(|sortie| 100.0 * sortie.battery_fraction)
                    .or(detail.map(|d| d.battery_percent)),
                distance_m: ground_distance_m(mission),
                return_point: detail.and_then(|d| d.return_point),
            }
        })
        .collect()
}

/// Horizontal distance along the items that move the drone, metres (locally flat Earth:
/// under 0.1 % off over a sortie's few kilometres).
fn ground_distance_m(mission: &SortieMission) -> f64 {
    const EARTH_RADIUS_M: f64 = 6_371_008.8;
    let places: Vec<(f64, f64)> = std::iter::once(&mission.home)
        .chain(&mission.items)
        .filter(|item| {
            matches!(
                item.action,
                Action::Takeoff | Action::Waypoint | Action::Land
            )
        })
        .map(|item| (item.lon.to_radians(), item.lat.to_radians()))
        .collect();
    places
        .windows(2)
        .map(|pair| {
            let (a, b) = (pair[0], pair[1]);
            let mean_latitude = 0.5 * (a.1 + b.1);
            EARTH_RADIUS_M * ((b.0 - a.0) * mean_latitude.cos()).hypot(b.1 - a.1)
        })
        .sum()
}

/// `seconds` as `h:mm:ss` or `m:ss`.
fn clock(seconds: f64) -> String {
    let total = seconds.round().max(0.0) as u64;
    let (hours, minutes, secs) = (total / 3600, (total / 60) % 60, total % 60);
    if hours > 0 {
        format!("{hours}:{minutes:02}:{secs:02}")
    } else {
        format!("{minutes}:{secs:02}")
    }
}

/// A place in the input's coordinates: lon/lat with 6 decimals (about 0.1 m), else metres.
fn place(point: [f64; 2], lon_lat: bool) -> String {
    if lon_lat {
        format!("{:.6}, {:.6}", point[0], point[1])
    } else {
        format!("{:.1} m, {:.1} m", point[0], point[1])
    }
}

const STYLE: &str = r#"
@page { size: A4; margin: 12mm; }
body { font: 10pt/1.35 "DejaVu Sans", Arial, sans-serif; color: #222; margin: 0 auto; max-width: 186mm; }
h1 { font-size: 15pt; margin: 0 0 2mm; }
h2 { font-size: 11pt; margin: 5mm 0 1.5mm; border-bottom: 0.4mm solid #4a7a2a; }
table { border-collapse: collapse; width: 100%; }
th, td { border: 0.2mm solid #bbb; padding: 0.8mm 1.5mm; vertical-align: top; }
th { background: #eef3e6; text-align: left; }
td.number, th.number { text-align: right; white-space: nowrap; }
tr.total td { font-weight: bold; background: #f4f4f4; }
dl { display: grid; grid-template-columns: 42mm 1fr; gap: 0.6mm 3mm; margin: 0; }
dt { color: #555; }
dd { margin: 0; }
.safe { color: #1b5e20; font-weight: bold; }
.unsafe { color: #b71c1c; font-weight: bold; }
.map { page-break-before: always; }
.map svg { width: 100%; height: auto; max-height: 250mm; }
@media screen { body { padding: 8mm; } }
"#;

/// What the sheet shows besides the report: the rows, the map and whether the verdict passed.
pub struct SheetParts<'a> {
    /// The plan's report (with its preflight verdict).
    pub report: &'a Report,
    /// One row per sortie.
    pub rows: &'a [SortieRow],
    /// The plan's map (`plan.svg`), inlined.
    pub map_svg: &'a str,
    /// Whether the farm's input was lon/lat (places are printed so).
    pub lon_lat: bool,
    /// The missions' home (takeoff and landing) as written in the files, lon/lat.
    pub home_lon_lat: Option<[f64; 2]>,
}

/// The page.
pub fn sheet_html(parts: &SheetParts) -> String {
    let report = parts.report;
    let survey = report.survey.as_ref();
    let (area_word, work_word) = if survey.is_some() {
        ("to survey", "surveying")
    } else {
        ("sprayable", "spraying")
    };
    let mut html = String::new();
    let _ = write!(
        html,
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>Mission sheet: {}</title><style>{STYLE}</style></head><body>\n",
        escape(&report.scenario)
    );
    let _ = writeln!(html, "<h1>Mission sheet: {}</h1>", escape(&report.scenario));
    html.push_str("<dl>\n");
    let mut term = |name: &str, value: String| {
        let _ = writeln!(html, "<dt>{name}</dt><dd>{value}</dd>");
    };
    term(
        "Fields",
        format!(
            "{} ({:.2} ha {area_word}, {:.2} % covered as planned)",
            report.fields.len(),
            report.sprayable_area_m2 / 10_000.0,
            100.0 * report.covered_fraction
        ),
    );
    term("Coordinates", escape(&report.coordinate_system));
    term(
        "Vehicle",
        match survey {
            Some(survey) => format!(
                "{}: survey camera, a photo every {} m along the swaths (about {} photos over {:.0} m), no tank; swath {} m, survey height {} m, safe height {} m",
                escape(&report.vehicle),
                survey.trigger_distance_m,
                survey.photos_estimate,
                survey.survey_length_m,
                report.swath_width_m,
                report.spray_height_m,
                report.safe_height_m
            ),
            None => format!(
                "{}: swath {} m, spray height {} m, safe height {} m",
                escape(&report.vehicle),
                report.swath_width_m,
                report.spray_height_m,
                report.safe_height_m
            ),
        },
    );
    term(
        "Altitudes",
        format!(
            "{}: {}",
            report.altitude_reference.key(),
            escape(&report.altitude_assumption)
        ),
    );
    // The sheet is what is taken to the field: the flat-ground warning goes with it.
    if let Some(warning) = &report.terrain_warning {
        term("Warning", format!("<strong>{}</strong>", escape(warning)));
    }
    if let Some(supply) = &report.supply {
        // Said which is which: a pilot typing it into a phone's map expects lat, lon.
        let at = supply.at.lon_lat.map_or_else(
            || place(supply.at.point_m, false),
            |p| format!("{} (lon, lat)", place(p, true)),
        );
        term(
            "Supply point",
            format!("{at}, ground {:.1} m; {}", supply.ground_m, supply.rule),
        );
    }
    if let Some(home) = parts.home_lon_lat {
        term(
            "Home in the files",
            format!(
                "{} (lon, lat: takeoff, refills and landing)",
                place(home, true)
            ),
        );
    }
    term(
        "Headings",
        report
            .fields
            .iter()
            .map(|field| format!("{} {:.1}°", escape(&field.name), field.heading_bearing_deg))
            .collect::<Vec<_>>()
            .join(", ")
            + " (true bearing of the swaths, 0° = true north, clockwise)",
    );
    term(
        "Time",
        format!(
            "{} {work_word}, {} not {work_word} (turns, transfers, returns, refills and swaps), {} in all; the sorties below fly {} of it",
            clock(report.spray_time_s),
            clock(report.non_spray_time_s),
            clock(report.total_time_s),
            clock(parts.rows.iter().map(|row| row.flight_time_s).sum())
        ),
    );
    if let Some(verdict) = &report.preflight {
        let class = if verdict.safe { "safe" } else { "unsafe" };
        term(
            "Preflight",
            format!(
                "<span class=\"{class}\">{}</span>{}",
                escape(&verdict.summary()),
                verdict
                    .failures
                    .iter()
                    .map(|line| format!("<br>{}", escape(line)))
                    .collect::<String>()
            ),
        );
    }
    html.push_str("</dl>\n");
    sortie_table(&mut html, parts.rows, parts.lon_lat, survey.is_some());
    let map = parts
        .map_svg
        .trim_start_matches(|c| c != '<')
        .trim_start_matches("<?xml version=\"1.0\" encoding=\"UTF-8\"?>");
    let _ = writeln!(
        html,
        "<div class=\"map\"><h2>Map</h2>{map}</div>\n</body></html>"
    );
    html
}

fn sortie_table(html: &mut String, rows: &[SortieRow], lon_lat: bool, survey: bool) {
    let _ = writeln!(
        html,
        "<h2>Sorties</h2>\n<table>\n<tr><th>#</th><th>fields: passes begun</th><th class=\"number\">strip ha (overlaps counted)</th><th class=\"number\">{}</th><th class=\"number\">time</th><th class=\"number\">battery used as flown</th><th class=\"number\">distance km</th><th>return point</th></tr>",
        if survey { "photos" } else { "litres as flown" }
    );
    // A survey's column is its photos; a sprayer's its litres.
    let amount = |row: &SortieRow| {
        if survey {
            row.photos.map(|photos| photos as f64)
        } else {
            row.litres
        }
    };
    let decimals = usize::from(!survey);
    let litres_known = rows.iter().all(|row| amount(row).is_some());
    for row in rows {
        let _ = writeln!(
            html,
            "<tr><td class=\"number\">{}</td><td>{}</td><td class=\"number\">{:.2}</td><td class=\"number\">{}</td><td class=\"number\">{}</td><td class=\"number\">{}</td><td class=\"number\">{:.2}</td><td>{}</td></tr>",
            row.sortie,
            row.fields
                .iter()
                .map(|(name, passes)| format!("{}: {passes}", escape(name)))
                .collect::<Vec<_>>()
                .join(", "),
            row.sprayed_area_ha,
            amount(row).map_or("—".into(), |l| format!("{l:.decimals$}")),
            clock(row.flight_time_s),
            row.battery_percent.map_or("—".into(), |b| format!("{b:.0} %")),
            row.distance_m / 1000.0,
            row.return_point.map_or("— (lands)".into(), |p| format!(
                "{} (alt. {:.1} m)",
                place([p[0], p[1]], lon_lat),
                p[2]
            )),
        );
    }
    let _ = writeln!(
        html,
        "<tr class=\"total\"><td></td><td>total, {} sortie(s)</td><td class=\"number\">{:.2}</td><td class=\"number\">{}</td><td class=\"number\">{}</td><td></td><td class=\"number\">{:.2}</td><td></td></tr>\n</table>",
        rows.len(),
        rows.iter().map(|row| row.sprayed_area_ha).sum::<f64>(),
        if litres_known {
            format!("{:.decimals$}", rows.iter().filter_map(amount).sum::<f64>())
        } else {
            "—".into()
        },
        clock(rows.iter().map(|row| row.flight_time_s).sum()),
        rows.iter().map(|row| row.distance_m).sum::<f64>() / 1000.0,
    );
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clock_reads_as_minutes_and_hours() {
        assert_eq!(clock(59.6), "1:00");
        assert_eq!(clock(754.0), "12:34");
        assert_eq!(clock(3_725.0), "1:02:05");
    }

    #[test]
    fn distance_follows_the_moving_items_only() {
        use crate::mission::flight::Item;
        let item = |action, lon: f64, lat: f64| Item {
            action,
            lon,
            lat,
            ground_m: 0.0,
            above_ground_m: 0.0,
        };
        // 0.001° of latitude is 111.2 m; a speed item between does not move the drone.
        let mission = SortieMission {
            sortie: 0,
            home: item(Action::Takeoff, 10.0, 50.0),
            items: vec![
                item(Action::Speed { mps: 5.0 }, 99.0, 0.0),
                item(Action::Waypoint, 10.0, 50.001),
                item(Action::Land, 10.0, 50.0),
            ],
        };
        let distance = ground_distance_m(&mission);
        assert!((distance - 2.0 * 111.195).abs() < 0.1, "{distance}");
    }
}
