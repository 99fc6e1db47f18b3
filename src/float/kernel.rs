//! The per-pixel stages of the float paths, written once over [`Lane`]: the scalar path runs
//! them on `f32`, the SIMD paths on `f32x4`/`f32x8`, one packet of consecutive pixels per call.
//! The fixed kernel (`src/fixed/kernel.rs`) has the same stages under the same names, in the
//! same order. This is the general kernel: frames of classic spheres under distant lights
//! take the narrow kernel instead ([`super::narrow`]), which shades from per-row quadrics
//! and calls into this one only for shadow rays toward other spheres and for outlines.
//!
//! | stage | what it computes |
//! |---|---|
//! | `shade` | the whole packet: the stages below, in this order |
//! | `ray` | the primary ray through each pixel centre |
//! | `hit` | the nearest sphere hit with `t > ε` among the packet's candidate spheres, and its material |
//! | `normal` | `N = (P − C)·(1/r)`: no square root |
//! | `lights` | the loop over every light, accumulating the diffuse and specular sums |
//! | `incoming` | per light: direction `L` toward it, arriving colour `I`, shadow-ray length |
//! | `shadow` | per light: a ray from `P + ε·N` toward the light, tested against each sphere that can shadow the hit sphere |
//! | `diffuse` | per light: `Σ vis·I·max(0, N·L)` |
//! | `specular` | per light: `Σ vis·I·max(0, c)^n`, `c = R·V` (Phong) or `N·H` (Blinn-Phong) |
//! | `combine` | `kd·albedo·diffuse + ks·specular`, saturated at `f32::MAX`; the background on misses |
//!
//! A sphere light (a point light with a radius, crate feature `area-lights`) has its own
//! `incoming` (`sphere_incoming`: the representative point's direction for the lobes, the
//! sphere's diffuse cosine) and `shadow` (`soft_shadow`: the share of the light's cap left
//! uncovered, analytic, no shadow rays), then the same `diffuse` and `specular` with
//! [`brdf::terms_with`]; see `area` for the formulas and their errors. A point light of
//! radius 0 is a `Point` light and takes exactly the stages above.
//!
//! (`diffuse` and `specular` accumulate [`brdf::terms`]: for the normalized models the diffuse
//! term carries `1 − F` and the specular term `max(0, N·L)·F·Σ wₖ·cₖ·max(0, c)^nₖ`, with
//! `kd·albedo/π` and `ks = 1` applied in `combine`; see [`crate::brdf`].) Quantizing the
//! result to a pixel format is the row driver's `encode` step, not a kernel stage.
//!
//! Decisions are lane masks, never per-lane branches, so a lane's result depends only on its
//! own pixel: which pixels share a packet, and how wide the packet is, cannot change any bit.
//! The only branches are on whole packets (skip a sphere's shadow test, skip lighting when no
//! lane hit) and those skip work whose result would be discarded. The normalized models'
//! extra work (their constants, more lobes, Fresnel) is such a branch too: a packet in which
//! no lane shows a normalized material does the classic models' arithmetic alone. On the
//! scalar paths, a frame with no normalized material at all (one the narrow kernel does not
//! take: point lights, a highlight past its cap, the camera inside a sphere) is shaded by a
//! second copy of the kernel that holds none of that code (`shade::<false>`, chosen once per
//! row): smaller, with more of its values in registers. Classic frames
//! shaded so take fewer instructions on a Cortex-M4F and on x86-64, for more flash per
//! scalar path a firmware renders. The SIMD paths keep one kernel, which serves them better
//! (the figures: `docs/performance.md, "Choices measured"`).
//!
//! Every stage is `#[inline(always)]`: the split into functions is for the reader, and the
//! compiler sees the packet loop as one function. The one exception is the second and third
//! shadings of anti-aliased edges (`shade_filtered` in `float::edges`, with `antialias`): out
//! of line and cold, so that the kernel holds one copy of itself, not three.

#[cfg(feature = "area-lights")]
use super::area;
use super::lane::Lane;
use super::prepare::{FloatPath, Prepared, PreparedLight, Row, MAX_ARRIVING};
use crate::brdf::{self, Params, Present};
use crate::real::Real;
use crate::vec3::Vec3;

