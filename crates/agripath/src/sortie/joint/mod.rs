//! `joint` (ours): the order of the passes and the returns to the supply point, optimised
//! together for what the operator pays, the total non-spray time (issue 19).
//!
//! Order first, then split (`exact` after `best`) minimises the transfers and then places the
//! returns where that order lets them fall; the order that is cheapest to fly in one piece
//! is rarely the one whose sorties end near the supply point. Route first, cluster second
//! (Beasley 1983; Prins 2004; docs/references.md) searches over giant tours with the optimal split as the
//! evaluation: here a giant tour of oriented passes, scored by its optimal split in linear
//! time ([`split::TourSplit`]: every sortie's legs out and home, the transfers it flies, the
//! service before it; a return at a pass's end skips the transfer to the next pass, a return
//! inside a pass resumes there), improved by [`search::JointSearch`]: relocations of chains
//! of passes, reversals and flips, each scored through the split, and seeded kicks, on
//! `swarm`'s Runner like every other search. The tour kept is split by the exact planner
//! ([`super::exact`]), which finds the same returns (tested).

pub mod petals;
pub mod search;
pub mod split;
pub mod starts;

use std::sync::Mutex;

use swarm::RunStream;

use crate::coverage::drape::GroundPoint;
use crate::sequence::tour::{OrderingProblem, Step};
use split::{PassProfile, SplitBuffers, SplitCache, SplitLimits, TourSplit};

use super::route::Speeds;
use super::SortieModel;

/// The joint problem: a giant tour of the ordering problem's passes, costed by its split.
pub struct JointProblem<'a> {
    /// The passes, their ends and the transfer costs between them.
    pub ordering: &'a OrderingProblem<'a>,
    profiles: Vec<PassProfile>,
    limits: SplitLimits,
    speeds: Speeds,
    /// The splits' buffers (the pinned tour and the last candidate, [`SplitCache`]), one set
    /// per core: candidates scored side by side ([`swarm::Search::evaluate_until`]) each
    /// take a free set.
    caches: Vec<Mutex<SplitCache>>,
}

impl<'a> JointProblem<'a> {
    /// The problem of flying `ordering`'s passes, whose draped points are `points` (by pass
    /// number), in sorties of `model` at `speeds`.
    pub fn new(
        ordering: &'a OrderingProblem<'a>,
        points: &[&[GroundPoint]],
        model: &SortieModel,
        speeds: Speeds,
    ) -> Self {
        let profiles = points
            .iter()
            .map(|points| {
                let mut spray_m = Vec::with_capacity(points.len());
                let mut spray_s = Vec::with_capacity(points.len());
                let (mut metres, mut seconds) = (0.0, 0.0);
                for (index, point) in points.iter().enumerate() {
                    if index > 0 {
                        let before = &points[index - 1];
                        let length = distance_3d(before, point);
                        metres += length;
                        seconds += speeds.spray_s(length, point.ground_m - before.ground_m);
                    }
                    spray_m.push(metres);
                    spray_s.push(seconds);
                }
                let leg_s = points
                    .iter()
                    .map(|point| {
                        model.leg_m(&super::route::RoutePoint::from(*point)) / model.transit_mps
                    })
                    .collect();
                PassProfile {
                    spray_m,
                    spray_s,
                    leg_s,
                }
            })
            .collect::<Vec<PassProfile>>();
        Self {
            ordering,
            profiles,
            limits: SplitLimits {
                tank_m: model.spray_per_tank_m.unwrap_or(f64::INFINITY),
                usable_s: model.usable_s(),
                battery_swap_s: model.battery_swap_s,
                refill_base_s: model.refill_base_s,
                refill_max_s: model.refill_max_s,
            },
            speeds,
            caches: split_caches(),
        }
    }

