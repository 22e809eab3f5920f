//! A carom world rebuilt in Rapier with matched parameters; see the crate docs for the mapping.

use std::collections::HashMap;

use carom::{
    Body, BodyKind, CollisionFilter, DragModel, Effect, Joint, JointKind, Polygon, Shape, Spring,
    World,
};
use rapier2d::math::Pose;
use rapier2d::prelude::{
    ActiveHooks, CCDSolver, CoefficientCombineRule, ColliderBuilder, ColliderSet,
    DefaultBroadPhase, GenericJoint, GenericJointBuilder, Group, ImpulseJointSet,
    IntegrationParameters, InteractionGroups, InteractionTestMode, IslandManager, JointAxesMask,
    JointAxis, MultibodyJointSet, NarrowPhase, PairFilterContext, PhysicsHooks, PhysicsPipeline,
    RigidBodyBuilder, RigidBodyHandle, RigidBodySet, RigidBodyType, SoftBodySet, SolverFlags,
    SpringCoefficients, Vector,
};

use crate::notes::Notes;

/// How far a polygon's edge may lean off an axis, in metres, and still count as a rectangle's.
const AXIS_TOLERANCE: f32 = 1e-6;

/// A Rapier world holding one rigid body per carom body, in carom's order, and one collider per
/// carom collider, placed on its body as carom places it.
pub struct RapierWorld {
    gravity: Vector,
    params: IntegrationParameters,
    pipeline: PhysicsPipeline,
    islands: IslandManager,
    broad_phase: DefaultBroadPhase,
    narrow_phase: NarrowPhase,
    bodies: RigidBodySet,
    colliders: ColliderSet,
    impulse_joints: ImpulseJointSet,
    multibody_joints: MultibodyJointSet,
    soft_bodies: SoftBodySet,
    ccd: CCDSolver,
    handles: Vec<RigidBodyHandle>,
    /// carom's collision filters, for the pairs Rapier's groups cannot decide.
    filters: GroupFilter,
    /// Which of the carom world's effects the copy follows.
    effects: Followed,
    /// Joint softness (Rapier's own).
    softness: SpringCoefficients<f32>,
    /// The copies of a scene's spawn events made so far and not yet removed, by their index
    /// in the schedule.
    spawned: HashMap<usize, Vec<RigidBodyHandle>>,
    /// What the copy leaves out or approximates.
    notes: Notes,
}

/// The carom effects a copy follows, and whether every category in the world fits Rapier's
/// 32 bits.
#[derive(Debug, Clone, Copy)]
struct Followed {
    drag: bool,
    can_sleep: bool,
    ccd: bool,
    friction: bool,
    restitution: bool,
    narrow_categories: bool,
}

/// carom's (and Box2D's) collision rule for the colliders Rapier's interaction groups cannot
/// express: those in a collision group (which overrides categories and masks) and, in a world
/// with categories beyond Rapier's 32 bits, every collider not at the default filter. Such a
/// collider's Rapier groups let everything through and this hook decides, from each collider's
/// carom filter (its `user_data` is its index here).
#[derive(Debug, Default)]
struct GroupFilter {
    filters: Vec<CollisionFilter>,
}

impl PhysicsHooks for GroupFilter {
    fn filter_contact_pair(&self, context: &PairFilterContext) -> Option<SolverFlags> {
        let filter = |handle: rapier2d::prelude::ColliderHandle| {
            let index = context.colliders[handle].user_data as usize;
            self.filters[index]
        };
        filter(context.collider1)
            .collides_with(&filter(context.collider2))
            .then_some(SolverFlags::COMPUTE_RIGID_IMPULSES)
    }
}

/// Rapier's groups for a carom filter, if they decide exactly as carom would: no collision
/// group, and every category in the world within 32 bits (a mask's higher bits then meet no
/// category, so cutting them changes nothing).
fn interaction_groups(
    filter: CollisionFilter,
    narrow_categories: bool,
) -> Option<InteractionGroups> {
    (filter.group == 0 && narrow_categories).then(|| {
        InteractionGroups::new(
            Group::from_bits_truncate(filter.category as u32),
            Group::from_bits_truncate(filter.mask as u32),
            InteractionTestMode::And,
        )
    })
}

