//! A list of stages on several threads in one parallel region, as Box2D runs its solver: each
//! stage is cut into blocks, the threads claim blocks through atomic flags, and every thread
//! waits (spinning) for the stage's last block before starting the next. One region for a
//! whole step's substeps, instead of a fork and join per pass, because a pass is short (a
//! colour of a 5000-box pyramid takes tens of microseconds) and waking a thread that went to
//! sleep between passes costs several.
//!
//! Each block belongs to one thread, which claims its own blocks first, so from stage to stage
//! a block's data stays in that core's cache; then it takes whatever is left. A thread that
//! starts late only finds fewer blocks left, so no thread ever waits for one that has not
//! started. On one thread (or with too little work to share) the stages simply run in order.

use crate::constants::MAX_BLOCKS;
use rayon::prelude::*;
use std::sync::atomic::{AtomicBool, AtomicU32, AtomicUsize, Ordering};

/// How many blocks to cut `items` into on `threads` threads, at least `min_block` items each.
pub(crate) fn block_count(items: usize, min_block: usize, threads: usize) -> usize {
    (items / min_block.max(1)).clamp(1, MAX_BLOCKS.min(2 * threads))
}

/// The `block`th of `count` nearly equal runs of `0..items`.
pub(crate) fn block_range(items: usize, count: usize, block: usize) -> std::ops::Range<usize> {
    let size = items.div_ceil(count.max(1));
    (block * size).min(items)..((block + 1) * size).min(items)
}

/// Runs stage after stage, each on `blocks(stage)` blocks (at most [`MAX_BLOCKS`]), calling
/// `task(stage, block)` once for every block; a stage starts only when the one before has
/// finished. With `shared` false, or one thread, on the calling thread in order.
pub(crate) fn run_stages(
    stages: usize,
    blocks: impl Fn(usize) -> usize + Sync,
    shared: bool,
    task: impl Fn(usize, usize) + Sync,
) {
    let threads = rayon::current_num_threads();
    if !shared || threads < 2 {
        for stage in 0..stages {
            for block in 0..blocks(stage) {
                task(stage, block);
            }
        }
        return;
    }
    // The stage being worked (FINISHED once all are), which blocks have been claimed (by the
    // last stage that claimed each, plus one), and how many of this stage's blocks are done.
    let current = AtomicUsize::new(WAITING);
    let claims: [AtomicU32; MAX_BLOCKS] = std::array::from_fn(|_| AtomicU32::new(0));
    let done = AtomicUsize::new(0);
    let leader = AtomicBool::new(false);
    let claim_and_run = |stage: usize, me: usize| {
        let count = blocks(stage);
        debug_assert!(count <= MAX_BLOCKS);
        let tag = stage as u32 + 1;
        // Own blocks first, then any left. A thread's own blocks are a run in the middle of
        // the stage, the same share in every stage (as Box2D's workers start): a colour's
        // contacts lie roughly in the order they were made, so a thread keeps working on the
        // same bodies, whose states stay in its cache.
        let own = (me * count / threads)..((me + 1) * count / threads);
        for block in own.chain(0..count) {
            // A plain read first: a block seen claimed costs no write to the shared line.
            if claims[block].load(Ordering::Relaxed) >= tag
                || claims[block].fetch_max(tag, Ordering::AcqRel) >= tag
            {
                continue;
            }
            // Counted when the block is done, even if `task` panics, so no thread spins
            // forever and rayon can pass the panic on.
            let _counted = CountOnDrop(&done);
            task(stage, block);
        }
    };
    (0..threads).into_par_iter().for_each(|_| {
        let me = rayon::current_thread_index().unwrap_or(0) % threads;
        if !leader.swap(true, Ordering::AcqRel) {
            // The leader publishes each stage, works on it, and waits for its last block.
            let _finish = FinishOnDrop(&current);
            for stage in 0..stages {
                let count = blocks(stage);
                if count == 0 {
                    continue;
                }
                done.store(0, Ordering::Relaxed);
                current.store(stage, Ordering::Release);
                claim_and_run(stage, me);
                while done.load(Ordering::Acquire) < count {
                    std::hint::spin_loop();
                }
            }
        } else {
            let mut seen = WAITING;
            loop {
                let stage = current.load(Ordering::Acquire);
                if stage == FINISHED {
                    return;
                }
                if stage != seen && stage != WAITING {
                    seen = stage;
                    claim_and_run(stage, me);
                }
                std::hint::spin_loop();
            }
        }
    });
}

