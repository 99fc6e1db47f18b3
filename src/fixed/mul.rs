//! Exact 32×32→64-bit products, the fixed kernel's only multiplication, and the count of
//! leading zeros its normalizations need.
//!
//! Every product the kernel forms has two operands that fit 32 bits (their formats bound
//! them, see [`super`]'s table), so it never needs a 64×64 product, let alone an overflow-
//! checked one. (The prepare's exact quadrics, and the row test of the spans without the
//! full-width kernel, need 64×64→128: [`mul_128`] and [`mul_u128`], from four
//! of these.) On targets with a widening multiply instruction these are the plain
//! `i64`/`u64` products. On ARMv6-M and ARMv8-M Baseline (`cfg(shadeline_short_mul)`, set by
//! the build script), whose only multiplier is 32×32→32, a 64-bit product is otherwise a call
//! to `__aeabi_lmul` (a full 64×64 product); here it is four 16×16→32 `MULS` and the
//! carries between them, about half the instructions, in one shared out-of-line routine per
//! signedness ([`mul_uu`], [`mul_ii`], [`mul_iu`]).
//!
//! Out of line, not inline at each product, because that is both smaller and faster on ARMv6-M: a
//! call costs a few instructions, and an inline sequence needs eight registers where the pixel loop
//! has eight low ones for all its state (the likely reason the inline form was slower; the
//! figures are in `docs/performance.md, "Choices measured"`).
//!
//! The routines are exact, so a frame is the same bits on every target
//! (`tests::split_products_are_exact` checks the split form against the plain one on the host).
//!
//! ARMv6-M has no `CLZ` either: `leading_zeros` is a call to `__clzsi2` (twice for a `u64`).
//! [`leading_zeros`] is a five-step binary search there (in its shared routine; the narrow
//! kernel inlines the 32-bit search), `u64::leading_zeros` elsewhere;
//! `tests::leading_zeros_match` checks the two agree. The narrow kernel's 32-bit counts
//! search on every core without `CLZ` (`shadeline_no_clz`, set by `build.rs`: ARMv6-M and
//! RISC-V without `Zbb`, where the count is a routine call too).

/// The number of leading zero bits of `x` (64 for 0).
#[inline(always)]
pub(crate) fn leading_zeros(x: u64) -> u32 {
    #[cfg(shadeline_short_mul)]
    {
        shared::leading_zeros(x)
    }
    #[cfg(not(shadeline_short_mul))]
    {
        x.leading_zeros()
    }
}

/// [`leading_zeros`] by binary search over the high or low word.
#[cfg_attr(not(shadeline_short_mul), allow(dead_code))]
#[inline(always)]
fn search_leading_zeros(x: u64) -> u32 {
    let high = (x >> 32) as u32;
    let (v, n) = if high != 0 { (high, 0) } else { (x as u32, 32) };
    if v == 0 {
        return 64;
    }
    n + search_leading_zeros32(v)
}

/// The leading zeros of a nonzero `u32` by a five-step binary search (for cores without
/// `CLZ`, `shadeline_no_clz`): [`search_pairs`], then the odd one.
#[cfg_attr(not(shadeline_no_clz), allow(dead_code))]
#[inline(always)]
pub(crate) fn search_leading_zeros32(x: u32) -> u32 {
    let (v, n) = search_pairs(x);
    n + (v >> 31 == 0) as u32
}

/// Whether `x << s` (`s < 64`) loses bits. Where the core has `CLZ`, from the leading-zero
/// count (one or two `CLZ`; the 64-bit shift takes more); on cores without it
/// (`shadeline_no_clz`: ARMv6-M, RISC-V without `Zbb`), where the count is a search or a
/// routine call, one comparison with `u64::MAX >> s`.
#[inline(always)]
pub(crate) fn shift_overflows(x: u64, s: u32) -> bool {
    #[cfg(shadeline_no_clz)]
    {
        x > u64::MAX >> s
    }
    #[cfg(not(shadeline_no_clz))]
    {
        x.leading_zeros() < s
    }
}

/// Whether `x << s` (`s < 32`) loses bits: [`shift_overflows`] for a `u32`.
#[inline(always)]
pub(crate) fn shift_overflows32(x: u32, s: u32) -> bool {
    #[cfg(shadeline_no_clz)]
    {
        x > u32::MAX >> s
    }
    #[cfg(not(shadeline_no_clz))]
    {
        x.leading_zeros() < s
    }
}

/// The leading zeros of a nonzero `u32` rounded down to even, by a four-step binary search:
/// [`search_leading_zeros32`] without its last step, which only adds the odd one.
#[cfg_attr(not(shadeline_no_clz), allow(dead_code))]
#[inline(always)]
pub(crate) fn search_even_leading_zeros32(x: u32) -> u32 {
    search_pairs(x).1
}

