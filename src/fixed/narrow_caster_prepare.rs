//! The narrow kernel's per-frame constants for its shadow filters ([`super::narrow_shadow`],
//! [`super::narrow_point_shadow`]): each sphere's casters per light and the `N·L` filter
//! that skips them ([`PreparedFixed::narrow_casters`],
//! [`PreparedFixed::narrow_point_casters`]), the spheres it touches, and the quick caster
//! test's basis across each distant light and its margin. Integers on the frame's scaled
//! geometry, like the rest of the narrow prepare ([`super::narrow_prepare`]), which calls
//! them; the plane rule below is `f32`, as the shadow rows are.
//!
//! A caster leaves a sphere's mask where the kernel could never find it blocking: too far
//! from the rays, or (feature `shadow-rows`) on the far side of a plane from every ray the
//! sphere's lit pixels cast ([`crate::caster_plane`], with this path's margin in
//! [`plane_clears`]), or behind every such ray, which moves away from its centre and leaves
//! it within `ε` where it starts inside it ([`recedes`]: a floor under a sphere resting on
//! it, lit from too low for the plane). The crate's tests assert,
//! at every pixel they render, that no caster these rules leave out blocks the ray the
//! kernel would cast.

use super::mul::{dot_ii, mul_ii, mul_iu, mul_uu};
use super::prepare::{FixedLight, FixedSphere, PreparedFixed};
use super::roots::{inv_sqrt, sqrt};
use super::vector::{each3, Len, Unit, V3};
use crate::scene::Scene;

impl<const S: usize, const L: usize> PreparedFixed<S, L> {
    /// The quick caster test's shift ([`Self::quick_shift`]) and each distant light's
    /// basis across it ([`Self::across`]).
    #[inline(always)]
    pub(super) fn prepare_across(&mut self) {
        let eps = self.epsilon.to_bits() as i64;
        let lift = self.spheres.iter().map(|s| s.radius.to_bits() as i64 + eps);
        self.quick_shift = 64u32.saturating_sub(lift.max().unwrap_or(0).leading_zeros() + 16);
        for (across, light) in self.across.iter_mut().zip(&self.lights) {
            if let FixedLight::Distant { to_light, .. } = light {
                *across = across_light(to_light.map(|c| c.to_bits()));
            }
        }
    }

    /// A raw point `p`'s offset from the eye across light `light`, `(p − eye)·u` and
    /// `(p − eye)·v` with `u`, `v` the light's [`PreparedFixed::across`], in the quick caster
    /// test's units, rounded to the nearest and held within `2³⁰` (a sphere's centre is well
    /// inside). From `eye_offset = eye − p` (raw, as [`FixedSphere::eye_offset`] holds it for
    /// a sphere's centre): `−(eye − p)·u`, the same integer as `p·u − eye·u` with three
    /// products where that takes six.
    pub(super) fn across_from_eye(&self, eye_offset: V3<i32>, light: usize) -> [i32; 2] {
        let shift = 15 + self.quick_shift;
        let limit = 1i64 << 30;
        self.across.get(light).map_or([0; 2], |uv| {
            // The offset times u in raw units times 2¹⁵, to the quick test's units.
            uv.map(|u| {
                let u = u.map(i32::from);
                let at = ((1 << (shift - 1)) - dot_ii(eye_offset, u)) >> shift;
                at.clamp(-limit, limit) as i32
            })
        })
    }

