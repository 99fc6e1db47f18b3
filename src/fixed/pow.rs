//! The specular lobe `cos^n` in integers only, for any shininess `n > 0` (not only integers)
//! and with precision where it matters: next to the highlight.
//!
//! # Why this form
//!
//! The input is not the cosine but `h = 1 − cos` as U3F61. For unit vectors
//! `1 − R·V = ½|R − V|²` (and `1 − N·H = ½|N − H|²`), so the kernel gets `h` from a sum of
//! squares of 30-bit-fraction differences, exactly, with full *relative* precision as
//! `h → 0`. A cosine held in I16F16 would be off by up to `2⁻¹⁷`, which becomes a relative
//! lobe error of `n·2⁻¹⁷`: 1% at `n = 1250`, 100% at `n ≈ 10⁵` (the test below prints it).
//!
//! Repeated squaring only handles integer `n`, and a per-material table over
//! `[ε^(1/n), 1]` costs 512 bytes of RAM per sphere (too much for a 16 KB Cortex-M0 frame), so
//! the lobe is `2^(−n·g)` with `g = −log2(1 − h)`:
//!
//! 1. `g`: for `h < 2⁻⁵` by its series `(h + h²/2 + h³/3 + h⁴/4 + h⁵/5)/ln 2`, computed as
//!    `h` times a 32-bit correction factor, so `g` keeps `h`'s relative precision however small
//!    `h` is (down to `2⁻⁶¹`); otherwise `1 − h = m·2^-e` with `m` in `[1, 2)`, `log2 m` from a
//!    64-entry table at `m₀` and `ln(1 + δ)`, `δ = m/m₀ − 1 < 2⁻⁶`, by four series terms
//!    (`m/m₀` is a multiplication by a tabulated `1/m₀`, not a division).
//! 2. `y = n·g` with `n` held exactly (the `f32`'s 24-bit mantissa and exponent), `g` as a
//!    normalized 32-bit mantissa and exponent, the product shifted into U6F26. `y ≥ 32` gives
//!    a lobe below the U1F31 resolution: 0.
//! 3. `2^-y = 2^-k · 2^(-i/64) · e^(−r·ln 2)`: a shift, a 64-entry table, and four series
//!    terms for `r < 2⁻⁶`.
//!
//! Every table is made at compile time by integer-only `const fn`s (binary logarithm by
//! repeated squaring, a root by bisection), so neither the tables nor the code hold a float.
//! Cost: about 12 32×32→64-bit multiplications, two leading-zero counts, no division.
//!
//! [`lobe`] is the full-width kernel's (feature `full-width`). The narrow kernel's lobe
//! (`narrow_lobe::narrow_lobe`) takes the same route in 32-bit arithmetic, with the tables and
//! its `2^-y` from here ([`exp2_neg_q16`]), which are all a build without `full-width` holds
//! of this module.
//!
//! # Measured error
//!
//! Against `f64` `powf` of the same `h` (test `lobe_error_per_n`, printed with
//! `cargo test --lib lobe_error_per_n -- --nocapture`), over 200 000 cosines dense near 1:
//!
//! | n | max abs error | max rel. error where lobe ≥ 10⁻³ | I16F16 cosine instead: max abs error |
//! |---|---|---|---|
//! | 0.5 | 1.1e-8 | 1.8e-8 | 1.3e-4 |
//! | 2 | 1.1e-8 | 2.2e-7 | 3.1e-5 |
//! | 10 | 1.1e-8 | 2.1e-7 | 1.5e-4 |
//! | 50 | 1.1e-8 | 2.7e-7 | 7.6e-4 |
//! | 250 | 1.1e-8 | 2.5e-7 | 3.8e-3 |
//! | 1250 | 1.1e-8 | 2.3e-7 | 1.9e-2 |
//! | 10⁴ | 1.1e-8 | 2.3e-7 | 0.14 |
//! | 10⁶ | 1.1e-8 | 2.4e-7 | 1.0 |
//!
//! The error does not grow with `n`: about 24 steps of U1F31 absolute (from the U6F26
//! exponent, `y·2⁻²⁶`, and the tables' last bits), and the relative error where the lobe is at
//! least 10⁻³ is one U1F31 step over 10⁻³. The last column is what the same pow would give
//! fed a cosine rounded to I16F16: its error grows as `n·2⁻¹⁶` and swamps an 8-bit level at
//! `n = 250`. In the image, the geometry's own error (the cosine from 30-bit unit vectors,
//! about 10⁻⁹ relative) takes over beyond `n ≈ 10⁵`.

