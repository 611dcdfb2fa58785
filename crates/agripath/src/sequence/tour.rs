//! The ordering problem: passes with two ends each (seed 001 §3: "each swath has two ends; the
//! drone enters at one and leaves at the other, so two swaths are four distances apart"), a
//! start, and tours that every sequencer returns and every cost is computed on.

use swarm::{below, RunStream};

use crate::coverage::drape::GroundPoint;

use super::transfer::TransferModel;

/// An end of a pass: `2·pass` is its first point (A), `2·pass + 1` its last (B).
pub type End = usize;

/// One pass in a tour: which, and whether it is flown from B to A.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Step {
    /// Index of the pass in the problem's `ends`.
    pub pass: usize,
    /// Whether the pass is flown from B to A.
    pub reversed: bool,
}

impl Step {
    /// The end the pass is entered by.
    pub fn entry(&self) -> End {
        2 * self.pass + usize::from(self.reversed)
    }

    /// The end the pass is left by.
    pub fn exit(&self) -> End {
        2 * self.pass + usize::from(!self.reversed)
    }

    /// The same pass flown the other way.
    pub fn flipped(self) -> Self {
        Self {
            reversed: !self.reversed,
            ..self
        }
    }
}

/// Where the flight starts and ends, which fixes what the tour cost counts (decision 0018).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Start {
    /// Starts and ends at a given point (the launch or supply point): the objective counts
    /// the leg out to the first pass and the leg home from the last.
    Fixed(GroundPoint),
    /// From a given point to wherever the last pass ends: the leg home is not counted, as
    /// seed 001 §4.2.2 counts its Table 8 tours from C1, A75 and B58.
    From(GroundPoint),
    /// No point; a closed tour that comes back to its first pass's entry (seed 001's free
    /// start, and the stand-in for a flight that must come back to a point not yet chosen).
    Closed,
    /// No point; an open path: the first and the last pass are free and nothing closes it.
    Open,
}

impl Start {
    /// The start point, when there is one.
    pub fn point(&self) -> Option<GroundPoint> {
        match self {
            Start::Fixed(point) | Start::From(point) => Some(*point),
            Start::Closed | Start::Open => None,
        }
    }

    /// Whether the tour wraps around: its last pass leads back to its first (no point).
    pub fn is_closed(&self) -> bool {
        matches!(self, Start::Closed)
    }

    /// Whether the objective counts a leg from the last pass back to the start point.
    pub fn returns_home(&self) -> bool {
        matches!(self, Start::Fixed(_))
    }

    /// Whether the first pass is free to be any pass (no start point before it).
    pub fn free_first(&self) -> bool {
        self.point().is_none()
    }
}

/// Where a part of an ordering problem ([`OrderingProblem::part`]) starts and ends, in ends
/// of the whole problem.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PartBounds {
    /// Between the end flown just before the part and the end flown just after it.
    Between {
        /// The exit of the pass before the part.
        before: End,
        /// The entry of the pass after the part.
        after: End,
    },
    /// From an end (the part's first pass follows it), to a free last pass.
    From(End),
}

/// Pass ends and the transfer cost between them.
pub struct OrderingProblem<'a> {
    /// For each pass, its two ends (equal for a closed edge pass).
    pub ends: Vec<[GroundPoint; 2]>,
    /// The field each pass lies in, when known (it narrows eq. 8's geometric test).
    pub fields: Option<Vec<usize>>,
    /// Where the flight starts (fixed at construction: the start costs are precomputed).
    pub start: Start,
    model: &'a TransferModel<'a>,
    /// Every end-to-end cost, precomputed when there are few enough ends.
    matrix: Option<Vec<f64>>,
    /// Without the full matrix: the costs between ends of one field, precomputed field by
    /// field (the only pairs eq. 8's geometric test is needed for).
    field_blocks: Option<FieldBlocks>,
    /// The cost between the start point and every end, precomputed (the local search asks
    /// for it at every move at the ends of the tour).
    start_costs: Vec<f64>,
}

/// Ends up to which all end-to-end costs are precomputed (2000² × 8 bytes = 32 MB).
const MATRIX_LIMIT_ENDS: usize = 2000;

/// Most costs the field blocks of a large problem hold in all (8 M × 8 bytes = 64 MB).
const FIELD_BLOCKS_LIMIT: usize = 8_000_000;

