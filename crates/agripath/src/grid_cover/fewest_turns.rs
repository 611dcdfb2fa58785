//! `ours`: a constructive route aimed at the fewest turns.
//!
//! 1. Straight runs ([`super::runs`]): maximal sequences of 4-adjacent valid points along y
//!    (columns) or along x (rows).
//! 2. Cells (boustrophedon decomposition): column runs of neighbouring columns that meet one
//!    to one form a cell; likewise for row runs. Each cell may be swept along y or along x.
//! 3. Rings ([`super::rings`]): a direction per point, parallel to the nearer boundary, so that
//!    the runs nest round the field's edge and round each obstacle and can be flown as a spiral
//!    of L-turns (both ways of sweeping a ring's corners).
//! 4. For every assignment of sweep directions to the cells (and the two single-direction
//!    sweeps, and the rings), runs are chained greedily from the field's corners; the best few
//!    are improved by local search over the run order and directions (relocation, reversal of a
//!    stretch, flips), counting turns exactly as the repro does (contract decision 5,
//!    docs/contract.md): a junction costs 2 turns as a U-turn, 1 as an L where the next run
//!    starts along the move, 2 for a reversal in place, more when it must go round an obstacle.
//!    Ties go to the shorter non-spray distance.

use std::collections::HashMap;

use geo::Coord;

pub use super::runs::{cells, runs, Sweep};
use super::{GridRoute, PointGrid};

/// A run as the search sees it: its points in order and whether it is flown reversed.
type Step = (usize, bool);
/// (turns, non-spray metres) of a route or a junction; `None` when no clear way exists.
type Cost = Option<(usize, f64)>;
/// A direction of flight (unit vector), if known.
type Heading = Option<(f64, f64)>;
/// A decomposition's runs and its greedy order, with their cost.
type Screened = (Cost, Vec<Vec<usize>>, Vec<Step>);

struct Search<'a> {
    grid: &'a PointGrid,
    runs: Vec<Vec<usize>>,
    /// Transit vertices between two points, cached (shared between decompositions).
    transits: HashMap<(usize, usize), Option<Vec<Coord<f64>>>>,
    /// For every (step, step) pair (index 2·run + reversed), the junction from the first's
    /// exit to the second's entry; filled on first use.
    junctions: Vec<Option<Option<Junction>>>,
}

/// The way from one run's exit to the next run's entry, as the turn count needs it.
#[derive(Debug, Clone, Copy)]
struct Junction {
    first: (f64, f64),
    last: (f64, f64),
    /// Transit vertices: each is a change of direction.
    inner: usize,
    /// Non-spray metres (0 for a move between neighbours).
    distance: f64,
}

fn step_index((run, reversed): Step) -> usize {
    2 * run + usize::from(reversed)
}

fn unit(a: Coord<f64>, b: Coord<f64>) -> (f64, f64) {
    let (dx, dy) = (b.x - a.x, b.y - a.y);
    let length = dx.hypot(dy).max(1e-12);
    (dx / length, dy / length)
}

fn same_direction(u: (f64, f64), v: (f64, f64)) -> bool {
    (u.0 * v.1 - u.1 * v.0).abs() < 1e-9 && u.0 * v.0 + u.1 * v.1 > 0.0
}

/// Turns between flying `heading` and then `next`, as [`GridRoute::measure`] counts them:
/// none straight on, two for a reversal in place, one for any other change.
fn turn_between(heading: Heading, next: (f64, f64)) -> usize {
    match heading {
        Some(h) if same_direction(h, next) => 0,
        Some(h) if h.0 * next.0 + h.1 * next.1 < -0.999_999 => 2,
        Some(_) => 1,
        None => 0,
    }
}

