//! A carom world rebuilt in Box2D v3 (the `boxdd` 0.6 bindings, Box2D 3.2.0 at commit
//! `56edae79`, compiled with AVX2) with matched parameters.
//!
//! Bodies keep the order of carom's `World::bodies()`, so index `i` is the same body in both
//! engines; [`Box2dWorld::index_of`] maps a carom [`BodyHandle`] to it.
//!
//! ## Parameter mapping, carom → Box2D
//!
//! | carom | Box2D | exact? |
//! |---|---|---|
//! | `BodyKind::Static` / `Kinematic` / `Dynamic` | `b2_staticBody` / `b2_kinematicBody` / `b2_dynamicBody` | yes |
//! | position (the body's origin), angle | body `position`, `rotation` | yes: both place a body by its origin and find the centre of mass from its shapes |
//! | each collider: shape, offset and angle, density, friction, restitution | one shape per collider, its vertices (or centre) moved into the body's frame | yes |
//! | linear and angular velocity | `linearVelocity`, `angularVelocity` | yes (not set on static bodies) |
//! | `gravity_scale` | `gravityScale` | yes |
//! | gravity (zero when the `Gravity` effect is off) | world `gravity` | yes |
//! | linear / angular drag (the `Drag` effect with [`carom::DragModel::Exponential`]) | `linearDamping` / `angularDamping` | yes: the same law, `v /= 1 + h c`; with `Drag` off, or the tutorial drag model, no damping is set |
//! | `Shape::Circle` | `b2Circle` at the body origin | yes |
//! | `Shape::Polygon` (convex, CCW, centred on its centroid, sharp or rounded) | `b2Polygon` with carom's own vertices and normals, centroid 0, carom's radius | yes, vertex for vertex: no hull is recomputed, as Box2D's would weld points closer than 4 slop (2 cm) and drop the 2 mm cards of the card house; at most 8 vertices (Box2D's limit) |
//! | `Shape::Capsule` / `Shape::Segment` | `b2Capsule` / `b2Segment`, moved into the body's frame | yes |
//! | `Shape::ChainSegment` (a chain's link) | `b2ChainSegment` with the link's ghost vertices | yes: one-sided and smooth across joins in both |
//! | density | shape `density` (mass and inertia from the shape) | yes |
//! | friction, mixed by geometric mean (`Friction` effect; 0 when off) | shape material `friction`, Box2D's default mixing `sqrt(a b)` | yes |
//! | restitution, mixed by max (`Restitution` effect; 0 when off) | shape material `restitution`, Box2D's default mixing `max(a, b)` | yes |
//! | `restitution_threshold` (1 m/s) | world `restitutionThreshold` (1 m/s) | yes |
//! | `Sleeping` effect | world `enableSleep` | switch yes, thresholds the same: both 0.05 m/s for 0.5 s, islands sleep whole |
//! | a body's `sleep_threshold` (default 0.05 m/s) | body `sleepThreshold` | yes |
//! | `Continuous` effect | world `enableContinuous` (dynamic against static) | yes |
//! | a body asleep when the copy is made (one added with `awake: false`) | body `isAwake` false (a sleeping set of its own, as Box2D makes one) | yes |
//! | `is_bullet` (with the `Continuous` effect) | body `isBullet` (dynamic against dynamic too) | yes; a bullet with `Continuous` off is not a bullet in either |
//! | soft step's `substeps` (default 4) | `subStepCount` of `b2World_Step` (4 in Box2D's samples) | yes |
//! | `contact_hertz` (30), `damping_ratio` (10) | world `contactHertz`, `contactDampingRatio` (30, 10) | yes at the defaults; Box2D caps the stiffness at an eighth of the substep rate (30 Hz at 4 substeps of 1/60 s), carom at a quarter (60 Hz), so carom's stiffer settings are capped in Box2D |
//! | `max_push_speed` (3 m/s) | world `contactSpeed` (Box2D 3.1's `maxContactPushSpeed`, 3 m/s) | yes |
//! | `max_linear_speed` (400 m/s) | world `maximumLinearSpeed` (400 m/s) | yes |
//! | `warm_starting` | `b2World_EnableWarmStarting` | yes |
//! | a collider's filter: `category`, `mask`, `group` | shape `filter`: `categoryBits`, `maskBits`, `groupIndex` | yes: both 64-bit, the same rule (one group: collide if positive, never if negative; else both masks) |
//! | a joint's bodies, anchors in each body, reference angle, axis (in A's frame) | `localFrameA` at A's anchor turned to the axis (a slider's or wheel's axis is the frame's x), `localFrameB` at B's anchor turned by the axis angle less the reference angle | yes: the joint's angle and translation are 0 where carom's are |
//! | `collide_connected` | `collideConnected` | yes |
//! | soft step's `joint_hertz` (60), `joint_damping_ratio` (2) | each joint's `constraintHertz`, `constraintDampingRatio` (60, 2) | yes; both cap it at a quarter of the substep rate |
//! | distance joint: rigid rod / spring (`hertz`, `damping_ratio`) with `limits` / rope (0 Hz, limits), `spring_force`, `motor` | `length`, `enableSpring`, `hertz`, `dampingRatio`, `enableLimit`, `minLength`, `maxLength`, `lowerSpringForce`, `upperSpringForce`, `enableMotor`, `motorSpeed`, `maxMotorForce` | yes (Box2D raises a lower limit below the slop, 5 mm, to it) |
//! | revolute joint: limits, motor (speed, torque), spring toward `target_angle` | `enableLimit`, `lowerAngle`, `upperAngle`, `enableMotor`, `motorSpeed`, `maxMotorTorque`, `enableSpring`, `hertz`, `dampingRatio`, `targetAngle` | yes; limits beyond Box2D's ±0.99π are narrowed to it (noted) |
//! | prismatic joint: axis, limits, motor, spring toward `target_translation` | the frame's x axis, the same settings, `targetTranslation` | yes |
//! | wheel joint: axis, suspension spring, limits, motor | the frame's x axis, `enableSpring`, ..., `maxMotorTorque` | yes |
//! | weld joint: linear and angular springs (none: rigid) | `linearHertz`, `angularHertz` and damping ratios (0 Hz: rigid) | yes |
//! | filter joint | `b2FilterJointDef` | yes |
//! | motor joint: velocity part and spring part, each with its cap; `linear_offset`, `angular_offset` | `linearVelocity`, `maxVelocityForce`, `angularVelocity`, `maxVelocityTorque`, `linearHertz`, ..., `maxSpringTorque`; the offsets move `localFrameA` | yes |
//! | an unbounded motor force | `f32::MAX` | yes |
//!
//! ## What does not map
//!
//! - The solver: Box2D has only its soft step. A carom world set to another solver is still
//!   run with Box2D's soft step (and its substeps), so compare soft step with soft step.
//! - Soft step's `iterations`: Box2D runs one solve and one relax pass per substep, which is
//!   carom's default (1); more carom iterations have no Box2D counterpart.
//! - `static_stiffness`: Box2D's contacts against static bodies are always twice as stiff,
//!   carom's default (2); another factor is not followed.
//! - `friction_in_bias_pass` (carom's default on, as Box2D v3.1): this Box2D (3.2) solves
//!   friction in the relax pass only, whatever carom does.
//! - `graph_coloring`: Box2D always solves in graph colours, as carom's default does.
//! - `direct_joints` and `shock_propagation` (carom's options, off by default): Box2D has
//!   neither and runs its plain soft step.
//! - `LINEAR_SLOP` (0.005 m) and `speculative_distance` (0.02 m) are compile-time constants in
//!   Box2D with the same values; a carom world that changes them is not followed.
//! - `max_rotation`: both turn a body at most π/4 per step (47 rad/s at 60 Hz); Box2D's is a
//!   constant, so a carom world that changes it is not followed. Box2D's per-body
//!   `allowFastRotation` is left off, as Box2D's default.
//! - carom's `aabb_margin` (0.05 m for every moving collider) against Box2D's per-shape
//!   margin, `min(0.05 m, 0.125 × the shape's largest extent from its centre)`
//!   (`b2ComputeShapeMargin`); static shapes take the 0.02 m speculative distance in both:
//!   only the broadphase's work differs.
//! - `look_ahead` (carom's default on): Box2D's contacts never look ahead, and keep points
//!   within the speculative distance only, which is what carom does with it off
//!   (`carom-bench --no-look-ahead`); on, carom makes more contacts than Box2D in a fast crowd.
//! - `contact_recycling`: Box2D recycles contacts too (on per body by default); the switch is
//!   left at Box2D's default.
//! - Box2D's extras are left off or at their defaults: rolling resistance 0, tangent speed 0,
//!   contact softening (mass-ratio softening) off; one worker thread unless
//!   [`Box2dWorld::with_workers`] asks for more (Box2D's built-in scheduler).
//! - The tutorial drag model has no Box2D counterpart (no damping is set).
//! - Mouse joints: Box2D 3.2 has none. Mover and pogo joints: the Box2D that boxdd 0.6
//!   bundles has neither (Box2D's repository does). They are left out, noted.
//! - Break thresholds: Box2D reports a joint past its force or torque threshold and leaves
//!   breaking it to the program; they are left out, noted. [`Box2dWorld::notes`] lists
//!   everything left out, and `carom-bench` prints it under its table.
//! - Scene events: a scene's spawn events are replayed. `carom-bench` writes out their schedule
//!   before timing ([`carom_scene::SceneWorld::spawn_schedule`]) and, inside the timed steps
//!   as Box2D's benchmark does in its step function, makes and removes the same bodies and
//!   joints before the same steps ([`Box2dWorld::add_spawned`],
//!   [`Box2dWorld::remove_spawned`]). Its other events (launches, respawns, spins) are not
//!   replayed, and `carom-bench` notes them.

