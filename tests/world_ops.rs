//! Any sequence of public calls on a world, read from bytes: the world-operations fuzz target
//! (`fuzz/fuzz_targets/world_ops.rs`) feeds it what libFuzzer makes, and `tests/robustness.rs`
//! feeds it seeded random bytes.
//!
//! Each call is made with values that are sometimes sensible, sometimes extreme and sometimes
//! not numbers at all. After each, it checks what carom promises: nothing panics, a call
//! either succeeds or returns an error (a time step is refused exactly when it is outside 1 µs to
//! 10 s), every body's position, angle and velocities stay finite, every query answers
//! with finite figures, the world's internal invariants hold
//! ([`carom::World::check_invariants`]), and a world saved and read back steps to the same
//! bits as the original.

use carom::{
    BodyDef, BodyHandle, BodyKind, Capacity, Capsule, CaromError, Character, CharacterDef,
    ColliderDef, ColliderHandle, CollisionFilter, CollisionPlane, Effects, ExplosionDef, JointDef,
    JointHandle, QueryFilter, Ray, Real, Shape, SolverKind, Vec2, World, WorldShape, solve_planes,
    vec2,
};

/// The most bodies a sequence keeps (more are not added), so each case stays quick.
const MAX_BODIES: usize = 48;

/// Bytes read as choices; past the end every read is zero.
struct Input<'a> {
    bytes: &'a [u8],
    at: usize,
    /// The odd numbers drawn for the call being made, named when a check fails.
    odd: Vec<Real>,
}

impl Input<'_> {
    fn byte(&mut self) -> u8 {
        let byte = self.bytes.get(self.at).copied().unwrap_or(0);
        self.at += 1;
        byte
    }

    fn done(&self) -> bool {
        self.at >= self.bytes.len()
    }

    fn below(&mut self, n: usize) -> usize {
        let wide = u16::from_le_bytes([self.byte(), self.byte()]) as usize;
        wide % n.max(1)
    }

    fn flag(&mut self) -> bool {
        self.byte() & 1 == 1
    }

    /// A number: mostly within `-span..span`, now and then one from the ends of the whole range
    /// (the largest finite values, subnormals, signed zeros), not a number, or any bit pattern.
    fn real(&mut self, span: Real) -> Real {
        const ODD: [Real; 22] = [
            0.0,
            -0.0,
            1e-30,
            -1e-7,
            1e6,
            -1e9,
            1e15,
            -1e30,
            1e38,
            Real::MAX,
            -Real::MAX,
            Real::MAX / 2.0,
            Real::EPSILON,
            Real::MIN_POSITIVE,
            -Real::MIN_POSITIVE / 4.0,
            Real::MIN_POSITIVE * Real::EPSILON,
            -Real::MIN_POSITIVE * Real::EPSILON,
            Real::NAN,
            -Real::NAN,
            Real::INFINITY,
            Real::NEG_INFINITY,
            1.0 - Real::EPSILON / 2.0,
        ];
        let kind = self.byte();
        if kind < 24 {
            let odd = if kind < 16 {
                ODD[self.below(ODD.len())]
            } else {
                self.any_bits()
            };
            self.odd.push(odd);
            odd
        } else {
            let unit = u16::from_le_bytes([self.byte(), self.byte()]) as Real / 65535.0;
            (unit * 2.0 - 1.0) * span
        }
    }

    /// Any bit pattern of a `Real`, whichever precision carom is built in.
    fn any_bits(&mut self) -> Real {
        let bits = u64::from_le_bytes(std::array::from_fn(|_| self.byte()));
        if std::mem::size_of::<Real>() == 4 {
            f32::from_bits(bits as u32) as Real
        } else {
            f64::from_bits(bits) as Real
        }
    }

    /// A number in `low..high`, never odd.
    fn within(&mut self, low: Real, high: Real) -> Real {
        let unit = u16::from_le_bytes([self.byte(), self.byte()]) as Real / 65535.0;
        low + unit * (high - low)
    }

    fn point(&mut self, span: Real) -> Vec2 {
        vec2(self.real(span), self.real(span))
    }

    fn shape(&mut self) -> Shape {
        let size = if self.byte() < 8 {
            self.real(1e6)
        } else {
            self.within(0.05, 2.0)
        };
        match self.below(7) {
            0 => Shape::circle(size),
            1 => Shape::rect(size, self.within(0.02, 2.0)),
            2 => Shape::rounded_rect(size, self.within(0.02, 1.0), self.within(0.0, 0.3)),
            3 => Shape::capsule(vec2(-size, 0.0), vec2(size, 0.0), self.within(0.01, 0.5)),
            4 => Shape::segment(self.point(3.0), self.point(3.0)),
            5 => {
                let points: Vec<Vec2> = (0..3 + self.below(6)).map(|_| self.point(2.0)).collect();
                Shape::hull(&points).unwrap_or_else(|_| Shape::circle(0.5))
            }
            _ => Shape::regular(3 + self.below(8), size).unwrap_or_else(|_| Shape::circle(0.5)),
        }
    }

    fn filter(&mut self) -> CollisionFilter {
        if self.byte() < 200 {
            return CollisionFilter::DEFAULT;
        }
        CollisionFilter {
            category: 1 << self.below(64),
            mask: u64::from_le_bytes(std::array::from_fn(|_| self.byte())),
            group: self.below(7) as i32 - 3,
        }
    }

    fn pick<T: Copy>(&mut self, items: &[T]) -> Option<T> {
        (!items.is_empty()).then(|| items[self.below(items.len())])
    }
}

