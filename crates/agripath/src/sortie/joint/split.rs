//! The optimal split of a giant tour into sorties in O(points), fast enough to score every
//! move of the joint search (Prins 2004: a giant tour is evaluated by its optimal split;
//! Vidal 2016's linear split for the same reason; docs/references.md).
//!
//! The tour's points p_0 … p_N (every draped point of every pass, in flying order) carry
//! S_i, the spray metres from p_0, and T_i, the non-spray seconds from p_0 (the transfers
//! between passes, at their speeds). A sortie flies p_s … p_e and costs, in non-spray seconds,
//!
//! c(s, e) = leg(s) + (T_e − T_s) + leg(e) + \[s > 0\]·max(T_e', t_b + α (S_e − S_s)),
//!
//! with leg(P) = (‖P, P0‖ + H + 2h) / v_off, T_e' the battery swap and t_b + α x the refill
//! of eq. 5 (α = (T_pmax − t_b) / D_max); it is flyable when S_e − S_s ≤ D_max and
//! leg(s) + (S_e − S_s)/v + (T_e − T_s) + leg(e) ≤ the usable battery. After a sortie ending
//! at e the next starts at e (a return from inside a pass, resumed there) or, where p_e ends
//! a pass, at e + 1: the transfer between the passes is not flown. This is the exact split
//! ([`super::super::exact`]) with the first leg out and the last leg home counted (they depend
//! on the tour), and the same value.
//!
//! With end(e) = min_s start(s) + leg(s) − T_s + service(s, e) + T_e, the service is the
//! swap while S_e − S_s < σ* = (T_e' − t_b)/α, and the refill beyond: the starts in reach of e
//! fall in two windows that only move forward with e, each minimised by a monotone queue
//! (keys start(s) + leg(s) − T_s, and the same − α S_s). The battery limit is not monotone
//! in s: where a queue's best start breaks it (rare: the tank binds first), the window is
//! scanned.
//!
//! The search scores tours that differ from the one it stands on only from some position i
//! on (a move changes a stretch of the tour). The labels start(s), the two queues and the
//! lowest start in reach before the first point of position i depend only on positions
//! 0 … i − 1, so the split resumes there: the buffers keep the last tour's layout and labels,
//! and a checkpoint of the queues at every position's first point ([`SplitCache`] keeps two,
//! the pinned tour and the last candidate). The sums S and T are redone in the same order, so
//! a resumed split's cost is the full split's to the bit.

use std::collections::VecDeque;

use crate::sequence::tour::Step;

/// One pass's profile: per point (in the pass's own order, A to B) the spray metres and
/// seconds from point A and the one-way return time to the supply point.
#[derive(Debug, Clone)]
pub struct PassProfile {
    /// Cumulative 3D spray metres from the first point.
    pub spray_m: Vec<f64>,
    /// Cumulative spray seconds from the first point ([`super::Speeds::spray_s`]: spray
    /// speed, or climb speed where the ground is steep).
    pub spray_s: Vec<f64>,
    /// One-way leg to the supply point from each point, seconds.
    pub leg_s: Vec<f64>,
}

impl PassProfile {
    fn length(&self) -> f64 {
        *self.spray_m.last().expect("a pass has points")
    }

    fn seconds(&self) -> f64 {
        *self.spray_s.last().expect("a pass has points")
    }
}

/// The limits and speeds the split obeys.
#[derive(Debug, Clone, Copy)]
pub struct SplitLimits {
    /// Spray metres per tank (`f64::INFINITY` when the tank does not limit a sortie).
    pub tank_m: f64,
    /// Usable battery seconds per sortie.
    pub usable_s: f64,
    /// T_e: battery swap, seconds.
    pub battery_swap_s: f64,
    /// t_b: refill of an empty sortie, seconds.
    pub refill_base_s: f64,
    /// T_pmax: refill of a full tank, seconds.
    pub refill_max_s: f64,
}

impl SplitLimits {
    /// α of the refill line, seconds per spray metre.
    fn refill_slope(&self) -> f64 {
        if self.tank_m.is_finite() && self.tank_m > 0.0 {
            ((self.refill_max_s - self.refill_base_s) / self.tank_m).max(0.0)
        } else {
            0.0
        }
    }

