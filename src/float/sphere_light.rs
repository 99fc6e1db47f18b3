//! A sphere light's own stages in the general float kernel (crate feature `area-lights`):
//! its `incoming` (`sphere_incoming`: the representative point's direction for the lobes,
//! the sphere's diffuse cosine, the cap's constants) and its `shadow` (`soft_shadow`: the
//! share of the light's cap the other spheres leave uncovered, analytic, no shadow rays),
//! followed by the `diffuse` and `specular` of [`super::light_loop`] with
//! [`brdf::terms_with`].
//!
//! The closed forms and their errors are in [`super::area`]; this file applies them to a
//! packet's surface points. It stands apart from the light loop because only frames with a
//! sphere light run it: `lights` calls `sphere_light` only when its `SPHERES` parameter is
//! set, so the kernel of every other frame holds none of this code.

use super::area;
use super::lane::Lane;
use super::light_loop::{diffuse, specular, Incoming, Surface};
use super::prepare::{FloatPath, Prepared, MAX_ARRIVING};
use crate::brdf::{self, Masks, Params, Present};
use crate::real::Real;
use crate::vec3::Vec3;

impl<W: FloatPath, const S: usize, const L: usize> Prepared<W, S, L> {
    /// One sphere light's part of [`Prepared::lights`] (the light at `position`, of `power`
    /// and `radius`): `sphere_incoming`, `soft_shadow`, then `diffuse` and `specular` added
    /// to the sums, weighted by the visible share of the light. Lanes that see none of it get
    /// the light's shadow bit in `shadowed` if `record_hits`.
    #[inline(always)]
    pub(super) fn sphere_light<const NORMALIZED: bool>(
        &self,
        (light_index, position, power, radius): (usize, Vec3, Vec3, f32),
        surface: &Surface<W::Lane>,
        (params, masks, present): (&Params<W::Lane>, &Masks<W::Lane>, Present),
        (record_hits, shadowed): (bool, &mut [u32; 8]),
        (diffuse_sum, specular_sum): (Vec3<W::Lane>, Vec3<W::Lane>),
    ) -> (Vec3<W::Lane>, Vec3<W::Lane>) {
        let zero = W::Lane::splat(0.0);
        let sphere = sphere_incoming(position, power, radius, surface);
        let (diffuse_vis, specular_vis) = self.soft_shadow(surface, &sphere);
        let seen = W::Lane::and(surface.any_hit, zero.lt(specular_vis));
        if record_hits && light_index < 32 {
            let bits = W::Lane::bitmask(W::Lane::and_not(surface.any_hit, seen));
            for (lane, word) in shadowed.iter_mut().enumerate() {
                *word |= ((bits >> lane) & 1) << light_index;
            }
        }
        if !W::Lane::any(seen) {
            return (diffuse_sum, specular_sum);
        }
        let (n, view) = (surface.n, surface.view);
        let area = brdf::Area {
            diffuse_cos: sphere.diffuse_cos,
            spread: sphere.sin_a,
        };
        let t = brdf::terms_with(
            params,
            masks,
            present,
            n,
            sphere.light.to_light,
            view,
            Some(area),
        );
        let diffuse_lit = W::Lane::select(seen, diffuse_vis, zero);
        let specular_lit = W::Lane::select(seen, specular_vis, zero);
        (
            diffuse(diffuse_sum, &sphere.light, t.diffuse, diffuse_lit),
            specular::<_, NORMALIZED>(specular_sum, &sphere.light, t.specular, specular_lit),
        )
    }

