//! The narrow kernel's fast point light ([`super::narrow`]): a point light's `N·L`, `L·D̂`,
//! `1/d²` and the lobe at a narrow hit in 15- and 16-bit fractions, where its error bound
//! lets it serve; `precise_light` everywhere else.
//!
//! # How
//!
//! For the quadrics a point light at `P` is a distant light along the unit vector `q̂` from
//! the eye toward it (`NarrowPoint`), so the fast cosines of [`super::narrow`] give `N·q̂`
//! and `q̂·D̂`. With `Q = P − eye` and the hit `X = eye + t·D̂`:
//!
//! ```text
//! t          = r·c/(N·V + √((N·V)² + c))        c = |ô|² − 1, per sphere
//! N·(P − X)  = |Q|·(N·q̂) + t·(N·V)
//! (P − X)·D̂  = |Q|·(q̂·D̂) − t
//! |P − X|²   = ((P − X)·D̂)² + |Q|² − (|Q|·(q̂·D̂))²
//! ```
//!
//! `t` takes the form without cancellation (the two roots' product is `r²·c`, and
//! `(ô·D̂)² = (N·V)² + c` on the sphere), so it keeps its relative precision on a floor
//! under a camera close to it, where `−ô·D̂ − N·V` would lose it. Every product is a raw
//! length times a Q15 cosine (two 16×16-bit products, [`mul_q15`]) or of two 15-bit
//! numbers after one shift that brings the longest length below `2¹⁵`; `1/|P − X|` and
//! the reciprocal in `t` come from the narrow kernel's `rsqrt_at`. No 32×32→64-bit product.
//!
//! # When
//!
//! The error of the fast `N·L` grows with `|Q|` and `t` against the distance to the light
//! (the terms above are that long), as the square of `|Q|/|P − X|` ([`point_error`]). The
//! prepare sets, per sphere and light, the largest `(|Q|/|P − X|)²` for which the diffuse
//! term stays within one level (a bound: the errors measured are far below) and the cosines within `2⁻⁹`
//! (`PointConstants::ratio`; a pixel above it, looking nearly toward the light from far
//! away, takes the precise light), and from that bound the fast lobe's limit
//! (`PointConstants::fast`), as `fast_lobe_max` is the distant lights'. A pixel whose lobe
//! is above that limit, or whose Blinn-Phong half vector is ill-conditioned, takes
//! `precise_light` for the light. Where a caster's cone ([`PointConstants::cone`](super::prepare::PointConstants::cone)) holds the
//! hit, the shadow ray toward the light is the precise one (`precise_light`'s, from the
//! precise `t`).

use super::exact::Exact;
use super::narrow::fast_cosines;
use super::narrow::Surface;
use super::narrow::{Casters, PointSeen};
use super::narrow_hit::{bit_length, fast_t, mul_q15, shift_u32};
use super::narrow_lobe::{fast_h, narrow_lobe};
use super::narrow_roots::rsqrt_high;
use super::narrow_scale::ONE;
use super::narrow_scale::{scale_q15, scale_q16};
use super::narrow_terms::fast_terms;
use super::prepare::{FixedLight, FixedSphere, NarrowLight, NarrowSphere, PreparedFixed};
use super::vector::{Len, V3};

/// The margin (in cosine) by which [`PointConstants::cone`](super::prepare::PointConstants::cone)'s threshold is lowered: many times
/// the error of the direction it is compared with, which the prepare holds below `2⁻⁹` where
/// the fast point light serves (`PointConstants::fast`), and of the `f32` arithmetic that makes it.
pub(crate) const CONE_MARGIN: f32 = 1.0 / 128.0;

/// The error bound of the fast point-light cosines per unit of [`point_error`]'s factor, in
/// steps of `2⁻¹⁵`, and of `1/|P − X|`, relative (twice that): test
/// `fast_point_cosines_within_their_bound` measures the largest errors over random frames
/// against them.
pub(crate) const POINT_ERROR_STEPS: f32 = 4.0;

