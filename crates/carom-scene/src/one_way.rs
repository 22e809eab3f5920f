//! One-way platforms: colliders that hold what comes down onto their top and let everything
//! else through, made of carom's pre-solve hook (Box2D's Platformer sample's rule).
//!
//! A scene marks a collider `one_way`; the loader has it show its contacts to the pre-solve
//! hook (the only colliders of a scene that do) and installs [`solid_from_above`] when there
//! are any. A platform's up is its collider's +y, turned by the collider's angle in its body
//! and by the body's rotation, so a tilted or turning platform's top is where its +y points.
//! A contact is solved while its normal, pointed from the platform to the other collider, is
//! within about 18° of up (a cosine above 0.95, Box2D's figure): something resting on the top
//! or coming down onto it. Otherwise (a body coming up from below or in from a side, whose
//! normal points down or sideways) the contact is disabled for the step and the body passes.
//! A body thrown up through a platform is caught once more than half of it is through (the
//! shortest way out, and so the normal, turns to the top) and pushed out onto it, where it
//! lands.
//!
//! Box2D's sample also keeps a contact solid while its shapes are still apart; not here:
//! carom's contacts look a whole step ahead, and a speculative point under a platform would
//! stop a body thrown up at it.

use carom::{PreSolveContact, Real, vec2};

/// The least cosine between a contact's normal and a platform's up for the contact to hold.
const SOLID_COSINE: Real = 0.95;

/// The pre-solve hook of a scene's one-way platforms (the colliders that show their contacts
/// to it): true, solving the contact, when the other collider is on top of every platform of
/// the pair.
pub(crate) fn solid_from_above(contact: &PreSolveContact) -> bool {
    // The normal points from the first collider to the second.
    let normal = contact.manifold.normal;
    let outward = [normal, -normal];
    (0..2).all(|side| {
        let (collider, body) = (contact.colliders[side], contact.bodies[side]);
        if !collider.pre_solve() {
            return true;
        }
        let up = body.rotation() * collider.local_transform().rotation * vec2(0.0, 1.0);
        outward[side].dot(&up) > SOLID_COSINE
    })
}
