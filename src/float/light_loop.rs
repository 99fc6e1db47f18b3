//! The `lights` stage of the general float kernel and the stages it runs once per light:
//! `incoming`, `shadow`, `diffuse` and `specular` (the stage table is in [`super::kernel`]).
//!
//! `normal` hands this stage the packet's [`Surface`]; it gives back the sums
//! `Σ vis·I·diffuse` and `Σ vis·I ⊙ specular` that `combine` weighs with the material. A
//! distant or point light goes through the stages written out in the loop's body; a sphere
//! light (crate feature `area-lights`) goes to `sphere_light`, which has its own `incoming`
//! and `shadow` and shares this file's `diffuse` and `specular`.
//!
//! Two const parameters keep code out of the packets and frames that do not need it:
//! `NORMALIZED`, the normalized models' arithmetic, and `SPHERES`, the sphere-light branch,
//! dispatched once per packet by `lights_of` rather than tested in the loop. Like every stage
//! of the kernel these are `#[inline(always)]`, so the packet loop compiles as one function
//! and the file boundary costs no call.

use super::intersect::meets;
use super::lane::Lane;
use super::prepare::{FloatPath, Prepared, PreparedLight, MAX_ARRIVING};
use crate::brdf::{self, Params, Present};
use crate::real::Real;
use crate::vec3::Vec3;

/// A packet's surface points: what the lighting stages read.
#[derive(Clone, Copy)]
pub(super) struct Surface<T: Lane> {
    /// The hit point `eye + t·d`.
    pub p: Vec3<T>,
    /// The unit normal.
    pub n: Vec3<T>,
    /// Unit vector toward the eye, `−d`.
    pub view: Vec3<T>,
    /// `P + ε·N`, where shadow rays start.
    pub shadow_origin: Vec3<T>,
    /// Lanes that hit a sphere.
    pub any_hit: T::Mask,
    /// The spheres some lane hit (`Hit::spheres`).
    pub hit_spheres: u32,
    /// The sphere each lane hit, as `f32` (`-1` on a miss): a sphere light's soft shadow
    /// leaves it out (its own sphere is the horizon), and a one-lane packet's shadow ray
    /// toward a light it faces does not test it.
    pub id: T,
}

/// One light as seen from a packet's surface points.
pub(super) struct Incoming<T> {
    /// Unit vector toward the light (zero where the point is at the light).
    pub to_light: Vec3<T>,
    /// Arriving colour `I`.
    pub arriving: Vec3<T>,
    /// Length of the shadow ray: the distance to a point light; `None` for a distant one,
    /// whose shadow rays have no end.
    pub t_max: Option<T>,
}

impl<W: FloatPath, const S: usize, const L: usize> Prepared<W, S, L> {
    /// [`Self::lights`] with its sphere-light branch only in frames that have a sphere
    /// light: in the light loop of every frame, that branch costs a frame without sphere
    /// lights more than dispatched here, once per packet (`docs/performance.md, "Choices measured"`).
    #[inline(always)]
    pub(super) fn lights_of<const NORMALIZED: bool>(
        &self,
        surface: &Surface<W::Lane>,
        params: &Params<W::Lane>,
        present: Present,
        record_hits: bool,
        shadowed: &mut [u32; 8],
    ) -> (Vec3<W::Lane>, Vec3<W::Lane>) {
        #[cfg(feature = "area-lights")]
        if self.sphere_lights {
            return self.lights::<NORMALIZED, true>(
                surface,
                params,
                present,
                record_hits,
                shadowed,
            );
        }
        self.lights::<NORMALIZED, false>(surface, params, present, record_hits, shadowed)
    }

