//! The world's moves of bodies, colliders, contacts and joints between solver sets (see
//! `crate::solver_set`), and, for the tests, a check that every item sits in its set.

use crate::dynamics::body::{BodyHandle, BodyKind};
use crate::dynamics::collider::ColliderHandle;
use crate::joint::Joint;
use crate::solver_set::SolverSet;
use crate::world::World;

impl World {
    /// The set a body belongs in, by its kind and state.
    pub(crate) fn set_for(&self, index: usize) -> SolverSet {
        let body = &self.state.bodies.as_slice()[index];
        if body.kind() == BodyKind::Static {
            SolverSet::Static
        } else if body.is_sleeping() {
            SolverSet::Asleep
        } else {
            SolverSet::Awake
        }
    }

    /// The set a joint belongs in, by its bodies' kinds and sets: with no dynamic body it is
    /// never solved (static); otherwise it is awake while a dynamic body of it is, and sleeps
    /// with their island (a static or kinematic partner does not keep it awake).
    #[allow(
        clippy::expect_used,
        reason = "a live joint's bodies are live: removing a body removes its joints"
    )]
    pub(crate) fn joint_set_for(&self, joint: &Joint) -> SolverSet {
        let mut set = SolverSet::Static;
        for handle in joint.bodies() {
            let index = self
                .state
                .bodies
                .dense_index(handle)
                .expect("joints join live bodies");
            if self.state.bodies.as_slice()[index].kind() != BodyKind::Dynamic {
                continue;
            }
            match self.state.body_sets.set_of(index) {
                SolverSet::Awake => return SolverSet::Awake,
                _ => set = SolverSet::Asleep,
            }
        }
        set
    }

    /// Moves the body at dense `index`, its colliders, its contacts and its joints, into the
    /// sets they then belong in (the body into `to`); returns the body's new index. The
    /// colliders of every body that changes place follow it.
    pub(crate) fn move_body(&mut self, index: usize, to: SolverSet) -> usize {
        let index = self.move_body_and_colliders(index, to);
        let handle = self.state.bodies.handles()[index];
        self.refile_contacts(handle);
        self.refile_joints(handle);
        index
    }

    /// Puts each of a body's joints in the set its bodies call for (after the body changed
    /// set or kind): the cost is the body's own joints.
    #[allow(
        clippy::expect_used,
        reason = "a body's joint list holds only live joints: removing a joint unlists it"
    )]
    fn refile_joints(&mut self, body: BodyHandle) {
        for k in 0..self.state.joints.of_body(body).len() {
            let handle = self.state.joints.of_body(body)[k];
            let joint = self.state.joints.get(handle).expect("listed joints live");
            let to = self.joint_set_for(joint);
            self.state.joints.refile(handle, to);
        }
    }

    /// [`World::move_body`] without refiling the contacts (for a body whose contacts are about
    /// to be destroyed).
    fn move_body_and_colliders(&mut self, index: usize, to: SolverSet) -> usize {
        // The colliders first, each on its own: one just attached may not be in its body's
        // set yet.
        for k in 0..self.state.bodies.as_slice()[index].colliders().len() {
            let collider = self.state.bodies.as_slice()[index].colliders()[k];
            self.move_collider(collider, to);
        }
        if self.state.body_sets.set_of(index) == to {
            return index;
        }
        let (bodies, colliders) = (&mut self.state.bodies, &mut self.state.colliders);
        self.state.body_sets.move_item(index, to, |i, j| {
            bodies.swap(i, j);
            for k in [i, j] {
                for &collider in bodies.as_slice()[k].colliders() {
                    if let Some(c) = colliders.get_mut(collider) {
                        c.set_body_index(k);
                    }
                }
            }
        })
    }

    /// Puts each of a body's contacts in the awake set if either of its bodies is awake, else
    /// in the sleeping set.
    #[allow(
        clippy::expect_used,
        reason = "a live contact's bodies are live: removing a body removes its contacts"
    )]
    fn refile_contacts(&mut self, body: BodyHandle) {
        let (bodies, sets) = (&self.state.bodies, self.state.body_sets);
        self.state.contacts.refile(body, |handle| {
            let index = bodies
                .dense_index(handle)
                .expect("contacts join live bodies");
            (sets.set_of(index), bodies.as_slice()[index].kind())
        });
    }

    /// Moves the body at `index` to the set its kind and state call for (after a change of
    /// kind); returns its new index.
    pub(crate) fn settle_body(&mut self, index: usize) -> usize {
        let to = self.set_for(index);
        self.move_body(index, to)
    }

    /// Colours a body's touching contacts again after its kind changed.
    #[allow(
        clippy::expect_used,
        reason = "a live contact's bodies are live: removing a body removes its contacts"
    )]
    pub(crate) fn repaint_contacts(&mut self, body: BodyHandle) {
        let bodies = &self.state.bodies;
        self.state.contacts.repaint(body, |handle| {
            bodies
                .get(handle)
                .expect("contacts join live bodies")
                .kind()
        });
    }

    /// Wakes the island of the body at `index` if it sleeps (or was just woken by an edit but
    /// still stands in the sleeping set).
    #[allow(
        clippy::expect_used,
        reason = "only a sleeping body is woken, and a sleeping body sleeps in an island"
    )]
    pub(crate) fn wake_body(&mut self, index: usize) {
        if self.state.body_sets.set_of(index) == SolverSet::Asleep {
            let island = self.state.bodies.as_slice()[index].island();
            self.wake_island(island.expect("sleeping bodies have islands"));
        }
    }

    /// Wakes the islands of the sleeping bodies that touch `body` (about to be removed or to
    /// lose a collider: what rested on it must be free to fall).
    pub(crate) fn wake_touching(&mut self, body: BodyHandle) {
        let mut partners = std::mem::take(&mut self.island_scratch.partners);
        self.state.contacts.touching_partners(body, &mut partners);
        for &partner in &partners {
            if let Some(index) = self.state.bodies.dense_index(partner) {
                self.wake_body(index);
            }
        }
        self.island_scratch.partners = partners;
    }

    /// Wakes every sleeping island.
    pub(crate) fn wake_all_islands(&mut self) {
        while self.state.body_sets.asleep_start() < self.state.bodies.len() {
            self.wake_body(self.state.body_sets.asleep_start());
        }
    }

    /// Takes the body at `index` out of its island and moves it, with its colliders, into the
    /// sleeping set, the last of each array: removing it from there moves only another sleeper
    /// into its place, so every set stays contiguous. Its contacts are left where they are,
    /// for the caller to destroy. Returns its index.
    pub(crate) fn prepare_removal(&mut self, index: usize) -> usize {
        self.leave_island(index);
        self.move_body_and_colliders(index, SolverSet::Asleep)
    }

    /// Moves a collider into the sleeping set, the last of the array, so removing it keeps
    /// every set contiguous.
    pub(crate) fn prepare_collider_removal(&mut self, collider: ColliderHandle) {
        self.move_collider(collider, SolverSet::Asleep);
    }

    /// Moves a live collider into set `to`, swapping it with the sets' ends.
    #[allow(
        clippy::expect_used,
        reason = "callers pass attached colliders: removing a collider detaches it"
    )]
    fn move_collider(&mut self, collider: ColliderHandle, to: SolverSet) {
        let at = self
            .state
            .colliders
            .checked_index(collider)
            .expect("attached");
        let colliders = &mut self.state.colliders;
        self.state
            .collider_sets
            .move_item(at, to, |i, j| colliders.swap(i, j));
    }
}

