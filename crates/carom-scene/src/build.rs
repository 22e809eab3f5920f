//! Turning a scene into a world: bodies, generators, settings and effects, each checked.

use crate::error::SceneError;
use crate::events::Events;
use crate::one_way;
use crate::player::Player;
use crate::scene::{
    Accuracy, BodySpec, Camera, Cells, Generator, JointKindSpec, JointSpec, Material, Pair,
    RevoluteSpec, Scene, ShapeSpec,
};
use crate::spawn::SpawnSchedule;
use carom::draw::{Color, DebugDraw, DrawFlags, DrawOptions};
use carom::{
    BodyDef, BodyHandle, BodyKind, CaromError, ChainDef, ColliderDef, DistanceJoint, JointDef,
    JointKind, Limits, MotorJoint, MouseJoint, MoverJoint, PogoJoint, PrismaticJoint, Real,
    RevoluteJoint, Shape, Surface, Vec2, WeldJoint, WheelJoint, World, vec2,
};
use serde::{Deserialize, Serialize};
use std::collections::HashMap;
use std::rc::Rc;

/// A scene built into a world, with what the scene adds on top: its time step, the names and
/// colours of its bodies, and its timed events.
#[derive(Debug)]
pub struct SceneWorld {
    /// The world.
    pub world: World,
    /// Seconds per step.
    pub time_step: Real,
    /// Bodies by the names the scene gave them.
    pub names: HashMap<String, BodyHandle>,
    /// Colours the scene asked for.
    pub colors: HashMap<BodyHandle, (f32, f32, f32)>,
    /// Where the scene's camera starts: its own, or one that frames its bodies.
    pub camera: Camera,
    /// What the scene asks to be drawn.
    pub draw: DrawFlags,
    /// How `carom bench` measures the scene's error, its body names checked.
    pub accuracy: Option<Accuracy>,
    /// The character the keyboard walks, if the scene has one: set its
    /// [`Player::input`] before each step.
    pub player: Option<Player>,
    pub(crate) events: Events,
}

impl SceneWorld {
    /// Fires the events due, moves the player, and advances the world by one time step.
    pub fn step(&mut self) -> Result<(), CaromError> {
        self.events
            .fire(&mut self.world, &mut self.colors, self.time_step);
        if let Some(player) = &mut self.player {
            player.step(&mut self.world, self.time_step)?;
        }
        self.world.step(self.time_step)
    }

    /// Fires the events due now without stepping (harmless: [`SceneWorld::step`] fires each
    /// event once), so the state at time 0 includes the launches at time 0.
    pub fn fire_events(&mut self) {
        self.events
            .fire(&mut self.world, &mut self.colors, self.time_step);
    }

    /// What the scene's spawn events will make and remove over the next `steps` steps,
    /// written out for another engine to do the same before the same steps (a benchmark's
    /// peers, say); see [`SpawnSchedule`].
    ///
    /// # Errors
    /// A spawn event that has made copies already: schedule a scene before its first step.
    pub fn spawn_schedule(&self, steps: u64) -> Result<SpawnSchedule, String> {
        let (spawns, others) = self.events.spawns();
        let now = self.world.step_count();
        SpawnSchedule::new(
            &spawns,
            self.world.settings(),
            (now, steps),
            self.time_step,
            others,
        )
    }

    /// Describes the world to `out` as `options` select, in the scene's colours.
    pub fn debug_draw(&self, options: &DrawOptions, out: &mut impl DebugDraw) {
        self.world.debug_draw(
            options,
            |body| {
                self.colors
                    .get(&body.handle())
                    .map(|&(r, g, b)| Color::rgb(r, g, b))
            },
            out,
        );
        if let Some(player) = &self.player {
            player.draw(out);
        }
    }
}

