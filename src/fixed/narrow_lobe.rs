//! The narrow kernel's lobe ([`super::narrow`]): `h = 1 − cos` of Phong (`1 − R·V`) and
//! Blinn-Phong (`1 − N·H`) from the cosines, fast (Q15, [`fast_h`]) or precise (30-bit
//! fractions from the exact quadrics, [`precise_h`]), whether the fast lobe serves
//! ([`fast_lobe`]), and the lobe `(1 − h)ⁿ` itself ([`narrow_lobe`]).

use super::exact::{shift_saturating, Exact};
use super::mul::{leading_zeros32, mul_ii, mul_iu, mul_uu};
use super::narrow_roots::rsqrt_high;
use super::narrow_scale::high_bits;
use super::pow::{exp2_neg_q16, INV_LN2_F31, LOG_TABLE};
use super::prepare::NarrowSphere;
use super::roots::{inv_sqrt, sqrt};
use super::vector::V3;

/// `|L + V|²` (Q30) below which the fast Blinn-Phong `h` is not within
/// [`H_ERROR`](super::narrow_prepare::H_ERROR): `9/16`. Its error grows as `1/|L + V|` (the half vector of
/// a light nearly behind the surface is ill-conditioned), and is within it from `|L + V| = ¾` on
/// (test `fast_h_within_its_bound`).
pub(super) const BLINN_LEN2_MIN: u32 = 9 << 26;

/// The fast `h = 1 − cos` (Q31, saturated: `h ≥ 1` is a lobe of 0) of Phong (`1 − R·V`) or
/// Blinn-Phong (`1 − N·H`) from `N·L`, `N·V` and `L·D̂` (Q15), and whether it is within
/// [`H_ERROR`](super::narrow_prepare::H_ERROR): not for Blinn-Phong where `|L + V|² < 9/16`, where the `h`
/// given is 0 if the lobe can be anything but 0 (`N·H > 0`), so that the precise lobe decides.
#[inline(always)]
pub(super) fn fast_h(blinn: bool, nl: i32, nv: i32, ld: i32) -> (u32, bool) {
    // h in Q29 (|h| < 2 here).
    let h29 = if blinn {
        // N·H = (N·L + N·V)/|L + V| with |L + V|² = 2 − 2·L·D̂ (V = −D̂).
        let len2 = ((2i64 << 30) - ((ld as i64) << 16)).clamp(0, u32::MAX as i64) as u32;
        if len2 < BLINN_LEN2_MIN {
            return (if nl + nv > 0 { 0 } else { u32::MAX }, false);
        }
        let (y, e) = rsqrt_high(len2);
        // 1/|L + V| = y·2^(15 − e) (len2 is Q30): N·H in Q29.
        let p = mul_ii(nl + nv, y as i32); // |p| < 2³³
        let nh = if e >= 29 {
            p >> (e - 29).min(63)
        } else {
            p << (29 - e) // e ≥ 16
        };
        (1 << 29) - nh.clamp(-(1 << 30), 1 << 30) as i32
    } else {
        // 1 − R·V = 1 − 2·(N·L)(N·V) − L·D̂.
        (1 << 29) - nl * nv - (ld << 14)
    };
    let h = if h29 <= 0 {
        0
    } else if h29 >= 1 << 30 {
        u32::MAX
    } else {
        (h29 as u32) << 2
    };
    (h, true)
}

/// The lobe (U1F16) of a pixel whose `h` needs more than the fast path's bits: the fast
/// path's formulas (`N·V = √E′·σ`, `L·D̂ = (d·L)·σ`, `N·L = G·σ² − (N·V)(L·D̂)`, then `h`) in
/// 30-bit fractions from the same exact `|D|²`, `E′`, `G` and `D·L` (`g_dl`, as the run
/// holds them), with `σ` and `√E′` from [`super::roots`] (within `2⁻³⁰`) instead of the
/// tables, then [`narrow_lobe`] of `h` in Q31. `h` is within `2⁻²⁴` (`2⁻²⁴/|L + V|` for
/// Blinn-Phong; test `precise_h_within_its_bound`), so the lobe, whose slope is at most `n`,
/// within `n·2⁻²⁴` and `narrow_lobe`'s own `7.2·10⁻⁵`: `7·10⁻⁴` of its peak at `n = 10⁴`, the
/// top of the range the fixed budget is held on; at the largest shininess, `10⁶`, up to 3%
/// at the peak of a pinpoint highlight. Out of line: a few hundred pixels of a frame take
/// it.
#[inline(never)]
pub(super) fn precise_lobe(
    blinn: bool,
    n: Exact,
    ns: &NarrowSphere,
    e: i64,
    d: V3<i32>,
    (g, dl): (i64, i64),
) -> u32 {
    match precise_h(blinn, ns, e, d, (g, dl)) {
        Some(h) => narrow_lobe(u32::try_from(h >> 30).unwrap_or(u32::MAX), n),
        None => 0,
    }
}

