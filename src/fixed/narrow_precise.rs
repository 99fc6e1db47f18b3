//! The narrow kernel's precise cosines ([`super::narrow`]): `N·V`, `N·L` and `L·D̂` in 30-bit
//! fractions from the same exact quadrics as the fast ones, with `σ` and the roots from
//! [`super::roots`], and what is shaded from them: a point light's geometry and shadow ray
//! (`precise_point`, `point_ray_blocked`) and the normalized models' terms
//! (`normalized_terms`). A light takes them (`precise_light`) at the pixels where the fast
//! stages' error bounds do not let them serve ([`super::narrow_point`],
//! [`super::narrow_terms`]), and a point light's shadow ray where the fast filters cannot
//! settle it; the bright part of a narrow classic highlight takes the same cosines in
//! `narrow`'s `precise_lobe`. They are kept apart from the fast stages because they cost a
//! dozen 32×32→64-bit products a light (calls on ARMv6-M), and the fast pixel loop must not
//! carry their registers.

use super::exact::{arriving, shift_saturating};
use super::mul::{dot_ii, mul_ii, mul_iu, mul_uu};
use super::narrow::{Surface, NORMAL_LIMIT};
use super::narrow_lobe::{narrow_lobe, precise_cosines, precise_h_of};
use super::narrow_scale::{scale_q15, scale_q16};
use super::prepare::{
    FixedLight, FixedSphere, NarrowLight, NarrowPoint, NarrowSphere, PreparedFixed,
};
use super::roots::{inv_sqrt, sqrt};
use super::vector::{each3, V3};

/// A normalized model's diffuse and specular sums for one light (U16F16 per channel, before
/// `kd·albedo/π` and `ks = 1`) from `N·L`, `N·V` and `L·D̂` (Q30) and the arriving colour:
/// the full-width kernel's terms, `Σ wₖcₖ·lobeₖ·(N·L)` times Schlick's `F` per channel
/// (`L·H = |L + V|/2`, with `|L + V|² = 2 − 2·L·D̂`) and the diffuse `N·L` times `1 − F`
/// where the model loses it, with no vector formed.
#[inline(never)]
fn normalized_terms(
    sphere: &FixedSphere,
    (nl, nv, ld): (i64, i64, i64),
    arriving: [u32; 3],
) -> ([u32; 3], [u32; 3]) {
    const ONE: u32 = 1 << 30;
    if nl <= 0 {
        return ([0; 3], [0; 3]);
    }
    let n_dot_l = nl.min(ONE as i64) as u32;
    let mut sum = 0u32;
    if let Some(h) = precise_h_of(sphere.blinn(), nl, nv, ld) {
        let h = u32::try_from(h >> 30).unwrap_or(u32::MAX);
        let exponents = [
            sphere.shininess,
            sphere.more_shininess[0],
            sphere.more_shininess[1],
        ];
        for (w, e) in sphere.weight.iter().zip(exponents) {
            if w.mantissa != 0 {
                // lobe·w in U16F16: (lobe·2⁻¹⁶)·(m·2^e)·2¹⁶.
                let term = shift_saturating(mul_uu(narrow_lobe(h, e), w.mantissa), w.exponent);
                sum = sum.saturating_add(term);
            }
        }
    }
    // Schlick: (1 − L·H)⁵ in U2F30, 0 where the half vector is undefined.
    let len2 = ((2 << 30) - 2 * ld).max(0) as u64;
    let weight5 = if sphere.schlick && len2 > 0 {
        let c = (sqrt(len2 << 30) >> 1).min(ONE as u64) as u32;
        let m = ONE - c;
        let m2 = (mul_uu(m, m) >> 30) as u32;
        let m4 = (mul_uu(m2, m2) >> 30) as u32;
        (mul_uu(m4, m) >> 30) as u32
    } else {
        0
    };
    let f = sphere
        .f0
        .map(|f0| f0 + (mul_uu(ONE.saturating_sub(f0), weight5) >> 30) as u32);
    let diffuse_scale = if sphere.diffuse_loss {
        ONE - f[0].min(ONE)
    } else {
        ONE
    };
    let lit = (mul_uu(n_dot_l, diffuse_scale) >> 30) as u32;
    let spec = (mul_uu(sum, n_dot_l) >> 30) as u32;
    let diffuse = arriving.map(|i| u32::try_from(mul_uu(i, lit) >> 30).unwrap_or(u32::MAX));
    let specular = each3(|c| {
        let t = u32::try_from(mul_uu(spec, f[c]) >> 30).unwrap_or(u32::MAX);
        u32::try_from(mul_uu(arriving[c], t) >> 16).unwrap_or(u32::MAX)
    });
    (diffuse, specular)
}

