//! The narrow kernel's fast terms of the normalized models ([`super::narrow`]): a light's
//! diffuse and specular sums on a sphere of normalized Phong or Blinn-Phong from the fast
//! cosines (Q15) and the fast `h`, in 16×16-bit products.
//!
//! They are the full-width kernel's terms (`normalized_terms` in 30-bit fractions is their
//! precise form): the lobes' weighted sum `Σ wₖ·lobeₖ` times `N·L`, Schlick's
//! `F = F₀ + (1 − F₀)·(1 − L·H)⁵` per channel with `L·H = |L + V|/2 = √((1 − L·D̂)/2)`,
//! and the diffuse `N·L`, times `1 − F` where the model loses it. A pixel takes them where
//! the fast lobe serves (the sphere's `fast_lobe_max`, or a point light's `PointConstants::fast`,
//! which the prepare makes from the weights' sum and the largest exponent); the others take
//! the precise light.

use super::narrow::fast_cosines;
use super::narrow::PointSeen;
use super::narrow::Surface;
use super::narrow_hit::shift_u32;
use super::narrow_lobe::{fast_h, fast_lobe, narrow_lobe};
use super::narrow_roots::sqrt_q30;
use super::narrow_scale::scale_q15;
use super::narrow_scale::ONE;
use super::prepare::{FixedLight, FixedSphere, NarrowLight, NarrowSphere, PreparedFixed};
use super::vector::V3;

/// `lobe·w` in U16F16 for a lobe in U1F16 and a weight held exactly: the weight's top 16
/// bits times the lobe, shifted, saturating.
#[inline(always)]
fn weighted(lobe: u32, w: super::exact::Exact) -> u32 {
    shift_u32((w.mantissa >> 8) * lobe.min(1 << 16), w.exponent + 8)
}

/// `k·v/2¹⁶` for U16F16 `k` and `v`, saturating: two 16×16-bit products when `k ≤ 1`, a
/// wider product (rare: the peak of a bright normalized highlight) otherwise.
#[inline(always)]
fn times(k: u32, v: u32) -> u32 {
    if k <= 1 << 16 {
        let high = (v >> 16) * k;
        let low = ((v & 0xffff) * k) >> 16;
        high.saturating_add(low)
    } else {
        u32::try_from(super::mul::mul_uu(k, v) >> 16).unwrap_or(u32::MAX)
    }
}

/// A normalized model's diffuse and specular sums for one light (U16F16 per channel, before
/// `kd·albedo/π` and `ks = 1`) from `N·L` and `L·D̂` (Q15), `lobes` (`h` in Q31, as the fast
/// `h` gives it, with lobe 0 at it in U1F16 from `narrow_lobe`; `None` where `h` is at or
/// above the sphere's cutoff, so that every lobe is 0), and the arriving colour.
#[inline(never)]
pub(super) fn fast_terms(
    sphere: &FixedSphere,
    (nl, ld): (i32, i32),
    lobes: Option<(u32, u32)>,
    arriving: [u32; 3],
) -> ([u32; 3], [u32; 3]) {
    if nl <= 0 {
        return ([0; 3], [0; 3]);
    }
    let nl = nl.min(ONE);
    let mut sum = 0;
    if let Some((h, lobe0)) = lobes {
        sum = weighted(lobe0, sphere.weight[0]);
        for (w, n) in sphere.weight[1..].iter().zip(sphere.more_shininess) {
            if w.mantissa != 0 {
                sum = sum.saturating_add(weighted(narrow_lobe(h, n), *w));
            }
        }
    }
    // Schlick: (1 − L·H)⁵ in Q15, L·H = √((1 − L·D̂)/2).
    let weight5 = if sphere.schlick {
        let half = ((ONE - ld.clamp(-ONE, ONE)) as u32) << 14; // (1 − L·D̂)/2 in Q30
        let m = ONE - sqrt_q30(half.min(1 << 30)).min(ONE);
        let m2 = (m * m) >> 15;
        let m4 = (m2 * m2) >> 15;
        (m4 * m) >> 15
    } else {
        0
    };
    let f = sphere.f0.map(|f0| {
        let f0 = (f0 >> 15).min(ONE as u32) as i32;
        f0 + (((ONE - f0) * weight5) >> 15)
    });
    let lit = if sphere.diffuse_loss {
        (nl * (ONE - f[0])) >> 15
    } else {
        nl
    };
    let spec = scale_q15(sum, nl);
    let diffuse = arriving.map(|a| scale_q15(a, lit));
    let specular = [0, 1, 2].map(|c| times(scale_q15(spec, f[c]), arriving[c]));
    (diffuse, specular)
}

