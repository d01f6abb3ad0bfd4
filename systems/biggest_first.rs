//! Uneven jobs over the rayon pool, biggest first: greedy list scheduling.
//!
//! Used by the Tessellate stage, whose dirty patches after one edit are a few big
//! meshes (a head, a course) among many small ones (necks, flange faces). A plain
//! parallel iterator splits the list into one half per thread and a half is only
//! split again when another thread steals from it, so one thread could mesh the
//! head, the other head and the course in a row while the other thread, done with
//! the necks, had nothing left to take: measured on a tank's diameter edit, one
//! thread idle for three quarters of the stage. Here every thread takes the next
//! job from one list sorted by estimated cost, largest first, until the list is
//! empty (and then helps with the big jobs' own parallel loops), which ends the
//! stage within the longest job of the optimum. Results come back in the items'
//! order, so the outcome does not depend on which thread ran what.

use std::cmp::Reverse;
use std::sync::OnceLock;
use std::sync::atomic::{AtomicUsize, Ordering};

/// `f` of every item, in the items' order, run on the current rayon pool with
/// the items of highest `cost` started first.
pub fn map_biggest_first<T: Sync, R: Send + Sync>(
    items: &[T],
    cost: impl Fn(&T) -> u64,
    f: impl Fn(&T) -> R + Sync,
) -> Vec<R> {
    let mut order: Vec<usize> = (0..items.len()).collect();
    // Stable: equal costs keep the items' order.
    order.sort_by_cached_key(|&i| Reverse(cost(&items[i])));
    let slots: Vec<OnceLock<R>> = (0..items.len()).map(|_| OnceLock::new()).collect();
    let next = AtomicUsize::new(0);
    let workers = rayon::current_num_threads().min(items.len());
    rayon::scope(|s| {
        for _ in 0..workers {
            s.spawn(|_| {
                while let Some(&i) = order.get(next.fetch_add(1, Ordering::Relaxed)) {
                    // Each index is taken once: the slot is empty.
                    let _ = slots[i].set(f(&items[i]));
                }
            });
        }
    });
    slots.into_iter().filter_map(OnceLock::into_inner).collect()
}

#[cfg(test)]
mod tests {
    use super::map_biggest_first;

    #[test]
    fn every_item_once_in_order_on_any_pool() {
        let items: Vec<u64> = (0..100).map(|k| (k * 37) % 101).collect();
        for threads in [1, 2, 3] {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            let out = pool.install(|| map_biggest_first(&items, |&x| x, |&x| x * 2));
            assert_eq!(out, items.iter().map(|x| x * 2).collect::<Vec<_>>());
        }
        assert!(map_biggest_first(&[] as &[u64], |&x| x, |&x| x).is_empty());
    }

    #[test]
    fn the_biggest_jobs_start_first() {
        // On one thread the jobs run in the order they are taken.
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(1)
            .build()
            .unwrap();
        let started = std::sync::Mutex::new(Vec::new());
        let items = [3u64, 9, 1, 7, 7];
        pool.install(|| map_biggest_first(&items, |&x| x, |&x| started.lock().unwrap().push(x)));
        assert_eq!(started.into_inner().unwrap(), vec![9, 7, 7, 3, 1]);
    }
}