    /// The problem of flying the passes of `coverage` (numbered as
    /// [`crate::sequence::passes_of`] numbers them, as `ordering`'s are) in sorties of
    /// `model` at `speeds`.
    pub fn of_coverage(
        ordering: &'a OrderingProblem<'a>,
        coverage: &crate::coverage::CoveragePlan,
        model: &SortieModel,
        speeds: Speeds,
    ) -> Self {
        let points: Vec<&[GroundPoint]> = crate::sequence::passes_of(coverage)
            .into_iter()
            .map(|(_, points)| points)
            .collect();
        Self::new(ordering, &points, model, speeds)
    }

    /// The same problem with split buffers of its own: for a branch of the search on
    /// another core ([`swarm::Search::branch_out`]), which would otherwise contend for, and
    /// overwrite, this one's. Costs are the same to the bit (the buffers only save work).
    pub fn fork(&self) -> Self {
        Self {
            ordering: self.ordering,
            profiles: self.profiles.clone(),
            limits: self.limits,
            speeds: self.speeds,
            caches: split_caches(),
        }
    }

    /// Route points of every tour of the problem (what one split lays out).
    pub fn points(&self) -> usize {
        self.profiles
            .iter()
            .map(|profile| profile.spray_m.len())
            .sum()
    }

    /// Seconds of the transfer from `from`'s exit to `to`'s entry: at transit speed, with its
    /// climb and descent at climb speed, when it climbs out of the field (eq. 8 adds 2h), else
    /// at turn speed, as
    /// [`super::route::WorkRoute::from_route`] times it.
    pub fn transfer_s(&self, from: Step, to: Step) -> f64 {
        let (exit, entry) = (from.exit(), to.entry());
        let (cost, climbs) = self.ordering.cost_and_climbs(exit, entry);
        if climbs {
            cost / self.speeds.transit_mps + self.speeds.transfer_climb_s
        } else {
            cost / self.speeds.turn_mps
        }
    }
}

/// A cache per core (at most [`SPLIT_CACHES`]).
fn split_caches() -> Vec<Mutex<SplitCache>> {
    (0..crate::parallel::threads().clamp(1, SPLIT_CACHES))
        .map(|_| Mutex::new(SplitCache::default()))
        .collect()
}

/// Most split caches of one problem: each holds two tours' layouts, and pinning a tour
/// lays it out in each.
const SPLIT_CACHES: usize = 4;

fn lock(cache: &Mutex<SplitCache>) -> std::sync::MutexGuard<'_, SplitCache> {
    cache
        .lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner)
}

fn distance_3d(a: &GroundPoint, b: &GroundPoint) -> f64 {
    ((a.x - b.x).powi(2) + (a.y - b.y).powi(2) + (a.ground_m - b.ground_m).powi(2)).sqrt()
}