/// A spring of `spring.hertz` and `spring.damping_ratio` as a Rapier motor's stiffness and
/// damping in its acceleration-based model (its default): `ω²` and `2ζω`. With them Rapier's
/// motor row has Box2D's soft-constraint bias rate, mass scale and impulse scale, the same
/// spring as carom's.
fn spring_gains(spring: Spring) -> (f32, f32) {
    let omega = std::f32::consts::TAU * spring.hertz;
    (omega * omega, 2.0 * spring.damping_ratio * omega)
}

/// The damping of a Rapier velocity motor standing for carom's rigid one (a motor that
/// reaches its speed unless held by its force cap): its softness `1 / (h c)` is then below
/// 1e-4 at any substep above a microsecond.
const RIGID_MOTOR_DAMPING: f32 = 1.0e10;

impl RapierWorld {
    /// Rebuilds `world` in Rapier, to be stepped by `dt` seconds at a time.
    ///
    /// # Errors
    /// A polygon Rapier cannot build a convex shape from, or a non-positive `dt`.
    pub fn from_carom(world: &World, dt: f32) -> Result<RapierWorld, String> {
        if !(dt.is_finite() && dt > 0.0) {
            return Err(format!("time step must be positive and finite, got {dt}"));
        }
        let effects = world.effects();
        let settings = world.settings();
        let solver = world.solver();
        // Carom zeroes gravity itself when the effect is off (`gravity()` is the setting, so
        // apply the effect here).
        let g = if effects.contains(Effect::Gravity) {
            world.gravity()
        } else {
            carom::Vec2::zeros()
        };

        let mut params = IntegrationParameters {
            dt,
            ..IntegrationParameters::default()
        };
        // Rapier's "solver iterations" are its substeps (each with its own integration); its
        // PGS iterations per substep are soft step's iterations. The classic solvers have no
        // substeps: they run one Rapier substep of `iterations` PGS sweeps.
        if solver.effective_kind().has_substeps() {
            params.num_solver_iterations = solver.substeps.max(1) as usize;
            params.num_internal_pgs_iterations = solver.effective_iterations() as usize;
        } else {
            params.num_solver_iterations = 1;
            params.num_internal_pgs_iterations = solver.effective_iterations() as usize;
        }
        if !solver.warm_starting {
            params.warmstart_coefficient = 0.0;
        }
        // Friction stays in Rapier's relaxation only (its default) whatever carom does: with
        // friction in its biased pass too, Rapier's 5050-box pyramid collapses (the top box
        // falls 34 m in 500 steps), so matching carom there would not be Rapier at its best.
        // Same meaning, same (Box2D) defaults in both engines; `length_unit` stays 1 m.
        params.normalized_prediction_distance = settings.speculative_distance;
        params.normalized_allowed_linear_error = carom::LINEAR_SLOP;
        params.normalized_max_corrective_velocity = solver.max_push_speed;
        params.normalized_max_linear_velocity = solver.max_linear_speed;
        // Contact softness is left at Rapier's defaults: 30 Hz, damping ratio 10, and twice
        // the frequency against fixed bodies, which are carom's soft-step defaults too.

        let narrow_categories = world.bodies().all(|body| {
            body.colliders()
                .iter()
                .filter_map(|&c| world.collider(c))
                .all(|c| c.filter().category <= u64::from(u32::MAX))
        });
        // Joints keep Rapier's own softness (1 MHz, ζ 1: nearly rigid), not soft step's 60 Hz
        // and 2. Rapier softens a joint in every pass, Box2D and carom only in the biased one,
        // so the same 60 Hz makes Rapier's joints far softer: Box2D's 100 x 100 joint grid
        // opens its widest joint to 0.82 m in a second at 60 Hz, 0.67 m at Rapier's default,
        // where carom's and Box2D's open to 0.36 m.
        let softness = SpringCoefficients::<f32>::joint_defaults();
        let mut out = RapierWorld {
            gravity: Vector::new(g.x, g.y),
            params,
            pipeline: PhysicsPipeline::new(),
            islands: IslandManager::new(),
            broad_phase: DefaultBroadPhase::new(),
            narrow_phase: NarrowPhase::new(),
            bodies: RigidBodySet::new(),
            colliders: ColliderSet::new(),
            impulse_joints: ImpulseJointSet::new(),
            multibody_joints: MultibodyJointSet::new(),
            soft_bodies: SoftBodySet::new(),
            ccd: CCDSolver::new(),
            handles: Vec::with_capacity(world.body_count()),
            filters: GroupFilter::default(),
            effects: Followed {
                drag: effects.contains(Effect::Drag) && settings.drag == DragModel::Exponential,
                can_sleep: effects.contains(Effect::Sleeping),
                ccd: effects.contains(Effect::Continuous),
                friction: effects.contains(Effect::Friction),
                restitution: effects.contains(Effect::Restitution),
                narrow_categories,
            },
            softness,
            spawned: HashMap::new(),
            notes: Notes::default(),
        };
        let mut index = HashMap::with_capacity(world.body_count());
        for body in world.bodies() {
            let handle = out.add_body(world, body)?;
            index.insert(body.handle(), handle);
            out.handles.push(handle);
        }
        for joint in world.joints() {
            let [a, b] = joint.bodies().map(|h| index.get(&h).copied());
            let (Some(a), Some(b)) = (a, b) else {
                return Err(format!(
                    "a {} joint's body is not in the copy",
                    joint.kind().name()
                ));
            };
            out.add_joint(joint, [a, b]);
        }
        Ok(out)
    }