/// A shaded packet: colour and hit record per lane.
pub(crate) struct Packet<L: Lane> {
    pub color: Vec3<L>,
    /// Index of the sphere hit, as `f32`; `-1` on a miss.
    pub sphere: L,
    /// Per lane (up to 8), bit `k` set if light `k` is blocked. Filled only when asked.
    pub shadowed: [u32; 8],
}

/// What `hit` found, per lane: the nearest `t`, the sphere, and its classic material
/// constants.
struct Hit<T: Lane> {
    /// Distance along the ray; `f32::MAX` on a miss.
    t: T,
    /// Index of the sphere hit, as `f32`; `-1` on a miss.
    id: T,
    /// The hit point relative to the sphere's centre (see [`nearest_hit`]).
    offset: Vec3<T>,
    /// `1/r` of the sphere hit.
    inv_r: T,
    /// `kd·albedo`, `ks`, exponent and Blinn flag of the sphere hit ([`NO_MATERIAL`]'s on a
    /// miss).
    kd_albedo: Vec3<T>,
    ks: T,
    shininess: T,
    blinn: T,
    /// Which optional parts of the models the packet shows (so far: `normalized`).
    present: Present,
    /// Bit `k`: some lane's nearest-so-far hit was sphere `k` (`k < 32`); a superset of the
    /// spheres the lanes finally hit.
    spheres: u32,
}

/// A packet's surface points: what the lighting stages read.
#[derive(Clone, Copy)]
struct Surface<T: Lane> {
    /// The hit point `eye + t·d`.
    p: Vec3<T>,
    /// The unit normal.
    n: Vec3<T>,
    /// Unit vector toward the eye, `−d`.
    view: Vec3<T>,
    /// `P + ε·N`, where shadow rays start.
    shadow_origin: Vec3<T>,
    /// Lanes that hit a sphere.
    any_hit: T::Mask,
    /// The spheres some lane hit (`Hit::spheres`).
    hit_spheres: u32,
    /// The sphere each lane hit, as `f32` (`-1` on a miss): a sphere light's soft shadow
    /// leaves it out (its own sphere is the horizon).
    #[cfg(feature = "area-lights")]
    id: T,
}

/// One light as seen from a packet's surface points.
struct Incoming<T> {
    /// Unit vector toward the light (zero where the point is at the light).
    to_light: Vec3<T>,
    /// Arriving colour `I`.
    arriving: Vec3<T>,
    /// Length of the shadow ray: the distance to a point light; `None` for a distant one,
    /// whose shadow rays have no end.
    t_max: Option<T>,
}

impl<W: FloatPath, const S: usize, const L: usize> Prepared<W, S, L> {
    /// `shade`: the packet of pixels `x0, x0 + 1, …` on the row `row`, testing primary rays
    /// against the spheres listed in `candidates` (in scene order). Shadow bits are recorded
    /// only if `record_hits`. With anti-aliasing on, lanes an outline crosses are then
    /// blended with a second shading (`edges`). Colours are saturated at `f32::MAX` (see
    /// [`combine`]) if `saturate`, or where anti-aliasing blends them; otherwise a channel
    /// may be `+∞`, which is for callers that clamp it anyway (quantizing to levels).
    ///
    /// `NORMALIZED`: whether the frame has a normalized material. Without one, the kernel
    /// holds only the classic models' code.
    #[inline(always)]
    pub(crate) fn shade<const NORMALIZED: bool>(
        &self,
        row: &Row,
        x0: u32,
        candidates: &[u16],
        record_hits: bool,
        saturate: bool,
    ) -> Packet<W::Lane> {
        let (u, d) = self.ray(row, x0);
        #[cfg(feature = "antialias")]
        let saturate = saturate || self.antialias;
        let (packet, t) =
            self.shade_along::<NORMALIZED>(d, candidates, None, record_hits, saturate);
        #[cfg(feature = "antialias")]
        let packet = self.antialiased(packet, row, u, d, t, candidates);
        #[cfg(not(feature = "antialias"))]
        let _ = (u, t);
        packet
    }

