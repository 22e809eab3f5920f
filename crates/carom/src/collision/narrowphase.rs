//! The narrowphase stage: each step, every awake contact's manifold is rebuilt from its
//! bodies' world shapes (or carried along while the pair barely moved), on as many threads as
//! rayon gives; then, serially and in a fixed order, the contacts whose state changed are
//! filed again: destroyed when their boxes parted, coloured as they start touching, and
//! reported as events, with the sleeping islands a moving body stirred listed to wake.
//! Box2D's `b2Collide` and `b2UpdateContact`.

use crate::capacity::room;
use crate::collision::broadphase::{FatBoxes, kinds_can_collide};
use crate::collision::contact::{Contact, ContactEvent, ContactSet};
use crate::collision::pre_solve::{PreSolveContact, PreSolveHook};
use crate::collision::recycle::ManifoldFrame;
use crate::constants::{
    CONTACTS_AHEAD, CONTACTS_PER_TASK, PREFETCH_AHEAD, PREFETCH_MIN_CONTACTS, TOUCH_BEGIN,
    TOUCH_END,
};
use crate::dynamics::body::{self, Body, BodyHandle, BodyKind};
use crate::dynamics::collider::{Collider, ColliderHandle};
use crate::geometry::query::collide;
use crate::geometry::query::manifold::{Manifold, Margins};
use crate::handle_map::HandleMap;
use crate::math::Real;
use crate::parallel::for_each_chunk_mut_with;
use crate::prefetch::{prefetch, prefetch_head};
use crate::stats::CollisionWork;
use std::collections::TryReserveError;

/// How the narrowphase builds manifolds this step.
#[derive(Debug, Clone, Copy)]
pub(crate) struct ManifoldOptions<'a> {
    /// Points are kept up to this far apart, m (the speculative distance).
    pub margin: Real,
    /// How far ahead a face point may look: it is kept while the pair could close its gap
    /// within that time at their present speeds.
    pub prediction: LookAhead,
    /// Carry a manifold along while its pair has moved less than this relative to each other
    /// since it was built, m, instead of building it again (`None`: build every manifold).
    pub recycling: Option<Real>,
    /// The world's pre-solve hook, asked about the contacts of colliders that opted in.
    pub pre_solve: Option<&'a PreSolveHook>,
}

/// How far ahead, s, contacts look this step: as far as a pair can close in that time, a face
/// point is kept, and a moving body's broadphase box covers where it can go (0 keeps points
/// within the margin only, and boxes where their bodies are).
#[derive(Debug, Clone, Copy)]
pub(crate) struct LookAhead {
    /// For every body: the step, when the world looks ahead.
    every: Real,
    /// For a body that asks to ([`crate::BodyDef::look_ahead`]): the step, with continuous
    /// collision on.
    asked: Real,
}

impl LookAhead {
    /// A step of `dt` in a world with continuous collision on or off, that looks ahead or not.
    pub(crate) fn new(continuous: bool, world_looks_ahead: bool, dt: Real) -> Self {
        let asked = if continuous { dt } else { 0.0 };
        LookAhead {
            every: if world_looks_ahead { asked } else { 0.0 },
            asked,
        }
    }

    /// How far ahead `body`'s broadphase box reaches.
    pub(crate) fn for_body(&self, body: &Body) -> Real {
        if body.looks_ahead() {
            self.asked
        } else {
            self.every
        }
    }

    /// How far ahead the contact of `a` and `b` looks: as the one that looks farther.
    fn for_pair(&self, a: &Body, b: &Body) -> Real {
        self.for_body(a).max(self.for_body(b))
    }
}

/// What updating one contact's manifold found.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Refresh {
    /// Nothing moves: left as it was.
    Unchanged,
    /// A body is gone, or the pair can no longer touch: the contact ends.
    Gone,
    /// The manifold was rebuilt (or carried along).
    Updated {
        /// Its deepest overlap (0 if it does not touch).
        depth: Real,
        /// Its manifold gained its first points or lost its last, or the shapes began or
        /// stopped touching.
        changed: bool,
        /// Whether the shapes touch now, as events report it.
        in_contact: bool,
        /// It touches a sleeping body that the other body stirs.
        wakes: bool,
        /// The manifold was carried along, not built.
        recycled: bool,
    },
}

