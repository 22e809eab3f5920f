//! A hint to the processor that memory is about to be read. Loops that reach items scattered
//! in memory by index (a contact's bodies) ask for the items a few iterations ahead, so that
//! the reads overlap instead of each stalling in turn. A hint changes no result; where the
//! target has no such instruction it does nothing.

/// Asks for the cache lines `item` spans.
#[inline(always)]
pub(crate) fn prefetch<T>(item: &T) {
    prefetch_head(item, size_of::<T>());
}

/// Asks for the cache lines that the first `bytes` of `item` span (wherever a line begins).
#[inline(always)]
pub(crate) fn prefetch_head<T>(item: &T, bytes: usize) {
    #[cfg(target_arch = "x86_64")]
    {
        use std::arch::x86_64::{_MM_HINT_T0, _mm_prefetch};
        let at = (item as *const T).cast::<i8>();
        // SAFETY: SSE, which the instruction needs, is part of every x86-64 processor, and
        // a prefetch reads nothing and cannot fault, whatever the address.
        #[allow(unsafe_code)]
        unsafe {
            for offset in (0..bytes).step_by(64) {
                _mm_prefetch::<_MM_HINT_T0>(at.wrapping_add(offset));
            }
            // The last byte's line, which the steps above miss when the head does not
            // begin a line.
            if bytes > 0 {
                _mm_prefetch::<_MM_HINT_T0>(at.wrapping_add(bytes - 1));
            }
        }
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = (item, bytes);
}