/// A point light's geometry at a narrow hit, precise (`precise_point`): the hit's distance
/// `t` along `D̂`, `N·(P − X)` and `(P − X)·D̂`, `|P − X|²` (raw, raw²) and
/// `1/|P − X| = y·2^-shift` as [`inv_sqrt`] gives it, and `D̂`'s `σ` (Q31).
pub(super) struct PointGeometry {
    pub t: i64,
    pub np: i64,
    pub pd: i64,
    pub dist2: u64,
    pub inv: (u32, u32),
    pub sigma: u32,
}

impl PointGeometry {
    /// `v/|P − X|` in Q30, clamped to `±1`.
    fn over(&self, v: i64) -> i64 {
        const ONE30: i64 = 1 << 30;
        let v = v.clamp(i32::MIN as i64, i32::MAX as i64) as i32;
        let (y, shift) = self.inv;
        (mul_iu(v, y) >> (shift - 30).min(63)).clamp(-ONE30, ONE30)
    }
}

/// The precise geometry of point light `point` at a narrow hit on `sphere` along `d`, from
/// the precise cosines `(σ, N·q̂, N·V, q̂·D̂)` ([`precise_cosines`]): with `Q = P − eye` and
/// `X = eye + t·D̂`,
///
/// ```text
/// N·(P − X) = |Q|·(N·q̂) + t·(N·V)        t = −(oc·D̂) − r·(N·V)
/// (P − X)·D̂ = |Q|·(q̂·D̂) − t
/// |P − X|²  = ((P − X)·D̂)² + |Q|² − (|Q|·(q̂·D̂))²
/// ```
///
/// `σ` and `N·V` within `2⁻³⁰` (from [`super::roots`]), so `t` is within a few raw units,
/// whatever the sphere's radius: a floor's pixels under a nearby lamp need that for the
/// shadow ray's origin. No term cancels beyond the distance's own size.
#[inline(always)]
fn precise_point(
    sphere: &FixedSphere,
    point: &NarrowPoint,
    d: V3<i32>,
    (sigma, nq, nv, qd): (u32, i64, i64, i64),
) -> Option<PointGeometry> {
    // t, raw: on a hit b = oc·D < 0, and (−b)/2³⁰ is −oc·d/2 (below 2³¹), times σ.
    let b = dot_ii(sphere.eye_offset.map(|c| c.to_bits()), d);
    let along = (mul_uu(((-b).max(0) >> 30) as u32, sigma) >> 30) as i64;
    let t = along - (mul_uu(sphere.radius.to_bits() as u32, nv as u32) >> 30) as i64;
    // Every point lies within 2³⁰ raw of the origin per component: each length below 2³¹.
    let q = point.distance as i64;
    let qq = (q * qd) >> 30;
    let pd = qq - t;
    let np = ((q * nq) >> 30) + ((t * nv) >> 30);
    let perp2 = (q * q - qq * qq).max(0) as u64;
    let dist2 = (pd * pd) as u64 + perp2;
    let inv = inv_sqrt(dist2)?;
    Some(PointGeometry {
        t,
        np,
        pd,
        dist2,
        inv,
        sigma,
    })
}