use std::collections::HashMap;

use boxdd::{
    BodyBuilder, BodyId, BodyType, ConstraintTuning, DistanceJointDef, Filter, FilterJointDef,
    Foundation, JointBase, JointId, MotorJointDef, Position, PrismaticJointDef, RevoluteJointDef,
    ShapeDef, SurfaceMaterial, Transform, Vec2, WeldJointDef, WheelJointDef, WorldBuilder, shapes,
};
use boxdd_sys::ffi;
use carom::{
    Body, BodyHandle, BodyKind, Collider, DragModel, Effect, Joint, JointKind, Polygon, Shape,
    Spring, World,
};

use crate::notes::Notes;

/// Box2D's limit on polygon vertices.
const MAX_POLYGON_VERTICES: usize = 8;

/// A collider's shape in its body's frame, kept to measure the body's bounding box exactly
/// (Box2D's own body box is grown by the speculative distance, 2 cm, and carom's is not).
#[derive(Debug, Clone)]
enum LocalShape {
    Circle([f32; 2], f32),
    /// A core's vertices (a polygon's, a capsule's two centres, a segment's ends) and radius.
    Polygon(Vec<[f32; 2]>, f32),
}

/// A Box2D world holding one body per carom body, in carom's order, and one shape per collider.
pub struct Box2dWorld {
    world: boxdd::World,
    foundation: &'static Foundation,
    substeps: i32,
    ids: Vec<BodyId>,
    index: HashMap<BodyHandle, usize>,
    kinds: Vec<BodyKind>,
    shapes: Vec<Vec<LocalShape>>,
    /// Box2D's mass and rotational inertia (about the centre of mass) of each body.
    mass: Vec<(f32, f32)>,
    /// Which of the carom world's effects the copy follows.
    effects: Followed,
    /// Soft step's joint stiffness, every joint's own in Box2D 3.2.
    tuning: ConstraintTuning,
    /// The copies of a scene's spawn events made so far and not yet removed, by their index
    /// in the schedule: their bodies and joints.
    spawned: HashMap<usize, (Vec<BodyId>, Vec<JointId>)>,
    /// What the copy leaves out or approximates.
    notes: Notes,
}

