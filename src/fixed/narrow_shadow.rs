//! The narrow kernel's shadow stage ([`super::narrow`]) beyond the sphere's own shadow: the
//! normal formed on demand (`narrow_normal`), the quick caster test for floor-like receivers
//! (`quick_casters`) and the exact test of a shadow ray against the casters
//! (`blocked_along`), toward a distant light (`narrow_blocked`) or a point light (whose ray
//! `precise_light` makes).

use super::mul::{dot_ii, mul_ii};
use super::narrow::NORMAL_LIMIT;
use super::narrow_caster_prepare::QUICK_CASTER_TEST;
use super::prepare::{FixedLight, FixedSphere, NarrowSphere, PreparedFixed};
use super::vector::{each3, V3};

impl<const S: usize, const L: usize> PreparedFixed<S, L> {
    /// The unit normal (Q15) of a narrow hit, for caster tests: `N = D̂ × u − (N·V)·D̂` with
    /// `u = (oc × D)·σ/(r·2²⁹)` from six exact 32×32→64 products. Out of line on ARMv6-M,
    /// where the pixel loop needs its registers.
    #[cfg_attr(shadeline_short_mul, inline(never))]
    #[cfg_attr(not(shadeline_short_mul), inline(always))]
    pub(super) fn narrow_normal(
        &self,
        sphere: &FixedSphere,
        ns: &NarrowSphere,
        d: V3<i32>,
        sigma: i32,
        nv: i32,
    ) -> V3<i32> {
        let oc = sphere.eye_offset.map(|c| c.to_bits());
        let w = [
            mul_ii(oc[1], d[2]) - mul_ii(oc[2], d[1]),
            mul_ii(oc[2], d[0]) - mul_ii(oc[0], d[2]),
            mul_ii(oc[0], d[1]) - mul_ii(oc[1], d[0]),
        ];
        // |oc × D| ≤ r·|D| on a hit (up to E′'s rounding, far below a unit here) and
        // |D| ≤ √2·2²⁹ in a narrow frame: below √2·2¹⁵ after the shift, so `c·mu` below
        // (mu ≤ 2¹⁵) fits an `i32`.
        let high = w.map(|c| {
            let high = c >> (ns.cross_shift as u32).min(63);
            debug_assert!(high.unsigned_abs() < 46_400, "|oc × D| above r·|D|: {high}");
            high as i32
        });
        let mu = ((sigma as u32 * ns.gain) >> 16) as i32; // ≤ 2¹⁵
        let u = high.map(|c| (c * mu) >> 14);
        let dh = d.map(|c| ((c >> 15) * sigma) >> 14);
        let cross = [
            dh[1] * u[2] - dh[2] * u[1],
            dh[2] * u[0] - dh[0] * u[2],
            dh[0] * u[1] - dh[1] * u[0],
        ];
        each3(|i| (cross[i] - nv * dh[i]) >> 15)
    }

    /// Under test: no caster the mask leaves out for being separated from sphere `index`
    /// ([`NarrowLight::separated`](super::prepare::NarrowLight)) blocks the ray toward
    /// distant light `light_index` from its point of normal `n`.
    #[cfg(test)]
    pub(super) fn assert_separated_clear(
        &self,
        index: usize,
        n: V3<i32>,
        light_index: usize,
        light: &super::prepare::NarrowLight,
    ) {
        assert!(
            light.separated == 0 || !self.narrow_blocked(index, n, light_index, light.separated),
            "a caster separated from sphere {index} blocks its ray toward light {light_index}"
        );
    }

