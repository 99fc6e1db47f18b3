//! The per-pixel stages of the float paths, written once over [`Lane`]: the scalar path runs
//! them on `f32`, the SIMD paths on `f32x4`/`f32x8`, one packet of consecutive pixels per call.
//! The fixed kernel (`src/fixed/kernel.rs`) has the same stages under the same names, in the
//! same order. This is the general kernel: frames of classic spheres under distant lights
//! take the narrow kernel instead ([`super::narrow`]), which shades from per-row quadrics
//! and calls into this one only for shadow rays toward other spheres and for outlines.
//!
//! | stage | what it computes | file |
//! |---|---|---|
//! | `shade` | the whole packet: the stages below, in this order | `kernel` |
//! | `ray` | the primary ray through each pixel centre | `kernel` |
//! | `hit` | the nearest sphere hit with `t > ε` among the packet's candidate spheres, and its material | `kernel` (the ray–sphere test: `intersect`) |
//! | `normal` | `N = (P − C)·(1/r)`: no square root | `kernel` |
//! | `lights` | the loop over every light, accumulating the diffuse and specular sums | `light_loop` |
//! | `incoming` | per light: direction `L` toward it, arriving colour `I`, shadow-ray length | `light_loop` |
//! | `shadow` | per light: a ray from `P + ε·N` toward the light, tested against each sphere that can shadow the hit sphere | `light_loop` (the ray–sphere test: `intersect`) |
//! | `diffuse` | per light: `Σ vis·I·max(0, N·L)` | `light_loop` |
//! | `specular` | per light: `Σ vis·I·max(0, c)^n`, `c = R·V` (Phong) or `N·H` (Blinn-Phong) | `light_loop` |
//! | `combine` | `kd·albedo·diffuse + ks·specular`, saturated at `f32::MAX`; the background on misses | `kernel` |
//!
//! The files follow what a stage works on: this one holds the stages that run once per
//! packet (`shade`, the surface's `ray`, `hit` and `normal`, and `combine`),
//! [`super::light_loop`] those that run once per light, `sphere_light` a sphere light's own
//! `incoming` and `shadow`, and [`super::intersect`] the ray–sphere tests that `hit`,
//! `shadow`, the narrow kernel and the `edges` stage share.
//!
//! A sphere light (a point light with a radius, crate feature `area-lights`) has its own
//! `incoming` (`sphere_incoming`: the representative point's direction for the lobes, the
//! sphere's diffuse cosine) and `shadow` (`soft_shadow`: the share of the light's cap left
//! uncovered, analytic, no shadow rays), both in `sphere_light`, then the same `diffuse` and
//! `specular` with [`brdf::terms_with`]; see `area` for the formulas and their errors. A point light of
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
//! Every stage is `#[inline(always)]`: the split into functions and files is for the reader,
//! and the compiler sees the packet loop as one function. The one exception is the second and
//! third shadings of anti-aliased edges (`shade_filtered` in `float::edges`, with
//! `antialias`): out of line and cold, so that the kernel holds one copy of itself, not three.

use super::intersect::{nearest_hit, Filter};
use super::lane::Lane;
use super::light_loop::Surface;
use super::prepare::{FloatPath, Prepared, Row};
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
            id: hit.id,
        }
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