/// The precise `h = 1 − cos` of [`precise_lobe`] in U3F61 (`None` where Blinn-Phong's half
/// vector is undefined, `L = −V`).
#[inline(always)]
pub(super) fn precise_h(
    blinn: bool,
    ns: &NarrowSphere,
    e: i64,
    d: V3<i32>,
    (g, dl): (i64, i64),
) -> Option<u64> {
    let (_, nl, nv, ld) = precise_cosines(ns, e, d, (g, dl))?;
    precise_h_of(blinn, nl, nv, ld)
}

/// The precise cosines at a narrow hit, from the exact `|D|²` (of `d`), `E′` (`e`, as the
/// track holds it) and a light's `G` and `D·L` (`g_dl`, as the run holds them): `σ = 2²⁹/|D|`
/// in Q31, and `N·L`, `N·V` and `L·D̂` in Q30, each within a few units of `2⁻³⁰` (`σ` and
/// `√E′` from [`super::roots`]). `None` for `d = 0`, which a narrow frame never has. Shared
/// by the precise lobe and `precise_light`.
#[inline(always)]
pub(super) fn precise_cosines(
    ns: &NarrowSphere,
    e: i64,
    d: V3<i32>,
    (g, dl): (i64, i64),
) -> Option<(u32, i64, i64, i64)> {
    const ONE30: i64 = 1 << 30;
    let a = d.iter().map(|&c| mul_ii(c, c) as u64).sum::<u64>(); // |D|² < 2⁶¹
    let (ya, sa) = inv_sqrt(a)?;
    // σ = 2²⁹/|D| in Q31: ya·2^(60 − sa), at most 2³¹.
    let sigma = shift_saturating(ya as u64, 60 - sa as i32).min(1 << 31);
    // √E′ in Q30 from E′ in Q60 (E′ ≤ 2, so below 2⁶¹), and N·V = √E′·σ, Q30.
    let e60 = (e.max(0) as u64) << (31 - (ns.e_shift as u32).min(31));
    let root = sqrt(e60).min(u32::MAX as u64) as u32;
    let nv = ((mul_uu(root, sigma) >> 31) as i64).min(ONE30);
    // L·D̂ = (d·L)·σ, Q30: D·L is d·L in Q59, |d·L| ≤ √2; clamped to the rounding's ±1.
    let ld = (mul_iu((dl >> 29) as i32, sigma) >> 31).clamp(-ONE30, ONE30);
    // N·L = G·σ² − (N·V)(L·D̂): G in Q29 (|G·σ²| ≤ 2 on a hit), σ² in Q30.
    let g29 = high_bits(g, ns.g_shift as u32); // |G| ≤ |d|² ≤ 2 on a hit, as in `fast_cosines`
    let sigma2 = (mul_uu(sigma, sigma) >> 32) as i32;
    let nl =
        ((mul_ii(g29, sigma2) >> 29) - (mul_ii(nv as i32, ld as i32) >> 30)).clamp(-ONE30, ONE30);
    Some((sigma, nl, nv, ld))
}

/// The lobe's `h = 1 − cos` in U3F61 from `N·L`, `N·V` and `L·D̂` in Q30 (`None` where
/// Blinn-Phong's half vector is undefined, `L = −V`): the tail of [`precise_h`], and of a
/// point light's lobe (`point_light`).
#[inline(always)]
pub(super) fn precise_h_of(blinn: bool, nl: i64, nv: i64, ld: i64) -> Option<u64> {
    const ONE30: i64 = 1 << 30;
    let cos = if blinn {
        // N·H = (N·L + N·V)/|L + V|, |L + V|² = 2 − 2·L·D̂ (V = −D̂), Q30.
        let len2 = (2 * ONE30 - 2 * ld).max(0) as u64;
        let (y, s) = inv_sqrt(len2)?;
        // 1/|L + V| = y·2^(15 − s); |N·L + N·V| ≤ 2.
        let sum = (nl + nv).clamp(-2 * ONE30, 2 * ONE30);
        let p = mul_iu((sum >> 1) as i32, y); // (N·L + N·V)/2 times y, Q30 + s − 15
        p >> (s - 16).min(63)
    } else {
        // R·V = 2·(N·L)(N·V) + L·D̂.
        (mul_ii(nl as i32, nv as i32) >> 29) + ld
    };
    // h = 1 − cos in Q30, then U3F61 (h ≥ 1 is a lobe of 0, which `lobe` gives).
    Some(((ONE30 - cos).clamp(0, 4 * ONE30 - 1) as u64) << 31)
}

