//! Independent work spread over the machine's cores, its results in input order, so that a
//! plan is the same to the bit whatever the number of cores (decision 0025).

use std::sync::atomic::{AtomicUsize, Ordering};

/// Most threads, whatever `RAYON_NUM_THREADS` asks for.
const MOST_THREADS: usize = 64;

/// A worker's stack: as the main thread's (8 MiB on Linux), not a spawned thread's 2 MiB,
/// since the work on a field recurses with its rings (`geo`'s simplification).
const WORKER_STACK_BYTES: usize = 8 << 20;

/// Threads to use: `RAYON_NUM_THREADS` when it is a whole number from 1 (the variable that
/// sets the swarm runs' pool too, so one knob sets all of the program's threads; 1 measures
/// one core; anything else is ignored), else the machine's available parallelism; at most
/// 64.
pub fn threads() -> usize {
    std::env::var("RAYON_NUM_THREADS")
        .ok()
        .and_then(|value| value.trim().parse::<usize>().ok())
        .filter(|&count| count > 0)
        .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |count| count.get()))
        .min(MOST_THREADS)
}

/// `work(index, item)` for every item on [`threads`] threads, the results in the items'
/// order, or the fault of the first item (by index) that failed. Items are started in index
/// order, each thread taking the next one not yet taken (the items may differ much in size:
/// one large field and four small ones); once an item has failed, no item after it is
/// started, as a loop on one thread would stop there.
pub fn try_map_in_order<T: Sync, R: Send, E: Send>(
    items: &[T],
    work: impl Fn(usize, &T) -> Result<R, E> + Sync,
) -> Result<Vec<R>, E> {
    try_map_in_order_on(threads(), items, work)
}

/// `work(item)` for every item on [`threads`] threads, the results in the items' order (as
/// [`try_map_in_order`], for work that cannot fail).
pub fn map_in_order<T: Sync, R: Send>(items: &[T], work: impl Fn(&T) -> R + Sync) -> Vec<R> {
    let outcome = try_map_in_order(items, |_, item| {
        Ok::<R, std::convert::Infallible>(work(item))
    });
    match outcome {
        Ok(results) => results,
        Err(never) => match never {},
    }
}

/// [`try_map_in_order`] on `threads` threads (the caller's among them).
fn try_map_in_order_on<T: Sync, R: Send, E: Send>(
    threads: usize,
    items: &[T],
    work: impl Fn(usize, &T) -> Result<R, E> + Sync,
) -> Result<Vec<R>, E> {
    let helpers = threads.min(items.len()).saturating_sub(1);
    if helpers == 0 {
        return items
            .iter()
            .enumerate()
            .map(|(index, item)| work(index, item))
            .collect();
    }
    let next = AtomicUsize::new(0);
    let first_failed = AtomicUsize::new(usize::MAX);
    let take_items = || {
        let mut mine = Vec::new();
        loop {
            let index = next.fetch_add(1, Ordering::SeqCst);
            if index >= items.len() || index > first_failed.load(Ordering::SeqCst) {
                return mine;
            }
            let result = work(index, &items[index]);
            if result.is_err() {
                first_failed.fetch_min(index, Ordering::SeqCst);
            }
            mine.push((index, result));
        }
    };
    let mut done: Vec<(usize, Result<R, E>)> = std::thread::scope(|scope| {
        // A helper the system refuses is left out: the caller's thread works too.
        let workers: Vec<_> = (0..helpers)
            .filter_map(|_| {
                std::thread::Builder::new()
                    .stack_size(WORKER_STACK_BYTES)
                    .spawn_scoped(scope, take_items)
                    .ok()
            })
            .collect();
        let mut done = take_items();
        for worker in workers {
            // A panic in the work is the caller's panic, as it would be on one thread.
            done.extend(
                worker
                    .join()
                    .unwrap_or_else(|panic| std::panic::resume_unwind(panic)),
            );
        }
        done
    });
    done.sort_unstable_by_key(|&(index, _)| index);
    // Items are started in index order and none after a failed one, so every item before
    // the first failure is here, and the first `Err` in order is that failure.
    done.into_iter().map(|(_, result)| result).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Uneven work (so that threads finish out of order), failing at the indices `failing`.
    fn work(failing: &[usize]) -> impl Fn(usize, &u64) -> Result<(usize, u64), usize> + Sync + '_ {
        move |index, item| {
            let mut value = *item;
            for _ in 0..(item % 7) * 2_000 {
                value = value.wrapping_mul(6364136223846793005).wrapping_add(1);
            }
            if failing.contains(&index) {
                Err(index)
            } else {
                Ok((index, value))
            }
        }
    }

    #[test]
    fn results_come_in_the_items_order_whatever_the_threads() {
        let items: Vec<u64> = (0..200).collect();
        let alone = try_map_in_order_on(1, &items, work(&[])).unwrap();
        assert_eq!(alone.len(), 200);
        for threads in [2, 3, 8] {
            assert_eq!(
                try_map_in_order_on(threads, &items, work(&[])).unwrap(),
                alone
            );
        }
        assert!(try_map_in_order_on(4, &[] as &[u64], work(&[]))
            .unwrap()
            .is_empty());
    }

    #[test]
    fn the_first_failure_by_index_is_the_one_returned() {
        let items: Vec<u64> = (0..200).collect();
        for threads in [1, 2, 8] {
            let started = AtomicUsize::new(0);
            let counted = |index: usize, item: &u64| {
                started.fetch_add(1, Ordering::SeqCst);
                work(&[150, 40, 41])(index, item)
            };
            assert_eq!(try_map_in_order_on(threads, &items, counted), Err(40));
            // On one thread nothing after the failure starts; on several, what had started
            // finishes (how much depends on the scheduler, so it is not asserted).
            if threads == 1 {
                assert_eq!(started.load(Ordering::SeqCst), 41);
            }
        }
    }
}
