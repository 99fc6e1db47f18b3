//! The per-pixel stages of the fixed path, in the float kernel's order and under its names
//! (`src/float/kernel.rs`), one pixel per call:
//!
//! | stage | what it computes | formats |
//! |---|---|---|
//! | `shade` | the whole pixel: the stages below, in this order | |
//! | `ray` | the primary ray through the pixel centre, normalized (the row driver calls it) | I16F48 → I2F30 |
//! | `hit` | the nearest sphere hit with `t > ε` among the pixel's candidate spheres | I16F16, I32F32 |
//! | `normal` | `N = (P − C)·(1/r)`: no square root, `1/r` prepared | I16F16 → I2F30 |
//! | `lights` | the loop over every light, accumulating the diffuse and specular sums | |
//! | `incoming` | per light: direction `L` toward it, arriving colour `I`, shadow-ray length | I2F30, U16F16 |
//! | `shadow` | per light: a ray from `P + ε·N` toward the light, tested against the sphere itself and its prepared casters | as `hit` |
//! | `diffuse` | per light: `Σ vis·I·max(0, N·L)` | U16F16 |
//! | `specular` | per light: `Σ vis·I·lobe`, lobe `= (1 − h)^n`, `h = ½|R − V|²` or `½|N − H|²` | U3F61 → U1F31 → U16F16 |
//! | `combine` | `kd·albedo·diffuse + ks·specular`, saturating | U16F16 |
//!
//! A sphere light (feature `area-lights`) takes the float kernel's stages for it, in
//! integers: `sphere_incoming` (the representative point's direction and the light's cap)
//! and `soft_shadow` (the uncovered share of the cap), in `kernel_sphere`, with
//! `specular` and `normalized` given the light's diffuse cosine and spread; the formulas are
//! in `area`. `incoming` is in `kernel_light`, which both use, and Oren–Nayar's
//! and GGX's terms (feature `models`) in `kernel_models`.
//!
//! (The spans stage is the row driver's, in [`super::spans`] and [`super::row`]; quantizing
//! to a pixel format is the row driver's `encode` step.) The normalized models' `diffuse`
//! and `specular` are one function, `normalized`, since both need `N·L` and Fresnel's `F`.
//!
//! Every product is an exact 32×32→64-bit product from [`super::mul`] (the formats bound
//! every operand to 32 bits), every sum that could leave its format saturates, and no
//! division or square root can see a zero or negative input: `1/√x` and `√x` come from
//! [`super::roots`], which return `None` or 0 for zero and take unsigned input. Nothing here
//! can panic, in release or debug.

use super::exact::shift_saturating;
use super::kernel_light::Incoming;
#[cfg(feature = "models")]
use super::kernel_models::{ggx_term, oren_nayar};
#[cfg(feature = "area-lights")]
use super::kernel_sphere::times;
use super::mul::{mul_ii, mul_iu, mul_uu};
use super::narrow::Shaded;
use super::pow::lobe;
#[cfg(feature = "area-lights")]
use super::prepare::FixedLight;
use super::prepare::{FixedSphere, PreparedFixed};
use super::roots::sqrt;
use super::vector::{dot_len_unit, dot_unit, each3, len_times_unit, length_sq, normalize, to_len};
use super::vector::{Len, Unit, V3};
use crate::pixel::HitRecord;
use crate::runs::Span;
use fixed::types::I16F48;

/// The unit direction of the unnormalized camera-plane direction `dir` (I16F48).
#[inline(always)]
pub(crate) fn ray(dir: V3<I16F48>) -> Option<V3<Unit>> {
    normalize(dir.map(|c| c.to_bits()))
}

/// Nearest `t > eps` (raw I16F16) where `origin + t·dir` meets the sphere, `oc` being
/// `origin − centre`. Closest-approach form: `f = oc − (oc·d)d`, `disc = r² − |f|²`, which
/// keeps precision for small spheres far away.
#[inline(always)]
fn nearest_hit(oc: V3<Len>, dir: V3<Unit>, radius_sq: i64, eps: i64) -> Option<i64> {
    let b = dot_len_unit(oc, dir);
    let f = each3(|i| (oc[i].to_bits() as i64).saturating_sub(len_times_unit(b, dir[i])));
    let disc = radius_sq.saturating_sub(length_sq(f));
    if disc < 0 {
        return None;
    }
    let root = sqrt(disc as u64) as i64;
    let t_near = -b - root;
    let t_far = root - b;
    let t = if t_near > eps { t_near } else { t_far };
    (t > eps).then_some(t)
}

