//! Sphere lights on the float paths (crate feature `area-lights`): the closed forms the kernel
//! shades a point light with a `radius` by, written once over [`Real`] so that every lane
//! width gives the same bits (and the tests below can evaluate them in `f64`).
//!
//! Seen from a surface point `P` at distance `d` from the light's centre, a light of radius
//! `R` is a cap of directions of half-angle `α`, `sin α = R/d`, around the unit `A` toward
//! the centre. Its power arrives as from the point at its centre (`power/d²`), and:
//!
//! - **Diffuse** takes the irradiance of the sphere instead of `max(0, N·A)`
//!   ([`horizon_cosine`]): with `c = N·A` and `s = sin α`, exactly `c` while the sphere is
//!   wholly above the horizon (`c ≥ s`: the form factor of a sphere, `c·sin²α`, over the
//!   head-on `sin²α`), 0 while wholly below (`c ≤ −s`), and in between the quadratic
//!   `(c + s)²/(4s)`, which meets both with the same value and slope. The exact clipped
//!   form factor (Snyder's) has no closed form in these operations; against a numerical
//!   integration (test `horizon_cosine_error`), the quadratic is off by at most 0.011 of the
//!   head-on irradiance for `α ≤ 30°` and 0.045 for `α ≤ 60°` (largest where the horizon
//!   cuts the cap near its middle).
//! - **Specular** lobes are shaded at the representative point (the kernel's `incoming`):
//!   the point of the light's sphere closest to the reflected view ray, with the lobe's
//!   energy factor ([`crate::brdf::lobe_widening`]).
//! - **Soft shadows**: the visibility is the fraction of the light's cap that the other
//!   spheres leave uncovered. Each sphere nearer than the light's centre covers a cap too,
//!   of half-angle `asin(r/d′)` around its own direction; the covered fraction of the
//!   light's cap is the overlap of two circles ([`covered`]) in the Lambert azimuthal
//!   equal-area projection centred on `A`: a cap of half-angle `θ` maps to a disc of radius
//!   `2 sin(θ/2)` (the chord, computed without cancellation by [`chord`]), and directions
//!   at angle `γ` from `A` to distance `2 sin(γ/2) = |A − B|`. The light's cap maps to an
//!   exact disc of its exact area; the occluder's, off centre, maps to a shape of exactly
//!   its area that the formula takes as a disc of the same chord radius. Measured against a
//!   numerical integration on the sphere (test `cap_overlap_error`), the covered fraction is
//!   off by at most 0.006 with both caps up to 20° and by at most 0.052 with the light up
//!   to 30° and the occluder up to 60° (the occluder's image is then visibly not a disc).
//!   Several occluders combine as the product of their uncovered fractions, which is exact
//!   when their covers are independent and too bright where they overlap each other inside
//!   the light's cap (two occluders covering the same half give ¼ for the true ½).
//! - The surface's own sphere is the horizon: for the specular term and the umbra bit, the
//!   part of the cap above the tangent plane ([`above_horizon`]), the share of a disc on
//!   one side of a chord at `c/s` of its radius (exact in the limit of small caps; at most
//!   0.015 off for `α ≤ 30°`, test `horizon_share_error`). The diffuse term has it already.
//!
//! Every quantity is a lane select, never a branch per lane; the two branches on whole
//! packets (skip an occluder no lane's cap overlaps, stop when no lane sees the light) skip
//! work whose result is exactly 1, or would be multiplied by 0.

use crate::real::Real;

/// `acos x` for `x` in `[−1, 1]` (clamped there; NaN gives `acos 1 = 0`): Abramowitz and
/// Stegun 4.4.46, `√(1 − |x|)` times a degree-7 polynomial, error below `2·10⁻⁸` in exact
/// arithmetic, and `π − acos|x|` for negative `x`.
#[inline(always)]
pub(crate) fn acos<T: Real>(x: T) -> T {
    const C: [f32; 8] = [
        core::f32::consts::FRAC_PI_2,
        -0.214_598_8,
        0.088_978_99,
        -0.050_174_303,
        0.030_891_88,
        -0.017_088_126,
        0.006_670_09,
        -0.001_262_491_1,
    ];
    let (zero, one) = (T::splat(0.0), T::splat(1.0));
    let negative = x.lt(zero);
    let a = one.min(T::select(negative, -x, x));
    let mut p = T::splat(C[7]);
    for &c in C[..7].iter().rev() {
        p = p * a + T::splat(c);
    }
    let r = (one - a).max(zero).sqrt() * p;
    T::select(negative, T::pi() - r, r)
}

