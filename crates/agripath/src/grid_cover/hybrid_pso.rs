//! `hpso`: seed 004's hybrid particle swarm over permutations of the path points (§2).
//!
//! A particle is a route: a permutation of the valid points. The terms of PSO's velocity
//! update (eq. 2) become operators, each kept only if it makes the particle better:
//! - ω·v: mutation by the seed's own rule: pick P_i whose successor P_{i+1} is not its
//!   neighbour on the grid, pick P_j (≠ P_i) with the same property, swap them;
//! - c1·r1·(pbest − x): crossover with the particle's best: take a random sub-path C0 of
//!   pbest, delete its points from the route and put C0 back (1) at the end, (2) where it was
//!   in pbest, or (3) at a random place — the three variants the seed lists;
//! - c2·r2·(gbest − x): the same crossover with the swarm's best.
//!
//! Fitness (eq. 3) falls with the turn count T (the seed maximises a fitness of T; we minimise
//! T). A move that crosses an obstacle is not a route: each costs 1,000 turns, so valid routes
//! always win. Initial routes are random permutations (step 1).
//!
//! Parameters the seed does not give: 40 particles, 1,000 iterations (the 1 s budget), the crossover variant
//! drawn uniformly for every crossover, sub-paths of 2 to n/4 points. The swarm runs on
//! `swarm`'s Runner over [`TurnProblem`] (a permutation of the points): one iteration per step,
//! run 0 of the settings' seed; the route returned is the Runner's best.
//!
//! The seed leaves four choices open (its steps 3-5 are missing from the text); the settings
//! name them so that the ablation of issue 20 can try each reading (`examples/
//! seed004_hpso_ablation.rs`, decision 0010), the defaults being the reading above:
//! - the initial population ([`Initial`]): random permutations (step 1 as printed), or seeded
//!   with a boustrophedon, particle k being it after k of the seed's mutations (k = 0 … P − 1);
//! - the mutation rate: the probability that a particle gets the ω·v mutation in an iteration
//!   (1: every time, as eq. 2 has the term in every update);
//! - the crossover placement ([`Placement`]): one of the seed's three, or drawn per crossover;
//! - the iterations.

use swarm::{below, Optimizer, RunStream, Runner, Search, Termination};

use super::{GridRoute, PointGrid};

/// HPSO's settings.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HpsoSettings {
    /// Swarm size, in routes (at least 1).
    pub particles: usize,
    /// Iterations the swarm runs (at least 1).
    pub iterations: usize,
    /// The Runner's seed; the swarm is its run 0.
    pub seed: u64,
    /// Where the routes start.
    pub initial: Initial,
    /// Probability in [0, 1] that a particle gets the mutation in an iteration.
    pub mutation_rate: f64,
    /// Where a crossover puts the sub-path it takes from the guide.
    pub placement: Placement,
}

impl Default for HpsoSettings {
    fn default() -> Self {
        Self {
            particles: 40,
            iterations: 1_000,
            seed: 1,
            initial: Initial::Random,
            mutation_rate: 1.0,
            placement: Placement::Drawn,
        }
    }
}

/// HPSO's initial population (an open choice of the seed).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Initial {
    /// Uniform random permutations: the seed's step 1 as printed.
    Random,
    /// The baseline's route ([`super::boustrophedon`]): cells swept along y.
    Baseline,
    /// The best single-direction boustrophedon (rows or columns, whichever has fewer runs).
    SingleDirection,
}

/// Where the crossover puts the sub-path C0 it takes from the guide (the seed lists three).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Placement {
    /// One of the three below, drawn uniformly for every crossover.
    #[default]
    Drawn,
    /// (1) At the end of the route.
    End,
    /// (2) Where it was in the guide.
    InPlace,
    /// (3) At a random place.
    Anywhere,
}

const CROSSING_PENALTY: usize = 1_000;

/// Seed 004's problem: the turn count (plus penalties) of a permutation of a grid's path
/// points, on precomputed tables.
pub struct TurnProblem {
    n: usize,
    cells: Vec<(i64, i64)>,
    clear: Vec<bool>,
}

fn reduced(dc: i64, dr: i64) -> (i64, i64) {
    fn gcd(a: i64, b: i64) -> i64 {
        if b == 0 {
            a.abs()
        } else {
            gcd(b, a % b)
        }
    }
    let g = gcd(dc, dr).max(1);
    (dc / g, dr / g)
}

impl TurnProblem {
    /// The problem of visiting every valid point of `grid`.
    pub fn new(grid: &PointGrid) -> Self {
        Self {
            n: grid.points.len(),
            cells: grid.points.iter().map(|&p| grid.cell(p)).collect(),
            clear: grid.clear_table(),
        }
    }