impl<const S: usize, const L: usize> PreparedFixed<S, L> {
    /// Shades pixel `x` of a row whose spans are `spans`, along the unit ray `d`: `hit`,
    /// `normal`, `lights`, `combine`.
    #[inline(always)]
    pub(crate) fn shade(
        &self,
        d: V3<Unit>,
        x: u32,
        spans: &[Option<Span>],
        record_hits: bool,
    ) -> Option<Shaded> {
        let (index, sphere, t) = self.hit(d, x, spans, |_| true)?;
        Some(self.shade_hit(index, sphere, d, t, record_hits))
    }

    /// The stages after `hit`: `normal`, `lights` and `combine` of sphere `index`, met by the
    /// unit ray `d` at distance `t`.
    #[inline(always)]
    pub(super) fn shade_hit(
        &self,
        index: usize,
        sphere: &FixedSphere,
        d: V3<Unit>,
        t: i64,
        record_hits: bool,
    ) -> Shaded {
        let (p, n) = self.normal(sphere, d, t);
        let (diffuse, specular, shadowed) = self.lights(index, sphere, p, n, d, record_hits);
        Shaded {
            color: self.combine(sphere, diffuse, specular),
            hit: HitRecord {
                sphere: Some(index as u16),
                shadowed,
            },
        }
    }

    /// The nearest sphere with `t > ε` among those whose span on this row covers `x` and
    /// that `keep` keeps (the edges stage leaves some out).
    #[inline(always)]
    pub(super) fn hit(
        &self,
        d: V3<Unit>,
        x: u32,
        spans: &[Option<Span>],
        keep: impl Fn(usize) -> bool,
    ) -> Option<(usize, &FixedSphere, i64)> {
        let eps = self.epsilon.to_bits() as i64;
        let mut best: Option<(usize, &FixedSphere, i64)> = None;
        for (k, (s, span)) in self.spheres.iter().zip(spans).enumerate() {
            if !span.is_some_and(|span| span.start <= x && x < span.end) || !keep(k) {
                continue;
            }
            if let Some(t) = nearest_hit(s.eye_offset, d, s.radius_sq.to_bits(), eps) {
                if best.is_none_or(|(_, _, t_best)| t < t_best) {
                    best = Some((k, s, t));
                }
            }
        }
        best
    }

    /// The hit point `P = eye + t·d` and the unit normal `N = (P − C)·(1/r)`.
    #[inline(always)]
    pub(super) fn normal(&self, s: &FixedSphere, d: V3<Unit>, t: i64) -> (V3<Len>, V3<Unit>) {
        let step = d.map(|c| len_times_unit(t, c));
        let p = each3(|i| to_len(self.eye[i].to_bits() as i64 + step[i]));
        let (y, shift) = s.inv_radius;
        let n = each3(|i| {
            // (P − C) from the offset, not from the rounded P: one rounding fewer. It is
            // within a radius of the centre, so it fits I16F16.
            let pc = to_len(s.eye_offset[i].to_bits() as i64 + step[i]).to_bits();
            let v = mul_iu(pc, y) >> (shift - 30).min(63);
            Unit::from_bits(v.clamp(-(1 << 31), (1 << 31) - 1) as i32)
        });
        (p, n)
    }