impl JointProblem<'_> {
    /// Runs `work` with this problem's split.
    fn with_split<T>(&self, work: impl FnOnce(&TourSplit) -> T) -> T {
        let transfer = |from: Step, to: Step| self.transfer_s(from, to);
        let split = TourSplit {
            profiles: &self.profiles,
            transfer_s: &transfer,
            limits: self.limits,
        };
        work(&split)
    }

    /// Runs `work` with this problem's split and the first of its caches no other thread
    /// holds (the first, waiting for it, when all are held). Any cache gives the same cost
    /// to the bit: the buffers only save work.
    fn with_cache<T>(&self, work: impl FnOnce(&TourSplit, &mut SplitCache) -> T) -> T {
        let mut cache = self
            .caches
            .iter()
            .find_map(|cache| match cache.try_lock() {
                Ok(held) => Some(held),
                Err(std::sync::TryLockError::Poisoned(poisoned)) => Some(poisoned.into_inner()),
                Err(std::sync::TryLockError::WouldBlock) => None,
            })
            .unwrap_or_else(|| {
                self.caches[0]
                    .lock()
                    .unwrap_or_else(std::sync::PoisonError::into_inner)
            });
        self.with_split(|split| work(split, &mut cache))
    }

    /// The steps the split of `tour` takes ([`SplitBuffers`]' count, a split from the
    /// first position): the unit of [`JointSettings::most_split_steps`].
    pub fn split_steps(&self, tour: &[Step]) -> u64 {
        let mut buffers = SplitBuffers::default();
        self.with_split(|split| split.cost(tour, &mut buffers));
        buffers.steps
    }

    /// The non-spray seconds of `tour`'s best split from the first position, with fresh
    /// buffers (what [`swarm::Problem::evaluate`] resumes; for tests and benchmarks).
    pub fn full_split_cost(&self, tour: &[Step]) -> f64 {
        self.with_split(|split| split.cost(tour, &mut SplitBuffers::default()))
    }

    /// The sorties of the tour's cheapest split, as the tour positions of the passes each
    /// begins and ends in ([`TourSplit::sorties`]); the tour is pinned.
    pub fn sorties(&self, tour: &[Step]) -> Vec<(usize, usize)> {
        self.with_cache(|split, cache| cache.sorties(split, tour))
    }

    /// Keeps `tour`'s split for the evaluations that follow to resume from (the tour a
    /// search stands on, whose neighbours it scores next): saves time, changes no cost.
    pub fn pin(&self, tour: &[Step]) {
        self.with_split(|split| {
            for cache in &self.caches {
                lock(cache).pin(split, tour);
            }
        });
    }

    /// Evaluations this problem serves at once, each with split buffers of its own.
    pub fn caches(&self) -> usize {
        self.caches.len()
    }

    /// Route points the evaluations so far laid out and labelled (a full split lays out
    /// [`JointProblem::points`], a resumed one fewer).
    pub fn points_labelled(&self) -> u64 {
        self.caches
            .iter()
            .map(|cache| lock(cache).points_labelled())
            .sum()
    }
}

impl swarm::Problem for JointProblem<'_> {
    type Solution = [Step];

    /// Non-spray seconds of the tour's best split.
    fn evaluate(&self, tour: &[Step]) -> f64 {
        self.with_cache(|split, cache| cache.cost(split, tour))
    }

    fn first_solution(&self) -> Vec<Step> {
        swarm::Problem::first_solution(self.ordering)
    }

    fn random_solution(&self, stream: &mut RunStream) -> Vec<Step> {
        swarm::Problem::random_solution(self.ordering, stream)
    }
}

/// `joint`'s settings.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct JointSettings {
    /// Evaluations through the split per pass (the budget is this × passes + 2,000).
    pub evaluations_per_pass: u64,
    /// Start tours [`search()`] races from one order ([`starts::start_tours`], 1 to
    /// [`starts::MOST_STARTS`]); the pipeline gives its own ([`starts::of_paths`]).
    pub starts: usize,
    /// Share of the budget the race of the starts uses, split evenly among them.
    pub race_share: f64,
    /// Whether the petal moves ([`petals`]) re-fly the incumbent's sorties out and back.
    pub petals: bool,
    /// Most split steps (start positions considered, [`JointProblem::split_steps`]) the
    /// splits of a run may take in all: bounds the run's time on big farms, where a split
    /// costs thousands of times a small farm's, deterministically (a count, not a clock).
    pub most_split_steps: u64,
    /// Seed of the kicks (run 0 of this seed).
    pub seed: u64,
}

impl Default for JointSettings {
    fn default() -> Self {
        Self {
            evaluations_per_pass: 12,
            starts: 2,
            race_share: 0.5,
            petals: true,
            // Binds only on big farms: the 11 farms of `bench_joint` (up to 250 swaths) plan the
            // same with it as without; the 4,556-swath tiled farm plans in 9.4 s
            // (docs/benchmarks.md, "5,000 swaths on a flyable farm").
            most_split_steps: 1_000_000_000,
            seed: 1,
        }
    }
}

impl JointSettings {
    /// The Runner's budget on `problem` from a tour whose split takes `steps_per_split`
    /// steps: evaluations per pass × passes + 2,000, but no more splits than take
    /// `most_split_steps` steps in all (at least one).
    pub fn budget(&self, problem: &JointProblem, steps_per_split: u64) -> u64 {
        let passes = problem.profiles.len() as u64;
        let wanted = self.evaluations_per_pass * passes + 2000;
        let affordable = self.most_split_steps / steps_per_split.max(1);
        wanted.min(affordable).max(1)
    }
}