impl<const S: usize, const L: usize> PreparedFixed<S, L> {
    /// Light `light_index` at a narrow hit, from the precise cosines: its diffuse and
    /// specular sums (U16F16 per channel, before `kd·albedo` and `ks`), or `None` where it is
    /// blocked. A point light's shadow ray tests `casters` (the light's, or those the fast
    /// filters left); a distant light's shadow takes its own filters. The path of point
    /// lights, and of every light on a sphere of a normalized model (`NarrowSphere::terms`,
    /// whose terms are the full-width kernel's, `normalized_terms`).
    /// In 30-bit fractions and raw lengths throughout, from the exact quadrics of the light's
    /// direction (`G` and `D·L` as the run holds them, `g_dl`); for a point light that is the
    /// direction `q̂` from the eye toward it, and the light's geometry is [`precise_point`]'s.
    /// Out of line: a point light's pixels take 64-bit products and two roots here.
    #[inline(never)]
    pub(super) fn precise_light(
        &self,
        surface: &Surface,
        (sphere, ns, light): (&FixedSphere, &NarrowSphere, &NarrowLight),
        (light_index, casters): (usize, u32),
        d: V3<i32>,
        (g, dl): (i64, i64),
    ) -> Option<([u32; 3], [u32; 3])> {
        // N·q̂ and q̂·D̂ for a point light (its quadrics are those of the direction q̂).
        let (sigma, nq, nv, qd) = precise_cosines(ns, surface.e, d, (g, dl))?;
        let (nl, ld, arriving) = match self.lights.get(light_index)? {
            FixedLight::Point { power, .. } => {
                let point = self.points.get(light_index)?;
                let geometry = precise_point(sphere, point, d, (sigma, nq, nv, qd))?;
                let (nl, ld) = (geometry.over(geometry.np), geometry.over(geometry.pd));
                // The sphere's own shadow, as for a distant light (the light lies outside it).
                if nl < 0 && (mul_ii(nl as i32, nl as i32) >> 30) as u64 > ns.shadow_limit as u64 {
                    return None;
                }
                let ray = |casters| {
                    self.point_ray_blocked(
                        surface,
                        (sphere, ns),
                        light_index,
                        d,
                        &geometry,
                        casters,
                    )
                };
                #[cfg(test)]
                assert!(
                    surface.shadows || light.casters == 0 || !ray(light.casters),
                    "a caster blocks a ray outside the sphere's shadow rows"
                );
                #[cfg(test)]
                assert!(
                    light.separated == 0 || !ray(light.separated),
                    "a caster separated from sphere {} blocks its ray toward light {light_index}",
                    surface.index
                );
                #[cfg(test)]
                assert!(
                    !surface.shadows || !ray(light.casters & !casters),
                    "a caster the fast filters cleared blocks the precise ray"
                );
                if casters != 0 && surface.shadows && ray(casters) {
                    return None;
                }
                (nl, ld, arriving(*power, geometry.inv))
            }
            FixedLight::Distant { arriving, .. } => {
                let at = (light_index, light);
                if self.precise_distant_shadowed(surface, (sphere, ns), at, d, (nq >> 15) as i32) {
                    return None;
                }
                (nq, qd, arriving.map(|c| c.to_bits()))
            }
            #[allow(unreachable_patterns)]
            _ => return None,
        };
        if ns.terms {
            return Some(normalized_terms(sphere, (nl, nv, ld), arriving));
        }
        let nl15 = (nl >> 15) as i32;
        let diffuse = if nl15 > 0 {
            each3(|c| scale_q15(arriving[c], nl15))
        } else {
            [0; 3]
        };
        let lobe = match precise_h_of(sphere.blinn(), nl, nv, ld) {
            Some(h) if (h >> 30) < ns.cutoff as u64 => {
                narrow_lobe(u32::try_from(h >> 30).unwrap_or(u32::MAX), sphere.shininess)
            }
            _ => 0,
        };
        Some((diffuse, each3(|c| scale_q16(arriving[c], lobe))))
    }