    /// The stages from `hit` on, along the unit directions `d`; also returns the hit
    /// distance per lane (`f32::MAX` on a miss). `filter`, for the second shading of
    /// anti-aliased edges, limits each lane to some spheres (see [`Filter`]). `saturate`: see
    /// [`combine`]. `NORMALIZED`: see [`Self::shade`]; the edges' shadings always pass
    /// `true`, as they run rarely and serve every frame.
    #[inline(always)]
    pub(crate) fn shade_along<const NORMALIZED: bool>(
        &self,
        d: Vec3<W::Lane>,
        candidates: &[u16],
        filter: Option<Filter<W::Lane>>,
        record_hits: bool,
        saturate: bool,
    ) -> (Packet<W::Lane>, W::Lane) {
        let mut hit = self.hit(d, candidates, filter);
        if filter.is_some() {
            // An edge's shading takes a lane whose ray misses the edge's sphere at the ray's
            // closest approach, off the sphere: by rounding, or by far where a pixel is large
            // against the sphere and the first-order step toward the outline overshoots. The
            // casters of `Scene::shadow_casters` hold for points on the sphere only, so these
            // shadow rays test every sphere.
            hit.spheres = u32::MAX;
        }
        let bg = self.background;
        let background = Vec3::splat(Vec3::new(bg.r, bg.g, bg.b));
        let any_hit = W::Lane::splat(0.0).le(hit.id);
        let mut packet = Packet {
            color: background,
            sphere: hit.id,
            shadowed: [0; 8],
        };
        if !W::Lane::any(any_hit) {
            return (packet, hit.t);
        }
        let surface = self.normal(d, &hit, any_hit);
        let mut params = Params {
            kd_albedo: hit.kd_albedo,
            ks: hit.ks,
            shininess: hit.shininess,
            blinn: hit.blinn,
            ..Params::splat(&NO_MATERIAL)
        };
        let mut present = hit.present;
        present.normalized &= NORMALIZED;
        if present.normalized {
            self.normalized_constants(candidates, hit.id, &mut params, &mut present);
        }
        let shadowed = &mut packet.shadowed;
        let (diffuse, specular) = if present.normalized {
            self.lights_of::<true>(&surface, &params, present, record_hits, shadowed)
        } else {
            self.lights_of::<false>(&surface, &params, present, record_hits, shadowed)
        };
        packet.color = combine(&params, diffuse, specular, any_hit, background, saturate);
        (packet, hit.t)
    }

    /// `ray`: the direction through each pixel centre, `u = x·right + row.base` with
    /// `x = (2(i + ½)/w − 1)·(w/h)·tan(vfov/2)`, and the unit `d = normalize(u)`.
    #[inline(always)]
    pub(super) fn ray(&self, row: &Row, x0: u32) -> (Vec3<W::Lane>, Vec3<W::Lane>) {
        let one = W::Lane::splat(1.0);
        let i = W::Lane::ramp(x0 as f32 + 0.5);
        let xc = ((i * W::Lane::splat(2.0)) / W::Lane::splat(self.width_f) - one)
            * W::Lane::splat(self.x_scale);
        let u = Vec3::splat(self.right) * xc + Vec3::splat(row.base);
        (u, u * (one / u.dot(u).sqrt()))
    }