    fn adjacent(&self, a: usize, b: usize) -> bool {
        let ((ca, ra), (cb, rb)) = (self.cells[a], self.cells[b]);
        (ca - cb).abs() + (ra - rb).abs() == 1
    }

    /// Turns of the route visiting the points in `order` (a reversal in place counts two),
    /// plus 1,000 per move through an obstacle.
    pub fn cost(&self, order: &[usize]) -> usize {
        let mut turns = 0;
        let mut previous: Option<(i64, i64)> = None;
        for pair in order.windows(2) {
            let (a, b) = (pair[0], pair[1]);
            if !self.clear[a * self.n + b] {
                turns += CROSSING_PENALTY;
            }
            let (ca, ra) = self.cells[a];
            let (cb, rb) = self.cells[b];
            let direction = reduced(cb - ca, rb - ra);
            match previous {
                // Straight back along the last move: a 180° turn, counted as two (issue 20).
                Some(p) if p == (-direction.0, -direction.1) => turns += 2,
                Some(p) if p != direction => turns += 1,
                _ => {}
            }
            previous = Some(direction);
        }
        turns
    }
}

impl swarm::Problem for TurnProblem {
    type Solution = [usize];

    fn evaluate(&self, order: &[usize]) -> f64 {
        self.cost(order) as f64
    }

    /// The points in grid order.
    fn first_solution(&self) -> Vec<usize> {
        (0..self.n).collect()
    }

    /// A uniform permutation (Fisher-Yates), seed 004's step 1.
    fn random_solution(&self, stream: &mut RunStream) -> Vec<usize> {
        let mut order = self.first_solution();
        for i in (1..self.n).rev() {
            order.swap(i, below(stream, i + 1));
        }
        order
    }
}

/// The shared check of a point order: every one of `points` points exactly once.
pub fn check_point_order(order: &[usize], points: usize) -> Result<(), String> {
    if order.len() != points {
        return Err(format!("{} visits for {points} points", order.len()));
    }
    let mut seen = vec![false; points];
    for (index, &point) in order.iter().enumerate() {
        if point >= points || std::mem::replace(&mut seen[point], true) {
            return Err(format!(
                "visit {index} (point {point}) is outside or repeated"
            ));
        }
    }
    Ok(())
}

fn mutate(order: &mut [usize], fitness: &TurnProblem, stream: &mut RunStream) {
    let n = order.len();
    let loose: Vec<usize> = (0..n - 1)
        .filter(|&i| !fitness.adjacent(order[i], order[i + 1]))
        .collect();
    let (i, j) = if loose.len() >= 2 {
        let i = loose[below(stream, loose.len())];
        let mut j = loose[below(stream, loose.len())];
        while j == i {
            j = loose[below(stream, loose.len())];
        }
        (i, j)
    } else {
        (below(stream, n), below(stream, n))
    };
    order.swap(i, j);
}

fn crossover(
    order: &[usize],
    guide: &[usize],
    placement: Placement,
    stream: &mut RunStream,
) -> Vec<usize> {
    let n = guide.len();
    let length = 2 + below(stream, (n / 4).max(1));
    let start = below(stream, n.saturating_sub(length) + 1);
    let piece = &guide[start..(start + length).min(n)];
    let mut taken = vec![false; n];
    for &p in piece {
        taken[p] = true;
    }
    let mut rest: Vec<usize> = order.iter().copied().filter(|&p| !taken[p]).collect();
    let variant = match placement {
        Placement::Drawn => below(stream, 3),
        Placement::End => 0,
        Placement::InPlace => 1,
        Placement::Anywhere => 2,
    };
    let at = match variant {
        0 => rest.len(),
        1 => start.min(rest.len()),
        _ => below(stream, rest.len() + 1),
    };
    rest.splice(at..at, piece.iter().copied());
    rest
}

/// HPSO as an optimizer of [`TurnProblem`]: particles, their bests and the swarm's best.
#[derive(Debug, Clone, Default)]
pub struct HybridPso {
    particles: usize,
    /// A route every particle starts from (mutated k times for particle k); random when empty.
    seed_route: Vec<usize>,
    mutation_rate: f64,
    placement: Placement,
    routes: Vec<Vec<usize>>,
    costs: Vec<f64>,
    personal: Vec<Vec<usize>>,
    personal_costs: Vec<f64>,
    /// The swarm's best as the seed keeps it: updated after each particle's three moves, so
    /// a particle's c2 crossover follows the best of the particles before it. Not the
    /// Runner's best, which may already hold this particle's first move.
    global: Vec<usize>,
    global_cost: f64,
}

