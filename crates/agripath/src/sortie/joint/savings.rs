//! Clarke & Wright's savings (1964) as a start tour for the joint search: sorties built out and
//! back from the supply point, the shape a multi-trip plan has, where the open path's start is
//! one sweep of the farm that the split cuts into sorties.
//!
//! Every pass starts as its own sortie, S → pass → S. Two sorties whose ends x and y are
//! joined by a transfer save
//!
//! s(x, y) = leg(x) + leg(y) − λ · t(x, y)
//!
//! seconds (leg the one-way flight between an end and the supply point, t the transfer
//! between the ends, eq. 8 at its speed); the pairs are joined in decreasing order of s while
//! both are still ends of their sorties and the joined sortie fits one tank and the battery
//! (the parallel savings algorithm; λ is Yellow's 1970 shape parameter: above 1 it favours
//! short transfers, below 1 long petals). The sorties are then flown one after another, each
//! entered at the end nearest the last one's exit, as a giant tour that the split cuts again
//! (it may still return inside a pass). Only the ends among each end's nearest are paired, so
//! the work is O(n log n) in the passes.

use crate::sequence::local_search::nearest_ends;
use crate::sequence::tour::{End, Step};

use super::JointProblem;

/// Nearest ends each end is paired with.
const PAIRED_ENDS: usize = 24;

/// Shape parameters λ tried by [`best_savings_tour`].
pub const SHAPES: [f64; 6] = [0.6, 0.8, 1.0, 1.2, 1.5, 2.0];

/// A sortie being built: its passes in flying order, spray metres and seconds flown.
struct Sortie {
    steps: Vec<Step>,
    spray_m: f64,
    flight_s: f64,
}

impl Sortie {
    fn head(&self) -> End {
        self.steps[0].entry()
    }

    fn tail(&self) -> End {
        self.steps[self.steps.len() - 1].exit()
    }

    fn reverse(&mut self) {
        self.steps = super::starts::backwards(&self.steps);
    }
}

/// The step that leaves its pass by `end`.
fn leaving_by(end: End) -> Step {
    Step {
        pass: end / 2,
        reversed: end % 2 == 0,
    }
}

/// The step that enters its pass by `end`.
fn entering_by(end: End) -> Step {
    Step {
        pass: end / 2,
        reversed: end % 2 == 1,
    }
}

/// The savings tour of `problem` for shape λ = `shape` (module doc).
pub fn savings_tour(problem: &JointProblem, shape: f64) -> Vec<Step> {
    let passes = problem.ordering.passes();
    if passes == 0 {
        return Vec::new();
    }
    let leg = |end: End| {
        let profile = &problem.profiles[end / 2];
        if end % 2 == 0 {
            profile.leg_s[0]
        } else {
            profile.leg_s[profile.leg_s.len() - 1]
        }
    };
    let transfer = |from: End, to: End| problem.transfer_s(leaving_by(from), entering_by(to));
    let mut sorties: Vec<Option<Sortie>> = (0..passes)
        .map(|pass| {
            let profile = &problem.profiles[pass];
            let step = Step {
                pass,
                reversed: false,
            };
            Some(Sortie {
                steps: vec![step],
                spray_m: profile.length(),
                flight_s: leg(step.entry()) + profile.seconds() + leg(step.exit()),
            })
        })
        .collect();
    let mut sortie_of: Vec<usize> = (0..passes).collect();
    let neighbours = nearest_ends(problem.ordering, PAIRED_ENDS, |end, other| {
        other / 2 != end / 2
    });
    let mut pairs: Vec<(f64, End, End)> = Vec::with_capacity(neighbours.len() * PAIRED_ENDS);
    for (x, near) in neighbours.iter().enumerate() {
        for &y in near {
            if x < y || !neighbours[y].contains(&x) {
                pairs.push((leg(x) + leg(y) - shape * transfer(x, y), x, y));
            }
        }
    }
    pairs.sort_by(|a, b| b.0.total_cmp(&a.0).then(a.1.cmp(&b.1)).then(a.2.cmp(&b.2)));
    let limits = problem.limits;
    for (_, x, y) in pairs {
        let (first, second) = (sortie_of[x / 2], sortie_of[y / 2]);
        if first == second {
            continue;
        }
        let (Some(a), Some(b)) = (&sorties[first], &sorties[second]) else {
            continue;
        };
        let x_is_end = a.head() == x || a.tail() == x;
        let y_is_end = b.head() == y || b.tail() == y;
        if !x_is_end || !y_is_end {
            continue;
        }
        let spray_m = a.spray_m + b.spray_m;
        let flight_s = a.flight_s - leg(x) + transfer(x, y) - leg(y) + b.flight_s;
        if spray_m > limits.tank_m || flight_s > limits.usable_s {
            continue;
        }
        let mut a = sorties[first].take().expect("checked above");
        let mut b = sorties[second].take().expect("checked above");
        if a.tail() != x {
            a.reverse();
        }
        if b.head() != y {
            b.reverse();
        }
        for step in &b.steps {
            sortie_of[step.pass] = first;
        }
        a.steps.extend(b.steps);
        a.spray_m = spray_m;
        a.flight_s = flight_s;
        sorties[first] = Some(a);
    }
    chain(problem, sorties.into_iter().flatten().collect(), leg)
}

/// The sorties flown one after another: first the one with an end nearest the supply point,
/// then always the one with an end nearest the last exit, entered there.
fn chain(problem: &JointProblem, mut left: Vec<Sortie>, leg: impl Fn(End) -> f64) -> Vec<Step> {
    let mut tour = Vec::with_capacity(problem.ordering.passes());
    let mut at: Option<End> = None;
    while !left.is_empty() {
        let cost = |end: End| at.map_or_else(|| leg(end), |exit| problem.ordering.cost(exit, end));
        let (index, reverse) = left
            .iter()
            .enumerate()
            .flat_map(|(index, sortie)| {
                [
                    (cost(sortie.head()), index, false),
                    (cost(sortie.tail()), index, true),
                ]
            })
            .min_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)).then(a.2.cmp(&b.2)))
            .map(|(_, index, reverse)| (index, reverse))
            .expect("a sortie is left");
        let mut sortie = left.swap_remove(index);
        if reverse {
            sortie.reverse();
        }
        at = Some(sortie.tail());
        tour.extend(sortie.steps);
    }
    tour
}

/// The cheapest by its split of the savings tours for [`SHAPES`], with its shape.
pub fn best_savings_tour(problem: &JointProblem) -> (Vec<Step>, f64) {
    SHAPES
        .iter()
        .map(|&shape| {
            let tour = savings_tour(problem, shape);
            (problem.full_split_cost(&tour), tour, shape)
        })
        .min_by(|a, b| a.0.total_cmp(&b.0))
        .map(|(_, tour, shape)| (tour, shape))
        .expect("at least one shape")
}