    /// [`NarrowSphere::quick_margin`] of sphere `i`, in the quick test's units (`2^s` raw,
    /// `s` the frame's `quick_shift`): with `Ω` the largest `|O − C_k|` over its lifted
    /// points `O` and the casters `k` (at most the largest distance of centres plus
    /// `r + ε`), `17 + Ω·2⁻¹¹ + 2√(2Ω + 1)`, each in units. The quick test's own rounding
    /// is below 10 units; `u` and `v` are within `2⁻¹⁴` of an exact basis across the
    /// light, which moves a distance by `Ω·2⁻¹⁴`; and the exact test's `b`, rounded down to
    /// a raw unit, and `|L|`'s distance from 1 let it block a ray up to
    /// `√(2Ω + 1) + Ω·2⁻¹⁴` raw beyond the caster's radius. Each term is doubled or more.
    /// `−1` where the test is off or the radius too large for its units.
    pub(super) fn quick_margin(&self, i: usize) -> i32 {
        let Some(own) = self.spheres.get(i) else {
            return -1;
        };
        let lift = own.radius.to_bits() as i64 + self.epsilon.to_bits() as i64;
        let shift = self.quick_shift;
        if !QUICK_CASTER_TEST || lift >> shift >= 1 << 16 {
            return -1;
        }
        // Only a receiver four times the radius of each of its casters (a floor under the
        // spheres resting on it) takes the test: most of its pixels lie far from every
        // caster's cylinder, where the test saves the exact one; on spheres of like sizes
        // it costs more than it saves.
        let casters = self
            .narrow_lights
            .get(i)
            .map_or(0, |l| l.iter().fold(0, |m, l| m | l.casters));
        let mut far = 0u64;
        for (k, s) in self.spheres.iter().enumerate() {
            if k < 32 && casters & (1 << k) != 0 && s.radius.to_bits() > own.radius.to_bits() / 4 {
                return -1;
            }
            let d = each3(|j| own.center[j].to_bits().wrapping_sub(s.center[j].to_bits()));
            far = far.max(d.iter().map(|&v| mul_ii(v, v) as u64).sum::<u64>());
        }
        // Centres within 2³⁰ raw of each other: Ω below 2³¹.
        let omega = sqrt(far) + 1 + lift as u64;
        let root = sqrt(2 * omega + 1) + 1;
        (16 + ((omega >> shift) >> 11) + ((2 * root) >> shift) + 1).min(i32::MAX as u64) as i32
    }

    /// The spheres whose surface comes within `4ε` of sphere `i`'s (bit `k` for sphere `k`,
    /// the first 32), from the exact squared distance of the centres.
    pub(super) fn touching(&self, i: usize) -> u32 {
        let Some(own) = self.spheres.get(i) else {
            return 0;
        };
        let eps = self.epsilon.to_bits() as i64;
        let mut mask = 0;
        for (k, s) in self.spheres.iter().enumerate().take(32) {
            let d = each3(|j| own.center[j].to_bits().wrapping_sub(s.center[j].to_bits()));
            let len2 = d.iter().map(|&v| mul_ii(v, v)).sum::<i64>();
            // Radii below 2²⁹ raw and ε far below: the sum fits an `i32`.
            let apart = (own.radius.to_bits() as i64 + s.radius.to_bits() as i64 + 4 * eps)
                .min(i32::MAX as i64) as i32;
            if k != i && len2 <= mul_ii(apart, apart) {
                mask |= 1 << k;
            }
        }
        mask
    }