/// What a sequence did, so a caller can see that it did something.
#[derive(Debug, Default, Clone, Copy)]
pub struct Tally {
    /// Calls made.
    pub calls: usize,
    /// Calls refused with an error.
    pub refused: usize,
    /// Steps taken.
    pub steps: usize,
    /// Saves read back and compared.
    pub restores: usize,
}

/// Plays the calls `bytes` spell on a new world, checking carom's promises after each
/// (panicking on the first broken one); returns what it did.
pub fn run(bytes: &[u8]) -> Tally {
    let mut input = Input {
        bytes,
        at: 0,
        odd: Vec::new(),
    };
    let mut world = World::new();
    let mut tally = Tally::default();
    let mut bodies: Vec<BodyHandle> = Vec::new();
    let mut colliders: Vec<ColliderHandle> = Vec::new();
    let mut joints: Vec<JointHandle> = Vec::new();
    let mut character: Option<Character> = None;
    // A floor, so piles form, contacts persist and bodies sleep.
    world
        .add_body(BodyDef::static_body(Shape::rect(40.0, 0.5)).position(vec2(0.0, -0.5)))
        .expect("a floor");
    // The calls made so far, by number, with the odd numbers each drew, named when a check
    // fails.
    let mut calls: Vec<(usize, Vec<Real>)> = Vec::new();
    while !input.done() && tally.calls < 400 {
        tally.calls += 1;
        let call = input.below(26);
        input.odd.clear();
        let refused = match call {
            0..=3 if bodies.len() < MAX_BODIES => {
                let kind = [
                    BodyKind::Dynamic,
                    BodyKind::Dynamic,
                    BodyKind::Static,
                    BodyKind::Kinematic,
                ][input.below(4)];
                let def = BodyDef::new(kind, input.shape())
                    .position(input.point(20.0) + vec2(0.0, 10.0))
                    .angle(input.real(7.0))
                    .linear_velocity(input.point(30.0))
                    .angular_velocity(input.real(20.0))
                    .density(input.within(0.1, 5.0))
                    .friction(input.within(0.0, 1.0))
                    .restitution(input.within(0.0, 1.0))
                    .filter(input.filter())
                    .sensor(input.byte() < 20)
                    .hit_events(input.flag())
                    .bullet(input.byte() < 30)
                    .awake(input.byte() > 20);
                match world.add_body(def) {
                    Ok(handle) => {
                        bodies.push(handle);
                        colliders.extend(world.body(handle).map_or(&[][..], |b| b.colliders()));
                        false
                    }
                    Err(_) => true,
                }
            }
            4 => {
                let Some(body) = input.pick(&bodies) else {
                    continue;
                };
                let removed = world.remove_body(body).is_err();
                bodies.retain(|&b| b != body);
                removed
            }
            5 => {
                let Some(body) = input.pick(&bodies) else {
                    continue;
                };
                let def = ColliderDef::new(input.shape())
                    .offset(input.point(2.0))
                    .angle(input.real(3.0))
                    .density(input.real(5.0))
                    .sensor(input.byte() < 30);
                refused_or_kept(world.add_collider(body, def), &mut colliders)
            }
            6 => {
                let Some(collider) = input.pick(&colliders) else {
                    continue;
                };
                colliders.retain(|&c| c != collider);
                world.remove_collider(collider).is_err()
            }
            7 | 8 => {
                let (Some(a), Some(b)) = (input.pick(&bodies), input.pick(&bodies)) else {
                    continue;
                };
                let anchor = input.point(20.0);
                let axis = input.point(1.0);
                let def = match input.below(11) {
                    0 => JointDef::distance(a, b, anchor, input.point(20.0)),
                    1 => JointDef::revolute(a, b, anchor).limits(input.real(3.0), input.real(3.0)),
                    2 => JointDef::prismatic(a, b, anchor, axis)
                        .motor_drive(input.real(10.0), input.real(1000.0)),
                    3 => JointDef::weld(a, b, anchor).spring(input.real(30.0), input.real(2.0)),
                    4 => JointDef::wheel(a, b, anchor, axis),
                    5 => {
                        JointDef::motor(a, b, input.point(2.0), input.real(3.0), input.real(500.0))
                    }
                    6 => JointDef::mouse(a, anchor, input.real(1e4)),
                    7 => JointDef::filter(a, b),
                    8 => JointDef::mover(a, b, input.point(20.0), input.point(500.0)),
                    9 => JointDef::pogo(
                        a,
                        b,
                        anchor,
                        input.point(20.0),
                        axis,
                        input.real(3.0),
                        (input.real(1e4), input.real(1e4)),
                    ),
                    _ => JointDef::rope(a, b, anchor, input.point(20.0), input.real(10.0)),
                }
                .collide_connected(input.flag())
                .break_force(if input.flag() {
                    input.real(1e4)
                } else {
                    Real::INFINITY
                });
                // Now and then a spring, limits, a motor or a torque to break at, which kinds
                // that have none refuse.
                let def = match input.byte() {
                    0..16 => def.spring(input.real(30.0), input.real(2.0)),
                    16..32 => def.limits(input.real(3.0), input.real(3.0)),
                    32..48 => def.motor_drive(input.real(10.0), input.real(1000.0)),
                    48..56 => def.spring_force(input.real(1e3), input.real(1e3)),
                    56..64 => def.break_torque(input.real(1e4)),
                    _ => def,
                };
                refused_or_kept(world.add_joint(def), &mut joints)
            }
            9 => {
                let Some(joint) = input.pick(&joints) else {
                    continue;
                };
                joints.retain(|&j| j != joint);
                world.remove_joint(joint).is_err()
            }
            10 | 11 => {
                let Some(body) = input.pick(&bodies) else {
                    continue;
                };
                let Some(mut body) = world.body_mut(body) else {
                    tally.refused += 1;
                    continue;
                };
                match input.below(18) {
                    0 => body.set_position(input.point(50.0)).is_err(),
                    1 => body.set_angle(input.real(10.0)).is_err(),
                    2 => body.set_linear_velocity(input.point(100.0)).is_err(),
                    3 => body.set_angular_velocity(input.real(100.0)).is_err(),
                    4 => body
                        .move_kinematic_to(input.point(20.0), input.real(5.0), input.real(0.1))
                        .is_err(),
                    5 => body.set_gravity_scale(input.real(5.0)).is_err(),
                    6 => body.set_damping(input.real(5.0), input.real(5.0)).is_err(),
                    7 => body
                        .apply_force(input.point(1e4), input.point(20.0))
                        .is_err(),
                    8 => body
                        .apply_impulse(input.point(1e3), input.point(20.0))
                        .is_err(),
                    9 => body.apply_torque(input.real(1e4)).is_err(),
                    10 => body.apply_angular_impulse(input.real(1e3)).is_err(),
                    11 => {
                        let kinds = [BodyKind::Static, BodyKind::Kinematic, BodyKind::Dynamic];
                        body.set_kind(kinds[input.below(3)]).is_err()
                    }
                    12 => {
                        body.set_bullet(input.flag());
                        body.wake_up();
                        false
                    }
                    13 => body.set_sweep_threshold(input.real(2.0)).is_err(),
                    14 => {
                        body.set_fixed_rotation(input.flag());
                        false
                    }
                    15 => body.apply_force_at_center(input.point(1e4)).is_err(),
                    16 => body.apply_impulse_at_center(input.point(1e3)).is_err(),
                    _ => {
                        body.clear_forces();
                        false
                    }
                }
            }
            12 => {
                let Some(collider) = input.pick(&colliders) else {
                    continue;
                };
                let Some(mut collider) = world.collider_mut(collider) else {
                    tally.refused += 1;
                    continue;
                };
                match input.below(6) {
                    0 => collider.set_friction(input.real(2.0)).is_err(),
                    1 => collider.set_restitution(input.real(2.0)).is_err(),
                    2 => collider.set_density(input.real(10.0)).is_err(),
                    3 => collider.set_rolling_resistance(input.real(1.0)).is_err(),
                    4 => collider.set_tangent_speed(input.real(10.0)).is_err(),
                    _ => {
                        collider.set_filter(input.filter());
                        false
                    }
                }
            }
            13 => {
                let Some(joint) = input.pick(&joints) else {
                    continue;
                };
                match world.joint_mut(joint) {
                    Some(mut joint) => joint.set_mouse_target(input.point(20.0)).is_err(),
                    None => true,
                }
            }
            14 => {
                let explosion =
                    ExplosionDef::new(input.point(20.0), input.real(10.0), input.real(100.0))
                        .falloff(input.real(5.0));
                world.explode(&explosion).is_err()
            }
            15 => {
                let settings = (
                    input.point(20.0),
                    input.below(4),
                    1 + input.below(8) as u32,
                    input.byte(),
                );
                // Now and then the solver's and the broadphase's numbers too.
                let numbers = (input.byte() < 64).then(|| {
                    [
                        input.real(0.1),
                        input.real(0.2),
                        input.real(400.0),
                        input.real(1.0),
                        input.real(60.0),
                        input.real(10.0),
                        input.real(60.0),
                        input.real(5.0),
                        input.real(1.0),
                    ]
                });
                world
                    .update_settings(|s| {
                        if let Some(n) = numbers {
                            s.speculative_distance = n[0];
                            s.aabb_margin = n[1];
                            s.solver.max_linear_speed = n[2];
                            s.solver.max_rotation = n[3];
                            s.solver.contact_hertz = n[4];
                            s.solver.damping_ratio = n[5];
                            s.solver.joint_hertz = n[6];
                            s.solver.max_push_speed = n[7];
                            s.solver.restitution_threshold = n[8];
                        }
                        s.gravity = settings.0;
                        s.solver.kind = [
                            SolverKind::SoftStep,
                            SolverKind::SequentialImpulse,
                            SolverKind::TutorialImpulse,
                            SolverKind::PushOut,
                        ][settings.1];
                        s.solver.substeps = settings.2;
                        let mut effects = Effects::ALL;
                        for (bit, effect) in Effects::ALL.iter().enumerate() {
                            effects.set(effect, settings.3 & (1 << bit) == 0);
                        }
                        s.effects = effects;
                    })
                    .is_err()
            }
            16 => {
                query(&world, &mut input);
                false
            }
            17 => {
                restore_and_compare(&world);
                tally.restores += 1;
                false
            }
            18 => {
                world.wake_all();
                false
            }
            24 => {
                // A character made, moved or put somewhere.
                match character.as_mut() {
                    None => {
                        let def = CharacterDef::capsule(input.real(1.0), input.real(0.5))
                            .position(input.point(20.0) + vec2(0.0, 10.0))
                            .up(input.point(1.0))
                            .max_slope(input.real(1.0))
                            .step(input.real(0.3), input.real(0.3))
                            .snap_distance(input.real(0.3))
                            .mass(input.real(100.0))
                            .max_push_force(input.real(1e3));
                        match Character::new(def) {
                            Ok(made) => {
                                character = Some(made);
                                false
                            }
                            Err(_) => true,
                        }
                    }
                    Some(walker) if input.byte() < 16 => {
                        walker.set_position(input.point(20.0)).is_err()
                    }
                    Some(walker) => {
                        let dt = if input.byte() < 12 {
                            input.real(1.0)
                        } else {
                            1.0 / 60.0
                        };
                        let moved = world.move_character(walker, input.point(1.0), dt);
                        if let Ok(moved) = &moved {
                            assert!(
                                moved.translation.iter().all(|x| x.is_finite())
                                    && walker.position().iter().all(|x| x.is_finite()),
                                "{moved:?}"
                            );
                        }
                        moved.is_err()
                    }
                }
            }
            25 => {
                // The mover's parts on their own: planes from any numbers.
                let mut planes: Vec<CollisionPlane> = (0..input.below(5))
                    .map(|_| {
                        let normal = input.point(1.0);
                        let offset = input.real(1.0);
                        if input.flag() {
                            CollisionPlane::rigid(normal, offset)
                        } else {
                            CollisionPlane::soft(normal, offset, input.real(1.0))
                        }
                    })
                    .collect();
                let target = input.point(1.0);
                let solution = solve_planes(target, &mut planes);
                assert!(
                    !target.iter().all(|x| x.is_finite())
                        || solution.delta.iter().all(|x| x.is_finite()),
                    "{solution:?} from {planes:?}"
                );
                false
            }
            23 => {
                // Room for a few hundred of each, or more than any heap holds.
                let mut count = || match input.byte() {
                    0..8 => usize::MAX,
                    8..16 => usize::MAX / 64,
                    _ => input.below(400),
                };
                let capacity = Capacity {
                    bodies: count(),
                    colliders: count(),
                    contacts: count(),
                    joints: count(),
                };
                let reserved = world.reserve(capacity);
                assert!(
                    matches!(reserved, Ok(()) | Err(CaromError::OutOfMemory { .. })),
                    "reserve({capacity:?}) gave {reserved:?}"
                );
                reserved.is_err()
            }
            _ => {
                let dt = if input.byte() < 12 {
                    input.real(1.0)
                } else {
                    1.0 / 60.0
                };
                let valid = (1e-6..=10.0).contains(&dt);
                for _ in 0..1 + input.below(6) {
                    let stepped = world.step(dt);
                    assert_eq!(stepped.is_ok(), valid, "step({dt}) gave {stepped:?}");
                    if !valid {
                        break;
                    }
                    tally.steps += 1;
                    read_events(&world);
                }
                !valid
            }
        };
        tally.refused += usize::from(refused);
        calls.push((call, std::mem::take(&mut input.odd)));
        // Handles the world dropped along with something else (a body's joints and colliders).
        colliders.retain(|&c| world.collider(c).is_some());
        joints.retain(|&j| world.joint(j).is_some());
        let checked = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| check(&world)));
        if let Err(broken) = checked {
            eprintln!(
                "after calls (number, odd values drawn) {:?}",
                &calls[calls.len().saturating_sub(8)..]
            );
            std::panic::resume_unwind(broken);
        }
    }
    tally
}