    /// Whether one of the `casters` (a mask as `NarrowLight::casters` holds it) blocks
    /// the ray toward the distant light `to_light` from the point of sphere `index` with
    /// normal `n`, lifted by ε: the shadow stage's caster test, from the narrow normal.
    ///
    /// A caster more than `4ε` from the sphere blocks iff the ray moves toward its centre
    /// (`b = (O − C)·L < 0`) and passes within its radius (`|O − C|² − b² ≤ r²`): the lifted
    /// point is outside it, and no square root is needed. A caster the sphere touches
    /// ([`NarrowSphere::touching`](super::prepare::NarrowSphere), a sphere resting on a floor
    /// sphere) takes the full-width kernel's rule, a crossing beyond `ε`
    /// ([`Self::crosses_beyond_epsilon`]), since the lifted point may lie inside it. `light`
    /// is the light's index.
    #[inline(always)]
    pub(super) fn narrow_blocked(
        &self,
        index: usize,
        n: V3<i32>,
        light: usize,
        casters: u32,
    ) -> bool {
        debug_assert!(index < self.spheres.len(), "hit on sphere {index}");
        let (Some(own), Some(FixedLight::Distant { to_light, .. })) =
            (self.spheres.get(index), self.lights.get(light))
        else {
            return false;
        };
        let to_light = to_light.map(|c| c.to_bits());
        let quick = own.narrow.as_ref().map_or(-1, |n| n.quick_margin);
        let casters = if QUICK_CASTER_TEST && quick >= 0 {
            let left = self.quick_casters(index, n, light, casters);
            // Spheres from 32 on are not in the mask: they are always tested.
            if left == 0 && self.spheres.len() <= 32 {
                return false;
            }
            left
        } else {
            casters
        };
        self.blocked_along(index, casters, || {
            let lift =
                (own.radius.to_bits() as i64 + self.epsilon.to_bits() as i64).min(i32::MAX as i64);
            let origin = each3(|i| {
                debug_assert!(n[i].abs() <= NORMAL_LIMIT, "normal {n:?}");
                let n = n[i].clamp(-NORMAL_LIMIT, NORMAL_LIMIT);
                own.center[i].to_bits() + (mul_ii(lift as i32, n) >> 15) as i32
            });
            (origin, to_light, i64::MAX)
        })
    }

    /// Whether one of the `casters` of sphere `index` (a mask as `NarrowLight::casters`
    /// holds it; spheres from 32 on always) blocks the shadow ray `ray` makes: its lifted
    /// origin `O` (raw), unit direction `L` (I2F30) and the light's distance (raw,
    /// `i64::MAX` for a distant light). `ray` runs at the first caster to test, if any.
    #[inline(always)]
    pub(super) fn blocked_along(
        &self,
        index: usize,
        casters: u32,
        ray: impl FnOnce() -> (V3<i32>, V3<i32>, i64),
    ) -> bool {
        let touching = self
            .spheres
            .get(index)
            .and_then(|s| s.narrow.as_ref())
            .map_or(u32::MAX, |n| n.touching);
        let (mut ray, mut made) = (Some(ray), None);
        for (k, s) in self.spheres.iter().enumerate() {
            if k == index || (k < 32 && casters & (1 << k) == 0) {
                continue;
            }
            if let Some(ray) = ray.take() {
                made = Some(ray());
            }
            let Some((origin, to_light, reach)) = made else {
                return false;
            };
            // |O − C| per component is below 2³⁰ + 2²² (see `NORMAL_LIMIT`), so |O − C|² is
            // below 2⁶² and b = (O − C)·L (L within 2⁻²⁹ of unit length) fits an `i32`:
            // every step below is exact, with no clamp or saturation.
            let oc = each3(|i| origin[i] - s.center[i].to_bits());
            let b = (dot_ii(oc, to_light) >> 30) as i32;
            let touches = k < 32 && touching & (1 << k) != 0;
            if b >= 0 {
                // Moving away from the caster's centre: blocked only from inside it, which
                // a lifted point can be only at a sphere it touches.
                if touches && self.crosses_beyond_epsilon(oc, b, s) {
                    return true;
                }
                continue;
            }
            let miss = dot_ii(oc, oc) - mul_ii(b, b);
            if miss <= s.radius_sq.to_bits()
                && before(reach, b, s.radius_sq.to_bits() - miss)
                && (!touches || self.crosses_beyond_epsilon(oc, b, s))
            {
                return true;
            }
        }
        false
    }

    /// The `casters` (a mask of the first 32 spheres; the spheres from 32 on are not in the
    /// mask and are always tested) that the quick caster test does not clear for sphere
    /// `index` with normal `n` and light `light`: [`Self::quick_across`] and
    /// [`Self::quick_clear`]. Out of line: on ARMv6-M the pixel loop needs its registers,
    /// and one copy serves every instance of the loop.
    #[inline(never)]
    fn quick_casters(&self, index: usize, n: V3<i32>, light: usize, casters: u32) -> u32 {
        let Some((at, margin)) = self.quick_across(index, n, light) else {
            return casters;
        };
        let mut left = casters;
        // By index, not by the mask's trailing zeros: ARMv6-M has no instruction for those.
        for (k, s) in self.spheres.iter().enumerate().take(32) {
            if casters & (1 << k) != 0 && self.quick_clear(at, margin, k, s, light) {
                left &= !(1 << k);
            }
        }
        left
    }