/// The fast lobe (U1F16) at `h` (Q31) where it is within half a level (see the module
/// docs): everywhere the fast `h` is `trusted` if the sphere's `fast_lobe_max` says so,
/// otherwise where `h ≤ ½` and the lobe is at most `fast_lobe_max`; `None` where the
/// precise lobe must decide.
#[inline(always)]
pub(super) fn fast_lobe(ns: &NarrowSphere, n: Exact, h: u32, trusted: bool) -> Option<u32> {
    if !trusted || ns.fast_lobe_max == 0 {
        return None;
    }
    let lobe = narrow_lobe(h, n);
    (ns.fast_lobe_max >= 1 << 16 || (h <= 1 << 30 && lobe <= ns.fast_lobe_max)).then_some(lobe)
}

/// The lobe `(1 − h)ⁿ` in U1F16 (`1 << 16` is 1) for `h` in Q31, in 32-bit arithmetic: the
/// fast lobe's and the precise lobe's.
///
/// The same route as [`super::pow::lobe`] (the full-width kernel's) with fewer bits:
/// `g = −log2(1 − h)` in Q27 (by its series `h·(1 + h/2 + h²/3)/ln 2` for `h < 2⁻⁵`, the
/// factor times the whole of `h` in one 32×32→64 product so that `g` keeps `h`'s relative
/// precision however small `h` is; otherwise from a power of two, the shared 64-entry table
/// of `log2 m₀` and `ln(1 + δ) ≈ δ − δ²/2 + δ³/3`), `y = n·g` in Q16 (one 32×32→64
/// product), and `2^-y` ([`exp2_neg_q16`]).
/// Within `5.4·10⁻⁵` of `powf` for `n` up to 1250 and `7.2·10⁻⁵` at `10⁴` (`g`'s last bit
/// times `n` beyond: `5·10⁻³` at `10⁶`; test `narrow_lobe_matches_powf`), a few U1F16 steps,
/// which is the precision the kernel keeps of a lobe. A fraction of the 64-bit `pow::lobe`'s
/// instructions on ARMv6-M; out of line there, where it is both smaller and faster than
/// inlined in the pixel loop and the precise lobe (`docs/performance.md, "Choices measured"`).
#[cfg_attr(shadeline_short_mul, inline(never))]
#[cfg_attr(not(shadeline_short_mul), inline(always))]
pub(super) fn narrow_lobe(h: u32, n: Exact) -> u32 {
    const ONE_Q31: u32 = 1 << 31;
    if h >= ONE_Q31 {
        return 0;
    }
    let g = if h < 1 << 26 {
        // p = 1 + h/2 + h²/3 in Q30; (h>>11)² is h² in Q40.
        let h2 = ((h >> 11) * (h >> 11)) >> 10;
        let p = (1 << 30) + (h >> 2) + (((h2 >> 4) * 21_845) >> 12);
        // q = p/ln 2 in Q31 (< 1.5·2³¹), then g = h·q in Q27, from the whole of h: a
        // 32×32→64 product, so that g keeps h's relative precision however small h is.
        let q = (p >> 14) * ((INV_LN2_F31 >> 16) as u32);
        (mul_uu(h, q) >> 35) as u32
    } else {
        let c = ONE_Q31 - h; // 1 − h in Q31, > 0
        let e = leading_zeros32(c); // ≥ 1
        let m = c << e; // m₀·(1 + δ) in U1F31
        let (inv_m0, log2_m0) = LOG_TABLE
            .get(((m >> 25) & 63) as usize)
            .copied()
            .unwrap_or((1 << 31, 0));
        // δ = (m − m₀)/m₀ in Q31 (< 2²⁵): (m − m₀) < 2²⁵ in Q31, taken as Q22.
        let delta = ((((m & ((1 << 25) - 1)) >> 9) * (inv_m0 >> 15)) >> 7) as i32;
        let d10 = delta >> 10; // Q21, |d10| < 2¹⁵
        let d2 = (d10 * d10) >> 11; // δ² in Q31
        let d3 = ((((d2 >> 9) * d10) >> 12) * 21_845) >> 16; // δ³/3 in Q31 (|δ³| < 2¹³)
        let ln = delta - (d2 >> 1) + d3; // ln(1 + δ), Q31
        let log2_1p = ((ln >> 9) * ((INV_LN2_F31 >> 17) as i32)) >> 9; // Q27
        let log2_m = (log2_m0 >> 5) as i64 + log2_1p as i64; // Q27, in [0, 1)
        (((e as i64) << 27) - log2_m).clamp(0, u32::MAX as i64) as u32
    };
    exp2_neg_q16(shift_saturating(mul_uu(n.mantissa, g), n.exponent - 11))
}