/// The chord `2 sin(θ/2)` of a cap of half-angle `θ ≤ 90°` from `sin²θ` (clamped to
/// `[0, 1]`): `√(2(1 − cos θ))`, with `1 − cos θ = sin²θ/(1 + cos θ)`, which keeps its
/// precision for small caps.
#[inline(always)]
pub(crate) fn chord<T: Real>(sin2: T) -> T {
    let (zero, one) = (T::splat(0.0), T::splat(1.0));
    let sin2 = one.min(zero.max(sin2));
    let cos = (one - sin2).sqrt();
    (T::splat(2.0) * sin2 / (one + cos)).sqrt()
}

/// The share of a disc of radius `r1` that a disc of radius `r2` at distance `delta` from
/// its centre covers, in `[0, 1]`: the lens area
/// `r1²·acos c1 + r2²·acos c2 − δ·r1·√(1 − c1²)` over `π r1²`, with
/// `c1 = (δ² + r1² − r2²)/(2δ r1)` and `c2 = (δ² + r2² − r1²)/(2δ r2)` clamped to
/// `[−1, 1]`, which also gives the nested cases (`π·min(r1, r2)²`). Exactly 0 where
/// `δ ≥ r1 + r2`. `r1`, `r2` positive.
#[inline(always)]
pub(crate) fn covered<T: Real>(r1: T, r2: T, delta: T) -> T {
    let (zero, one, two) = (T::splat(0.0), T::splat(1.0), T::splat(2.0));
    // δ = 0 is the limit of small δ (concentric discs).
    let d = T::splat(1.0e-12).max(delta);
    let (d2, r1s, r2s) = (d * d, r1 * r1, r2 * r2);
    let c1 = (d2 + r1s - r2s) / (two * d * r1);
    let c2 = (d2 + r2s - r1s) / (two * d * r2);
    let c1 = one.min((-one).max(c1));
    let q = r2 / r1;
    let kite = (d / r1) * (one - c1 * c1).max(zero).sqrt();
    let lens = (acos(c1) + q * q * acos(c2) - kite) / T::pi();
    let share = one.min(zero.max(lens));
    T::select(delta.lt(r1 + r2), share, zero)
}

/// The diffuse cosine of a sphere light: its irradiance over that of the point at its centre
/// seen head-on, from `c = N·A` and `s = sin α` (see the module docs): `c` for `c ≥ s`, 0
/// for `c ≤ −s`, `(c + s)²/(4s)` between.
#[inline(always)]
pub(crate) fn horizon_cosine<T: Real>(c: T, s: T) -> T {
    let zero = T::splat(0.0);
    let t = c + s;
    let straddling = (t * t) / (T::splat(4.0) * s);
    let below = T::select(t.le(zero), zero, straddling);
    T::select(s.le(c), c, below)
}

