//! The per-pixel stages of the float paths, written once over [`Lane`]: the scalar path runs
//! them on `f32`, the SIMD paths on `f32x4`/`f32x8`, one packet of consecutive pixels per call.
//!
//! | stage | what it computes |
//! |---|---|
//! | `ray` | the primary ray through each pixel centre |
//! | `hit` | the nearest sphere hit with `t > ε` among the packet's candidate spheres |
//! | `normal` | `N = (P − C)·(1/r)`: no square root |
//! | `lights` | per light: direction `L` toward it, arriving colour `I` |
//! | `shadow` | a ray from `P + ε·N` toward the light, tested against every sphere |
//! | `diffuse` | `Σ vis·I·max(0, N·L)`, times `kd·albedo` at the end |
//! | `specular` | `Σ vis·I·max(0, c)^n`, `c = R·V` (Phong) or `N·H` (Blinn-Phong), times `ks` |
//!
//! (`diffuse` and `specular` are [`brdf::terms`]: for the normalized models the diffuse term
//! carries `1 − F` and the specular term `max(0, N·L)·F·Σ wₖ·cₖ·max(0, c)^nₖ`, with
//! `kd·albedo/π` and `ks = 1` applied at the end; see [`crate::brdf`].)
//!
//! Misses get the background. Decisions are lane masks, never per-lane branches, so a lane's
//! result depends only on its own pixel: which pixels share a packet, and how wide the packet
//! is, cannot change any bit. The only branches are on whole packets (skip a sphere's shadow
//! test, skip lighting when no lane hit) and those skip work whose result would be discarded.
//! The normalized models' extra work (their constants, more lobes, Fresnel) is such a branch
//! too: a packet in which no lane shows a normalized material does exactly the classic
//! models' arithmetic, as before they existed.

use crate::brdf::{self, Params, Present};
use crate::lane::Lane;
use crate::prepare::{FloatPath, Prepared, PreparedLight, MAX_ARRIVING};
use crate::vec3::Vec3;

/// A shaded packet: colour and hit record per lane.
pub(crate) struct Packet<L: Lane> {
    pub color: Vec3<L>,
    /// Index of the sphere hit, as `f32`; `-1` on a miss.
    pub sphere: L,
    /// Per lane (up to 8), bit `k` set if light `k` is blocked. Filled only when asked.
    pub shadowed: [u32; 8],
}

/// Per-row constants: the camera-plane `y` term of every primary direction on row `j`.
#[derive(Clone, Copy)]
pub(crate) struct Row {
    /// `y_j·up + forward`.
    pub base: Vec3,
}

impl<W: FloatPath, const S: usize, const L: usize> Prepared<W, S, L> {
    /// Camera-plane `y` of row `j`: `(1 − 2(j + ½)/h)·tan(vfov/2)`.
    #[inline]
    pub(crate) fn row(&self, j: u32) -> Row {
        let yc = (1.0 - (2.0 * (j as f32 + 0.5)) / self.height_f) * self.y_scale;
        Row {
            base: self.up.scale(yc) + self.forward,
        }
    }

