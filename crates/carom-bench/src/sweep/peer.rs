//! A peer's copy of a carom world: Box2D v3 or Rapier, rebuilt from it by
//! `Box2dWorld::from_carom` or `RapierWorld::from_carom` and stepped in its place. Without the `peers` feature (the web build, which cannot compile
//! Box2D's C) there are no peers, and asking for one is an error.

use super::Engine;
use carom::{BodyHandle, Real, Vec2, World};

#[cfg(feature = "peers")]
pub use with_peers::Peer;
#[cfg(not(feature = "peers"))]
pub use without_peers::Peer;

#[cfg(feature = "peers")]
mod with_peers {
    use super::*;
    use crate::{Box2dWorld, RapierWorld};
    use carom::vec2;
    use std::collections::HashMap;

    /// A peer's copy of a carom world, stepped in its place.
    pub enum Peer {
        /// Box2D's copy.
        Box2d(Box<Box2dWorld>),
        /// Rapier's copy, with each carom body's index in it.
        Rapier(Box<RapierWorld>, HashMap<BodyHandle, usize>),
    }

    impl Peer {
        /// `engine`'s copy of `world`, stepping `time_step` seconds at a time (`None` for carom
        /// itself). Rapier's stabilization iterations are set when given.
        pub fn of(
            engine: Engine,
            world: &World,
            time_step: Real,
            stabilization: Option<u32>,
        ) -> Result<Option<Peer>, String> {
            Ok(match engine {
                Engine::Carom => None,
                Engine::Box2d => Some(Peer::Box2d(Box::new(Box2dWorld::from_carom(world)?))),
                Engine::Rapier => {
                    let mut rapier = RapierWorld::from_carom(world, time_step)?;
                    if let Some(iterations) = stabilization {
                        rapier.set_stabilization_iterations(iterations as usize);
                    }
                    let index = world
                        .bodies()
                        .enumerate()
                        .map(|(i, b)| (b.handle(), i))
                        .collect();
                    Some(Peer::Rapier(Box::new(rapier), index))
                }
            })
        }

        /// One step of `time_step` seconds.
        pub fn step(&mut self, time_step: Real) -> Result<(), String> {
            match self {
                Peer::Box2d(world) => world.step(time_step),
                Peer::Rapier(world, _) => {
                    world.step();
                    Ok(())
                }
            }
        }

        /// Where the body's origin is and how it is turned; `None` for a body the copy lacks.
        pub fn pose(&mut self, body: BodyHandle) -> Option<(Vec2, Real)> {
            match self {
                Peer::Box2d(world) => {
                    let i = world.index_of(body)?;
                    let [x, y] = world.position(i).ok()?;
                    Some((vec2(x, y), world.angle(i).ok()?))
                }
                Peer::Rapier(world, index) => {
                    let i = *index.get(&body)?;
                    let rigid = &world.bodies()[world.handle(i)?];
                    let t = rigid.translation();
                    Some((vec2(t.x, t.y), rigid.rotation().angle()))
                }
            }
        }

        /// Total linear momentum and kinetic energy of the copy's dynamic bodies, in double
        /// precision, each body weighed as the peer weighs it.
        pub fn momentum_and_energy(&mut self, world: &World) -> ([f64; 2], f64) {
            let mut momentum = [0.0; 2];
            let mut energy = 0.0;
            for body in world.bodies().filter(|b| b.is_dynamic()) {
                let Some((v, w, mass, inertia)) = self.motion(body.handle()) else {
                    continue;
                };
                momentum[0] += v.x as f64 * mass;
                momentum[1] += v.y as f64 * mass;
                energy += 0.5 * mass * (v.norm_squared() as f64) + 0.5 * inertia * (w * w) as f64;
            }
            (momentum, energy)
        }

        /// A body's linear and angular velocity, mass and rotational inertia about its centre of
        /// mass, as the peer has them.
        fn motion(&mut self, body: BodyHandle) -> Option<(Vec2, Real, f64, f64)> {
            match self {
                Peer::Box2d(world) => {
                    let i = world.index_of(body)?;
                    let [x, y] = world.linear_velocity(i).ok()?;
                    let w = world.angular_velocity(i).ok()?;
                    Some((
                        vec2(x, y),
                        w,
                        world.mass(i) as f64,
                        world.rotational_inertia(i) as f64,
                    ))
                }
                Peer::Rapier(world, index) => {
                    let i = *index.get(&body)?;
                    let rigid = &world.bodies()[world.handle(i)?];
                    let (v, w) = (rigid.linvel(), rigid.angvel());
                    let properties = rigid.mass_properties().local_mprops;
                    Some((
                        vec2(v.x, v.y),
                        w,
                        rigid.mass() as f64,
                        properties.principal_inertia() as f64,
                    ))
                }
            }
        }
    }
}

#[cfg(not(feature = "peers"))]
mod without_peers {
    use super::*;

    /// No peer: this build has none.
    pub enum Peer {}

    impl Peer {
        /// `None` for carom itself; any other engine is an error.
        pub fn of(
            engine: Engine,
            _: &World,
            _: Real,
            _: Option<u32>,
        ) -> Result<Option<Peer>, String> {
            match engine {
                Engine::Carom => Ok(None),
                other => Err(format!(
                    "{} is not in this build (built without the `peers` feature)",
                    other.name()
                )),
            }
        }

        /// Never called: there is no peer to step.
        pub fn step(&mut self, _: Real) -> Result<(), String> {
            match *self {}
        }

        /// Never called: there is no peer to ask.
        pub fn pose(&mut self, _: BodyHandle) -> Option<(Vec2, Real)> {
            match *self {}
        }

        /// Never called: there is no peer to ask.
        pub fn momentum_and_energy(&mut self, _: &World) -> ([f64; 2], f64) {
            match *self {}
        }
    }
}
