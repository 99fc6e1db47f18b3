//! Sphere lights on the fixed path (crate features `area-lights` and `full-width`): the
//! integer forms of the float paths' closed forms (`src/float/area.rs`, whose module docs
//! give the geometry and each formula's error), in 30-bit fractions.
//!
//! Every cosine, sine, chord and share is F30 (`1 << 30` is 1) in a `u32` or an `i64`, and
//! every angle from [`acos`] is F30 too (`π` is below `2³²`). Products are the kernel's exact
//! 32×32→64-bit ones, square roots come from [`super::roots::sqrt`], and a ratio is one
//! integer division ([`ratio`], [`quotient`]): the divisions are why this code lives only in
//! the full-width kernel, which a frame with a sphere light always takes. Each function
//! clamps its result into the range the float form's result has, so no input, however far
//! outside what the geometry gives, can wrap or panic.

use super::mul::{mul_ii, mul_uu};
use super::roots::sqrt;

/// 1 in F30.
pub(crate) const ONE: u32 = 1 << 30;
/// 1 in F60.
const ONE60: u64 = 1 << 60;
/// `π` in F30.
const PI: u32 = 3_373_259_426;
/// `1/π` in F32.
const INV_PI: u32 = 1_367_130_551;
/// Above this ratio of an occluder's chord to the light's, the occluder's outline is taken as
/// a straight line across the light's disc ([`covered`]).
const STRAIGHT: u64 = 256;

/// `num/den` in F30, clamped to `[−1, 1]`, for a `den > 0` of the same format as `num`
/// (0 for `den = 0`).
#[inline(always)]
pub(crate) fn ratio(num: i64, den: u64) -> i32 {
    if den == 0 {
        return 0;
    }
    let magnitude = num.unsigned_abs();
    if magnitude >= den {
        return if num < 0 { -(ONE as i32) } else { ONE as i32 };
    }
    // Both shifted right alike until the divisor has 32 bits: the quotient's error stays
    // below 2⁻³⁰ of its magnitude, and `magnitude < den < 2³²` leaves room for the F30 shift.
    let shift = 32u32.saturating_sub(den.leading_zeros());
    let (m, d) = (magnitude >> shift, (den >> shift).max(1));
    let q = ((m << 30) / d).min(ONE as u64) as i32;
    if num < 0 {
        -q
    } else {
        q
    }
}

/// `num/den` for `den > 0`, any size, as `u64` (saturating; `u64::MAX` for `den = 0`).
#[inline(always)]
pub(crate) fn quotient(num: u64, den: u64) -> u64 {
    num.checked_div(den).unwrap_or(u64::MAX)
}

/// `√x` of an F30 value, F30.
#[inline(always)]
fn sqrt30(x: u32) -> u32 {
    sqrt((x as u64) << 30).min(u32::MAX as u64) as u32
}

/// `√(1 − x²)` of an F30 `x` in `[−1, 1]`, F30.
#[inline(always)]
fn sine_of(x: i32) -> u32 {
    let m = x.unsigned_abs().min(ONE);
    sqrt(ONE60 - mul_uu(m, m)).min(ONE as u64) as u32
}

/// `acos x` for an F30 `x` (clamped to `[−1, 1]`), F30 in `[0, π]`: the float paths'
/// polynomial (Abramowitz and Stegun 4.4.46), its coefficients in F30.
#[inline(always)]
pub(crate) fn acos(x: i32) -> u32 {
    const C: [i32; 8] = [
        1_686_629_713,
        -230_423_707,
        95_540_463,
        -53_874_248,
        33_169_904,
        -18_348_236,
        7_161_955,
        -1_355_589,
    ];
    let a = x.unsigned_abs().min(ONE) as i32;
    let mut p = C[7] as i64;
    for &c in C[..7].iter().rev() {
        p = (mul_ii(p.clamp(i32::MIN as i64, i32::MAX as i64) as i32, a) >> 30) + c as i64;
    }
    let p = p.clamp(0, u32::MAX as i64) as u32;
    let r = (mul_uu(sqrt30(ONE - a as u32), p) >> 30).min(PI as u64) as u32;
    if x < 0 {
        PI - r
    } else {
        r
    }
}