    /// Every light's `incoming`, `shadow`, `diffuse` and `specular` at the surface point
    /// `p` of sphere `index` with normal `n`: the sums `Σ vis·I·diffuse` and
    /// `Σ vis·I·specular` (U16F16 per channel, saturating), and, if `record_hits`, the bits
    /// of the lights that are blocked.
    #[inline(always)]
    fn lights(
        &self,
        index: usize,
        sphere: &FixedSphere,
        p: V3<Len>,
        n: V3<Unit>,
        d: V3<Unit>,
        record_hits: bool,
    ) -> ([u32; 3], [u32; 3], u32) {
        let eps = self.epsilon.to_bits() as i64;
        let shadow_origin: V3<Len> =
            each3(|i| to_len(p[i].to_bits() as i64 + len_times_unit(eps, n[i])));
        let mut diffuse = [0u32; 3];
        let mut specular = [0u32; 3];
        let mut shadowed = 0u32;
        for (light_index, light) in self.lights.iter().enumerate() {
            #[cfg(feature = "area-lights")]
            if let FixedLight::Sphere {
                position,
                power,
                radius,
            } = *light
            {
                let lit = self
                    .sphere_incoming(position, power, radius, p, n, d)
                    .and_then(|seen| {
                        let (vis_diffuse, vis_specular) =
                            self.soft_shadow(index, shadow_origin, &seen);
                        (vis_specular > 0).then_some((seen, vis_diffuse, vis_specular))
                    });
                let Some((seen, vis_diffuse, vis_specular)) = lit else {
                    if record_hits && light_index < 32 {
                        shadowed |= 1 << light_index;
                    }
                    continue;
                };
                let area = Some(Area {
                    diffuse_cos: seen.diffuse_cos,
                    spread: seen.sin_a,
                });
                let (dif, spec) = if sphere.normalized {
                    self.normalized(sphere, n, d, &seen.incoming, area)
                } else {
                    (
                        times(seen.incoming.arriving, seen.diffuse_cos),
                        self.specular(sphere, n, d, &seen.incoming, area),
                    )
                };
                add(&mut diffuse, times(dif, vis_diffuse));
                add(&mut specular, times(spec, vis_specular));
                continue;
            }
            let incoming = self.incoming(light, p);
            let casters = self.casters(index, light_index);
            if self.shadow(index, shadow_origin, &incoming, casters) {
                if record_hits && light_index < 32 {
                    shadowed |= 1 << light_index;
                }
                continue;
            }
            let (dif, spec) = if sphere.normalized {
                self.normalized(sphere, n, d, &incoming, None)
            } else {
                (
                    self.diffuse(n, &incoming),
                    self.specular(sphere, n, d, &incoming, None),
                )
            };
            add(&mut diffuse, dif);
            add(&mut specular, spec);
        }
        (diffuse, specular, shadowed)
    }

    /// The spheres that can block light `light` from reaching sphere `index` (bit `k` for
    /// sphere `k`; spheres from index 32 on are always tested), prepared per frame.
    #[inline(always)]
    pub(crate) fn casters(&self, index: usize, light: usize) -> u32 {
        debug_assert!(index < self.casters.len(), "casters of sphere {index}");
        debug_assert!(light < self.lights.len(), "casters for light {light}");
        self.casters
            .get(index)
            .and_then(|c| c.get(light))
            .copied()
            .unwrap_or(u32::MAX)
    }

    /// Whether any sphere blocks the ray from `origin` (on sphere `index`, lifted by ε
    /// along the normal) toward the light before it arrives.
    ///
    /// Only the sphere itself and its prepared `casters` can (see [`super::prepare`]). The
    /// sphere itself cannot when the ray leaves its surface outward (`(origin − C)·L ≥ 0`):
    /// then the far root lies behind the origin, so its test is only made when it can hit.
    #[inline(always)]
    fn shadow(&self, index: usize, origin: V3<Len>, incoming: &Incoming, casters: u32) -> bool {
        let eps = self.epsilon.to_bits() as i64;
        let blocks = |s: &FixedSphere| {
            let oc = each3(|i| to_len(origin[i].to_bits() as i64 - s.center[i].to_bits() as i64));
            nearest_hit(oc, incoming.to_light, s.radius_sq.to_bits(), eps)
                .is_some_and(|t| incoming.reach.is_none_or(|reach| t < reach))
        };
        if let Some(own) = self.spheres.get(index) {
            let oc = each3(|i| to_len(origin[i].to_bits() as i64 - own.center[i].to_bits() as i64));
            if dot_len_unit(oc, incoming.to_light) < 0 {
                if blocks(own) {
                    return true;
                }
            } else {
                debug_assert!(!blocks(own), "a ray leaving its own sphere hit it");
            }
        }
        self.spheres
            .iter()
            .enumerate()
            .any(|(k, s)| k != index && (k >= 32 || casters & (1 << k) != 0) && blocks(s))
    }

