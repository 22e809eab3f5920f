//! Cloning into old memory, for snapshots: `derive(Clone)` gives `clone_from` as a whole new
//! clone, which allocates every array again; a rollback loop that restores a world each frame
//! wants the old arrays filled in place.

/// Implements `Clone` field by field, its `clone_from` cloning each field into the old one
/// (so a `Vec` keeps its buffer, and a `Vec` of such values theirs). Fields after `keep` are
/// working memory: a clone starts them empty and `clone_from` leaves them as they are. Every
/// field is named in a pattern without `..`, so a field added later fails to compile until it
/// is listed here.
macro_rules! clone_in_place {
    (
        $type:ident $(<$($generic:ident),*>)? { $($field:ident),* $(,)? }
        $(keep { $($kept:ident),* $(,)? })?
    ) => {
        impl $(<$($generic: Clone),*>)? Clone for $type $(<$($generic),*>)? {
            fn clone(&self) -> Self {
                let $type { $($field,)* $($($kept: _,)*)? } = self;
                $type {
                    $($field: $field.clone(),)*
                    $($($kept: Default::default(),)*)?
                }
            }

            fn clone_from(&mut self, source: &Self) {
                let $type { $($field,)* $($($kept: _,)*)? } = self;
                $($field.clone_from(&source.$field);)*
            }
        }
    };
}
pub(crate) use clone_in_place;