    /// Rebuilds one body of `world` in Rapier with a collider per carom collider, placed on it
    /// as carom places it, and returns its handle.
    fn add_body(&mut self, world: &World, body: &Body) -> Result<RigidBodyHandle, String> {
        let Followed {
            drag,
            can_sleep,
            ccd,
            friction,
            restitution,
            narrow_categories,
        } = self.effects;
        let handle = self.bodies.insert(rigid_body(body, drag, can_sleep, ccd));
        if can_sleep && body.sleep_threshold() != carom::SLEEP_THRESHOLD {
            // Rapier's threshold is on the same speed: the fastest point's.
            self.bodies[handle]
                .activation_mut()
                .normalized_linear_threshold = body.sleep_threshold();
        }
        for part in body.colliders().iter().filter_map(|&c| world.collider(c)) {
            if matches!(part.shape(), Shape::ChainSegment(_)) {
                self.notes.add(
                    "a chain link: a plain segment in Rapier (two-sided, without the ghost \
                     vertices that smooth a chain's joins)",
                );
            }
            let place = part.local_transform();
            let collider = collider(part.shape())?
                .position(Pose::new(
                    Vector::new(place.translation.x, place.translation.y),
                    place.rotation.angle(),
                ))
                .density(part.density())
                .friction(if friction { part.friction() } else { 0.0 })
                .friction_combine_rule(CoefficientCombineRule::GeometricMean)
                .restitution(if restitution { part.restitution() } else { 0.0 })
                .restitution_combine_rule(CoefficientCombineRule::Max);
            let filter = part.filter();
            let narrow = narrow_categories && filter.category <= u64::from(u32::MAX);
            let collider = match interaction_groups(filter, narrow) {
                Some(groups) => collider.collision_groups(groups),
                None => collider
                    .collision_groups(InteractionGroups::all())
                    .active_hooks(ActiveHooks::FILTER_CONTACT_PAIRS),
            }
            .user_data(self.filters.filters.len() as u128);
            self.filters.filters.push(filter);
            self.colliders
                .insert_with_parent(collider, handle, &mut self.bodies);
        }
        Ok(handle)
    }

    /// Rebuilds one joint between Rapier's bodies `a` and `b`, unless Rapier cannot express it
    /// (noted).
    fn add_joint(&mut self, joint: &Joint, [a, b]: [RigidBodyHandle; 2]) {
        if let Some((data, motor)) = generic_joint(joint, self.softness, &mut self.notes) {
            self.impulse_joints.insert(a, b, data, true);
            if let Some(motor) = motor {
                self.impulse_joints.insert(a, b, motor, true);
            }
        }
    }

