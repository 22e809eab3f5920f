//! Where each contact is stored: the awake contacts colour by colour (a touching contact takes
//! a graph colour and moves into its part), then the ones that do not touch, then the
//! sleeping ones (see `graph::layout`); moves between parts, and what a step reads of them.

use super::{BodyIndices, Contact, ContactSet, body_indices_of};
use crate::constants::CONTACTS_PER_TASK;
use crate::dynamics::body::{BodyHandle, BodyKind};
use crate::graph::colors::{ColorBody, NO_COLOR};
use crate::graph::layout::{ASLEEP, ColorRanges, NOT_TOUCHING, color_part, color_ranges};
use crate::parallel::for_each_with;
use crate::partition::shift_along;
use crate::solver_set::SolverSet;

impl ContactSet {
    /// Moves the contact at `from` along `path`, and the contacts on it one place back, with
    /// what is kept beside them (see [`crate::partition::Partition::move_item_along`]); their
    /// ids learn where they went.
    pub(super) fn shift(&mut self, from: usize, path: &[usize]) {
        shift_along(&mut self.contacts, from, path);
        shift_along(&mut self.body_indices, from, path);
        shift_along(&mut self.ids, from, path);
        for &index in std::iter::once(&from).chain(path) {
            self.slots[self.ids[index] as usize].index = index as u32;
        }
    }

    /// Moves the contact at `index` into part `to`; returns its new index.
    pub(super) fn move_part(&mut self, index: usize, to: usize) -> usize {
        let mut parts = self.parts;
        let index = parts.move_item_along(index, to, |from, path| self.shift(from, path));
        self.parts = parts;
        index
    }

    /// The set of the contact at `index`.
    pub(super) fn set_of(&self, index: usize) -> SolverSet {
        if index < self.parts.start(ASLEEP) {
            SolverSet::Awake
        } else {
            SolverSet::Asleep
        }
    }

    /// Gives the awake touching contact at `index` a colour and moves it into the colour's
    /// part; returns its new index.
    pub(in crate::collision) fn paint(
        &mut self,
        index: usize,
        kinds: &impl Fn(BodyHandle) -> BodyKind,
    ) -> usize {
        let contact = &self.contacts[index];
        debug_assert!(contact.touching && contact.color == NO_COLOR);
        let side = |body: BodyHandle| ColorBody {
            slot: body.index(),
            dynamic: kinds(body) == BodyKind::Dynamic,
        };
        let (a, b) = (side(contact.body_a), side(contact.body_b));
        let color = self.colors.add(a, b);
        let contact = &mut self.contacts[index];
        contact.color = color;
        contact.color_holds = [a.dynamic, b.dynamic];
        self.move_part(index, color_part(color))
    }

    /// Takes the contact at `index` out of its colour, if it has one, freeing there the
    /// bodies it held (whatever their kind is now), into the awake part that does not touch;
    /// returns its new index.
    pub(in crate::collision) fn unpaint(&mut self, index: usize) -> usize {
        let contact = &mut self.contacts[index];
        if contact.color == NO_COLOR {
            return index;
        }
        let color = contact.color;
        contact.color = NO_COLOR;
        let side = |body: BodyHandle, held: bool| ColorBody {
            slot: body.index(),
            dynamic: held,
        };
        let [held_a, held_b] = contact.color_holds;
        let (a, b) = (side(contact.body_a, held_a), side(contact.body_b, held_b));
        self.colors.remove(color, a, b);
        self.move_part(index, NOT_TOUCHING)
    }

    /// Moves the contact at `index` into `set`; returns its new index. A touching contact
    /// takes a colour in the awake set and gives it back in the sleeping one.
    pub(super) fn move_to(
        &mut self,
        index: usize,
        set: SolverSet,
        kinds: &impl Fn(BodyHandle) -> BodyKind,
    ) -> usize {
        if self.set_of(index) == set {
            return index;
        }
        let touching = self.contacts[index].touching;
        if set == SolverSet::Asleep {
            self.asleep_touching += usize::from(touching);
            let index = self.unpaint(index);
            self.move_part(index, ASLEEP)
        } else {
            self.asleep_touching -= usize::from(touching);
            let index = self.move_part(index, NOT_TOUCHING);
            if touching {
                self.paint(index, kinds)
            } else {
                index
            }
        }
    }