impl Search<'_> {
    fn ends(&self, (run, reversed): Step) -> (usize, usize) {
        let points = &self.runs[run];
        let (first, last) = (points[0], *points.last().expect("runs are not empty"));
        if reversed {
            (last, first)
        } else {
            (first, last)
        }
    }

    /// The direction a step flies, if it has two points or more.
    fn along(&self, step: Step) -> Option<(f64, f64)> {
        let (first, last) = self.ends(step);
        (first != last).then(|| unit(self.grid.centre(first), self.grid.centre(last)))
    }

    fn transit(&mut self, a: usize, b: usize) -> Option<Vec<Coord<f64>>> {
        let grid = self.grid;
        self.transits
            .entry((a, b))
            .or_insert_with(|| grid.transit(a, b))
            .clone()
    }

    fn junction(&mut self, from: Step, to: Step) -> Option<Junction> {
        let key = step_index(from) * 2 * self.runs.len() + step_index(to);
        if self.junctions.is_empty() {
            self.junctions = vec![None; 4 * self.runs.len() * self.runs.len()];
        }
        if let Some(known) = self.junctions[key] {
            return known;
        }
        let (_, exit) = self.ends(from);
        let (entry, _) = self.ends(to);
        let junction = self.transit(exit, entry).map(|via| {
            let mut vertices = vec![self.grid.centre(exit)];
            vertices.extend(via.iter().copied());
            vertices.push(self.grid.centre(entry));
            let adjacent = via.is_empty() && self.grid.adjacent(exit, entry);
            let distance = if adjacent {
                0.0
            } else {
                vertices
                    .windows(2)
                    .map(|w| (w[1].x - w[0].x).hypot(w[1].y - w[0].y))
                    .sum()
            };
            Junction {
                first: unit(vertices[0], vertices[1]),
                last: unit(vertices[vertices.len() - 2], vertices[vertices.len() - 1]),
                inner: via.len(),
                distance,
            }
        });
        self.junctions[key] = Some(junction);
        junction
    }

    /// (turns, non-spray metres) of flying the runs in this order; `None` if a junction has
    /// no clear way.
    fn cost(&mut self, order: &[Step]) -> Option<(usize, f64)> {
        let mut turns = 0;
        let mut distance = 0.0;
        // The direction the drone flies at the end of what came before.
        let mut heading: Option<(f64, f64)> = None;
        for (k, &step) in order.iter().enumerate() {
            let (first, last) = self.ends(step);
            if first != last {
                let along = unit(self.grid.centre(first), self.grid.centre(last));
                turns += turn_between(heading, along);
                heading = Some(along);
            }
            if let Some(&next) = order.get(k + 1) {
                let junction = self.junction(step, next)?;
                turns += turn_between(heading, junction.first);
                turns += junction.inner;
                distance += junction.distance;
                heading = Some(junction.last);
            }
        }
        Some((turns, distance))
    }

    fn better(a: Option<(usize, f64)>, b: Option<(usize, f64)>) -> bool {
        match (a, b) {
            (Some(a), Some(b)) => a.0 < b.0 || (a.0 == b.0 && a.1 < b.1 - 1e-9),
            (Some(_), None) => true,
            _ => false,
        }
    }

    /// Greedy chains from the run ends nearest the field's corners; the best.
    fn greedy(&mut self) -> Vec<Step> {
        let corners = {
            let (w, h) = (self.grid.columns as i64 - 1, self.grid.rows as i64 - 1);
            [(0, 0), (w, 0), (0, h), (w, h)]
        };
        let mut starts: Vec<Step> = Vec::new();
        for corner in corners {
            let nearest = (0..self.runs.len())
                .flat_map(|r| [(r, false), (r, true)])
                .min_by_key(|&step| {
                    let (c, r) = self.grid.cell(self.ends(step).0);
                    ((c - corner.0).abs() + (r - corner.1).abs(), step.0, step.1)
                })
                .expect("at least one run");
            if !starts.contains(&nearest) {
                starts.push(nearest);
            }
        }
        let mut best: Option<(Vec<Step>, Cost)> = None;
        for start in starts {
            let mut order = vec![start];
            let mut used = vec![false; self.runs.len()];
            used[start.0] = true;
            let mut heading = self.along(start);
            while order.len() < self.runs.len() {
                let last = *order.last().expect("not empty");
                // Only the entries nearest the exit are worth a junction: a far one costs at
                // least the same turns and more distance.
                let (_, exit) = self.ends(last);
                let mut nearby: Vec<(i64, Step)> = (0..self.runs.len())
                    .filter(|&run| !used[run])
                    .flat_map(|run| [(run, false), (run, true)])
                    .map(|step| {
                        let ((a, b), (c, d)) =
                            (self.grid.cell(exit), self.grid.cell(self.ends(step).0));
                        ((a - c).abs() + (b - d).abs(), step)
                    })
                    .collect();
                nearby.sort_unstable();
                nearby.truncate(NEAREST_ENTRIES);
                let mut choice: Option<(Step, (usize, f64), Heading)> = None;
                for &(_, next) in &nearby {
                    {
                        let Some(junction) = self.junction(last, next) else {
                            continue;
                        };
                        let mut turns = junction.inner + turn_between(heading, junction.first);
                        let along = self.along(next);
                        let after = along.or(Some(junction.last));
                        if let Some(along) = along {
                            turns += turn_between(Some(junction.last), along);
                        }
                        let cost = (turns, junction.distance);
                        if choice
                            .as_ref()
                            .is_none_or(|(_, c, _)| Self::better(Some(cost), Some(*c)))
                        {
                            choice = Some((next, cost, after));
                        }
                    }
                }
                let Some((next, _, after)) = choice else {
                    break;
                };
                used[next.0] = true;
                order.push(next);
                heading = after;
            }
            if order.len() < self.runs.len() {
                continue;
            }
            let cost = self.cost(&order);
            if best.as_ref().is_none_or(|(_, c)| Self::better(cost, *c)) {
                best = Some((order, cost));
            }
        }
        best.map(|(order, _)| order)
            .unwrap_or_else(|| (0..self.runs.len()).map(|r| (r, false)).collect())
    }

    /// Relocation (with either direction), reversal of a stretch, single flips: first
    /// improvement until none helps.
    fn improve(&mut self, mut order: Vec<Step>) -> Vec<Step> {
        let mut cost = self.cost(&order);
        let mut improved = true;
        while improved {
            improved = false;
            let n = order.len();
            for i in 0..n {
                for j in (i + 1)..=(i + WINDOW).min(n) {
                    let mut candidate = order.clone();
                    candidate[i..j].reverse();
                    for step in &mut candidate[i..j] {
                        step.1 = !step.1;
                    }
                    let c = self.cost(&candidate);
                    if Self::better(c, cost) {
                        (order, cost, improved) = (candidate, c, true);
                    }
                }
            }
            for i in 0..n {
                for target in i.saturating_sub(WINDOW)..(i + WINDOW + 1).min(n) {
                    if target == i {
                        continue;
                    }
                    for flip in [false, true] {
                        let mut candidate = order.clone();
                        let mut step = candidate.remove(i);
                        step.1 ^= flip;
                        candidate.insert(target, step);
                        let c = self.cost(&candidate);
                        if Self::better(c, cost) {
                            (order, cost, improved) = (candidate, c, true);
                        }
                    }
                }
            }
        }
        order
    }

    fn route(&mut self, order: &[Step]) -> GridRoute {
        let mut visits = Vec::new();
        let mut via = Vec::new();
        for (k, &step) in order.iter().enumerate() {
            let mut points = self.runs[step.0].clone();
            if step.1 {
                points.reverse();
            }
            for (i, &p) in points.iter().enumerate() {
                visits.push(p);
                if i + 1 < points.len() {
                    via.push(vec![]);
                }
            }
            if let Some(&next) = order.get(k + 1) {
                let (entry, _) = self.ends(next);
                let last = *points.last().expect("runs are not empty");
                let vertices = self.transit(last, entry).unwrap_or_default();
                via.push(vertices.iter().map(|c| [c.x, c.y]).collect());
            }
        }
        GridRoute { visits, via }
    }
}

