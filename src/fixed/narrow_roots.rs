//! The narrow kernel's table roots ([`super::narrow`]): `σ = 1/|d|` from `|d|²`
//! ([`sigma_of`]), `1/√x` ([`rsqrt_at`]) and `√x` of a Q30 value ([`sqrt_q30`]), each a small
//! table made at compile time and one interpolation or Newton step, with the error bound its
//! test holds it to. The precise forms, in 30-bit fractions, are [`super::roots`]', and
//! [`rsqrt_at`] starts from their table (one table of `1/√u` in the crate).

use super::roots::initial;

/// Bins of [`SIGMA_TABLE`] per unit of `|d|²`.
const SIGMA_BINS: u32 = 256;

/// `σ = 1/√A` for `A = 1 + i/256`, `i` in `0..=257` (`|d|²` is in `[1, 2]` on a narrow frame,
/// within `2⁻²⁰`), Q30, rounded down; made at compile time with integers only.
static SIGMA_TABLE: [u32; SIGMA_BINS as usize + 2] = sigma_table();

const fn sigma_table() -> [u32; SIGMA_BINS as usize + 2] {
    let mut table = [0u32; SIGMA_BINS as usize + 2];
    let mut i = 0;
    while i < table.len() {
        // 2³⁰/√(1 + i/256) = √(2⁶⁸/(256 + i)).
        table[i] = ((1u128 << 68) / (256 + i as u128)).isqrt() as u32;
        i += 1;
    }
    table
}

/// `σ = 1/|d|` (Q15) and `σ²` (Q16, rounded) from `|D|²` as the run holds it (`|d|²` is its
/// high word in Q26): [`SIGMA_TABLE`] and linear interpolation, within `2⁻¹⁹` relative
/// (the table's bins are `2⁻⁸` wide and `σ''/σ ≤ ¾`).
#[inline(always)]
pub(super) fn sigma_of(a: i64) -> (i32, u32) {
    // |d|² − 1 in Q26, in [0, 1] up to rounding: the bin (8 bits) and the place in it (11).
    let t = (((a >> 32) as i32) - (1 << 26)).clamp(0, (1 << 26) + (1 << 18) - 1) as u32;
    let bin = (t >> 18) as usize;
    let frac = (t >> 7) & 0x7ff;
    let (lo, hi) = (
        SIGMA_TABLE.get(bin).copied().unwrap_or(1 << 30),
        SIGMA_TABLE.get(bin + 1).copied().unwrap_or(1 << 30),
    );
    // The table falls by at most 2²¹ per bin.
    let s30 = lo - (((lo - hi) * frac) >> 11);
    let s16 = ((s30 + (1 << 13)) >> 14).min(0xffff);
    ((s30 >> 15) as i32, (s16 * s16 + (1 << 15)) >> 16)
}

/// [`rsqrt_at`] for an `x > 0` mostly in `[2²⁶, 2³²)` (`|P − X|²` at the fast point
/// light's shift, `|L + V|²`): on cores without `CLZ` (`shadeline_no_clz`), where the count
/// of leading zeros is a search, its even count from [`even_leading_zeros_high`]'s two
/// comparisons.
#[inline(always)]
pub(super) fn rsqrt_high(x: u32) -> (u32, u32) {
    let k = if cfg!(shadeline_no_clz) {
        even_leading_zeros_high(x)
    } else {
        even_leading_zeros(x)
    };
    rsqrt_at(x, k)
}

/// [`rsqrt_at`] for an `x > 0` mostly in `[2¹², 2²⁰)` (the denominator of the fast `t`,
/// about `2¹⁵` times `N·V + √((N·V)² + c)`): on cores without `CLZ`, its even count of
/// leading zeros from two or three comparisons there, the search elsewhere.
#[inline(always)]
pub(super) fn rsqrt_mid(x: u32) -> (u32, u32) {
    if !cfg!(shadeline_no_clz) {
        return rsqrt_at(x, even_leading_zeros(x));
    }
    let k = if x >= 1 << 16 {
        if x >= 1 << 18 {
            if x >= 1 << 20 {
                outside_range(x)
            } else {
                12
            }
        } else {
            14
        }
    } else if x >= 1 << 14 {
        16
    } else if x >= 1 << 12 {
        18
    } else {
        outside_range(x)
    };
    rsqrt_at(x, k)
}