/// On a farm with more ends than [`MATRIX_LIMIT_ENDS`], the end-to-end costs within each
/// field. Between two fields a transfer always climbs (eq. 8's test is only needed inside
/// one field), so those costs are cheap to compute; within a field each needs the polygon
/// test, and the local search asks for the same pairs again and again: a 5,000-swath farm
/// spent most of its ordering time in that test. Values are the same as computed.
struct FieldBlocks {
    /// Each end's row in its field's block.
    row: Vec<usize>,
    /// Each field's block (its ends × its ends), when it fitted in [`FIELD_BLOCKS_LIMIT`].
    blocks: Vec<Option<(usize, Vec<f64>)>>,
}

impl FieldBlocks {
    fn build(problem: &OrderingProblem, fields: &[usize]) -> Self {
        let count = 2 * problem.ends.len();
        let field_count = fields.iter().max().map_or(0, |&field| field + 1);
        let mut members: Vec<Vec<End>> = vec![Vec::new(); field_count];
        let mut row = vec![0; count];
        for (end, row) in row.iter_mut().enumerate() {
            let members = &mut members[fields[end / 2]];
            *row = members.len();
            members.push(end);
        }
        // Fields in order while the blocks fit; a field left out is computed on demand.
        let mut room = FIELD_BLOCKS_LIMIT;
        let wanted: Vec<bool> = members
            .iter()
            .map(|ends| {
                let size = ends.len() * ends.len();
                let fits = ends.len() <= MATRIX_LIMIT_ENDS && size <= room;
                if fits {
                    room -= size;
                }
                fits
            })
            .collect();
        let blocks = members
            .iter()
            .zip(wanted)
            .map(|(ends, wanted)| {
                wanted.then(|| {
                    let size = ends.len();
                    let mut block = vec![0.0; size * size];
                    for (from_row, &from) in ends.iter().enumerate() {
                        for (to_row, &to) in ends.iter().enumerate().take(from_row) {
                            let cost = problem.compute(from, to);
                            block[from_row * size + to_row] = cost;
                            block[to_row * size + from_row] = cost;
                        }
                    }
                    (size, block)
                })
            })
            .collect();
        Self { row, blocks }
    }

    /// The precomputed cost, when both ends lie in one field that has a block.
    fn cost(&self, fields: &[usize], from: End, to: End) -> Option<f64> {
        let field = fields[from / 2];
        if field != fields[to / 2] {
            return None;
        }
        let (size, block) = self.blocks[field].as_ref()?;
        Some(block[self.row[from] * size + self.row[to]])
    }
}

impl<'a> OrderingProblem<'a> {
    /// The problem of ordering the passes with `ends` from `start`, transfers costed by
    /// `model`; all end-to-end costs are precomputed when there are at most 2,000 ends.
    pub fn new(ends: Vec<[GroundPoint; 2]>, start: Start, model: &'a TransferModel<'a>) -> Self {
        Self::build(ends, None, start, model)
    }

    /// As [`Self::new`], knowing the field of each pass.
    pub fn with_fields(
        ends: Vec<[GroundPoint; 2]>,
        fields: Vec<usize>,
        start: Start,
        model: &'a TransferModel<'a>,
    ) -> Self {
        Self::build(ends, Some(fields), start, model)
    }

    fn build(
        ends: Vec<[GroundPoint; 2]>,
        fields: Option<Vec<usize>>,
        start: Start,
        model: &'a TransferModel<'a>,
    ) -> Self {
        let count = 2 * ends.len();
        let mut problem = Self {
            ends,
            fields,
            start,
            model,
            matrix: None,
            field_blocks: None,
            start_costs: Vec::new(),
        };
        if let Some(point) = start.point() {
            problem.start_costs = (0..count)
                .map(|end| model.cost(point, problem.point(end)))
                .collect();
        }
        if count <= MATRIX_LIMIT_ENDS {
            // The lower triangle row by row, rows spread over the cores (eq. 8's polygon test
            // is most of an ordering problem's build); the same costs on any number of them.
            let rows: Vec<usize> = (0..count).collect();
            let lower = crate::parallel::map_in_order(&rows, |&from| {
                (0..from)
                    .map(|to| problem.compute(from, to))
                    .collect::<Vec<f64>>()
            });
            let mut matrix = vec![0.0; count * count];
            for (from, row) in lower.iter().enumerate() {
                for (to, &cost) in row.iter().enumerate() {
                    matrix[from * count + to] = cost;
                    matrix[to * count + from] = cost;
                }
            }
            problem.matrix = Some(matrix);
        } else {
            let blocks = problem
                .fields
                .as_deref()
                .map(|fields| FieldBlocks::build(&problem, fields));
            problem.field_blocks = blocks;
        }
        problem
    }