/// The joint search from `starts` (tours of `problem`'s passes, the first preferred on ties;
/// the pipeline's are [`starts::of_paths`]): the cheapest tour found within the budget.
pub fn improve(
    problem: &JointProblem,
    starts: Vec<Vec<Step>>,
    settings: &JointSettings,
) -> Vec<Step> {
    let first = starts.first().expect("at least one start tour");
    let budget = settings.budget(problem, problem.split_steps(first));
    search_from(problem, starts, settings, budget).tour
}

/// What a run of the joint search found.
#[derive(Debug, Clone)]
pub struct JointOutcome {
    /// The cheapest tour found.
    pub tour: Vec<Step>,
    /// Its non-spray seconds (the split's, with the first and last legs).
    pub cost: f64,
    /// Splits scored (the Runner's evaluations).
    pub evaluations: u64,
    /// The Runner's iterations after the start (kicks and petal rounds).
    pub iterations: usize,
}

/// The joint search from `order` and the start tours made from it (`settings.starts` of
/// them, [`starts::start_tours`]), within `evaluations` splits.
pub fn search(
    problem: &JointProblem,
    order: Vec<Step>,
    settings: &JointSettings,
    evaluations: u64,
) -> JointOutcome {
    let starts = starts::start_tours(problem.ordering, order, settings.starts);
    search_from(problem, starts, settings, evaluations)
}