/// Builds a scene; `file` names it in error messages.
pub fn build(scene: &Scene, file: &str) -> Result<SceneWorld, SceneError> {
    let invalid = |what: String, reason: String| SceneError::Invalid {
        file: file.to_string(),
        what,
        reason,
    };
    let time_step = scene.time_step;
    if !carom::TIME_STEP_RANGE.contains(&time_step) {
        return Err(invalid(
            "time_step".into(),
            format!("time_step must be from 1e-6 s to 10 s, got {time_step}"),
        ));
    }
    if let Some(state) = &scene.state {
        let mut saved = state
            .parts()
            .map_err(|reason| invalid("state".into(), reason))?;
        if saved.world.colliders().any(|c| c.pre_solve()) {
            saved.world.set_pre_solve(one_way::solid_from_above);
        }
        let (world, names, colors, events) = (saved.world, saved.names, saved.colors, saved.events);
        let mut built = finish(scene, world, names, colors, events, time_step, &invalid)?;
        if let (Some(player), Some(state)) = (&mut built.player, saved.player) {
            player
                .restore(state)
                .map_err(|reason| invalid("state".into(), reason))?;
        }
        return Ok(built);
    }
    let mut world =
        World::with_settings(scene.world).map_err(|e| invalid("world".into(), e.to_string()))?;
    let mut names = HashMap::new();
    let mut colors = HashMap::new();
    let mut initial = HashMap::new();

    for (index, spec) in scene.bodies.iter().enumerate() {
        let what = match &spec.name {
            Some(name) => format!("body {index} ({name:?})"),
            None => format!("body {index}"),
        };
        let def = body_def(spec).map_err(|e| invalid(what.clone(), e))?;
        let handle = world
            .add_body(def.clone())
            .map_err(|e| invalid(what.clone(), e.to_string()))?;
        if let Some(color) = spec.material.color {
            colors.insert(handle, color);
        }
        if let Some(name) = &spec.name {
            if names.insert(name.clone(), handle).is_some() {
                return Err(invalid(what, format!("the name {name:?} is used twice")));
            }
            initial.insert(handle, def);
        }
    }
    let mut pending = Vec::new();
    // Collision groups handed out to copies of groups that do not collide with themselves.
    let mut groups_used = 0;
    for (index, generator) in scene.generators.iter().enumerate() {
        let what = format!("generator {index} ({})", generator_name(generator));
        let batch = generate(generator).map_err(|e| invalid(what.clone(), e))?;
        let copies = batch.copies_apart();
        let Batch {
            defs,
            colors: batch_colors,
            joints,
            apart,
        } = batch;
        let parts = (&batch_colors[..], &apart[..]);
        let handles = add_bodies(&mut world, defs, parts, groups_used, &mut colors)
            .map_err(|e| invalid(what.clone(), e.to_string()))?;
        groups_used += copies as i32;
        // Joined once every generator's bodies exist (a chain may hang from a later one).
        // The joints share their batch's handles: a copy each cost the joint grid's 19,800
        // joints 1.6 GB of copying.
        let handles: Rc<[BodyHandle]> = handles.into();
        pending.extend(
            joints
                .into_iter()
                .map(|joint| (what.clone(), joint, Rc::clone(&handles))),
        );
    }
    for (index, spec) in scene.joints.iter().enumerate() {
        let what = format!("joint {index} ({:?} to {:?})", spec.bodies.0, spec.bodies.1);
        let joint = PendingJoint::named(spec, Vec2::zeros());
        pending.push((what, joint, Rc::from([])));
    }
    for (what, joint, handles) in pending {
        let def = joint
            .def(&handles, &names)
            .map_err(|e| invalid(what.clone(), e))?;
        world
            .add_joint(def)
            .map_err(|e| invalid(what.clone(), e.to_string()))?;
    }
    if world.colliders().any(|c| c.pre_solve()) {
        world.set_pre_solve(one_way::solid_from_above);
    }
    let events = Events::new(&scene.events, &names, initial, &world, groups_used)
        .map_err(|(index, reason)| invalid(format!("event {index}"), reason))?;
    finish(scene, world, names, colors, events, time_step, &invalid)
}

/// The scene's world with what the scene adds on top, its accuracy measure checked.
fn finish(
    scene: &Scene,
    world: World,
    names: HashMap<String, BodyHandle>,
    colors: HashMap<BodyHandle, (f32, f32, f32)>,
    events: Events,
    time_step: Real,
    invalid: &dyn Fn(String, String) -> SceneError,
) -> Result<SceneWorld, SceneError> {
    if let Some(accuracy) = &scene.accuracy {
        check_accuracy(accuracy, &names, &world)
            .map_err(|reason| invalid("accuracy".into(), reason))?;
    }
    let player = scene
        .player
        .as_ref()
        .map(Player::new)
        .transpose()
        .map_err(|reason| invalid("player".into(), reason))?;
    let camera = scene.camera.unwrap_or_else(|| Camera::framing(&world));
    Ok(SceneWorld {
        world,
        time_step,
        names,
        colors,
        camera,
        draw: scene.draw,
        accuracy: scene.accuracy.clone(),
        player,
        events,
    })
}

