//! Square roots and inverse square roots of unsigned integers, in integer arithmetic only.
//!
//! The fixed kernel needs `1/|v|` to make unit vectors (the primary ray, the direction to a
//! point light, Blinn-Phong's half vector), `1/r` for normals and `1/d²` for point-light
//! falloff, and `√disc` for ray-sphere hits. The `fixed` crate has a `sqrt` (bit by bit: one
//! iteration per result bit, and it panics on negative input) but no inverse square root and
//! no reciprocal that cannot divide by zero, so both are built here from one primitive:
//!
//! - normalize `x` by an even shift so that its top 32 bits `u` read as a value in `[1, 4)`;
//! - look up `1/√u` at the centre of one of 192 bins (relative error ≤ 2⁻⁸; the table is made
//!   at compile time by [`u64::isqrt`], integers only);
//! - two Newton steps `y ← y·(3 − u·y²)/2` in 32-bit fractions (error ≤ 1.5·(1.5·2⁻¹⁶)² ≈ 2⁻³⁰).
//!
//! Six exact 32×32→64-bit products ([`super::mul`]), no division, no loop, no branch on the
//! value: on a Cortex-M0 cheaper than the 64-bit division routine a plain reciprocal would
//! call. Measured (tests below): relative error below `3·2⁻³¹` over the whole `u64`
//! range for `inv_sqrt`, below `4·2⁻³¹` for `sqrt`.

use super::mul::{leading_zeros, mul_uu};

/// Entries of the table: one per top-8-bit pattern of a `u32`. A value in `[1, 4)` (U2F30)
/// reads `64..=255`; the entries below 64, which it never reaches, repeat bin 64's, so that
/// the top byte indexes the table with no check (the narrow kernel's `rsqrt_at` reads it per
/// pixel).
const BINS: usize = 256;

/// `2³¹/√u` at the centre of each bin, U1F31 (`(2³⁰, 2³¹]`).
static INV_SQRT_TABLE: [u32; BINS] = inv_sqrt_table();

const fn inv_sqrt_table() -> [u32; BINS] {
    let mut table = [0u32; BINS];
    let mut i = 0;
    while i < BINS {
        // Bin `64 + j` covers u in [(64 + j)/64, (65 + j)/64); its centre in U2F30.
        let j = i.saturating_sub(64) as u64;
        let centre = ((64 + j) << 24) + (1 << 23);
        // 2³¹/√(centre/2³⁰) = 2⁶¹/√(centre·2³⁰); the rounding error is below 2⁻³¹ relative.
        let root = (centre << 30).isqrt();
        table[i] = ((1u64 << 61) / root) as u32;
        i += 1;
    }
    table
}

/// `1/√x` for `x > 0`, as `(y, shift)` with `1/√x ≈ y·2^-shift` and `y` in `(2³⁰, 2³¹]`
/// (a U1F31 value in `(½, 1]`); `shift` is in `31..=62`. `None` for `x = 0`.
///
/// The result applies to the raw integer: if `x` is the raw bits of a squared length in some
/// fixed format, `v·y >> (shift − F)` turns a component `v` of the same format into an F-bit
/// fraction of the unit vector.
#[inline]
pub(crate) fn inv_sqrt(x: u64) -> Option<(u32, u32)> {
    if x == 0 {
        return None;
    }
    let (_, y, half_shift) = estimate(x);
    Some((y, 62 - half_shift))
}

/// `√x` within `4·2⁻³¹` relative (0 for 0), as an integer.
#[inline]
pub(crate) fn sqrt(x: u64) -> u64 {
    if x == 0 {
        return 0;
    }
    let (u, y, half_shift) = estimate(x);
    // √u = u·(1/√u): U2F30 × U1F31 = F61, down to F31: √u·2³¹ in [2³¹, 2³²).
    let root = mul_uu(u, y) >> 30;
    // x·2^(2·half_shift) ≈ u·2³² with u = √u-value²·2³⁰, so √x = (√u-value·2³¹)·2^-half_shift.
    root >> half_shift
}

/// The shared part of [`inv_sqrt`] and [`sqrt`] for `x > 0`: `(u, y, half_shift)` with `u`
/// the top bits of `x` ([`top_bits`]) and `y ≈ 2³¹/√u` in U1F31 ([`refine`]). One copy on
/// ARMv6-M, for its flash (the prepare, the precise lobe and the vector normalization take
/// square roots, none of them per pixel); inlined elsewhere.
#[cfg_attr(shadeline_short_mul, inline(never))]
#[cfg_attr(not(shadeline_short_mul), inline(always))]
fn estimate(x: u64) -> (u32, u32, u32) {
    let (u, half_shift) = top_bits(x);
    (u, refine(u, initial(u)), half_shift)
}

