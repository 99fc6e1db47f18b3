//! The narrow kernel's scalings ([`super::narrow`]): a U16F16 value times a Q15 or Q16
//! factor, and the high word of a 64-bit value, in 16×16-bit products (no 32×32→64-bit
//! product on ARMv6-M).

use super::mul::mul_uu;

/// One, Q15.
pub(super) const ONE: i32 = 1 << 15;

/// `(v >> s) as i32` for `s` in `1..=31`, where the result fits: two 32-bit shifts (a
/// variable 64-bit shift is a library call on ARMv6-M).
#[inline(always)]
pub(super) fn high_bits(v: i64, s: u32) -> i32 {
    debug_assert!((1..32).contains(&s), "shift {s}");
    debug_assert!((v >> s) as i32 as i64 == v >> s, "{v} >> {s} does not fit");
    let s = s & 31;
    ((((v >> 32) as u32) << ((32 - s) & 31)) | ((v as u32) >> s)) as i32
}

/// `v·s/2¹⁶` for a signed `v` and `s` in `[0, 2¹⁶]`, rounded down: two 16×16 products.
#[inline(always)]
pub(super) fn scale_signed_q16(v: i32, s: u32) -> i32 {
    let high = (v >> 16) * s as i32;
    let low = (((v & 0xffff) as u32 * s) >> 16) as i32;
    high + low
}

/// `a·b/2¹⁶` for `b` in `[0, 2¹⁶]`, exact (rounded down), saturating: two 16×16 products
/// on ARMv6-M, one widening product elsewhere.
#[inline(always)]
pub(super) fn scale_q16(a: u32, b: u32) -> u32 {
    #[cfg(shadeline_short_mul)]
    {
        let high = (a >> 16) * b; // ≤ 2³²− 2¹⁶
        let low = ((a & 0xffff) * b) >> 16;
        high.saturating_add(low)
    }
    #[cfg(not(shadeline_short_mul))]
    {
        u32::try_from(mul_uu(a, b) >> 16).unwrap_or(u32::MAX)
    }
}

/// `k·v/2¹⁶`, rounded down, saturating: [`scale_q16`] when `k ≤ 1` (U16F16), which
/// `kd·albedo` and `ks` nearly always are, a full product otherwise.
#[inline(always)]
pub(super) fn mul_u16f16(k: u32, v: u32) -> u32 {
    if k <= 1 << 16 {
        scale_q16(v, k)
    } else {
        u32::try_from(mul_uu(k, v) >> 16).unwrap_or(u32::MAX)
    }
}

/// `a·b/2¹⁵` for `b` in `[0, 2¹⁵]`, exact (rounded down), saturating: two 16×16 products
/// on ARMv6-M, one widening product elsewhere.
#[inline(always)]
pub(super) fn scale_q15(a: u32, b: i32) -> u32 {
    let b = b.clamp(0, ONE) as u32;
    #[cfg(shadeline_short_mul)]
    {
        let high = (a >> 16) * b; // < 2³¹
        let low = ((a & 0xffff) * b) >> 15;
        high.checked_mul(2)
            .and_then(|h| h.checked_add(low))
            .unwrap_or(u32::MAX)
    }
    #[cfg(not(shadeline_short_mul))]
    {
        u32::try_from(mul_uu(a, b) >> 15).unwrap_or(u32::MAX)
    }
}
