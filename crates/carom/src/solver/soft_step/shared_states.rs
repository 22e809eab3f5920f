//! The body states while soft step solves a pass of graph colours, shared by the threads that
//! solve it.
//!
//! The threads write the states in place, as Box2D's do: no two constraints of one colour
//! share a body the solver moves (the colouring guarantees it, and
//! [`crate::graph::order::ColorCheck`] checks it again as the step's order is built, sending
//! any constraint that would break it to the overflow, solved on one thread), static and
//! kinematic bodies are only read, and a colour starts only once the one before it is finished
//! (an acquire-release barrier between stages, [`super::scheduler::run_stages`]). So within a
//! colour each state has at most one writer and no other reader: plain loads and stores, no
//! atomics, which lets the solver load a body in one or two vector loads instead of eight
//! scalar ones.
//!
//! The promise is made once per step, where the solver's stages borrow the states
//! ([`SharedStates::new`], in `WideContacts::execute`); the loads and stores of single states
//! are then safe to call. A stage that changes whole runs of states (integration, or the
//! overflow solved one by one) borrows them with [`SharedStates::range_mut`], promising that no
//! other thread touches them meanwhile (the stages around it are over, and no other block of it
//! holds them). All of carom's `unsafe` code is in this folder: this module, the executor of
//! the stages (`super::executor`), which makes those promises, its entry
//! (`WideContacts::execute`), and the AVX lanes (`super::lanes::avx`).
#![allow(unsafe_code)]

use crate::math::Real;
use crate::solver::body_state::BodyState;
use crate::solver::soft_step::lanes::Lane;
use std::marker::PhantomData;

/// A mutable borrow of the body states, readable and writable from several threads under the
/// rule above.
pub(crate) struct SharedStates<'a> {
    states: *mut BodyState,
    len: usize,
    _borrow: PhantomData<&'a mut [BodyState]>,
}

// SAFETY: whoever made the `SharedStates` promised that no state is written by one thread
// while another reads or writes it.
unsafe impl Send for SharedStates<'_> {}
// SAFETY: as for `Send`.
unsafe impl Sync for SharedStates<'_> {}

impl<'a> SharedStates<'a> {
    /// Borrows the states for the length of a pass.
    ///
    /// # Safety
    /// While the borrow lasts, no state is written by one thread while another reads or
    /// writes it.
    pub(crate) unsafe fn new(states: &'a mut [BodyState]) -> Self {
        SharedStates {
            states: states.as_mut_ptr(),
            len: states.len(),
            _borrow: PhantomData,
        }
    }

    /// State `index` as eight floats: `[v.x, v.y, w, held, dp.x, dp.y, dq.cos, dq.sin]`
    /// (`held`'s bits, which the solver ignores).
    #[inline(always)]
    pub(crate) fn read(&self, index: u32) -> [Real; 8] {
        let index = index as usize;
        assert!(index < self.len, "state {index} of {}", self.len);
        // SAFETY: in bounds (checked), aligned, and `BodyState` is eight `Real`s in this order
        // (asserted beside its definition); no other thread writes it (promised in `new`).
        unsafe { std::ptr::read(self.states.add(index).cast::<[Real; 8]>()) }
    }

    /// State `index` as eight lanes' floats, in [`read`](Self::read)'s order: the same floats
    /// where a lane is as wide as [`Real`], else each rounded to the nearest (the solver's
    /// values are relative to the body, so this loses nothing a contact needs).
    #[inline(always)]
    pub(crate) fn read_lanes(&self, index: u32) -> [Lane; 8] {
        let [v_x, v_y, w, held, dp_x, dp_y, cos, sin] = self.read(index);
        // Float by float: an array `map` here stays a call in WebAssembly builds.
        let (v_x, v_y, w, held) = (v_x as Lane, v_y as Lane, w as Lane, held as Lane);
        let (dp_x, dp_y, cos, sin) = (dp_x as Lane, dp_y as Lane, cos as Lane, sin as Lane);
        [v_x, v_y, w, held, dp_x, dp_y, cos, sin]
    }

    /// State `index`, copied (for a joint, which works on its own copies of two states).
    #[inline(always)]
    pub(crate) fn get(&self, index: usize) -> BodyState {
        assert!(index < self.len, "state {index} of {}", self.len);
        // SAFETY: in bounds (checked) and aligned; no other thread writes it (promised in
        // `new`).
        unsafe { std::ptr::read(self.states.add(index)) }
    }