    fn service_s(&self, spray_m: f64) -> f64 {
        let spray_m = spray_m.min(self.tank_m);
        self.battery_swap_s
            .max(self.refill_base_s + self.refill_slope() * spray_m)
    }
}

/// The state of the split just before the first point of one tour position: the two queues
/// and the lowest start in reach, from which the split of a tour that differs from the one
/// laid out only from that position on resumes.
#[derive(Debug, Default, Clone)]
struct Checkpoint {
    swap: Vec<usize>,
    refill: Vec<usize>,
    lowest: usize,
}

/// Reused buffers of one evaluation, which remember the last tour split with them: a tour
/// that shares its first k positions with it resumes the split at position k (the labels,
/// queues and layout before it depend only on those positions, so the result is the full
/// split's, bit for bit). Use one set of buffers with one [`TourSplit`] only.
#[derive(Debug, Default)]
pub struct SplitBuffers {
    /// The tour laid out last; its first `valid` positions' state is kept.
    tour: Vec<Step>,
    valid: usize,
    /// The last tour's cost (when `valid` covers it).
    cost: f64,
    /// Per tour position: its first point, the spray metres and transfer seconds before it,
    /// and the split's state before its first point.
    position_first: Vec<usize>,
    position_spray: Vec<f64>,
    position_spray_time: Vec<f64>,
    position_transfer: Vec<f64>,
    checkpoints: Vec<Checkpoint>,
    spray: Vec<f64>,
    /// Cumulative spray seconds at each point.
    spray_time: Vec<f64>,
    transfer: Vec<f64>,
    leg: Vec<f64>,
    /// Whether the segment after a point is a transfer between passes.
    between: Vec<bool>,
    /// The tour position of each point's pass.
    owner: Vec<usize>,
    start: Vec<f64>,
    /// For each point, the first point of the best sortie ending there.
    came: Vec<usize>,
    /// For each point, the last point of the sortie whose return gave its start label.
    label_end: Vec<usize>,
    swap_window: VecDeque<usize>,
    refill_window: VecDeque<usize>,
    /// Start positions considered by the splits run with these buffers (each point once,
    /// and every start in reach where the battery breaks a queue's order): the work a split
    /// costs, which the joint search's budget is measured in on big farms.
    pub(super) steps: u64,
    /// Points the splits run with these buffers laid out and labelled (a resumed split only
    /// those from its first changed position on).
    pub(super) points_labelled: u64,
}

impl SplitBuffers {
    /// The leading positions of `tour` whose split state these buffers hold.
    fn resumable(&self, tour: &[Step]) -> usize {
        if tour.len() != self.tour.len() {
            return 0;
        }
        let shared = tour
            .iter()
            .zip(&self.tour)
            .take_while(|(a, b)| a == b)
            .count();
        shared.min(self.valid)
    }

    /// Whether these buffers hold the whole split of `tour`.
    fn holds(&self, tour: &[Step]) -> bool {
        self.valid == tour.len() && self.tour == tour
    }

    /// Makes these buffers' state that of `other` for its first `upto` positions (which
    /// `other` holds, `upto` < its tour's length), copying only what differs.
    fn take_prefix(&mut self, other: &SplitBuffers, upto: usize) {
        let from = self.resumable(&other.tour);
        if from >= upto {
            return;
        }
        let (first, last) = (other.position_first[from], other.position_first[upto]);
        fn copy<T: Copy>(into: &mut Vec<T>, from: &[T], range: std::ops::Range<usize>) {
            into.truncate(range.start);
            into.extend_from_slice(&from[range]);
        }
        copy(&mut self.spray, &other.spray, first..last);
        copy(&mut self.spray_time, &other.spray_time, first..last);
        copy(&mut self.transfer, &other.transfer, first..last);
        copy(&mut self.leg, &other.leg, first..last);
        copy(&mut self.between, &other.between, first..last);
        copy(&mut self.owner, &other.owner, first..last);
        copy(&mut self.came, &other.came, first..last);
        copy(&mut self.start, &other.start, first..last + 1);
        copy(&mut self.label_end, &other.label_end, first..last + 1);
        copy(
            &mut self.position_first,
            &other.position_first,
            from..upto + 1,
        );
        copy(
            &mut self.position_spray,
            &other.position_spray,
            from..upto + 1,
        );
        copy(
            &mut self.position_spray_time,
            &other.position_spray_time,
            from..upto + 1,
        );
        copy(
            &mut self.position_transfer,
            &other.position_transfer,
            from..upto + 1,
        );
        self.checkpoints.truncate(upto + 1);
        self.checkpoints.resize_with(upto + 1, Checkpoint::default);
        for position in from..=upto {
            self.checkpoints[position].clone_from(&other.checkpoints[position]);
        }
        self.tour.clone_from(&other.tour);
        self.valid = upto;
    }
}

