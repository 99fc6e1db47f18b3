//! The fast point light's shadow filters ([`super::narrow_point`]): which casters can block
//! the shadow ray toward a point light, decided from the fast geometry where its error
//! bound allows, so that only the pixels near a shadow's edge take the precise ray
//! (`point_shadowed`).
//!
//! Two tests, each a few 16×16-bit products per caster:
//!
//! - **the cone**: a ray from the hit `X` toward the light at `P` meets a caster only if
//!   the direction from `P` toward `X` lies in the cone from `P` that holds the caster
//!   ([`PointConstants::cone`](super::prepare::PointConstants::cone), widened by a margin): one dot product of two Q15 vectors;
//! - **the distance**: with `v = C − X` and `L̂` the unit vector toward the light, the
//!   caster is ahead along the ray by `b = v·L̂` and off it by `|v − b·L̂|`. Allowing a
//!   margin `m` for the fast `X` and `L̂` (`t/2¹⁰` for `X`, the sphere's bound on `L̂`'s
//!   error, [`PointConstants::slack`](super::prepare::PointConstants::slack), times the caster's distance, and `2ε` for the
//!   ray's lift off the surface), the caster is clear if it lies behind the hit
//!   (`b < −(r + m)`), beyond the light (`b − r − m > |P − X|`) or off the ray
//!   (`|v − b·L̂| > r + m`), or if the ray moves away from its centre from a point outside
//!   it (`b < −m`, `|v| > r + m`), and it blocks if the hit is outside it, it lies ahead and
//!   before the light and the ray passes through it (`r + m < b`,
//!   `b + r + m < |P − X|`, `|v − b·L̂| < r − m`), which is the precise ray's rule for
//!   those cases (including a caster the sphere touches, whose rule differs only for a ray
//!   that starts inside it). Every other caster is left to the precise ray.
//!
//! The crate's tests hold both to the precise ray: no caster they clear blocks it, and
//! every pixel they find blocked, it blocks (assertions in `fast_point` under `cfg(test)`).

use super::narrow::Casters;
use super::narrow_hit::{bit_length, mul_q15};
#[cfg(feature = "narrow-precise")]
use super::narrow_point::FastPoint;
#[cfg(feature = "narrow-precise")]
use super::prepare::NarrowLight;
use super::prepare::{FixedLight, PreparedFixed};
#[cfg(feature = "narrow-precise")]
use super::vector::Len;
use super::vector::{each3, V3};

/// `D`'s coordinate along `u` (Q15) in Q12, from the narrow direction `d` (`|d| ≤ √2`, Q29),
/// within three units: `d`'s top bits in 16×16-bit products.
#[inline(always)]
fn across_q12(d: V3<i32>, u: &[i16; 3]) -> i32 {
    let [u0, u1, u2] = *u;
    ((d[0] >> 16) * u0 as i32 + (d[1] >> 16) * u1 as i32 + (d[2] >> 16) * u2 as i32) >> 16
}

/// `a·b/2¹²` rounded down (within one unit), for `0 ≤ a < 2²⁸` and `|b| < 2¹³`, in
/// 32×32→32-bit products.
#[inline(always)]
fn mul_q12(a: i32, b: i32) -> i32 {
    (a >> 12) * b + (((a & 0xfff) * b) >> 12)
}

/// What the distance test found for one caster.
#[derive(PartialEq, Eq)]
enum Verdict {
    Clear,
    Blocks,
    Unknown,
}

