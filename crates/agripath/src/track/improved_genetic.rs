//! Seed 002's improved genetic algorithm (§3): variable-length chromosomes of waypoints,
//! hybrid no-duplicate selection, asymmetric mapping crossover with its two duplicate-gene
//! treatments, and heuristic multi-mutation. Smoothing is [`super::bspline`].
//!
//! - **Encoding** (§3.1): a chromosome is the list of waypoints between start and goal, real
//!   coded; the initial ones have `initial_length` random waypoints in the space.
//! - **Selection** (§3.3.1): a share α of the mating pool by binary tournament, 1 − α by
//!   roulette with probability ∝ 1 / cost; a candidate equal to one already chosen is dropped
//!   and drawn again.
//! - **Crossover** (§3.3.2, p_c = 1): two parents, one cut in each (asymmetric: the cuts
//!   differ, so children change length); children A₁B₂ and B₁A₂. Genes are duplicates when
//!   they fall in the same cell of the space divided into m intervals per axis (eqs. 18-19,
//!   x and y). While t ≤ β·T, *mapping before the cut*: genes before the cut stay, a duplicate
//!   after it is replaced by the gene it was exchanged with (A₂\[k\] for B₂\[k\]), following the
//!   mapping until a gene is new (dropped if none is). Later, *order copy after the cut*:
//!   genes after the cut stay, duplicates before it are filled, in order, with the other
//!   parent's genes the child lacks.
//! - **Mutation** (§3.3.3), on every child (p_m = 1/length: one gene per chromosome on
//!   average), `tries` times, the cheapest try kept: (1) find waypoints under the terrain,
//!   outside the space or whose incoming or outgoing leg cuts the terrain; (2) while there are
//!   any, redraw them at random (at most 10 rounds); (3) otherwise move one random waypoint
//!   (Gaussian, σ = 10 % of the space) and record in R the waypoints whose neighbours see each
//!   other directly; (4) delete one waypoint of R, or a random one if R is empty.
//! - **Replacement**: steady state without duplicates: parents and children together, equal
//!   chromosomes once, the best `population` kept.
//!
//! Decisions where the seed is silent (`docs/decisions/0011-tracks.md`): binary tournaments;
//! m = 20 intervals on x and y; R read as "redundant waypoints" (step 4 deletes a point the
//! path can skip); chromosomes between 1 and `max_length` waypoints; the run is measured in
//! evaluations like every planner here.
//!
//! The optimizer works on [`super::problem::TrackProblem`] with the Cartesian encoding and
//! room for `max_length` waypoints: a chromosome shorter than that is evaluated with its
//! remaining waypoints at the goal (zero-length legs, which seed 002's cost does not count).

use swarm::{Continuous, Optimizer, Search};

use super::scenario::TrackScenario;

/// The improved GA's parameters; `Default` is this planner's setting.
#[derive(Debug, Clone, PartialEq)]
pub struct ImprovedGeneticParameters {
    /// Chromosomes kept after each replacement (at least 2).
    pub population: usize,
    /// Waypoints of each initial chromosome (1 to `max_length`).
    pub initial_length: usize,
    /// Most waypoints a chromosome may hold; also the room of the Cartesian encoding.
    pub max_length: usize,
    /// α: the share of the mating pool chosen by tournament.
    pub tournament_share: f64,
    /// β: the share of the run using mapping-before-cut.
    pub phase_switch: f64,
    /// Mutation tries per child (the seed: 3 or 4).
    pub tries: usize,
    /// m of eq. (18) per axis.
    pub intervals: usize,
}

impl Default for ImprovedGeneticParameters {
    fn default() -> Self {
        Self {
            population: 50,
            initial_length: 9,
            max_length: 18,
            tournament_share: 0.8,
            phase_switch: 0.4,
            tries: 3,
            intervals: 20,
        }
    }
}

#[derive(Debug, Clone, PartialEq)]
struct Chromosome {
    genes: Vec<[f64; 3]>,
    cost: f64,
}

/// Seed 002's improved genetic algorithm: an optimizer of a [`super::problem::TrackProblem`]
/// with the Cartesian encoding and room for `max_length` waypoints.
pub struct ImprovedGenetic<'a> {
    parameters: ImprovedGeneticParameters,
    scenario: &'a TrackScenario,
    population: Vec<Chromosome>,
}

