//! Box2D's heap where the bench can count it. Box2D takes memory through C's allocator unless
//! told otherwise (`b2SetAllocator`); routed through Rust's global allocator instead, its
//! blocks are counted by the bench's instrumented allocator exactly as carom's and Rapier's
//! are, step by step.
#![allow(unsafe_code)]

use boxdd_sys::ffi;
use std::alloc::{Layout, alloc, dealloc};
use std::os::raw::{c_int, c_void};
use std::ptr::null_mut;

/// The alignment of every block Box2D takes, which its sizes are rounded up to (`core.c`'s
/// `b2Alloc`: "a multiple of 32 or risk a seg fault").
const BLOCK: usize = 32;

/// Box2D's allocation function: `size` is already rounded to a whole number of blocks and
/// `alignment` is the block.
unsafe extern "C" fn allocate(size: usize, alignment: c_int) -> *mut c_void {
    match Layout::from_size_align(size, alignment as usize) {
        // SAFETY: the layout is valid and not zero-sized.
        Ok(layout) if size > 0 => unsafe { alloc(layout).cast() },
        _ => null_mut(),
    }
}

/// Box2D's free function: `size` is what was asked for, before `b2Alloc` rounded it, so the
/// block's layout is found again by rounding it the same way.
unsafe extern "C" fn free(memory: *mut c_void, size: usize) {
    let rounded = size.saturating_sub(1) | (BLOCK - 1);
    if let Ok(layout) = Layout::from_size_align(rounded + 1, BLOCK)
        && !memory.is_null()
    {
        // SAFETY: `memory` came from `allocate` with this layout (Box2D frees each block
        // with the size it asked for it with).
        unsafe { dealloc(memory.cast(), layout) }
    }
}

/// Routes Box2D's allocations through Rust's global allocator from now on. Call it once,
/// before any Box2D world is made: a block taken from C's allocator must not be given back
/// to Rust's.
pub fn route_through_global_allocator() {
    // SAFETY: both functions keep Box2D's contract (blocks of the size and alignment asked
    // for, freed with the size they were asked for), and no Box2D block exists yet.
    unsafe { ffi::b2SetAllocator(Some(allocate), Some(free)) }
}
