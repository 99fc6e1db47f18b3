//! Stack high-water mark by painting: fill the free stack with a pattern before the render,
//! then find the lowest word that no longer holds it.
//!
//! The board gives the region: from the lowest address the stack may reach (the end of
//! `.bss`, where the linker scripts put the stack's limit) up to a little below the current
//! stack pointer, so that painting never touches a live frame. No interrupt is enabled in the
//! demos, so nothing else writes there. A word that the render wrote with exactly the
//! pattern would be missed; the pattern is an odd, unaligned-looking value that no pointer,
//! float or pixel of ours produces, and one such word could only hide the deepest 4 bytes.

/// The paint: not a valid pointer, not a likely float or pixel pair.
pub const PATTERN: u32 = 0xa5c3_5a3c;

/// Bytes left unpainted just below the stack pointer, for the painting call's own frame.
pub const GUARD: usize = 256;

/// Paints every word in `[bottom, top)` with [`PATTERN`].
///
/// # Safety
/// The range must be RAM that nothing live uses (free stack below the current frame, with
/// room for this call's own frame), word-aligned.
#[inline(never)]
pub unsafe fn paint(bottom: usize, top: usize) {
    let mut p = bottom;
    while p + 4 <= top {
        // SAFETY: the caller guarantees [bottom, top) is free, word-aligned RAM.
        unsafe { core::ptr::write_volatile(p as *mut u32, PATTERN) };
        p += 4;
    }
}

/// The lowest address in `[bottom, top)` whose word differs from [`PATTERN`], or `top` if
/// every word still holds it: the deepest point the stack reached since [`paint`].
///
/// # Safety
/// The range must be readable, word-aligned RAM.
#[inline(never)]
pub unsafe fn deepest_touched(bottom: usize, top: usize) -> usize {
    let mut p = bottom;
    while p + 4 <= top {
        // SAFETY: the caller guarantees [bottom, top) is readable, word-aligned RAM.
        if unsafe { core::ptr::read_volatile(p as *const u32) } != PATTERN {
            return p;
        }
        p += 4;
    }
    top
}
