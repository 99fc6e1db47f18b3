//! The fast point light's shadow filters ([`super::narrow_point`]): which casters can block
//! the shadow ray toward a point light, decided from the fast geometry where its error
//! bound allows, so that only the pixels near a shadow's edge take the precise ray
//! (`point_shadowed`).
//!
//! Two tests, each a few 16×16-bit products per caster:
//!
//! - **the cone**: a ray from the hit `X` toward the light at `P` meets a caster only if
//!   the direction from `P` toward `X` lies in the cone from `P` that holds the caster
//!   ([`NarrowLight::cone`], widened by a margin): one dot product of two Q15 vectors;
//! - **the distance**: with `v = C − X` and `L̂` the unit vector toward the light, the
//!   caster is ahead along the ray by `b = v·L̂` and off it by `|v − b·L̂|`. Allowing a
//!   margin `m` for the fast `X` and `L̂` (`t/2¹⁰` for `X`, the sphere's bound on `L̂`'s
//!   error, [`NarrowLight::point_slack`], times the caster's distance, and `2ε` for the
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
use super::prepare::{FixedLight, NarrowLight, PreparedFixed};
#[cfg(feature = "narrow-precise")]
use super::vector::Len;
use super::vector::{each3, V3};

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
    /// whose distance test ([`distance_test`]) cannot settle them, from the fast `t`, or
    /// [`Casters::Blocked`]. The margin for the direction is its Q15 rounding. First, the
    /// same distance across the light in two coordinates, from the quick caster test's
    /// basis (`PreparedFixed::across`) and each caster's `NarrowLight::across`: a caster
    /// farther across than its radius and a margin (the fast `X`'s, as for the distance test,
    /// and `2¹⁸` raw for the basis's error over the scene's extent) is clear. Out of line:
    /// only pixels the caster filter passes take it.
    #[inline(never)]
    pub(super) fn distant_casters(
        &self,
        light_index: usize,
        casters: u32,
        (t, d, sigma): (u32, V3<i32>, i32),
    ) -> Casters {
        let Some(FixedLight::Distant { to_light, .. }) = self.lights.get(light_index) else {
            return Casters::Left(casters);
        };
        let away = to_light.map(|c| -((c.to_bits() + (1 << 14)) >> 15));
        let x = self.hit_point(t, d, sigma);
        let base = (t >> 10) as i32 + 2 * self.epsilon.to_bits() + 256;
        // X across the light, in the quick caster test's units: a first, two-coordinate
        // distance test against each caster's `across` (see the module docs).
        let shift = self.quick_shift.min(31);
        let Some([u, w]) = self.across.get(light_index) else {
            return Casters::Left(casters);
        };
        let across = |u: &[i16; 3]| {
            let p = (0..3).fold(0i32, |p, i| p.wrapping_add(mul_q15(x[i], u[i] as i32)));
            p >> shift
        };
        let (xu, xw) = (across(u), across(w));
        let slack = ((base + (1 << 18)) >> shift) + 3;
        let mut left = casters;
        for (k, (lights, s)) in self
            .narrow_lights
            .iter()
            .zip(&self.spheres)
            .enumerate()
            .take(32)
        {
            if casters & (1 << k) == 0 {
                continue;
            }
            let Some(&NarrowLight {
                across: [cu, cw], ..
            }) = lights.get(light_index)
            else {
                continue;
            };
            let reach = (s.radius.to_bits() >> shift) + slack;
            if (xu - cu).abs() > reach || (xw - cw).abs() > reach {
                left &= !(1 << k);
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
            let Some(cone) = lights.get(light_index).map(|l| l.cone) else {
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
            let margin = (base, light.point_slack as i32);
            match distance_test(v, away, s.radius.to_bits(), margin, beyond) {
                Verdict::Clear => left &= !(1 << k),
                Verdict::Blocks => return Casters::Blocked,
                Verdict::Unknown => {}
            }
        }
        Casters::Left(left)
    }
}
