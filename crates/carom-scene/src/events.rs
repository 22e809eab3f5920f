//! Timed events: launching a body at a moment, respawning one periodically, spinning a
//! kinematic frame, shuttling kinematic bodies back and forth, making and remaking copies of
//! bodies and joints in turn.

use crate::limits::{Limits, counts};
use crate::scene::EventSpec;
use crate::spawn::Spawn;
use carom::{BodyDef, BodyHandle, BodyKind, Real, World, vec2};
use serde::{Deserialize, Serialize};
use std::collections::HashMap;

#[derive(Debug, Clone, Serialize, Deserialize)]
enum Action {
    Launch {
        at: f64,
        body: BodyHandle,
        velocity: carom::Vec2,
        angular_velocity: Real,
        done: bool,
    },
    Respawn {
        every: f64,
        body: BodyHandle,
        start: BodyDef,
        next: f64,
    },
    Spin {
        pivot: carom::Vec2,
        angular_velocity: f64,
        /// Each body with its offset from the pivot and its angle at time zero.
        bodies: Vec<(BodyHandle, carom::Vec2, Real)>,
    },
    Shuttle {
        /// The way there and back, m.
        offset: carom::Vec2,
        period: f64,
        /// Each body with where it starts.
        bodies: Vec<(BodyHandle, carom::Vec2)>,
    },
    Spawn(Spawn),
}

/// A scene's events, ready to fire.
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
pub(crate) struct Events {
    actions: Vec<Action>,
}

impl Events {
    /// About the heap memory the events hold, bytes: their list (not what a spawn's bodies
    /// own in turn, which is small beside a world).
    pub(crate) fn heap_bytes(&self) -> usize {
        self.actions.capacity() * size_of::<Action>()
    }

    /// Resolves body names; an error gives the event's index and the reason. Spawned copies
    /// that keep apart take collision groups after the first `groups_used`.
    pub fn new(
        specs: &[EventSpec],
        names: &HashMap<String, BodyHandle>,
        mut initial: HashMap<BodyHandle, BodyDef>,
        world: &World,
        (mut groups_used, limits): (i32, &Limits),
    ) -> Result<Self, (usize, String)> {
        let find = |index: usize, name: &str| {
            names
                .get(name)
                .copied()
                .ok_or((index, format!("no body is named {name:?}")))
        };
        // The named bodies, each kinematic (the events that move them drive them), with
        // where they are and their angle.
        let kinematic = |index: usize, bodies: &[String], verb: &str| {
            bodies
                .iter()
                .map(|name| {
                    let handle = find(index, name)?;
                    let body = world
                        .body(handle)
                        .ok_or((index, format!("{name:?} is gone")))?;
                    if body.kind() != BodyKind::Kinematic {
                        return Err((index, format!("{name:?} must be kinematic to {verb}")));
                    }
                    Ok((handle, body.position(), body.angle()))
                })
                .collect::<Result<Vec<_>, _>>()
        };
        let mut actions = Vec::new();
        for (index, spec) in specs.iter().enumerate() {
            actions.push(match spec {
                EventSpec::Launch {
                    at,
                    body,
                    velocity,
                    angular_velocity,
                } => {
                    if !at.is_finite() || *at < 0.0 {
                        return Err((index, format!("`at` must be a time ≥ 0, got {at}")));
                    }
                    Action::Launch {
                        at: *at as f64,
                        body: find(index, body)?,
                        velocity: vec2(velocity.0, velocity.1),
                        angular_velocity: *angular_velocity,
                        done: false,
                    }
                }
                EventSpec::Respawn { every, body } => {
                    if !(every.is_finite() && *every > 0.0) {
                        return Err((index, format!("`every` must be positive, got {every}")));
                    }
                    let handle = find(index, body)?;
                    let start = initial
                        .remove(&handle)
                        .ok_or((index, format!("{body:?} is respawned twice")))?;
                    Action::Respawn {
                        every: *every as f64,
                        body: handle,
                        start,
                        next: *every as f64,
                    }
                }
                EventSpec::Spin {
                    bodies,
                    pivot,
                    angular_velocity,
                } => {
                    if !angular_velocity.is_finite() || !pivot.0.is_finite() || !pivot.1.is_finite()
                    {
                        return Err((index, "pivot and angular_velocity must be finite".into()));
                    }
                    let pivot = vec2(pivot.0, pivot.1);
                    let frame = kinematic(index, bodies, "spin")?
                        .into_iter()
                        .map(|(handle, at, angle)| (handle, at - pivot, angle))
                        .collect();
                    Action::Spin {
                        pivot,
                        angular_velocity: *angular_velocity as f64,
                        bodies: frame,
                    }
                }
                EventSpec::Shuttle {
                    bodies,
                    offset,
                    period,
                } => {
                    let good = period.is_finite()
                        && *period > 0.0
                        && offset.0.is_finite()
                        && offset.1.is_finite();
                    if !good {
                        return Err((index, "offset must be finite and period positive".into()));
                    }
                    let starts = kinematic(index, bodies, "shuttle")?
                        .into_iter()
                        .map(|(handle, at, _)| (handle, at))
                        .collect();
                    Action::Shuttle {
                        offset: vec2(offset.0, offset.1),
                        period: *period as f64,
                        bodies: starts,
                    }
                }
                EventSpec::Spawn {
                    at,
                    every,
                    origin,
                    columns,
                    rows,
                    spacing,
                    of,
                } => {
                    // Each spawn adds its copies at once: held to the limits as a build is.
                    let copies = u64::from(*columns).saturating_mul(u64::from(*rows));
                    if let Some(over) = limits.exceeded(counts(of).times(copies)) {
                        return Err((index, format!("one spawn would add {over}")));
                    }
                    let template = crate::generate::generate(of).map_err(|e| (index, e))?;
                    let groups = Spawn::groups(&template, *columns, *rows);
                    let spawn = Spawn::new(
                        (*at, *every),
                        vec2(origin.0, origin.1),
                        (*columns, *rows),
                        vec2(spacing.0, spacing.1),
                        template,
                        groups_used,
                        world,
                    )
                    .map_err(|e| (index, e))?;
                    groups_used = groups_used.saturating_add(groups);
                    Action::Spawn(spawn)
                }
            });
        }
        Ok(Events { actions })
    }

