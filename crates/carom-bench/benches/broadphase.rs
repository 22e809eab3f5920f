//! Broadphase cost against collider count (one per body here): building the tree for n boxes and finding their pairs,
//! then one step of motion (every box drifts, some leave their fat boxes) and the pair update.
//!
//! Run with `cargo bench -p carom-bench --features criterion --bench broadphase`. Time per box should grow like log n.

use carom::testing::BroadPhase;
use carom::{Aabb, BodyHandle, BodyKind, ColliderHandle, Real, vec2};
use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use std::hint::black_box;

const MARGIN: Real = 0.05;

/// `n` unit boxes scattered at random over a square field with about four square metres
/// each, so every box has a few neighbours, as in a pile. One in ten is static.
fn scene(n: usize) -> Vec<(ColliderHandle, BodyKind, Aabb)> {
    let side = (4.0 * n as f64).sqrt() as Real;
    let mut state = 0x2545_f491_4f6c_dd1d_u64;
    let mut next = move || {
        state ^= state >> 12;
        state ^= state << 25;
        state ^= state >> 27;
        (state.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 40) as Real / (1u64 << 24) as Real
    };
    (0..n)
        .map(|i| {
            let center = vec2(next() * side, next() * side);
            let half = vec2(0.5, 0.5);
            let kind = if i % 10 == 0 {
                BodyKind::Static
            } else {
                BodyKind::Dynamic
            };
            (
                ColliderHandle::from_raw_parts(i as u32, 0),
                kind,
                Aabb::new(center - half, center + half),
            )
        })
        .collect()
}

fn build(bodies: &[(ColliderHandle, BodyKind, Aabb)]) -> BroadPhase {
    let mut broadphase = BroadPhase::new();
    for (handle, kind, aabb) in bodies {
        // One collider per body, which shares its index.
        let body = BodyHandle::from_raw_parts(handle.index(), 0);
        broadphase.insert(*handle, body, *kind, *aabb, MARGIN);
    }
    black_box(broadphase.update_pairs(|_, _| false));
    broadphase
}

fn bench(c: &mut Criterion) {
    let mut group = c.benchmark_group("broadphase");
    group.sample_size(10);
    for n in [1_000, 10_000, 100_000] {
        let bodies = scene(n);
        group.bench_with_input(BenchmarkId::new("build", n), &bodies, |b, bodies| {
            b.iter(|| build(bodies));
        });
        // One step: every dynamic box drifts 2 cm (a box at 1.2 m/s at 60 Hz) along a
        // direction that varies with its index, so a fraction leave their fat boxes each step;
        // as in a world's step, those are enlarged in place, the pairs found, and the moving
        // tree rebuilt.
        group.bench_with_input(BenchmarkId::new("update", n), &bodies, |b, bodies| {
            let mut broadphase = build(bodies);
            let mut moved = bodies.to_vec();
            let mut step = 0u32;
            b.iter(|| {
                step += 1;
                for (i, (handle, kind, aabb)) in moved.iter_mut().enumerate() {
                    if *kind == BodyKind::Static {
                        continue;
                    }
                    let angle = (i as u32 ^ step) as Real * 0.618;
                    let d = vec2(angle.cos(), angle.sin()) * 0.02;
                    *aabb = Aabb::new(aabb.min + d, aabb.max + d);
                    broadphase.enlarge(*handle, *kind, *aabb, MARGIN);
                }
                let pairs = broadphase.update_pairs(|_, _| false).len();
                broadphase.rebuild_moving_tree();
                black_box(pairs)
            });
        });
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