    /// `hit`: the nearest `t > ε` among the `candidates` along `d`, with the hit sphere's
    /// material per lane. Closest-approach form of the quadratic (see [`nearest_hit`]).
    #[inline(always)]
    fn hit(
        &self,
        d: Vec3<W::Lane>,
        candidates: &[u16],
        filter: Option<Filter<W::Lane>>,
    ) -> Hit<W::Lane> {
        let eps = W::Lane::splat(self.epsilon);
        let zero = W::Lane::splat(0.0);
        let mut best = Hit {
            t: W::Lane::splat(f32::MAX),
            id: W::Lane::splat(-1.0),
            offset: Vec3::splat(Vec3::default()),
            inv_r: zero,
            kd_albedo: Vec3::splat(Vec3::default()),
            ks: zero,
            shininess: W::Lane::splat(1.0),
            blinn: zero,
            present: Present::default(),
            spheres: 0,
        };
        for &k in candidates {
            // Candidates come from the row's spans, one per sphere: always a sphere.
            debug_assert!((k as usize) < self.spheres.len(), "candidate {k}");
            let Some(s) = self.spheres.get(k as usize) else {
                continue;
            };
            let oc = Vec3::splat(s.eye_offset);
            let radius_sq = W::Lane::splat(s.radius_sq);
            let (t, hit, offset) = match filter {
                None => nearest_hit(oc, d, radius_sq, eps),
                Some(filter) => filter.nearest_hit(k, oc, d, radius_sq, eps),
            };
            let hit = W::Lane::and(hit, t.lt(best.t));
            if !W::Lane::any(hit) {
                continue;
            }
            // Spheres from 32 on are in no mask: their shadow test is never skipped.
            best.spheres |= 1u32.checked_shl(k as u32).unwrap_or(0);
            best.t = W::Lane::select(hit, t, best.t);
            best.id = W::Lane::select(hit, W::Lane::splat(k as f32), best.id);
            best.offset = Vec3::select(hit, offset, best.offset);
            best.inv_r = W::Lane::select(hit, W::Lane::splat(s.inv_radius), best.inv_r);
            let m = &s.params;
            best.kd_albedo = Vec3::select(hit, Vec3::splat(m.kd_albedo), best.kd_albedo);
            best.ks = W::Lane::select(hit, W::Lane::splat(m.ks), best.ks);
            best.shininess = W::Lane::select(hit, W::Lane::splat(m.shininess), best.shininess);
            best.blinn = W::Lane::select(hit, W::Lane::splat(m.blinn), best.blinn);
            // Conservative: a nearer sphere may still take these lanes.
            best.present.normalized |= s.normalized;
        }
        best
    }

    /// The rest of `hit`'s material, only in packets that show a normalized model: the
    /// normalized models' constants, lane by lane from the sphere each lane hit (`id`).
    #[inline(always)]
    fn normalized_constants(
        &self,
        candidates: &[u16],
        id: W::Lane,
        params: &mut Params<W::Lane>,
        present: &mut Present,
    ) {
        for &k in candidates {
            // Candidates come from the row's spans, one per sphere: always a sphere.
            debug_assert!((k as usize) < self.spheres.len(), "candidate {k}");
            let Some(s) = self.spheres.get(k as usize) else {
                continue;
            };
            let kf = W::Lane::splat(k as f32);
            let here = W::Lane::and(id.le(kf), kf.le(id));
            if s.normalized && W::Lane::any(here) {
                Params::select_normalized(here, &Params::splat(&s.params), params);
                present.schlick |= s.schlick;
                present.more_lobes |= s.more_lobes;
                #[cfg(feature = "models")]
                {
                    present.oren_nayar |= s.oren_nayar;
                    present.ggx |= s.ggx;
                }
            }
        }
    }

    /// `normal`: `N = (P − C)/r`, with `P − C` from the hit test (see [`nearest_hit`]),
    /// normalized once more; the hit point itself, for shadow rays and point lights, is
    /// `eye + t·d`.
    #[inline(always)]
    fn normal(
        &self,
        d: Vec3<W::Lane>,
        hit: &Hit<W::Lane>,
        any_hit: <W::Lane as Real>::Mask,
    ) -> Surface<W::Lane> {
        let one = W::Lane::splat(1.0);
        let p = Vec3::splat(self.eye) + d * hit.t;
        let n = hit.offset * hit.inv_r;
        let n = n * (one / n.dot(n).sqrt());
        Surface {
            p,
            n,
            view: -d,
            shadow_origin: p + n * W::Lane::splat(self.epsilon),
            any_hit,
            hit_spheres: hit.spheres,
            #[cfg(feature = "area-lights")]
            id: hit.id,
        }
    }

