//! The full-width kernel's stages for a sphere light (feature `area-lights`): the float
//! kernel's `sphere_incoming` and `soft_shadow` in integers, the formulas in `area`.
//!
//! A sphere light replaces a point light's `incoming` and `shadow` and changes nothing else
//! of the light loop but two factors (`kernel::Area`), so its stages live apart from the
//! kernel and are compiled only with the feature.

use super::area::{above_horizon, chord, covered, horizon_cosine, ONE};
use super::exact::{arriving, Exact};
use super::kernel_light::{unit_component, Incoming};
use super::mul::{mul_ii, mul_uu};
use super::prepare::PreparedFixed;
use super::roots::{inv_sqrt, sqrt};
use super::vector::{
    dot_len_unit, dot_unit, each3, len_times_unit, length_sq, normalize, to_len, Len, Unit, V3,
};

/// A sphere light as seen from one surface point (see `sphere_incoming`).
pub(super) struct SphereSeen {
    /// The representative point's direction, the colour arriving from the centre, no reach
    /// (the soft shadow has its own test).
    pub(super) incoming: Incoming,
    /// Unit vector toward the centre, `A`.
    pub(super) axis: V3<Unit>,
    /// Squared distance to the centre, raw I32F32.
    pub(super) dist2: i64,
    /// `sin α = R/d`, F30.
    pub(super) sin_a: u32,
    /// The chord of the light's cap, `2 sin(α/2)` (F30): its radius in the equal-area
    /// projection.
    pub(super) rho: u32,
    /// `N·A`, F30.
    pub(super) cos_axis: i64,
    /// The diffuse cosine, `area::horizon_cosine`, F30.
    pub(super) diffuse_cos: u32,
}

/// `v·f` per channel for an F30 factor `f ≤ 1`.
#[inline(always)]
pub(super) fn times(v: [u32; 3], f: u32) -> [u32; 3] {
    v.map(|c| (mul_uu(c, f) >> 30).min(u32::MAX as u64) as u32)
}

impl<const S: usize, const L: usize> PreparedFixed<S, L> {
    /// `incoming` for a sphere light of `radius` at `position` with `power`, seen from the
    /// surface point `p` with normal `n` along the view ray `d`: the direction toward the
    /// representative point (the point of the light's sphere closest to the reflected ray
    /// `R = 2(N·V)N − V`: the centre moved toward the ray by up to the radius), the colour
    /// arriving from the centre, and the cap's constants. `None` at the light's centre,
    /// which validation keeps clear of every sphere.
    #[inline(always)]
    pub(super) fn sphere_incoming(
        &self,
        position: V3<Len>,
        power: V3<Exact>,
        radius: Len,
        p: V3<Len>,
        n: V3<Unit>,
        d: V3<Unit>,
    ) -> Option<SphereSeen> {
        // Both points lie within ±2¹³ units: the difference fits I16F16.
        let lv = each3(|i| position[i].to_bits() as i64 - p[i].to_bits() as i64);
        let dist2 = length_sq(lv).max(0);
        let (y, shift) = inv_sqrt(dist2 as u64)?;
        let axis = lv.map(|c| unit_component(c, (y, shift)));
        let r = radius.to_bits().max(0) as u32;
        let sin_a = (mul_uu(r, y) >> (shift - 30).min(63)).min(ONE as u64) as u32;
        let cos_axis = dot_unit(n, axis);
        // R = 2(N·V)N − V with V = −d, each component within ±1 (F30).
        let k = (-dot_unit(n, d)).clamp(i32::MIN as i64, i32::MAX as i64) as i32;
        let reflected = each3(|i| {
            let c = (mul_ii(k, n[i].to_bits()) >> 29) + d[i].to_bits() as i64;
            Unit::from_bits(c.clamp(-(1 << 30), 1 << 30) as i32)
        });
        let along = dot_len_unit(lv.map(to_len), reflected);
        let to_ray = each3(|i| len_times_unit(along, reflected[i]) - lv[i]);
        let to_ray2 = length_sq(to_ray);
        let r2 = mul_uu(r, r) as i64;
        let rep = match inv_sqrt(to_ray2.max(0) as u64) {
            Some(inv) if r2 < to_ray2 => {
                each3(|i| lv[i] + len_times_unit(r as i64, unit_component(to_ray[i], inv)))
            }
            _ => each3(|i| lv[i] + to_ray[i]),
        };
        Some(SphereSeen {
            incoming: Incoming {
                to_light: normalize(rep).unwrap_or([Unit::ZERO; 3]),
                arriving: arriving(power, (y, shift)),
                reach: None,
            },
            axis,
            dist2,
            sin_a,
            rho: chord(sin_a),
            cos_axis,
            diffuse_cos: horizon_cosine(cos_axis, sin_a),
        })
    }

    /// `shadow` for a sphere light: the share of the light's cap that the other spheres
    /// leave uncovered, seen from `origin` (`P + ε·N` on sphere `index`), and that times the
    /// share above the horizon: `(diffuse, specular)` visibility, F30. The float kernel's
    /// `soft_shadow` in integers: each sphere nearer than the light's centre whose cap
    /// overlaps the light's multiplies the visibility by `1 −` its `area::covered` share, a
    /// point inside a sphere sees none of the light, and the own sphere is the horizon.
    #[inline(always)]
    pub(super) fn soft_shadow(
        &self,
        index: usize,
        origin: V3<Len>,
        light: &SphereSeen,
    ) -> (u32, u32) {
        let horizon = above_horizon(light.cos_axis, light.sin_a);
        let mut visible = ONE;
        for (k, s) in self.spheres.iter().enumerate() {
            if k == index {
                continue;
            }
            let to_center = each3(|i| s.center[i].to_bits() as i64 - origin[i].to_bits() as i64);
            let d2 = length_sq(to_center);
            if d2 <= s.radius_sq.to_bits() {
                return (0, 0);
            }
            if d2 >= light.dist2 {
                continue;
            }
            let Some((y, shift)) = inv_sqrt(d2 as u64) else {
                continue;
            };
            let r = s.radius.to_bits().max(0) as u32;
            let sin = (mul_uu(r, y) >> (shift - 30).min(63)).min(ONE as u64) as u32;
            let rho = chord(sin);
            // |B − A|² in F60 from the F30 components, B the unit vector toward the centre.
            let gap2 = each3(|i| {
                let b = unit_component(to_center[i], (y, shift)).to_bits() as i64;
                let g = (b - light.axis[i].to_bits() as i64)
                    .unsigned_abs()
                    .min(u32::MAX as u64);
                mul_uu(g as u32, g as u32)
            });
            let delta = sqrt(gap2[0].saturating_add(gap2[1]).saturating_add(gap2[2]))
                .min(u32::MAX as u64) as u32;
            if delta as u64 >= light.rho as u64 + rho as u64 {
                continue;
            }
            let share = covered(light.rho, rho, delta);
            visible = (mul_uu(visible, ONE - share.min(ONE)) >> 30) as u32;
            if (mul_uu(visible, horizon) >> 30) == 0 {
                break;
            }
        }
        (visible, (mul_uu(visible, horizon) >> 30) as u32)
    }
}