    /// Every body the events move: not the copies spawn events make, which may be removed by
    /// hand (the place is made again at its turn all the same).
    pub fn bodies(&self) -> Vec<BodyHandle> {
        let mut moved = Vec::new();
        for action in &self.actions {
            match action {
                Action::Launch { body, .. } | Action::Respawn { body, .. } => moved.push(*body),
                Action::Spin { bodies, .. } => {
                    moved.extend(bodies.iter().map(|(body, _, _)| *body))
                }
                Action::Shuttle { bodies, .. } => moved.extend(bodies.iter().map(|(b, _)| *b)),
                Action::Spawn(_) => {}
            }
        }
        moved
    }

    /// The spawn events, in order, and the names of the other events' kinds, in order.
    pub fn spawns(&self) -> (Vec<&Spawn>, Vec<&'static str>) {
        let mut spawns = Vec::new();
        let mut others = Vec::new();
        for action in &self.actions {
            match action {
                Action::Spawn(spawn) => spawns.push(spawn),
                Action::Launch { .. } => others.push("launch"),
                Action::Respawn { .. } => others.push("respawn"),
                Action::Spin { .. } => others.push("spin"),
                Action::Shuttle { .. } => others.push("shuttle"),
            }
        }
        (spawns, others)
    }

    /// Fires every event due at the world's current time, before a step of `dt` seconds;
    /// bodies an event makes or removes take or lose their colour in `colors`.
    pub fn fire(
        &mut self,
        world: &mut World,
        colors: &mut HashMap<BodyHandle, (f32, f32, f32)>,
        dt: Real,
    ) {
        let now = world.time() + 1e-9;
        for action in &mut self.actions {
            match action {
                Action::Launch {
                    at,
                    body,
                    velocity,
                    angular_velocity,
                    done,
                } => {
                    if !*done && now >= *at {
                        *done = true;
                        if let Some(mut b) = world.body_mut(*body) {
                            // Values were checked when the scene was built.
                            let _ = b.set_linear_velocity(*velocity);
                            let _ = b.set_angular_velocity(*angular_velocity);
                        }
                    }
                }
                Action::Respawn {
                    every,
                    body,
                    start,
                    next,
                } => {
                    if now >= *next {
                        *next += *every;
                        if let Some(mut b) = world.body_mut(*body) {
                            let _ = b.set_position(start.position);
                            let _ = b.set_angle(start.angle);
                            let _ = b.set_linear_velocity(start.linear_velocity);
                            let _ = b.set_angular_velocity(start.angular_velocity);
                        }
                    }
                }
                Action::Spin {
                    pivot,
                    angular_velocity,
                    bodies,
                } => {
                    // Aim at the exact pose at the end of the step, so the frame stays
                    // rigid however long it turns (velocities alone would spiral out).
                    let turn = (*angular_velocity * (world.time() + dt as f64)) as Real;
                    let rotation = carom::rotation(turn);
                    for (handle, offset, angle) in bodies.iter() {
                        if let Some(mut b) = world.body_mut(*handle) {
                            let _ =
                                b.move_kinematic_to(*pivot + rotation * offset, angle + turn, dt);
                        }
                    }
                }
                Action::Shuttle {
                    offset,
                    period,
                    bodies,
                } => {
                    // Eased out and back (a cosine), aimed at the exact place at the end of the
                    // step so no drift builds up.
                    let phase = std::f64::consts::TAU * (world.time() + dt as f64) / *period;
                    let along = (0.5 * (1.0 - phase.cos())) as Real;
                    for (handle, start) in bodies.iter() {
                        if let Some(mut b) = world.body_mut(*handle) {
                            let angle = b.angle();
                            let _ = b.move_kinematic_to(*start + *offset * along, angle, dt);
                        }
                    }
                }
                Action::Spawn(spawn) => spawn.fire(world, colors, dt),
            }
        }
    }
}