/// `1 − cos` in U3F61: `1.0` is `1 << 61`.
#[cfg(feature = "full-width")]
const ONE_F61: u64 = 1 << 61;
/// Below this `h` (`2⁻⁵`), `g` comes from its series; above, from the table.
#[cfg(feature = "full-width")]
const SERIES_LIMIT: u64 = 1 << 56;
/// `1.0` in U1F31.
#[cfg(feature = "full-width")]
const ONE_F31: u64 = 1 << 31;
/// `1/ln 2` in U1F31.
pub(super) const INV_LN2_F31: u64 = 3_098_164_009;
/// `ln 2` in U0F32.
#[cfg(feature = "full-width")]
const LN2_F32: u64 = 2_977_044_472;
/// `1/k` in U1F31.
#[cfg(feature = "full-width")]
const HALF_F31: u64 = 1 << 30;
#[cfg(feature = "full-width")]
const THIRD_F31: u64 = 715_827_883;
#[cfg(feature = "full-width")]
const QUARTER_F31: u64 = 1 << 29;
#[cfg(feature = "full-width")]
const FIFTH_F31: u64 = 429_496_730;
#[cfg(feature = "full-width")]
const SIXTH_F31: u64 = 357_913_941;
#[cfg(feature = "full-width")]
const TWENTYFOURTH_F31: u64 = 89_478_485;

#[cfg(feature = "full-width")]
use super::exact::Exact;
#[cfg(feature = "full-width")]
use super::mul::{leading_zeros, mul_iu, mul_uu};

/// The product of two values held in `u64` that both fit 32 bits (every operand in this
/// module does: the formats above bound them), exact.
#[cfg(feature = "full-width")]
#[inline(always)]
fn mul(a: u64, b: u64) -> u64 {
    mul_uu(a as u32, b as u32)
}

/// `(1 − h)^n` in U1F31 (`1 << 31` is 1.0) for `h` in U3F61; 0 where `h ≥ 1` (cosine ≤ 0).
#[cfg(feature = "full-width")]
#[inline]
pub(crate) fn lobe(h: u64, n: Exact) -> u32 {
    if h >= ONE_F61 {
        return 0;
    }
    if h == 0 {
        return ONE_F31 as u32;
    }
    let (g_mantissa, g_exponent) = if h < SERIES_LIMIT {
        neg_log2_small(h)
    } else {
        neg_log2_table(h)
    };
    let product = mul_uu(n.mantissa, g_mantissa);
    match to_u6f26(product, n.exponent + g_exponent + 26) {
        Some(y) => exp2_neg(y),
        None => 0,
    }
}

/// `−log2(1 − h)` for `0 < h < 2⁻⁵` (U3F61) as `(m, e)`, value `m·2^e`, `m` normalized.
#[cfg(feature = "full-width")]
#[inline(always)]
fn neg_log2_small(h: u64) -> (u32, i32) {
    let h32 = h >> 29; // U0F32, < 2²⁷
                       // (1 + h/2 + h²/3 + h³/4 + h⁴/5)/ln 2, Horner in U1F31.
    let mut p = FIFTH_F31;
    p = QUARTER_F31 + (mul(h32, p) >> 32);
    p = THIRD_F31 + (mul(h32, p) >> 32);
    p = HALF_F31 + (mul(h32, p) >> 32);
    p = ONE_F31 + (mul(h32, p) >> 32);
    let q = mul(p, INV_LN2_F31) >> 31; // < 1.48·2³¹
                                       // h ≈ top·2^(−29 − hz) with top its 32 leading bits.
    let hz = leading_zeros(h);
    let top = (h << hz) >> 32;
    let g = mul(top, q); // value g·2^(−60 − hz)
    let gz = leading_zeros(g);
    (((g << gz) >> 32) as u32, -28 - gz as i32 - hz as i32)
}