/// Two sets of buffers: the tour the search stands on (`pinned`, [`SplitCache::pin`]) and
/// the candidates, each resumed from whichever of the two shares more of its start.
#[derive(Debug, Default)]
pub struct SplitCache {
    pinned: SplitBuffers,
    scratch: SplitBuffers,
}

impl SplitCache {
    /// The cost of `tour` by `split` ([`TourSplit::cost`]), resumed from the pinned tour or
    /// the last candidate.
    pub fn cost(&mut self, split: &TourSplit, tour: &[Step]) -> f64 {
        if self.pinned.holds(tour) {
            return self.pinned.cost;
        }
        let pinned = self.pinned.resumable(tour);
        if pinned > self.scratch.resumable(tour) {
            self.scratch.take_prefix(&self.pinned, pinned);
        }
        split.cost(tour, &mut self.scratch)
    }

    /// The sorties of `tour` by `split` ([`TourSplit::sorties`]).
    pub fn sorties(&mut self, split: &TourSplit, tour: &[Step]) -> Vec<(usize, usize)> {
        if !self.pinned.holds(tour) {
            self.cost(split, tour);
            std::mem::swap(&mut self.pinned, &mut self.scratch);
        }
        split.sorties_of(&self.pinned)
    }

    /// Keeps `tour`'s split as the one candidates resume from.
    pub fn pin(&mut self, split: &TourSplit, tour: &[Step]) {
        if !self.pinned.holds(tour) {
            self.cost(split, tour);
            std::mem::swap(&mut self.pinned, &mut self.scratch);
        }
    }

    /// Points laid out and labelled by the splits of this cache (both sets of buffers).
    pub fn points_labelled(&self) -> u64 {
        self.pinned.points_labelled + self.scratch.points_labelled
    }
}

/// The split of tours of given passes.
pub struct TourSplit<'a> {
    /// Every pass's profile, by pass number.
    pub profiles: &'a [PassProfile],
    /// Transfer seconds from the exit of one step to the entry of the next.
    pub transfer_s: &'a dyn Fn(Step, Step) -> f64,
    /// The limits.
    pub limits: SplitLimits,
}

/// Slack on the limits, as the sortie planners use.
const SLACK: f64 = 1e-6;