    /// The casters of sphere `i` for the distant light `to_light` and their filter, as
    /// [`NarrowLight`] holds them: `(casters, ahead, reach)`. One pass over the other
    /// spheres, on the frame's scaled integers.
    ///
    /// A shadow ray from the sphere's surface, lifted by `ε`, starts within `r + ε` of the
    /// half-line from its centre toward the light, so only a sphere whose centre comes within
    /// `r + r_k + ε` of that half-line can block it. The mask takes the spheres within
    /// `r + r_k + 5ε` and `2⁻⁹` of the radii (looser than the rule of
    /// [`Scene::shadow_casters`]), so it is never short of a caster. `ahead` and `reach` are
    /// the loosest over the casters, each rounded toward passing more pixels, then widened by
    /// the fast `N·L`'s error (`2⁻¹²`, and `2⁻¹¹` for its square); with no caster nothing
    /// passes.
    ///
    /// Integers only, from exact 32×32→64 products: the scene lies within `2¹³` units, so
    /// every centre and radius is below `2²⁹` raw and every difference below `2³⁰`. The
    /// distance of a caster's centre from the half-line is `|Δ × L|` (no cancellation, unlike
    /// `|Δ|² − (Δ·L)²`), each component taken to raw units (rounded down, within one unit)
    /// and the root ([`sqrt`], within `2⁻²⁹`) lowered by four units and that relative error,
    /// which also covers `|L|`'s distance from 1 (`2⁻²⁹`).
    ///
    /// A caster on the far side of the sphere from the light, which a plane keeps from every
    /// ray the sphere's pixels cast ([`separated`]: the floor under a sphere resting on it,
    /// lit from above), is not in the mask. Any other caster touching the sphere is, like
    /// any other; where the lifted point lies within `ε` of it and ahead of its centre along
    /// the light, the filter passes the pixel as unblocked, which the full-width kernel's
    /// ray, starting inside the caster, may not: a sliver of width `ε` at the contact.
    ///
    /// `None` if the frame has spheres beyond the mask's 32 bits. Out of line: once per
    /// sphere and light.
    #[inline(never)]
    pub(super) fn narrow_casters(&self, i: usize, to_light: V3<Unit>) -> Option<(u32, i32, u32)> {
        let own = self.spheres.get(i)?;
        let eps = self.epsilon.to_bits() as i64;
        let radius = |s: &FixedSphere| s.radius.to_bits() as i64;
        let r = radius(own);
        let l = to_light.map(|c| c.to_bits());
        // r + ε is at least one unit (2¹⁶ raw) and below 2³¹: the `max`es only show the
        // compiler that no divisor below is 0.
        let lift = ((r + eps) as u64).max(1);
        let (mut mask, mut ahead, mut reach) = (0u32, i64::MIN, i64::MIN);
        for (k, c) in self.spheres.iter().enumerate() {
            if k == i {
                continue;
            }
            if k >= 32 {
                return None;
            }
            let rk = radius(c);
            let d = each3(|j| own.center[j].to_bits().wrapping_sub(c.center[j].to_bits()));
            let len2 = d.iter().map(|&v| mul_ii(v, v)).sum::<i64>();
            // Δ·L in raw units times 2³⁰, exact.
            let along = mul_ii(d[0], l[0]) + mul_ii(d[1], l[1]) + mul_ii(d[2], l[2]);
            // |Δ × L| in raw units, rounded down per component: below 2³¹ each.
            let cross =
                |a: usize, b: usize| ((mul_ii(d[a], l[b]) - mul_ii(d[b], l[a])) >> 30) as i32;
            let cross = [cross(1, 2), cross(2, 0), cross(0, 1)];
            let cross2 = cross.iter().map(|&v| mul_ii(v, v) as u64).sum::<u64>();
            let root = sqrt(cross2);
            let across = (root - (root >> 28)) as i64 - 4;
            let radii = r + rk;
            let near = radii + (radii >> 9) + 5 * eps;
            // The half-line's closest point to the caster's centre: its start where the
            // caster lies behind the sphere along the light (`Δ·L ≥ 0`).
            let far = if along < 0 {
                across >= near
            } else {
                len2 >= mul_ii(near as i32, near as i32)
            };
            if far || separated((r, rk, eps), len2, along) {
                continue;
            }
            mask |= 1 << k;
            // −(Δ·L)/(r + ε) in Q15, rounded up (by a whole step where it is positive).
            let q = (along.unsigned_abs() / (lift << 15).max(1)) as i64;
            ahead = ahead.max(if along < 0 { q + 1 } else { -q });
            // 1 − (gap/(r + ε))² in Q30, the ratio rounded down to 30 bits (gap < 2³¹).
            let gap = across - rk;
            let g30 = if gap <= 0 {
                0
            } else {
                ((gap as u64) << 30) / lift
            };
            let g30 = g30.min(u32::MAX as u64) as u32;
            reach = reach.max((1 << 30) - (mul_uu(g30, g30) >> 30) as i64);
        }
        if mask == 0 {
            return Some((0, i32::MIN, 0));
        }
        let q15 = (ahead + 8).clamp(-2 << 15, 2 << 15);
        let q30 = (reach + (1 << 19)).clamp(0, 2 << 30);
        Some((mask, q15 as i32, q30 as u32))
    }
}

impl<const S: usize, const L: usize> PreparedFixed<S, L> {
    /// The casters of sphere `i` for the point light `light` (its index; as [`NarrowLight`]
    /// holds them): [`Scene::shadow_casters`]' mask, the same spheres the full-width kernel
    /// tests, less those a plane keeps off every ray toward the light or that every ray
    /// recedes from ([`point_separated`]),
    /// and a filter that passes every pixel (`N·L` alone does not bound a ray toward a
    /// point). `None` if the frame has spheres beyond the mask's 32 bits.
    pub(super) fn narrow_point_casters(
        &self,
        scene: &Scene<S, L>,
        i: usize,
        light: usize,
    ) -> Option<(u32, i32, u32)> {
        if scene.spheres().len() > 32 {
            return None;
        }
        let mask = scene
            .lights()
            .get(light)
            .map_or(0, |l| scene.shadow_casters(i, l))
            & !self.point_separated_casters(i, light);
        Some(match mask {
            0 => (0, i32::MIN, 0),
            mask => (mask, i32::MAX, u32::MAX),
        })
    }