/// `−log2(1 − h)` for `2⁻⁵ ≤ h < 1` (U3F61) as `(m, e)`, value `m·2^e`, `m` normalized.
#[cfg(feature = "full-width")]
#[inline(always)]
fn neg_log2_table(h: u64) -> (u32, i32) {
    let x = ONE_F61 - h; // > 0, ≤ 2⁶¹·(1 − 2⁻⁵)
    let xz = leading_zeros(x); // ≥ 3
    let xn = x << xz; // m·2⁶³, m in [1, 2); x = m·2^(2 − xz)
    let m = xn >> 32; // U1F31
    let bin = ((xn >> 57) & 63) as usize;
    debug_assert!(bin < LOG_TABLE.len());
    let (inv_m0, log2_m0) = LOG_TABLE.get(bin).copied().unwrap_or((1 << 31, 0));
    // δ = m/m₀ − 1 in [0, 2⁻⁶), signed F31 (rounding of 1/m₀ may make it −1 ulp).
    let delta = (mul(m, inv_m0 as u64) >> 31) as i64 - ONE_F31 as i64;
    // ln(1 + δ) = δ(1 − δ(1/2 − δ(1/3 − δ/4))); |δ| < 2²⁵ and 0 < t ≤ 2³¹ + 1.
    let signed = |delta: i64, t: i64| mul_iu(delta as i32, t as u32);
    let mut t = THIRD_F31 as i64 - (signed(delta, QUARTER_F31 as i64) >> 31);
    t = HALF_F31 as i64 - (signed(delta, t) >> 31);
    t = ONE_F31 as i64 - (signed(delta, t) >> 31);
    let ln = signed(delta, t) >> 31;
    let log2_1p = signed(ln, INV_LN2_F31 as i64) >> 31; // F31
    let log2_m = log2_m0 as i64 + 2 * log2_1p; // F32, in [0, 1)
    let g = (((xz as i64) - 2) << 32) - log2_m; // F32, > 0
    let g = g.max(1) as u64;
    let gz = leading_zeros(g);
    (((g << gz) >> 32) as u32, -(gz as i32))
}

/// `p·2^e` as U6F26, or `None` if it is 64 or more.
#[cfg(feature = "full-width")]
#[inline(always)]
fn to_u6f26(p: u64, e: i32) -> Option<u32> {
    if p == 0 {
        return Some(0);
    }
    let s = e.unsigned_abs();
    if e >= 0 {
        if s >= 32 || (p >> (32 - s)) != 0 {
            return None;
        }
        Some((p << s) as u32)
    } else {
        let v = p.checked_shr(s).unwrap_or(0);
        u32::try_from(v).ok()
    }
}

/// `2^-y` in U1F31 for `y` in U6F26.
#[cfg(feature = "full-width")]
#[inline(always)]
fn exp2_neg(y: u32) -> u32 {
    let k = y >> 26;
    if k >= 32 {
        return 0;
    }
    let f = y & 0x3ff_ffff;
    let bin = (f >> 20) as usize;
    let r = (f & 0xf_ffff) as u64; // F26, < 2⁻⁶
    let a = mul(r << 5, LN2_F32) >> 32; // r·ln 2 in F31, < 0.011
                                        // e^-a = 1 − a(1 − a(1/2 − a(1/6 − a/24))).
    let mut t = SIXTH_F31 - (mul(a, TWENTYFOURTH_F31) >> 31);
    t = HALF_F31 - (mul(a, t) >> 31);
    t = ONE_F31 - (mul(a, t) >> 31);
    let e = ONE_F31 - (mul(a, t) >> 31);
    debug_assert!(bin < EXP_TABLE.len(), "exponent bin {bin}");
    let base = EXP_TABLE.get(bin).copied().unwrap_or(0) as u64;
    let v = (mul(base, e) + (1 << 30)) >> 31; // ≤ 2³¹
    let v = if k == 0 { v } else { (v + (1 << (k - 1))) >> k };
    v.min(ONE_F31) as u32
}