    /// `lights`: the loop over every light, `incoming`, `shadow`, then `diffuse` and
    /// `specular`, giving the sums `Σ vis·I·diffuse` and `Σ vis·I ⊙ specular`. `NORMALIZED` is
    /// whether the packet shows a normalized material: without one, this is the classic
    /// models' arithmetic alone. `SPHERES` is whether the frame has a sphere light: without
    /// one, the loop holds no sphere-light code.
    #[inline(always)]
    fn lights<const NORMALIZED: bool, const SPHERES: bool>(
        &self,
        surface: &Surface<W::Lane>,
        params: &Params<W::Lane>,
        present: Present,
        record_hits: bool,
        shadowed: &mut [u32; 8],
    ) -> (Vec3<W::Lane>, Vec3<W::Lane>) {
        let one = W::Lane::splat(1.0);
        let zero = W::Lane::splat(0.0);
        let present = Present {
            normalized: NORMALIZED,
            ..present
        };
        let masks = params.masks();

        let mut diffuse_sum = Vec3::splat(Vec3::default());
        let mut specular_sum = Vec3::splat(Vec3::default());
        for (light_index, light) in self.lights.iter().enumerate() {
            #[cfg(feature = "area-lights")]
            if let (
                true,
                PreparedLight::Sphere {
                    position,
                    power,
                    radius,
                },
            ) = (SPHERES, *light)
            {
                (diffuse_sum, specular_sum) = self.sphere_light::<NORMALIZED>(
                    (light_index, position, power, radius),
                    surface,
                    (params, &masks, present),
                    (record_hits, &mut *shadowed),
                    (diffuse_sum, specular_sum),
                );
                continue;
            }
            // A distant or point light. Its stages stay written out here: moved into an
            // `#[inline(always)]` function of their own, they take the general kernel more
            // instructions on the M4F (`docs/performance.md, "Choices measured"`).
            let light = incoming(light, surface.p);
            // `N·L` as `terms` forms it. Where it is not positive, a normalized lane (every
            // normalized model and Lambert carry `max(0, N·L)` in both terms) gets exactly
            // nothing from this light, shadowed or not: a packet of only such lanes skips it
            // unless it records the shadows.
            let n_dot_l = surface.n.dot(light.to_light);
            let facing_away = n_dot_l.le(zero);
            let lit =
                W::Lane::and_not(surface.any_hit, W::Lane::and(masks.normalized, facing_away));
            if !record_hits && !W::Lane::any(lit) {
                continue;
            }
            let casters = self.light_casters(surface, light_index, facing_away);
            let blocked = self.shadow(surface, &light, casters);
            if record_hits && light_index < 32 {
                let bits = W::Lane::bitmask(W::Lane::and(surface.any_hit, blocked));
                for (lane, word) in shadowed.iter_mut().enumerate() {
                    *word |= ((bits >> lane) & 1) << light_index;
                }
            }
            let visible = W::Lane::and_not(surface.any_hit, blocked);
            if !W::Lane::any(visible) {
                continue;
            }
            let (n, view) = (surface.n, surface.view);
            let t = brdf::terms(params, &masks, present, n, light.to_light, view);
            let lit = W::Lane::select(visible, one, zero);
            diffuse_sum = diffuse(diffuse_sum, &light, t.diffuse, lit);
            specular_sum = specular::<_, NORMALIZED>(specular_sum, &light, t.specular, lit);
        }
        (diffuse_sum, specular_sum)
    }

    /// [`Self::casters_of`] for a packet's shadow rays toward light `light`, less a one-lane
    /// packet's own sphere where the lane faces the light (`facing_away` false): the ray from
    /// `P + ε·N` starts `ε` above the sphere's tangent plane at `P` and moves away from it,
    /// and the sphere lies below that plane; `meets` finds `b + ε > 0` and `(b + ε)² − disc`
    /// about `2rε`, far above its rounding, so its own sphere cannot block it. (The SIMD
    /// paths test it and must agree bit for bit: `tests/paths_agree.rs`.)
    #[inline(always)]
    fn light_casters(
        &self,
        surface: &Surface<W::Lane>,
        light: usize,
        facing_away: <W::Lane as Real>::Mask,
    ) -> u32 {
        let mut casters = self.casters_of(surface.hit_spheres, light);
        if W::Lane::LANES == 1 && !W::Lane::any(facing_away) {
            let own = surface.id.lane(0);
            if (0.0..32.0).contains(&own) {
                casters &= !(1u32 << own as u32);
            }
        }
        casters
    }

    /// The spheres a packet's shadow rays toward light `light` must test: the spheres its
    /// lanes hit (`hit_spheres`) and those that can shadow them
    /// ([`Scene::shadow_casters`](crate::Scene)), as a mask over the first 32 spheres.
    #[inline(always)]
    fn casters_of(&self, hit_spheres: u32, light: usize) -> u32 {
        let mut mask = hit_spheres;
        let mut rest = hit_spheres;
        while rest != 0 {
            let k = rest.trailing_zeros() as usize;
            rest &= rest - 1;
            if let Some(c) = self.casters.get(k).and_then(|c| c.get(light)) {
                mask |= c;
            }
        }
        mask
    }