    /// [`Self::lights`] with its sphere-light branch only in frames that have a sphere
    /// light: in the light loop of every frame, that branch costs a frame without sphere
    /// lights more than dispatched here, once per packet (`docs/performance.md, "Choices measured"`).
    #[inline(always)]
    fn lights_of<const NORMALIZED: bool>(
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
                    continue;
                }
                let (n, view) = (surface.n, surface.view);
                let area = brdf::Area {
                    diffuse_cos: sphere.diffuse_cos,
                    spread: sphere.sin_a,
                };
                let t = brdf::terms_with(
                    params,
                    &masks,
                    present,
                    n,
                    sphere.light.to_light,
                    view,
                    Some(area),
                );
                let diffuse_lit = W::Lane::select(seen, diffuse_vis, zero);
                let specular_lit = W::Lane::select(seen, specular_vis, zero);
                diffuse_sum = diffuse(diffuse_sum, &sphere.light, t.diffuse, diffuse_lit);
                specular_sum = specular::<_, NORMALIZED>(
                    specular_sum,
                    &sphere.light,
                    t.specular,
                    specular_lit,
                );
                continue;
            }
            let light = incoming(light, surface.p);
            let blocked = self.shadow(
                surface,
                &light,
                self.casters_of(surface.hit_spheres, light_index),
            );
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

    /// `shadow` for a sphere light: the share of the light's cap the other spheres leave
    /// uncovered, as seen from `P + ε·N` (the product over every sphere nearer than the
    /// light's centre of `1 −` its [`area::covered`] share; a point inside a sphere sees
    /// none of the light), and that times the share above the horizon
    /// ([`area::above_horizon`]): `(diffuse, specular)` visibility. The lane's own sphere
    /// is the horizon and is left out of the product. Every sphere is tested: the casters
    /// of `Scene::shadow_casters` are for point lights.
    #[cfg(feature = "area-lights")]
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
#[cfg(feature = "area-lights")]
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
#[cfg(feature = "area-lights")]
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
fn diffuse<T: Lane>(sum: Vec3<T>, light: &Incoming<T>, term: T, lit: T) -> Vec3<T> {
    sum + light.arriving * (term * lit)
}