impl<'a> ImprovedGenetic<'a> {
    /// The improved GA over `scenario`; the population is drawn when the run starts.
    pub fn new(scenario: &'a TrackScenario, parameters: ImprovedGeneticParameters) -> Self {
        Self {
            parameters,
            scenario,
            population: Vec::new(),
        }
    }

    /// The padded Cartesian vector of a chromosome: unused room at the goal.
    fn padded(&self, genes: &[[f64; 3]]) -> Vec<f64> {
        let goal = self.scenario.cruise_goal;
        (0..self.parameters.max_length)
            .flat_map(|index| *genes.get(index).unwrap_or(&goal))
            .collect()
    }

    fn evaluate(&self, search: &mut Search<Continuous<'_>>, genes: Vec<[f64; 3]>) -> Chromosome {
        let mut x = self.padded(&genes);
        search.clamp(&mut x);
        let cost = search.evaluate(&x);
        Chromosome { genes, cost }
    }

    fn random_gene(&self, search: &mut Search<Continuous<'_>>) -> [f64; 3] {
        let (min_x, min_y, max_x, max_y) = self.scenario.area;
        let (low, high) = self.scenario.altitude_bounds;
        [
            search.uniform_in(min_x, max_x),
            search.uniform_in(min_y, max_y),
            search.uniform_in(low, high),
        ]
    }

    /// The interval cell of a gene on x and y (eqs. 18-19).
    fn cell(&self, gene: [f64; 3]) -> (usize, usize) {
        let (min_x, min_y, max_x, max_y) = self.scenario.area;
        let m = self.parameters.intervals;
        let index = |value: f64, low: f64, high: f64| {
            (((value - low) / (high - low) * m as f64) as usize).min(m - 1)
        };
        (index(gene[0], min_x, max_x), index(gene[1], min_y, max_y))
    }

    fn select(&self, search: &mut Search<Continuous<'_>>) -> Vec<Chromosome> {
        let wanted = self.population.len();
        let tournaments = (self.parameters.tournament_share * wanted as f64).round() as usize;
        let inverse: Vec<f64> = self
            .population
            .iter()
            .map(|c| 1.0 / c.cost.max(1e-12))
            .collect();
        let total: f64 = inverse.iter().sum();
        let mut pool: Vec<Chromosome> = Vec::with_capacity(wanted);
        let mut attempts = 0;
        while pool.len() < wanted {
            let pick = if pool.len() < tournaments {
                let (a, b) = (search.below(wanted), search.below(wanted));
                if self.population[a].cost <= self.population[b].cost {
                    a
                } else {
                    b
                }
            } else {
                let mut target = search.uniform() * total;
                let mut chosen = wanted - 1;
                for (index, weight) in inverse.iter().enumerate() {
                    target -= weight;
                    if target <= 0.0 {
                        chosen = index;
                        break;
                    }
                }
                chosen
            };
            attempts += 1;
            let candidate = &self.population[pick];
            // No duplicate strings, unless the population has too few distinct ones.
            if attempts < 20 * wanted && pool.iter().any(|c| c.genes == candidate.genes) {
                continue;
            }
            pool.push(candidate.clone());
        }
        pool
    }

    /// Children A₁B₂ and B₁A₂ of two parents cut at `cut_a` and `cut_b`, duplicates treated
    /// by the phase's rule.
    fn cross(
        &self,
        a: &[[f64; 3]],
        b: &[[f64; 3]],
        cut_a: usize,
        cut_b: usize,
        early: bool,
    ) -> [Vec<[f64; 3]>; 2] {
        let child = |head: &[[f64; 3]],
                     tail: &[[f64; 3]],
                     replaced: &[[f64; 3]],
                     other_parent: &[[f64; 3]]| {
            let genes = if early {
                self.map_before_cut(head, tail, replaced)
            } else {
                self.copy_after_cut(head, tail, other_parent)
            };
            let mut genes = genes;
            genes.truncate(self.parameters.max_length);
            genes
        };
        [
            child(&a[..cut_a], &b[cut_b..], &a[cut_a..], b),
            child(&b[..cut_b], &a[cut_a..], &b[cut_b..], a),
        ]
    }