/// The chord `2 sin(θ/2)` of a cap of half-angle `θ ≤ 90°` from `sin θ` (F30, clamped to
/// 1): `sin θ·√(2/(1 + cos θ))`, which keeps its relative precision for small caps.
#[inline(always)]
pub(crate) fn chord(sin: u32) -> u32 {
    let s = sin.min(ONE);
    let cos = sine_of(s as i32) as u64; // F30
    let factor = quotient(2 * ONE60, ONE as u64 + cos).min(u32::MAX as u64) as u32; // F30, [1, 2]
    (mul_uu(s, sqrt30(factor)) >> 30) as u32
}

/// The share of a unit disc beyond a chord at signed distance `t` (F30, clamped to
/// `[−1, 1]`) from its centre: `(acos t − t√(1 − t²))/π`, F30 in `[0, 1]`.
#[inline(always)]
pub(crate) fn segment(t: i32) -> u32 {
    let t = t.clamp(-(ONE as i32), ONE as i32);
    let kite = mul_ii(t, sine_of(t) as i32) >> 30;
    let area = (acos(t) as i64 - kite).clamp(0, PI as i64) as u32;
    over_pi(area)
}

/// `x/π` for an F30 `x` in `[0, π]`, rounded to nearest: F30 in `[0, 1]`, exactly 1 at `π`.
#[inline(always)]
fn over_pi(x: u32) -> u32 {
    (((mul_uu(x, INV_PI) + (1 << 31)) >> 32) as u32).min(ONE)
}

/// The share of a disc of radius `r1` that a disc of radius `r2` at distance `delta` from
/// its centre covers (all F30, `r1 > 0`), F30 in `[0, 1]`: the float paths' lens formula
/// `(acos c1 + q²·acos c2 − (δ/r1)·√(1 − c1²))/π` with `q = r2/r1`, and the nested and
/// disjoint cases exactly. Where `q` exceeds 256 the lens formula's terms grow as `q` while
/// their difference stays below 1, so there the occluder's outline is taken as the straight
/// line at `δ − r2` from the centre ([`segment`]): its curvature over the light's disc
/// changes the share by less than `1/(πq)`, 0.13%.
#[inline(always)]
pub(crate) fn covered(r1: u32, r2: u32, delta: u32) -> u32 {
    let (r1, r2, d) = (r1 as u64, r2 as u64, delta.max(1) as u64);
    if r1 == 0 || d >= r1 + r2 {
        return 0;
    }
    if d + r1 <= r2 {
        return ONE;
    }
    let q = quotient(r2 << 30, r1); // F30
    if d + r2 <= r1 {
        // The occluder's disc lies inside the light's: q ≤ 1.
        return (mul_uu(q as u32, q as u32) >> 30) as u32;
    }
    if q >= STRAIGHT << 30 {
        let t = ratio(d as i64 - r2 as i64, r1);
        return segment(t);
    }
    let (d2, r1s, r2s) = (d * d, r1 * r1, r2 * r2); // F60, each below 2⁶²
    let c1 = ratio(d2 as i64 + r1s as i64 - r2s as i64, 2 * d * r1);
    let c2 = ratio(d2 as i64 + r2s as i64 - r1s as i64, 2 * d * r2);
    let kite = quotient(mul_uu(d as u32, sine_of(c1)), r1); // F30, below 2³⁹
                                                            // q < 2³⁸: q² from its F22 part, F30 below 2⁴⁶; times acos c2 from q²'s F16 part.
    let q22 = (q >> 8) as u32;
    let q2 = mul_uu(q22, q22) >> 14;
    let far = mul_uu((q2 >> 14).min(u32::MAX as u64) as u32, acos(c2)) >> 16;
    let lens = (acos(c1) as i64 + far as i64 - kite as i64).clamp(0, PI as i64) as u32;
    over_pi(lens)
}