/// The carom effects a copy's bodies and shapes follow (each off makes its setting 0 or
/// leaves it out).
#[derive(Debug, Clone, Copy)]
struct Followed {
    drag: bool,
    friction: bool,
    restitution: bool,
    bullets: bool,
}

impl std::fmt::Debug for Box2dWorld {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Box2dWorld")
            .field("bodies", &self.ids.len())
            .field("substeps", &self.substeps)
            .finish_non_exhaustive()
    }
}

fn err(e: boxdd::Error) -> String {
    e.to_string()
}

impl Box2dWorld {
    /// Rebuilds `world` in Box2D, stepped on one worker; see the module docs for the mapping.
    ///
    /// # Errors
    /// A polygon Box2D cannot take (more than 8 vertices, or one its validation refuses), or a
    /// setting out of Box2D's range.
    pub fn from_carom(world: &World) -> Result<Box2dWorld, String> {
        Self::with_workers(world, 1)
    }

    /// [`Box2dWorld::from_carom`], stepped on `workers` threads by Box2D's own scheduler.
    ///
    /// # Errors
    /// As [`Box2dWorld::from_carom`], or a worker count outside Box2D's 1 to 32.
    pub fn with_workers(world: &World, workers: u32) -> Result<Box2dWorld, String> {
        let foundation = Foundation::initialize_default().map_err(|e| e.to_string())?;
        let effects = world.effects();
        let settings = world.settings();
        let solver = world.solver();
        // carom keeps the gravity setting while the effect is off; Box2D has no switch.
        let g = if effects.contains(Effect::Gravity) {
            world.gravity()
        } else {
            carom::Vec2::zeros()
        };
        let def = WorldBuilder::from(foundation.world_def())
            .gravity(Vec2::new(g.x, g.y))
            .restitution_threshold(solver.restitution_threshold)
            .contact_hertz(solver.contact_hertz)
            .contact_damping_ratio(solver.damping_ratio)
            .contact_speed(solver.max_push_speed)
            .maximum_linear_speed(solver.max_linear_speed)
            .enable_sleep(effects.contains(Effect::Sleeping))
            .enable_continuous(effects.contains(Effect::Continuous))
            .worker_count(boxdd::WorkerCount::new(workers).map_err(err)?)
            .build()
            .map_err(err)?;
        let mut b2 = foundation.create_world(def).map_err(err)?;
        b2.enable_warm_starting(solver.warm_starting).map_err(err)?;

        let effects = Followed {
            drag: effects.contains(Effect::Drag) && settings.drag == DragModel::Exponential,
            friction: effects.contains(Effect::Friction),
            restitution: effects.contains(Effect::Restitution),
            bullets: effects.contains(Effect::Continuous),
        };
        // Soft step's joint stiffness is each Box2D 3.2 joint's own (`constraintHertz`,
        // `constraintDampingRatio`; Box2D's 60 Hz and 2 are carom's defaults).
        let tuning =
            ConstraintTuning::new(solver.joint_hertz, solver.joint_damping_ratio).map_err(err)?;
        let mut out = Box2dWorld {
            world: b2,
            foundation,
            substeps: i32::try_from(solver.substeps.max(1)).map_err(|e| e.to_string())?,
            ids: Vec::with_capacity(world.body_count()),
            index: HashMap::with_capacity(world.body_count()),
            kinds: Vec::with_capacity(world.body_count()),
            shapes: Vec::with_capacity(world.body_count()),
            mass: Vec::with_capacity(world.body_count()),
            effects,
            tuning,
            spawned: HashMap::new(),
            notes: Notes::default(),
        };
        for body in world.bodies() {
            let mut locals = Vec::with_capacity(body.colliders().len());
            let id = out.add_body(world, body, Some(&mut locals))?;
            let handle = out.world.body(id).map_err(err)?;
            let mass = (
                handle.mass().map_err(err)?,
                handle.rotational_inertia().map_err(err)?,
            );
            out.index.insert(body.handle(), out.ids.len());
            out.ids.push(id);
            out.kinds.push(body.kind());
            out.shapes.push(locals);
            out.mass.push(mass);
        }
        for joint in world.joints() {
            let [a, b] = joint.bodies().map(|h| {
                out.body_id(h).ok_or(format!(
                    "a {} joint's body is not in the copy",
                    joint.kind().name()
                ))
            });
            out.add_joint(joint, [a?, b?])?;
        }
        Ok(out)
    }