/// The distance test (see the module docs) of a caster of radius `r` (raw) at `v = C − X`
/// (raw) for the ray toward `−away` (Q15; `away` points from the light, so `L̂ = −away`),
/// with the margin `base + (|b| + r)·slack` (`slack` Q15), and `beyond`, whether a raw
/// length along the ray reaches past the light.
#[inline(always)]
fn distance_test(
    v: V3<i32>,
    away: V3<i32>,
    r: i32,
    (base, slack): (i32, i32),
    beyond: impl Fn(i32) -> bool,
) -> Verdict {
    // b = v·L̂, raw.
    let b = -(mul_q15(v[0], away[0]) + mul_q15(v[1], away[1]) + mul_q15(v[2], away[2]));
    let m = base + mul_q15(b.unsigned_abs() as i32 + r, slack);
    let (high, low) = (r + m, r - m);
    if b < -high || beyond(b - high) {
        return Verdict::Clear;
    }
    let w = each3(|i| v[i] + mul_q15(b, away[i]));
    if w.iter().any(|c| c.unsigned_abs() > high as u32) {
        return Verdict::Clear;
    }
    let shift = bit_length(high as u32).saturating_sub(15);
    let ws = w.map(|c| c >> shift);
    let w2 = ws
        .iter()
        .map(|&c| (c * c) as u32)
        .fold(0u32, u32::wrapping_add);
    let hs = ((high >> shift) + 1) as u32;
    if w2 > hs * hs {
        return Verdict::Clear;
    }
    // Moving away from the caster's centre from a point outside it: clear.
    let bs = (b >> shift).unsigned_abs();
    if b < -m && w2 + bs * bs > hs * hs {
        return Verdict::Clear;
    }
    let ls = (low.max(0) >> shift) as u32;
    if low > 0 && b > high && !beyond(b + high) && w2 < ls * ls {
        return Verdict::Blocks;
    }
    Verdict::Unknown
}

impl<const S: usize, const L: usize> PreparedFixed<S, L> {
    /// The hit `X = eye + t·D̂` (raw) of a narrow pixel along `d` (`σ` in Q15) from the fast
    /// `t` (raw).
    #[inline(always)]
    fn hit_point(&self, t: u32, d: V3<i32>, sigma: i32) -> V3<i32> {
        each3(|i| {
            let unit = ((d[i] >> 15) * sigma) >> 14; // D̂, Q15
            self.eye[i].to_bits().wrapping_add(mul_q15(t as i32, unit))
        })
    }

    /// The `casters` of distant light `light_index` at a narrow hit along `d` (`σ` in Q15)
    /// whose tests cannot settle them, from the fast `t`, or [`Casters::Blocked`]. Two
    /// stages per caster, the second only for those the first leaves:
    ///
    /// - the distance across the light of the fast `X = eye + t·D̂` from the caster's axis, in
    ///   two coordinates (the light's `u`, `v`, [`PreparedFixed::across`], in the quick
    ///   caster test's units): `X⊥ − C⊥ = t·D̂⊥ − (C⊥ − eye⊥)`, from `D̂⊥` ([`across_q12`]
    ///   times `σ`) and each caster's `NarrowLight::across`, with no hit point. A caster
    ///   farther than its radius and a margin in either coordinate is clear. The margin:
    ///   `2ε`, 256 raw for the exact ray's own rounding, `2¹⁸` raw for the basis's error over
    ///   the scene's extent, `t/2¹⁰` raw for the fast `t`, and `t/2⁹` with nine units more
    ///   (in the quick units) for `D̂⊥`'s, `t`'s and `C⊥ − eye⊥`'s roundings;
    /// - the distance test ([`distance_test`]) from the fast `X`, with the margin of the
    ///   direction's Q15 rounding.
    ///
    /// Out of line: only pixels the caster filter passes take it.
    #[inline(never)]
    pub(super) fn distant_casters(
        &self,
        light_index: usize,
        casters: u32,
        (t, d, sigma): (u32, V3<i32>, i32),
    ) -> Casters {
        let (Some(FixedLight::Distant { to_light, .. }), Some([u, v])) =
            (self.lights.get(light_index), self.across.get(light_index))
        else {
            return Casters::Left(casters);
        };
        let shift = self.quick_shift.min(31);
        // t in the quick test's units, and D̂⊥ in Q12 (σ = 1/|d| ≤ 1 in Q15).
        let tq = (t >> shift) as i32;
        let near = tq < 1 << 28;
        let (hu, hv) = (
            (across_q12(d, u) * sigma) >> 15,
            (across_q12(d, v) * sigma) >> 15,
        );
        let base = (t >> 10) as i32 + 2 * self.epsilon.to_bits() + 256;
        let slack = ((base + (1 << 18)) >> shift) + (tq >> 9) + 10;
        let mut left = 0;
        let mut rest = casters;
        let mut k = 0;
        while rest != 0 {
            let bit = rest & 1;
            (rest, k) = (rest >> 1, k + 1);
            let (Some(lights), Some(s)) = (self.narrow_lights.get(k - 1), self.spheres.get(k - 1))
            else {
                break;
            };
            let Some(light) = lights.get(light_index).filter(|_| bit != 0) else {
                continue;
            };
            let k = k - 1;
            let r = s.radius.to_bits() >> shift;
            if near {
                let [ou, ov] = light.across;
                let reach = r + slack;
                let xu = mul_q12(tq, hu) - ou;
                let xv = mul_q12(tq, hv) - ov;
                if xu.abs() > reach || xv.abs() > reach {
                    continue;
                }
            }
            left |= 1 << k;
        }
        if left == 0 {
            return Casters::Left(0);
        }
        let away = to_light.map(|c| -((c.to_bits() + (1 << 14)) >> 15));
        let x = self.hit_point(t, d, sigma);
        for (k, s) in self.spheres.iter().enumerate().take(32) {
            if left & (1 << k) == 0 {
                continue;
            }
            let v = each3(|i| s.center[i].to_bits().wrapping_sub(x[i]));
            match distance_test(v, away, s.radius.to_bits(), (base, 4), |_| false) {
                Verdict::Clear => left &= !(1 << k),
                Verdict::Blocks => return Casters::Blocked,
                Verdict::Unknown => {}
            }
        }
        Casters::Left(left)
    }