    /// `I·max(0, N·L)` per channel, U16F16.
    #[inline(always)]
    fn diffuse(&self, n: V3<Unit>, incoming: &Incoming) -> [u32; 3] {
        let n_dot_l = dot_unit(n, incoming.to_light).clamp(0, u32::MAX as i64) as u32; // U2F30
        incoming
            .arriving
            .map(|i| u32::try_from(mul_uu(i, n_dot_l) >> 30).unwrap_or(u32::MAX))
    }

    /// `I·lobe` per channel, U16F16, with the lobe's `h = 1 − cos` from a sum of squares
    /// (under a sphere light, times its energy factor).
    #[inline(always)]
    fn specular(
        &self,
        s: &FixedSphere,
        n: V3<Unit>,
        d: V3<Unit>,
        incoming: &Incoming,
        area: Option<Area>,
    ) -> [u32; 3] {
        let l = incoming.to_light;
        let blinn = s.blinn();
        if !blinn && l == [Unit::ZERO; 3] {
            return [0; 3];
        }
        let half = if blinn { half_vector(l, d) } else { None };
        let Some(h) = lobe_h(blinn, n, l, d, half) else {
            return [0; 3];
        };
        let lobe = widened(lobe(h, s.shininess), s, 0, area); // U1F31
        incoming
            .arriving
            .map(|i| u32::try_from(mul_uu(i, lobe) >> 31).unwrap_or(u32::MAX))
    }

    /// The normalized models' `diffuse` and `specular` terms, U16F16 per channel: the
    /// integer form of [`crate::brdf::terms`]. Diffuse `I·max(0, N·L)·(1 − F)` (or without
    /// `1 − F`), specular `I·max(0, N·L)·F·Σ wₖcₖ·lobeₖ`, every lobe from the same `h` and
    /// the same [`lobe`] as the classic models; `F = F₀ + (1 − F₀)(1 − L·H)⁵` in U2F30.
    #[inline(always)]
    fn normalized(
        &self,
        s: &FixedSphere,
        n: V3<Unit>,
        d: V3<Unit>,
        incoming: &Incoming,
        area: Option<Area>,
    ) -> ([u32; 3], [u32; 3]) {
        const ONE: u32 = 1 << 30;
        let l = incoming.to_light;
        let n_dot_l = dot_unit(n, l).clamp(0, ONE as i64) as u32; // U2F30
                                                                  // A sphere light's diffuse term has its own cosine, whatever N·L of the
                                                                  // representative point is.
        if (n_dot_l == 0 || l == [Unit::ZERO; 3]) && area.is_none() {
            return ([0; 3], [0; 3]);
        }
        // H is needed by Blinn-Phong lobes, by Fresnel and by GGX.
        let ggx = is_ggx(s);
        let half = (s.blinn() || s.schlick || ggx)
            .then(|| half_vector(l, d))
            .flatten();
        // Σ wₖcₖ·lobeₖ in U16F16 (GGX has its own lobe, below).
        let mut sum = 0u32;
        if let Some(h) = lobe_h(s.blinn(), n, l, d, half).filter(|_| !ggx) {
            let exponents = [s.shininess, s.more_shininess[0], s.more_shininess[1]];
            for (k, (w, e)) in s.weight.iter().zip(exponents).enumerate() {
                if w.mantissa == 0 {
                    continue;
                }
                // lobe·w as U16F16: (lobe·2⁻³¹)·(m·2^e)·2¹⁶.
                let lobe = widened(lobe(h, e), s, k, area);
                let term = shift_saturating(mul_uu(lobe, w.mantissa), w.exponent - 15);
                sum = sum.saturating_add(term);
            }
        }
        // Schlick: (1 − L·H)⁵ in U2F30.
        let weight5 = match half {
            Some(h) if s.schlick => {
                let c = dot_unit(l, h).clamp(0, ONE as i64) as u32;
                let m = ONE - c;
                let m2 = (mul_uu(m, m) >> 30) as u32;
                let m4 = (mul_uu(m2, m2) >> 30) as u32;
                (mul_uu(m4, m) >> 30) as u32
            }
            _ => 0,
        };
        // F ≤ F₀ + (1 − F₀) ≤ 1 (U2F30, ≤ 2³⁰).
        let f =
            s.f0.map(|f0| f0 + (mul_uu(ONE.saturating_sub(f0), weight5) >> 30) as u32);
        let diffuse_scale = if s.diffuse_loss {
            ONE - f[0].min(ONE)
        } else {
            ONE
        };
        // The diffuse lobe times N·L: Lambert's N·L, or Oren–Nayar's (below 1.45).
        let cos_diffuse = area.map_or(n_dot_l, |a| a.diffuse_cos);
        #[cfg(feature = "models")]
        let n_dot_l_diffuse = match s.oren_nayar {
            Some([a, b]) => oren_nayar(a, b, cos_diffuse, n, l, d),
            None => cos_diffuse,
        };
        #[cfg(not(feature = "models"))]
        let n_dot_l_diffuse = cos_diffuse;
        let lit = (mul_uu(n_dot_l_diffuse, diffuse_scale) >> 30) as u32; // U2F30
                                                                         // U16F16: Σ wₖcₖ·lobeₖ·(N·L) (≤ sum), or GGX's ks·D·V₂·(N·L).
        let spec = ggx_specular(s, n_dot_l, n, d, half, area)
            .unwrap_or_else(|| (mul_uu(sum, n_dot_l) >> 30) as u32);
        let diffuse = incoming
            .arriving
            .map(|i| u32::try_from(mul_uu(i, lit) >> 30).unwrap_or(u32::MAX));
        let specular = each3(|c| {
            let t = u32::try_from(mul_uu(spec, f[c]) >> 30).unwrap_or(u32::MAX);
            u32::try_from(mul_uu(incoming.arriving[c], t) >> 16).unwrap_or(u32::MAX)
        });
        (diffuse, specular)
    }