    /// Rebuilds one body of `world` in Box2D with a shape per collider, and returns its id;
    /// each shape's outline in the body's frame goes to `locals` if it is given.
    fn add_body(
        &mut self,
        world: &World,
        body: &Body,
        mut locals: Option<&mut Vec<LocalShape>>,
    ) -> Result<BodyId, String> {
        let Followed {
            drag,
            friction,
            restitution,
            bullets,
        } = self.effects;
        let def = body_def(self.foundation, body, drag, bullets).map_err(err)?;
        let id = self.world.create_body(def).map_err(err)?;
        let mut handle = self.world.body(id).map_err(err)?;
        for collider in body.colliders().iter().filter_map(|&c| world.collider(c)) {
            let material = SurfaceMaterial::new()
                .with_friction(if friction { collider.friction() } else { 0.0 })
                .and_then(|m| {
                    m.with_restitution(if restitution {
                        collider.restitution()
                    } else {
                        0.0
                    })
                })
                .map_err(err)?;
            let filter = collider.filter();
            let shape_def = ShapeDef::builder()
                .density(collider.density())
                .material(material)
                .filter(Filter {
                    category_bits: filter.category,
                    mask_bits: filter.mask,
                    group_index: filter.group,
                })
                .build()
                .map_err(err)?;
            let place = collider.local_transform();
            let local = match collider.shape() {
                Shape::Circle(c) => {
                    let o = place.translation.vector;
                    let circle = shapes::circle(Vec2::new(o.x, o.y), c.radius()).map_err(err)?;
                    handle.create_circle(&shape_def, &circle).map_err(err)?;
                    locals
                        .is_some()
                        .then(|| LocalShape::Circle([o.x, o.y], c.radius()))
                }
                Shape::Polygon(p) => {
                    handle
                        .create_polygon(&shape_def, &polygon(p, collider)?)
                        .map_err(err)?;
                    locals.is_some().then(|| {
                        let placed = p
                            .vertices()
                            .iter()
                            .map(|v| place.rotation * v + place.translation.vector);
                        LocalShape::Polygon(placed.map(|v| [v.x, v.y]).collect(), p.radius())
                    })
                }
                Shape::Capsule(c) => {
                    let [c1, c2] = [c.center1(), c.center2()].map(|v| point_in_body(&place, v));
                    let capsule = shapes::capsule(c1, c2, c.radius()).map_err(err)?;
                    handle.create_capsule(&shape_def, &capsule).map_err(err)?;
                    locals
                        .is_some()
                        .then(|| LocalShape::Polygon(vec![[c1.x, c1.y], [c2.x, c2.y]], c.radius()))
                }
                Shape::Segment(s) => {
                    let [p1, p2] = [s.point1(), s.point2()].map(|v| point_in_body(&place, v));
                    let segment = shapes::segment(p1, p2).map_err(err)?;
                    handle.create_segment(&shape_def, &segment).map_err(err)?;
                    locals
                        .is_some()
                        .then(|| LocalShape::Polygon(vec![[p1.x, p1.y], [p2.x, p2.y]], 0.0))
                }
                Shape::ChainSegment(s) => {
                    let [g1, p1, p2, g2] = [s.ghost1(), s.point1(), s.point2(), s.ghost2()]
                        .map(|v| point_in_body(&place, v));
                    let link = shapes::chain_segment(g1, p1, p2, g2).map_err(err)?;
                    handle
                        .create_chain_segment(&shape_def, &link)
                        .map_err(err)?;
                    locals
                        .is_some()
                        .then(|| LocalShape::Polygon(vec![[p1.x, p1.y], [p2.x, p2.y]], 0.0))
                }
            };
            if let (Some(locals), Some(local)) = (locals.as_deref_mut(), local) {
                locals.push(local);
            }
        }
        Ok(id)
    }