/// `1/√x` for `x > 0` as `(y, e)`: `1/√x ≈ y·2^-e`, `y` in about `[2¹⁵, 2¹⁶]`, within
/// `1.5·2⁻¹⁵` relative: a table lookup and one Newton step `y·(3 − m·y²)/2`. `k` is `x`'s
/// count of leading zeros rounded down to even ([`even_leading_zeros`]).
#[inline(always)]
pub(super) fn rsqrt_at(x: u32, k: u32) -> (u32, u32) {
    debug_assert_eq!(k, even_leading_zeros(x));
    (rsqrt_normalized(x << k), 31 - k / 2)
}

/// `2³¹/√m` for `m` in `[2³⁰, 2³²)`, within `1.5·2⁻¹⁵` relative (in about `[2¹⁵, 2¹⁶]`).
#[inline(always)]
fn rsqrt_normalized(m: u32) -> u32 {
    debug_assert!(m >= 1 << 30, "m = {m:#x} is not normalized");
    // The full-width roots' table of `2³¹/√u` at each bin's centre (`u = 4m`), to 16 bits:
    // `2¹⁵/√m` at the centre, rounded down.
    let y0 = initial(m) >> 15;
    // m·y0² as Q30 from their top 16 bits (y0² Q30 → Q14, m Q32 → Q16): about 2³⁰.
    let p = ((y0 * y0 + (1 << 15)) >> 16) * (m.saturating_add(1 << 15) >> 16);
    let corr = (3u32 << 30).saturating_sub(p);
    // y0·corr/2³¹, rounded at both steps (y0 < 2¹⁶, corr < 3·2³⁰: no overflow).
    (y0 * ((corr + (1 << 15)) >> 16) + (1 << 14)) >> 15
}

/// `√x` for `x = i/256`, `i` in `0..=256`, Q29, rounded down; made at compile time with
/// integers only. A normalized argument only reads entries from 64 on; the ones below are
/// there so that the top byte indexes the table with no check.
static SQRT_TABLE: [u32; 257] = sqrt_table();

const fn sqrt_table() -> [u32; 257] {
    let mut table = [0u32; 257];
    let mut i = 0;
    while i < table.len() {
        // 2²⁹·√(i/256) = √(2⁵⁰·i).
        table[i] = ((1u64 << 50) * i as u64).isqrt() as u32;
        i += 1;
    }
    table
}

/// `√x` of a Q30 value in `[0, 2³⁰]`, as Q15: the value normalized by an even shift to
/// `[¼, 1)`, [`SQRT_TABLE`] and linear interpolation (within `2⁻¹⁷` relative: `√''/√ ≥ −4`
/// on `[¼, 1)`, bins `2⁻⁸` wide), rounded. Out of line on ARMv6-M: the pixel loop calls it
/// from two places, and one copy is smaller there at no more instructions per frame.
#[cfg_attr(not(shadeline_short_mul), inline(always))]
#[cfg_attr(shadeline_short_mul, inline(never))]
pub(super) fn sqrt_q30(x: u32) -> i32 {
    if x == 0 {
        return 0;
    }
    // N·V's argument is mostly in [2²⁶, 2³⁰].
    let k = even_leading_zeros_high(x);
    let m = x << k; // in [2³⁰, 2³²)
    let bin = (m >> 24) as usize; // 64..=255
    let frac = (m >> 13) & 0x7ff;
    let (lo, hi) = (
        SQRT_TABLE.get(bin).copied().unwrap_or(1 << 29),
        SQRT_TABLE.get(bin + 1).copied().unwrap_or(1 << 29),
    );
    // The table rises by at most 2²¹ per bin. √(m/2³²) in Q29; √x = that·2^(1 − k/2).
    let root = lo + (((hi - lo) * frac) >> 11);
    let shift = 13 + k / 2;
    ((root + (1 << (shift - 1))) >> shift) as i32
}