    /// `combine`: `kd·albedo·diffuse + ks·specular` per channel, U16F16, saturating.
    #[inline(always)]
    fn combine(&self, s: &FixedSphere, diffuse: [u32; 3], specular: [u32; 3]) -> [u32; 3] {
        let ks = s.ks.to_bits();
        each3(|c| {
            let a = mul_uu(s.kd_albedo[c].to_bits(), diffuse[c]) >> 16;
            let b = mul_uu(ks, specular[c]) >> 16;
            u32::try_from(a.saturating_add(b)).unwrap_or(u32::MAX)
        })
    }
}

/// The half vector `H = normalize(L + V)`, `V = −d`; `None` where `L = −V`.
#[inline(always)]
pub(super) fn half_vector(l: V3<Unit>, d: V3<Unit>) -> Option<V3<Unit>> {
    normalize(each3(|i| l[i].to_bits() as i64 - d[i].to_bits() as i64))
}

/// The lobe's `h = 1 − cos` in U3F61 from `u = R − V` (Phong: `R = 2(N·L)N − L`, `V = −d`)
/// or `u = N − H` (Blinn-Phong; `None` without a half vector): for unit vectors
/// `1 − cos = ½|u|²`, and `|u|²` of 30-bit fractions in F60 is `½|u|²` in F61, exact from
/// the components, with full relative precision at the highlight.
#[inline(always)]
pub(super) fn lobe_h(
    blinn: bool,
    n: V3<Unit>,
    l: V3<Unit>,
    d: V3<Unit>,
    half: Option<V3<Unit>>,
) -> Option<u64> {
    let u: V3<i64> = if blinn {
        let h = half?;
        each3(|i| n[i].to_bits() as i64 - h[i].to_bits() as i64)
    } else {
        // |N·L| ≤ 1 (U2F30), so it fits i32; (2k·n) >> 30 is (k·n) >> 29.
        let k = dot_unit(n, l).clamp(i32::MIN as i64, i32::MAX as i64) as i32;
        each3(|i| {
            let r = (mul_ii(k, n[i].to_bits()) >> 29) - l[i].to_bits() as i64;
            r + d[i].to_bits() as i64
        })
    };
    // Each component is within ±2 (F30, below 2³²).
    Some(u.iter().fold(0u64, |acc, &c| {
        let m = c.unsigned_abs().min(u32::MAX as u64) as u32;
        acc.saturating_add(mul_uu(m, m))
    }))
}