    fn map_before_cut(
        &self,
        head: &[[f64; 3]],
        tail: &[[f64; 3]],
        replaced: &[[f64; 3]],
    ) -> Vec<[f64; 3]> {
        let mut genes: Vec<[f64; 3]> = head.to_vec();
        let mut cells: Vec<(usize, usize)> = head.iter().map(|&g| self.cell(g)).collect();
        for (position, &gene) in tail.iter().enumerate() {
            let mut candidate = gene;
            let mut link = position;
            let mut hops = 0;
            while cells.contains(&self.cell(candidate)) && hops <= tail.len() + replaced.len() {
                // Follow the exchange: the gene this one displaced, then the one that displaced.
                match replaced.get(link) {
                    Some(&mapped) => candidate = mapped,
                    None => break,
                }
                link = tail
                    .iter()
                    .position(|&g| g == candidate)
                    .unwrap_or(usize::MAX);
                hops += 1;
            }
            if !cells.contains(&self.cell(candidate)) {
                cells.push(self.cell(candidate));
                genes.push(candidate);
            }
        }
        genes
    }

    fn copy_after_cut(
        &self,
        head: &[[f64; 3]],
        tail: &[[f64; 3]],
        other_parent: &[[f64; 3]],
    ) -> Vec<[f64; 3]> {
        let tail_cells: Vec<(usize, usize)> = tail.iter().map(|&g| self.cell(g)).collect();
        let mut kept: Vec<Option<[f64; 3]>> = Vec::with_capacity(head.len());
        let mut cells = tail_cells.clone();
        for &gene in head {
            if cells.contains(&self.cell(gene)) {
                kept.push(None); // "*"
            } else {
                cells.push(self.cell(gene));
                kept.push(Some(gene));
            }
        }
        let mut fillers = other_parent
            .iter()
            .filter(|&&g| !cells.contains(&self.cell(g)));
        let mut genes = Vec::with_capacity(head.len() + tail.len());
        let mut used: Vec<(usize, usize)> = Vec::new();
        for slot in kept {
            match slot {
                Some(gene) => genes.push(gene),
                None => {
                    for &filler in fillers.by_ref() {
                        if !used.contains(&self.cell(filler)) {
                            used.push(self.cell(filler));
                            genes.push(filler);
                            break;
                        }
                    }
                }
            }
        }
        genes.extend_from_slice(tail);
        genes
    }

    /// Whether the leg a → b stays in the space and above the terrain.
    fn leg_is_clear(&self, a: [f64; 3], b: [f64; 3]) -> bool {
        self.scenario
            .cost_ground()
            .segment_clears(a, b, self.scenario.cost_clearance())
    }

    fn gene_is_valid(&self, gene: [f64; 3]) -> bool {
        let (min_x, min_y, max_x, max_y) = self.scenario.area;
        let (low, high) = self.scenario.altitude_bounds;
        (min_x..=max_x).contains(&gene[0])
            && (min_y..=max_y).contains(&gene[1])
            && (low..=high).contains(&gene[2])
            && gene[2]
                > self.scenario.cost_ground().height(gene[0], gene[1])
                    + self.scenario.cost_clearance()
    }

    /// Steps (1)-(4) of the heuristic multi-mutation, once.
    fn mutate_once(
        &self,
        search: &mut Search<Continuous<'_>>,
        mut genes: Vec<[f64; 3]>,
    ) -> Vec<[f64; 3]> {
        let (start, goal) = (self.scenario.cruise_start, self.scenario.cruise_goal);
        let neighbour = |genes: &[[f64; 3]], index: isize| -> [f64; 3] {
            if index < 0 {
                start
            } else {
                *genes.get(index as usize).unwrap_or(&goal)
            }
        };
        for _round in 0..10 {
            let bad: Vec<usize> = (0..genes.len())
                .filter(|&i| {
                    let gene = genes[i];
                    !self.gene_is_valid(gene)
                        || !self.leg_is_clear(neighbour(&genes, i as isize - 1), gene)
                        || !self.leg_is_clear(gene, neighbour(&genes, i as isize + 1))
                })
                .collect();
            if bad.is_empty() {
                break;
            }
            for index in bad {
                genes[index] = self.random_gene(search);
            }
        }
        if genes.is_empty() {
            genes.push(self.random_gene(search));
            return genes;
        }
        let (min_x, min_y, max_x, max_y) = self.scenario.area;
        let (low, high) = self.scenario.altitude_bounds;
        let index = search.below(genes.len());
        let sigma = [
            0.1 * (max_x - min_x),
            0.1 * (max_y - min_y),
            0.1 * (high - low),
        ];
        for axis in 0..3 {
            genes[index][axis] += sigma[axis] * search.normal();
        }
        genes[index] = [
            genes[index][0].clamp(min_x, max_x),
            genes[index][1].clamp(min_y, max_y),
            genes[index][2].clamp(low, high),
        ];
        if genes.len() > 1 {
            let redundant: Vec<usize> = (0..genes.len())
                .filter(|&i| {
                    self.leg_is_clear(
                        neighbour(&genes, i as isize - 1),
                        neighbour(&genes, i as isize + 1),
                    )
                })
                .collect();
            let removed = if redundant.is_empty() {
                search.below(genes.len())
            } else {
                redundant[search.below(redundant.len())]
            };
            genes.remove(removed);
        }
        genes
    }
}

