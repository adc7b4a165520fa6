//! The tile pass's scheduler: which thread draws which group of tiles, and when.

use std::sync::Mutex;
use std::sync::atomic::{AtomicU64, AtomicUsize, Ordering};

/// Draws every group of tiles on the pool's threads, the costliest first, each thread taking the
/// next group as it finishes one; returns the sum of `draw`'s results (fragments that passed).
///
/// Groups differ wildly in cost (most are empty, a few hold most of a mesh). Rayon's halving of an
/// index range left one thread with a costly group to finish while the other idled: on the bunny's
/// eye pass the tile pass kept two threads 92–97 % busy. Taking groups in order of decreasing cost
/// from one shared counter leaves at most a cheap group's time at the end. Which thread draws a
/// group does not change what is drawn into it, and the sum is of integers, so the result does not
/// depend on the schedule.
pub(crate) fn costliest_first<G: Send>(
    groups: Vec<G>,
    cost: impl Fn(usize) -> u64,
    draw: impl Fn(usize, G) -> u64 + Sync,
) -> u64 {
    let mut order: Vec<(u64, usize)> = (0..groups.len()).map(|g| (cost(g), g)).collect();
    // Decreasing cost, ties in group order.
    order.sort_unstable_by_key(|&(c, g)| (std::cmp::Reverse(c), g));
    let mut groups: Vec<Option<G>> = groups.into_iter().map(Some).collect();
    let queue: Vec<(usize, Mutex<Option<G>>)> = order
        .iter()
        .map(|&(_, g)| (g, Mutex::new(groups[g].take())))
        .collect();
    let next = AtomicUsize::new(0);
    let passed = AtomicU64::new(0);
    let worker = || {
        let mut mine = 0;
        while let Some((g, slot)) = queue.get(next.fetch_add(1, Ordering::Relaxed)) {
            let group = slot
                .lock()
                .unwrap_or_else(std::sync::PoisonError::into_inner)
                .take();
            if let Some(group) = group {
                mine += draw(*g, group);
            }
        }
        passed.fetch_add(mine, Ordering::Relaxed);
    };
    rayon::scope(|scope| {
        for _ in 1..rayon::current_num_threads() {
            scope.spawn(|_| worker());
        }
        worker();
    });
    passed.into_inner()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every group is drawn once, whatever its cost and however many threads share the work.
    #[test]
    fn every_group_is_drawn_once_costliest_first() {
        for threads in [1, 2, 3] {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .expect("a pool");
            let mut drawn = vec![0u32; 37];
            let total = pool.install(|| {
                let groups: Vec<&mut u32> = drawn.iter_mut().collect();
                costliest_first(
                    groups,
                    |g| (g as u64 * 7) % 5,
                    |g, count| {
                        *count += 1;
                        g as u64
                    },
                )
            });
            assert_eq!(drawn, vec![1; 37], "{threads} threads");
            assert_eq!(total, (0..37).sum::<u64>());
        }
    }
}