/// The accuracy measure names bodies that exist (with a joint, for the joint measures) and
/// asks for a positive time, and positive or finite values where it has them.
fn check_accuracy(
    accuracy: &Accuracy,
    names: &HashMap<String, BodyHandle>,
    world: &World,
) -> Result<(), String> {
    let positive = |name: &str, value: Real| {
        if value.is_finite() && value > 0.0 {
            Ok(())
        } else {
            Err(format!("{name} must be finite and positive, got {value}"))
        }
    };
    // The bodies it names, and whether they must have a joint (the joint measures read it).
    let (bodies, jointed, seconds): (&[String], bool, Real) = match accuracy {
        Accuracy::Rest { bodies, seconds } => (bodies, false, *seconds),
        Accuracy::Conservation { seconds } => (&[], false, *seconds),
        Accuracy::SlideAngle {
            body,
            friction,
            seconds,
        } => {
            positive("friction", *friction)?;
            (std::slice::from_ref(body), false, *seconds)
        }
        Accuracy::Period {
            body,
            expected,
            seconds,
        } => {
            positive("expected", *expected)?;
            (std::slice::from_ref(body), true, *seconds)
        }
        Accuracy::Stretch {
            body,
            anchor,
            length,
            seconds,
        } => {
            positive("length", *length)?;
            if !(anchor.0.is_finite() && anchor.1.is_finite()) {
                return Err(format!("anchor must be finite, got {anchor:?}"));
            }
            (std::slice::from_ref(body), true, *seconds)
        }
        Accuracy::Gaps { length, seconds } => {
            positive("length", *length)?;
            if world.joint_count() == 0 {
                return Err("the scene has no joints to measure".into());
            }
            (&[], false, *seconds)
        }
        Accuracy::Hinges { seconds } => {
            let hinges = world
                .joints()
                .any(|j| matches!(j.kind(), carom::JointKind::Revolute(_)));
            if !hinges {
                return Err("the scene has no hinges (revolute joints) to measure".into());
            }
            (&[], false, *seconds)
        }
        Accuracy::Sink { ground, seconds } => {
            if !ground.is_finite() {
                return Err(format!("ground must be finite, got {ground}"));
            }
            (&[], false, *seconds)
        }
    };
    positive("seconds", seconds)?;
    for name in bodies {
        let Some(&handle) = names.get(name) else {
            return Err(format!("no body is named {name:?}"));
        };
        if jointed && world.joints_of(handle).is_empty() {
            return Err(format!("{name:?} has no joint to measure"));
        }
    }
    Ok(())
}

/// The shape of a single collider (a chain makes several: [`colliders_of`] builds those), or
/// what is wrong with it.
fn shape(spec: &ShapeSpec) -> Result<Shape, String> {
    if let ShapeSpec::Chain { .. } = spec {
        return Err(
            "a chain can be a body's shape or one of its colliders, not a generator's \
                    shape"
                .into(),
        );
    }
    single_shape(spec).map_err(|e| e.to_string())
}

#[allow(
    clippy::unreachable,
    reason = "its one caller, `shape`, answers chains with an error before calling it"
)]
fn single_shape(spec: &ShapeSpec) -> Result<Shape, CaromError> {
    let points =
        |points: &[(Real, Real)]| points.iter().map(|&(x, y)| vec2(x, y)).collect::<Vec<_>>();
    let rounded = |shape: Shape, radius: Real| match shape {
        Shape::Polygon(p) if radius != 0.0 => checked(Shape::Polygon(p.rounded(radius))),
        shape => Ok(shape),
    };
    match spec {
        ShapeSpec::Circle { radius } => checked(Shape::circle(*radius)),
        ShapeSpec::Box { width, height } => checked(Shape::rect(0.5 * width, 0.5 * height)),
        ShapeSpec::RoundedBox {
            width,
            height,
            radius,
        } => {
            let fits = radius.is_finite() && *radius >= 0.0 && 2.0 * radius < width.min(*height);
            if !fits {
                return Err(CaromError::OutOfRange {
                    name: "rounded box radius",
                    expected: "at least 0 and less than half the width and half the height",
                    value: *radius,
                });
            }
            checked(Shape::rounded_rect(
                0.5 * width - radius,
                0.5 * height - radius,
                *radius,
            ))
        }
        ShapeSpec::Capsule { length, radius } => checked(Shape::capsule(
            vec2(-0.5 * length, 0.0),
            vec2(0.5 * length, 0.0),
            *radius,
        )),
        ShapeSpec::Regular {
            sides,
            radius,
            rounding,
        } => rounded(Shape::regular(*sides as usize, *radius)?, *rounding),
        ShapeSpec::Polygon { points: p, radius } => rounded(Shape::polygon(&points(p))?, *radius),
        ShapeSpec::Hull { points: p, radius } => rounded(Shape::hull(&points(p))?, *radius),
        ShapeSpec::Segment { from, to, radius } => {
            let (from, to) = (vec2(from.0, from.1), vec2(to.0, to.1));
            if *radius == 0.0 {
                checked(Shape::segment(from, to))
            } else {
                checked(Shape::capsule(from, to, *radius))
            }
        }
        ShapeSpec::Chain { .. } => unreachable!("chains are made by `colliders_of`"),
    }
}