/// The top 32 bits of `x` after an even left shift, `u` in `[2³⁰, 2³²)` (a U2F30 value in
/// `[1, 4)`), and half of that shift.
#[inline(always)]
fn top_bits(x: u64) -> (u32, u32) {
    let half_shift = leading_zeros(x) / 2;
    let normalized = x << (2 * half_shift);
    ((normalized >> 32) as u32, half_shift)
}

/// The table's estimate of `1/√u` for `u` in U2F30, `[1, 4)`, in U1F31: also the narrow
/// kernel's `rsqrt_at` (`super::narrow_roots`), which takes its top 16 bits.
#[inline(always)]
pub(super) fn initial(u: u32) -> u32 {
    debug_assert!(u >= 1 << 30, "u = {u:#x} is not in [1, 4)");
    INV_SQRT_TABLE
        .get((u >> 24) as usize)
        .copied()
        .unwrap_or(1 << 30)
}

/// Two Newton steps for `1/√u`: `y ← y·(3 − u·y²)/2`, all U1F31 / U2F30 in `u64`.
#[inline(always)]
fn refine(u: u32, y0: u32) -> u32 {
    let mut y = y0;
    for _ in 0..2 {
        // Every product has two 32-bit operands: y ≤ 2³¹, y² ≤ 2³¹, u < 2³².
        let y2 = (mul_uu(y, y) >> 31) as u32; // U1F31, ≤ 2³¹
        let uy2 = mul_uu(u, y2) >> 30; // F31, ≈ 2³¹
        let t = (3u64 << 31).saturating_sub(uy2); // F31, ≈ 2³², below 2³³
                                                  // y·t with t split at bit 32 (its high part is 0 or 1).
        let high = if t >> 32 != 0 { (y as u64) << 32 } else { 0 };
        let yt = mul_uu(y, t as u32) + high;
        y = (yt >> 32).min(u32::MAX as u64) as u32; // y·t/2 in F31
    }
    // Newton for 1/√u approaches from below: y ≤ 2³¹ (value ≤ 1). The clamp is for the proof.
    y.min(1 << 31)
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;
    use std::println;

    fn rel_inv_sqrt(x: u64) -> f64 {
        let (y, shift) = inv_sqrt(x).unwrap();
        let got = y as f64 * (-(shift as f64)).exp2();
        let want = 1.0 / (x as f64).sqrt();
        (got - want).abs() / want
    }

    #[test]
    fn inv_sqrt_is_accurate() {
        let mut worst = 0.0f64;
        let mut x = 1u64;
        // Every power of two and a dense walk between them.
        while x < u64::MAX / 3 {
            for k in 0..64u64 {
                let v = x + (x / 64) * k;
                worst = worst.max(rel_inv_sqrt(v));
            }
            x *= 2;
        }
        for v in [
            1u64,
            2,
            3,
            4,
            5,
            u64::MAX,
            u64::MAX - 1,
            1 << 63,
            (1 << 62) - 1,
        ] {
            worst = worst.max(rel_inv_sqrt(v));
        }
        println!(
            "inv_sqrt worst relative error {worst:e} ({:.2}·2^-31)",
            worst * 2f64.powi(31)
        );
        assert!(worst < 3.0 * 2f64.powi(-31), "{worst:e}");
        assert_eq!(inv_sqrt(0), None);
    }

    #[test]
    fn sqrt_is_accurate() {
        let mut worst = 0.0f64;
        let mut x = 1u64 << 20;
        while x < u64::MAX / 3 {
            for k in 0..64u64 {
                let v = x + (x / 64) * k;
                let got = sqrt(v) as f64;
                let want = (v as f64).sqrt();
                // An integer result: within one unit, or 4·2⁻³¹ relative.
                worst = worst.max(((got - want).abs() - 1.0).max(0.0) / want);
            }
            x *= 2;
        }
        println!("sqrt worst relative error {worst:e}");
        assert!(worst < 4.0 * 2f64.powi(-31) + 1e-12, "{worst:e}");
        assert_eq!(sqrt(0), 0);
        assert!(sqrt(1 << 32).abs_diff(1 << 16) <= 1);
        assert!(sqrt(u64::MAX).abs_diff(1 << 32) <= 2);
    }
}