/// The diffuse cosine of a sphere light from `c = N·A` and `s = sin α` (F30): `c` for
/// `c ≥ s`, 0 for `c ≤ −s`, `(c + s)²/(4s)` between; F30 in `[0, 1]`.
#[inline(always)]
pub(crate) fn horizon_cosine(c: i64, s: u32) -> u32 {
    let c = c.clamp(-(ONE as i64), ONE as i64);
    if c >= s as i64 {
        return c as u32;
    }
    let t = c + s as i64;
    if t <= 0 {
        return 0;
    }
    let t = t as u32;
    ratio(mul_uu(t, t) as i64, (s as u64) << 32) as u32
}

/// The share of a sphere light's cap above the horizon from `c = N·A` and `s = sin α`
/// (F30): 1 for `c ≥ s`, else `1 −` [`segment`]`(c/s)`; F30 in `[0, 1]`.
#[inline(always)]
pub(crate) fn above_horizon(c: i64, s: u32) -> u32 {
    let c = c.clamp(-(ONE as i64), ONE as i64);
    if c >= s as i64 {
        return ONE;
    }
    if c <= -(s as i64) {
        return 0;
    }
    ONE - segment(ratio(c, s as u64))
}

/// A lobe's energy factor at a sphere light's representative point,
/// `1/(1 + s·a + b·s²)` (see [`crate::brdf::lobe_widening`]), from `s = sin α` (F30) and the
/// lobe's prepared `a = √(πn′/2)` (U16F16) and `b = n′/2` (U20F12); F30 in `(0, 1]`.
#[inline(always)]
pub(crate) fn lobe_widening(s: u32, [a, b]: [u32; 2]) -> u32 {
    let s = s.min(ONE);
    let s2 = (mul_uu(s, s) >> 30) as u32;
    let den = (ONE as u64) + (mul_uu(s, a) >> 16) + (mul_uu(s2, b) >> 12);
    quotient(ONE60, den).min(ONE as u64) as u32
}