impl TourSplit<'_> {
    /// Lays out the points of `tour` in flying order from position `resume` on (the
    /// buffers hold the layout of the positions before it).
    fn lay_out(&self, tour: &[Step], resume: usize, buffers: &mut SplitBuffers) {
        let SplitBuffers {
            spray,
            spray_time,
            transfer,
            leg,
            between,
            owner,
            position_first,
            position_spray,
            position_spray_time,
            position_transfer,
            ..
        } = buffers;
        let (mut spray_before, mut seconds_before, mut transfer_before) = if resume == 0 {
            (0.0, 0.0, 0.0)
        } else {
            // The same sums, in the same order, as a layout from the first position.
            let last = tour[resume - 1];
            let profile = &self.profiles[last.pass];
            (
                position_spray[resume - 1] + profile.length(),
                position_spray_time[resume - 1] + profile.seconds(),
                position_transfer[resume - 1] + (self.transfer_s)(last, tour[resume]),
            )
        };
        let first_point = if resume == 0 {
            0
        } else {
            position_first[resume]
        };
        for values in [&mut *spray, &mut *spray_time, &mut *transfer, &mut *leg] {
            values.truncate(first_point);
        }
        between.truncate(first_point);
        owner.truncate(first_point);
        position_first.truncate(resume);
        position_spray.truncate(resume);
        position_spray_time.truncate(resume);
        position_transfer.truncate(resume);
        for (position, step) in tour.iter().enumerate().skip(resume) {
            position_first.push(spray.len());
            position_spray.push(spray_before);
            position_spray_time.push(seconds_before);
            position_transfer.push(transfer_before);
            let profile = &self.profiles[step.pass];
            let (length, seconds) = (profile.length(), profile.seconds());
            let count = profile.spray_m.len();
            // A vector at a time (tight loops, one capacity check each): the same sums as a
            // point at a time, so the same bits.
            if step.reversed {
                spray.extend(
                    profile
                        .spray_m
                        .iter()
                        .rev()
                        .map(|m| spray_before + (length - m)),
                );
                spray_time.extend(
                    profile
                        .spray_s
                        .iter()
                        .rev()
                        .map(|s| seconds_before + (seconds - s)),
                );
                leg.extend(profile.leg_s.iter().rev());
            } else {
                spray.extend(profile.spray_m.iter().map(|m| spray_before + m));
                spray_time.extend(profile.spray_s.iter().map(|s| seconds_before + s));
                leg.extend(&profile.leg_s);
            }
            transfer.resize(transfer.len() + count, transfer_before);
            between.resize(between.len() + count, false);
            owner.resize(owner.len() + count, position);
            spray_before += length;
            seconds_before += seconds;
            if let Some(next) = tour.get(position + 1) {
                transfer_before += (self.transfer_s)(*step, *next);
                *between.last_mut().expect("a pass has points") = true;
            }
        }
    }

    /// The least non-spray seconds of any split of `tour` (`f64::INFINITY` when none is
    /// flyable), resumed at the first position where `tour` differs from the tour last split
    /// with `buffers`.
    pub fn cost(&self, tour: &[Step], buffers: &mut SplitBuffers) -> f64 {
        if buffers.holds(tour) {
            return buffers.cost;
        }
        if tour.is_empty() {
            buffers.tour.clear();
            buffers.spray.clear();
            buffers.valid = 0;
            buffers.cost = 0.0;
            return 0.0;
        }
        let resume = buffers.resumable(tour);
        buffers.tour.clear();
        buffers.tour.extend_from_slice(tour);
        buffers.valid = 0;
        self.lay_out(tour, resume, buffers);
        let cost = self.label(resume, buffers);
        buffers.valid = tour.len();
        buffers.cost = cost;
        cost
    }

    /// The split's labels from the first point of position `resume` on (the buffers hold
    /// the labels and the checkpoints of the positions before it): the cost.
    fn label(&self, resume: usize, buffers: &mut SplitBuffers) -> f64 {
        let SplitBuffers {
            spray,
            spray_time,
            transfer,
            leg,
            between,
            position_first,
            checkpoints,
            start,
            came,
            label_end,
            swap_window,
            refill_window,
            steps,
            points_labelled,
            ..
        } = buffers;
        let count = spray.len();
        let limits = self.limits;
        let tank = limits.tank_m + SLACK;
        let usable = limits.usable_s + SLACK;
        let slope = limits.refill_slope();
        // Spray metres of a sortie beyond which the refill outlasts the battery swap.
        let threshold = if slope > 0.0 {
            ((limits.battery_swap_s - limits.refill_base_s) / slope).max(0.0)
        } else {
            f64::INFINITY
        };
        let flight = |s: usize, e: usize| spray_time[e] - spray_time[s] + transfer[e] - transfer[s];
        let positions = position_first.len();
        checkpoints.resize_with(positions, Checkpoint::default);
        let (first_point, mut lowest) = if resume == 0 {
            start.clear();
            start.resize(count + 1, f64::INFINITY);
            start[0] = 0.0;
            label_end.clear();
            label_end.resize(count + 1, 0);
            swap_window.clear();
            refill_window.clear();
            (1, 1)
        } else {
            let first_point = position_first[resume];
            start.truncate(first_point + 1);
            start.resize(count + 1, f64::INFINITY);
            label_end.truncate(first_point + 1);
            label_end.resize(count + 1, 0);
            let checkpoint = &checkpoints[resume];
            swap_window.clear();
            swap_window.extend(&checkpoint.swap);
            refill_window.clear();
            refill_window.extend(&checkpoint.refill);
            (first_point, checkpoint.lowest)
        };
        came.truncate(first_point);
        came.resize(count, 0);
        *points_labelled += (count - first_point.min(count)) as u64;
        let mut next_position = resume.max(1);
        let key = |s: usize, start: &[f64]| start[s] + leg[s] - transfer[s];
        let refill_key = |s: usize, start: &[f64]| key(s, start) - slope * spray[s];
        for e in first_point..count {
            // The state before a position's first point, for the splits that resume there.
            if next_position < positions && position_first[next_position] == e {
                let checkpoint = &mut checkpoints[next_position];
                checkpoint.swap.clear();
                checkpoint.swap.extend(swap_window.iter());
                checkpoint.refill.clear();
                checkpoint.refill.extend(refill_window.iter());
                checkpoint.lowest = lowest;
                next_position += 1;
            }
            // Start e − 1 is final: it enters the swap window (s = 0, the first sortie,
            // pays no service and is costed on its own below).
            let entering = e - 1;
            if entering > 0 && start[entering].is_finite() {
                let entering_key = key(entering, start);
                while swap_window
                    .back()
                    .is_some_and(|&s| key(s, start) >= entering_key)
                {
                    swap_window.pop_back();
                }
                swap_window.push_back(entering);
            }
            // Starts far enough back that the refill outlasts the swap move to the refill
            // window (in order of s); starts out of a tank's or the battery's reach leave.
            while let Some(&s) = swap_window.front() {
                if spray[e] - spray[s] < threshold {
                    break;
                }
                swap_window.pop_front();
                let moving_key = refill_key(s, start);
                while refill_window
                    .back()
                    .is_some_and(|&r| refill_key(r, start) >= moving_key)
                {
                    refill_window.pop_back();
                }
                refill_window.push_back(s);
            }
            while lowest < e && (spray[e] - spray[lowest] > tank || flight(lowest, e) > usable) {
                lowest += 1;
            }
            for window in [&mut *swap_window, &mut *refill_window] {
                while window.front().is_some_and(|&s| s < lowest) {
                    window.pop_front();
                }
            }
            let sortie = |s: usize, start: &[f64]| {
                let service = if s == 0 {
                    0.0
                } else {
                    limits.service_s(spray[e] - spray[s])
                };
                start[s] + leg[s] + transfer[e] - transfer[s] + service
            };
            let flyable =
                |s: usize| spray[e] - spray[s] <= tank && leg[s] + flight(s, e) + leg[e] <= usable;
            let (mut best, mut best_from) = (f64::INFINITY, 0);
            let mut consider = |s: usize, start: &[f64]| {
                let cost = sortie(s, start);
                if cost < best {
                    (best, best_from) = (cost, s);
                }
            };
            let mut scan = false;
            for front in [swap_window.front(), refill_window.front()]
                .into_iter()
                .flatten()
            {
                if flyable(*front) {
                    consider(*front, start);
                } else {
                    scan = true;
                }
            }
            *steps += 1;
            if scan {
                // The battery breaks at a queue's best start: every start in reach, directly.
                *steps += e.saturating_sub(lowest.max(1)) as u64;
                for s in lowest.max(1)..e {
                    if start[s].is_finite() && flyable(s) {
                        consider(s, start);
                    }
                }
            }
            if flyable(0) {
                consider(0, start);
            }
            came[e] = best_from;
            if e == count - 1 {
                return best + leg[e];
            }
            if !best.is_finite() {
                continue;
            }
            // Back to the supply point from e; out again to e, or past the transfer.
            let back = best + leg[e];
            if between[e] && back < start[e + 1] {
                start[e + 1] = back;
                label_end[e + 1] = e;
            }
            if back < start[e] {
                start[e] = back;
                label_end[e] = e;
            }
        }
        // A tour of one point.
        0.0
    }

    /// The sorties of the cheapest split of `tour`, in flying order, each as the tour
    /// positions of the passes its first and last points lie in (empty when no split is
    /// flyable).
    pub fn sorties(&self, tour: &[Step], buffers: &mut SplitBuffers) -> Vec<(usize, usize)> {
        self.cost(tour, buffers);
        self.sorties_of(buffers)
    }

    /// The sorties of the split `buffers` hold (of the tour last split with them).
    fn sorties_of(&self, buffers: &SplitBuffers) -> Vec<(usize, usize)> {
        if !buffers.cost.is_finite() || buffers.spray.len() < 2 {
            return Vec::new();
        }
        let mut sorties = Vec::new();
        let mut end = buffers.spray.len() - 1;
        loop {
            let first = buffers.came[end];
            sorties.push((buffers.owner[first], buffers.owner[end]));
            if first == 0 {
                break;
            }
            end = buffers.label_end[first];
        }
        sorties.reverse();
        sorties
    }
}