/// The candidate decompositions with the fewest runs: the two single-direction sweeps and
/// every assignment of a direction to the cells of each boustrophedon decomposition (up to
/// 2^12 per decomposition, counted from per-cell run counts before any is built), keeping
/// those within `EXTRA_RUNS` of the fewest, at most `SCREENED` of them.
fn decompositions(grid: &PointGrid) -> Vec<Vec<Vec<usize>>> {
    let mut candidates: Vec<(usize, Vec<Vec<usize>>)> = [Sweep::AlongY, Sweep::AlongX]
        .into_iter()
        .map(|sweep| {
            let all = runs(grid, &grid.points, sweep);
            (all.len(), all)
        })
        .collect();
    let mut assignments: Vec<(usize, usize, u32)> = Vec::new();
    let decompositions = [cells(grid, Sweep::AlongY), cells(grid, Sweep::AlongX)];
    let per_cell: Vec<Vec<[Vec<Vec<usize>>; 2]>> = decompositions
        .iter()
        .map(|cells| {
            cells
                .iter()
                .map(|cell| {
                    [
                        runs(grid, cell, Sweep::AlongY),
                        runs(grid, cell, Sweep::AlongX),
                    ]
                })
                .collect()
        })
        .collect();
    for (d, cells) in per_cell.iter().enumerate() {
        if cells.len() > 12 {
            continue;
        }
        for mask in 0u32..(1 << cells.len()) {
            let count = cells
                .iter()
                .enumerate()
                .map(|(k, both)| both[usize::from(mask & (1 << k) != 0)].len())
                .sum();
            assignments.push((count, d, mask));
        }
    }
    let fewest = candidates
        .iter()
        .map(|c| c.0)
        .chain(assignments.iter().map(|a| a.0))
        .min()
        .unwrap_or(0);
    assignments.retain(|a| a.0 <= fewest + EXTRA_RUNS);
    assignments.sort_unstable();
    assignments.truncate(SCREENED);
    for (count, d, mask) in assignments {
        let all = per_cell[d]
            .iter()
            .enumerate()
            .flat_map(|(k, both)| both[usize::from(mask & (1 << k) != 0)].clone())
            .collect();
        candidates.push((count, all));
    }
    candidates
        .into_iter()
        .filter(|c| c.0 <= fewest + EXTRA_RUNS)
        .map(|c| c.1)
        .collect()
}

