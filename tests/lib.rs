//! Helpers shared by the suites in `tests/`. What they share with `carom-bench` (the hard
//! cases' worlds, the joint measures, `Rng`) is in `carom_bench::cases`.

use carom::{BodyHandle, World, WorldShape};

pub mod untrusted_files;
pub mod world_ops;

/// The position, angle and velocities of the first body any of which is not finite, if one is.
pub fn first_non_finite_body(world: &World) -> Option<[carom::Real; 6]> {
    world
        .bodies()
        .map(|body| {
            [
                body.position().x,
                body.position().y,
                body.angle(),
                body.linear_velocity().x,
                body.linear_velocity().y,
                body.angular_velocity(),
            ]
        })
        .find(|figures| !figures.iter().all(|x| x.is_finite()))
}

/// Panics, naming its figures, if any body is not finite ([`first_non_finite_body`]).
pub fn assert_bodies_finite(world: &World) {
    if let Some(figures) = first_non_finite_body(world) {
        panic!("a body went non-finite: {figures:?}");
    }
}

/// Every scene file in `demos/`, sorted by name.
pub fn demo_files() -> Vec<std::path::PathBuf> {
    let folder = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../demos");
    let mut files: Vec<_> = std::fs::read_dir(&folder)
        .expect("the demos folder is there")
        .map(|entry| entry.expect("a readable folder entry").path())
        .filter(|path| path.extension().is_some_and(|e| e == "ron"))
        .collect();
    files.sort();
    files
}

/// The world shape of a body made of one collider.
///
/// # Panics
/// A stale handle.
pub fn world_shape(world: &World, body: BodyHandle) -> &WorldShape {
    let body = world.body(body).expect("a live body");
    world
        .collider(body.colliders()[0])
        .expect("a body's collider is live")
        .world_shape()
}

/// Adds an `n` x `n` grid of circles of radius 0.4, 1 m apart, its first at `origin` and its
/// rows going down, each joined to its neighbours by hinges at the midpoints and hung from
/// the two top corners (static): `2 n (n - 1)` joints.
pub fn hanging_grid(world: &mut World, origin: carom::Vec2, n: usize) {
    let at = |i: usize, k: usize| origin + carom::vec2(k as carom::Real, -(i as carom::Real));
    let mut grid = Vec::with_capacity(n * n);
    for i in 0..n {
        for k in 0..n {
            let shape = carom::Shape::circle(0.4);
            let def = if i == 0 && (k == 0 || k == n - 1) {
                carom::BodyDef::static_body(shape)
            } else {
                carom::BodyDef::dynamic(shape)
            };
            grid.push(world.add_body(def.position(at(i, k))).unwrap());
        }
    }
    for i in 0..n {
        for k in 0..n {
            let here = grid[i * n + k];
            if i > 0 {
                let above = grid[(i - 1) * n + k];
                let def = carom::JointDef::revolute(above, here, at(i, k) + carom::vec2(0.0, 0.5));
                world.add_joint(def).unwrap();
            }
            if k > 0 {
                let left = grid[i * n + k - 1];
                let def = carom::JointDef::revolute(left, here, at(i, k) - carom::vec2(0.5, 0.0));
                world.add_joint(def).unwrap();
            }
        }
    }
}

/// Runs `work` on a rayon pool of `threads` threads, so what it steps is shared among them.
///
/// # Panics
/// A pool that cannot be built.
pub fn on_threads<T: Send>(threads: usize, work: impl FnOnce() -> T + Send) -> T {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .expect("a thread pool")
        .install(work)
}