    /// Makes copy `copy` of a scene's spawn events: `made`'s bodies of `world` (the
    /// schedule's), then their joints, kept apart from the bodies copied at the start (the
    /// indices of [`Box2dWorld::position`] and the rest do not count them).
    ///
    /// # Errors
    /// A body or joint Box2D refuses, or a joint whose bodies are not in the copy.
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
            bodies.push(self.add_body(world, body, None)?);
        }
        let find = |h: BodyHandle| {
            made.bodies
                .iter()
                .position(|&b| b == h)
                .map(|i| bodies[i])
                .ok_or("a spawned joint's body is not in its copy")
        };
        let mut joints = Vec::with_capacity(made.joints.len());
        for &handle in &made.joints {
            let joint = world
                .joint(handle)
                .ok_or("a spawned joint is not in its world")?;
            let [a, b] = joint.bodies().map(find);
            if let Some(id) = self.add_joint(joint, [a?, b?])? {
                joints.push(id);
            }
        }
        self.spawned.insert(copy, (bodies, joints));
        Ok(())
    }

    /// Removes copy `copy` of a scene's spawn events as Box2D's benchmark removes a group of
    /// ragdolls: its joints without waking their bodies, then its bodies (which wakes what
    /// touches them).
    ///
    /// # Errors
    /// A copy not made, or one Box2D no longer holds.
    pub fn remove_spawned(&mut self, copy: usize) -> Result<(), String> {
        let (bodies, joints) = self
            .spawned
            .remove(&copy)
            .ok_or_else(|| format!("spawned copy {copy} is not in the world"))?;
        for joint in joints {
            self.world
                .joint(joint)
                .map_err(err)?
                .destroy(false)
                .map_err(err)?;
        }
        for body in bodies {
            self.world.body(body).map_err(err)?.destroy().map_err(err)?;
        }
        Ok(())
    }

    /// Positions (centres of mass) of the spawned bodies there are now.
    ///
    /// # Errors
    /// A body Box2D no longer holds.
    pub fn spawned_positions(&mut self) -> Result<Vec<[f32; 2]>, String> {
        let ids: Vec<BodyId> = self
            .spawned
            .values()
            .flat_map(|(b, _)| b)
            .copied()
            .collect();
        ids.into_iter()
            .map(|id| {
                let p = self.world.body(id).map_err(err)?.position().map_err(err)?;
                Ok([p.x, p.y])
            })
            .collect()
    }

    /// What this copy leaves out of the carom world or approximates (empty if nothing).
    pub fn notes(&self) -> &Notes {
        &self.notes
    }

    /// Number of joints Box2D holds.
    ///
    /// # Errors
    /// A world Box2D no longer holds.
    pub fn joint_count(&self) -> Result<usize, String> {
        let counters = self.world.counters().map_err(err)?;
        usize::try_from(counters.joint_count).map_err(|e| e.to_string())
    }

    /// Number of contacts Box2D holds: pairs whose fattened boxes overlap and that its filters
    /// let collide, touching or not.
    ///
    /// # Errors
    /// A world Box2D no longer holds.
    pub fn contact_count(&self) -> Result<usize, String> {
        let counters = self.world.counters().map_err(err)?;
        usize::try_from(counters.contact_count).map_err(|e| e.to_string())
    }

    /// Rebuilds one carom joint in Box2D 3.2, whose joints hold a frame in each body (an
    /// anchor and a rotation): the anchors are carom's, body A's frame is turned to the axis
    /// of a slider or a wheel (Box2D's axis is that frame's x), and body B's frame by the
    /// reference angle less, so the joint's angle is 0 where carom's is. Joints Box2D cannot
    /// express are noted and left out (`None`). `bodies` are Box2D's bodies for the joint's
    /// two.
    fn add_joint(&mut self, joint: &Joint, [a, b]: [BodyId; 2]) -> Result<Option<JointId>, String> {
        let tuning = self.tuning;
        let kind = joint.kind();
        let name = kind.name();
        let skip = match kind {
            JointKind::Mouse(_) => Some(
                "a mouse joint: not translated (Box2D 3.2 has no mouse joint; its samples drag \
                 bodies with a motor joint's spring instead)",
            ),
            JointKind::Mover(_) | JointKind::Pogo(_) => Some(
                "a mover or pogo joint: not translated (the Box2D that boxdd 0.6 bundles has \
                 neither)",
            ),
            _ => None,
        };
        if let Some(what) = skip {
            self.notes.add(what);
            return Ok(None);
        }
        let (break_force, break_torque) = joint.break_thresholds();
        if break_force.is_finite() || break_torque.is_finite() {
            self.notes.add(
                "a joint's break force or torque: not translated (Box2D reports a joint past \
                 its threshold and leaves breaking it to the program)",
            );
        }
        let axis_angle = match kind {
            JointKind::Prismatic(j) => j.axis.y.atan2(j.axis.x),
            JointKind::Wheel(j) => j.axis.y.atan2(j.axis.x),
            _ => 0.0,
        };
        let [mut la, lb] = joint.local_anchors();
        // Box2D's motor joint pulls frame B onto frame A: carom's offsets move frame A.
        let mut angle_a = axis_angle;
        if let JointKind::Motor(m) = kind {
            la += m.linear_offset;
            angle_a += m.angular_offset;
        }
        let frame_a = Transform::from_pos_angle(Vec2::new(la.x, la.y), angle_a).map_err(err)?;
        let frame_b =
            Transform::from_pos_angle(Vec2::new(lb.x, lb.y), axis_angle - joint.reference_angle())
                .map_err(err)?;
        let base: JointBase = self
            .world
            .joint_base(a, b)
            .map_err(err)?
            .with_local_frames(frame_a, frame_b)
            .with_collide_connected(joint.collide_connected())
            .with_constraint_tuning(tuning);
        // carom allows an unbounded motor; Box2D wants a finite one.
        let finite = |force: f32| force.min(f32::MAX);
        let created = match *kind {
            JointKind::Distance(d) => {
                let mut def = DistanceJointDef::new(base).length(d.length);
                // Without a spring carom holds the rod rigidly and ignores limits, as Box2D does.
                if let Some(spring) = d.spring {
                    def = def
                        .enable_spring(true)
                        .hertz(spring.hertz)
                        .damping_ratio(spring.damping_ratio);
                    if let Some(force) = d.spring_force {
                        def = def
                            .lower_spring_force(force.lower.max(-f32::MAX))
                            .upper_spring_force(finite(force.upper));
                    }
                    if let Some(motor) = d.motor {
                        def = def
                            .enable_motor(true)
                            .motor_speed(motor.speed)
                            .max_motor_force(finite(motor.max_force));
                    }
                    if let Some(limits) = d.limits {
                        def = def
                            .enable_limit(true)
                            .min_length(limits.lower)
                            .max_length(limits.upper);
                    }
                }
                self.world.create_distance_joint(&def)
            }
            JointKind::Revolute(r) => {
                let mut def = RevoluteJointDef::new(base);
                if let Some(limits) = r.limits {
                    // Box2D's hinge limits stay within ±0.99π.
                    let most = 0.99 * std::f32::consts::PI;
                    if limits.lower < -most || limits.upper > most {
                        self.notes.add(
                            "a revolute joint's limits beyond ±0.99π: narrowed to Box2D's range",
                        );
                    }
                    def = def
                        .enable_limit(true)
                        .lower_angle(limits.lower.clamp(-most, most))
                        .upper_angle(limits.upper.clamp(-most, most));
                }
                if let Some(motor) = r.motor {
                    def = def
                        .enable_motor(true)
                        .motor_speed(motor.speed)
                        .max_motor_torque(finite(motor.max_force));
                }
                if let Some(spring) = r.spring {
                    def = def
                        .enable_spring(true)
                        .hertz(spring.hertz)
                        .damping_ratio(spring.damping_ratio)
                        .target_angle(r.target_angle);
                }
                self.world.create_revolute_joint(&def)
            }
            JointKind::Prismatic(p) => {
                let mut def = PrismaticJointDef::new(base);
                if let Some(limits) = p.limits {
                    def = def
                        .enable_limit(true)
                        .lower_translation(limits.lower)
                        .upper_translation(limits.upper);
                }
                if let Some(motor) = p.motor {
                    def = def
                        .enable_motor(true)
                        .motor_speed(motor.speed)
                        .max_motor_force(finite(motor.max_force));
                }
                if let Some(spring) = p.spring {
                    def = def
                        .enable_spring(true)
                        .hertz(spring.hertz)
                        .damping_ratio(spring.damping_ratio)
                        .translation(p.target_translation);
                }
                self.world.create_prismatic_joint(&def)
            }
            JointKind::Weld(w) => {
                // Box2D's 0 Hz is rigid, as carom's weld without a spring (or with one of 0 Hz).
                let rigid = Spring::new(0.0, 0.0);
                let (linear, angular) = (w.linear.unwrap_or(rigid), w.angular.unwrap_or(rigid));
                let def = WeldJointDef::new(base)
                    .linear_hertz(linear.hertz)
                    .linear_damping_ratio(linear.damping_ratio)
                    .angular_hertz(angular.hertz)
                    .angular_damping_ratio(angular.damping_ratio);
                self.world.create_weld_joint(&def)
            }
            JointKind::Wheel(w) => {
                let mut def = WheelJointDef::new(base).enable_spring(w.spring.is_some());
                if let Some(spring) = w.spring {
                    def = def.hertz(spring.hertz).damping_ratio(spring.damping_ratio);
                }
                if let Some(limits) = w.limits {
                    def = def
                        .enable_limit(true)
                        .lower_translation(limits.lower)
                        .upper_translation(limits.upper);
                }
                if let Some(motor) = w.motor {
                    def = def
                        .enable_motor(true)
                        .motor_speed(motor.speed)
                        .max_motor_torque(finite(motor.max_force));
                }
                self.world.create_wheel_joint(&def)
            }
            JointKind::Motor(m) => {
                let def = MotorJointDef::new(base)
                    .linear_velocity(Vec2::new(m.linear_velocity.x, m.linear_velocity.y))
                    .max_velocity_force(finite(m.max_velocity_force))
                    .angular_velocity(m.angular_velocity)
                    .max_velocity_torque(finite(m.max_velocity_torque))
                    .linear_hertz(m.linear_spring.hertz)
                    .linear_damping_ratio(m.linear_spring.damping_ratio)
                    .max_spring_force(finite(m.max_spring_force))
                    .angular_hertz(m.angular_spring.hertz)
                    .angular_damping_ratio(m.angular_spring.damping_ratio)
                    .max_spring_torque(finite(m.max_spring_torque));
                self.world.create_motor_joint(&def)
            }
            JointKind::Filter => self.world.create_filter_joint(&FilterJointDef::new(base)),
            JointKind::Mouse(_) | JointKind::Mover(_) | JointKind::Pogo(_) => {
                unreachable!("noted and skipped above")
            }
        };
        created
            .map(Some)
            .map_err(|e| format!("Box2D refused a {name} joint: {e}"))
    }

    /// Advances the world by `dt` seconds in the carom world's soft-step substeps.
    ///
    /// # Errors
    /// A time step Box2D refuses, or a failure it reports after stepping.
    pub fn step(&mut self, dt: f32) -> Result<(), String> {
        let done = self.world.step(dt, self.substeps).map_err(err)?;
        match done.post_step_error() {
            Some(e) => Err(e.to_string()),
            None => Ok(()),
        }
    }

    /// Substeps per step (the carom world's soft-step substeps).
    pub fn substeps(&self) -> i32 {
        self.substeps
    }

    /// Number of bodies (static ones included).
    pub fn body_count(&self) -> usize {
        self.ids.len()
    }

    /// Number of bodies Box2D itself counts.
    ///
    /// # Errors
    /// A world Box2D no longer holds.
    pub fn native_body_count(&self) -> Result<usize, String> {
        let counters = self.world.counters().map_err(err)?;
        usize::try_from(counters.body_count).map_err(|e| e.to_string())
    }

    /// Index (carom's dense order) of the body built from the carom body `handle`.
    pub fn index_of(&self, handle: BodyHandle) -> Option<usize> {
        self.index.get(&handle).copied()
    }

    /// Box2D's id of the body built from the carom body `handle`.
    pub fn body_id(&self, handle: BodyHandle) -> Option<BodyId> {
        self.index_of(handle).map(|i| self.ids[i])
    }

    /// The carom kind of the `i`-th body.
    pub fn kind(&self, i: usize) -> BodyKind {
        self.kinds[i]
    }

    /// Box2D's mass of the `i`-th body, kg (0 for static and kinematic bodies).
    pub fn mass(&self, i: usize) -> f32 {
        self.mass[i].0
    }

    /// Box2D's rotational inertia of the `i`-th body about its centre of mass, kg m².
    pub fn rotational_inertia(&self, i: usize) -> f32 {
        self.mass[i].1
    }

    /// Friction of the `i`-th body's shape, as Box2D holds it.
    ///
    /// # Errors
    /// A body or shape Box2D no longer holds.
    pub fn friction(&mut self, i: usize) -> Result<f32, String> {
        let shape = self.shape_id(i)?;
        let shape = self.world.shape(shape).map_err(err)?;
        shape.friction().map_err(err)
    }

    /// The `i`-th body, as Box2D holds it.
    fn body(&mut self, i: usize) -> Result<boxdd::Body<'_>, String> {
        self.world.body(self.ids[i]).map_err(err)
    }

    fn shape_id(&mut self, i: usize) -> Result<boxdd::ShapeId, String> {
        let body = self.body(i)?;
        body.shapes()
            .map_err(err)?
            .first()
            .copied()
            .ok_or_else(|| format!("body {i} has no shape"))
    }

    /// Position (centre of mass) of the `i`-th body.
    ///
    /// # Errors
    /// A body Box2D no longer holds.
    pub fn position(&mut self, i: usize) -> Result<[f32; 2], String> {
        let p = self.body(i)?.position().map_err(err)?;
        Ok([p.x, p.y])
    }

    /// Angle of the `i`-th body, rad.
    ///
    /// # Errors
    /// A body Box2D no longer holds.
    pub fn angle(&mut self, i: usize) -> Result<f32, String> {
        let r = self.body(i)?.rotation().map_err(err)?;
        Ok(r.angle())
    }

    /// Linear velocity of the `i`-th body (zero while it sleeps).
    ///
    /// # Errors
    /// A body Box2D no longer holds.
    pub fn linear_velocity(&mut self, i: usize) -> Result<[f32; 2], String> {
        let v = self.body(i)?.linear_velocity().map_err(err)?;
        Ok([v.x, v.y])
    }

    /// Angular velocity of the `i`-th body, rad/s (zero while it sleeps).
    ///
    /// # Errors
    /// A body Box2D no longer holds.
    pub fn angular_velocity(&mut self, i: usize) -> Result<f32, String> {
        self.body(i)?.angular_velocity().map_err(err)
    }

    /// Box2D's explosion (`b2World_Explode`) at `center`, every category, as carom's
    /// [`carom::World::explode`] takes it.
    ///
    /// # Errors
    /// Box2D refuses the explosion.
    pub fn explode(&mut self, explosion: &carom::ExplosionDef) -> Result<(), String> {
        let def = boxdd::ExplosionDef::new()
            .position([explosion.center.x, explosion.center.y])
            .radius(explosion.radius)
            .falloff(explosion.falloff)
            .impulse_per_length(explosion.impulse_per_length)
            .mask_bits(explosion.mask);
        self.world.explode(&def).map_err(err)
    }

    /// Whether the `i`-th body is awake.
    ///
    /// # Errors
    /// A body Box2D no longer holds.
    pub fn is_awake(&mut self, i: usize) -> Result<bool, String> {
        self.body(i)?.is_awake().map_err(err)
    }

    /// The `i`-th body's tight bounding box `(min, max)`, from its shape at its current pose:
    /// the measure carom's `Body::aabb` gives (Box2D's own is grown by 2 cm).
    ///
    /// # Errors
    /// A body Box2D no longer holds.
    pub fn aabb(&mut self, i: usize) -> Result<([f32; 2], [f32; 2]), String> {
        let body = self.body(i)?;
        let p = body.position().map_err(err)?;
        let r = body.rotation().map_err(err)?;
        let (c, s) = (r.cosine(), r.sine());
        let place = |v: &[f32; 2]| [p.x + c * v[0] - s * v[1], p.y + s * v[0] + c * v[1]];
        let mut lo = [f32::INFINITY; 2];
        let mut hi = [f32::NEG_INFINITY; 2];
        let mut cover = |point: [f32; 2], radius: f32| {
            for k in 0..2 {
                lo[k] = lo[k].min(point[k] - radius);
                hi[k] = hi[k].max(point[k] + radius);
            }
        };
        for shape in &self.shapes[i] {
            match shape {
                LocalShape::Circle(center, radius) => cover(place(center), *radius),
                LocalShape::Polygon(vertices, radius) => {
                    for v in vertices {
                        cover(place(v), *radius);
                    }
                }
            }
        }
        Ok((lo, hi))
    }

    /// Moves the `i`-th body to `position` at `angle` (for relaunches).
    ///
    /// # Errors
    /// A non-finite pose, or a body Box2D no longer holds.
    pub fn set_pose(&mut self, i: usize, position: [f32; 2], angle: f32) -> Result<(), String> {
        self.body(i)?
            .set_position_and_rotation(Position::new(position[0], position[1]), angle)
            .map_err(err)
    }

    /// Sets the `i`-th body's linear and angular velocity (for relaunches).
    ///
    /// # Errors
    /// A non-finite velocity, or a body Box2D no longer holds.
    pub fn set_velocity(&mut self, i: usize, linear: [f32; 2], angular: f32) -> Result<(), String> {
        let mut body = self.body(i)?;
        body.set_linear_velocity(Vec2::new(linear[0], linear[1]))
            .map_err(err)?;
        body.set_angular_velocity(angular).map_err(err)
    }

    /// Kinetic energy of the awake dynamic bodies, J: what carom's `StepStats::kinetic_energy`
    /// sums.
    ///
    /// # Errors
    /// A body Box2D no longer holds.
    pub fn kinetic_energy(&mut self) -> Result<f64, String> {
        let mut energy = 0.0;
        for i in 0..self.ids.len() {
            if self.kinds[i] != BodyKind::Dynamic {
                continue;
            }
            let v = self.linear_velocity(i)?;
            let w = self.angular_velocity(i)?;
            let (m, inertia) = self.mass[i];
            energy += 0.5 * f64::from(m) * f64::from(v[0] * v[0] + v[1] * v[1])
                + 0.5 * f64::from(inertia) * f64::from(w * w);
        }
        Ok(energy)
    }

    /// The deepest overlap among the touching contacts of awake bodies, m (0 if none), from the
    /// manifolds the last step built: what carom's `StepStats::max_penetration` reports.
    ///
    /// # Errors
    /// A body Box2D no longer holds, or one whose contacts boxdd refuses to hand back
    /// ([`Box2dWorld::max_penetration_read`] reads past them).
    pub fn max_penetration(&mut self) -> Result<f32, String> {
        match self.max_penetration_read()? {
            (deepest, 0) => Ok(deepest),
            (_, refused) => Err(format!(
                "boxdd refused the contacts of {refused} awake bodies (a manifold it found \
                 malformed)"
            )),
        }
    }

    /// The deepest overlap among the contacts boxdd hands back, and how many awake
    /// bodies' contacts it refused to (it checks each manifold, and turns down a body's
    /// contacts when one has a normal it finds not unit): with any refused, the figure is only
    /// a lower bound.
    ///
    /// # Errors
    /// A body Box2D no longer holds.
    pub fn max_penetration_read(&mut self) -> Result<(f32, usize), String> {
        let (mut deepest, mut refused): (f32, usize) = (0.0, 0);
        // The bodies copied at the start that are dynamic, and every spawned one (a static
        // body is never awake, so it is passed over below).
        let copied = self.ids.iter().zip(&self.kinds);
        let dynamic = copied.filter(|(_, kind)| **kind == BodyKind::Dynamic);
        let spawned = self.spawned.values().flat_map(|(bodies, _)| bodies);
        let ids: Vec<BodyId> = dynamic.map(|(id, _)| *id).chain(spawned.copied()).collect();
        for id in ids {
            let body = self.world.body(id).map_err(err)?;
            if !body.is_awake().map_err(err)? {
                continue;
            }
            let Ok(contacts) = body.contact_data() else {
                refused += 1;
                continue;
            };
            for contact in contacts {
                for point in contact.manifold.points() {
                    deepest = deepest.max(-point.separation);
                }
            }
        }
        Ok((deepest, refused))
    }

    /// The Box2D world, for inspection.
    pub fn native(&mut self) -> &mut boxdd::World {
        &mut self.world
    }
}