/// `specular`: adds `vis·I ⊙ term` to the sum, `term` being [`brdf::Terms::specular`]. Without
/// a normalized material in the packet the lobe is the same in every channel.
#[inline(always)]
fn specular<T: Lane, const NORMALIZED: bool>(
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

/// `combine`: `kd·albedo ⊙ diffuse + ks·specular` on lanes that hit, the background elsewhere.
///
/// `kd·albedo` (up to 1e12) times arriving light (up to 1e30 per light) can exceed
/// `f32::MAX`: with `saturate`, the sum saturates there, so the output is finite. Every term
/// is ≥ 0 and finite, so the sum is never NaN, and `min` leaves every finite value's bits
/// unchanged. Without `saturate` an overflowing channel is `+∞`: the row driver asks for
/// that only when it quantizes the colour to levels, where `clamp(+∞, 0, 1)` and
/// `clamp(f32::MAX, 0, 1)` are both 1, so the stored pixel is the same and the three
/// compare-and-selects per pixel are saved.
#[inline(always)]
fn combine<T: Lane>(
    params: &Params<T>,
    diffuse: Vec3<T>,
    specular: Vec3<T>,
    any_hit: T::Mask,
    background: Vec3<T>,
    saturate: bool,
) -> Vec3<T> {
    combine_with(
        (params.kd_albedo, params.ks),
        (diffuse, specular),
        any_hit,
        background,
        saturate,
    )
}

/// [`combine`] from the two constants it reads, `kd·albedo` and `ks`: the narrow kernel's
/// `combine` too.
#[inline(always)]
pub(super) fn combine_with<T: Lane>(
    (kd_albedo, ks): (Vec3<T>, T),
    (diffuse, specular): (Vec3<T>, Vec3<T>),
    any_hit: T::Mask,
    background: Vec3<T>,
    saturate: bool,
) -> Vec3<T> {
    let shaded = Vec3::new(
        kd_albedo.x * diffuse.x,
        kd_albedo.y * diffuse.y,
        kd_albedo.z * diffuse.z,
    ) + specular * ks;
    let shaded = if saturate {
        let cap = T::splat(f32::MAX);
        Vec3::new(shaded.x.min(cap), shaded.y.min(cap), shaded.z.min(cap))
    } else {
        shaded
    };
    Vec3::select(any_hit, shaded, background)
}

/// The constants of lanes that hit nothing: no light is reflected (`kd·albedo = 0`,
/// `ks = 0`), exponent 1, classic.
const NO_MATERIAL: Params<f32> = Params {
    kd_albedo: Vec3::new(0.0, 0.0, 0.0),
    ks: 0.0,
    shininess: 1.0,
    blinn: 0.0,
    normalized: 0.0,
    weight: [0.0; brdf::LOBES],
    more_shininess: [1.0; crate::scene::MORE_LOBES],
    f0: Vec3::new(1.0, 1.0, 1.0),
    schlick: 0.0,
    diffuse_loss: 0.0,
    #[cfg(feature = "models")]
    oren_nayar: 0.0,
    #[cfg(feature = "models")]
    on_a: 1.0,
    #[cfg(feature = "models")]
    on_b: 0.0,
    #[cfg(feature = "models")]
    ggx: 0.0,
    #[cfg(feature = "models")]
    alpha2: 1.0,
};

/// Which spheres an edge's extra shading may hit, per lane: the edge's sphere alone
/// (`only` lanes, where the centre ray misses it), or every candidate but the edge's sphere
/// and `also` (an edge in front of it, already accounted for).
// Built only by the `edges` stage.
#[cfg_attr(not(feature = "antialias"), allow(dead_code))]
#[derive(Clone, Copy)]
pub(crate) struct Filter<T: Lane> {
    /// The edge's sphere, as `f32`; `-1` on lanes with no edge.
    pub sphere: T,
    /// A sphere the lanes that are not `only` leave out as well; `-1`: none.
    pub also: T,
    /// Lanes that shade the edge's sphere alone.
    pub only: T::Mask,
}

#[cfg_attr(not(feature = "antialias"), allow(dead_code))]
impl<T: Lane> Filter<T> {
    /// [`nearest_hit`] for candidate sphere `k` under the filter: lanes that may not hit `k`
    /// miss it, and `only` lanes hit it even where rounding puts their ray just outside it,
    /// at the closest approach (the outline itself).
    #[inline(always)]
    pub(crate) fn nearest_hit(
        &self,
        k: u16,
        oc: Vec3<T>,
        dir: Vec3<T>,
        radius_sq: T,
        eps: T,
    ) -> (T, T::Mask, Vec3<T>) {
        let (zero, one) = (T::splat(0.0), T::splat(1.0));
        let kf = T::splat(k as f32);
        let is = |v: T| T::and(v.le(kf), kf.le(v));
        let is_k = is(self.sphere);
        let forced = T::and(self.only, is_k);
        // The closest-approach form of `nearest_hit`, with no early exit.
        let b = oc.dot(dir);
        let f = oc - dir * b;
        let disc = radius_sq - f.dot(f);
        let touches = zero.le(disc);
        let (t, offset) = nearer_root(b, f, disc, dir, eps);
        let left_out = T::or(is_k, is(self.also));
        let allowed = T::select(
            self.only,
            T::select(is_k, one, zero),
            T::select(left_out, zero, one),
        );
        let meets = T::and(T::or(touches, forced), eps.lt(t));
        (t, T::and(meets, zero.lt(allowed)), offset)
    }
}

/// Nearest intersection with `t > ε` of the ray `origin + t·dir` (`dir` unit) with the sphere
/// at offset `oc = origin − center`: `(t, hit, offset)`, where `offset` is the hit point
/// relative to the centre.
///
/// The offset is not computed as `origin + t·dir − center`: with the eye ten or more radii
/// away, `t` carries an absolute error of a few `ulp(|oc|)`, and the resulting normal would
/// be off unit length by about `|oc|·2⁻²³/r`, which `max(0, R·V)^n` amplifies `n` times
/// (a 1 % error at `n = 1250`). Instead it is `f ∓ √disc·dir`, from the closest-approach
/// vector `f = oc − (oc·dir)·dir` and `disc = r² − f·f`: its squared length is `f·f + disc
/// = r²` up to one rounding, so the normal is unit length to within a few `f32` ulps.
#[inline(always)]
pub(crate) fn nearest_hit<T: Lane>(
    oc: Vec3<T>,
    dir: Vec3<T>,
    radius_sq: T,
    eps: T,
) -> (T, T::Mask, Vec3<T>) {
    let zero = T::splat(0.0);
    let Some((b, f, disc, touches)) = closest_approach(oc, dir, radius_sq) else {
        // No lane meets the sphere: skip the square root (the mask is all false, so the
        // caller reads neither `t` nor `offset`).
        return (zero, T::lt(zero, zero), oc);
    };
    let (t, offset) = nearer_root(b, f, disc, dir, eps);
    (t, T::and(touches, eps.lt(t)), offset)
}

/// From the closest-approach quantities (`b`, `f`, `disc`, see [`closest_approach`]): the
/// near root `t = −b − √disc` where it lies beyond `eps`, the far one otherwise, and the hit
/// point's offset from the centre, `f ∓ √disc·dir` (see [`nearest_hit`]). A negative `disc`
/// counts as 0: the point of closest approach.
#[inline(always)]
fn nearer_root<T: Lane>(b: T, f: Vec3<T>, disc: T, dir: Vec3<T>, eps: T) -> (T, Vec3<T>) {
    let root = disc.max(T::splat(0.0)).sqrt();
    let t_near = -b - root;
    let near = eps.lt(t_near);
    let t = T::select(near, t_near, -b + root);
    (t, f + dir * T::select(near, -root, root))
}

/// The closest-approach quantities of the ray `origin + t·dir` (`dir` unit) and the sphere at
/// `oc = origin − center`: `b = oc·dir`, `f = oc − b·dir`, `disc = r² − |f|²` and the lanes
/// with `disc ≥ 0`; `None` when no lane has.
#[inline(always)]
fn closest_approach<T: Lane>(
    oc: Vec3<T>,
    dir: Vec3<T>,
    radius_sq: T,
) -> Option<(T, Vec3<T>, T, T::Mask)> {
    let b = oc.dot(dir);
    let f = oc - dir * b;
    let disc = radius_sq - f.dot(f);
    let touches = T::splat(0.0).le(disc);
    T::any(touches).then_some((b, f, disc, touches))
}

/// Whether the ray `origin + t·dir` (`dir` unit, `oc = origin − center`) meets the sphere at
/// some `ε < t < t_max` (`t_max = None`: no end): the shadow test. It decides from the signs
/// and squares of `b = oc·dir`, `disc = r² − |oc − b·dir|²` and the bounds, with no square
/// root, by
///
/// | condition | holds exactly when |
/// |---|---|
/// | `t_near = −b − √disc > ε` | `b + ε < 0` and `disc < (b + ε)²` |
/// | `t_far = −b + √disc > ε` | `b + ε < 0` or `disc > (b + ε)²` |
/// | `t_near < t_max` | `b + t_max > 0` or `disc > (b + t_max)²` |
/// | `t_far < t_max` | `b + t_max > 0` and `disc < (b + t_max)²` |
///
/// and takes, as [`nearest_hit`] does, the near root when it lies beyond `ε` and the far
/// root otherwise. A square that overflows to infinity keeps every line of the table true
/// to its left side. Without `t_max` the last two lines hold for every ray (they do for
/// `t_max = f32::MAX` too, with `b` and `disc` bounded by the scene's coordinates), and the
/// test is `t_far > ε`: the near root's line implies the far root's.
#[inline(always)]
pub(crate) fn meets<T: Lane>(
    oc: Vec3<T>,
    dir: Vec3<T>,
    radius_sq: T,
    eps: T,
    t_max: Option<T>,
) -> T::Mask {
    let zero = T::splat(0.0);
    let Some((b, _, disc, touches)) = closest_approach(oc, dir, radius_sq) else {
        return T::lt(zero, zero);
    };
    let be = b + eps;
    let be2 = be * be;
    let far = T::or(be.lt(zero), be2.lt(disc));
    let Some(t_max) = t_max else {
        return T::and(touches, far);
    };
    let near = T::and(be.lt(zero), disc.lt(be2));
    let bm = b + t_max;
    let bm2 = bm * bm;
    let near_before = T::or(zero.lt(bm), bm2.lt(disc));
    let far_before = T::and(zero.lt(bm), disc.lt(bm2));
    let by_near = T::and(near, near_before);
    let by_far = T::and(T::and_not(far, near), far_before);
    T::and(touches, T::or(by_near, by_far))
}