/// The bound of the fast point light's `N·L` and `L·D̂` error at a pixel (its `1/|P − X|`'s
/// relative error is within twice this): [`POINT_ERROR_STEPS`]`·2⁻¹⁵·(1 + |Q|/g)²`, with
/// `|Q|` the light's distance from the eye and `g` its distance from the hit (at least its
/// distance from the sphere's surface). The lengths
/// in the module docs' formulas are up to `|Q|/g` times `|P − X|`, and where they are, the
/// view ray passes close to the light (`q̂·D̂` near 1), so that `|P − X|²`'s part across the
/// ray, `|Q|²·(1 − (q̂·D̂)²)`, takes the square of that ratio.
pub(crate) fn point_error(light_distance: f32, gap: f32) -> f32 {
    let k = 1.0 + light_distance / gap;
    POINT_ERROR_STEPS / 32768.0 * k * k
}

/// The fast point-light geometry at a hit ([`point_cosines`]): `N·L` and `L·D̂` (Q15),
/// `t` (raw), `1/|P − X| = y·2^-shift` (raw; `y` in `[2¹⁵, 2¹⁶]`), and the shift `s` that
/// brings every length of the light's triangle below `2¹⁵`.
pub(super) struct FastPoint {
    pub nl: i32,
    pub ld: i32,
    pub t: u32,
    pub y: u32,
    pub shift: u32,
    pub s: u32,
    /// `|Q|²` and `|P − X|²` at that shift (below `2³¹`): their ratio is the pixel's part of
    /// [`point_error`]'s factor.
    pub q2: u32,
    pub dist2: u32,
}

impl FastPoint {
    /// `v/|P − X|` (Q15, clamped to `±1`) for a raw `|v| ≤ |P − X|`: `(v >> s)·y/2` is
    /// below `2³¹`.
    #[inline(always)]
    pub(super) fn over(&self, v: i32) -> i32 {
        (((v >> self.s) * (self.y >> 1) as i32) >> (self.shift - self.s - 16)).clamp(-ONE, ONE)
    }
}

/// The fast point-light geometry at a hit from `N·V` (Q15), the fast cosines `N·q̂` and
/// `q̂·D̂` (Q15) and the light's distance `|Q|` from the eye (raw) with the shift that brings
/// it below `2¹⁵` (`NarrowPoint::distance_shift`).
#[inline(always)]
pub(super) fn point_cosines(
    ns: &NarrowSphere,
    nv: i32,
    (nq, qd): (i32, i32),
    (q, q_shift): (u32, u32),
) -> FastPoint {
    let t = fast_t(ns, nv);
    let qq = mul_q15(q as i32, qd);
    let pd = qq.wrapping_sub(t as i32);
    let np = mul_q15(q as i32, nq).wrapping_add(mul_q15(t as i32, nv));
    // The lengths below 2¹⁵ after one shift: |P − X|² of the shifted ones below 2³¹. The
    // shift is that of the longer of (P − X)·D̂ and |Q|: |Q|'s, made once per frame, unless
    // the other is longer.
    let s = if pd.unsigned_abs() > q {
        bit_length(pd.unsigned_abs()).saturating_sub(15)
    } else {
        q_shift
    };
    let (ps, qs, qqs) = (pd >> s, (q >> s) as i32, qq >> s);
    let q2 = (qs * qs) as u32;
    let dist2 = (ps * ps + qs * qs - qqs * qqs).max(1) as u32;
    // 1/|P − X| = y·2^-(e + s), e ≥ 16.
    let (y, e) = rsqrt_high(dist2);
    let mut point = FastPoint {
        nl: 0,
        ld: 0,
        t,
        y,
        shift: e + s,
        s,
        q2,
        dist2,
    };
    (point.nl, point.ld) = (point.over(np), point.over(pd));
    point
}