    /// Makes copy `copy` of a scene's spawn events: `made`'s bodies of `world` (the
    /// schedule's), then their joints, kept apart from the bodies copied at the start (the
    /// indices of [`RapierWorld::positions`] and the rest do not count them).
    ///
    /// # Errors
    /// A shape Rapier cannot build, or a joint whose bodies are not in the copy.
    pub fn add_spawned(
        &mut self,
        copy: usize,
        world: &World,
        made: &carom_scene::Made,
    ) -> Result<(), String> {
        let mut bodies = Vec::with_capacity(made.bodies.len());
        for &handle in &made.bodies {
            let body = world
                .body(handle)
                .ok_or("a spawned body is not in its world")?;
            bodies.push(self.add_body(world, body)?);
        }
        let find = |h: carom::BodyHandle| {
            made.bodies
                .iter()
                .position(|&b| b == h)
                .map(|i| bodies[i])
                .ok_or("a spawned joint's body is not in its copy")
        };
        for &handle in &made.joints {
            let joint = world
                .joint(handle)
                .ok_or("a spawned joint is not in its world")?;
            let [a, b] = joint.bodies().map(find);
            self.add_joint(joint, [a?, b?]);
        }
        self.spawned.insert(copy, bodies);
        Ok(())
    }

    /// Removes copy `copy` of a scene's spawn events: its bodies, with their colliders and
    /// joints, waking what touched them.
    ///
    /// # Errors
    /// A copy not made.
    pub fn remove_spawned(&mut self, copy: usize) -> Result<(), String> {
        let bodies = self
            .spawned
            .remove(&copy)
            .ok_or_else(|| format!("spawned copy {copy} is not in the world"))?;
        for body in bodies {
            self.bodies.remove(
                body,
                &mut self.islands,
                &mut self.colliders,
                &mut self.impulse_joints,
                &mut self.multibody_joints,
                &mut self.soft_bodies,
                true,
            );
        }
        Ok(())
    }

    /// Positions of the spawned bodies there are now.
    pub fn spawned_positions(&self) -> Vec<[f32; 2]> {
        self.spawned
            .values()
            .flatten()
            .map(|&h| {
                let t = self.bodies[h].translation();
                [t.x, t.y]
            })
            .collect()
    }

    /// What this copy leaves out of the carom world or approximates (empty if nothing).
    pub fn notes(&self) -> &Notes {
        &self.notes
    }

    /// Number of joints Rapier holds.
    pub fn joint_count(&self) -> usize {
        self.impulse_joints.len()
    }

    /// Number of contact pairs with at least one point within the prediction distance (what
    /// Rapier solves). A pair the filters reject has none, though the narrowphase may still
    /// list it.
    pub fn contact_count(&self) -> usize {
        self.narrow_phase
            .contact_pairs()
            .filter(|pair| pair.has_any_active_contact())
            .count()
    }

    /// Angle of the `index`-th body, rad.
    pub fn angle(&self, index: usize) -> Option<f32> {
        let body = &self.bodies[*self.handles.get(index)?];
        Some(body.rotation().angle())
    }

    /// Linear and angular velocity of the `index`-th body.
    pub fn velocity(&self, index: usize) -> Option<([f32; 2], f32)> {
        let body = &self.bodies[*self.handles.get(index)?];
        let v = body.linvel();
        Some(([v.x, v.y], body.angvel()))
    }

    /// Sets Rapier's stabilization iterations per substep (its
    /// `num_internal_stabilization_iterations`, 1 by default), which carom has no setting for.
    pub fn set_stabilization_iterations(&mut self, iterations: usize) {
        self.params.num_internal_stabilization_iterations = iterations.max(1);
    }

    /// Advances the world by one time step.
    pub fn step(&mut self) {
        self.pipeline.step(
            self.gravity,
            &self.params,
            &mut self.islands,
            &mut self.broad_phase,
            &mut self.narrow_phase,
            &mut self.bodies,
            &mut self.colliders,
            &mut self.impulse_joints,
            &mut self.multibody_joints,
            &mut self.soft_bodies,
            &mut self.ccd,
            &self.filters,
            &(),
        );
    }

    /// Number of rigid bodies (static ones included).
    pub fn body_count(&self) -> usize {
        self.bodies.len()
    }

    /// Position of every body, in the order of the carom world's `bodies()`.
    pub fn positions(&self) -> Vec<[f32; 2]> {
        self.handles
            .iter()
            .map(|h| {
                let t = self.bodies[*h].translation();
                [t.x, t.y]
            })
            .collect()
    }

    /// Whether each body is dynamic, in the order of [`RapierWorld::positions`].
    pub fn dynamic_flags(&self) -> Vec<bool> {
        self.handles
            .iter()
            .map(|h| self.bodies[*h].is_dynamic())
            .collect()
    }

