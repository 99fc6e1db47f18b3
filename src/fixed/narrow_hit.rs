//! The fast distance `t` of a narrow hit along its ray, and the products of raw lengths and
//! Q15 cosines it and the fast stages after it take ([`super::narrow_point`], the shadow
//! filters of [`super::narrow_point_shadow`]).
//!
//! On a sphere with `ô = (eye − C)/r` and `c = |ô|² − 1`, the two roots of the ray's
//! quadratic multiply to `r²·c` and `(ô·D̂)² = (N·V)² + c` on the sphere, so the near hit is
//!
//! ```text
//! t = r·c/(N·V + √((N·V)² + c))
//! ```
//!
//! a sum of two positive terms: no cancellation where the camera is close to a large sphere
//! (a floor), where `−ô·D̂·r − r·(N·V)` would lose the relative precision the Q15 `N·V` has.
//! One table square root and one reciprocal (the narrow kernel's `rsqrt_at`, squared) per
//! pixel; `c` and `r·c` are the sphere's (`NarrowSphere::c_q30`, `t_mantissa`).

use super::narrow_roots::{rsqrt_mid, sqrt_q30};
use super::prepare::NarrowSphere;

/// The hit's distance `t` (raw) along `D̂` on sphere `ns` from `N·V` (Q15):
/// `r·c/(N·V + √((N·V)² + c))` (see the module docs), within a few `2⁻¹⁵` relative.
#[inline(always)]
pub(super) fn fast_t(ns: &NarrowSphere, nv: i32) -> u32 {
    // √((N·V)² + c)·2^-j in Q15, from ((N·V)² + c)·2^-2j in Q30 (at most 2³⁰: see the field).
    let j = ns.c_shift as u32;
    let arg = ((nv * nv) as u32 >> (2 * j))
        .saturating_add(ns.c_q30)
        .min(1 << 30);
    let den = (nv as u32)
        .saturating_add((sqrt_q30(arg) as u32) << j)
        .max(1);
    // 1/den = y²·2^-2e: t = r·c·2¹⁵/den.
    let (y, e) = rsqrt_mid(den);
    let y2 = (y.min(0xffff) * y.min(0xffff)) >> 16;
    shift_u32(
        ns.t_mantissa as u32 * y2,
        ns.t_exponent as i32 + 31 - 2 * e as i32,
    )
    .min(i32::MAX as u32)
}

/// `⌊a·b/2¹⁵⌋` for a raw length `|a| < 2³¹` and a Q15 cosine `|b| ≤ 2¹⁵`: two 16×16-bit
/// products, `a = aₕ·2¹⁶ + aₗ` with `aₗ` unsigned (the result is below `|a|` in magnitude,
/// so it fits).
#[inline(always)]
pub(super) fn mul_q15(a: i32, b: i32) -> i32 {
    let high = (a >> 16).wrapping_mul(b) << 1;
    let low = (a & 0xffff).wrapping_mul(b) >> 15;
    high.wrapping_add(low)
}

/// `v·2^e`, saturating at `u32::MAX`, rounded down.
#[inline(always)]
pub(super) fn shift_u32(v: u32, e: i32) -> u32 {
    if e >= 0 {
        let e = e as u32;
        if e >= 32 || super::mul::shift_overflows32(v, e) {
            if v == 0 {
                0
            } else {
                u32::MAX
            }
        } else {
            v << e
        }
    } else {
        v.checked_shr(e.unsigned_abs()).unwrap_or(0)
    }
}

/// The number of bits of `v` (0 for 0).
#[inline(always)]
pub(super) fn bit_length(v: u32) -> u32 {
    #[cfg(shadeline_no_clz)]
    {
        if v == 0 {
            0
        } else {
            32 - super::mul::search_leading_zeros32(v)
        }
    }
    #[cfg(not(shadeline_no_clz))]
    {
        32 - v.leading_zeros()
    }
}