/// True when the call that made `made` was refused; else keeps the handle it made in `into`.
fn refused_or_kept<H>(made: Result<H, carom::CaromError>, into: &mut Vec<H>) -> bool {
    match made {
        Ok(handle) => {
            into.push(handle);
            false
        }
        Err(_) => true,
    }
}

/// Every body's figures are finite, the world holds together, and the most it has held is
/// at least what it holds.
fn check(world: &World) {
    crate::assert_bodies_finite(world);
    world.check_invariants();
    let most = world.high_water();
    assert!(most.bodies >= world.body_count(), "{most:?}");
    assert!(most.joints >= world.joint_count(), "{most:?}");
    assert!(most.contacts >= world.stats().contacts, "{most:?}");
}

/// Every query, checked for finite answers.
fn query(world: &World, input: &mut Input) {
    let filter = if input.flag() {
        QueryFilter::default()
    } else {
        QueryFilter::mask(u64::from(input.byte()))
    };
    let ray = Ray::new(input.point(30.0), input.point(60.0));
    for hit in world.cast_ray_all(&ray, filter) {
        assert!(hit.fraction.is_finite() && hit.point.x.is_finite() && hit.normal.y.is_finite());
    }
    if let Some(hit) = world.cast_ray(&ray, filter) {
        assert!(hit.fraction.is_finite() && hit.normal.x.is_finite());
    }
    let shape = WorldShape::at(&input.shape(), input.point(20.0), input.real(3.0));
    let _ = world.query_shape(&shape, filter);
    let translation = input.point(30.0);
    if let Some(hit) = world.cast_shape(&shape, translation, filter) {
        assert!(
            hit.fraction.is_finite() && hit.point.x.is_finite(),
            "{hit:?} casting {shape:?} along {translation:?}"
        );
    }
    let _ = world.query_aabb(&shape.aabb(), filter);
    let mover = Capsule::new(input.point(20.0), input.point(20.0), input.real(0.5));
    for plane in world.collide_mover(&mover, filter) {
        assert!(
            plane
                .normal
                .iter()
                .chain(plane.point.iter())
                .all(|x| x.is_finite())
                && plane.depth.is_finite(),
            "{plane:?} for {mover:?}"
        );
    }
    let translation = input.point(30.0);
    let fraction = world.cast_mover(&mover, translation, filter);
    assert!(
        (0.0..=1.0).contains(&fraction),
        "{fraction} casting {mover:?} along {translation:?}"
    );
}

/// Reads every event list (they must be readable after any step).
fn read_events(world: &World) {
    let _ = (
        world.contact_events().len(),
        world.sensor_events().len(),
        world.joint_events().len(),
        world.hit_events().len(),
    );
    for contact in world.contacts() {
        assert!(contact.total_normal_impulse().is_finite());
    }
}

/// Saves the world as RON and reads it back: the copy must read, and step to the same bits.
fn restore_and_compare(world: &World) {
    let text = ron::to_string(world).expect("a world saves");
    let mut restored: World =
        ron::from_str(&text).unwrap_or_else(|e| panic!("a saved world reads back: {e}"));
    restored.check_invariants();
    let mut original = world.clone();
    assert_eq!(restored.state_hash(), original.state_hash());
    for _ in 0..3 {
        original.step(1.0 / 60.0).expect("a valid step");
        restored.step(1.0 / 60.0).expect("a valid step");
    }
    assert_eq!(
        restored.state_hash(),
        original.state_hash(),
        "a restored world stepped to other bits"
    );
}
