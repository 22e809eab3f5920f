//! The package's worlds, each in a slot that a JS `World` owns and its handles name.
//!
//! A handle (a body, a collider, a joint) keeps only its world's key and its own id, never the
//! world: freeing a `World` frees its memory at once, whatever handles JavaScript still holds,
//! and those handles then answer with an error that says so. Slots are generational, so a key
//! never reaches a world created later in a freed world's slot.

use crate::sim::Sim;
use std::cell::RefCell;
use wasm_bindgen::JsError;

/// Which world a handle belongs to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct WorldKey {
    index: u32,
    generation: u32,
}

impl WorldKey {
    /// The key's two numbers, as a handle's hidden key carries them.
    pub(crate) fn parts(self) -> [u32; 2] {
        [self.index, self.generation]
    }

    /// A key from [`WorldKey::parts`]; a made-up one reaches no world.
    pub(crate) fn from_parts([index, generation]: [u32; 2]) -> Self {
        WorldKey { index, generation }
    }
}

struct Slot {
    generation: u32,
    sim: Option<Sim>,
}

thread_local! {
    static WORLDS: RefCell<Vec<Slot>> = const { RefCell::new(Vec::new()) };
}

/// Keeps `sim` until [`remove`] and answers its key.
pub(crate) fn insert(sim: Sim) -> WorldKey {
    WORLDS.with_borrow_mut(|slots| {
        if let Some(index) = slots.iter().position(|slot| slot.sim.is_none()) {
            let slot = &mut slots[index];
            slot.generation = slot.generation.wrapping_add(1);
            slot.sim = Some(sim);
            return WorldKey {
                index: index as u32,
                generation: slot.generation,
            };
        }
        slots.push(Slot {
            generation: 0,
            sim: Some(sim),
        });
        WorldKey {
            index: (slots.len() - 1) as u32,
            generation: 0,
        }
    })
}

/// Drops the world under `key`, if it is still there.
pub(crate) fn remove(key: WorldKey) {
    // No JavaScript runs while a world is borrowed (inputs are read before, and outputs are
    // fresh plain objects), so the borrow is free here. Were it not, the world would stay
    // until the page closes: a leak, not a trap.
    let _ = WORLDS.try_with(|worlds| {
        if let Ok(mut slots) = worlds.try_borrow_mut()
            && let Some(slot) = slots.get_mut(key.index as usize)
            && slot.generation == key.generation
        {
            slot.sim = None;
        }
    });
}

/// Runs `f` on the world under `key`; `what` names the caller for the error when that world
/// was freed ("this body's world").
pub(crate) fn with<R>(
    key: WorldKey,
    what: &str,
    f: impl FnOnce(&mut Sim) -> Result<R, JsError>,
) -> Result<R, JsError> {
    WORLDS.with(|worlds| {
        let Ok(mut slots) = worlds.try_borrow_mut() else {
            return Err(JsError::new(
                "carom was called from inside another call to carom (a getter of an object \
                 passed to it?)",
            ));
        };
        match slots.get_mut(key.index as usize) {
            Some(Slot {
                generation,
                sim: Some(sim),
            }) if *generation == key.generation => f(sim),
            _ => Err(JsError::new(&format!("{what} was freed"))),
        }
    })
}

/// How many worlds are alive, for the tests of freeing.
pub(crate) fn live_worlds() -> usize {
    WORLDS.with_borrow(|slots| slots.iter().filter(|slot| slot.sim.is_some()).count())
}
