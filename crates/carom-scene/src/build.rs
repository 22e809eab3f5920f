//! Turning a scene into a world: its bodies, generators and joints added, its events and
//! player wired, its accuracy measure checked.

use crate::defs::body_def;
use crate::error::SceneError;
use crate::events::Events;
use crate::generate::{Batch, add_bodies, generate, generator_name};
use crate::limits::{Counts, Limits, counts};
use crate::one_way;
use crate::pending_joint::PendingJoint;
use crate::player::Player;
use crate::scene::{Accuracy, Camera, Scene};
use crate::scene_world::SceneWorld;
use carom::{BodyHandle, Real, Vec2, World};
use std::collections::HashMap;
use std::rc::Rc;

/// Builds a scene within the default [`Limits`]; `file` names it in error messages.
pub fn build(scene: &Scene, file: &str) -> Result<SceneWorld, SceneError> {
    build_with_limits(scene, file, Limits::default())
}

/// Builds a scene; one that asks for more bodies or joints than `limits` allow is refused
/// before anything is made. `file` names it in error messages.
pub fn build_with_limits(
    scene: &Scene,
    file: &str,
    limits: Limits,
) -> Result<SceneWorld, SceneError> {
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
    // Counted before anything is made: a few bytes of generator can ask for billions.
    let mut asked = Counts {
        bodies: scene.bodies.len() as u64,
        joints: scene.joints.len() as u64,
    };
    if let Some(over) = limits.exceeded(asked) {
        return Err(invalid(
            "scene".into(),
            format!("the scene would have {over}"),
        ));
    }
    for (index, generator) in scene.generators.iter().enumerate() {
        asked = asked.plus(counts(generator));
        if let Some(over) = limits.exceeded(asked) {
            let what = format!("generator {index} ({})", generator_name(generator));
            return Err(invalid(what, format!("the scene would have {over}")));
        }
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
    let events = Events::new(
        &scene.events,
        &names,
        initial,
        &world,
        (groups_used, &limits),
    )
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