    /// The quick caster test's view of sphere `index`'s lifted point `O = C + (r + ε)·N`
    /// for light `light`: `((O − eye)·u, (O − eye)·v)` in its units
    /// ([`PreparedFixed::quick_shift`]; `u`, `v` the light's
    /// [`across`](PreparedFixed::across)), from `NarrowLight::across` and `N·u`, `N·v` in
    /// 16×16-bit products, and the sphere's margin; `None` where the sphere has no quick
    /// test.
    #[inline(always)]
    fn quick_across(&self, index: usize, n: V3<i32>, light: usize) -> Option<([i32; 2], i32)> {
        let own = self.spheres.get(index)?;
        let margin = own.narrow.as_ref()?.quick_margin;
        let across = self.narrow_lights.get(index)?.get(light)?.across;
        let uv = self.across.get(light)?;
        if margin < 0 {
            return None;
        }
        // (r + ε) below 2¹⁶ units (the margin is −1 otherwise).
        let lift = (own.radius.to_bits() + self.epsilon.to_bits()) >> self.quick_shift.min(31);
        let [n0, n1, n2] = n;
        let (n0, n1, n2) = (
            n0.clamp(-NORMAL_LIMIT, NORMAL_LIMIT),
            n1.clamp(-NORMAL_LIMIT, NORMAL_LIMIT),
            n2.clamp(-NORMAL_LIMIT, NORMAL_LIMIT),
        );
        let [cu, cv] = across;
        let [u, v] = uv;
        // N·u in Q29 (each product below 2³⁰·1.01), then Q14: below 2¹⁴·1.02. No array
        // maps: on ARMv6-M they go through the stack.
        let along = |u: &[i16; 3]| {
            let [u0, u1, u2] = *u;
            let nu = ((n0 * u0 as i32) >> 1) + ((n1 * u1 as i32) >> 1) + ((n2 * u2 as i32) >> 1);
            (lift * (nu >> 15)) >> 14
        };
        Some(([cu + along(u), cv + along(v)], margin))
    }

    /// Whether the quick caster test clears caster `k` (`s`): the lifted point `at` (see
    /// [`Self::quick_across`]) lies farther across light `light` from the caster's centre
    /// than its radius plus `margin`, so no ray from it along the light meets the caster
    /// (the exact test, `narrow_blocked`'s, would find `|oc|² − b² > r²`). A few 16×16-bit
    /// products, where the exact test takes a dozen 32×32→64-bit ones; it never clears a
    /// caster the exact test finds blocking (test `the_quick_caster_test_changes_no_pixel`).
    #[inline(always)]
    fn quick_clear(
        &self,
        at: [i32; 2],
        margin: i32,
        k: usize,
        s: &FixedSphere,
        light: usize,
    ) -> bool {
        let Some(c) = self.narrow_lights.get(k).and_then(|l| l.get(light)) else {
            return false;
        };
        let reach = (s.radius.to_bits() >> self.quick_shift.min(31)) + 1 + margin;
        if reach >= 1 << 15 {
            return false;
        }
        let ([au, av], [cu, cv]) = (at, c.across);
        let (du, dv) = (au - cu, av - cv);
        if du.abs() > reach || dv.abs() > reach {
            return true;
        }
        // Both below 2¹⁵: the squares' sum below 2³¹.
        (du * du) as u32 + (dv * dv) as u32 > (reach * reach) as u32
    }

    /// Whether the ray from `oc` (raw, from the caster's centre) along the light, `b` being
    /// `oc·L` (raw), leaves the caster `s` beyond `ε`, given that its line meets it: ahead of
    /// the point (`b < −ε`), or from a point inside or within `ε` of it, iff
    /// `r² − |oc|² > ε·(2b + ε)`. Only where the sphere touches the caster; out of line.
    #[inline(never)]
    fn crosses_beyond_epsilon(&self, oc: V3<i32>, b: i32, s: &FixedSphere) -> bool {
        let eps = self.epsilon.to_bits() as i64;
        (b as i64) < -eps || s.radius_sq.to_bits() - dot_ii(oc, oc) > eps * (2 * b as i64 + eps)
    }
}

/// Whether a ray that meets a sphere ahead (`b = (O − C)·L < 0`, raw, and `r² − |O − C|² +
/// b² = rest ≥ 0`) meets it before `reach` (raw): its near root `−b − √rest` is below it.
#[inline(always)]
fn before(reach: i64, b: i32, rest: i64) -> bool {
    let gap = -(b as i64) - reach;
    gap <= 0
        || mul_ii(
            gap.min(i32::MAX as i64) as i32,
            gap.min(i32::MAX as i64) as i32,
        ) < rest
}