    /// The problem of flying only `passes` of this one (pass i of the part is `passes[i]`, its
    /// ends in the same order), with every cost read from this problem's matrix, so a part
    /// costs no eq. (8) test. Its start, in ends of this problem:
    ///
    /// - `Between(before, after)`: the part lies between two ends flown before and after it.
    ///   The part gets one more pass, the *connector*, whose ends are `after` and `before`,
    ///   and is a closed tour: flying the connector from `after` to `before` (its length is
    ///   no transfer, so it costs nothing) closes the part's passes into the cycle `before`
    ///   → passes → `after`, whose transfers are exactly those the part adds between them;
    /// - `From(end)`: a path from `end` with a free last pass.
    ///
    /// `None` when this problem has no cost matrix (above 2,000 ends).
    pub fn part(&self, passes: &[usize], bounds: PartBounds) -> Option<OrderingProblem<'a>> {
        let parent = self.matrix.as_ref()?;
        let parent_count = 2 * self.ends.len();
        let mut parent_ends: Vec<End> = passes
            .iter()
            .flat_map(|&pass| [2 * pass, 2 * pass + 1])
            .collect();
        let start = match bounds {
            PartBounds::Between { before, after } => {
                parent_ends.extend([after, before]);
                Start::Closed
            }
            PartBounds::From(end) => Start::From(self.point(end)),
        };
        let count = parent_ends.len();
        let mut matrix = vec![0.0; count * count];
        for (from, &parent_from) in parent_ends.iter().enumerate() {
            let row = &parent[parent_from * parent_count..(parent_from + 1) * parent_count];
            for (to, &parent_to) in parent_ends.iter().enumerate() {
                matrix[from * count + to] = row[parent_to];
            }
        }
        let start_costs = match bounds {
            PartBounds::From(end) => parent_ends.iter().map(|&to| self.cost(end, to)).collect(),
            PartBounds::Between { .. } => Vec::new(),
        };
        Some(OrderingProblem {
            ends: parent_ends
                .chunks(2)
                .map(|pair| [self.point(pair[0]), self.point(pair[1])])
                .collect(),
            fields: None,
            start,
            model: self.model,
            matrix: Some(matrix),
            field_blocks: None,
            start_costs,
        })
    }

    fn compute(&self, from: End, to: End) -> f64 {
        match &self.fields {
            Some(fields) => self.model.cost_between_fields(
                self.point(from),
                self.point(to),
                fields[from / 2],
                fields[to / 2],
            ),
            None => self.model.cost(self.point(from), self.point(to)),
        }
    }

    /// The same problem with its costs computed on demand, as above 2,000 ends (for tests of
    /// the paths that run without the matrix, on small instances).
    #[cfg(test)]
    pub(crate) fn without_cost_matrix(mut self) -> Self {
        self.matrix = None;
        self
    }

    /// Number of passes.
    pub fn passes(&self) -> usize {
        self.ends.len()
    }

    /// Where `end` lies.
    pub fn point(&self, end: End) -> GroundPoint {
        self.ends[end / 2][end % 2]
    }

    /// Whether every end-to-end cost is precomputed (at most 2,000 ends): then a cost costs a
    /// lookup, and a scan of all ends by cost is cheap.
    pub fn has_cost_matrix(&self) -> bool {
        self.matrix.is_some()
    }

    /// Eq. (8) between two ends (symmetric).
    ///
    /// Inlined: the local search asks for costs in its innermost loops, where a call per
    /// lookup was a third of its time; the path without the matrix stays out of line.
    #[inline]
    pub fn cost(&self, from: End, to: End) -> f64 {
        match &self.matrix {
            Some(matrix) => matrix[from * 2 * self.ends.len() + to],
            None => self.cost_without_matrix(from, to),
        }
    }

    #[inline(never)]
    fn cost_without_matrix(&self, from: End, to: End) -> f64 {
        self.field_blocks
            .as_ref()
            .zip(self.fields.as_deref())
            .and_then(|(blocks, fields)| blocks.cost(fields, from, to))
            .unwrap_or_else(|| self.compute(from, to))
    }

    /// Whether the transfer from `from` to `to` climbs out of the field: eq. (8) adds 2h to
    /// its 3D length exactly then.
    pub fn climbs(&self, from: End, to: End) -> bool {
        self.cost_and_climbs(from, to).1
    }

    /// Eq. (8) between two ends and whether that transfer climbs out of the field, with
    /// one cost: above 2,000 ends a cost is computed (a polygon test), not looked up.
    pub fn cost_and_climbs(&self, from: End, to: End) -> (f64, bool) {
        let (a, b) = (self.point(from), self.point(to));
        let straight =
            ((a.x - b.x).powi(2) + (a.y - b.y).powi(2) + (a.ground_m - b.ground_m).powi(2)).sqrt();
        let cost = self.cost(from, to);
        (cost, cost > straight + 1e-6)
    }

    /// Between the start point and an end, either way (eq. 8 is symmetric); 0 when there is
    /// no start point.
    pub fn cost_from_start(&self, to: End) -> f64 {
        self.start_costs.get(to).copied().unwrap_or(0.0)
    }

    /// Total transfer cost of a tour, as [`Start`] says what counts: the transfers between
    /// passes; plus the leg from the start point (`Fixed`, `From`); plus the leg home
    /// (`Fixed`); plus the leg from the last pass back to the first (`Closed`). An `Open`
    /// tour has nothing else: its objective has no closing leg.
    pub fn tour_cost(&self, tour: &[Step]) -> f64 {
        let (Some(first), Some(last)) = (tour.first(), tour.last()) else {
            return 0.0;
        };
        let between: f64 = tour
            .windows(2)
            .map(|pair| self.cost(pair[0].exit(), pair[1].entry()))
            .sum();
        let ends = match self.start {
            Start::Fixed(_) => {
                self.cost_from_start(first.entry()) + self.cost_from_start(last.exit())
            }
            Start::From(_) => self.cost_from_start(first.entry()),
            Start::Closed => self.cost(last.exit(), first.entry()),
            Start::Open => 0.0,
        };
        between + ends
    }
}