    /// Files each contact of `body` in the awake set if one of its bodies is awake, else in
    /// the sleeping set; `bodies` tells each body's set and kind.
    pub(crate) fn refile(
        &mut self,
        body: BodyHandle,
        bodies: impl Fn(BodyHandle) -> (SolverSet, BodyKind),
    ) {
        let kinds = |b: BodyHandle| bodies(b).1;
        let awake = |b: BodyHandle| bodies(b).0 == SolverSet::Awake;
        self.for_each_of(body, |set, index| {
            let contact = &set.contacts[index];
            let to = if awake(contact.body_a) || awake(contact.body_b) {
                SolverSet::Awake
            } else {
                SolverSet::Asleep
            };
            set.move_to(index, to, &kinds);
        });
    }

    /// Colours each of a body's awake touching contacts again, after its kind changed (a body
    /// that became static frees its colours, one that became dynamic takes its own).
    pub(crate) fn repaint(&mut self, body: BodyHandle, kinds: impl Fn(BodyHandle) -> BodyKind) {
        self.for_each_of(body, |set, index| {
            if set.contacts[index].color != NO_COLOR {
                let index = set.unpaint(index);
                set.paint(index, &kinds);
            }
        });
    }

    /// The indices of the awake contacts (a body of the pair is awake): the first ones.
    pub(in crate::collision) fn awake_range(&self) -> std::ops::Range<usize> {
        0..self.parts.start(ASLEEP)
    }

    /// How many contacts are in the awake set.
    #[cfg(any(test, all(feature = "testing", feature = "serde")))]
    pub(crate) fn awake_len(&self) -> usize {
        self.awake_range().end
    }

    /// The part of the contact at `index`, for tests of the layout.
    #[cfg(any(test, all(feature = "testing", feature = "serde")))]
    pub(crate) fn part_of(&self, index: usize) -> usize {
        self.parts.part_of(index)
    }

    /// How many sleeping contacts touch, as counted while filing them.
    #[cfg(any(test, all(feature = "testing", feature = "serde")))]
    pub(crate) fn asleep_touching(&self) -> usize {
        self.asleep_touching
    }

    /// Finds where the awake contacts' bodies are among all bodies (`dense_index`), on all
    /// threads: once a step, after the narrowphase and the wakes and links it caused, when
    /// no body changes set again before the solver reads them.
    pub(crate) fn find_body_indices(&mut self, dense_index: impl Fn(BodyHandle) -> usize + Sync) {
        let awake = self.awake_range();
        let (contacts, indices) = (&self.contacts[awake.clone()], &mut self.body_indices[awake]);
        for_each_with(contacts, indices, CONTACTS_PER_TASK, |contact, indices| {
            *indices = body_indices_of(contact, &dense_index);
        });
    }

    /// The bodies of every awake contact that touches (the overflow's and the colours'), in
    /// memory order: what splitting a large island reads.
    pub(crate) fn awake_touching_bodies(&self) -> impl Iterator<Item = [BodyHandle; 2]> + '_ {
        self.contacts[..self.parts.start(NOT_TOUCHING)]
            .iter()
            .map(|contact| [contact.body_a, contact.body_b])
    }

    /// Where each colour's contacts (then the overflow's) are among the awake contacts.
    pub(crate) fn color_ranges(&self) -> ColorRanges {
        color_ranges(&self.parts)
    }

    /// The awake contacts and where their bodies are (current from the narrowphase until the
    /// step ends).
    pub(crate) fn awake_and_bodies(&self) -> (&[Contact], &[BodyIndices]) {
        let awake = self.awake_range();
        (&self.contacts[awake.clone()], &self.body_indices[awake])
    }

    /// The awake contacts, mutably, for the solver, where their bodies are, and where each
    /// colour's contacts are among them.
    pub(crate) fn awake_mut_and_colors(&mut self) -> (&mut [Contact], &[BodyIndices], ColorRanges) {
        let awake = self.awake_range();
        let colors = self.color_ranges();
        (
            &mut self.contacts[awake.clone()],
            &self.body_indices[awake],
            colors,
        )
    }

    /// How many contacts touch: the awake ones coloured, the sleeping ones remembered.
    pub(crate) fn touching_count(&self) -> usize {
        self.awake_range().len() - self.parts.range(NOT_TOUCHING).len() + self.asleep_touching
    }
}