    /// The spheres [`point_separated`] from sphere `i` for point light `light` (bit `k` for
    /// sphere `k`, the first 32; none for a distant light).
    pub(super) fn point_separated_casters(&self, i: usize, light: usize) -> u32 {
        let (Some(own), Some(FixedLight::Point { position, .. })) =
            (self.spheres.get(i), self.lights.get(light))
        else {
            return 0;
        };
        let eps = self.epsilon.to_bits() as i64;
        let raw = |c: Len| c.to_bits() as i64;
        let q = each3(|j| raw(position[j]) - raw(own.center[j]));
        let mut mask = 0;
        for (k, c) in self.spheres.iter().enumerate().take(32) {
            let d = each3(|j| raw(own.center[j]) - raw(c.center[j]));
            if k != i && point_separated((raw(own.radius), raw(c.radius), eps), d, q) {
                mask |= 1 << k;
            }
        }
        mask
    }

    /// Under test, the spheres [`separated`] from sphere `i` for the distant light
    /// `to_light` (I2F30 bits): those `narrow_casters` leaves out for it, near or far.
    #[cfg(test)]
    pub(super) fn separated_casters(&self, i: usize, to_light: [i32; 3]) -> u32 {
        let Some(own) = self.spheres.get(i) else {
            return 0;
        };
        let eps = self.epsilon.to_bits() as i64;
        let mut mask = 0;
        for (k, c) in self.spheres.iter().enumerate().take(32) {
            let d = each3(|j| own.center[j].to_bits().wrapping_sub(c.center[j].to_bits()));
            let len2 = d.iter().map(|&v| mul_ii(v, v)).sum::<i64>();
            let along = (0..3).map(|j| mul_ii(d[j], to_light[j])).sum::<i64>();
            let radii = (own.radius.to_bits() as i64, c.radius.to_bits() as i64, eps);
            if k != i && separated(radii, len2, along) {
                mask |= 1 << k;
            }
        }
        mask
    }
}

/// Whether a caster of radius `rk` (raw) lies beyond a plane that every shadow ray toward a
/// distant light from the pixels of a sphere of radius `r` keeps off: `len2` is `|Δ|²` and
/// `along` is `Δ·L·2³⁰` (raw), with `Δ` the sphere's centre less the caster's and `L` the
/// unit vector toward the light. [`plane_clears`] or [`recedes`], with `δ = Δ·L/|Δ|` and
/// the fast `N·L`'s error (`2⁻¹²`) widened to `2⁻¹⁰`.
///
/// This is what takes a floor sphere out of the casters of a sphere resting on it under a
/// light from above, which otherwise meets the caster tests of every lit pixel: the plane
/// where the light is high, the receding rays where it is lower.
fn separated(radii: (i64, i64, i64), len2: i64, along: i64) -> bool {
    distant_pair(len2, along).is_some_and(|(len, delta)| {
        plane_clears(radii, len, delta, DISTANT_WIDEN) || recedes(radii, len, delta, DISTANT_WIDEN)
    })
}

/// The fast `N·L`'s error (`2⁻¹²`) widened, for [`separated`]'s own-shadow limit.
const DISTANT_WIDEN: f32 = 1.0 / 1024.0;

/// `|Δ|` and `δ = Δ·L/|Δ|` in `f32` from `len2 = |Δ|²` and `along = Δ·L·2³⁰` (raw), where
/// the rules of [`separated`] can apply: with the plane rule built in, and the caster
/// behind the sphere along the light.
fn distant_pair(len2: i64, along: i64) -> Option<(f32, f32)> {
    if !PLANE_RULE || along <= 0 || len2 <= 0 {
        return None;
    }
    let len = libm::sqrtf(len2 as f32);
    Some((len, along as f32 / (len * (1u64 << 30) as f32)))
}