/// The colliders a shape makes, with `base`'s placement and material: one, or a chain's links.
fn colliders_of(spec: &ShapeSpec, base: ColliderDef) -> Result<Vec<ColliderDef>, String> {
    match spec {
        ShapeSpec::Chain { points, closed } => {
            let points: Vec<Vec2> = points.iter().map(|&(x, y)| vec2(x, y)).collect();
            let chain = if *closed {
                ChainDef::closed(points)
            } else {
                ChainDef::open(points)
            };
            Ok(chain
                .segments()
                .map_err(|e| e.to_string())?
                .into_iter()
                .map(|link| ColliderDef {
                    shape: Shape::ChainSegment(link),
                    density: 0.0,
                    ..base.clone()
                })
                .collect())
        }
        _ => Ok(vec![ColliderDef {
            shape: shape(spec)?,
            ..base
        }]),
    }
}

/// The shape, if it is valid: checked here so the error can name its place in the file.
fn checked(shape: Shape) -> Result<Shape, CaromError> {
    shape.validate()?;
    Ok(shape)
}

fn with_material(def: BodyDef, material: &Material) -> BodyDef {
    def.filter(material.filter)
        .density(material.density)
        .surface(surface(material))
        .damping(material.damping.0, material.damping.1)
}

/// The surface a material gives.
fn surface(material: &Material) -> Surface {
    Surface {
        friction: material.friction,
        restitution: material.restitution,
        rolling_resistance: material.rolling_resistance,
        tangent_speed: material.tangent_speed,
        material: 0,
    }
}

/// A body's definition; a collider that is both a sensor and one-way is refused.
fn body_def(spec: &BodySpec) -> Result<BodyDef, String> {
    let flags = spec.shape.iter().map(|_| (spec.sensor, spec.one_way));
    let parts = spec.colliders.iter().map(|part| {
        (
            part.sensor.unwrap_or(spec.sensor),
            part.one_way.unwrap_or(spec.one_way),
        )
    });
    if flags
        .chain(parts)
        .any(|(sensor, one_way)| sensor && one_way)
    {
        return Err("a sensor never collides, so it cannot be one_way".into());
    }
    body_def_of(spec)
}

/// [`body_def`], its flags checked. A one-way collider is shown to the pre-solve hook, which
/// [`crate::one_way`] installs.
fn body_def_of(spec: &BodySpec) -> Result<BodyDef, String> {
    let material = &spec.material;
    let mut colliders = Vec::with_capacity(spec.colliders.len() + 1);
    // Placeholder shapes: `colliders` puts each spec's own in.
    let placeholder = || ColliderDef::new(Shape::circle(1.0));
    if let Some(first) = &spec.shape {
        colliders.extend(colliders_of(
            first,
            placeholder()
                .density(material.density)
                .surface(surface(material))
                .filter(material.filter)
                .sensor(spec.sensor)
                .pre_solve(spec.one_way),
        )?);
    }
    for part in &spec.colliders {
        colliders.extend(colliders_of(
            &part.shape,
            placeholder()
                .offset(vec2(part.offset.0, part.offset.1))
                .angle(part.angle)
                .density(part.density.unwrap_or(material.density))
                .surface(surface(material))
                .friction(part.friction.unwrap_or(material.friction))
                .restitution(part.restitution.unwrap_or(material.restitution))
                .filter(part.filter.unwrap_or(material.filter))
                .sensor(part.sensor.unwrap_or(spec.sensor))
                .pre_solve(part.one_way.unwrap_or(spec.one_way)),
        )?);
    }
    let Some(first) = colliders.first() else {
        return Err(CaromError::NoCollider.to_string());
    };
    let mut def = BodyDef::new(spec.kind, first.shape.clone())
        .position(vec2(spec.position.0, spec.position.1))
        .angle(spec.angle)
        .linear_velocity(vec2(spec.linear_velocity.0, spec.linear_velocity.1))
        .angular_velocity(spec.angular_velocity)
        .damping(material.damping.0, material.damping.1)
        .bullet(spec.bullet)
        .fixed_rotation(spec.fixed_rotation)
        .awake(spec.awake)
        .sleep_threshold(spec.sleep_threshold);
    def.colliders = colliders;
    Ok(def)
}

fn generator_name(generator: &Generator) -> &'static str {
    match generator {
        Generator::Stack { .. } => "stack",
        Generator::Pyramid { .. } => "pyramid",
        Generator::Grid { .. } => "grid",
        Generator::JointGrid { .. } => "joint grid",
        Generator::Room { .. } => "room",
        Generator::Rain { .. } => "rain",
        Generator::Repeat { .. } => "repeat",
        Generator::Chain { .. } => "chain",
        Generator::Group { .. } => "group",
    }
}

/// A batch's colours and copies that keep apart, body by body.
pub(crate) type BatchParts<'a> = (&'a [Option<(f32, f32, f32)>], &'a [Option<u32>]);

