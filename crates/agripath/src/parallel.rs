//! Independent work spread over the machine's cores, its results in input order, so that a
//! plan is the same to the bit whatever the number of cores.

use std::sync::atomic::{AtomicUsize, Ordering};

/// Threads to use: `AGRIPATH_THREADS` when set to a whole number (1 measures one core), else
/// the machine's available parallelism.
pub fn threads() -> usize {
    std::env::var("AGRIPATH_THREADS")
        .ok()
        .and_then(|value| value.parse::<usize>().ok())
        .filter(|&count| count > 0)
        .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |count| count.get()))
}

/// `work(index, item)` for every item, each thread taking the next item not yet taken (the
/// items may differ much in size: one large field and four small ones), and the results in
/// the items' order. On one thread, or for one item, it runs in the caller's thread.
pub fn map_in_order<T: Sync, R: Send>(items: &[T], work: impl Fn(usize, &T) -> R + Sync) -> Vec<R> {
    let count = threads().min(items.len());
    if count <= 1 {
        return items
            .iter()
            .enumerate()
            .map(|(index, item)| work(index, item))
            .collect();
    }
    let next = AtomicUsize::new(0);
    let mut done: Vec<(usize, R)> = std::thread::scope(|scope| {
        let workers: Vec<_> = (0..count)
            .map(|_| {
                scope.spawn(|| {
                    let mut mine = Vec::new();
                    loop {
                        let index = next.fetch_add(1, Ordering::Relaxed);
                        let Some(item) = items.get(index) else {
                            return mine;
                        };
                        mine.push((index, work(index, item)));
                    }
                })
            })
            .collect();
        workers
            .into_iter()
            .flat_map(|worker| {
                // A panic in the work is the caller's panic, as it would be on one thread.
                worker
                    .join()
                    .unwrap_or_else(|panic| std::panic::resume_unwind(panic))
            })
            .collect()
    });
    done.sort_unstable_by_key(|&(index, _)| index);
    done.into_iter().map(|(_, result)| result).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn results_come_in_the_items_order_whatever_the_threads() {
        let items: Vec<u64> = (0..200).collect();
        // Uneven work, so that the threads finish out of order.
        let work = |index: usize, item: &u64| {
            let spin = (item % 7) * 2_000;
            let mut value = *item;
            for _ in 0..spin {
                value = value.wrapping_mul(6364136223846793005).wrapping_add(1);
            }
            (index, value)
        };
        let together = map_in_order(&items, work);
        let alone: Vec<(usize, u64)> = items.iter().enumerate().map(|(i, x)| work(i, x)).collect();
        assert_eq!(together, alone);
        assert!(map_in_order(&[] as &[u64], work).is_empty());
    }
}
