//! A collider lent out to be changed, so that what depends on it (its body's mass, its
//! contacts, the broadphase) follows at once.

use crate::dynamics::collider::{Collider, ColliderHandle, check_non_negative};
use crate::dynamics::filter::CollisionFilter;
use crate::dynamics::surface::Surface;
use crate::error::CaromError;
use crate::math::Real;
use crate::world::World;
use std::ops::Deref;

/// A collider borrowed from its world to be changed ([`crate::World::collider_mut`]). It reads
/// as a [`Collider`] and has the collider's setters; each change that other state depends on
/// (its body's mass, which contacts may exist) updates that state before it returns.
#[derive(Debug)]
pub struct ColliderMut<'w> {
    world: &'w mut World,
    handle: ColliderHandle,
}

impl<'w> ColliderMut<'w> {
    pub(crate) fn new(world: &'w mut World, handle: ColliderHandle) -> Self {
        ColliderMut { world, handle }
    }

    #[allow(
        clippy::expect_used,
        reason = "the collider was checked live when it was lent, and the loan holds the world"
    )]
    fn collider(&mut self) -> &mut Collider {
        self.world
            .state
            .colliders
            .get_mut(self.handle)
            .expect("lent live")
    }

    /// Sets the friction coefficient (from 0 to 1000); its contacts use it from the
    /// next step.
    ///
    /// # Errors
    /// A negative or non-finite friction; it is then left as it was.
    pub fn set_friction(&mut self, friction: Real) -> Result<(), CaromError> {
        self.change_surface(|surface| surface.friction = friction)
    }

    /// Sets the restitution (from 0 to 1000); its contacts use it from the next step.
    ///
    /// # Errors
    /// A negative or non-finite restitution; it is then left as it was.
    pub fn set_restitution(&mut self, restitution: Real) -> Result<(), CaromError> {
        self.change_surface(|surface| surface.restitution = restitution)
    }

    /// Sets the rolling resistance (from 0 to 1000; see
    /// [`crate::Surface::rolling_resistance`]); its contacts use it from the next step.
    ///
    /// # Errors
    /// A negative or non-finite resistance; it is then left as it was.
    pub fn set_rolling_resistance(&mut self, resistance: Real) -> Result<(), CaromError> {
        self.change_surface(|surface| surface.rolling_resistance = resistance)
    }

    /// Sets the tangent speed (within 1e4 m/s either way; see [`crate::Surface::tangent_speed`]): a conveyor
    /// belt's; its contacts use it from the next step.
    ///
    /// # Errors
    /// A speed outside that range or not finite; it is then left as it was.
    pub fn set_tangent_speed(&mut self, speed: Real) -> Result<(), CaromError> {
        self.change_surface(|surface| surface.tangent_speed = speed)
    }

    /// Sets the material id the world's mixers see (see [`crate::Surface::material`]).
    pub fn set_material(&mut self, material: u64) {
        // An id is any number: nothing to refuse.
        let _ = self.change_surface(|surface| surface.material = material);
    }

    /// Changes the surface as `change` says, if the result is valid, and mixes it into the
    /// contacts.
    fn change_surface(&mut self, change: impl FnOnce(&mut Surface)) -> Result<(), CaromError> {
        let mut surface = *self.collider().surface();
        change(&mut surface);
        self.collider().set_surface(surface)?;
        self.remix_contacts();
        Ok(())
    }

    /// Mixes the collider's material into its contacts again.
    fn remix_contacts(&mut self) {
        let body = self.body();
        let world = &mut *self.world;
        world.state.contacts.remix(body, &world.state.colliders);
    }

    /// Sets the density; the body's mass, centre of mass and inertia follow, and it wakes.
    ///
    /// # Errors
    /// A density that is negative or not finite, or a dynamic body left without mass; the
    /// density is then left as it was.
    #[allow(
        clippy::expect_used,
        reason = "a live collider's body is live: removing a body removes its colliders"
    )]
    pub fn set_density(&mut self, density: Real) -> Result<(), CaromError> {
        check_non_negative("density", density)?;
        let previous = self.density();
        self.collider().set_density(density);
        let body = self.body();
        if let Err(e) = self.world.rebuild_mass_of(body) {
            self.collider().set_density(previous);
            return Err(e);
        }
        let index = self.world.state.bodies.checked_index(body).expect("live");
        self.world.wake_body(index);
        Ok(())
    }

    /// Changes what the collider collides with: its contacts the new filter forbids end
    /// (reported after the next step), its body wakes, and the broadphase looks at it again
    /// for pairs the filter now allows.
    #[allow(
        clippy::expect_used,
        reason = "the collider was checked live when it was lent, and its body is live with it"
    )]
    pub fn set_filter(&mut self, filter: CollisionFilter) {
        self.collider().set_filter(filter);
        let world = &mut *self.world;
        let body = world
            .state
            .colliders
            .get(self.handle)
            .expect("lent live")
            .body();
        let colliders = &world.state.colliders;
        world.state.contacts.remove_where(body, |c| {
            let (Some(a), Some(b)) = (colliders.get(c.collider_a()), colliders.get(c.collider_b()))
            else {
                return false;
            };
            !a.filter().collides_with(&b.filter())
        });
        let index = world.state.bodies.checked_index(body).expect("live");
        world.wake_body(index);
        world.apply_touch_changes();
        world.state.broadphase.set_filter(self.handle, filter);
    }
}

impl Deref for ColliderMut<'_> {
    type Target = Collider;

    #[allow(
        clippy::expect_used,
        reason = "the collider was checked live when it was lent, and the loan holds the world"
    )]
    fn deref(&self) -> &Collider {
        self.world
            .state
            .colliders
            .get(self.handle)
            .expect("lent live")
    }
}