/// Adds a batch's bodies (`defs`, with their colours and the copies that keep apart, from
/// `parts`) to `world`: the bodies of copy `k` of a group that does not collide with itself
/// take collision group `-(1 + first_group + k)`. Returns their handles, in order.
pub(crate) fn add_bodies(
    world: &mut World,
    defs: impl IntoIterator<Item = BodyDef>,
    (batch_colors, apart): BatchParts<'_>,
    first_group: i32,
    colors: &mut HashMap<BodyHandle, (f32, f32, f32)>,
) -> Result<Vec<BodyHandle>, CaromError> {
    let mut handles = Vec::with_capacity(apart.len());
    for ((mut def, color), apart) in defs.into_iter().zip(batch_colors).zip(apart) {
        if let Some(copy) = apart {
            let group = -(1 + first_group + *copy as i32);
            for collider in &mut def.colliders {
                collider.filter.group = group;
            }
        }
        let handle = world.add_body(def)?;
        if let Some(color) = color {
            colors.insert(handle, *color);
        }
        handles.push(handle);
    }
    Ok(handles)
}

/// The bodies a generator makes, their colours, and the joints between them.
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
pub(crate) struct Batch {
    pub defs: Vec<BodyDef>,
    pub colors: Vec<Option<(f32, f32, f32)>>,
    pub joints: Vec<PendingJoint>,
    /// Per body, the copy of a group that must not collide with itself it belongs to.
    pub apart: Vec<Option<u32>>,
}

impl Batch {
    /// How many copies of groups that keep apart it holds (each takes a collision group).
    pub fn copies_apart(&self) -> u32 {
        self.apart.iter().flatten().max().map_or(0, |&k| k + 1)
    }

    /// Bodies all of one material.
    fn of(defs: Vec<BodyDef>, material: &Material) -> Self {
        Batch {
            colors: vec![material.color; defs.len()],
            apart: vec![None; defs.len()],
            defs,
            joints: Vec::new(),
        }
    }
}

/// A joint's body: one of its batch's (by index), or one the scene named.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub(crate) enum Target {
    Local(usize),
    Named(String),
}

/// A joint waiting for its bodies to exist.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub(crate) struct PendingJoint {
    pub bodies: [Target; 2],
    kind: JointKindSpec,
    anchor: Vec2,
    anchor_b: Option<Vec2>,
    collide_connected: bool,
    break_force: Option<Real>,
    break_torque: Option<Real>,
}

fn point((x, y): Pair) -> Vec2 {
    vec2(x, y)
}

impl PendingJoint {
    /// `spec`, its bodies found by name among the scene's, moved by `shift`.
    fn named(spec: &JointSpec, shift: Vec2) -> Self {
        Self::with_targets(
            spec,
            [
                Target::Named(spec.bodies.0.clone()),
                Target::Named(spec.bodies.1.clone()),
            ],
            shift,
        )
    }

    fn with_targets(spec: &JointSpec, bodies: [Target; 2], shift: Vec2) -> Self {
        PendingJoint {
            bodies,
            kind: spec.kind,
            anchor: point(spec.anchor) + shift,
            anchor_b: spec.anchor_b.map(|b| point(b) + shift),
            collide_connected: spec.collide_connected,
            break_force: spec.break_force,
            break_torque: spec.break_torque,
        }
    }

    /// The same joint moved by `shift`, its batch bodies `offset` further on.
    pub fn shifted(&self, shift: Vec2, offset: usize) -> Self {
        let mut moved = self.clone();
        for target in &mut moved.bodies {
            if let Target::Local(index) = target {
                *index += offset;
            }
        }
        moved.anchor += shift;
        moved.anchor_b = moved.anchor_b.map(|b| b + shift);
        if let JointKindSpec::Mouse { target, .. } = &mut moved.kind {
            *target = (target.0 + shift.x, target.1 + shift.y);
        }
        moved
    }

