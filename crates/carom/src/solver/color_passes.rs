//! One pass over the graph colours on several threads. The colours must be solved one after the
//! other, and each is quick (a few hundred microseconds in a 5000-box pyramid), so a fork and
//! join per colour would cost more than it saves. Instead the threads stay together for the
//! whole pass, as Box2D's solver stages do: each colour is cut into blocks, a thread claims
//! blocks through atomic flags, and every thread waits (spinning) for the colour's last block
//! before starting the next colour. Each block belongs to one thread of the pool, which claims
//! its own blocks first, so from pass to pass a block's data stays in that core's cache; then
//! it takes whatever is left. A thread that starts late only finds fewer blocks left, so no
//! thread ever waits for one that has not started.

use crate::constants::{COLOR_COUNT, MAX_BLOCKS, MIN_BLOCK, MIN_SHARED};
use rayon::prelude::*;
use std::ops::Range;
use std::sync::Mutex;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

/// Runs `task` on every item, colour by colour (`colors` are consecutive ranges of `items`),
/// on the threads of the current rayon pool when there is enough to share. `task` takes a
/// block of items of one colour at a time (on one thread, all of them at once, in order).
pub(crate) fn for_each_by_color<T: Send>(
    items: &mut [T],
    colors: &[Range<usize>],
    task: impl Fn(&mut [T]) + Sync,
) {
    let threads = rayon::current_num_threads();
    if threads < 2 || items.len() < MIN_SHARED || colors.len() > COLOR_COUNT {
        task(items);
        return;
    }
    // Cut every colour into blocks, each behind a lock that is never contended (a block is
    // claimed once), which is how a claimed block is lent mutably to whichever thread claims it.
    let mut blocks: [[Option<Mutex<&mut [T]>>; MAX_BLOCKS]; COLOR_COUNT] =
        std::array::from_fn(|_| std::array::from_fn(|_| None));
    let mut block_counts = [0usize; COLOR_COUNT];
    let mut rest = items;
    for (color, range) in colors.iter().enumerate() {
        let (mut of_color, after) = rest.split_at_mut(range.len());
        rest = after;
        let count = (of_color.len() / MIN_BLOCK).clamp(1, MAX_BLOCKS.min(2 * threads));
        let size = of_color.len().div_ceil(count);
        for block in blocks[color].iter_mut().take(count) {
            let (this, more) = of_color.split_at_mut(size.min(of_color.len()));
            of_color = more;
            *block = Some(Mutex::new(this));
        }
        block_counts[color] = count;
    }
    let taken: [[AtomicBool; MAX_BLOCKS]; COLOR_COUNT] =
        std::array::from_fn(|_| std::array::from_fn(|_| AtomicBool::new(false)));
    let done: [AtomicUsize; COLOR_COUNT] = std::array::from_fn(|_| AtomicUsize::new(0));
    let work = || {
        let me = rayon::current_thread_index().unwrap_or(0) % threads;
        for color in 0..colors.len() {
            let count = block_counts[color];
            // Own blocks first (me, me + threads, ...), then any left.
            let own = (me..count).step_by(threads);
            for index in own.chain(0..count) {
                if taken[color][index].swap(true, Ordering::Relaxed) {
                    continue;
                }
                // Counted when the block is done, even if `task` panics, so no thread spins
                // forever and rayon can pass the panic on.
                let _counted = CountOnDrop(&done[color]);
                if let Some(block) = &blocks[color][index] {
                    let mut block = block.lock().unwrap_or_else(|e| e.into_inner());
                    task(&mut block);
                }
            }
            while done[color].load(Ordering::Acquire) < count {
                std::hint::spin_loop();
            }
        }
    };
    (0..threads).into_par_iter().for_each(|_| work());
}

/// Adds one to a colour's count of finished blocks when dropped. Release: whoever sees the
/// count also sees what the block wrote.
struct CountOnDrop<'a>(&'a AtomicUsize);

impl Drop for CountOnDrop<'_> {
    fn drop(&mut self) {
        self.0.fetch_add(1, Ordering::Release);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each item records the sum of the items of the previous colour when its turn comes:
    /// right only if every colour is finished before the next begins.
    #[test]
    fn colours_run_in_order_and_every_item_once() {
        let colors: Vec<Range<usize>> = vec![0..900, 900..940, 940..3000, 3000..3001];
        let mut items: Vec<(usize, std::sync::atomic::AtomicUsize, usize)> = (0..3001)
            .map(|i| {
                let color = colors.iter().position(|c| c.contains(&i)).unwrap();
                (color, AtomicUsize::new(0), 0)
            })
            .collect();
        let finished: [AtomicUsize; 4] = std::array::from_fn(|_| AtomicUsize::new(0));
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(3)
            .build()
            .unwrap();
        pool.install(|| {
            for_each_by_color(&mut items, &colors, |block| {
                for (color, runs, seen_before) in block {
                    runs.fetch_add(1, Ordering::Relaxed);
                    *seen_before = if *color == 0 {
                        0
                    } else {
                        finished[*color - 1].load(Ordering::Relaxed)
                    };
                    finished[*color].fetch_add(1, Ordering::Relaxed);
                }
            });
        });
        for (color, runs, seen_before) in &items {
            assert_eq!(runs.load(Ordering::Relaxed), 1);
            if *color > 0 {
                assert_eq!(
                    *seen_before,
                    colors[*color - 1].len(),
                    "colour {color} began early"
                );
            }
        }
    }

    /// A task that panics ends the pass with that panic, not with threads spinning forever.
    #[test]
    fn a_panicking_task_is_passed_on() {
        let colors: Vec<Range<usize>> = vec![0..1500, 1500..3000];
        let mut items: Vec<usize> = (0..3000).collect();
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(2)
            .build()
            .unwrap();
        let result = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
            pool.install(|| {
                for_each_by_color(&mut items, &colors, |block| {
                    if block.contains(&700) {
                        panic!("item 700");
                    }
                });
            })
        }));
        assert!(result.is_err());
    }
}
