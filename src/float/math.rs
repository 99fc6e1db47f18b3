//! The one transcendental the float kernel needs — `x^n` for the specular lobe — written once
//! over [`Lane`], so that the scalar and SIMD paths compute it with the same operations in the
//! same order and agree bit for bit.
//!
//! Why not a library pow: `micromath::powf` is off by up to 0.27 absolute for the exponents we
//! use (measured), far outside a one-level budget; `libm::powf` is accurate but scalar-only, and
//! `wide`'s `powf` is a different algorithm from any scalar one, so either would break the
//! bit-identity contract between widths. Repeated squaring (`powi`) is accurate but only for
//! integer `n`, and the material model accepts any `n > 0`.
//!
//! The algorithm, for `x` in `(0, 1]` and `n > 0`:
//!
//! 1. `log2 x`: split `x = m·2^e` exactly, fold `m` into `[√½, √2)`, then
//!    `ln m = 2·atanh(t)`, `t = (m − 1)/(m + 1)`, `|t| ≤ 0.1716`, as an odd series through
//!    `t^9` (truncation error below `3e-9` relative). `m − 1` is exact (Sterbenz), so `log2 x`
//!    keeps full relative precision as `x → 1`, where the highlight is.
//! 2. `y = n · log2 x ≤ 0`.
//! 3. `2^y`: `y = k + f` with `k` the nearest integer (the `1.5·2^23` rounding trick, exact) and
//!    `|f| ≤ ½`; `2^f` by its Taylor series through degree 7 (truncation below `5e-9`), and
//!    `2^k` built exactly from bits. Results below `2^-125` flush to zero.
//!
//! Measured against `f64::powf` (test `pow_accuracy` below), for `n` in `1..=10000`: relative
//! error at most `1.3e-6` where the result is at least `1e-3`, at most `3e-6` down to `1e-6`,
//! and absolute error below `4e-12` under that. The relative error grows with `|y|` because
//! `y` itself is an `f32`: its last-bit rounding, `|y|·6e-8`, becomes a relative error of
//! `|y|·4e-8` after `2^y`.

use super::lane::Lane;
use crate::brdf::Pow;

const SQRT_2: f32 = core::f32::consts::SQRT_2;
/// `2 / ln 2`: turns `atanh` into `log2`.
const TWO_OVER_LN2: f32 = 2.0 * core::f32::consts::LOG2_E;
/// `1.5 · 2^23`: adding and subtracting it rounds to the nearest integer for `|y| < 2^22`.
const ROUND_MAGIC: f32 = 12_582_912.0;
/// `ln(2)^k / k!` for `k = 1..=7`: Taylor coefficients of `2^f`.
const EXP2_C: [f32; 7] = [
    core::f32::consts::LN_2,
    0.240_226_5,
    0.055_504_11,
    0.009_618_129,
    0.001_333_355_8,
    0.000_154_035_3,
    0.000_015_252_734,
];

/// `log2(x)` for positive, normal `x`; other lanes give unspecified finite values.
#[inline(always)]
pub fn log2<L: Lane>(x: L) -> L {
    let (m, e) = x.split_exponent();
    let big = L::splat(SQRT_2).lt(m);
    let m = L::select(big, m * L::splat(0.5), m);
    let e = L::select(big, e + L::splat(1.0), e);
    let one = L::splat(1.0);
    let t = (m - one) / (m + one);
    let z = t * t;
    // (2/ln 2)·(1 + z/3 + z²/5 + z³/7 + z⁴/9), Horner, with the constant folded in.
    let c = TWO_OVER_LN2;
    let p = L::splat(c)
        + z * (L::splat(c / 3.0)
            + z * (L::splat(c / 5.0) + z * (L::splat(c / 7.0) + z * L::splat(c / 9.0))));
    e + t * p
}

/// `2^y` for `y ≤ 0`; lanes with `y < -125` give exactly `0`.
#[inline(always)]
pub fn exp2_neg<L: Lane>(y: L) -> L {
    let floor_limit = L::splat(-125.0);
    let underflow = y.lt(floor_limit);
    let yc = y.max(floor_limit);
    let magic = L::splat(ROUND_MAGIC);
    let k = (yc + magic) - magic;
    let f = yc - k;
    let c = EXP2_C;
    let p = L::splat(1.0)
        + f * (L::splat(c[0])
            + f * (L::splat(c[1])
                + f * (L::splat(c[2])
                    + f * (L::splat(c[3])
                        + f * (L::splat(c[4]) + f * (L::splat(c[5]) + f * L::splat(c[6])))))));
    L::select(underflow, L::splat(0.0), p * L::pow2i(k))
}

