//! Hit events: contacts that were struck hard, for sounds, damage and sparks.
//!
//! A collider asks for them ([`crate::ColliderDef::hit_events`]); after each step, every awake
//! contact of such a collider is looked at, and reports a hit if one of its points pushed
//! during the step (its [`crate::PointImpulse::total_normal_impulse`] is positive, so a
//! speculative point the bodies never reached does not count) and was approaching faster than
//! the world's [`crate::WorldSettings::hit_event_threshold`] as the step began. That is Box2D's
//! rule: a hit is reported on any step a fast approach is stopped, not only the step a contact
//! begins, so a ball bouncing on a floor reports each bounce. The fastest such point stands
//! for the contact. A world with no collider asking does none of this.

use crate::collision::contact::{BodyIndices, Contact, ContactPair};
use crate::dynamics::body::{Body, BodyKind};
use crate::math::{Real, Vec2};

/// A contact struck hard during the last step.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct HitEvent {
    /// The colliders and bodies struck together.
    pub pair: ContactPair,
    /// Where, in world coordinates: on the surface of the pair's static body if it has one
    /// (exact, as that body did not move), else on the first collider's surface, carried with
    /// its body through the step.
    pub point: Vec2,
    /// The contact normal, unit, from the first collider to the second.
    pub normal: Vec2,
    /// How fast the surfaces approached along the normal as the step began, m/s (above the
    /// world's threshold).
    pub approach_speed: Real,
}

/// The hits of the last step among the awake `contacts` (whose bodies are at `body_indices`
/// among `bodies`), into `out`, in contact order: the contacts of colliders asking for hits
/// whose fastest pushing point approached faster than `threshold`.
pub(crate) fn find_hits(
    contacts: &[Contact],
    body_indices: &[BodyIndices],
    bodies: &[Body],
    threshold: Real,
    out: &mut Vec<HitEvent>,
) {
    for (contact, &[a, b]) in contacts.iter().zip(body_indices) {
        if !contact.reports_hits() {
            continue;
        }
        let manifold = contact.manifold();
        let pushed = manifold.points().iter().zip(contact.point_impulses());
        let fastest = pushed
            .filter(|(_, i)| i.total_normal_impulse > 0.0 && -i.normal_velocity > threshold)
            .max_by(|(_, i), (_, j)| j.normal_velocity.total_cmp(&i.normal_velocity));
        let Some((fastest, impulse)) = fastest else {
            continue;
        };
        let (a, b) = (&bodies[a as usize], &bodies[b as usize]);
        let normal = manifold.normal;
        // The point lies midway between the surfaces as the step began; each surface is half
        // the separation from it along the normal.
        let half_gap = normal * (0.5 * fastest.separation);
        let point = if b.kind() == BodyKind::Static && a.kind() != BodyKind::Static {
            b.center_of_mass() + fastest.anchor_b + half_gap
        } else {
            a.center_of_mass() + fastest.anchor_a - half_gap
        };
        out.push(HitEvent {
            pair: contact.pair(),
            point,
            normal,
            approach_speed: -impulse.normal_velocity,
        });
    }
}