    /// Total mass of the dynamic bodies, kg.
    pub fn dynamic_mass(&self) -> f32 {
        self.handles
            .iter()
            .map(|h| &self.bodies[*h])
            .filter(|b| b.is_dynamic())
            .map(|b| b.mass())
            .sum()
    }

    /// The Rapier bodies, for inspection.
    pub fn bodies(&self) -> &RigidBodySet {
        &self.bodies
    }

    /// The Rapier colliders, for inspection.
    pub fn colliders(&self) -> &ColliderSet {
        &self.colliders
    }

    /// Rapier's handle of the `index`-th carom body (in `bodies()` order).
    pub fn handle(&self, index: usize) -> Option<RigidBodyHandle> {
        self.handles.get(index).copied()
    }

    /// The integration parameters every step uses.
    pub fn integration_parameters(&self) -> &IntegrationParameters {
        &self.params
    }
}

/// The rigid body matching a carom body (its collider comes separately).
fn rigid_body(body: &Body, drag: bool, can_sleep: bool, ccd: bool) -> RigidBodyBuilder {
    let kind = match body.kind() {
        BodyKind::Static => RigidBodyType::Fixed,
        BodyKind::Kinematic => RigidBodyType::KinematicVelocityBased,
        BodyKind::Dynamic => RigidBodyType::Dynamic,
    };
    let p = body.position();
    let mut rb = RigidBodyBuilder::new(kind)
        .translation(Vector::new(p.x, p.y))
        .rotation(body.angle())
        .gravity_scale(body.gravity_scale())
        .can_sleep(can_sleep)
        .sleeping(body.is_sleeping())
        .ccd_enabled(ccd && body.is_bullet());
    if body.kind() != BodyKind::Static {
        let v = body.linear_velocity();
        rb = rb
            .linvel(Vector::new(v.x, v.y))
            .angvel(body.angular_velocity());
    }
    if drag {
        rb = rb
            .linear_damping(body.linear_damping())
            .angular_damping(body.angular_damping());
    }
    rb
}

/// The collider matching a carom shape, in the collider's own frame (carom recentres a shape
/// on its centroid; the caller places the collider on its body at the carom collider's offset
/// and angle).
///
/// A chain link becomes a plain segment: Rapier's segments are two-sided and have no ghost
/// vertices (its polylines smooth their joins, but only within one polyline).
fn collider(shape: &Shape) -> Result<ColliderBuilder, String> {
    let point = |v: carom::Vec2| Vector::new(v.x, v.y);
    match shape {
        Shape::Circle(c) => Ok(ColliderBuilder::ball(c.radius())),
        Shape::Capsule(c) => Ok(ColliderBuilder::capsule_from_endpoints(
            point(c.center1()),
            point(c.center2()),
            c.radius(),
        )),
        Shape::Segment(s) => Ok(ColliderBuilder::segment(
            point(s.point1()),
            point(s.point2()),
        )),
        Shape::ChainSegment(s) => Ok(ColliderBuilder::segment(
            point(s.point1()),
            point(s.point2()),
        )),
        Shape::Polygon(p) => {
            let rounding = p.radius();
            if let Some((hx, hy)) = axis_aligned_rectangle(p) {
                return Ok(if rounding > 0.0 {
                    ColliderBuilder::round_cuboid(hx, hy, rounding)
                } else {
                    ColliderBuilder::cuboid(hx, hy)
                });
            }
            let points: Vec<Vector> = p.vertices().iter().map(|&v| point(v)).collect();
            if rounding > 0.0 {
                return ColliderBuilder::round_convex_polyline(points, rounding)
                    .ok_or_else(|| format!("Rapier rejected the polygon {:?}", p.vertices()));
            }
            // Carom polygons are convex and counter-clockwise already, as `convex_polyline`
            // wants; the hull is only a fallback for near-degenerate outlines it rejects.
            ColliderBuilder::convex_polyline(points.clone())
                .or_else(|| ColliderBuilder::convex_hull(&points))
                .ok_or_else(|| format!("Rapier rejected the polygon {:?}", p.vertices()))
        }
    }
}

