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
//! drawn uniformly for every crossover, sub-paths of 2 to n/4 points. Permutations are not a
//! box, so this search has its own loop rather than `swarm`'s Runner; it is seeded the same way.

use swarm::{below, run_stream, RunStream};

use super::{GridRoute, PointGrid};

/// HPSO's settings.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HpsoSettings {
    pub particles: usize,
    pub iterations: usize,
    pub seed: u64,
}

impl Default for HpsoSettings {
    fn default() -> Self {
        Self {
            particles: 40,
            iterations: 1_000,
            seed: 1,
        }
    }
}

const CROSSING_PENALTY: usize = 1_000;

/// The turn count (plus penalties) of a permutation, on precomputed tables.
struct Fitness {
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

impl Fitness {
    fn adjacent(&self, a: usize, b: usize) -> bool {
        let ((ca, ra), (cb, rb)) = (self.cells[a], self.cells[b]);
        (ca - cb).abs() + (ra - rb).abs() == 1
    }

    fn cost(&self, order: &[usize]) -> usize {
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
            if previous.is_some_and(|p| p != direction) {
                turns += 1;
            }
            previous = Some(direction);
        }
        turns
    }
}

fn mutate(order: &mut [usize], fitness: &Fitness, stream: &mut RunStream) {
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

fn crossover(order: &[usize], guide: &[usize], stream: &mut RunStream) -> Vec<usize> {
    let n = guide.len();
    let length = 2 + below(stream, (n / 4).max(1));
    let start = below(stream, n.saturating_sub(length) + 1);
    let piece = &guide[start..(start + length).min(n)];
    let mut taken = vec![false; n];
    for &p in piece {
        taken[p] = true;
    }
    let mut rest: Vec<usize> = order.iter().copied().filter(|&p| !taken[p]).collect();
    let at = match below(stream, 3) {
        0 => rest.len(),
        1 => start.min(rest.len()),
        _ => below(stream, rest.len() + 1),
    };
    rest.splice(at..at, piece.iter().copied());
    rest
}

/// Runs HPSO on `grid`; returns the best route and its cost (turns, plus 1,000 per crossing).
pub fn plan(grid: &PointGrid, settings: &HpsoSettings) -> (GridRoute, usize) {
    let n = grid.points.len();
    if n < 3 {
        return (GridRoute::direct(grid.points.clone()), 0);
    }
    let fitness = Fitness {
        n,
        cells: grid.points.iter().map(|&p| grid.cell(p)).collect(),
        clear: grid.clear_table(),
    };
    let mut stream = run_stream(settings.seed, 0);
    let mut particles: Vec<Vec<usize>> = (0..settings.particles.max(1))
        .map(|_| {
            let mut order: Vec<usize> = (0..n).collect();
            for i in (1..n).rev() {
                order.swap(i, below(&mut stream, i + 1));
            }
            order
        })
        .collect();
    let mut costs: Vec<usize> = particles.iter().map(|p| fitness.cost(p)).collect();
    let mut personal = particles.clone();
    let mut personal_costs = costs.clone();
    let first_best = (0..particles.len())
        .min_by_key(|&k| costs[k])
        .expect("one particle");
    let (mut global, mut global_cost) = (particles[first_best].clone(), costs[first_best]);
    for _ in 0..settings.iterations {
        for k in 0..particles.len() {
            // ω·v: the seed's mutation, kept if better.
            let mut candidate = particles[k].clone();
            mutate(&mut candidate, &fitness, &mut stream);
            let cost = fitness.cost(&candidate);
            if cost < costs[k] {
                (particles[k], costs[k]) = (candidate, cost);
            }
            // c1·r1·(pbest − x) and c2·r2·(gbest − x): crossovers, kept if better.
            for guide in [personal[k].clone(), global.clone()] {
                let candidate = crossover(&particles[k], &guide, &mut stream);
                let cost = fitness.cost(&candidate);
                if cost < costs[k] {
                    (particles[k], costs[k]) = (candidate, cost);
                }
            }
            if costs[k] < personal_costs[k] {
                (personal[k], personal_costs[k]) = (particles[k].clone(), costs[k]);
            }
            if costs[k] < global_cost {
                (global, global_cost) = (particles[k].clone(), costs[k]);
            }
        }
    }
    let visits = global.iter().map(|&p| grid.points[p]).collect();
    (
        GridRoute::direct(visits).around_obstacles(grid),
        global_cost,
    )
}