/// The bound of [`exp2_neg_q16`]'s error, in U1F16 steps (`2⁻¹⁶`), against `2^-y` of the
/// same `y` (test `exp2_neg_q16_within_its_bound`). Only the tests read it.
#[cfg_attr(not(test), allow(dead_code))]
pub(super) const EXP2_NEG_Q16_STEPS: f64 = 3.5;

/// `2^-y` in U1F16 (`1 << 16` is 1), rounded, for `y` in Q16: the narrow kernel's, in 32-bit
/// arithmetic. `2^-k` as a shift, `2^(−i/64)` from [`EXP_TABLE`]'s top 17 bits, and
/// `e^(−r·ln 2) ≈ 1 − a + a²/2` for the rest `r < 2⁻⁶`; 0 from `y ≥ 17` on, where `2^-y` is
/// below half a step. Within [`EXP2_NEG_Q16_STEPS`].
#[inline(always)]
pub(super) fn exp2_neg_q16(y: u32) -> u32 {
    let k = y >> 16;
    if k >= 17 {
        return 0;
    }
    let f = y & 0xffff;
    debug_assert!(((f >> 10) as usize) < EXP_TABLE.len());
    let base = EXP_TABLE.get((f >> 10) as usize).copied().unwrap_or(0) >> 15; // Q16, ≤ 2¹⁶
    let a = ((f & 1023) * 45_426) >> 16; // r·ln 2 in Q16, < 2¹⁰
    let e = (1 << 16) - a + ((a * a) >> 17); // e^(−a), Q16
    let v = (base * (e >> 1)) >> 15; // ≤ 2¹⁶
    (v + ((1 << k) >> 1)) >> k
}

/// `(round(2³¹/m₀), log2(m₀) in U0F32)` for `m₀ = 1 + i/64`.
pub(super) static LOG_TABLE: [(u32, u32); 64] = log_table();
/// `round(2³¹·2^(−i/64))`.
pub(super) static EXP_TABLE: [u32; 64] = exp_table();

const fn log_table() -> [(u32, u32); 64] {
    let mut table = [(0u32, 0u32); 64];
    let mut i = 0;
    while i < 64 {
        let num = 64 + i as u64;
        let inv = ((1u64 << 38) / num).div_ceil(2); // round(2³⁷/num) = round(2³¹·64/num)
        table[i] = (inv as u32, log2_fraction(num << 56));
        i += 1;
    }
    table
}

/// `log2(x)` for `x` in `[1, 2)` given in U2F62, as U0F32 (rounded), by repeated squaring:
/// each squaring doubles the logarithm, and a result of 2 or more is one more bit.
const fn log2_fraction(x: u64) -> u32 {
    let mut x = x as u128;
    let mut bits: u64 = 0;
    let mut i = 0;
    while i < 40 {
        x = (x * x) >> 62;
        bits <<= 1;
        if x >= 2u128 << 62 {
            x >>= 1;
            bits |= 1;
        }
        i += 1;
    }
    ((bits + 128) >> 8) as u32
}