/// [`even_leading_zeros`] of `x > 0` mostly in `[2²⁶, 2³²)`: two comparisons there, the
/// count elsewhere. [`sqrt_q30`] takes it on every core (`N·V`'s square is there; on the
/// M4F too the comparisons cost its pixel loop less than `CLZ` and the rounding to even,
/// `docs/performance.md`, "Choices measured").
#[inline(always)]
fn even_leading_zeros_high(x: u32) -> u32 {
    let k = if x >= 1 << 28 {
        if x >= 1 << 30 {
            0
        } else {
            2
        }
    } else if x >= 1 << 26 {
        4
    } else {
        outside_range(x)
    };
    debug_assert_eq!(k, even_leading_zeros(x));
    k
}

/// [`even_leading_zeros`] for the arguments outside the range a caller's comparisons
/// cover. Out of line and cold on ARMv6-M, so that the pixel loops, which inline those
/// comparisons at each of their copies, share one search there (its flash); inline
/// elsewhere, where the call costs the M4F's and RV32's point-lit frames more than the
/// flash it saves (`docs/performance.md`, "Choices measured").
#[cfg_attr(shadeline_short_mul, inline(never), cold)]
#[cfg_attr(not(shadeline_short_mul), inline(always))]
fn outside_range(x: u32) -> u32 {
    even_leading_zeros(x)
}

/// The number of leading zeros of `x > 0`, rounded down to even: the shift that brings `x`
/// into `[2³⁰, 2³²)` by a power of four. `CLZ` where the core has it; where it has not
/// (`shadeline_no_clz`), the binary search of [`super::mul`].
#[inline(always)]
pub(super) fn even_leading_zeros(x: u32) -> u32 {
    #[cfg(shadeline_no_clz)]
    {
        super::mul::search_even_leading_zeros32(x)
    }
    #[cfg(not(shadeline_no_clz))]
    {
        x.leading_zeros().min(30) & !1
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rsqrt_starts_from_two_to_the_15_over_the_root_of_each_bins_centre() {
        // Bin `64 + j` of the top byte of a normalized `m` covers [(64 + j)/256, (65 + j)/256):
        // the start is 2¹⁵/√centre rounded down, √(2³⁹/(2j + 129)).
        for top in 64u32..=255 {
            let want = ((1u64 << 39) / (2 * (top as u64 - 64) + 129)).isqrt() as u32;
            for m in [top << 24, (top << 24) | 0x00ff_ffff] {
                assert_eq!(initial(m) >> 15, want, "bin {top}");
            }
        }
    }

    #[test]
    fn rsqrt_within_one_and_a_half_steps_of_two_to_the_minus_15() {
        let mut worst = 0.0f64;
        let mut x = 1u64;
        while x <= u32::MAX as u64 {
            for v in [x, x + x / 3, x + x / 2, x + 7 * x / 9] {
                let Ok(v) = u32::try_from(v) else {
                    continue;
                };
                let (y, e) = rsqrt_at(v, even_leading_zeros(v));
                let got = y as f64 / (e as f64).exp2();
                let want = 1.0 / (v as f64).sqrt();
                worst = worst.max((got / want - 1.0).abs());
            }
            x = x * 2 + 1;
        }
        assert!(worst <= 1.5 / 32768.0, "relative error {worst}");
    }

    #[test]
    fn sqrt_q30_within_one_step() {
        for k in 0..=1000u64 {
            let x = ((k << 30) / 1000) as u32;
            let want = ((x as f64) / (1u64 << 30) as f64).sqrt() * 32768.0;
            let got = sqrt_q30(x) as f64;
            assert!((got - want).abs() <= 1.5, "{x}: {got} vs {want}");
        }
    }
}
