//! Cache hints: a record's lines asked for ahead of its use (hints only:
//! nothing is read, and no result can change).

/// Asks the processor to bring `value`'s (first) cache line in ahead of
/// its use (a hint: nothing is read, and the results cannot change).
#[inline(always)]
pub(super) fn prefetch<T: ?Sized>(value: &T) {
    prefetch_line((value as *const T).cast::<u8>());
}

/// [`prefetch`] of every cache line `value` touches (from the 64-byte
/// boundary at or below its start: a record need not be aligned to one).
#[inline(always)]
pub(super) fn prefetch_all<T>(value: &T) {
    let start = (value as *const T).cast::<u8>();
    let below = start as usize % 64;
    let first = start.wrapping_sub(below);
    for offset in (0..below + std::mem::size_of::<T>()).step_by(64) {
        prefetch_line(first.wrapping_add(offset));
    }
}

/// The cache line of `address` into the cache (any address: never read).
#[inline(always)]
fn prefetch_line(address: *const u8) {
    #[cfg(target_arch = "x86_64")]
    {
        use std::arch::x86_64::{_MM_HINT_T0, _mm_prefetch};
        // SAFETY: SSE is part of x86_64's baseline, and a prefetch never
        // faults nor reads memory the program sees (any address is allowed).
        unsafe { _mm_prefetch::<_MM_HINT_T0>(address.cast::<i8>()) };
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = address;
}