    /// The casters of point light `light_index` at the hit of the fast geometry `fast`
    /// along `d` (`σ` in Q15), `light` being the receiving sphere's constants for it: see
    /// the module docs. Out of line: once per pixel of a sphere with casters.
    #[cfg(feature = "narrow-precise")]
    #[inline(never)]
    pub(super) fn point_casters(
        &self,
        light_index: usize,
        light: &NarrowLight,
        (position, d, sigma): (&V3<Len>, V3<i32>, i32),
        fast: &FastPoint,
    ) -> Casters {
        // X (raw) and −L̂ = (X − P)/|P − X| (Q15).
        let x = self.hit_point(fast.t, d, sigma);
        let away = each3(|i| fast.over(x[i].wrapping_sub(position[i].to_bits())));
        let base = (fast.t >> 10) as i32 + 2 * self.epsilon.to_bits() + 256;
        // Whether a raw length is beyond the light: its square against |P − X|², both at
        // the geometry's shift (a length above 2¹⁶ there is beyond, as |P − X| < 2^15.5).
        let beyond = |v: i32| {
            let vs = (v >> fast.s) as u32;
            v > 0 && (vs >= 1 << 16 || vs * vs > fast.dist2)
        };
        let mut left = light.casters;
        for (k, (lights, s)) in self
            .narrow_lights
            .iter()
            .zip(&self.spheres)
            .enumerate()
            .take(32)
        {
            if light.casters & (1 << k) == 0 {
                continue;
            }
            let Some(cone) = lights.get(light_index).map(|l| l.point.cone) else {
                continue;
            };
            let [a0, a1, a2, threshold] = cone;
            // cos of the angle from the cone's axis, Q29.
            let cos = ((away[0] * a0 as i32) >> 1)
                + ((away[1] * a1 as i32) >> 1)
                + ((away[2] * a2 as i32) >> 1);
            if cos < (threshold as i32) << 14 {
                left &= !(1 << k);
                continue;
            }
            let v = each3(|i| s.center[i].to_bits().wrapping_sub(x[i]));
            let margin = (base, light.point.slack as i32);
            match distance_test(v, away, s.radius.to_bits(), margin, beyond) {
                Verdict::Clear => left &= !(1 << k),
                Verdict::Blocks => return Casters::Blocked,
                Verdict::Unknown => {}
            }
        }
        Casters::Left(left)
    }
}