/// Whether sphere `s` has a GGX lobe.
#[inline(always)]
fn is_ggx(s: &FixedSphere) -> bool {
    #[cfg(feature = "models")]
    {
        s.ggx.is_some()
    }
    #[cfg(not(feature = "models"))]
    {
        let _ = s;
        false
    }
}

/// GGX's specular term times `N·L` in U16F16, saturating, for a GGX sphere (`None` for the
/// others): `ks·D(H)·V₂(L, V)·(N·L)`, the integer form of [`crate::brdf::ggx`], for
/// `N·L > 0` (U2F30) and `half` the unit `H` (none where `L = −V`: 0).
///
/// `D·V₂·(N·L) = ks·α²/(2π) · (N·L) / (q²·den)` with `q = α²(N·H)² + |N × H|²` and
/// `den = (N·L)·Λ(N·V) + (N·V)·Λ(N·L)`, `Λ(x) = √(x²(1 − α²) + α²)`: `q` and `den` in F60
/// from 30-bit components (`|N × H|²` from the cross product keeps its relative precision
/// at the peak, where `q` falls to `α²`), their reciprocals from `inv_sqrt` squared, and
/// the product of the four factors as a mantissa and a power of two (`kernel_models`): the
/// term spans from 0 to about `1/(2πα³)` (10⁷ at the smallest roughness), beyond any one
/// fixed format, and saturates only where it exceeds U16F16.
#[inline(always)]
fn ggx_specular(
    s: &FixedSphere,
    n_dot_l: u32,
    n: V3<Unit>,
    d: V3<Unit>,
    half: Option<V3<Unit>>,
    area: Option<Area>,
) -> Option<u32> {
    #[cfg(feature = "models")]
    {
        let g = s.ggx.as_ref()?;
        let term = ggx_term(g, n_dot_l, n, d, half);
        #[cfg(feature = "area-lights")]
        if let Some(a) = area {
            let w = super::area::ggx_widening(g.alpha, g.alpha2, a.spread);
            return Some((mul_uu(term, w) >> 30) as u32);
        }
        let _ = area;
        Some(term)
    }
    #[cfg(not(feature = "models"))]
    {
        let _ = (s, n_dot_l, n, d, half, area);
        None
    }
}

/// What a sphere light changes in `specular` and `normalized` (see `area`): the diffuse
/// cosine (F30) replaces `max(0, N·L)` in the diffuse term, and every lobe is widened by
/// the light's `spread = sin α` (F30). Without the `area-lights` feature it is never built.
#[derive(Clone, Copy)]
#[cfg_attr(not(feature = "area-lights"), allow(dead_code))]
pub(super) struct Area {
    diffuse_cos: u32,
    spread: u32,
}

/// A lobe (U1F31) times lobe `k`'s energy factor under a sphere light, if `area` is one.
#[inline(always)]
fn widened(lobe: u32, s: &FixedSphere, k: usize, area: Option<Area>) -> u32 {
    #[cfg(feature = "area-lights")]
    if let (Some(a), Some(&constants)) = (area, s.widening.get(k)) {
        let w = super::area::lobe_widening(a.spread, constants);
        return (mul_uu(lobe, w) >> 30) as u32;
    }
    let _ = (s, k, area);
    lobe
}

/// `acc += v` per channel, saturating.
#[inline(always)]
fn add(acc: &mut [u32; 3], v: [u32; 3]) {
    for (a, v) in acc.iter_mut().zip(v) {
        *a = a.saturating_add(v);
    }
}