/// The share of a sphere light's cap above the horizon, from `c = N·A` and `s = sin α`: the
/// share of a unit disc beyond a chord at signed distance `t = c/s` (clamped to `[−1, 1]`)
/// from its centre, `1 − (acos t − t√(1 − t²))/π`.
#[inline(always)]
pub(crate) fn above_horizon<T: Real>(c: T, s: T) -> T {
    let (zero, one) = (T::splat(0.0), T::splat(1.0));
    let t = one.min((-one).max(c / s));
    let segment = (acos(t) - t * (one - t * t).max(zero).sqrt()) / T::pi();
    let share = one - segment;
    T::select(s.le(c), one, zero.max(share))
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;
    use std::f64::consts::PI;

    type D = [f64; 3];
    fn dot(a: D, b: D) -> f64 {
        a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
    }

    /// Integrates `f` over the cap of half-angle `a` around +z, by `n × n` cells of equal
    /// solid angle: the mean of `f` over the cap.
    fn cap_mean(a: f64, n: usize, f: impl Fn(D) -> f64) -> f64 {
        let mut sum = 0.0;
        for i in 0..n {
            let ct = 1.0 - (i as f64 + 0.5) / n as f64 * (1.0 - a.cos());
            let st = (1.0 - ct * ct).max(0.0).sqrt();
            for j in 0..n {
                let phi = 2.0 * PI * (j as f64 + 0.5) / n as f64;
                sum += f([st * phi.cos(), st * phi.sin(), ct]);
            }
        }
        sum / (n * n) as f64
    }

    #[test]
    fn acos_is_accurate() {
        let mut worst = 0.0f64;
        for i in -1000..=1000 {
            let x = i as f64 / 1000.0;
            worst = worst.max((acos(x as f32) as f64 - x.acos()).abs());
            worst = worst.max((acos(x) - x.acos()).abs());
        }
        assert!(worst < 5e-7, "{worst}");
    }

    #[test]
    fn horizon_cosine_error() {
        // The normal at angle `theta` from the light's axis, in the x–z plane.
        let mut worst = [0.0f64; 2];
        for (k, max_deg) in [30.0f64, 60.0].iter().enumerate() {
            for ad in 1..=*max_deg as usize {
                let a = (ad as f64).to_radians();
                for td in (0..=180).step_by(2) {
                    let th = (td as f64).to_radians();
                    let n = [th.sin(), 0.0, th.cos()];
                    // The cap's mean cosine times its solid angle, over `π sin²α`.
                    let exact = cap_mean(a, 100, |l| dot(n, l).max(0.0)) * 2.0 / (1.0 + a.cos());
                    let got = horizon_cosine(th.cos(), a.sin());
                    worst[k] = worst[k].max((exact - got).abs());
                }
            }
        }
        std::println!(
            "horizon cosine: worst {:.4} (≤30°), {:.4} (≤60°)",
            worst[0],
            worst[1]
        );
        assert!(worst[0] < 0.011 && worst[1] < 0.045, "{worst:?}");
    }

    #[test]
    fn horizon_share_error() {
        let mut worst = 0.0f64;
        for ad in 1..=30 {
            let a = (ad as f64).to_radians();
            for td in (0..=180).step_by(2) {
                let th = (td as f64).to_radians();
                let n = [th.sin(), 0.0, th.cos()];
                let exact = cap_mean(a, 100, |l| (dot(n, l) > 0.0) as u8 as f64);
                let got = above_horizon(th.cos(), a.sin());
                worst = worst.max((exact - got).abs());
            }
        }
        std::println!("horizon share: worst {worst:.4}");
        assert!(worst < 0.015, "{worst}");
    }

    /// The largest error of [`covered`] (in the equal-area projection) against the covered
    /// share of the light's cap, integrated on the sphere, for light caps up to `max_l`
    /// degrees and occluder caps up to `max_o`.
    fn overlap_error(max_l: usize, max_o: usize) -> f64 {
        let mut worst = 0.0f64;
        for ld in (2..=max_l).step_by(2) {
            let al = (ld as f64).to_radians();
            for od in (2..=max_o).step_by(2) {
                let ao = (od as f64).to_radians();
                for gd in 0..=(ld + od + 2) {
                    let g = (gd as f64).to_radians();
                    let b = [g.sin(), 0.0, g.cos()];
                    let exact = cap_mean(al, 100, |l| (dot(b, l) >= ao.cos()) as u8 as f64);
                    let chord_l = chord(al.sin() * al.sin());
                    let chord_o = chord(ao.sin() * ao.sin());
                    let got = covered(chord_l, chord_o, 2.0 * (g / 2.0).sin());
                    worst = worst.max((exact - got).abs());
                }
            }
        }
        worst
    }

    #[test]
    fn cap_overlap_error() {
        let small = overlap_error(20, 20);
        let large = overlap_error(30, 60);
        std::println!(
            "cap overlap: worst {small:.4} (both ≤ 20°), {large:.4} (light ≤ 30°, occluder ≤ 60°)"
        );
        assert!(small < 0.006 && large < 0.052, "{small} {large}");
    }

    #[test]
    fn covered_limits() {
        assert_eq!(covered(1.0f32, 1.0, 2.0), 0.0);
        assert_eq!(covered(1.0f32, 0.5, 3.0), 0.0);
        assert!((covered(1.0f32, 0.5, 0.0) - 0.25).abs() < 1e-6);
        assert!((covered(1.0f32, 0.5, 0.3) - 0.25).abs() < 1e-6);
        assert!((covered(1.0f32, 2.0, 0.5) - 1.0).abs() < 1e-6);
        assert!((covered(1.0f32, 1.0, 0.0) - 1.0).abs() < 1e-6);
    }
}