    /// Sets state `index`'s velocities from `state` (a joint's copy, solved).
    #[inline(always)]
    pub(crate) fn set_velocity(&self, index: usize, state: &BodyState) {
        let velocity = [state.v.x, state.v.y, state.w, 0.0];
        self.write_velocity(index as u32, velocity);
    }

    /// Sets state `index`'s motion since the step began (`dp`, `dq`) from `state` (a joint
    /// tree's copy, its drift projected away); its velocities stay as they were.
    #[inline(always)]
    pub(crate) fn set_motion(&self, index: usize, state: &BodyState) {
        assert!(index < self.len, "state {index} of {}", self.len);
        // SAFETY: in bounds (checked).
        let target = unsafe { self.states.add(index) };
        // SAFETY: in bounds (checked) and aligned; no other thread touches it (promised in
        // `new`).
        unsafe {
            std::ptr::addr_of_mut!((*target).dp).write(state.dp);
            std::ptr::addr_of_mut!((*target).dq).write(state.dq);
        }
    }

    /// States `range`, to change whole (integration, the overflow's one-by-one solve).
    ///
    /// # Safety
    /// No other thread reads or writes these states while the borrow lasts.
    #[inline]
    #[allow(clippy::mut_from_ref)]
    pub(crate) unsafe fn range_mut(&self, range: std::ops::Range<usize>) -> &mut [BodyState] {
        assert!(
            range.start <= range.end && range.end <= self.len,
            "states {range:?}"
        );
        // SAFETY: in bounds (checked); nobody else touches them meanwhile (the caller's promise).
        unsafe { std::slice::from_raw_parts_mut(self.states.add(range.start), range.len()) }
    }

    /// Sets state `index`'s velocities from lanes' floats `[v.x, v.y, w, _]`, as
    /// [`write_velocity`](Self::write_velocity).
    #[inline(always)]
    pub(crate) fn write_lane_velocity(&self, index: u32, velocity: [Lane; 4]) {
        let [v_x, v_y, w, spare] = velocity;
        self.write_velocity(index, [v_x as Real, v_y as Real, w as Real, spare as Real]);
    }

    /// Sets state `index`'s velocities from `[v.x, v.y, w, _]`; its `held` stays as it was
    /// (the joints' warm start reads it after the contacts have solved).
    #[inline(always)]
    pub(crate) fn write_velocity(&self, index: u32, velocity: [Real; 4]) {
        let index = index as usize;
        assert!(index < self.len, "state {index} of {}", self.len);
        let [v_x, v_y, w, _] = velocity;
        // SAFETY: in bounds (checked), aligned, the first three floats of a `BodyState` are
        // `v.x, v.y, w`; no other thread touches it (promised in `new`).
        unsafe { std::ptr::write(self.states.add(index).cast::<[Real; 3]>(), [v_x, v_y, w]) }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::{Rot, Vec2};

    #[test]
    fn a_state_reads_as_its_eight_floats_and_takes_its_velocity() {
        let mut states = vec![BodyState::spare(); 3];
        states[1] = BodyState {
            v: Vec2::new(1.0, 2.0),
            w: 3.0,
            held: 1,
            dp: Vec2::new(5.0, 6.0),
            dq: Rot::from_cos_sin_unchecked(0.6, 0.8),
        };
        // SAFETY: one thread.
        let shared = unsafe { SharedStates::new(&mut states) };
        let held = Real::from_bits(1);
        assert_eq!(shared.read(1), [1.0, 2.0, 3.0, held, 5.0, 6.0, 0.6, 0.8]);
        shared.write_velocity(1, [7.0, 8.0, 9.0, 0.0]);
        assert_eq!((states[1].v, states[1].w), (Vec2::new(7.0, 8.0), 9.0));
        assert_eq!(states[1].held, 1, "the velocities' store leaves `held` be");
        assert_eq!(states[1].dp, Vec2::new(5.0, 6.0));
    }

    #[test]
    #[should_panic(expected = "state 3 of 3")]
    fn an_index_past_the_end_panics() {
        let mut states = vec![BodyState::spare(); 3];
        // SAFETY: one thread.
        let shared = unsafe { SharedStates::new(&mut states) };
        shared.read(3);
    }
}
