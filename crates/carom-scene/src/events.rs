//! Timed events: launching a body at a moment, respawning one periodically.

use crate::scene::EventSpec;
use carom::{BodyDef, BodyHandle, World, vec2};
use std::collections::HashMap;

#[derive(Debug)]
enum Action {
    Launch {
        at: f64,
        body: BodyHandle,
        velocity: carom::Vec2,
        angular_velocity: f32,
        done: bool,
    },
    Respawn {
        every: f64,
        body: BodyHandle,
        start: BodyDef,
        next: f64,
    },
}

/// A scene's events, ready to fire.
#[derive(Debug, Default)]
pub(crate) struct Events {
    actions: Vec<Action>,
}

impl Events {
    /// Resolves body names; an error gives the event's index and the reason.
    pub fn new(
        specs: &[EventSpec],
        names: &HashMap<String, BodyHandle>,
        mut initial: HashMap<BodyHandle, BodyDef>,
    ) -> Result<Self, (usize, String)> {
        let find = |index: usize, name: &str| {
            names
                .get(name)
                .copied()
                .ok_or((index, format!("no body is named {name:?}")))
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
            });
        }
        Ok(Events { actions })
    }

    /// Fires every event due at the world's current time.
    pub fn fire(&mut self, world: &mut World) {
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
                        if let Some(b) = world.body_mut(*body) {
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
                        if let Some(b) = world.body_mut(*body) {
                            let _ = b.set_position(start.position);
                            let _ = b.set_angle(start.angle);
                            let _ = b.set_linear_velocity(start.linear_velocity);
                            let _ = b.set_angular_velocity(start.angular_velocity);
                        }
                    }
                }
            }
        }
    }
}
