//! The flight through a coverage plan: which pass comes when, in which direction, and the
//! transfer legs between passes (seed 001 eq. 8, MISSION.md decision 3).
//!
//! A transfer between two pass ends costs its 3D length, plus 2h when the straight segment is
//! not inside the closed field polygon (its boundary counts as inside; holes and obstacles do
//! not): the drone climbs h above spray height to leave the work area and comes back down.
//! Until the sequencing issue lands its optimisers, the order is the plain one: each field in
//! file order, its edge passes first, then its swaths boustrophedon in scan-line order.

use geo::{Coord, Line, Polygon, Relate};
use serde::Serialize;

use crate::coverage::drape::GroundPoint;
use crate::coverage::CoveragePlan;
use crate::model::Farm;

/// A pass of the plan.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum Pass {
    /// Interior swath `swath` of field `field`.
    Swath { field: usize, swath: usize },
    /// Edge pass `edge` of field `field`.
    Edge { field: usize, edge: usize },
}

/// One pass in flight order.
#[derive(Debug, Clone, PartialEq)]
pub struct Visit {
    pub pass: Pass,
    /// The points in the direction flown.
    pub points: Vec<GroundPoint>,
}

/// A transfer leg between two pass ends.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Transfer {
    pub from: GroundPoint,
    pub to: GroundPoint,
    /// True when the leg leaves the field and climbs h.
    pub climbs: bool,
    /// 3D length plus 2h when it climbs, metres (eq. 8).
    pub cost_m: f64,
}

/// The flight: passes in order with the transfers between them (`transfers[i]` leads from
/// `visits[i]` to `visits[i + 1]`).
#[derive(Debug, Clone, PartialEq)]
pub struct Route {
    pub visits: Vec<Visit>,
    pub transfers: Vec<Transfer>,
}

impl Route {
    pub fn transfer_length_m(&self) -> f64 {
        self.transfers.iter().map(|transfer| transfer.cost_m).sum()
    }

    /// Changes of direction at path points along the flown polyline (every angle counts, as
    /// in MISSION.md decision 5), and the U-turns among the pass-to-pass junctions.
    pub fn turns(&self) -> (usize, usize) {
        let mut polyline: Vec<Coord<f64>> = Vec::new();
        let mut push = |point: &GroundPoint| {
            let coord = Coord {
                x: point.x,
                y: point.y,
            };
            if polyline
                .last()
                .is_none_or(|last| (last.x - coord.x).hypot(last.y - coord.y) > 1e-9)
            {
                polyline.push(coord);
            }
        };
        let mut u_turns = 0;
        for (index, visit) in self.visits.iter().enumerate() {
            visit.points.iter().for_each(&mut push);
            if let Some(next) = self.visits.get(index + 1) {
                if reverses(&visit.points, &next.points) {
                    u_turns += 1;
                }
            }
        }
        let turns = polyline
            .windows(3)
            .filter(|triple| {
                let (a, b, c) = (triple[0], triple[1], triple[2]);
                let incoming = (b.x - a.x, b.y - a.y);
                let outgoing = (c.x - b.x, c.y - b.y);
                let cross = incoming.0 * outgoing.1 - incoming.1 * outgoing.0;
                let dot = incoming.0 * outgoing.0 + incoming.1 * outgoing.1;
                cross.atan2(dot).abs() > 1f64.to_radians()
            })
            .count();
        (turns, u_turns)
    }
}

/// Whether the next pass runs back against this one (a U-turn at the headland).
fn reverses(points: &[GroundPoint], next: &[GroundPoint]) -> bool {
    let direction = |points: &[GroundPoint]| {
        let (first, last) = (points[0], points[points.len() - 1]);
        let length = (last.x - first.x).hypot(last.y - first.y);
        ((last.x - first.x) / length, (last.y - first.y) / length)
    };
    if points.len() < 2
        || next.len() < 2
        || points[0] == points[points.len() - 1]
        || next[0] == next[next.len() - 1]
    {
        return false;
    }
    let (a, b) = (direction(points), direction(next));
    a.0 * b.0 + a.1 * b.1 < -0.99
}

/// The transfer model of decision 3, shared by every sequencer and the report.
pub struct TransferModel<'a> {
    farm: &'a Farm,
    safe_height_m: f64,
}

impl<'a> TransferModel<'a> {
    pub fn new(farm: &'a Farm, safe_height_m: f64) -> Self {
        Self {
            farm,
            safe_height_m,
        }
    }

    /// The leg from `from` to `to` (pass ends, heights on the ground: both fly at spray height
    /// above it, so the climb between them is the ground's).
    pub fn transfer(&self, from: GroundPoint, to: GroundPoint) -> Transfer {
        let length = ((to.x - from.x).powi(2)
            + (to.y - from.y).powi(2)
            + (to.ground_m - from.ground_m).powi(2))
        .sqrt();
        let climbs = !self.inside_a_field(from, to);
        Transfer {
            from,
            to,
            climbs,
            cost_m: length
                + if climbs {
                    2.0 * self.safe_height_m
                } else {
                    0.0
                },
        }
    }

    /// The straight segment lies in one closed field polygon (boundary included), crossing no
    /// hole and no obstacle.
    fn inside_a_field(&self, from: GroundPoint, to: GroundPoint) -> bool {
        let line = Line::new(
            Coord {
                x: from.x,
                y: from.y,
            },
            Coord { x: to.x, y: to.y },
        );
        let covered_by = |polygon: &Polygon<f64>| {
            if line.start == line.end {
                polygon.relate(&geo::Point::from(line.start)).is_covers()
            } else {
                polygon.relate(&line).is_covers()
            }
        };
        let crosses_obstacle = || {
            self.farm.obstacles.iter().any(|obstacle| {
                obstacle.polygon.relate(&line).is_intersects()
                    && !touches_only(&obstacle.polygon, &line)
            })
        };
        self.farm
            .fields
            .iter()
            .any(|field| covered_by(&field.polygon))
            && !crosses_obstacle()
    }
}

/// The segment meets the obstacle only on its boundary (flying along its edge is allowed).
fn touches_only(polygon: &Polygon<f64>, line: &Line<f64>) -> bool {
    polygon.relate(line).is_touches()
}

/// The plain order: fields in file order; edge passes first, then swaths by scan line,
/// alternating direction (boustrophedon).
pub fn plain_route(plan: &CoveragePlan, model: &TransferModel) -> Route {
    let mut visits = Vec::new();
    for (field_index, field) in plan.fields.iter().enumerate() {
        for (edge_index, edge) in field.edges.iter().enumerate() {
            visits.push(Visit {
                pass: Pass::Edge {
                    field: field_index,
                    edge: edge_index,
                },
                points: edge.points.clone(),
            });
        }
        let mut order: Vec<usize> = (0..field.swaths.len()).collect();
        order.sort_by_key(|&index| field.swaths[index].line);
        for index in order {
            let swath = &field.swaths[index];
            let mut points = swath.points.clone();
            if swath.line % 2 == 1 {
                points.reverse();
            }
            visits.push(Visit {
                pass: Pass::Swath {
                    field: field_index,
                    swath: index,
                },
                points,
            });
        }
    }
    let transfers = visits
        .windows(2)
        .map(|pair| {
            let from = *pair[0].points.last().expect("a pass has points");
            let to = pair[1].points[0];
            model.transfer(from, to)
        })
        .collect();
    Route { visits, transfers }
}