/// The Box2D body definition matching a carom body (its shape comes separately).
fn body_def(
    foundation: &Foundation,
    body: &Body,
    drag: bool,
    bullets: bool,
) -> boxdd::Result<boxdd::BodyDef> {
    let kind = match body.kind() {
        BodyKind::Static => BodyType::Static,
        BodyKind::Kinematic => BodyType::Kinematic,
        BodyKind::Dynamic => BodyType::Dynamic,
    };
    let p = body.position();
    let mut def = BodyBuilder::from(foundation.body_def())
        .body_type(kind)
        .position(Position::new(p.x, p.y))
        .angle(body.angle())
        .gravity_scale(body.gravity_scale())
        .bullet(bullets && body.is_bullet())
        .sleep_threshold(body.sleep_threshold())
        .awake(!body.is_sleeping());
    if body.kind() != BodyKind::Static {
        let v = body.linear_velocity();
        def = def
            .linear_velocity(Vec2::new(v.x, v.y))
            .angular_velocity(body.angular_velocity());
    }
    if drag {
        def = def
            .linear_damping(body.linear_damping())
            .angular_damping(body.angular_damping());
    }
    def.build()
}

/// A point of a collider's frame in its body's frame, as Box2D's vector.
fn point_in_body(place: &carom::Isometry, v: carom::Vec2) -> Vec2 {
    let q = place.rotation * v + place.translation.vector;
    Vec2::new(q.x, q.y)
}