impl HybridPso {
    /// A swarm of `particles` routes (at least one), from random routes, the seed's
    /// mutation every iteration and the crossover placement drawn.
    pub fn new(particles: usize) -> Self {
        Self {
            particles: particles.max(1),
            mutation_rate: 1.0,
            placement: Placement::Drawn,
            ..Self::default()
        }
    }

    /// The swarm with the open choices of `settings`; `seed_route` (positions in the
    /// problem's points) is where every particle starts, or empty for random routes.
    pub fn with_settings(settings: &HpsoSettings, seed_route: Vec<usize>) -> Self {
        Self {
            seed_route,
            mutation_rate: settings.mutation_rate.clamp(0.0, 1.0),
            placement: settings.placement,
            ..Self::new(settings.particles)
        }
    }

    /// Keeps `candidate` for particle `k` if it is better (the seed's acceptance).
    fn offer(&mut self, k: usize, candidate: Vec<usize>, search: &mut Search<TurnProblem>) {
        let cost = search.evaluate(&candidate);
        if cost < self.costs[k] {
            (self.routes[k], self.costs[k]) = (candidate, cost);
        }
    }
}

impl Optimizer<TurnProblem> for HybridPso {
    fn name(&self) -> &'static str {
        "HPSO (seed 004)"
    }

    fn start(&mut self, search: &mut Search<TurnProblem>) {
        self.routes = if self.seed_route.is_empty() {
            (0..self.particles)
                .map(|_| search.random_solution())
                .collect()
        } else {
            let problem = search.problem();
            let mut route = self.seed_route.clone();
            let mut routes = Vec::with_capacity(self.particles);
            for _ in 0..self.particles {
                routes.push(route.clone());
                mutate(&mut route, problem, search.stream());
            }
            routes
        };
        self.costs = self.routes.iter().map(|p| search.evaluate(p)).collect();
        self.personal = self.routes.clone();
        self.personal_costs = self.costs.clone();
        let first_best = (0..self.routes.len())
            .min_by(|&a, &b| self.costs[a].total_cmp(&self.costs[b]))
            .expect("one particle");
        self.global = self.routes[first_best].clone();
        self.global_cost = self.costs[first_best];
    }

    fn step(&mut self, search: &mut Search<TurnProblem>) {
        let problem = search.problem();
        for k in 0..self.routes.len() {
            // ω·v: the seed's mutation, kept if better. At rate 1 no draw decides it, so the
            // default reading's random stream is the one it always was.
            if self.mutation_rate >= 1.0 || swarm::uniform(search.stream()) < self.mutation_rate {
                let mut candidate = self.routes[k].clone();
                mutate(&mut candidate, problem, search.stream());
                self.offer(k, candidate, search);
            }
            // c1·r1·(pbest − x) and c2·r2·(gbest − x): crossovers, kept if better.
            for guide in [self.personal[k].clone(), self.global.clone()] {
                let candidate = crossover(&self.routes[k], &guide, self.placement, search.stream());
                self.offer(k, candidate, search);
            }
            if self.costs[k] < self.personal_costs[k] {
                (self.personal[k], self.personal_costs[k]) =
                    (self.routes[k].clone(), self.costs[k]);
            }
            if self.costs[k] < self.global_cost {
                (self.global, self.global_cost) = (self.routes[k].clone(), self.costs[k]);
            }
        }
    }
}

/// Runs HPSO on `grid`; returns the best route and its cost (turns, plus 1,000 per crossing).
pub fn plan(grid: &PointGrid, settings: &HpsoSettings) -> (GridRoute, usize) {
    let n = grid.points.len();
    if n < 3 {
        return (GridRoute::direct(grid.points.clone()), 0);
    }
    let problem = TurnProblem::new(grid);
    let runner = Runner::new(
        Termination::iterations(settings.iterations.max(1)),
        settings.seed,
    )
    .expect("a budget of at least one iteration");
    let seed_route = match settings.initial {
        Initial::Random => Vec::new(),
        Initial::Baseline => positions(grid, &super::boustrophedon::plan(grid)),
        Initial::SingleDirection => positions(grid, &super::boustrophedon::single_direction(grid)),
    };
    let outcome = runner.run_problem(
        &mut HybridPso::with_settings(settings, seed_route),
        &problem,
        0,
        &mut (),
    );
    let visits = outcome
        .best_solution
        .iter()
        .map(|&p| grid.points[p])
        .collect();
    (
        GridRoute::direct(visits).around_obstacles(grid),
        outcome.best_cost as usize,
    )
}

/// The route's visits as positions in `grid.points` (the problem's numbering).
fn positions(grid: &PointGrid, route: &GridRoute) -> Vec<usize> {
    let mut position = vec![usize::MAX; grid.valid.len()];
    for (k, &p) in grid.points.iter().enumerate() {
        position[p] = k;
    }
    route.visits.iter().map(|&p| position[p]).collect()
}