/// The joint search from `starts` (the first preferred on ties), raced over
/// `settings.race_share` of the budget when there are several, within `evaluations` splits.
pub fn search_from(
    problem: &JointProblem,
    starts: Vec<Vec<Step>>,
    settings: &JointSettings,
    evaluations: u64,
) -> JointOutcome {
    let first = starts.first().expect("at least one start tour");
    if first.len() < 2 {
        let cost = swarm::Problem::evaluate(problem, first);
        return JointOutcome {
            tour: first.clone(),
            cost,
            evaluations: 1,
            iterations: 0,
        };
    }
    let race =
        (settings.race_share.clamp(0.0, 1.0) * evaluations as f64 / starts.len() as f64) as u64;
    let runner = swarm::Runner::new(
        swarm::Termination::evaluations(evaluations.max(1)),
        settings.seed,
    )
    .expect("a budget of at least one evaluation");
    let mut search = search::JointSearch::racing(starts, race);
    if settings.petals {
        search = search.with_petals();
    }
    let outcome = runner.run_problem(&mut search, problem, 0, &mut ());
    JointOutcome {
        tour: outcome.best_solution,
        cost: outcome.best_cost,
        evaluations: outcome.evaluations,
        iterations: outcome.iterations,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::coverage::{plan_coverage, CoveragePlan, CoverageSettings};
    use crate::sequence::tour::Start;
    use crate::sequence::{ordering_problem, route_of_tour, Sequencer, TransferModel};
    use crate::sortie::route::{RoutePoint, WorkRoute};
    use crate::sortie::{plan_sorties, SortiePlanner};
    use swarm::Problem;

    /// The joint problem of `scenario`'s default coverage from a supply point, and the
    /// sequencer's order from it.
    fn joint_of<R>(
        scenario: &crate::scenario::Scenario,
        supply: [f64; 2],
        work: impl FnOnce(&JointProblem, Vec<Step>, &CoveragePlan, &TransferModel) -> R,
    ) -> R {
        let vehicle = &scenario.vehicle;
        let coverage = plan_coverage(
            &scenario.farm,
            scenario.terrain.as_ref(),
            vehicle,
            &CoverageSettings::default(),
        )
        .unwrap();
        let model = TransferModel::new(&scenario.farm, vehicle.safe_height_m);
        let supply = GroundPoint {
            x: supply[0],
            y: supply[1],
            ground_m: scenario.terrain.height_m(supply[0], supply[1]).unwrap(),
        };
        let (problem, groups) = ordering_problem(&coverage, &model, Start::Fixed(supply));
        let sortie_model = crate::pipeline::sortie_model(vehicle, supply.into());
        let joint =
            JointProblem::of_coverage(&problem, &coverage, &sortie_model, Speeds::of(vehicle));
        let order = Sequencer::default().sequencer().order(&problem, &groups);
        work(&joint, order, &coverage, &model)
    }

    /// The resumed split (from the pinned tour or the last candidate) equals the split from
    /// the first position, bit for bit, with the same sorties, on random moves of every kind
    /// the search makes (reversals, flips, relocations of chains, kicks) anywhere in the
    /// tour, pinned or not, on the seed 001 farm and two random farms.
    #[test]
    fn the_resumed_split_equals_the_full_split_on_random_moves() {
        let seed001 = crate::demo::scenario().unwrap();
        let mut farms = vec![(seed001, [0.0, 0.0])];
        for seed in [1, 4] {
            let farm = crate::bench::farms::irregular_farm(seed, 150, 5.0);
            let supply = crate::bench::farms::supply_south_of(&farm);
            let scenario = crate::scenario::Scenario::with_farm(
                farm,
                crate::scenario::ScenarioParts::default(),
            )
            .unwrap();
            farms.push((scenario, supply));
        }
        for (farm, (scenario, supply)) in farms.iter().enumerate() {
            joint_of(scenario, *supply, |joint, order, _, _| {
                let n = order.len();
                let mut stream = swarm::run_stream(farm as u64, 0);
                let mut tour = order;
                let mut seen = vec![tour.clone()];
                let (mut resumed, mut checked) = (0u64, 0);
                for trial in 0..300 {
                    let mut candidate = match trial % 7 {
                        // An earlier tour again (the pinned one or any other).
                        6 => seen[swarm::below(&mut stream, seen.len())].clone(),
                        kind => {
                            let mut changed = tour.clone();
                            let a = swarm::below(&mut stream, n);
                            let b = (a + 1 + swarm::below(&mut stream, 40)).min(n);
                            match kind {
                                0 | 1 => {
                                    changed[a..b].reverse();
                                    changed[a..b]
                                        .iter_mut()
                                        .for_each(|step| *step = step.flipped());
                                }
                                2 => changed[a] = changed[a].flipped(),
                                _ => {
                                    let chain: Vec<Step> = changed.drain(a..b).collect();
                                    let at = swarm::below(&mut stream, changed.len() + 1);
                                    changed.splice(at..at, chain);
                                }
                            }
                            changed
                        }
                    };
                    if trial % 11 == 0 {
                        candidate = starts::backwards(&candidate);
                    }
                    let before = joint.points_labelled();
                    let cost = joint.evaluate(&candidate);
                    resumed += joint.points() as u64 - (joint.points_labelled() - before);
                    let full = joint.full_split_cost(&candidate);
                    assert_eq!(cost.to_bits(), full.to_bits(), "farm {farm} trial {trial}");
                    if trial % 5 == 0 {
                        let mut fresh = SplitBuffers::default();
                        let sorties =
                            joint.with_split(|split| split.sorties(&candidate, &mut fresh));
                        assert_eq!(
                            joint.sorties(&candidate),
                            sorties,
                            "farm {farm} trial {trial}"
                        );
                    }
                    checked += 1;
                    // Walk like a search: keep some candidates and pin them.
                    if swarm::uniform(&mut stream) < 0.3 {
                        tour = candidate.clone();
                        joint.pin(&tour);
                        seen.push(candidate);
                    }
                }
                // Not vacuous: the splits did resume (most points of most candidates were
                // not laid out again).
                assert!(
                    checked == 300 && resumed > 300 * joint.points() as u64 / 4,
                    "farm {farm}: {resumed} points reused"
                );
            });
        }
    }

    #[test]
    fn the_linear_split_equals_the_exact_split_with_the_first_and_last_legs() {
        let scenario = crate::demo::scenario().unwrap();
        let vehicle = &scenario.vehicle;
        joint_of(&scenario, [0.0, 0.0], |joint, order, coverage, model| {
            let speeds = Speeds::of(vehicle);
            let sortie_model = crate::pipeline::sortie_model(
                vehicle,
                RoutePoint {
                    x: 0.0,
                    y: 0.0,
                    ground_m: scenario.terrain.height_m(0.0, 0.0).unwrap(),
                },
            );
            let mut stream = swarm::run_stream(3, 0);
            let mut tours = vec![order];
            tours.extend((0..3).map(|_| joint.random_solution(&mut stream)));
            for tour in tours {
                let linear = joint.evaluate(&tour);
                let flight = route_of_tour(coverage, model, joint.ordering, &tour);
                let work = WorkRoute::from_route(&flight, speeds);
                let plan = plan_sorties(&work, &sortie_model, SortiePlanner::Exact, 1).unwrap();
                let ends = sortie_model.leg_m(&work.points()[0])
                    + sortie_model.leg_m(&work.points()[work.len() - 1]);
                let exact = plan.objective_s() + ends / sortie_model.transit_mps;
                assert!(
                    (exact - linear).abs() < 1e-6,
                    "exact {exact} against the linear split {linear}"
                );
            }
        });
    }

    /// Random passes (short polylines) in random orders and directions, with tanks and
    /// batteries tight enough that both bind (and the battery breaks the queues' best starts):
    /// the linear split equals the exact split with the first and last legs.
    #[test]
    fn the_linear_split_equals_the_exact_split_on_random_tours_and_tight_limits() {
        let farm = crate::demo::scenario().unwrap().farm;
        let model = TransferModel::new(&farm, 10.0);
        let speeds = Speeds {
            spray_mps: 3.0,
            turn_mps: 2.0,
            transit_mps: 6.0,
            climb_mps: 3.0,
            descent_mps: 3.0,
            transfer_climb_s: 12.0,
        };
        let (mut split, mut refused, mut conformed) = (0, 0, false);
        for seed in 0..60u64 {
            let mut stream = swarm::run_stream(seed, 0);
            let passes = 3 + swarm::below(&mut stream, 12);
            let mut lines: Vec<Vec<GroundPoint>> = Vec::new();
            for _ in 0..passes {
                let (x, y) = (
                    400.0 * swarm::uniform(&mut stream),
                    400.0 * swarm::uniform(&mut stream),
                );
                let angle = std::f64::consts::TAU * swarm::uniform(&mut stream);
                let count = 2 + swarm::below(&mut stream, 5);
                lines.push(
                    (0..count)
                        .map(|k| GroundPoint {
                            x: x + 15.0 * k as f64 * angle.cos(),
                            y: y + 15.0 * k as f64 * angle.sin(),
                            ground_m: 2.0 * swarm::uniform(&mut stream),
                        })
                        .collect(),
                );
            }
            let ends: Vec<[GroundPoint; 2]> = lines
                .iter()
                .map(|line| [line[0], line[line.len() - 1]])
                .collect();
            let supply = GroundPoint {
                x: 200.0,
                y: -30.0,
                ground_m: 0.0,
            };
            let problem =
                OrderingProblem::new(ends, crate::sequence::tour::Start::Fixed(supply), &model);
            let sortie_model = SortieModel {
                supply: supply.into(),
                spray_per_tank_m: Some(60.0 + 120.0 * swarm::uniform(&mut stream)),
                endurance_s: 400.0 + 400.0 * swarm::uniform(&mut stream),
                battery_reserve_s: 0.0,
                battery_swap_s: 30.0 + 60.0 * swarm::uniform(&mut stream),
                refill_base_s: 20.0,
                refill_max_s: 120.0,
                transit_mps: 6.0,
                return_climb_m: 20.0,
                litres_per_m: None,
            };
            let points: Vec<&[GroundPoint]> = lines.iter().map(Vec::as_slice).collect();
            let joint = JointProblem::new(&problem, &points, &sortie_model, speeds);
            let tour = joint.random_solution(&mut stream);
            // The flight of the tour, as the pipeline builds it.
            let mut route_points = Vec::new();
            let mut segments = Vec::new();
            let mut extra = Vec::new();
            for (position, step) in tour.iter().enumerate() {
                let mut line = lines[step.pass].clone();
                if step.reversed {
                    line.reverse();
                }
                if position > 0 {
                    let from: GroundPoint = *route_points.last().unwrap();
                    let cost = problem.cost(tour[position - 1].exit(), step.entry());
                    let straight = distance_3d(&from, &line[0]);
                    if cost > straight + 1e-6 {
                        segments.push(crate::sortie::route::Segment::Transfer);
                        extra.push(cost - straight);
                    } else {
                        segments.push(crate::sortie::route::Segment::Turn);
                        extra.push(0.0);
                    }
                }
                for (k, point) in line.iter().enumerate() {
                    if k > 0 {
                        segments.push(crate::sortie::route::Segment::Spray);
                        extra.push(0.0);
                    }
                    route_points.push(*point);
                }
            }
            let work = WorkRoute::new(
                route_points
                    .iter()
                    .map(|point| RoutePoint::from(*point))
                    .collect(),
                segments,
                Some(extra),
                speeds,
            );
            let linear = joint.evaluate(&tour);
            if passes >= 10 && linear.is_finite() && !conformed {
                // The engine's conformance suite: repeatable for a seed, different across
                // runs, within budget, every tour evaluated a permutation; and the search
                // never ends above its start. (Budgets large enough that the kicks start on
                // every instance: with the transfers' climb time the descent runs longer.)
                let outcome = swarm::conformance::check_problem(
                    || search::JointSearch::new(tour.clone()),
                    &joint,
                    1200,
                    |candidate: &[Step]| crate::sequence::tour::check_order(candidate, passes),
                )
                .unwrap();
                assert!(outcome.best_cost <= linear);
                // The same with the starts raced: and never above the cheapest start.
                let starts = starts::start_tours(&problem, tour.clone(), starts::MOST_STARTS);
                let cheapest = starts
                    .iter()
                    .map(|start| joint.evaluate(start))
                    .fold(f64::INFINITY, f64::min);
                let raced = swarm::conformance::check_problem(
                    || search::JointSearch::racing(starts.clone(), 60),
                    &joint,
                    1500,
                    |candidate: &[Step]| crate::sequence::tour::check_order(candidate, passes),
                )
                .unwrap();
                assert!(starts.len() > 1 && raced.best_cost <= cheapest);
                // A budget too small to share out among the starts: the race runs start
                // after start and keeps what it evaluated (not an unevaluated start).
                let tight = swarm::Runner::new(swarm::Termination::evaluations(2), 5)
                    .unwrap()
                    .run_problem(
                        &mut search::JointSearch::racing(starts.clone(), 60),
                        &joint,
                        0,
                        &mut (),
                    );
                assert_eq!(tight.evaluations, 2);
                assert!(tight.best_cost <= joint.evaluate(&starts[0]));
                conformed = true;
            }
            match plan_sorties(&work, &sortie_model, SortiePlanner::Exact, 1) {
                Ok(plan) => {
                    let ends = sortie_model.leg_m(&work.points()[0])
                        + sortie_model.leg_m(&work.points()[work.len() - 1]);
                    let exact = plan.objective_s() + ends / sortie_model.transit_mps;
                    assert!(
                        (exact - linear).abs() < 1e-6,
                        "seed {seed}: exact {exact} linear {linear}"
                    );
                    split += usize::from(plan.returns() >= 2);
                }
                Err(_) => {
                    assert!(linear.is_infinite(), "seed {seed}: linear {linear}");
                    refused += 1;
                }
            }
        }
        // Not vacuous: most tours need several returns, and few cannot be flown at all.
        assert!(
            split >= 30 && refused <= 10,
            "{split} split, {refused} refused"
        );
    }
}