/// The narrowphase's memory, kept from step to step so a step allocates nothing.
#[derive(Debug, Clone, Default)]
pub(crate) struct Narrowphase {
    /// What the last update found for each awake contact.
    refresh: Vec<Refresh>,
    /// The contacts it must then file again, by id.
    changed: Vec<(u32, Refresh)>,
}

impl Narrowphase {
    /// Makes room for `contacts` awake contacts.
    pub(crate) fn reserve(&mut self, contacts: usize) -> Result<(), TryReserveError> {
        room(&mut self.refresh, contacts)?;
        room(&mut self.changed, contacts)
    }

    /// The narrowphase stage, over the awake set: rebuilds every manifold from the bodies'
    /// world shapes, carries impulses over by feature id, reports touching changes, and drops
    /// contacts whose fat boxes no longer overlap (or whose bodies can no longer collide).
    /// Sleeping contacts are not visited. Sleeping islands touched by a moving body are added
    /// to `wake`. Returns the deepest penetration seen, and counts what it did into `work`.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn update(
        &mut self,
        set: &mut ContactSet,
        bodies: &HandleMap<BodyHandle, Body>,
        colliders: &HandleMap<ColliderHandle, Collider>,
        fat_boxes: FatBoxes<'_>,
        options: ManifoldOptions,
        wake: &mut Vec<u32>,
        work: &mut CollisionWork,
    ) -> Real {
        // First every manifold, on as many threads as rayon gives (each contact on its own),
        // then the bookkeeping that touches the whole set, in order, for the contacts that
        // need it: those that end, start or stop touching, or wake a sleeper.
        let awake = set.awake_range();
        self.refresh.clear();
        self.refresh.resize(awake.len(), Refresh::Unchanged);
        let ahead = if awake.len() >= PREFETCH_MIN_CONTACTS {
            PREFETCH_AHEAD
        } else {
            0
        };
        let contacts = &mut set.contacts[awake];
        for_each_chunk_mut_with(
            contacts,
            &mut self.refresh,
            CONTACTS_PER_TASK,
            |contacts, out| {
                for (index, refresh) in out.iter_mut().enumerate() {
                    // What a contact a few ahead reads is asked for now, so that those reads
                    // overlap this contact's work instead of each stalling in turn (in a set
                    // too large to stay cached); the contacts themselves farther ahead still,
                    // as their bodies are asked for from them.
                    if ahead > 0 {
                        if let Some(far) = contacts.get(index + CONTACTS_AHEAD * ahead) {
                            prefetch(far);
                        }
                        if let Some(ahead) = contacts.get(index + ahead) {
                            fetch_ahead(ahead, bodies, fat_boxes);
                        }
                    }
                    *refresh = refresh_manifold(
                        &mut contacts[index],
                        bodies,
                        colliders,
                        fat_boxes,
                        options,
                    );
                }
            },
        );
        let mut deepest: Real = 0.0;
        self.changed.clear();
        // Listed by id first, as filing them again moves contacts.
        for (index, &refresh) in self.refresh.iter().enumerate() {
            match refresh {
                Refresh::Unchanged => continue,
                Refresh::Gone => work.contacts_destroyed += 1,
                Refresh::Updated {
                    depth,
                    changed,
                    wakes,
                    recycled,
                    ..
                } => {
                    if recycled {
                        work.manifolds_recycled += 1;
                    } else {
                        work.manifolds_built += 1;
                    }
                    deepest = deepest.max(depth);
                    if !(changed || wakes) {
                        continue;
                    }
                }
            }
            self.changed.push((set.id_at(index), refresh));
        }
        // Filed by id, as Box2D files them: the colour a contact takes, the order islands
        // join in and the events' order follow from the ids alone, not from where contacts
        // happen to sit in the array (which moves as they change part). Highest first: a
        // pile made at once is then coloured from its last contact back, as array order did.
        self.changed
            .sort_unstable_by_key(|&(id, _)| std::cmp::Reverse(id));
        let touch_changes = (set.began.len(), set.ended.len());
        for &(id, refresh) in &self.changed {
            file(set, set.index_of(id), refresh, bodies, colliders, wake);
        }
        work.touches_began += set.began.len() - touch_changes.0;
        work.touches_ended += set.ended.len() - touch_changes.1;
        deepest
    }
}