    /// Whether a distant light is shadowed at a pixel of `precise_light`, from its precise
    /// `N·L` (Q15): the fast path's rules (the sphere's own shadow, then the casters its filter
    /// lets through, from the normal, where the pixel lies in the sphere's shadow rows).
    #[inline(always)]
    fn precise_distant_shadowed(
        &self,
        surface: &Surface,
        (sphere, ns): (&FixedSphere, &NarrowSphere),
        (light_index, light): (usize, &NarrowLight),
        d: V3<i32>,
        nl15: i32,
    ) -> bool {
        if ns.self_shadowed(nl15) {
            return true;
        }
        #[cfg(test)]
        {
            let n = self.narrow_normal(sphere, ns, d, surface.sigma, surface.nv);
            self.assert_separated_clear(surface.index, n, light_index, light);
        }
        if !light.casters_may_block(nl15) {
            return false;
        }
        let blocked = || {
            let n = self.narrow_normal(sphere, ns, d, surface.sigma, surface.nv);
            self.narrow_blocked(surface.index, n, light_index, light.casters)
        };
        #[cfg(test)]
        assert!(
            surface.shadows || !blocked(),
            "a caster blocks a ray outside the sphere's shadow rows"
        );
        surface.shadows && blocked()
    }

    /// Whether one of `casters` blocks the shadow ray toward point light `light_index` from
    /// the hit of `surface`, with the precise `geometry`: the ray leaves the hit point
    /// `X = eye + t·D̂` lifted by `ε·N` (within a few raw units, where `C + (r + ε)·N` from
    /// the Q15 normal could be `r·2⁻¹²` off) toward the light as seen from `X`, up to
    /// `|P − X|`, as the full-width kernel's does.
    pub(super) fn point_ray_blocked(
        &self,
        surface: &Surface,
        (sphere, ns): (&FixedSphere, &NarrowSphere),
        light_index: usize,
        d: V3<i32>,
        geometry: &PointGeometry,
        casters: u32,
    ) -> bool {
        let Some(FixedLight::Point { position, .. }) = self.lights.get(light_index) else {
            return false;
        };
        self.blocked_along(surface.index, casters, || {
            let n = self.narrow_normal(sphere, ns, d, surface.sigma, surface.nv);
            let eps = self.epsilon.to_bits() as i64;
            let (y, shift) = geometry.inv;
            let t = geometry.t.clamp(0, i32::MAX as i64);
            let (mut origin, mut to_light) = ([0; 3], [0; 3]);
            for i in 0..3 {
                let unit = mul_iu(d[i], geometry.sigma) >> 30; // D̂, Q30
                let x = self.eye[i].to_bits() as i64 + ((t * unit) >> 30);
                let n = n[i].clamp(-NORMAL_LIMIT, NORMAL_LIMIT) as i64;
                origin[i] = (x + ((eps * n) >> 15)) as i32;
                // P − X is within the light's distance, below 2³¹ raw.
                let v = (position[i].to_bits() as i64 - x).clamp(i32::MIN as i64, i32::MAX as i64)
                    as i32;
                to_light[i] = (mul_iu(v, y) >> (shift - 30).min(63)) as i32;
            }
            (origin, to_light, sqrt(geometry.dist2) as i64)
        })
    }

    /// Whether one of `casters` blocks point light `light_index` at the hit of `surface`:
    /// the precise cosines and geometry, then [`Self::point_ray_blocked`]. For the fast point
    /// light, whose own `t` is not precise enough for the ray's origin. Out of line: only
    /// pixels whose ray the casters' cones do not clear take it.
    #[inline(never)]
    pub(super) fn point_shadowed(
        &self,
        surface: &Surface,
        (sphere, ns): (&FixedSphere, &NarrowSphere),
        light_index: usize,
        d: V3<i32>,
        (g, dl): (i64, i64),
        casters: u32,
    ) -> bool {
        let Some(point) = self.points.get(light_index) else {
            return false;
        };
        let Some(cosines) = precise_cosines(ns, surface.e, d, (g, dl)) else {
            return false;
        };
        let Some(geometry) = precise_point(sphere, point, d, cosines) else {
            return false;
        };
        self.point_ray_blocked(surface, (sphere, ns), light_index, d, &geometry, casters)
    }
}