    /// The joint's definition, its bodies found among the batch's `handles` or the scene's
    /// `names`.
    pub fn def(
        &self,
        handles: &[BodyHandle],
        names: &HashMap<String, BodyHandle>,
    ) -> Result<JointDef, String> {
        let find = |target: &Target| match target {
            Target::Local(index) => Ok(handles[*index]),
            Target::Named(name) => names
                .get(name)
                .copied()
                .ok_or_else(|| format!("no body is named {name:?}")),
        };
        let (a, b) = (find(&self.bodies[0])?, find(&self.bodies[1])?);
        let anchor_b = self.anchor_b.unwrap_or(self.anchor);
        let limits = |limits: Option<Pair>| limits.map(|(lower, upper)| Limits { lower, upper });
        let kind = match self.kind {
            JointKindSpec::Distance {
                length,
                spring,
                limits: range,
            } => JointKind::Distance(DistanceJoint {
                length: length.unwrap_or_else(|| (anchor_b - self.anchor).norm()),
                spring,
                spring_force: None,
                motor: None,
                limits: limits(range),
            }),
            JointKindSpec::Revolute {
                limits: range,
                motor,
                spring,
                target_angle,
            } => JointKind::Revolute(RevoluteJoint {
                limits: limits(range),
                motor,
                spring,
                target_angle,
            }),
            JointKindSpec::Prismatic {
                axis,
                limits: range,
                motor,
                spring,
                target_translation,
            } => JointKind::Prismatic(PrismaticJoint {
                axis: point(axis),
                limits: limits(range),
                motor,
                spring,
                target_translation,
            }),
            JointKindSpec::Weld { linear, angular } => {
                JointKind::Weld(WeldJoint { linear, angular })
            }
            JointKindSpec::Wheel {
                axis,
                spring,
                limits: range,
                motor,
            } => JointKind::Wheel(WheelJoint {
                axis: point(axis),
                spring,
                limits: limits(range),
                motor,
            }),
            JointKindSpec::Motor {
                linear_velocity,
                max_velocity_force,
                angular_velocity,
                max_velocity_torque,
                linear_offset,
                angular_offset,
                linear_spring,
                max_spring_force,
                angular_spring,
                max_spring_torque,
            } => JointKind::Motor(MotorJoint {
                linear_velocity: point(linear_velocity),
                max_velocity_force,
                angular_velocity,
                max_velocity_torque,
                linear_offset: point(linear_offset),
                angular_offset,
                linear_spring,
                max_spring_force,
                angular_spring,
                max_spring_torque,
            }),
            JointKindSpec::Mover {
                velocity,
                max_force,
            } => JointKind::Mover(MoverJoint {
                velocity: point(velocity),
                max_force: point(max_force),
            }),
            JointKindSpec::Pogo {
                normal,
                rest_length,
                spring,
                max_compression,
                max_tension,
            } => JointKind::Pogo(PogoJoint {
                normal: point(normal),
                rest_length,
                spring,
                max_compression,
                max_tension,
            }),
            JointKindSpec::Mouse {
                target,
                spring,
                max_force,
            } => JointKind::Mouse(MouseJoint {
                target: point(target),
                spring,
                max_force,
            }),
            JointKindSpec::Filter => JointKind::Filter,
        };
        let mut def = JointDef::new(a, b, self.anchor, anchor_b, kind)
            .collide_connected(self.collide_connected);
        if let Some(force) = self.break_force {
            def = def.break_force(force);
        }
        if let Some(torque) = self.break_torque {
            def = def.break_torque(torque);
        }
        Ok(def)
    }
}