/// Files again the contact at `index`, which the narrowphase found `refresh`: destroys it,
/// colours it as its manifold gains points or takes its colour as it loses them, raises
/// the events as the shapes begin or stop touching, and adds to `wake` the sleeping islands
/// it stirs.
fn file(
    set: &mut ContactSet,
    index: usize,
    refresh: Refresh,
    bodies: &HandleMap<BodyHandle, Body>,
    colliders: &HandleMap<ColliderHandle, Collider>,
    wake: &mut Vec<u32>,
) {
    let (wakes, in_contact) = match refresh {
        Refresh::Unchanged => return,
        Refresh::Gone => return set.destroy(index, true),
        Refresh::Updated {
            wakes, in_contact, ..
        } => (wakes, in_contact),
    };
    let contact = &mut set.contacts[index];
    // Both colliders were there a moment ago (else the contact would be gone).
    let (Some(a), Some(b)) = (
        colliders.get(contact.collider_a),
        colliders.get(contact.collider_b),
    ) else {
        return;
    };
    let all = bodies.as_slice();
    let (a, b) = (&all[a.body_index()], &all[b.body_index()]);
    if wakes {
        for (sleeper, other) in [(a, b), (b, a)] {
            if stirred(sleeper, other) {
                wake.extend(sleeper.island());
            }
        }
    }
    if in_contact != contact.in_contact {
        contact.in_contact = in_contact;
        let pair = contact.pair();
        set.events.push(if in_contact {
            ContactEvent::Begin(pair)
        } else {
            ContactEvent::End(pair)
        });
    }
    let touching = !contact.manifold.is_empty();
    if touching == contact.touching {
        return;
    }
    set.set_touching(index, touching);
    let kinds = [(a.handle(), a.kind()), (b.handle(), b.kind())];
    let bodies = (a.handle(), b.handle());
    if touching {
        set.began.push(bodies);
        set.paint(index, &|body| {
            kinds
                .iter()
                .find(|k| k.0 == body)
                .map_or(BodyKind::Static, |k| k.1)
        });
    } else {
        set.ended.push(bodies);
        set.unpaint(index);
    }
}

/// Asks for the memory that refreshing `contact` reads first: its bodies' heads and its
/// colliders' broadphase proxies.
fn fetch_ahead(contact: &Contact, bodies: &HandleMap<BodyHandle, Body>, fat_boxes: FatBoxes<'_>) {
    for body in [contact.body_a(), contact.body_b()] {
        if let Some(body) = bodies.get(body) {
            prefetch_head(body, body::HEAD_BYTES);
        }
    }
    fat_boxes.prefetch(contact.collider_a, contact.collider_b);
}

/// True when `body` can disturb a sleeping body it touches: it is awake and dynamic, or
/// kinematic and moving. A still kinematic platform lets what rests on it sleep.
fn stirs(body: &Body) -> bool {
    match body.kind() {
        BodyKind::Dynamic => !body.is_sleeping(),
        BodyKind::Kinematic => {
            body.linear_velocity() != crate::math::Vec2::zeros() || body.angular_velocity() != 0.0
        }
        BodyKind::Static => false,
    }
}

/// True when `sleeper` sleeps and `other`, touching it, should wake it.
fn stirred(sleeper: &Body, other: &Body) -> bool {
    sleeper.is_sleeping() && stirs(other)
}

/// The fastest two bodies' surfaces can close on each other: their relative speed, and each
/// one's spin times its farthest point.
fn closing_speed(a: &Body, b: &Body) -> Real {
    let turning = |body: &Body| body.angular_velocity().abs() * body.reach();
    (b.linear_velocity() - a.linear_velocity()).norm() + turning(a) + turning(b)
}

