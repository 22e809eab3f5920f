//! Cloning into old memory, for snapshots: `derive(Clone)` gives `clone_from` as a whole new
//! clone, which allocates every array again; a rollback loop that restores a world each frame
//! wants the old arrays filled in place.

/// Implements `Clone` field by field, its `clone_from` cloning each field into the old one
/// (so a `Vec` keeps its buffer, and a `Vec` of such values theirs). Fields under `roomy` are
/// lists whose length goes up and down from step to step (the contacts, a step's events, the
/// proxies it moved): `clone_from` copies them with the original's capacity
/// ([`copy_with_room`]), so copying into an old snapshot allocates only when the world's own
/// list has grown, while a clone holds only their items. Fields after `keep` are working
/// memory: a clone starts them empty and `clone_from` leaves them as they are. Every field is
/// named in a pattern without `..`, so a field added later fails to compile until it is
/// listed here.
macro_rules! clone_in_place {
    (
        $type:ident $(<$($generic:ident),*>)? { $($field:ident),* $(,)? }
        $(roomy { $($roomy:ident),* $(,)? })?
        $(keep { $($kept:ident),* $(,)? })?
    ) => {
        impl $(<$($generic: Clone),*>)? Clone for $type $(<$($generic),*>)? {
            fn clone(&self) -> Self {
                let $type {
                    $($field,)* $($($roomy,)*)? $($($kept: _,)*)?
                } = self;
                $type {
                    $($field: $field.clone(),)*
                    $($($roomy: $roomy.clone(),)*)?
                    $($($kept: Default::default(),)*)?
                }
            }

            fn clone_from(&mut self, source: &Self) {
                let $type {
                    $($field,)* $($($roomy,)*)? $($($kept: _,)*)?
                } = self;
                $($field.clone_from(&source.$field);)*
                $($($crate::clone_in_place::copy_with_room($roomy, &source.$roomy);)*)?
            }
        }
    };
}
pub(crate) use clone_in_place;

/// Copies `from` into `to` with room for as many items as `from` has room for, so a later
/// copy of a longer `from` (still within its own room) allocates nothing.
pub(crate) fn copy_with_room<T: Clone>(to: &mut Vec<T>, from: &Vec<T>) {
    to.clear();
    to.reserve_exact(from.capacity());
    to.extend_from_slice(from);
}