/// The ordering problem as the engine sees it: a tour of oriented passes, costed by eq. (8)'s
/// transfers ([`OrderingProblem::tour_cost`]). The ant colony, the local search and the
/// random-search baseline all run on it through `swarm`'s Runner.
impl swarm::Problem for OrderingProblem<'_> {
    type Solution = [Step];

    fn evaluate(&self, tour: &[Step]) -> f64 {
        self.tour_cost(tour)
    }

    /// Every pass in its index order, flown A to B.
    fn first_solution(&self) -> Vec<Step> {
        (0..self.passes())
            .map(|pass| Step {
                pass,
                reversed: false,
            })
            .collect()
    }

    /// A uniform order (Fisher-Yates) with each pass's direction a fair coin.
    fn random_solution(&self, stream: &mut RunStream) -> Vec<Step> {
        let mut tour = self.first_solution();
        for index in (1..tour.len()).rev() {
            tour.swap(index, below(stream, index + 1));
        }
        for step in &mut tour {
            step.reversed = below(stream, 2) == 1;
        }
        tour
    }
}

/// The shared check of a pass order: every one of `passes` passes exactly once. Used by unit
/// and property tests, the engine's conformance runs and the sequencers' own assertions.
pub fn check_order(tour: &[Step], passes: usize) -> Result<(), String> {
    if tour.len() != passes {
        return Err(format!("{} steps for {passes} passes", tour.len()));
    }
    let mut seen = vec![false; passes];
    for (index, step) in tour.iter().enumerate() {
        if step.pass >= passes {
            return Err(format!(
                "step {index} flies pass {}, of {passes}",
                step.pass
            ));
        }
        if std::mem::replace(&mut seen[step.pass], true) {
            return Err(format!(
                "step {index} flies pass {} a second time",
                step.pass
            ));
        }
    }
    Ok(())
}

/// Every pass exactly once ([`check_order`] as a yes or no).
pub fn is_permutation(tour: &[Step], passes: usize) -> bool {
    check_order(tour, passes).is_ok()
}
