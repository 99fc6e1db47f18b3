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
//! Misses get the background. Decisions are lane masks, never per-lane branches, so a lane's
//! result depends only on its own pixel: which pixels share a packet, and how wide the packet
//! is, cannot change any bit. The only branches are on whole packets (skip a sphere's shadow
//! test, skip lighting when no lane hit) and those skip work whose result would be discarded.

use crate::brdf;
use crate::float_math::pow_clamped;
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
        let mut center = V::<W::Lane>::splat(Vec3::default());
        let mut inv_r = zero;
        let mut kd_albedo = V::<W::Lane>::splat(Vec3::default());
        let mut ks = zero;
        let mut shininess = one;
        let mut blinn = zero;
        for &k in candidates {
            let Some(s) = self.spheres.get(k as usize) else {
                continue;
            };
            let oc = V::splat(s.eye_offset);
            let (t, hit) = nearest_hit(oc, d, W::Lane::splat(s.radius_sq), eps);
            let hit = W::Lane::and(hit, t.lt(t_best));
            if !W::Lane::any(hit) {
                continue;
            }
            t_best = W::Lane::select(hit, t, t_best);
            id = W::Lane::select(hit, W::Lane::splat(k as f32), id);
            center = V::select(hit, V::splat(s.center), center);
            inv_r = W::Lane::select(hit, W::Lane::splat(s.inv_radius), inv_r);
            kd_albedo = V::select(hit, V::splat(s.kd_albedo), kd_albedo);
            ks = W::Lane::select(hit, W::Lane::splat(s.ks), ks);
            shininess = W::Lane::select(hit, W::Lane::splat(s.shininess), shininess);
            blinn = W::Lane::select(hit, W::Lane::splat(s.blinn), blinn);
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

        // normal: N = (P − C)/r, with P = eye + t·d.
        let p = V::splat(self.eye) + d * t_best;
        let n = (p - center) * inv_r;
        let view = -d;
        let shadow_origin = p + n * eps;
        let is_blinn = zero.lt(blinn);

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

            // shadow: any sphere between P + ε·N and the light blocks it.
            let mut blocked = W::Lane::lt(one, zero);
            for s in &self.spheres {
                let oc = shadow_origin - V::splat(s.center);
                let (t, hit) = nearest_hit(oc, to_light, W::Lane::splat(s.radius_sq), eps);
                blocked = W::Lane::or(blocked, W::Lane::and(hit, t.lt(t_max)));
                if !W::Lane::any(W::Lane::and_not(any_hit, blocked)) {
                    break;
                }
            }
            let visible = W::Lane::and_not(any_hit, blocked);
            if record_hits && light_index < 32 {
                let bits = W::Lane::bitmask(W::Lane::and(any_hit, blocked));
                for (lane, word) in packet.shadowed.iter_mut().enumerate() {
                    *word |= ((bits >> lane) & 1) << light_index;
                }
            }
            if !W::Lane::any(visible) {
                continue;
            }

            // diffuse and specular, from the brdf module's definitions.
            let n_dot_l = n.dot(to_light).max(zero);
            let cosine = brdf::specular_cosine(n, to_light, view, is_blinn);
            // pow_clamped is exactly 0 where the cosine is not positive, so a packet with no
            // positive lane can skip it without changing a bit.
            let lobe = if W::Lane::any(zero.lt(cosine)) {
                pow_clamped(cosine, shininess)
            } else {
                zero
            };
            let lit = W::Lane::select(visible, one, zero);
            diffuse = diffuse + arriving * (n_dot_l * lit);
            specular = specular + arriving * (lobe * lit);
        }

        let shaded = V::new(
            kd_albedo.x * diffuse.x,
            kd_albedo.y * diffuse.y,
            kd_albedo.z * diffuse.z,
        ) + specular * ks;
        // kd·albedo (up to 1e12) times arriving light (up to 1e30 per light) can exceed
        // f32::MAX: saturate there, so the output is finite. Every term is ≥ 0 and finite,
        // so the sum is never NaN, and `min` leaves every finite value's bits unchanged.
        let cap = W::Lane::splat(f32::MAX);
        let shaded = V::new(shaded.x.min(cap), shaded.y.min(cap), shaded.z.min(cap));
        packet.color = V::select(any_hit, shaded, background);
        packet
    }
}

/// Nearest intersection with `t > ε` of the ray `origin + t·dir` (`dir` unit) with the sphere
/// at offset `oc = origin − center`: `(t, hit)`.
#[inline(always)]
pub(crate) fn nearest_hit<T: Lane>(
    oc: Vec3<T>,
    dir: Vec3<T>,
    radius_sq: T,
    eps: T,
) -> (T, T::Mask) {
    let b = oc.dot(dir);
    let f = oc - dir * b;
    let disc = radius_sq - f.dot(f);
    let zero = T::splat(0.0);
    let root = disc.max(zero).sqrt();
    let t_near = -b - root;
    let t_far = -b + root;
    let t = T::select(eps.lt(t_near), t_near, t_far);
    (t, T::and(zero.le(disc), eps.lt(t)))
}