/// `power/d²` per channel (U16F16, saturating) from `1/d = y·2^-shift` (raw, `y` below
/// `2¹⁶`): the fast form of `exact::arriving`, from the power's top 16 bits.
#[inline(always)]
fn fast_arriving(power: &[Exact; 3], (y, shift): (u32, u32)) -> [u32; 3] {
    // 1/d² = y2·2^(16 − 2·shift); power·(1/d²) in units (2³² per raw²) and U16F16:
    // m·2^pe·y2·2^(16 − 2·shift + 48).
    let y2 = (y.min(0xffff) * y.min(0xffff)) >> 16;
    power.map(|p| {
        let m = p.mantissa >> 8;
        shift_u32(m * y2, p.exponent + 8 + 64 - 2 * shift as i32)
    })
}

impl<const S: usize, const L: usize> PreparedFixed<S, L> {
    /// Point light `light_index` at a narrow hit along `d`, fast (see the module docs): its
    /// diffuse and specular sums, blocked (the own shadow or a caster), or
    /// [`PointSeen::Precise`] where its error bound does not let it serve (then
    /// `precise_light` shades the light); [`PointSeen::PreciseLobe`] where only the lobe
    /// needs the precise path, with the casters the fast filters leave to its ray.
    #[inline(always)]
    pub(super) fn fast_point(
        &self,
        surface: &Surface,
        (sphere, ns, light): (&FixedSphere, &NarrowSphere, &NarrowLight),
        light_index: usize,
        d: V3<i32>,
        (g, dl): (i64, i64),
    ) -> PointSeen {
        if light.point.fast == 0 {
            return PointSeen::Precise;
        }
        let (Some(FixedLight::Point { power, position }), Some(point)) =
            (self.lights.get(light_index), self.points.get(light_index))
        else {
            return PointSeen::Precise;
        };
        let cosines = fast_cosines(
            dl,
            (surface.sigma, surface.sigma2, surface.nv),
            g,
            ns.g_shift as u32,
        );
        let q = (point.distance, point.distance_shift);
        let fast = point_cosines(ns, surface.nv, cosines, q);
        // (|Q|/|P − X|)² at most `point.ratio` (Q4): the error bound the prepare allowed for.
        if fast.q2 >> 4 > (fast.dist2 >> 8) * light.point.ratio as u32 {
            return PointSeen::Precise;
        }
        let (nl, ld) = (fast.nl, fast.ld);
        if ns.self_shadowed(nl) {
            return PointSeen::Blocked;
        }
        #[cfg(test)]
        self.assert_separated_point_clear(surface, (sphere, ns, light), light_index, d, (g, dl));
        // A cutoff of 0 (a Lambert sphere): no lobe, whatever `h`.
        let (h, trusted) = if ns.cutoff == 0 {
            (u32::MAX, true)
        } else {
            fast_h(sphere.blinn(), nl, surface.nv, ld)
        };
        let (lobes, precise) = if h >= ns.cutoff {
            (None, false)
        } else if !trusted {
            (None, true)
        } else {
            let lobe = narrow_lobe(h, sphere.shininess);
            let max = light.point.fast;
            let precise = max < u16::MAX && (h > 1 << 30 || lobe > max as u32);
            (Some((h, lobe)), precise)
        };
        let at = (light_index, position);
        let found = if light.casters == 0 {
            Casters::Left(0)
        } else {
            let filters = (sphere, ns, light);
            self.fast_point_filters(surface, filters, at, d, (g, dl), &fast)
        };
        // The bright part of a sharp highlight, or a Blinn-Phong half vector too close to
        // 0: the precise path shades the light, and its ray tests only the casters the fast
        // filters leave.
        let left = match found {
            Casters::Blocked => return PointSeen::Blocked,
            Casters::Left(left) if precise => return PointSeen::PreciseLobe(left),
            Casters::Left(left) => left,
        };
        if left != 0 && self.point_shadowed(surface, (sphere, ns), light_index, d, (g, dl), left) {
            return PointSeen::Blocked;
        }
        let arriving = fast_arriving(power, (fast.y, fast.shift));
        if ns.terms {
            let (diffuse, specular) = fast_terms(sphere, (nl, ld), lobes, arriving);
            return PointSeen::Lit(diffuse, specular);
        }
        let diffuse = if nl > 0 {
            arriving.map(|a| scale_q15(a, nl))
        } else {
            [0; 3]
        };
        // Outside the lobe's cutoff the specular sum is 0: the pixel's colour is its diffuse
        // term alone, with no `ks` product.
        match lobes {
            Some((_, lobe)) => PointSeen::Lit(diffuse, arriving.map(|a| scale_q16(a, lobe))),
            None => PointSeen::Matte(diffuse),
        }
    }
}