const fn exp_table() -> [u32; 64] {
    // c = 2^(−1/64) in U1F62, by bisection on c⁶⁴ = ½.
    let (mut lo, mut hi) = (1u128 << 61, 1u128 << 62);
    while hi - lo > 1 {
        let mid = (lo + hi) / 2;
        let mut p = mid;
        let mut k = 0;
        while k < 6 {
            p = (p * p) >> 62;
            k += 1;
        }
        if p >= 1u128 << 61 {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    let c = hi;
    let mut table = [0u32; 64];
    let mut acc = 1u128 << 62;
    let mut i = 0;
    while i < 64 {
        table[i] = ((acc + (1 << 30)) >> 31) as u32;
        acc = (acc * c) >> 62;
        i += 1;
    }
    table
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;
    use std::println;

    fn to_h(cos: f64) -> u64 {
        ((1.0 - cos) * ONE_F61 as f64) as u64
    }

    #[test]
    fn exp2_neg_q16_within_its_bound() {
        let mut worst = 0.0f64;
        // Every y below 17 in steps that visit each table bin at many places, and its end.
        for y in (0..17u32 << 16)
            .step_by(7)
            .chain([(17 << 16) - 1, 17 << 16, u32::MAX])
        {
            let want = (-(y as f64) / 65536.0).exp2() * 65536.0;
            worst = worst.max((exp2_neg_q16(y) as f64 - want).abs());
        }
        println!("exp2_neg_q16: worst {worst:.3} steps of 2^-16");
        assert!(worst <= EXP2_NEG_Q16_STEPS, "{worst}");
        assert_eq!(exp2_neg_q16(0), 1 << 16);
    }

    #[test]
    fn tables_match_f64() {
        for (i, &(inv, log)) in LOG_TABLE.iter().enumerate() {
            let m0 = 1.0 + i as f64 / 64.0;
            assert!(
                (inv as f64 - 2f64.powi(31) / m0).abs() <= 0.5 + 1e-9,
                "inv {i}"
            );
            assert!(
                (log as f64 - m0.log2() * 2f64.powi(32)).abs() <= 1.0,
                "log {i}"
            );
        }
        for (i, &e) in EXP_TABLE.iter().enumerate() {
            let want = 2f64.powi(31) * (-(i as f64) / 64.0).exp2();
            assert!((e as f64 - want).abs() <= 1.0, "exp {i}: {e} vs {want}");
        }
    }

    #[test]
    fn edges() {
        let n = Exact::from_f32(50.0);
        assert_eq!(lobe(0, n), 1 << 31);
        assert_eq!(lobe(ONE_F61, n), 0);
        assert_eq!(lobe(u64::MAX, n), 0);
        assert_eq!(lobe(1, Exact::from_f32(1.0e6)), 1 << 31);
        assert_eq!(lobe(ONE_F61 - 1, Exact::from_f32(1.0e-30)), 1 << 31);
        assert_eq!(lobe(ONE_F61 / 2, Exact::from_f32(1.0)), 1 << 30);
    }

    /// Max absolute error, and max relative error where the lobe is at least 1e-3, of the
    /// lobe against f64 for the same `h`; and the absolute error an I16F16 cosine would give.
    fn measure(n: f32) -> (f64, f64, f64) {
        let shin = Exact::from_f32(n);
        let nf = n as f64;
        let (mut abs, mut rel, mut coarse) = (0.0f64, 0.0f64, 0.0f64);
        let steps = 200_000;
        for k in 0..=steps {
            // Dense near the highlight: 1 − cos from 1e-12 to 1.
            let u = k as f64 / steps as f64;
            let h_real = (1e-12f64).powf(1.0 - u);
            let h = to_h(1.0 - h_real).min(ONE_F61);
            let hq = h as f64 / ONE_F61 as f64;
            let want = (1.0 - hq).max(0.0).powf(nf);
            let got = lobe(h, shin) as f64 / 2f64.powi(31);
            abs = abs.max((got - want).abs());
            if want >= 1e-3 {
                rel = rel.max((got - want).abs() / want);
            }
            let cos16 = ((1.0 - hq) * 65536.0).floor() / 65536.0;
            coarse = coarse.max((cos16.max(0.0).powf(nf) - want).abs());
        }
        (abs, rel, coarse)
    }

    #[test]
    fn lobe_error_per_n() {
        println!(
            "| n | max abs error | max rel. error (lobe ≥ 1e-3) | I16F16 cosine: max abs error |"
        );
        println!("|---|---|---|---|");
        for n in [0.5f32, 2.0, 10.0, 50.0, 250.0, 1250.0, 1.0e4, 1.0e6] {
            let (abs, rel, coarse) = measure(n);
            println!("| {n} | {abs:.1e} | {rel:.1e} | {coarse:.1e} |");
            assert!(abs < 2e-8, "n = {n}: abs {abs:e}");
            assert!(rel < 1e-6, "n = {n}: rel {rel:e}");
        }
        // Non-integer exponents work like any other.
        let (abs, rel, _) = measure(37.3);
        assert!(abs < 2e-8 && rel < 1e-6, "n = 37.3: {abs:e} {rel:e}");
    }
}