    /// `shadow`: the lanes where a sphere lies between `P + ε·N` and the light. Only the
    /// spheres in `casters` (and every sphere from index 32 on) are tested: the others cannot
    /// block any of the packet's rays, so leaving them out changes no lane.
    #[inline(always)]
    fn shadow(
        &self,
        surface: &Surface<W::Lane>,
        light: &Incoming<W::Lane>,
        casters: u32,
    ) -> <W::Lane as Real>::Mask {
        let eps = W::Lane::splat(self.epsilon);
        let mut blocked = W::Lane::lt(W::Lane::splat(1.0), W::Lane::splat(0.0));
        // The casters' bits, lowest first, then every sphere from 32 on (only a capacity
        // above 32 has them): a walk over the set bits rather than over every sphere (a lit
        // pixel of the exponent series tests one or two of its five).
        let mut rest = casters;
        let mut next = 32;
        while rest != 0 || (S > 32 && next < self.spheres.len()) {
            let k = if rest != 0 {
                let k = rest.trailing_zeros() as usize;
                rest &= rest - 1;
                k
            } else {
                next += 1;
                next - 1
            };
            let Some(s) = self.spheres.get(k) else {
                continue;
            };
            let oc = surface.shadow_origin - Vec3::splat(s.center);
            let hit = meets(
                oc,
                light.to_light,
                W::Lane::splat(s.radius_sq),
                eps,
                light.t_max,
            );
            blocked = W::Lane::or(blocked, hit);
            if !W::Lane::any(W::Lane::and_not(surface.any_hit, blocked)) {
                break;
            }
        }
        blocked
    }
}

/// `incoming`: the direction toward `light` from the points `p`, the colour arriving there
/// and the shadow ray's length.
#[inline(always)]
fn incoming<T: Lane>(light: &PreparedLight, p: Vec3<T>) -> Incoming<T> {
    match *light {
        PreparedLight::Distant { to_light, arriving } => Incoming {
            to_light: Vec3::splat(to_light),
            arriving: Vec3::splat(arriving),
            t_max: None,
        },
        // Shaded by `sphere_incoming`, never here; as the point at its centre otherwise.
        #[cfg(feature = "area-lights")]
        PreparedLight::Sphere {
            position, power, ..
        } => incoming(&PreparedLight::Point { position, power }, p),
        PreparedLight::Point { position, power } => {
            let (one, zero) = (T::splat(1.0), T::splat(0.0));
            let lv = Vec3::splat(position) - p;
            let d2 = lv.dot(lv);
            let dist = d2.sqrt();
            let reached = zero.lt(d2);
            let to_light = lv * T::select(reached, one / dist, zero);
            // 1/d² overflows to inf when d² is subnormal (the light within ~1e-19 of P,
            // reachable with a tiny field of view): saturate it at f32::MAX, or a black
            // channel of the light's colour would give 0·inf = NaN.
            let inv_d2 = (one / d2).min(T::splat(f32::MAX));
            let atten = T::select(reached, inv_d2, T::splat(MAX_ARRIVING));
            let cap = T::splat(MAX_ARRIVING);
            let arriving = Vec3::splat(power) * atten;
            Incoming {
                to_light,
                arriving: Vec3::new(
                    arriving.x.min(cap),
                    arriving.y.min(cap),
                    arriving.z.min(cap),
                ),
                t_max: Some(dist),
            }
        }
    }
}

/// `diffuse`: adds `vis·I·term` to the sum, `term` being [`brdf::Terms::diffuse`] and `lit`
/// 1 on visible lanes, 0 elsewhere.
#[inline(always)]
pub(super) fn diffuse<T: Lane>(sum: Vec3<T>, light: &Incoming<T>, term: T, lit: T) -> Vec3<T> {
    sum + light.arriving * (term * lit)
}

/// `specular`: adds `vis·I ⊙ term` to the sum, `term` being [`brdf::Terms::specular`]. Without
/// a normalized material in the packet the lobe is the same in every channel.
#[inline(always)]
pub(super) fn specular<T: Lane, const NORMALIZED: bool>(
    sum: Vec3<T>,
    light: &Incoming<T>,
    term: Vec3<T>,
    lit: T,
) -> Vec3<T> {
    let arriving = light.arriving;
    if NORMALIZED {
        sum + Vec3::new(
            arriving.x * (term.x * lit),
            arriving.y * (term.y * lit),
            arriving.z * (term.z * lit),
        )
    } else {
        sum + arriving * (term.x * lit)
    }
}