/// The bodies and joints a generator makes.
pub(crate) fn generate(generator: &Generator) -> Result<Batch, String> {
    let square =
        |size: Real| checked(Shape::rect(0.5 * size, 0.5 * size)).map_err(|e| e.to_string());
    let (defs, material) = match generator {
        Generator::Stack {
            base,
            count,
            size,
            offset,
            material,
        } => {
            let shape = square(*size)?;
            let defs = (0..*count)
                .map(|i| {
                    let shift = if i % 2 == 0 { *offset } else { -*offset };
                    let at = vec2(base.0 + shift, base.1 + (i as Real + 0.5) * size);
                    with_material(BodyDef::dynamic(shape.clone()).position(at), material)
                })
                .collect();
            (defs, *material)
        }
        Generator::Pyramid {
            base,
            count,
            size,
            rows,
            overlap,
            material,
        } => {
            if !(0.0..1.0).contains(overlap) {
                return Err(format!("overlap must be in [0, 1), got {overlap}"));
            }
            let shape = square(*size)?;
            // Centre to centre: a box, less the overlap.
            let pitch = size * (1.0 - overlap);
            let mut defs = Vec::new();
            for row in 0..rows.unwrap_or(*count).min(*count) {
                let in_row = count - row;
                for column in 0..in_row {
                    let x = base.0 + (column as Real - 0.5 * (in_row as Real - 1.0)) * pitch;
                    let y = base.1 + 0.5 * size + row as Real * pitch;
                    defs.push(with_material(
                        BodyDef::dynamic(shape.clone()).position(vec2(x, y)),
                        material,
                    ));
                }
            }
            (defs, *material)
        }
        Generator::Grid {
            origin,
            columns,
            rows,
            spacing,
            shape: one,
            shapes: cycle,
            count,
            kind: kind_name,
            material,
            awake,
            compound,
        } => {
            let shapes = match (one, cycle.is_empty()) {
                (Some(spec), true) => vec![shape(spec)?],
                (None, false) => cycle.iter().map(shape).collect::<Result<Vec<_>, _>>()?,
                (Some(_), false) => return Err("give `shape` or `shapes`, not both".into()),
                (None, true) => return Err("a grid needs a `shape` or `shapes`".into()),
            };
            let cells = columns.saturating_mul(*rows);
            let count = count.unwrap_or(cells);
            if count > cells {
                return Err(format!(
                    "count {count} is more than the {columns} x {rows} cells"
                ));
            }
            let cells = (0..count).map(|i| {
                let (row, column) = (i / columns, i % columns);
                let at = vec2(
                    origin.0 + column as Real * spacing.0,
                    origin.1 + row as Real * spacing.1,
                );
                (at, shapes[i as usize % shapes.len()].clone())
            });
            let defs = if *compound {
                let colliders: Vec<ColliderDef> = cells
                    .map(|(at, shape)| ColliderDef::new(shape).offset(at))
                    .collect();
                let Some(first) = colliders.first() else {
                    return Err("a compound grid needs at least one cell".into());
                };
                let mut def = BodyDef::new(*kind_name, first.shape.clone()).awake(*awake);
                def.colliders = colliders;
                vec![with_material(def, material)]
            } else {
                cells
                    .map(|(at, shape)| {
                        with_material(
                            BodyDef::new(*kind_name, shape).position(at).awake(*awake),
                            material,
                        )
                    })
                    .collect()
            };
            (defs, *material)
        }
        Generator::JointGrid {
            origin,
            columns,
            rows,
            spacing,
            shape: spec,
            material,
            fixed,
            joint,
        } => {
            let shape = shape(spec)?;
            return Ok(joint_grid(
                point(*origin),
                (*columns, *rows),
                point(*spacing),
                &shape,
                material,
                fixed,
                joint,
            ));
        }
        Generator::Rain {
            low,
            high,
            count,
            shape: spec,
            seed,
            material,
        } => {
            let shape = shape(spec)?;
            // xorshift64*: small, deterministic on every machine.
            let mut state = seed.wrapping_mul(0x9e37_79b9_7f4a_7c15) | 1;
            let mut unit = move || {
                state ^= state >> 12;
                state ^= state << 25;
                state ^= state >> 27;
                (state.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 40) as Real / (1u64 << 24) as Real
            };
            let defs = (0..*count)
                .map(|_| {
                    let at = vec2(
                        low.0 + (high.0 - low.0) * unit(),
                        low.1 + (high.1 - low.1) * unit(),
                    );
                    let angle = carom::consts::TAU * unit();
                    with_material(
                        BodyDef::dynamic(shape.clone()).position(at).angle(angle),
                        material,
                    )
                })
                .collect();
            (defs, *material)
        }
        Generator::Repeat {
            columns,
            rows,
            spacing,
            of,
        } => {
            let one = generate(of)?;
            let copies_apart = one.copies_apart();
            let mut all = Batch::default();
            for row in 0..*rows {
                for column in 0..*columns {
                    let copy = row * columns + column;
                    let apart = one.apart.iter().map(|k| k.map(|k| k + copy * copies_apart));
                    all.apart.extend(apart);
                    let shift = vec2(column as Real * spacing.0, row as Real * spacing.1);
                    let offset = all.defs.len();
                    all.defs.extend(one.defs.iter().cloned().map(|mut def| {
                        def.position += shift;
                        def
                    }));
                    all.colors.extend_from_slice(&one.colors);
                    all.joints
                        .extend(one.joints.iter().map(|j| j.shifted(shift, offset)));
                }
            }
            return Ok(all);
        }
        Generator::Chain {
            from,
            to,
            count,
            thickness,
            start,
            end,
            joint,
            material,
        } => {
            return chain(
                point(*from),
                point(*to),
                *count,
                *thickness,
                (start, end),
                joint,
                material,
            );
        }
        Generator::Group {
            bodies,
            joints,
            self_collide,
        } => return group(bodies, joints, *self_collide),
        Generator::Room {
            center,
            width,
            height,
            thickness,
            material,
        } => {
            let (c, w, h, t) = (vec2(center.0, center.1), *width, *height, *thickness);
            let wall = |half_w: Real, half_h: Real, dx: Real, dy: Real| {
                checked(Shape::rect(half_w, half_h))
                    .map(|s| {
                        with_material(BodyDef::static_body(s).position(c + vec2(dx, dy)), material)
                    })
                    .map_err(|e| e.to_string())
            };
            let defs = vec![
                wall(0.5 * w + t, 0.5 * t, 0.0, -0.5 * (h + t))?,
                wall(0.5 * w + t, 0.5 * t, 0.0, 0.5 * (h + t))?,
                wall(0.5 * t, 0.5 * h, -0.5 * (w + t), 0.0)?,
                wall(0.5 * t, 0.5 * h, 0.5 * (w + t), 0.0)?,
            ];
            (defs, *material)
        }
    };
    Ok(Batch::of(defs, &material))
}