/// `max(0, x)^n` for `n > 0`: the specular lobe's power.
///
/// `x ≤ 0` (and NaN) give `0`; `x ≥ 1` gives `1`; `n` may differ per lane.
#[inline(always)]
pub fn pow_clamped<L: Lane>(x: L, n: L) -> L {
    let zero = L::splat(0.0);
    let one = L::splat(1.0);
    // Below the smallest normal, x^n underflows for every n ≥ 1 and is < 1e-15 for n ≥ 0.1;
    // treating it as zero keeps `split_exponent` on normal inputs.
    let positive = L::splat(f32::MIN_POSITIVE).le(x);
    let xc = x.min(one).max(L::splat(f32::MIN_POSITIVE));
    let r = exp2_neg(n * log2(xc));
    L::select(positive, r, zero)
}

/// The lanes' power for [`crate::brdf`]: this module's `pow_clamped`, the same code at every
/// width.
impl<T: Lane> Pow for T {
    #[inline(always)]
    fn pow_clamped(x: Self, n: Self) -> Self {
        pow_clamped(x, n)
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;
    use wide::{f32x4, f32x8};

    /// Largest relative error against `f64::powf` for results in `[1e-3, 1]` and in
    /// `[1e-6, 1e-3)`; below `1e-6` the absolute error must stay under `4e-12`.
    fn max_rel_errors(n: f32) -> (f64, f64) {
        let (mut near, mut far) = (0.0f64, 0.0f64);
        let steps = 20_000;
        for i in 1..=steps {
            // Dense near 1, where the highlight is, and across (0, 1).
            let u = i as f64 / steps as f64;
            for x in [u as f32, (1.0 - (1.0 - u).powi(4) * 0.999) as f32] {
                let got = pow_clamped(x, n) as f64;
                let want = (x as f64).powf(n as f64);
                let rel = ((got - want) / want).abs();
                if want >= 1e-3 {
                    near = near.max(rel);
                } else if want >= 1e-6 {
                    far = far.max(rel);
                } else {
                    assert!((got - want).abs() < 4e-12, "x={x} n={n}: {got} vs {want}");
                }
            }
        }
        (near, far)
    }

    #[test]
    fn pow_accuracy() {
        for n in [
            1.0f32, 2.0, 2.5, 10.0, 37.3, 50.0, 250.0, 1250.0, 5000.0, 10000.0,
        ] {
            let (near, far) = max_rel_errors(n);
            assert!(
                near < 1.5e-6,
                "n={n}: max relative error {near:e} for results >= 1e-3"
            );
            assert!(
                far < 3.5e-6,
                "n={n}: max relative error {far:e} for results in [1e-6, 1e-3)"
            );
        }
    }

    #[test]
    fn pow_edges() {
        assert_eq!(pow_clamped(0.0f32, 2.0), 0.0);
        assert_eq!(pow_clamped(-0.5f32, 2.0), 0.0);
        assert_eq!(pow_clamped(f32::NAN, 2.0), 0.0);
        assert_eq!(pow_clamped(1.0f32, 1e6), 1.0);
        assert_eq!(pow_clamped(2.0f32, 3.0), 1.0);
        assert_eq!(pow_clamped(0.5f32, 1e6), 0.0);
        assert!(pow_clamped(f32::MIN_POSITIVE, 0.01) > 0.0);
    }

    #[test]
    fn pow_is_bit_identical_at_every_width() {
        let mut x = 0.000_123f32;
        while x < 1.0 {
            for n in [1.0f32, 7.7, 1250.0, 10000.0] {
                let s = pow_clamped(x, n);
                let v4 = pow_clamped(f32x4::splat(x), f32x4::splat(n));
                let v8 = pow_clamped(f32x8::splat(x), f32x8::splat(n));
                for i in 0..8 {
                    assert_eq!(v8.lane(i).to_bits(), s.to_bits());
                    assert_eq!(v4.lane(i % 4).to_bits(), s.to_bits());
                }
            }
            x = x * 1.0137 + 1e-5;
        }
    }
}
