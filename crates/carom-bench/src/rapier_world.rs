//! A carom world rebuilt in Rapier with matched parameters; see the crate docs for the mapping.

use carom::{Body, BodyKind, DragModel, Effect, Polygon, Shape, World};
use rapier2d::math::Pose;
use rapier2d::prelude::{
    CCDSolver, CoefficientCombineRule, ColliderBuilder, ColliderSet, DefaultBroadPhase,
    ImpulseJointSet, IntegrationParameters, IslandManager, MultibodyJointSet, NarrowPhase,
    PhysicsPipeline, RigidBodyBuilder, RigidBodyHandle, RigidBodySet, RigidBodyType, SoftBodySet,
    Vector,
};

/// How far a polygon's edge may lean off an axis, in metres, and still count as a rectangle's.
const AXIS_TOLERANCE: f32 = 1e-6;

/// A Rapier world holding one rigid body and one collider per carom body, in carom's order.
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
}

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
            params.num_internal_pgs_iterations = solver.iterations.max(1) as usize;
        } else {
            params.num_solver_iterations = 1;
            params.num_internal_pgs_iterations = solver.iterations.max(1) as usize;
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
        };
        let drag = effects.contains(Effect::Drag) && settings.drag == DragModel::Exponential;
        let can_sleep = effects.contains(Effect::Sleeping);
        let ccd = effects.contains(Effect::Continuous);
        let friction = effects.contains(Effect::Friction);
        let restitution = effects.contains(Effect::Restitution);
        for body in world.bodies() {
            let rb = rigid_body(body, drag, can_sleep, ccd);
            let handle = out.bodies.insert(rb);
            for part in body.colliders().iter().filter_map(|&c| world.collider(c)) {
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
                out.colliders
                    .insert_with_parent(collider, handle, &mut out.bodies);
            }
            out.handles.push(handle);
        }
        Ok(out)
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
            &(),
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

/// The collider matching a carom shape, in body space (carom recentres shapes on the centroid,
/// which is the body's origin, so the collider sits at the body's origin too).
fn collider(shape: &Shape) -> Result<ColliderBuilder, String> {
    match shape {
        Shape::Circle(c) => Ok(ColliderBuilder::ball(c.radius())),
        Shape::Polygon(p) => {
            if let Some((hx, hy)) = axis_aligned_rectangle(p) {
                return Ok(ColliderBuilder::cuboid(hx, hy));
            }
            let points: Vec<Vector> = p.vertices().iter().map(|v| Vector::new(v.x, v.y)).collect();
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
    let scale = p.radius().max(1.0);
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