/// A chain of `count` box links from `from` to `to`, each joined to the next at their shared
/// end, the first to `start` and the last to `end` (scene body names) if given.
fn chain(
    from: Vec2,
    to: Vec2,
    count: u32,
    thickness: Real,
    (start, end): (&Option<String>, &Option<String>),
    joint: &RevoluteSpec,
    material: &Material,
) -> Result<Batch, String> {
    if count == 0 {
        return Err("a chain needs at least one link".into());
    }
    let step = (to - from) / count as Real;
    let length = step.norm();
    let link = checked(Shape::rect(0.5 * length, 0.5 * thickness)).map_err(|e| e.to_string())?;
    let angle = carom::atan2(step.y, step.x);
    let defs: Vec<BodyDef> = (0..count)
        .map(|i| {
            let at = from + step * (i as Real + 0.5);
            with_material(
                BodyDef::dynamic(link.clone()).position(at).angle(angle),
                material,
            )
        })
        .collect();
    let spec = JointSpec {
        bodies: (String::new(), String::new()),
        kind: JointKindSpec::Revolute {
            limits: joint.limits,
            motor: joint.motor,
            spring: joint.spring,
            target_angle: joint.target_angle,
        },
        anchor: (0.0, 0.0),
        anchor_b: None,
        collide_connected: false,
        break_force: None,
        break_torque: None,
    };
    let n = count as usize;
    let mut joints = Vec::new();
    for i in 0..=n {
        let before = match i {
            0 => start.clone().map(Target::Named),
            _ => Some(Target::Local(i - 1)),
        };
        let after = match i {
            _ if i == n => end.clone().map(Target::Named),
            _ => Some(Target::Local(i)),
        };
        if let (Some(a), Some(b)) = (before, after) {
            let at = from + step * i as Real;
            joints.push(PendingJoint::with_targets(&spec, [a, b], at));
        }
    }
    Ok(Batch {
        joints,
        ..Batch::of(defs, material)
    })
}

/// A hinge with `joint`'s settings between batch bodies `a` and `b` at `at`.
fn hinge(joint: &RevoluteSpec, a: usize, b: usize, at: Vec2) -> PendingJoint {
    PendingJoint {
        bodies: [Target::Local(a), Target::Local(b)],
        kind: JointKindSpec::Revolute {
            limits: joint.limits,
            motor: joint.motor,
            spring: joint.spring,
            target_angle: joint.target_angle,
        },
        anchor: at,
        anchor_b: None,
        collide_connected: false,
        break_force: None,
        break_torque: None,
    }
}

/// `columns × rows` bodies made column by column, each hinged to the one before it in its
/// column and to its neighbour in the column before, at the midpoints (Box2D's joint grid).
fn joint_grid(
    origin: Vec2,
    (columns, rows): (u32, u32),
    spacing: Vec2,
    shape: &Shape,
    material: &Material,
    fixed: &[Cells],
    joint: &RevoluteSpec,
) -> Batch {
    let (n, m) = (columns as usize, rows as usize);
    let mut defs = Vec::with_capacity(n * m);
    let mut joints = Vec::with_capacity(2 * n * m);
    let at =
        |column: u32, row: u32| origin + vec2(column as Real * spacing.x, row as Real * spacing.y);
    for column in 0..columns {
        for row in 0..rows {
            let kind = if fixed.iter().any(|cells| cells.contains(column, row)) {
                BodyKind::Static
            } else {
                BodyKind::Dynamic
            };
            let here = at(column, row);
            let index = defs.len();
            defs.push(with_material(
                BodyDef::new(kind, shape.clone()).position(here),
                material,
            ));
            // Box2D's order: the joint up the column, then the one across from the column
            // before, each right after the body.
            if row > 0 {
                let mid = 0.5 * (at(column, row - 1) + here);
                joints.push(hinge(joint, index - 1, index, mid));
            }
            if column > 0 {
                let mid = 0.5 * (at(column - 1, row) + here);
                joints.push(hinge(joint, index - m, index, mid));
            }
        }
    }
    Batch {
        joints,
        ..Batch::of(defs, material)
    }
}

/// Bodies and joints defined together; a joint's names are looked up among the group's
/// bodies first, then the scene's.
fn group(bodies: &[BodySpec], joints: &[JointSpec], self_collide: bool) -> Result<Batch, String> {
    let mut batch = Batch::default();
    let mut local = HashMap::new();
    for (index, spec) in bodies.iter().enumerate() {
        let def = body_def(spec).map_err(|e| format!("body {index}: {e}"))?;
        if let Some(name) = &spec.name
            && local.insert(name.clone(), index).is_some()
        {
            return Err(format!("body {index}: the name {name:?} is used twice"));
        }
        batch.defs.push(def);
        batch.colors.push(spec.material.color);
        batch.apart.push((!self_collide).then_some(0));
    }
    let target = |name: &String| match local.get(name) {
        Some(&index) => Target::Local(index),
        None => Target::Named(name.clone()),
    };
    for spec in joints {
        let bodies = [target(&spec.bodies.0), target(&spec.bodies.1)];
        batch
            .joints
            .push(PendingJoint::with_targets(spec, bodies, Vec2::zeros()));
    }
    Ok(batch)
}