/// The four steps of the searches above: `x` shifted left by its leading zeros rounded down
/// to even (its top two bits not both 0), and that count.
#[cfg_attr(not(shadeline_no_clz), allow(dead_code))]
#[inline(always)]
fn search_pairs(x: u32) -> (u32, u32) {
    let (mut v, mut n) = (x, 0);
    if v >> 24 == 0 {
        if v >> 16 == 0 {
            n += 16;
            v <<= 16;
        }
        if v >> 24 == 0 {
            n += 8;
            v <<= 8;
        }
    }
    if v >> 28 == 0 {
        n += 4;
        v <<= 4;
    }
    if v >> 30 == 0 {
        n += 2;
        v <<= 2;
    }
    (v, n)
}

/// The leading zeros of a nonzero `u32`: `CLZ` where the core has it, the binary search where
/// `u32::leading_zeros` is a routine call (`shadeline_no_clz`).
#[inline(always)]
pub(crate) fn leading_zeros32(x: u32) -> u32 {
    #[cfg(shadeline_no_clz)]
    {
        search_leading_zeros32(x)
    }
    #[cfg(not(shadeline_no_clz))]
    {
        x.leading_zeros()
    }
}

/// `a·b`, exact.
#[inline(always)]
pub(crate) fn mul_uu(a: u32, b: u32) -> u64 {
    #[cfg(shadeline_short_mul)]
    {
        shared::mul_uu(a, b)
    }
    #[cfg(not(shadeline_short_mul))]
    {
        a as u64 * b as u64
    }
}

/// `a·b` for `b` below `2¹⁶`, exact: on ARMv6-M two `MULS` of `a`'s halves, no routine
/// call (where the core multiplies 32×32→64 in one instruction, that instruction).
#[inline(always)]
pub(crate) fn mul_u32_u16(a: u32, b: u32) -> u64 {
    debug_assert!(b < 1 << 16, "{b:#x} is not a 16-bit factor");
    #[cfg(shadeline_short_mul)]
    {
        ((((a >> 16) * b) as u64) << 16) + ((a & 0xffff) * b) as u64
    }
    #[cfg(not(shadeline_short_mul))]
    {
        a as u64 * b as u64
    }
}

/// `a·b`, exact.
#[inline(always)]
pub(crate) fn mul_ii(a: i32, b: i32) -> i64 {
    #[cfg(shadeline_short_mul)]
    {
        shared::mul_ii(a, b)
    }
    #[cfg(not(shadeline_short_mul))]
    {
        a as i64 * b as i64
    }
}

/// `a·b`, exact (`|a·b| < 2⁶³`).
#[inline(always)]
pub(crate) fn mul_iu(a: i32, b: u32) -> i64 {
    #[cfg(shadeline_short_mul)]
    {
        shared::mul_iu(a, b)
    }
    #[cfg(not(shadeline_short_mul))]
    {
        a as i64 * b as i64
    }
}

/// `a·b` for an `i64` and an `i32`, wrapping: the exact product wherever it fits `i64`
/// (where its callers use it, their bounds say it does). `a = aₕ·2³² + aₗ` with `aₗ`
/// unsigned: `aₕ·b` wraps into the high word, and `aₗ·b` is one exact 32×32→64 product, so
/// on ARMv6-M it is one `MULS` and a call of [`mul_iu`]'s routine instead of a call to
/// `__aeabi_lmul`.
#[inline(always)]
pub(crate) fn mul_wide(a: i64, b: i32) -> i64 {
    let high = ((a >> 32) as i32).wrapping_mul(b);
    ((high as i64) << 32).wrapping_add(mul_iu(b, a as u32))
}

/// The out-of-line routines behind the products and the count of leading zeros on ARMv6-M.
#[cfg(shadeline_short_mul)]
mod shared {
    #[inline(never)]
    pub(super) fn leading_zeros(x: u64) -> u32 {
        super::search_leading_zeros(x)
    }

    #[inline(never)]
    pub(super) fn mul_uu(a: u32, b: u32) -> u64 {
        super::split_uu(a, b)
    }

    #[inline(never)]
    pub(super) fn mul_ii(a: i32, b: i32) -> i64 {
        super::split_ii(a, b)
    }

    #[inline(never)]
    pub(super) fn mul_iu(a: i32, b: u32) -> i64 {
        super::split_iu(a, b)
    }
}

/// `a·b` from four 16×16→32 products: `a = aₕ·2¹⁶ + aₗ`, likewise `b`.
#[cfg_attr(not(shadeline_short_mul), allow(dead_code))]
#[inline(always)]
fn split_uu(a: u32, b: u32) -> u64 {
    let (al, ah) = (a & 0xffff, a >> 16);
    let (bl, bh) = (b & 0xffff, b >> 16);
    let low = al * bl;
    let high = ah * bh;
    // The two middle products each fit 32 bits; their sum may carry into bit 32 (2⁴⁸ overall).
    let (mid, carry) = (ah * bl).overflowing_add(al * bh);
    let (low, carry_low) = low.overflowing_add(mid << 16);
    let high = high + (mid >> 16) + ((carry as u32) << 16) + carry_low as u32;
    ((high as u64) << 32) | low as u64
}