/// GGX's energy factor at a sphere light's representative point, `(α/α′)²` with
/// `α′ = min(1, α + s/2)` (see [`crate::brdf::ggx_widening`]), from `α` and `α²` (U1F31)
/// and `s = sin α_L` (F30); F30 in `(0, 1]`.
#[cfg(feature = "models")]
#[inline(always)]
pub(crate) fn ggx_widening(alpha: u32, alpha2: u32, s: u32) -> u32 {
    // s/2 in F31 is s's F30 bits.
    let wide = (alpha as u64 + s.min(ONE) as u64).min(1 << 31) as u32; // F31
    let wide2 = mul_uu(wide, wide) >> 31; // F31
    quotient((alpha2 as u64) << 30, wide2).min(ONE as u64) as u32
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;
    use crate::float::area as float;

    fn f30(x: f64) -> i32 {
        (x * ONE as f64).round() as i32
    }
    fn of30(x: u32) -> f64 {
        x as f64 / ONE as f64
    }

    #[test]
    fn constants() {
        assert_eq!(PI, (core::f64::consts::PI * ONE as f64).round() as u32);
        assert_eq!(
            INV_PI,
            (core::f64::consts::FRAC_1_PI * (1u64 << 32) as f64).round() as u32
        );
    }

    #[test]
    fn acos_matches_the_float_form() {
        let mut worst = 0.0f64;
        for i in -2000..=2000 {
            let x = i as f64 / 2000.0;
            worst = worst.max((of30(acos(f30(x))) - x.acos()).abs());
        }
        assert!(worst < 1e-7, "{worst}");
        assert_eq!(acos(i32::MAX), 0);
        assert_eq!(acos(i32::MIN), PI);
        assert_eq!(segment(-(ONE as i32)), ONE);
        assert_eq!(segment(ONE as i32), 0);
        assert!(segment(0).abs_diff(ONE / 2) <= 1);
        assert_eq!(above_horizon(-(ONE as i64), 1000), 0);
        assert_eq!(above_horizon(1001, 1000), ONE);
    }

    #[test]
    fn ratio_and_quotient() {
        assert_eq!(ratio(1, 2), 1 << 29);
        assert_eq!(ratio(-3, 4), -(3 << 28));
        assert_eq!(ratio(5, 4), ONE as i32);
        assert_eq!(ratio(-5, 4), -(ONE as i32));
        assert_eq!(ratio(7, 0), 0);
        assert_eq!(ratio(1 << 61, 3 << 60), f30(2.0 / 3.0) - 1);
        assert_eq!(quotient(9, 0), u64::MAX);
    }

    #[test]
    fn closed_forms_match_the_float_forms() {
        let mut worst = [0.0f64; 5];
        for i in 1..=40 {
            // Relative error, down to the caps of lights a thousandth of their distance.
            let s = 1e-5 * 1.34f64.powi(i);
            let got = of30(chord(f30(s) as u32));
            worst[0] = worst[0].max((got / float::chord(s * s) - 1.0).abs());
        }
        for i in 1..=200 {
            let s = i as f64 / 200.0;
            for j in -100..=100 {
                let c = j as f64 / 100.0;
                let cf = f30(c) as i64;
                let sf = f30(s) as u32;
                worst[1] = worst[1]
                    .max((of30(horizon_cosine(cf, sf)) - float::horizon_cosine(c, s)).abs());
                worst[2] =
                    worst[2].max((of30(above_horizon(cf, sf)) - float::above_horizon(c, s)).abs());
            }
        }
        for i in 1..=40 {
            let r1 = i as f64 / 40.0 * 0.6;
            for j in 1..=40 {
                let r2 = j as f64 / 40.0 * 1.2;
                for k in 0..=60 {
                    let delta = k as f64 / 60.0 * (r1 + r2) * 1.1;
                    let got = of30(covered(f30(r1) as u32, f30(r2) as u32, f30(delta) as u32));
                    let want = float::covered(r1, r2, delta);
                    worst[3] = worst[3].max((got - want).abs());
                }
            }
        }
        for e in [1.0f64, 10.0, 100.0, 1e4, 1e6] {
            let a = (core::f64::consts::FRAC_PI_2 * e).sqrt();
            let b = e / 2.0;
            let ab = [
                (a * 65536.0).round() as u32,
                ((b * 4096.0).round() as u64).min(u32::MAX as u64) as u32,
            ];
            for i in 0..=100 {
                let s = i as f64 / 100.0;
                let want = 1.0 / (1.0 + s * a + b * s * s);
                let got = of30(lobe_widening(f30(s) as u32, ab));
                worst[4] = worst[4].max((got - want).abs());
            }
        }
        std::println!(
            "chord (relative), horizon cosine, above horizon, covered, widening: {worst:?}"
        );
        assert!(worst[0] < 1e-4, "chord {}", worst[0]);
        assert!(worst[1] < 1e-8, "horizon cosine {}", worst[1]);
        assert!(worst[2] < 1e-7, "above horizon {}", worst[2]);
        // The lens formula multiplies acos's error by q² (here up to 6,400).
        assert!(worst[3] < 5e-4, "covered {}", worst[3]);
        assert!(worst[4] < 1e-4, "widening {}", worst[4]);
    }

    #[test]
    fn covered_limits_and_straight_edges() {
        let (one, half) = (ONE, ONE / 2);
        assert_eq!(covered(one, one, 2 * one), 0);
        assert_eq!(covered(one, half, 0), ONE / 4);
        assert_eq!(covered(half, one, 0), ONE);
        assert_eq!(covered(0, one, 0), 0);
        // A large occluder whose outline passes through the light's centre covers half of it.
        let r1 = ONE / 1000;
        let r2 = ONE;
        let got = of30(covered(r1, r2, r2));
        assert!((got - 0.5).abs() < 1e-3, "{got}");
        // Straight or curved, the share is within 1/(πq) of the float lens formula.
        for k in 0..=40 {
            let d = 1.0 - 0.001 + 0.002 * k as f64 / 40.0;
            let got = of30(covered(r1, r2, f30(d) as u32));
            let want = float::covered(0.001f64, 1.0, d);
            assert!((got - want).abs() < 2e-3, "{d}: {got} {want}");
        }
    }
}