/// Rebuilds one contact's manifold if either body moves (or, `recycling`, carries the last one
/// along if they barely moved relative to each other); says whether the contact lives on.
/// A manifold carried along reads the contact, its bodies and their fat boxes, not its
/// colliders: those are read only to build one (or to show the pre-solve hook).
fn refresh_manifold(
    contact: &mut Contact,
    bodies: &HandleMap<BodyHandle, Body>,
    colliders: &HandleMap<ColliderHandle, Collider>,
    fat_boxes: FatBoxes<'_>,
    options: ManifoldOptions,
) -> Refresh {
    let ManifoldOptions {
        margin,
        prediction,
        recycling,
        pre_solve,
    } = options;
    let (Some(a), Some(b)) = (bodies.get(contact.body_a()), bodies.get(contact.body_b())) else {
        return Refresh::Gone;
    };
    if !a.moves() && !b.moves() {
        return Refresh::Unchanged;
    }
    if !kinds_can_collide(a.kind(), b.kind())
        || !fat_boxes.may_keep(contact.collider_a, contact.collider_b)
    {
        return Refresh::Gone;
    }
    // A body stopped by continuous collision barely moved, but only because it was put back:
    // its manifold may lack the points its motion was about to meet.
    let stopped = a.had_time_of_impact() || b.had_time_of_impact();
    let carried = |distance| contact.frame.carry(&mut contact.manifold, a, b, distance);
    if !stopped && recycling.is_some_and(carried) {
        return settled(contact, colliders, [a, b], pre_solve, true);
    }
    let (Some(shape_a), Some(shape_b)) = (
        colliders.get(contact.collider_a),
        colliders.get(contact.collider_b),
    ) else {
        return Refresh::Gone;
    };
    let ahead = prediction.for_pair(a, b);
    let margins = Margins {
        any: margin,
        face: if ahead > 0.0 {
            margin + closing_speed(a, b) * ahead
        } else {
            margin
        },
    };
    collide::update(
        shape_a.world_shape(),
        shape_b.world_shape(),
        margins,
        &mut contact.manifold,
    );
    contact
        .manifold
        .set_anchors(a.center_of_mass(), b.center_of_mass());
    if contact.manifold.is_empty() {
        // Apart: a rolling resistance met again starts over, as the points' impulses do.
        contact.rolling_impulse = 0.0;
    }
    contact.frame = ManifoldFrame::of(
        &contact.manifold,
        (a, shape_a),
        (b, shape_b),
        &contact.frame,
    );
    settled(contact, colliders, [a, b], pre_solve, false)
}

/// Asks the pre-solve `hook`, if the contact's colliders opted in and its manifold has points,
/// whether it is solved this step; one turned down loses its points (and with them what it
/// would warm start from) and its recycling frame, so next step builds it afresh. Then what
/// the bookkeeping needs to know of it (`recycled`: its manifold was carried along).
#[inline]
fn settled(
    contact: &mut Contact,
    colliders: &HandleMap<ColliderHandle, Collider>,
    bodies: [&Body; 2],
    hook: Option<&PreSolveHook>,
    recycled: bool,
) -> Refresh {
    if let Some(hook) = hook
        && contact.pre_solve
        && !contact.manifold.is_empty()
        && let (Some(a), Some(b)) = (
            colliders.get(contact.collider_a),
            colliders.get(contact.collider_b),
        )
    {
        let shown = PreSolveContact {
            pair: contact.pair(),
            manifold: &contact.manifold,
            colliders: [a, b],
            bodies,
        };
        if !hook.allows(&shown) {
            contact.manifold = Manifold::default();
            contact.frame = ManifoldFrame::default();
        }
    }
    updated(contact, bodies[0], bodies[1], recycled)
}

/// What the bookkeeping after the narrowphase needs to know of a contact of bodies `a` and
/// `b` whose manifold was just updated (`recycled`: carried along).
fn updated(contact: &Contact, a: &Body, b: &Body, recycled: bool) -> Refresh {
    let touching = !contact.manifold.is_empty();
    let closest = contact.manifold.min_separation();
    // Hysteresis: closer than TOUCH_BEGIN to begin, within TOUCH_END to go on.
    let reach = if contact.in_contact {
        TOUCH_END
    } else {
        TOUCH_BEGIN
    };
    let in_contact = closest.is_some_and(|s| s <= reach);
    Refresh::Updated {
        depth: if touching {
            -closest.unwrap_or(0.0)
        } else {
            0.0
        },
        changed: touching != contact.touching || in_contact != contact.in_contact,
        in_contact,
        wakes: touching && (stirred(a, b) || stirred(b, a)),
        recycled,
    }
}