#[cfg(any(test, all(feature = "testing", feature = "serde")))]
impl World {
    /// Checks every invariant the world keeps between calls, panicking on the first broken
    /// one: each item in the solver set it belongs in, and everything a saved world is checked
    /// for as it is read (every handle and index points at something that exists, every
    /// number is finite). For fuzzing and carom's own tests (features `testing` and `serde`).
    #[allow(
        clippy::panic,
        reason = "checking is what this is for: it panics on a broken invariant, for tests and fuzzing"
    )]
    pub fn check_invariants(&self) {
        self.check_sets();
        #[cfg(feature = "serde")]
        if let Err(reason) = self.check_saved() {
            panic!("the world does not hold together: {reason}");
        }
    }

    /// Checks every invariant of the sets, panicking on the first broken one: each body is in
    /// the set its kind and state call for, its colliders in the same set and pointing at it,
    /// each contact awake exactly when one of its bodies is, each joint in the set its bodies
    /// call for, and each sleeping island's list holds exactly the bodies that name it.
    #[allow(
        clippy::expect_used,
        reason = "checking is what this is for: it panics on a broken invariant, for tests and fuzzing"
    )]
    pub(crate) fn check_sets(&self) {
        let bodies = self.state.bodies.as_slice();
        for (index, body) in bodies.iter().enumerate() {
            let set = self.state.body_sets.set_of(index);
            assert_eq!(set, self.set_for(index), "body {index} ({:?})", body.kind());
            for &c in body.colliders() {
                let at = self
                    .state
                    .colliders
                    .dense_index(c)
                    .expect("attached colliders live");
                assert_eq!(
                    self.state.collider_sets.set_of(at),
                    set,
                    "collider of body {index}"
                );
                assert_eq!(self.state.colliders.as_slice()[at].body_index(), index);
            }
            let dynamic = body.kind() == BodyKind::Dynamic;
            assert_eq!(body.island().is_some(), dynamic, "body {index} island");
        }
        assert_eq!(
            self.state.colliders.len(),
            bodies.iter().map(|b| b.colliders().len()).sum::<usize>()
        );
        let awake_body = |h: BodyHandle| {
            let i = self
                .state
                .bodies
                .dense_index(h)
                .expect("contacts join live bodies");
            self.state.body_sets.set_of(i) == SolverSet::Awake
        };
        let mut asleep_touching = 0;
        for (i, contact) in self.state.contacts.iter().enumerate() {
            let awake = awake_body(contact.body_a()) || awake_body(contact.body_b());
            assert_eq!(awake, i < self.state.contacts.awake_len(), "contact {i}");
            if !awake && contact.is_solved() {
                asleep_touching += 1;
            }
        }
        assert_eq!(asleep_touching, self.state.contacts.asleep_touching());
        self.state.contacts.check_ids();
        for (i, joint) in self.state.joints.as_slice().iter().enumerate() {
            let set = self.state.joints.set_of(i);
            assert_eq!(set, self.joint_set_for(joint), "joint {i}");
        }
        self.check_colors();
        self.check_islands();
    }

    /// Checks the islands: each live island's list, walked both ways, is exactly the bodies
    /// that name it, all in one set; every touching contact and every joint between dynamic
    /// bodies joins two bodies of one island.
    #[allow(
        clippy::expect_used,
        clippy::unwrap_used,
        reason = "checking is what this is for: it panics on a broken invariant, for tests and fuzzing"
    )]
    fn check_islands(&self) {
        for id in self.state.islands.live_ids() {
            let island = self.state.islands.get(id);
            let mut walked = Vec::new();
            let mut prev = None;
            let mut next = island.head;
            while let Some(handle) = next {
                let body = self.state.bodies.get(handle).expect("island members live");
                assert_eq!(body.island(), Some(id));
                assert_eq!(body.island_neighbours().0, prev, "island {id} back link");
                walked.push(handle);
                assert!(
                    walked.len() <= self.state.bodies.len(),
                    "island {id} list loops"
                );
                prev = Some(handle);
                next = body.island_neighbours().1;
            }
            assert_eq!(island.tail, prev, "island {id} tail");
            assert_eq!(walked.len(), island.len as usize, "island {id} length");
            let named = self.bodies().filter(|b| b.island() == Some(id)).count();
            assert_eq!(walked.len(), named, "island {id} members");
            let sets: std::collections::HashSet<SolverSet> = walked
                .iter()
                .map(|&h| {
                    self.state
                        .body_sets
                        .set_of(self.state.bodies.dense_index(h).unwrap())
                })
                .collect();
            assert_eq!(sets.len(), 1, "island {id} in one set");
        }
        for contact in self.state.contacts.iter().filter(|c| c.is_solved()) {
            let (a, b) = (
                self.state.bodies.get(contact.body_a()).unwrap(),
                self.state.bodies.get(contact.body_b()).unwrap(),
            );
            if a.is_dynamic() && b.is_dynamic() {
                assert_eq!(a.island(), b.island(), "touching bodies share an island");
            }
        }
        for joint in self.state.joints.as_slice() {
            let [a, b] = joint.bodies().map(|h| self.state.bodies.get(h).unwrap());
            if a.is_dynamic() && b.is_dynamic() {
                assert_eq!(a.island(), b.island(), "joined bodies share an island");
            }
        }
    }
}