/// Signed `a·b` from the unsigned product of the two's-complement bits: for a negative
/// operand, subtract the other operand from the high word.
#[cfg_attr(not(shadeline_short_mul), allow(dead_code))]
#[inline(always)]
fn split_ii(a: i32, b: i32) -> i64 {
    let p = split_uu(a as u32, b as u32);
    let high = (p >> 32) as u32;
    let high = high
        .wrapping_sub(b as u32 & (a >> 31) as u32)
        .wrapping_sub(a as u32 & (b >> 31) as u32);
    (((high as u64) << 32) | (p & 0xffff_ffff)) as i64
}

/// Signed × unsigned: only `a`'s sign needs the correction.
#[cfg_attr(not(shadeline_short_mul), allow(dead_code))]
#[inline(always)]
fn split_iu(a: i32, b: u32) -> i64 {
    let p = split_uu(a as u32, b);
    let high = ((p >> 32) as u32).wrapping_sub(b & (a >> 31) as u32);
    (((high as u64) << 32) | (p & 0xffff_ffff)) as i64
}

/// `a·b` of two `i32` vectors, exact (`|a·b| < 2⁶³`: where it is used, the operands' bounds
/// say so): for the narrow run's set-up and the prepare's dot products. One routine on
/// ARMv6-M rather than three products and their sums at each (smaller, most of all in the
/// run set-up); inline elsewhere.
#[cfg_attr(not(shadeline_short_mul), inline(always))]
#[cfg_attr(shadeline_short_mul, inline(never))]
pub(crate) fn dot_ii(a: [i32; 3], b: [i32; 3]) -> i64 {
    mul_ii(a[0], b[0]) + mul_ii(a[1], b[1]) + mul_ii(a[2], b[2])
}

/// `a·b` of two `i64`, exact: four 32×32→64 products ([`mul_u128`]), not a call to the
/// 128×128 multiplication routine. Out of line, like [`mul_u128`].
#[inline(never)]
pub(crate) fn mul_128(a: i64, b: i64) -> i128 {
    let p = mul_u128(a.unsigned_abs(), b.unsigned_abs()) as i128;
    if (a < 0) != (b < 0) {
        -p
    } else {
        p
    }
}

/// `a·b` of two `u64`, exact, from four 32×32→64 products. Out of line, like [`mul_128`]:
/// the prepare's quadrics and the outline's row test run it a few hundred times a frame,
/// and inlined it would repeat its products in the firmware's flash.
#[inline(never)]
pub(crate) fn mul_u128(a: u64, b: u64) -> u128 {
    let (xh, xl, yh, yl) = ((a >> 32) as u32, a as u32, (b >> 32) as u32, b as u32);
    ((mul_uu(xh, yh) as u128) << 64)
        + (((mul_uu(xh, yl) as u128) + (mul_uu(xl, yh) as u128)) << 32)
        + mul_uu(xl, yl) as u128
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A small xorshift generator: no dependency, the same numbers on every run.
    fn numbers() -> impl Iterator<Item = u32> {
        let edges = [
            0,
            1,
            2,
            0xffff,
            0x1_0000,
            0x7fff_ffff,
            0x8000_0000,
            0x8000_0001,
            u32::MAX,
        ];
        let mut s = 0x9e37_79b9_7f4a_7c15u64;
        let random = core::iter::repeat_with(move || {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            (s >> 16) as u32
        });
        edges.into_iter().chain(random.take(3000))
    }

    #[test]
    fn leading_zeros_match() {
        for a in numbers() {
            for b in numbers().step_by(97) {
                let x = ((a as u64) << 32) | b as u64;
                for v in [x, x >> (a % 64), b as u64, x << (b % 64)] {
                    assert_eq!(search_leading_zeros(v), v.leading_zeros(), "{v:#x}");
                }
            }
        }
        assert_eq!(search_leading_zeros(0), 64);
        for v in numbers() {
            for s in 0..32 {
                let wide = (v as u64) << s;
                assert_eq!(shift_overflows32(v, s), wide >> 32 != 0, "{v:#x} << {s}");
                assert_eq!(shift_overflows(wide, s), (wide as u128) << s >> 64 != 0);
            }
        }
        for v in numbers().filter(|&v| v != 0) {
            assert_eq!(
                search_even_leading_zeros32(v),
                v.leading_zeros() & !1,
                "{v:#x}"
            );
            assert_eq!(leading_zeros32(v), v.leading_zeros(), "{v:#x}");
        }
    }

    #[test]
    fn split_products_are_exact() {
        for a in numbers() {
            for b in numbers().step_by(31) {
                let b = b >> (16 + b % 16);
                assert_eq!(mul_u32_u16(a, b), a as u64 * b as u64, "{a:#x}·{b:#x}");
            }
        }
        for a in numbers() {
            for b in numbers().step_by(7) {
                assert_eq!(split_uu(a, b), a as u64 * b as u64, "{a} × {b}");
                let (sa, sb) = (a as i32, b as i32);
                assert_eq!(split_ii(sa, sb), sa as i64 * sb as i64, "{sa} × {sb}");
                assert_eq!(split_iu(sa, b), sa as i64 * b as i64, "{sa} × {b}");
            }
        }
    }
}