/// At most this many cell assignments are chained.
const SCREENED: usize = 12;

/// Run entries the greedy chain looks at from each exit.
const NEAREST_ENTRIES: usize = 8;
/// How many decompositions get the local search.
const REFINED: usize = 2;
/// Moves in the local search stay within this many places of the run moved (runs near in
/// the order are near in the field; far junctions are dear to compute and never pay).
const WINDOW: usize = 8;
/// Decompositions with more runs than the fewest plus this are not tried.
const EXTRA_RUNS: usize = 2;

/// The fewest-turn route over `grid`.
pub fn plan(grid: &PointGrid) -> GridRoute {
    if grid.points.is_empty() {
        return GridRoute::direct(vec![]);
    }
    let mut screened: Vec<Screened> = Vec::new();
    let mut transits = HashMap::new();
    let mut all = decompositions(grid);
    // Rings have more runs than a boustrophedon but join them with L-turns (one turn, not
    // two), so they are screened by their chained turns, not by their run count.
    for corner in [Sweep::AlongX, Sweep::AlongY] {
        all.push(super::rings::ring_runs(grid, corner));
    }
    for decomposition in all {
        let mut search = Search {
            grid,
            runs: decomposition,
            transits: std::mem::take(&mut transits),
            junctions: Vec::new(),
        };
        let order = search.greedy();
        let cost = search.cost(&order);
        transits = search.transits;
        screened.push((cost, search.runs, order));
    }
    screened.sort_by(|a, b| {
        if Search::better(a.0, b.0) {
            std::cmp::Ordering::Less
        } else if Search::better(b.0, a.0) {
            std::cmp::Ordering::Greater
        } else {
            std::cmp::Ordering::Equal
        }
    });
    let mut best: Option<(Option<(usize, f64)>, GridRoute)> = None;
    for (_, runs, order) in screened.into_iter().take(REFINED) {
        let mut search = Search {
            grid,
            runs,
            transits: std::mem::take(&mut transits),
            junctions: Vec::new(),
        };
        let order = search.improve(order);
        let cost = search.cost(&order);
        let route = search.route(&order);
        transits = search.transits;
        if best.as_ref().is_none_or(|(c, _)| Search::better(cost, *c)) {
            best = Some((cost, route));
        }
    }
    best.expect("at least one decomposition")
        .1
        .around_obstacles(grid)
}

/// The route through `runs` in the given order, each entered at its end nearer the previous
/// exit (the first from its first point): how a fixed-order plan is flown.
pub fn fly_in_order(grid: &PointGrid, runs: Vec<Vec<usize>>) -> GridRoute {
    fly_in_order_unchecked(grid, runs).around_obstacles(grid)
}

fn fly_in_order_unchecked(grid: &PointGrid, runs: Vec<Vec<usize>>) -> GridRoute {
    let mut search = Search {
        grid,
        runs,
        transits: HashMap::new(),
        junctions: Vec::new(),
    };
    let mut order: Vec<Step> = Vec::new();
    for run in 0..search.runs.len() {
        let reversed = order.last().is_some_and(|&previous| {
            let (_, exit) = search.ends(previous);
            let distance = |p: usize| {
                let (a, b) = (grid.cell(exit), grid.cell(p));
                (a.0 - b.0).abs() + (a.1 - b.1).abs()
            };
            let points = &search.runs[run];
            distance(*points.last().expect("runs are not empty")) < distance(points[0])
        });
        order.push((run, reversed));
    }
    search.route(&order)
}