/// Box2D's polygon with carom's own vertices (counter-clockwise, centred on the centroid),
/// edge normals and rounding, placed in the body's frame as `collider` places it.
fn polygon(p: &Polygon, collider: &Collider) -> Result<shapes::Polygon, String> {
    let place = collider.local_transform();
    let v = p.vertices();
    if v.len() > MAX_POLYGON_VERTICES {
        return Err(format!(
            "Box2D takes at most {MAX_POLYGON_VERTICES} polygon vertices, carom's has {}",
            v.len()
        ));
    }
    let zero = ffi::b2Vec2 { x: 0.0, y: 0.0 };
    let mut raw = ffi::b2Polygon {
        vertices: [zero; MAX_POLYGON_VERTICES],
        normals: [zero; MAX_POLYGON_VERTICES],
        centroid: zero,
        radius: p.radius(),
        count: v.len() as i32,
    };
    for (i, (q, n)) in v.iter().zip(p.normals()).enumerate() {
        let (q, n) = (
            place.rotation * q + place.translation.vector,
            place.rotation * n,
        );
        raw.vertices[i] = ffi::b2Vec2 { x: q.x, y: q.y };
        raw.normals[i] = ffi::b2Vec2 { x: n.x, y: n.y };
    }
    let c = place.translation.vector;
    raw.centroid = ffi::b2Vec2 { x: c.x, y: c.y };
    shapes::Polygon::from_raw(raw).map_err(|e| format!("{e}: carom polygon {v:?}"))
}

impl Box2dWorld {
    /// Box2D's own profile of the last step (ms per stage).
    ///
    /// # Errors
    /// A world Box2D no longer holds.
    pub fn profile(&self) -> Result<boxdd::Profile, String> {
        self.world.profile().map_err(err)
    }

    /// Box2D's counters after the last step (contacts, awake and recycled contacts, graph
    /// colours).
    ///
    /// # Errors
    /// A world Box2D no longer holds.
    pub fn counters(&self) -> Result<boxdd::Counters, String> {
        self.world.counters().map_err(err)
    }
}