/// `current` before the first stage is published.
const WAITING: usize = usize::MAX - 1;
/// `current` once every stage is done.
const FINISHED: usize = usize::MAX;

/// Adds one to a stage's count of finished blocks when dropped. Release: whoever sees the
/// count also sees what the block wrote.
struct CountOnDrop<'a>(&'a AtomicUsize);

impl Drop for CountOnDrop<'_> {
    fn drop(&mut self) {
        self.0.fetch_add(1, Ordering::Release);
    }
}

/// Tells the other threads that the stages are over when dropped, even if the leader panics.
struct FinishOnDrop<'a>(&'a AtomicUsize);

impl Drop for FinishOnDrop<'_> {
    fn drop(&mut self) {
        self.0.store(FINISHED, Ordering::Release);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each block records how many blocks of the stage before had finished when it began:
    /// all of them, only if every stage ends before the next begins; and each runs once.
    #[test]
    fn stages_run_in_order_and_every_block_once() {
        let counts = [3, 1, 8, 0, 5, 2];
        let finished: Vec<AtomicUsize> = counts.iter().map(|_| AtomicUsize::new(0)).collect();
        let runs: Vec<Vec<AtomicUsize>> = counts
            .iter()
            .map(|&c| (0..c).map(|_| AtomicUsize::new(0)).collect())
            .collect();
        let early = AtomicUsize::new(0);
        for threads in [1, 2, 3] {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            for counter in runs.iter().flatten().chain(&finished) {
                counter.store(0, Ordering::Relaxed);
            }
            pool.install(|| {
                run_stages(
                    counts.len(),
                    |s| counts[s],
                    true,
                    |stage, block| {
                        runs[stage][block].fetch_add(1, Ordering::Relaxed);
                        let before = (0..stage).rev().find(|&s| counts[s] > 0);
                        if let Some(before) = before
                            && finished[before].load(Ordering::Acquire) != counts[before]
                        {
                            early.fetch_add(1, Ordering::Relaxed);
                        }
                        std::thread::yield_now();
                        finished[stage].fetch_add(1, Ordering::Release);
                    },
                );
            });
            for (stage, blocks) in runs.iter().enumerate() {
                for (block, count) in blocks.iter().enumerate() {
                    assert_eq!(
                        count.load(Ordering::Relaxed),
                        1,
                        "{stage}/{block}, {threads}"
                    );
                }
            }
        }
        assert_eq!(early.load(Ordering::Relaxed), 0, "a stage began early");
    }

    /// A block that panics ends the stages with that panic, not with threads spinning forever.
    #[test]
    fn a_panicking_block_is_passed_on() {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(2)
            .build()
            .unwrap();
        let result = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
            pool.install(|| {
                run_stages(
                    4,
                    |_| 4,
                    true,
                    |stage, block| {
                        if (stage, block) == (2, 1) {
                            panic!("block 2/1");
                        }
                    },
                );
            })
        }));
        assert!(result.is_err());
    }

    #[test]
    fn blocks_cover_the_items_once() {
        for (items, count) in [(10, 3), (3, 8), (0, 1), (1000, 4)] {
            let covered: usize = (0..count).map(|b| block_range(items, count, b).len()).sum();
            assert_eq!(covered, items);
        }
        assert_eq!(block_count(5, 16, 2), 1);
        assert_eq!(block_count(10_000, 16, 2), 4);
    }
}