impl<const S: usize, const L: usize> PreparedFixed<S, L> {
    /// A light the classic fast stages do not shade, at a narrow hit: a point light (the
    /// fast point light, [`Self::fast_point`], where it serves), or any light on a sphere of
    /// a normalized model (the fast cosines, the fast shadow rules and [`fast_terms`] for a
    /// distant light where the fast lobe serves); `precise_light` everywhere else.
    /// [`PointSeen::Lit`], [`PointSeen::Matte`] or [`PointSeen::Blocked`].
    #[inline(always)]
    pub(super) fn point_or_terms_light(
        &self,
        surface: &Surface,
        (sphere, ns, light): (&FixedSphere, &NarrowSphere, &NarrowLight),
        (light_index, point): (usize, bool),
        d: V3<i32>,
        (g, dl): (i64, i64),
    ) -> PointSeen {
        let fast = if point {
            self.fast_point(surface, (sphere, ns, light), light_index, d, (g, dl))
        } else {
            self.distant_terms(surface, (sphere, ns, light), light_index, d, (g, dl))
        };
        let casters = match fast {
            PointSeen::Precise => light.casters,
            PointSeen::PreciseLobe(casters) => casters,
            _ => return fast,
        };
        let at = (light_index, casters);
        match self.precise_light(surface, (sphere, ns, light), at, d, (g, dl)) {
            Some((diffuse, specular)) => PointSeen::Lit(diffuse, specular),
            None => PointSeen::Blocked,
        }
    }

    /// Distant light `light_index` on a sphere of a normalized model, fast: the classic fast
    /// stages' cosines and shadow stage (`distant_shadowed`), then [`fast_terms`]; [`PointSeen::Precise`] where
    /// the fast lobe does not serve (`fast_lobe`).
    #[inline(never)]
    fn distant_terms(
        &self,
        surface: &Surface,
        (sphere, ns, light): (&FixedSphere, &NarrowSphere, &NarrowLight),
        light_index: usize,
        d: V3<i32>,
        (g, dl): (i64, i64),
    ) -> PointSeen {
        let Surface {
            nv, sigma, sigma2, ..
        } = *surface;
        let Some(FixedLight::Distant { arriving, .. }) = self.lights.get(light_index) else {
            return PointSeen::Precise;
        };
        let arriving = arriving.map(|c| c.to_bits());
        let (nl, ld) = fast_cosines(dl, (sigma, sigma2, nv), g, ns.g_shift as u32);
        let at = (light_index, light);
        if self.distant_shadowed(surface, (sphere, ns), at, (nl, d), &mut None) {
            return PointSeen::Blocked;
        }
        let (h, trusted) = fast_h(sphere.blinn(), nl, nv, ld);
        let lobes = if h >= ns.cutoff {
            None
        } else {
            match fast_lobe(ns, sphere.shininess, h, trusted) {
                Some(lobe) => Some((h, lobe)),
                None => return PointSeen::Precise,
            }
        };
        let (diffuse, specular) = fast_terms(sphere, (nl, ld), lobes, arriving);
        PointSeen::Lit(diffuse, specular)
    }
}