impl<'p> Optimizer<Continuous<'p>> for ImprovedGenetic<'_> {
    fn name(&self) -> &'static str {
        "improved GA"
    }

    fn start(&mut self, search: &mut Search<Continuous<'p>>) {
        let length = self
            .parameters
            .initial_length
            .clamp(1, self.parameters.max_length);
        self.population = (0..self.parameters.population.max(2))
            .map(|_| {
                let genes = (0..length).map(|_| self.random_gene(search)).collect();
                self.evaluate(search, genes)
            })
            .collect();
    }

    fn step(&mut self, search: &mut Search<Continuous<'p>>) {
        let early = search.progress() <= self.parameters.phase_switch;
        let pool = self.select(search);
        let mut children = Vec::with_capacity(pool.len());
        for pair in pool.chunks(2) {
            let (a, b) = (&pair[0].genes, &pair[pair.len() - 1].genes);
            let cut_a = search.below(a.len() + 1);
            let cut_b = search.below(b.len() + 1);
            for child in self.cross(a, b, cut_a, cut_b, early) {
                let mut best: Option<Chromosome> = None;
                for _ in 0..self.parameters.tries.max(1) {
                    let genes = self.mutate_once(search, child.clone());
                    let candidate = self.evaluate(search, genes);
                    if best.as_ref().is_none_or(|b| candidate.cost < b.cost) {
                        best = Some(candidate);
                    }
                }
                children.extend(best);
            }
        }
        let mut everyone = std::mem::take(&mut self.population);
        everyone.extend(children);
        everyone.sort_by(|a, b| a.cost.total_cmp(&b.cost));
        everyone.dedup_by(|a, b| a.genes == b.genes);
        everyone.truncate(self.parameters.population.max(2));
        self.population = everyone;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn optimizer(scenario: &TrackScenario) -> ImprovedGenetic<'_> {
        ImprovedGenetic::new(scenario, ImprovedGeneticParameters::default())
    }

    #[test]
    fn mapping_before_the_cut_leaves_no_duplicate_cells() {
        let scenario = TrackScenario::seed002().unwrap();
        let ga = optimizer(&scenario);
        let gene = |x: f64, y: f64| [x, y, 30.0];
        let a = [
            gene(10.0, 10.0),
            gene(120.0, 10.0),
            gene(240.0, 10.0),
            gene(360.0, 10.0),
        ];
        let b = [
            gene(10.0, 500.0),
            gene(125.0, 15.0),
            gene(600.0, 600.0),
            gene(700.0, 700.0),
        ];
        for early in [true, false] {
            for child in ga.cross(&a, &b, 2, 1, early) {
                let mut cells: Vec<_> = child.iter().map(|&g| ga.cell(g)).collect();
                let count = cells.len();
                cells.sort_unstable();
                cells.dedup();
                assert_eq!(cells.len(), count, "early {early}: {child:?}");
            }
        }
        // A₁B₂ with cuts 2 and 1: a's first two genes, then b's tail, whose (125, 15) shares
        // a cell with (120, 10) and is mapped to the gene it displaced, (240, 10).
        let [first, _] = ga.cross(&a, &b, 2, 1, true);
        assert_eq!(first, vec![a[0], a[1], a[2], b[2], b[3]]);
    }
}