/// [`separated`] for a point light at `q = P − C` (raw) from the sphere's centre, `d` being
/// `Δ`: `δ` is the least `n·L` over the lifted sphere's points, `cos(γ + β)` with `γ` the
/// angle between `Δ` and `q` and `sin β = (r + ε)/|q|`, and the fast point light's `N·L`
/// error (within `2⁻⁹` where it serves, see `point_fast`) is widened to `2⁻⁸`. Each sine
/// is rounded up and each cosine down, by more than the `f32` rounding of their square
/// roots where those lose most (near 1). Both of [`separated`]'s rules hold with the rays'
/// directions varying: each needs only a lower bound on `n·L` over them.
fn point_separated(radii: (i64, i64, i64), d: [i64; 3], q: [i64; 3]) -> bool {
    if !PLANE_RULE {
        return false;
    }
    let (r, _, eps) = radii;
    let (d, q) = (d.map(|c| c as f32), q.map(|c| c as f32));
    let dot = |a: [f32; 3], b: [f32; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let (len, q_len) = (libm::sqrtf(dot(d, d)), libm::sqrtf(dot(q, q)));
    let lift = (r + eps) as f32;
    if !(len > 0.0 && q_len > lift * 1.001) {
        return false;
    }
    let cos_g = dot(d, q) / (len * q_len) - 1.0 / 1_048_576.0;
    let sin_b = lift / q_len * (1.0 + 1.0 / 1_048_576.0);
    let sin_g = libm::sqrtf((1.0 - cos_g * cos_g).max(0.0)) + 1.0 / 2048.0;
    let cos_b = libm::sqrtf((1.0 - sin_b * sin_b).max(0.0)) - 1.0 / 2048.0;
    let delta = cos_g * cos_b - sin_g * sin_b;
    plane_clears(radii, len, delta, 1.0 / 256.0) || recedes(radii, len, delta, 1.0 / 256.0)
}

/// Whether the plane across `Δ` (`|Δ| = len`, raw) keeps a caster of radius `rk` off every
/// shadow ray from the pixels of a sphere of radius `r` that test casters, given a lower
/// bound `δ` on `n·L` and the bound `widen` of the error of the `N·L` the own-shadow test
/// reads: [`crate::caster_plane::clearance`] above a margin of twice how far beyond its
/// radius the exact ray can find the caster blocked at the distance `Ω = |Δ| + r + ε`
/// (`√(r_k² + 2Ω + 1) − r_k`, the rounding of `b` to a raw unit), four times `Ω·2⁻¹⁴` for
/// the light's direction (as in [`PreparedFixed::quick_margin`]), `256` raw, `ε`, and
/// `r/2¹²` for the normal's error.
///
/// In `f32`, as the shadow rows are (feature `shadow-rows`, which holds this rule too):
/// `δ` is lowered by `2⁻²⁰`, and the clearance given `2⁻¹²` of the lift (the cosine's
/// rounding near 1) and `2⁻¹⁶` of the distance, each many times the rounding of the few
/// operations before it.
fn plane_clears((r, rk, eps): (i64, i64, i64), len: f32, delta: f32, widen: f32) -> bool {
    let (r, rk, eps) = (r as f32, rk as f32, eps as f32);
    let lift = r + eps;
    let omega = len + lift;
    let spread = 2.0 * omega + 1.0;
    let beyond = libm::sqrtf(spread).min(spread / (2.0 * rk.max(1.0)) + 1.0);
    let margin = 2.0 * (beyond + 1.0) + omega / 4096.0 + 256.0 + eps + r / 4096.0;
    let slack = lift / 4096.0 + len / 65536.0;
    let delta = delta - 1.0 / 1_048_576.0;
    crate::caster_plane::clearance((r, rk, eps), len, delta, widen)
        .is_some_and(|c| c - slack > margin)
}

/// Whether every shadow ray toward a light (`δ` a lower bound on `n·L` over the rays) from
/// the pixels of a sphere of radius `r` that test casters moves away from the centre of a
/// caster of radius `rk` at `|Δ| = len` (raw), and, where it starts inside the caster,
/// leaves it within `ε`: then the
/// exact ray ([`PreparedFixed::blocked_along`]) never finds the caster blocking, although
/// the plane may not keep it off ([`plane_clears`]). `δ` and `widen` as there; the
/// geometry is [`crate::caster_plane::recession`]'s and
/// [`crate::caster_plane::leaves_within`]'s.
///
/// This is a floor under a sphere resting on it, lit from low enough that the lifted
/// points near the contact, inside the floor by up to `ε`, are not all in the sphere's own
/// shadow. The margins: the exact `b` is rounded down to a raw unit and the light's
/// direction is within `2⁻²⁹` of unit length (256 raw), and the kernel's lifted point is
/// within `2⁻¹¹` of the lift of the exact one (the normal's error, doubled); `x` takes the
/// plane rule's slack besides, for the `f32` roundings. The exact test's own arithmetic is
/// exact.
fn recedes((r, rk, eps): (i64, i64, i64), len: f32, delta: f32, widen: f32) -> bool {
    let (r, rk, eps) = (r as f32, rk as f32, eps as f32);
    let delta = delta - 1.0 / 1_048_576.0;
    let Some((b, x)) = crate::caster_plane::recession((r, eps), len, delta, widen) else {
        return false;
    };
    let lift = r + eps;
    let point_error = lift / 2048.0 + 4.0;
    let slack = lift / 4096.0 + len / 65536.0 + 256.0;
    let bounds = (b - point_error - 256.0, x - point_error - slack);
    crate::caster_plane::leaves_within(rk, eps, bounds, 0.0)
}

/// Whether the casters' masks leave out what a plane keeps off ([`plane_clears`]): with
/// the feature `shadow-rows`, whose prepare holds the floors' `f32` shadow geometry.
const PLANE_RULE: bool = cfg!(feature = "shadow-rows");

/// Whether the narrow kernel takes the quick caster test (`narrow_blocked`): on ARMv6-M,
/// where each 32×32→64-bit product of the exact test is a call, it saves most of a floor's
/// caster tests, and on RV32, whose 64-bit product is two instructions, some; with the
/// Cortex-M4's one-instruction product the exact test is about as cheap, and the quick one
/// costs the loop more than it saves (`docs/performance.md`, "Choices measured"). The
/// crate's own tests turn it on everywhere, to hold it to changing no pixel.
pub(crate) const QUICK_CASTER_TEST: bool =
    cfg!(any(shadeline_short_mul, target_arch = "riscv32", test));

/// Two unit vectors across the unit vector `l` (Q30), in Q15: `u = (l × e)/|l × e|` for the
/// axis `e` least along `l` (so `|l × e|² ≥ 2/3`), and `v = l × u`. Each is within `2⁻¹⁵`
/// of the exact basis across `l/|l|` in length (rounding down to Q15, `inv_sqrt`'s error,
/// and `|l|` within `2⁻²⁹` of 1).
fn across_light(l: [i32; 3]) -> [[i16; 3]; 2] {
    let [x, y, z] = l;
    let m = l.map(|c| c.unsigned_abs());
    // Components of a unit vector in Q30: negating one cannot overflow.
    let w = if m[0] <= m[1] && m[0] <= m[2] {
        [0, z, -y]
    } else if m[1] <= m[2] {
        [-z, 0, x]
    } else {
        [y, -x, 0]
    };
    let len2 = w.iter().map(|&c| mul_ii(c, c) as u64).sum::<u64>();
    let unit = |c: i64| c.clamp(-(1 << 15) + 1, (1 << 15) - 1) as i32;
    // w·(1/|w|) in Q15: `inv_sqrt`'s `v·y >> (shift − 15)`, `shift` at least 31.
    let (inv, shift) = inv_sqrt(len2).unwrap_or((0, 31));
    let [u0, u1, u2] = w.map(|c| unit(mul_iu(c, inv) >> (shift - 15)));
    let cross = |a: i32, b: i32, c: i32, d: i32| unit((mul_ii(a, b) - mul_ii(c, d)) >> 30);
    let v = [
        cross(y, u2, z, u1),
        cross(z, u0, x, u2),
        cross(x, u1, y, u0),
    ];
    [[u0, u1, u2].map(|c| c as i16), v.map(|c| c as i16)]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::vec3::Vec3;

    /// `narrow_casters` against the same geometry in `f64`, from the prepared integers, over
    /// random pairs of spheres under a random distant light: the mask never leaves out a
    /// sphere within the rule of `Scene::shadow_casters` (nor takes one well outside its own),
    /// and `ahead` and `reach` are never tighter than the exact values widened by the fast
    /// `N·L`'s error, nor looser than that by more than their rounding.
    #[test]
    fn caster_filter_is_the_exact_filter_rounded_outward() {
        use crate::scene::{Camera, Light, Material, Sphere};
        use crate::LinearRgb;
        let mut state = 0x853c_49e6_748f_ea9bu64;
        let mut next = |lo: f64, hi: f64| {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (lo + (hi - lo) * ((state >> 11) as f64 / (1u64 << 53) as f64)) as f32
        };
        let (mut masked, mut left_out, mut separated_near) = (0, 0, 0);
        for round in 0..4000 {
            let camera = Camera {
                position: Vec3::new(0.0, 0.0, 40.0),
                look_at: Vec3::new(0.0, 0.0, 0.0),
                up: Vec3::new(0.0, 1.0, 0.0),
                vfov_degrees: 30.0,
            };
            let mut scene: Scene<2, 1> = Scene::new(camera, LinearRgb::new(0.0, 0.0, 0.0)).unwrap();
            let direction = Vec3::new(next(-1.0, 1.0), next(-1.0, 1.0), next(-1.0, 1.0));
            let mut spheres = [0; 2].map(|_| Sphere {
                center: Vec3::new(next(-3.0, 3.0), next(-3.0, 3.0), next(-3.0, 3.0)),
                radius: next(0.2, 1.5),
                material: Material::default(),
            });
            if round % 2 == 1 {
                // The second sphere ahead of the first along the light, its centre about the
                // radii from the half-line: where the mask's margins decide (ε is 0.004 here).
                let Some(u) = (-direction).normalized() else {
                    continue;
                };
                let Some(p) = u.cross(Vec3::new(next(-1.0, 1.0), 1.0, 0.5)).normalized() else {
                    continue;
                };
                let radii = spheres[0].radius + spheres[1].radius;
                let offset = u.scale(next(1.0, 3.0)) + p.scale(radii + next(0.0, 0.04));
                spheres[1].center = spheres[0].center + offset;
            }
            if spheres.iter().any(|s| scene.add_sphere(*s).is_err()) {
                continue;
            }
            let light = Light::Distant {
                direction,
                color: LinearRgb::new(1.0, 1.0, 1.0),
                intensity: 1.0,
            };
            if scene.add_light(light).is_err() {
                continue;
            }
            let Ok(frame) = PreparedFixed::new(&scene, 64, 48) else {
                continue;
            };
            if frame.narrow.is_none() {
                continue;
            }
            let Some(FixedLight::Distant { to_light, .. }) = frame.lights.first() else {
                panic!("a distant light");
            };
            let l = to_light.map(|c| c.to_bits() as f64);
            let norm = (l[0] * l[0] + l[1] * l[1] + l[2] * l[2]).sqrt();
            let l = l.map(|c| c / norm);
            let eps = frame.epsilon.to_bits() as f64;
            for (i, k) in [(0, 1), (1, 0)] {
                let (own, other) = (&frame.spheres[i], &frame.spheres[k]);
                let d = each3(|j| (own.center[j].to_bits() - other.center[j].to_bits()) as f64);
                let (r, rk) = (own.radius.to_bits() as f64, other.radius.to_bits() as f64);
                let along = d[0] * l[0] + d[1] * l[1] + d[2] * l[2];
                let len = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
                let across = (len * len - along * along).max(0.0).sqrt();
                let dist = if along < 0.0 { across } else { len };
                let filter = frame.narrow_lights[i][0];
                let bit = filter.casters & (1 << k) != 0;
                let radii = r + rk;
                if dist < radii + 5.0 * eps + 1.0e-3 * radii && !bit {
                    // Only a caster a plane keeps off every ray leaves the mask this near.
                    let pair = crate::test_scenes::PlanePair {
                        r,
                        rc: rk,
                        eps,
                        d,
                        l,
                    };
                    assert!(
                        along > 0.0
                            && (pair.clearance().is_some_and(|c| c > 0.0) || pair.recedes()),
                        "sphere {k} left out of {i}'s casters at {dist} raw"
                    );
                    separated_near += 1;
                }
                if dist > radii * (1.0 + 1.0 / 512.0) + 5.0 * eps + 16.0 {
                    assert!(!bit, "sphere {k} among {i}'s casters at {dist} raw");
                    left_out += 1;
                }
                if !bit {
                    continue;
                }
                masked += 1;
                let lift = r + eps;
                let ahead = ((-along / lift + 1.0 / 4096.0) * 32768.0).clamp(-65536.0, 65536.0);
                let got = filter.ahead as f64;
                assert!(
                    got >= ahead - 1e-3 && got <= ahead + 2.01,
                    "ahead {got} for {ahead}"
                );
                let gap = across - rk;
                let reach = if gap <= 0.0 {
                    1.0
                } else {
                    1.0 - (gap / lift).powi(2)
                };
                let reach = ((reach + 1.0 / 2048.0) * (1u64 << 30) as f64)
                    .clamp(0.0, 2.0 * (1u64 << 30) as f64);
                let got = filter.reach as f64;
                assert!(
                    got >= reach - 1.0 && got <= reach + (1 << 18) as f64,
                    "reach {got} for {reach}"
                );
            }
        }
        assert!(
            masked > 1000 && left_out > 3000 && separated_near > 10,
            "{masked} masked, {left_out} left out, {separated_near} near ones separated"
        );
    }

    /// The plane rule of [`separated`] ([`plane_clears`]) against the geometry in `f64`,
    /// over random pairs of spheres (the caster up to 200 times the radius, a floor) and
    /// lights: wherever it leaves a caster out, no
    /// shadow ray from a lifted point of the sphere that tests casters (`N·L` at or above
    /// minus the own-shadow limit, widened by `2⁻¹¹`) passes within the caster's radius, at
    /// the worst such point and at random ones; and it leaves out most pairs whose exact
    /// clearance is a tenth of the radius or more.
    #[test]
    fn separated_casters_meet_no_ray() {
        use crate::test_scenes::{uniform64, PlanePair};
        let mut next = uniform64(0x2545_f491_4f6c_dd1d);
        let (mut dropped, mut clear, mut clear_dropped) = (0, 0, 0);
        for _ in 0..20_000 {
            let pair = PlanePair::random(&mut next, 65536.0);
            let PlanePair { r, rc, eps, d, l } = pair;
            let l_q30 = l.map(|c| (c * (1u64 << 30) as f64).round() as i64);
            let d_raw = d.map(|c| c as i64);
            let along: i64 = (0..3).map(|j| d_raw[j] * l_q30[j]).sum();
            let len2: i64 = d_raw.iter().map(|c| c * c).sum();
            let is_clear = pair.clearance().is_some_and(|c| c > 0.1 * r);
            clear += is_clear as u32;
            let radii = (r as i64, rc as i64, eps as i64);
            let plane = distant_pair(len2, along)
                .is_some_and(|(len, delta)| plane_clears(radii, len, delta, DISTANT_WIDEN));
            if !plane {
                continue;
            }
            clear_dropped += is_clear as u32;
            dropped += 1;
            let s = (eps * (2.0 * r + eps)).sqrt() / (r + eps) + 1.0 / 2048.0;
            // Beyond the exact ray's rounding too (`plane_clears`' margin).
            let omega = pair.len_and_delta().0 + r + eps;
            let spread = 2.0 * omega + 1.0;
            let beyond = spread.sqrt().min(spread / (2.0 * rc)) + omega / 16384.0;
            pair.assert_no_ray_within(&mut next, s, rc + beyond);
        }
        // The clear pairs it keeps are those within its margins.
        assert!(
            dropped > 3000 && clear_dropped * 10 > clear * 8,
            "{dropped} left out; {clear_dropped} of {clear} clear pairs"
        );
    }

    /// The receding rule of [`separated`] ([`recedes`]) against the geometry in `f64`, over
    /// random pairs as above: wherever it leaves a caster out, every shadow ray from a
    /// lifted point of the sphere that tests casters (`N·L` at or above minus the
    /// own-shadow limit, widened by `2⁻¹¹`) moves away from the caster's centre and leaves
    /// it within `ε` where it starts inside it, at the lifted point nearest the caster and
    /// at random ones; and it leaves out pairs that the plane keeps in (touching ones, lit
    /// from low), and most of the pairs that recede in `f64`.
    #[test]
    fn receding_casters_are_never_met() {
        extern crate std;
        use crate::test_scenes::{uniform64, PlanePair};
        let mut next = uniform64(0x9e37_79b9_7f4a_7c15);
        let (mut dropped, mut beyond_plane, mut exact, mut exact_dropped) = (0, 0, 0, 0);
        for _ in 0..40_000 {
            let mut pair = PlanePair::random(&mut next, 65536.0);
            // Half of the pairs touching, as a sphere resting on another.
            if next(0.0, 1.0) < 0.5 {
                pair = pair.touching(65536.0);
            }
            let PlanePair { r, rc, eps, d, l } = pair;
            let l_q30 = l.map(|c| (c * (1u64 << 30) as f64).round() as i64);
            let d_raw = d.map(|c| c as i64);
            let along: i64 = (0..3).map(|j| d_raw[j] * l_q30[j]).sum();
            let len2: i64 = d_raw.iter().map(|c| c * c).sum();
            let radii = (r as i64, rc as i64, eps as i64);
            let recede = pair.recedes();
            exact += recede as u32;
            let Some((len, delta)) = distant_pair(len2, along) else {
                continue;
            };
            if !recedes(radii, len, delta, DISTANT_WIDEN) {
                continue;
            }
            dropped += 1;
            exact_dropped += recede as u32;
            beyond_plane += !plane_clears(radii, len, delta, DISTANT_WIDEN) as u32;
            let s = (eps * (2.0 * r + eps)).sqrt() / (r + eps) + 1.0 / 2048.0;
            pair.assert_rays_recede(&mut next, s);
        }
        std::println!(
            "{dropped} left out, {beyond_plane} of them kept by the plane; \
             {exact_dropped} of {exact} receding pairs"
        );
        assert!(
            dropped > 3000 && beyond_plane > 100 && exact_dropped * 10 > exact * 8,
            "{dropped} left out, {beyond_plane} of them kept by the plane; \
             {exact_dropped} of {exact} receding pairs"
        );
    }
}