    /// Shades the packet of pixels `x0, x0 + 1, …` on the row `row`, testing primary rays
    /// against the spheres listed in `candidates` (in scene order).
    #[inline(always)]
    pub(crate) fn shade_packet(
        &self,
        row: &Row,
        x0: u32,
        candidates: &[u16],
        record_hits: bool,
    ) -> Packet<W::Lane> {
        type V<T> = Vec3<T>;
        let one = W::Lane::splat(1.0);
        let zero = W::Lane::splat(0.0);
        let eps = W::Lane::splat(self.epsilon);

        // ray: x = (2(i + ½)/w − 1)·(w/h)·tan(vfov/2); d = normalize(x·right + row.base).
        let i = W::Lane::ramp(x0 as f32 + 0.5);
        let xc = ((i * W::Lane::splat(2.0)) / W::Lane::splat(self.width_f) - one)
            * W::Lane::splat(self.x_scale);
        let d = V::splat(self.right) * xc + V::splat(row.base);
        let d = d * (one / d.dot(d).sqrt());

        // hit: nearest t > ε. Closest-approach form of the quadratic: `f = oc − (oc·d)d`,
        // `disc = r² − f·f`, which keeps precision for small spheres far away.
        let mut t_best = W::Lane::splat(f32::MAX);
        let mut id = W::Lane::splat(-1.0);
        let mut from_center = V::<W::Lane>::splat(Vec3::default());
        let mut inv_r = zero;
        let mut kd_albedo = V::<W::Lane>::splat(Vec3::default());
        let mut ks = zero;
        let mut shininess = one;
        let mut blinn = zero;
        let mut present = Present::default();
        let mut hit_spheres = 0u32;
        for &k in candidates {
            let Some(s) = self.spheres.get(k as usize) else {
                continue;
            };
            let oc = V::splat(s.eye_offset);
            let (t, hit, offset) = nearest_hit(oc, d, W::Lane::splat(s.radius_sq), eps);
            let hit = W::Lane::and(hit, t.lt(t_best));
            if !W::Lane::any(hit) {
                continue;
            }
            // Spheres from 32 on are in no mask: their shadow test is never skipped.
            hit_spheres |= 1u32.checked_shl(k as u32).unwrap_or(0);
            t_best = W::Lane::select(hit, t, t_best);
            id = W::Lane::select(hit, W::Lane::splat(k as f32), id);
            from_center = V::select(hit, offset, from_center);
            inv_r = W::Lane::select(hit, W::Lane::splat(s.inv_radius), inv_r);
            let m = &s.params;
            kd_albedo = V::select(hit, V::splat(m.kd_albedo), kd_albedo);
            ks = W::Lane::select(hit, W::Lane::splat(m.ks), ks);
            shininess = W::Lane::select(hit, W::Lane::splat(m.shininess), shininess);
            blinn = W::Lane::select(hit, W::Lane::splat(m.blinn), blinn);
            // Conservative: a nearer sphere may still take these lanes.
            present.normalized |= s.normalized;
        }
        let background = V::splat(Vec3::new(
            self.background.r,
            self.background.g,
            self.background.b,
        ));
        let any_hit = zero.le(id);
        let mut packet = Packet {
            color: background,
            sphere: id,
            shadowed: [0; 8],
        };
        if !W::Lane::any(any_hit) {
            return packet;
        }

        // normal: N = (P − C)/r, with P − C from the hit test (see `nearest_hit`); the hit
        // point itself, for shadow rays and point lights, is eye + t·d.
        let p = V::splat(self.eye) + d * t_best;
        let n = from_center * inv_r;
        let n = n * (one / n.dot(n).sqrt());
        let view = -d;
        let shadow_origin = p + n * eps;
        let mut params = Params {
            kd_albedo,
            ks,
            shininess,
            blinn,
            ..Params::splat(&NO_MATERIAL)
        };
        if present.normalized {
            // The normalized models' constants, only in packets that show one: lane by lane
            // from the sphere it hit.
            for &k in candidates {
                let Some(s) = self.spheres.get(k as usize) else {
                    continue;
                };
                let kf = W::Lane::splat(k as f32);
                let here = W::Lane::and(id.le(kf), kf.le(id));
                if s.normalized && W::Lane::any(here) {
                    Params::select_normalized(here, &Params::splat(&s.params), &mut params);
                    present.schlick |= s.schlick;
                    present.more_lobes |= s.more_lobes;
                }
            }
        }
        let surface = Surface {
            p,
            n,
            view,
            shadow_origin,
            any_hit,
            hit_spheres,
        };
        let (diffuse, specular) = if present.normalized {
            self.lights::<true>(
                &surface,
                &params,
                present,
                record_hits,
                &mut packet.shadowed,
            )
        } else {
            self.lights::<false>(
                &surface,
                &params,
                present,
                record_hits,
                &mut packet.shadowed,
            )
        };

        let kd_albedo = params.kd_albedo;
        let shaded = V::new(
            kd_albedo.x * diffuse.x,
            kd_albedo.y * diffuse.y,
            kd_albedo.z * diffuse.z,
        ) + specular * params.ks;
        // kd·albedo (up to 1e12) times arriving light (up to 1e30 per light) can exceed
        // f32::MAX: saturate there, so the output is finite. Every term is ≥ 0 and finite,
        // so the sum is never NaN, and `min` leaves every finite value's bits unchanged.
        let cap = W::Lane::splat(f32::MAX);
        let shaded = V::new(shaded.x.min(cap), shaded.y.min(cap), shaded.z.min(cap));
        packet.color = V::select(any_hit, shaded, background);
        packet
    }