impl<const S: usize, const L: usize> PreparedFixed<S, L> {
    /// Under test: no caster the mask leaves out for being separated from the sphere of
    /// `surface` ([`NarrowLight::separated`](super::prepare::NarrowLight)) blocks the
    /// precise ray toward point light `light_index`.
    #[cfg(test)]
    fn assert_separated_point_clear(
        &self,
        surface: &Surface,
        (sphere, ns, light): (&FixedSphere, &NarrowSphere, &NarrowLight),
        light_index: usize,
        d: V3<i32>,
        (g, dl): (i64, i64),
    ) {
        let casters = light.separated;
        assert!(
            casters == 0
                || !self.point_shadowed(surface, (sphere, ns), light_index, d, (g, dl), casters),
            "a caster separated from sphere {} blocks its ray toward light {light_index}",
            surface.index
        );
    }

    /// The casters' filters (`point_casters`) of the fast point light (`fast` its geometry
    /// at the hit) toward point light `light_index` at `position`: the casters they leave
    /// to the precise ray, or [`Casters::Blocked`]; none off the sphere's shadow rows. Under
    /// `cfg(test)`, every decision of the filters is asserted against the precise ray.
    #[inline(always)]
    fn fast_point_filters(
        &self,
        surface: &Surface,
        (sphere, ns, light): (&FixedSphere, &NarrowSphere, &NarrowLight),
        (light_index, position): (usize, &V3<Len>),
        d: V3<i32>,
        (g, dl): (i64, i64),
        fast: &FastPoint,
    ) -> Casters {
        let ray = (position, d, surface.sigma);
        let found = if surface.shadows {
            self.point_casters(light_index, light, ray, fast)
        } else {
            Casters::Left(0)
        };
        #[cfg(test)]
        {
            let shadowed = |casters| {
                self.point_shadowed(surface, (sphere, ns), light_index, d, (g, dl), casters)
            };
            match found {
                Casters::Blocked => assert!(
                    shadowed(light.casters),
                    "the quick test found blocked a ray that is not"
                ),
                Casters::Left(left) => assert!(
                    !shadowed(light.casters & !left),
                    "the quick tests cleared a caster that blocks"
                ),
            }
        }
        #[cfg(not(test))]
        let _ = (sphere, ns, g, dl);
        found
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fixed::narrow::tests::surfaces;
    use crate::fixed::vector::each3;
    use crate::test_scenes::{random_lamp_scene, uniform};
    extern crate std;
    use std::vec::Vec;

    /// Frames with point lights over floors (random lamps over random floors, and the
    /// `lamp` and `three-lights` presets) that take the narrow kernel.
    fn lamp_frames(seed: u64, count: usize) -> Vec<PreparedFixed<16, 8>> {
        let mut next = uniform(seed);
        let mut out: Vec<_> = (0..count)
            .filter_map(|_| PreparedFixed::new(&random_lamp_scene::<16, 8>(&mut next), 96, 72).ok())
            .collect();
        for scene in [crate::lamp(), crate::three_lights()].into_iter().flatten() {
            let big = crate::test_scenes::with_capacity::<16, 8, 6, 3>(&scene);
            out.push(PreparedFixed::new(&big, 160, 120).unwrap());
        }
        out.retain(|f| f.narrow.is_some());
        out
    }

    /// The fast point-light cosines against the exact ones at every narrow surface and
    /// point light of the frames above: `N·L` and `L·D̂` within [`POINT_ERROR_STEPS`] steps
    /// of `2⁻¹⁵` per unit of [`point_error`]'s factor (at the pixel's own `|P − X|`), and
    /// `1/|P − X|` within twice that, relative.
    #[test]
    fn fast_point_cosines_within_their_bound() {
        let frames = lamp_frames(0x2545_f491_4f6c_dd1d, 60);
        let (mut worst, mut worst_inv, mut count) = (0.0f64, 0.0f64, 0usize);
        for frame in &frames {
            for seen in surfaces(frame) {
                let s = &frame.spheres[seen.surface.index];
                let ns = s.narrow.as_ref().unwrap();
                let d = seen.d.map(|c| c as f64);
                let len = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
                let dh = d.map(|c| c / len);
                let oc = s.eye_offset.map(|c| c.to_bits() as f64);
                let r = (s.radius_sq.to_bits() as f64).sqrt();
                let oc2 = oc[0] * oc[0] + oc[1] * oc[1] + oc[2] * oc[2];
                let b = oc[0] * dh[0] + oc[1] * dh[1] + oc[2] * dh[2];
                let disc = b * b - oc2 + r * r;
                if disc < 0.0 {
                    continue;
                }
                let t = -b - disc.sqrt();
                let n = each3(|i| (oc[i] + t * dh[i]) / r);
                for (k, light) in frame.lights.iter().enumerate() {
                    let FixedLight::Point { position, .. } = light else {
                        continue;
                    };
                    let x = each3(|i| frame.eye[i].to_bits() as f64 + t * dh[i]);
                    let w = each3(|i| position[i].to_bits() as f64 - x[i]);
                    let dist = (w[0] * w[0] + w[1] * w[1] + w[2] * w[2]).sqrt();
                    let nl_x = (n[0] * w[0] + n[1] * w[1] + n[2] * w[2]) / dist;
                    let ld_x = (w[0] * dh[0] + w[1] * dh[1] + w[2] * dh[2]) / dist;
                    let Surface {
                        nv, sigma, sigma2, ..
                    } = seen.surface;
                    let cosines = fast_cosines(
                        seen.dl[k].v,
                        (sigma, sigma2, nv),
                        seen.g[k].v,
                        ns.g_shift as u32,
                    );
                    let (q, q_shift) = (frame.points[k].distance, frame.points[k].distance_shift);
                    let fast = point_cosines(ns, nv, cosines, (q, q_shift));
                    let factor = (1.0 + q as f64 / dist).powi(2);
                    let err = (fast.nl as f64 / 32768.0 - nl_x)
                        .abs()
                        .max((fast.ld as f64 / 32768.0 - ld_x).abs());
                    worst = worst.max(err * 32768.0 / factor);
                    let inv = fast.y as f64 / (fast.shift as f64).exp2();
                    worst_inv = worst_inv.max((inv * dist - 1.0).abs() / factor);
                    count += 1;
                }
            }
        }
        std::println!(
            "{count} point-lit terms in {} frames, in steps of 2⁻¹⁵ per unit of the factor: \
             |Δ(N·L)|, |Δ(L·D̂)| ≤ {worst:.2}, 1/|P − X| within {:.2} relative",
            frames.len(),
            worst_inv * 32768.0
        );
        assert!(count > 20_000, "{count} terms");
        assert!(worst <= POINT_ERROR_STEPS as f64, "{worst} steps");
        assert!(
            worst_inv * 32768.0 <= 2.0 * POINT_ERROR_STEPS as f64,
            "1/|P − X| off by {worst_inv}"
        );
    }
}