    /// `shadow` for a sphere light: the share of the light's cap the other spheres leave
    /// uncovered, as seen from `P + ε·N` (the product over every sphere nearer than the
    /// light's centre of `1 −` its [`area::covered`] share; a point inside a sphere sees
    /// none of the light), and that times the share above the horizon
    /// ([`area::above_horizon`]): `(diffuse, specular)` visibility. The lane's own sphere
    /// is the horizon and is left out of the product. Every sphere is tested: the casters
    /// of `Scene::shadow_casters` are for point lights.
    #[inline(always)]
    fn soft_shadow(
        &self,
        surface: &Surface<W::Lane>,
        light: &SphereIncoming<W::Lane>,
    ) -> (W::Lane, W::Lane) {
        let (zero, one) = (W::Lane::splat(0.0), W::Lane::splat(1.0));
        let horizon = area::above_horizon(light.cos_axis, light.sin_a);
        let mut visible = one;
        for (k, s) in self.spheres.iter().enumerate() {
            let kf = W::Lane::splat(k as f32);
            let own = W::Lane::and(surface.id.le(kf), kf.le(surface.id));
            let to_center = Vec3::splat(s.center) - surface.shadow_origin;
            let d2 = to_center.dot(to_center);
            let r2 = W::Lane::splat(s.radius_sq);
            let inside = d2.le(r2);
            let nearer = d2.lt(light.dist2);
            let axis = to_center * (one / d2.sqrt());
            let rho = area::chord(r2 / d2);
            let gap = axis - light.axis;
            let delta = gap.dot(gap).sqrt();
            let overlaps = W::Lane::or(inside, W::Lane::and(nearer, delta.lt(light.rho + rho)));
            let counts = W::Lane::and_not(W::Lane::and(surface.any_hit, overlaps), own);
            // A sphere whose cap misses every lane's light cap leaves `visible` unchanged.
            if !W::Lane::any(counts) {
                continue;
            }
            let share = area::covered(light.rho, rho, delta);
            let share = W::Lane::select(inside, one, share);
            visible = W::Lane::select(counts, visible * (one - share), visible);
            if !W::Lane::any(W::Lane::and(surface.any_hit, zero.lt(visible * horizon))) {
                break;
            }
        }
        (visible, visible * horizon)
    }
}

/// A sphere light as seen from a packet's surface points (see `area`).
struct SphereIncoming<T> {
    /// The representative point's direction as `to_light`, the colour arriving from the
    /// centre, no `t_max` (the soft shadow has its own test).
    light: Incoming<T>,
    /// Unit vector toward the centre, `A`.
    axis: Vec3<T>,
    /// Squared distance from `P` to the centre.
    dist2: T,
    /// `sin α = R/d`.
    sin_a: T,
    /// The chord of the light's cap, `2 sin(α/2)`: its radius in the equal-area projection.
    rho: T,
    /// `N·A`.
    cos_axis: T,
    /// The diffuse cosine, [`area::horizon_cosine`].
    diffuse_cos: T,
}

/// `incoming` for a sphere light of radius `radius` at `position` with `power`: the
/// direction to the representative point, the point of the light's sphere closest to the
/// reflected view ray `2(N·V)N − V` (the centre moved toward the ray by up to `R`,
/// Karis 2013), and the cap's constants. The light is clear of every scene sphere
/// (validated), so `d > R > 0`.
#[inline(always)]
fn sphere_incoming<T: Lane>(
    position: Vec3,
    power: Vec3,
    radius: f32,
    surface: &Surface<T>,
) -> SphereIncoming<T> {
    let (zero, one) = (T::splat(0.0), T::splat(1.0));
    let (n, view) = (surface.n, surface.view);
    let lv = Vec3::splat(position) - surface.p;
    let dist2 = lv.dot(lv);
    let axis = lv * (one / dist2.sqrt());
    let r2 = T::splat(radius * radius);
    let sin2 = one.min(r2 / dist2);
    let sin_a = sin2.sqrt();
    let cos_axis = n.dot(axis);
    let reflected = n * (T::splat(2.0) * n.dot(view)) - view;
    let to_ray = reflected * lv.dot(reflected) - lv;
    let to_ray2 = to_ray.dot(to_ray);
    let scale = T::select(r2.lt(to_ray2), T::splat(radius) / to_ray2.sqrt(), one);
    let rep = lv + to_ray * scale;
    let rep2 = rep.dot(rep);
    let to_light = rep * T::select(zero.lt(rep2), one / rep2.sqrt(), zero);
    let cap = T::splat(MAX_ARRIVING);
    let arriving = Vec3::splat(power) * (one / dist2);
    SphereIncoming {
        light: Incoming {
            to_light,
            arriving: Vec3::new(
                arriving.x.min(cap),
                arriving.y.min(cap),
                arriving.z.min(cap),
            ),
            t_max: None,
        },
        axis,
        dist2,
        sin_a,
        rho: area::chord(sin2),
        cos_axis,
        diffuse_cos: area::horizon_cosine(cos_axis, sin_a),
    }
}