    /// The `lights`, `shadow`, `diffuse` and `specular` stages over every light: the sums
    /// `Σ vis·I·diffuse` and `Σ vis·I ⊙ specular`. `NORMALIZED` is whether the packet shows a
    /// normalized material: without one, this is the classic models' arithmetic alone.
    #[inline(always)]
    fn lights<const NORMALIZED: bool>(
        &self,
        surface: &Surface<W::Lane>,
        params: &Params<W::Lane>,
        present: Present,
        record_hits: bool,
        shadowed: &mut [u32; 8],
    ) -> (Vec3<W::Lane>, Vec3<W::Lane>) {
        type V<T> = Vec3<T>;
        let one = W::Lane::splat(1.0);
        let zero = W::Lane::splat(0.0);
        let eps = W::Lane::splat(self.epsilon);
        let Surface {
            p,
            n,
            view,
            shadow_origin,
            any_hit,
            hit_spheres,
        } = *surface;
        let present = Present {
            normalized: NORMALIZED,
            ..present
        };
        let masks = params.masks();

        let mut diffuse = V::<W::Lane>::splat(Vec3::default());
        let mut specular = V::<W::Lane>::splat(Vec3::default());
        for (light_index, light) in self.lights.iter().enumerate() {
            // lights: direction toward the light, arriving colour, shadow-ray length.
            let (to_light, arriving, t_max) = match *light {
                PreparedLight::Distant { to_light, arriving } => (
                    V::splat(to_light),
                    V::splat(arriving),
                    W::Lane::splat(f32::MAX),
                ),
                PreparedLight::Point { position, power } => {
                    let lv = V::splat(position) - p;
                    let d2 = lv.dot(lv);
                    let dist = d2.sqrt();
                    let reached = zero.lt(d2);
                    let to_light = lv * W::Lane::select(reached, one / dist, zero);
                    // 1/d² overflows to inf when d² is subnormal (the light within ~1e-19 of
                    // P, reachable with a tiny field of view): saturate it at f32::MAX, or a
                    // black channel of the light's colour would give 0·inf = NaN.
                    let inv_d2 = (one / d2).min(W::Lane::splat(f32::MAX));
                    let atten = W::Lane::select(reached, inv_d2, W::Lane::splat(MAX_ARRIVING));
                    let cap = W::Lane::splat(MAX_ARRIVING);
                    let arriving = V::splat(power) * atten;
                    let arriving = V::new(
                        arriving.x.min(cap),
                        arriving.y.min(cap),
                        arriving.z.min(cap),
                    );
                    (to_light, arriving, dist)
                }
            };

            // shadow: any sphere between P + ε·N and the light blocks it. Only the spheres
            // some lane hit, and those that can shadow them from this light, are tested.
            let casters = self
                .casters
                .iter()
                .enumerate()
                .fold(hit_spheres, |m, (k, c)| {
                    let hit = hit_spheres & 1u32.checked_shl(k as u32).unwrap_or(0) != 0;
                    match c.get(light_index) {
                        Some(c) if hit => m | c,
                        _ => m,
                    }
                });
            let mut blocked = W::Lane::lt(one, zero);
            for (k, s) in self.spheres.iter().enumerate() {
                if k < 32 && casters & (1 << k) == 0 {
                    continue;
                }
                let oc = shadow_origin - V::splat(s.center);
                let (t, hit, _) = nearest_hit(oc, to_light, W::Lane::splat(s.radius_sq), eps);
                blocked = W::Lane::or(blocked, W::Lane::and(hit, t.lt(t_max)));
                if !W::Lane::any(W::Lane::and_not(any_hit, blocked)) {
                    break;
                }
            }
            let visible = W::Lane::and_not(any_hit, blocked);
            if record_hits && light_index < 32 {
                let bits = W::Lane::bitmask(W::Lane::and(any_hit, blocked));
                for (lane, word) in shadowed.iter_mut().enumerate() {
                    *word |= ((bits >> lane) & 1) << light_index;
                }
            }
            if !W::Lane::any(visible) {
                continue;
            }

            // diffuse and specular, from the brdf module's definitions.
            let t = brdf::terms(params, &masks, present, n, to_light, view);
            let lit = W::Lane::select(visible, one, zero);
            diffuse = diffuse + arriving * (t.diffuse * lit);
            specular = if NORMALIZED {
                let s = t.specular;
                specular
                    + V::new(
                        arriving.x * (s.x * lit),
                        arriving.y * (s.y * lit),
                        arriving.z * (s.z * lit),
                    )
            } else {
                // Classic lanes only: the lobe is the same in every channel.
                specular + arriving * (t.specular.x * lit)
            };
        }

        (diffuse, specular)
    }
}

/// A packet's surface points: what the lighting stages read.
#[derive(Clone, Copy)]
struct Surface<T: Lane> {
    p: Vec3<T>,
    n: Vec3<T>,
    view: Vec3<T>,
    shadow_origin: Vec3<T>,
    any_hit: T::Mask,
    /// Bit `k`: some lane's nearest-so-far hit was sphere `k` (`k < 32`).
    hit_spheres: u32,
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
};

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
    let b = oc.dot(dir);
    let f = oc - dir * b;
    let disc = radius_sq - f.dot(f);
    let zero = T::splat(0.0);
    let root = disc.max(zero).sqrt();
    let t_near = -b - root;
    let t_far = -b + root;
    let near = eps.lt(t_near);
    let t = T::select(near, t_near, t_far);
    let offset = f + dir * T::select(near, -root, root);
    (t, T::and(zero.le(disc), eps.lt(t)), offset)
}