/// Half-extents if the polygon is a rectangle centred on the origin with axis-aligned edges.
fn axis_aligned_rectangle(p: &Polygon) -> Option<(f32, f32)> {
    let v = p.vertices();
    if v.len() != 4 {
        return None;
    }
    let scale = p.circumradius().max(1.0);
    let tol = AXIS_TOLERANCE * scale;
    for i in 0..4 {
        let e = v[(i + 1) % 4] - v[i];
        if e.x.abs() > tol && e.y.abs() > tol {
            return None;
        }
    }
    let hx = v.iter().map(|q| q.x.abs()).fold(0.0, f32::max);
    let hy = v.iter().map(|q| q.y.abs()).fold(0.0, f32::max);
    // Every corner must be at (±hx, ±hy): the centroid is the origin, so a rectangle is.
    if v.iter()
        .all(|q| (q.x.abs() - hx).abs() <= tol && (q.y.abs() - hy).abs() <= tol)
        && hx > 0.0
        && hy > 0.0
    {
        Some((hx, hy))
    } else {
        None
    }
}

/// A carom joint as a Rapier generic joint: one frame in each body, the anchors carom's, body
/// A's frame turned to a slider's or wheel's axis (Rapier's free axis is that frame's x) and
/// body B's by the reference angle less, so the joint's angle is 0 where carom's is. A hinge
/// or slider with both a spring and a motor comes with a second joint on the same frames,
/// every axis free, whose velocity motor is the motor (Rapier has one motor per axis, and
/// the first joint's holds the spring): joint friction on a sprung ragdoll's hinges. `None`
/// for a joint Rapier cannot express, with a note saying so; approximations are noted too.
fn generic_joint(
    joint: &Joint,
    softness: SpringCoefficients<f32>,
    notes: &mut Notes,
) -> Option<(GenericJoint, Option<GenericJoint>)> {
    let kind = joint.kind();
    let (break_force, break_torque) = joint.break_thresholds();
    if break_force.is_finite() || break_torque.is_finite() {
        notes.add("a joint's break force or torque: not translated (Rapier's joints do not break)");
    }
    let axis_angle = match kind {
        JointKind::Prismatic(j) => j.axis.y.atan2(j.axis.x),
        JointKind::Wheel(j) => j.axis.y.atan2(j.axis.x),
        _ => 0.0,
    };
    let [la, lb] = joint.local_anchors();
    let builder = |locked: JointAxesMask| {
        GenericJointBuilder::new(locked)
            .local_frame1(Pose::new(Vector::new(la.x, la.y), axis_angle))
            .local_frame2(Pose::new(
                Vector::new(lb.x, lb.y),
                axis_angle - joint.reference_angle(),
            ))
            .contacts_enabled(joint.collide_connected())
            .softness(softness)
    };
    // A spring on a free axis: Rapier's position motor, mass-independent (see `spring_gains`).
    let spring_on = |b: GenericJointBuilder, axis: JointAxis, target: f32, spring: Spring| {
        let (stiffness, damping) = spring_gains(spring);
        b.motor_position(axis, target, stiffness, damping)
    };
    // carom's motor: the speed, reached rigidly within the force cap.
    let drive = |b: GenericJointBuilder, axis: JointAxis, motor: carom::Motor| {
        b.motor_velocity(axis, motor.speed, RIGID_MOTOR_DAMPING)
            .motor_max_force(axis, motor.max_force.min(f32::MAX))
    };
    // The motor of a joint whose own motor holds its spring, on a joint of its own.
    let mut second = None;
    let built = match *kind {
        JointKind::Distance(d) => {
            // The distance between the anchors is Rapier's coupled linear axis (as in its rope
            // and spring joints).
            let mut b = builder(JointAxesMask::empty()).coupled_axes(JointAxesMask::LIN_AXES);
            match d.spring {
                None => {
                    // Rapier's coupled axis takes only an upper limit (its source: "FIXME:
                    // handle min limit too"): the rod is rigid against stretching and held at
                    // its length against shortening by a spring as stiff as Rapier's joints.
                    notes.add(
                        "a rigid distance joint: rigid only against stretching in Rapier (its \
                         distance limit has no lower side), held against shortening by a spring \
                         as stiff as its joints",
                    );
                    let hold = Spring::new(softness.natural_frequency, softness.damping_ratio);
                    b = spring_on(b, JointAxis::LinX, d.length, hold)
                        .limits(JointAxis::LinX, [0.0, d.length]);
                }
                Some(spring) => {
                    if spring.hertz > 0.0 {
                        b = spring_on(b, JointAxis::LinX, d.length, spring);
                    }
                    if let Some(limits) = d.limits {
                        if limits.lower > 0.0 {
                            notes.add(
                                "a distance joint's lower limit: not translated (Rapier's \
                                 distance limit has no lower side)",
                            );
                        }
                        b = b.limits(JointAxis::LinX, [0.0, limits.upper]);
                    }
                }
            }
            b
        }
        JointKind::Revolute(r) => {
            let mut b = builder(JointAxesMask::LOCKED_REVOLUTE_AXES);
            if let Some(limits) = r.limits {
                b = b.limits(JointAxis::AngX, [limits.lower, limits.upper]);
            }
            match (r.spring.filter(|s| s.hertz > 0.0), r.motor) {
                (Some(spring), Some(motor)) => {
                    b = spring_on(b, JointAxis::AngX, r.target_angle, spring);
                    let free = builder(JointAxesMask::empty());
                    second = Some(drive(free, JointAxis::AngX, motor).build());
                }
                (Some(spring), None) => b = spring_on(b, JointAxis::AngX, r.target_angle, spring),
                (None, Some(motor)) => b = drive(b, JointAxis::AngX, motor),
                (None, None) => {}
            }
            b
        }
        JointKind::Prismatic(p) => {
            let mut b = builder(JointAxesMask::LOCKED_PRISMATIC_AXES);
            if let Some(limits) = p.limits {
                b = b.limits(JointAxis::LinX, [limits.lower, limits.upper]);
            }
            match (p.spring.filter(|s| s.hertz > 0.0), p.motor) {
                (Some(spring), Some(motor)) => {
                    b = spring_on(b, JointAxis::LinX, p.target_translation, spring);
                    let free = builder(JointAxesMask::empty());
                    second = Some(drive(free, JointAxis::LinX, motor).build());
                }
                (Some(spring), None) => {
                    b = spring_on(b, JointAxis::LinX, p.target_translation, spring)
                }
                (None, Some(motor)) => b = drive(b, JointAxis::LinX, motor),
                (None, None) => {}
            }
            b
        }
        JointKind::Weld(w) => {
            // A sprung part of the weld is freed and pulled home by a position motor: per axis
            // of A's frame for the point, where carom and Box2D solve it as one 2x2 block.
            let (linear, angular) = (
                w.linear.filter(|s| s.hertz > 0.0),
                w.angular.filter(|s| s.hertz > 0.0),
            );
            let mut locked = JointAxesMask::LOCKED_FIXED_AXES;
            if linear.is_some() {
                locked.remove(JointAxesMask::LIN_AXES);
            }
            if angular.is_some() {
                locked.remove(JointAxesMask::ANG_X);
            }
            let mut b = builder(locked);
            if let Some(spring) = linear {
                b = spring_on(b, JointAxis::LinX, 0.0, spring);
                b = spring_on(b, JointAxis::LinY, 0.0, spring);
            }
            if let Some(spring) = angular {
                b = spring_on(b, JointAxis::AngX, 0.0, spring);
            }
            b
        }
        JointKind::Wheel(w) => {
            // Rapier's pin-slot: B's anchor on A's axis, free to slide along it and to turn.
            let mut b = builder(JointAxesMask::LOCKED_PIN_SLOT_AXES);
            if let Some(spring) = w.spring.filter(|s| s.hertz > 0.0) {
                b = spring_on(b, JointAxis::LinX, 0.0, spring);
            }
            if let Some(limits) = w.limits {
                b = b.limits(JointAxis::LinX, [limits.lower, limits.upper]);
            }
            if let Some(motor) = w.motor {
                b = drive(b, JointAxis::AngX, motor);
            }
            b
        }
        // No axis locked: the joint only keeps the bodies from colliding (and in one island).
        JointKind::Filter => builder(JointAxesMask::empty()),
        JointKind::Motor(_) | JointKind::Mover(_) | JointKind::Pogo(_) => {
            notes.add(
                "a motor, mover or pogo joint: not translated (Rapier has no joint that drives \
                 a body's velocity or pose within a force cap without a fixed axis)",
            );
            return None;
        }
        JointKind::Mouse(_) => {
            notes.add("a mouse joint: not translated (Rapier has no mouse joint)");
            return None;
        }
    };
    Some((built.build(), second))
}