#[cfg(any(test, all(feature = "testing", feature = "serde")))]
impl World {
    /// Checks the graph colouring: exactly the awake touching contacts have colours, each
    /// contact is kept in its colour's part (or the awake part that does not touch, or the
    /// sleeping one), no dynamic body is twice in a colour, and each colour holds exactly the
    /// bodies of its contacts.
    #[allow(
        clippy::unwrap_used,
        reason = "checking is what this is for: it panics on a broken invariant, for tests and fuzzing"
    )]
    fn check_colors(&self) {
        use crate::constants::COLOR_COUNT;
        use crate::graph::colors::{NO_COLOR, OVERFLOW};
        use crate::graph::layout::{ASLEEP, NOT_TOUCHING, color_part};
        use std::collections::HashSet;
        let mut held: [HashSet<u32>; COLOR_COUNT] = std::array::from_fn(|_| HashSet::new());
        for (i, contact) in self.state.contacts.iter().enumerate() {
            let (color, holds) = contact.color();
            let awake = i < self.state.contacts.awake_len();
            assert_eq!(
                color != NO_COLOR,
                contact.is_solved() && awake,
                "contact {i}"
            );
            let part = match (awake, color) {
                (false, _) => ASLEEP,
                (true, NO_COLOR) => NOT_TOUCHING,
                (true, color) => color_part(color),
            };
            assert_eq!(self.state.contacts.part_of(i), part, "contact {i}'s part");
            if color == NO_COLOR || color == OVERFLOW {
                continue;
            }
            for (body, holds) in [(contact.body_a(), holds[0]), (contact.body_b(), holds[1])] {
                let dynamic = self.state.bodies.get(body).unwrap().is_dynamic();
                assert_eq!(holds, dynamic, "contact {i} holds its dynamic bodies");
                if holds {
                    let fresh = held[color as usize].insert(body.index());
                    assert!(fresh, "body twice in colour {color}");
                }
            }
        }
        let slots = self
            .state
            .bodies
            .handles()
            .iter()
            .map(|h| h.index() + 1)
            .max();
        let colors = self.state.contacts.colors();
        for (color, held) in held.iter().enumerate() {
            for slot in 0..slots.unwrap_or(0) {
                assert_eq!(colors.holds(color as u8, slot), held.contains(&slot));
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dynamics::body_def::BodyDef;
    use crate::dynamics::collider::ColliderDef;
    use crate::geometry::shape::Shape;
    use crate::math::{Real, vec2};

    /// A small linear congruential generator, so the test is the same every run.
    struct Lcg(u32);

    impl Lcg {
        fn next(&mut self) -> u32 {
            self.0 = self.0.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
            self.0 >> 8
        }

        fn below(&mut self, n: usize) -> usize {
            self.next() as usize % n
        }
    }

    /// Piles that fall asleep, interrupted at random by every edit a user can make (add and
    /// remove bodies and colliders, change kinds, push, move, wake all): after every edit and
    /// every step, each body, collider and contact is in the set it belongs in.
    #[test]
    fn random_edits_keep_every_item_in_its_set() {
        let mut world = World::new();
        world
            .add_body(BodyDef::static_body(Shape::rect(30.0, 0.5)).position(vec2(0.0, -0.5)))
            .unwrap();
        let mut rng = Lcg(7);
        let mut handles = Vec::new();
        let mut slept = 0;
        for round in 0..400 {
            let edit = rng.below(12);
            let pick = (!handles.is_empty()).then(|| handles[rng.below(handles.len())]);
            match (edit, pick) {
                (0..=2, _) | (_, None) => {
                    let x = rng.below(40) as Real - 20.0;
                    let y = 0.5 + rng.below(6) as Real;
                    let def = if rng.below(8) == 0 {
                        BodyDef::static_body(Shape::rect(0.5, 0.5))
                    } else {
                        BodyDef::dynamic(Shape::rect(0.5, 0.5))
                    };
                    handles.push(world.add_body(def.position(vec2(x, y))).unwrap());
                }
                (3, Some(h)) => {
                    world.remove_body(h).unwrap();
                    handles.retain(|&k| k != h);
                }
                (4, Some(h)) => {
                    world
                        .add_collider(
                            h,
                            ColliderDef::new(Shape::circle(0.3)).offset(vec2(0.0, 0.5)),
                        )
                        .unwrap();
                }
                (5, Some(h)) => {
                    let colliders = world.body(h).unwrap().colliders().to_vec();
                    if colliders.len() > 1 {
                        world.remove_collider(colliders[1]).unwrap();
                    }
                }
                (6, Some(h)) => {
                    let kinds = [BodyKind::Static, BodyKind::Kinematic, BodyKind::Dynamic];
                    world
                        .body_mut(h)
                        .unwrap()
                        .set_kind(kinds[rng.below(3)])
                        .unwrap();
                }
                (7, Some(h)) => {
                    world
                        .body_mut(h)
                        .unwrap()
                        .apply_impulse_at_center(vec2(0.0, 1.0))
                        .unwrap();
                }
                (8, Some(h)) => {
                    let mut body = world.body_mut(h).unwrap();
                    let p = body.position();
                    body.set_position(p + vec2(0.1, 0.0)).unwrap();
                }
                (9, _) if round % 50 == 0 => world.wake_all(),
                _ => {
                    for _ in 0..40 {
                        world.step(1.0 / 60.0).unwrap();
                        world.check_sets();
                    }
                }
            }
            world.check_sets();
            slept = slept.max(world.stats().sleeping_bodies);
        }
        assert!(
            slept > 10,
            "piles fell asleep along the way ({slept} at most)"
        );
    }

    /// Editing a sleeping body's colliders (adding one, removing one, changing a density)
    /// wakes it with its island, even when it rests on nothing but the ground.
    #[test]
    fn editing_a_sleeping_body_wakes_it() {
        let mut world = World::new();
        world
            .add_body(BodyDef::static_body(Shape::rect(5.0, 0.5)).position(vec2(0.0, -0.5)))
            .unwrap();
        let body = world
            .add_body(
                BodyDef::dynamic(Shape::rect(0.5, 0.5))
                    .collider(ColliderDef::new(Shape::circle(0.25)).offset(vec2(0.0, 0.5)))
                    .position(vec2(0.0, 0.5)),
            )
            .unwrap();
        let settle = |world: &mut World| {
            for _ in 0..120 {
                world.step(1.0 / 60.0).unwrap();
            }
            assert!(world.body(body).unwrap().is_sleeping());
        };
        settle(&mut world);
        let circle = world.body(body).unwrap().colliders()[1];
        world.remove_collider(circle).unwrap();
        world.check_sets();
        assert!(!world.body(body).unwrap().is_sleeping());
        settle(&mut world);
        let added = world
            .add_collider(body, ColliderDef::new(Shape::circle(0.25)))
            .unwrap();
        world.check_sets();
        assert!(!world.body(body).unwrap().is_sleeping());
        settle(&mut world);
        world.collider_mut(added).unwrap().set_density(2.0).unwrap();
        world.check_sets();
        assert!(!world.body(body).unwrap().is_sleeping());
    }

    /// A grid of boxes added asleep, with gravity and sleeping off (Box2D's smash): nothing
    /// of it is solved until a box thrown at it arrives; then the boxes it touches wake, and
    /// those it has not reached sleep on, unmoved.
    #[test]
    fn bodies_added_asleep_wait_until_something_touches_them() {
        let mut world = World::new();
        let effects = world
            .effects()
            .without(crate::Effect::Gravity)
            .without(crate::Effect::Sleeping);
        world.update_settings(|s| s.effects = effects).unwrap();
        let mut grid = Vec::new();
        for column in 0..20 {
            for row in 0..5 {
                let at = vec2(10.0 + column as Real * 0.4, row as Real * 0.4);
                let def = BodyDef::dynamic(Shape::rect(0.2, 0.2))
                    .position(at)
                    .awake(false);
                grid.push(world.add_body(def).unwrap());
            }
        }
        world.check_sets();
        assert!(grid.iter().all(|&h| world.body(h).unwrap().is_sleeping()));
        let thrown = world
            .add_body(
                BodyDef::dynamic(Shape::rect(0.5, 0.5))
                    .position(vec2(0.0, 0.8))
                    .linear_velocity(vec2(20.0, 0.0)),
            )
            .unwrap();
        world.step(1.0 / 60.0).unwrap();
        world.check_sets();
        assert_eq!(
            world.stats().sleeping_bodies,
            grid.len(),
            "still on its way"
        );
        for _ in 0..40 {
            world.step(1.0 / 60.0).unwrap();
            world.check_sets();
        }
        let (asleep, woken): (Vec<BodyHandle>, Vec<BodyHandle>) = grid
            .iter()
            .partition(|&&h| world.body(h).unwrap().is_sleeping());
        assert!(!woken.is_empty(), "the thrown box woke what it hit");
        assert!(!asleep.is_empty(), "and not yet what lies beyond");
        for (i, &h) in grid.iter().enumerate() {
            let body = world.body(h).unwrap();
            let start = vec2(10.0 + (i / 5) as Real * 0.4, (i % 5) as Real * 0.4);
            if body.is_sleeping() {
                assert_eq!(body.position(), start, "a sleeping box does not move");
            }
        }
        assert!(world.body(thrown).unwrap().position().x > 9.0);
    }

    /// A box on `base` (a 1 m box, at rest on the ground) stepped until it sleeps; the world,
    /// the base and the box.
    fn box_asleep_on(base: BodyDef) -> (World, crate::BodyHandle, crate::BodyHandle) {
        let mut world = World::new();
        world
            .add_body(BodyDef::static_body(Shape::rect(5.0, 0.5)).position(vec2(0.0, -0.5)))
            .unwrap();
        let base = world.add_body(base.position(vec2(0.0, 0.5))).unwrap();
        let top = world
            .add_body(BodyDef::dynamic(Shape::rect(0.5, 0.5)).position(vec2(0.0, 1.5)))
            .unwrap();
        for _ in 0..120 {
            world.step(1.0 / 60.0).unwrap();
        }
        assert!(world.body(top).unwrap().is_sleeping());
        (world, base, top)
    }

    /// A static block turned dynamic under a sleeping box joins the box's island and wakes
    /// it: an island is awake or asleep as a whole.
    #[test]
    fn a_support_turned_dynamic_wakes_what_slept_on_it() {
        let (mut world, block, top) = box_asleep_on(BodyDef::static_body(Shape::rect(0.5, 0.5)));
        world
            .body_mut(block)
            .unwrap()
            .set_kind(BodyKind::Dynamic)
            .unwrap();
        world.check_sets();
        let (block, top) = (world.body(block).unwrap(), world.body(top).unwrap());
        assert!(!top.is_sleeping());
        assert_eq!(block.island(), top.island());
    }

    /// Removing what a sleeping stack rests on wakes the stack, so it falls.
    #[test]
    fn removing_a_support_wakes_what_slept_on_it() {
        let (mut world, base, top) = box_asleep_on(BodyDef::dynamic(Shape::rect(0.5, 0.5)));
        world.remove_body(base).unwrap();
        world.check_sets();
        assert!(!world.body(top).unwrap().is_sleeping());
        let before = world.body(top).unwrap().position().y;
        for _ in 0..30 {
            world.step(1.0 / 60.0).unwrap();
        }
        let fell = before - world.body(top).unwrap().position().y;
        assert!(fell > 0.5, "fell {fell} m");
    }
}
