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
//! A sphere light (features `area-lights` and `full-width`) takes the float kernel's stages
//! for it, in integers: `sphere_incoming` (the representative point's direction and the
//! light's cap) and `soft_shadow` (the uncovered share of the cap), with `specular` and
//! `normalized` given the light's diffuse cosine and spread; the formulas are in `area`.
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

#[cfg(all(feature = "area-lights", feature = "full-width"))]
use super::exact::Exact;
#[cfg(feature = "full-width")]
use super::exact::{arriving, shift_saturating};
#[cfg(all(feature = "models", feature = "full-width"))]
use super::mul::leading_zeros;
use super::mul::{mul_ii, mul_iu, mul_uu};
use super::narrow::Shaded;
#[cfg(feature = "full-width")]
use super::pow::lobe;
#[cfg(all(feature = "models", feature = "full-width"))]
use super::prepare::FixedGgx;
#[cfg(feature = "full-width")]
use super::prepare::FixedLight;
use super::prepare::{FixedSphere, PreparedFixed};
#[cfg(feature = "full-width")]
use super::roots::{inv_sqrt, sqrt};
#[cfg(feature = "full-width")]
use super::vector::{dot_len_unit, length_sq};
use super::vector::{dot_unit, each3, len_times_unit, normalize, to_len, Len, Unit, V3};
use crate::pixel::HitRecord;
#[cfg(feature = "full-width")]
use crate::runs::Span;
#[cfg(feature = "full-width")]
use fixed::types::{I16F48, U16F16};

/// A light as seen from one surface point.
#[cfg(feature = "full-width")]
struct Incoming {
    /// Unit vector toward the light; zero if the point is at the light.
    to_light: V3<Unit>,
    /// Arriving light per channel.
    arriving: [u32; 3],
    /// Distance to a point light (raw I16F16); `None` for a distant light.
    reach: Option<i64>,
}

/// A sphere light as seen from one surface point (see `sphere_incoming`).
#[cfg(all(feature = "area-lights", feature = "full-width"))]
struct SphereSeen {
    /// The representative point's direction, the colour arriving from the centre, no reach
    /// (the soft shadow has its own test).
    incoming: Incoming,
    /// Unit vector toward the centre, `A`.
    axis: V3<Unit>,
    /// Squared distance to the centre, raw I32F32.
    dist2: i64,
    /// `sin α = R/d`, F30.
    sin_a: u32,
    /// The chord of the light's cap, `2 sin(α/2)` (F30): its radius in the equal-area
    /// projection.
    rho: u32,
    /// `N·A`, F30.
    cos_axis: i64,
    /// The diffuse cosine, `area::horizon_cosine`, F30.
    diffuse_cos: u32,
}

/// The unit direction of the unnormalized camera-plane direction `dir` (I16F48).
#[cfg(feature = "full-width")]
#[inline(always)]
pub(crate) fn ray(dir: V3<I16F48>) -> Option<V3<Unit>> {
    normalize(dir.map(|c| c.to_bits()))
}

/// Nearest `t > eps` (raw I16F16) where `origin + t·dir` meets the sphere, `oc` being
/// `origin − centre`. Closest-approach form: `f = oc − (oc·d)d`, `disc = r² − |f|²`, which
/// keeps precision for small spheres far away.
#[cfg(feature = "full-width")]
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
    #[cfg(feature = "full-width")]
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
    #[cfg(feature = "full-width")]
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
    #[cfg(feature = "full-width")]
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
    #[cfg(feature = "full-width")]
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
    #[cfg(feature = "full-width")]
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

    /// One light as seen from `p`: direction toward it, arriving colour, shadow-ray length.
    #[cfg(feature = "full-width")]
    #[inline(always)]
    fn incoming(&self, light: &FixedLight, p: V3<Len>) -> Incoming {
        match *light {
            FixedLight::Distant { to_light, arriving } => Incoming {
                to_light,
                arriving: arriving.map(U16F16::to_bits),
                reach: None,
            },
            // Shaded by `sphere_incoming`, never here; as the point at its centre otherwise.
            #[cfg(feature = "area-lights")]
            FixedLight::Sphere {
                position, power, ..
            } => self.incoming(&FixedLight::Point { position, power }, p),
            FixedLight::Point { position, power } => {
                // Both points lie within ±2¹³ units: the difference fits I16F16.
                let lv = each3(|i| position[i].to_bits() as i64 - p[i].to_bits() as i64);
                let d2 = length_sq(lv).max(0) as u64;
                let Some((y, shift)) = inv_sqrt(d2) else {
                    // At the light: arriving light is capped, the direction is undefined.
                    return Incoming {
                        to_light: [Unit::ZERO; 3],
                        arriving: [u32::MAX; 3],
                        reach: Some(0),
                    };
                };
                Incoming {
                    to_light: lv.map(|c| unit_component(c, (y, shift))),
                    arriving: arriving(power, (y, shift)),
                    reach: Some(sqrt(d2) as i64),
                }
            }
        }
    }

    /// `incoming` for a sphere light of `radius` at `position` with `power`, seen from the
    /// surface point `p` with normal `n` along the view ray `d`: the direction toward the
    /// representative point (the point of the light's sphere closest to the reflected ray
    /// `R = 2(N·V)N − V`: the centre moved toward the ray by up to the radius), the colour
    /// arriving from the centre, and the cap's constants. `None` at the light's centre,
    /// which validation keeps clear of every sphere.
    #[cfg(all(feature = "area-lights", feature = "full-width"))]
    #[inline(always)]
    fn sphere_incoming(
        &self,
        position: V3<Len>,
        power: V3<Exact>,
        radius: Len,
        p: V3<Len>,
        n: V3<Unit>,
        d: V3<Unit>,
    ) -> Option<SphereSeen> {
        use super::area::{chord, horizon_cosine, ONE};
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
    #[cfg(all(feature = "area-lights", feature = "full-width"))]
    #[inline(always)]
    fn soft_shadow(&self, index: usize, origin: V3<Len>, light: &SphereSeen) -> (u32, u32) {
        use super::area::{above_horizon, chord, covered, ONE};
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

    /// The spheres that can block light `light` from reaching sphere `index` (bit `k` for
    /// sphere `k`; spheres from index 32 on are always tested), prepared per frame.
    #[cfg(feature = "full-width")]
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
    #[cfg(feature = "full-width")]
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
    #[cfg(feature = "full-width")]
    #[inline(always)]
    fn diffuse(&self, n: V3<Unit>, incoming: &Incoming) -> [u32; 3] {
        let n_dot_l = dot_unit(n, incoming.to_light).clamp(0, u32::MAX as i64) as u32; // U2F30
        incoming
            .arriving
            .map(|i| u32::try_from(mul_uu(i, n_dot_l) >> 30).unwrap_or(u32::MAX))
    }

    /// `I·lobe` per channel, U16F16, with the lobe's `h = 1 − cos` from a sum of squares
    /// (under a sphere light, times its energy factor).
    #[cfg(feature = "full-width")]
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
    #[cfg(feature = "full-width")]
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
    #[cfg(feature = "full-width")]
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

/// Component `v` (raw I16F16) of a vector over its length, `1/|v| = y·2^-shift` as
/// [`inv_sqrt`] returns it: I2F30, clamped to `[−1, 1]`.
#[cfg(feature = "full-width")]
#[inline(always)]
fn unit_component(v: i64, (y, shift): (u32, u32)) -> Unit {
    let u = mul_iu(to_len(v).to_bits(), y) >> (shift - 30).min(63);
    Unit::from_bits(u.clamp(-(1 << 30), 1 << 30) as i32)
}

/// The half vector `H = normalize(L + V)`, `V = −d`; `None` where `L = −V`.
#[cfg(feature = "full-width")]
#[inline(always)]
pub(super) fn half_vector(l: V3<Unit>, d: V3<Unit>) -> Option<V3<Unit>> {
    normalize(each3(|i| l[i].to_bits() as i64 - d[i].to_bits() as i64))
}

/// The lobe's `h = 1 − cos` in U3F61 from `u = R − V` (Phong: `R = 2(N·L)N − L`, `V = −d`)
/// or `u = N − H` (Blinn-Phong; `None` without a half vector): for unit vectors
/// `1 − cos = ½|u|²`, and `|u|²` of 30-bit fractions in F60 is `½|u|²` in F61, exact from
/// the components, with full relative precision at the highlight.
#[cfg(feature = "full-width")]
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

/// Oren–Nayar's diffuse factor times `N·L`, U2F30, the integer form of
/// [`crate::brdf::oren_nayar`]: `A·(N·L) + B·max(0, s)·(N·L/max(N·L, N·V))` with
/// `s = L·V − (N·L)(N·V)` and `V = −d`, for `A`, `B` and `N·L > 0` in U2F30. The ratio is 1
/// where `N·L ≥ N·V` and otherwise one 64-bit division, exact to the last of its 30 bits:
/// the only division of the fixed kernel, and only for Oren–Nayar spheres.
#[cfg(all(feature = "models", feature = "full-width"))]
#[inline(always)]
fn oren_nayar(a: u32, b: u32, n_dot_l: u32, n: V3<Unit>, l: V3<Unit>, d: V3<Unit>) -> u32 {
    const ONE: u32 = 1 << 30;
    let v = d.map(|c| c.saturating_neg());
    let n_dot_v = dot_unit(n, v).clamp(0, ONE as i64) as u32;
    let l_dot_v = dot_unit(l, v);
    // s = sin θ_i·sin θ_r·cos Δφ ≤ 1.
    let s = (l_dot_v - (mul_uu(n_dot_l, n_dot_v) >> 30) as i64).clamp(0, ONE as i64) as u32;
    let ratio = if n_dot_l >= n_dot_v {
        ONE
    } else {
        // N·V > N·L ≥ 0, so the quotient is below 2³⁰ and the divisor not 0.
        (((n_dot_l as u64) << 30).checked_div(n_dot_v as u64)).unwrap_or(0) as u32
    };
    let rough = (mul_uu((mul_uu(b, s) >> 30) as u32, ratio) >> 30) as u32;
    ((mul_uu(a, n_dot_l) >> 30) as u32).saturating_add(rough)
}

/// Whether sphere `s` has a GGX lobe.
#[cfg(feature = "full-width")]
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
/// at the peak, where `q` falls to `α²`), their reciprocals from [`inv_sqrt`] squared, and
/// the product of the four factors in [`Wide`]: the term spans from 0 to about
/// `1/(2πα³)` (10⁷ at the smallest roughness), beyond any one fixed format, and saturates
/// only where it exceeds U16F16.
#[cfg(feature = "full-width")]
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

/// The body of [`ggx_specular`].
#[cfg(all(feature = "models", feature = "full-width"))]
#[inline(always)]
fn ggx_term(g: &FixedGgx, n_dot_l: u32, n: V3<Unit>, d: V3<Unit>, half: Option<V3<Unit>>) -> u32 {
    const ONE: u32 = 1 << 30;
    let Some(h) = half else {
        return 0;
    };
    let n_dot_h = dot_unit(n, h);
    if n_dot_h <= 0 {
        return 0;
    }
    let c = n_dot_h.min(ONE as i64) as u32; // F30
    let n_dot_v = dot_unit(n, d.map(|x| x.saturating_neg())).clamp(0, ONE as i64) as u32;
    let (nb, hb) = (n.map(|x| x.to_bits()), h.map(|x| x.to_bits()));
    // N × H in F60 (each component below 2⁶¹), then |N × H|² in F60 from its F30 components.
    let cross = [
        mul_ii(nb[1], hb[2]) - mul_ii(nb[2], hb[1]),
        mul_ii(nb[2], hb[0]) - mul_ii(nb[0], hb[2]),
        mul_ii(nb[0], hb[1]) - mul_ii(nb[1], hb[0]),
    ];
    let sin2 = cross.iter().fold(0u64, |acc, &x| {
        let m = (x >> 30).unsigned_abs().min(u32::MAX as u64) as u32;
        acc.saturating_add(mul_uu(m, m))
    });
    // F60 × U1F31 (through F31 × F31 = F62).
    let times = |x60: u64, f31: u32| mul_uu((x60 >> 29).min(u32::MAX as u64) as u32, f31) >> 2;
    let q = times(mul_uu(c, c), g.alpha2).saturating_add(sin2);
    let lambda = |x: u32| {
        let l2 = times(mul_uu(x, x), g.one_minus_alpha2) + ((g.alpha2 as u64) << 29);
        sqrt(l2).min(u32::MAX as u64) as u32 // F30
    };
    let den = mul_uu(n_dot_l, lambda(n_dot_v)) + mul_uu(n_dot_v, lambda(n_dot_l)); // F60
    let (Some((yq, sq)), Some((yd, sd))) = (inv_sqrt(q), inv_sqrt(den)) else {
        return 0;
    };
    // 1/x = y²·2^(60 − 2·shift) for x in F60 with 1/√x_raw = y·2^-shift.
    let inv_q = Wide::new(mul_uu(yq, yq), 60 - 2 * sq as i32);
    let inv_den = Wide::new(mul_uu(yd, yd), 60 - 2 * sd as i32);
    let term = Wide::new(g.scale.mantissa as u64, g.scale.exponent)
        .mul(Wide::new(n_dot_l as u64, -30))
        .mul(inv_q)
        .mul(inv_q)
        .mul(inv_den);
    shift_saturating(term.m as u64, term.e + 16)
}

/// `m·2^e` with `m` normalized to its top bit (0 is `m = 0`): products of factors whose
/// range no fixed format holds, to 31 bits, rounded toward zero.
#[cfg(all(feature = "models", feature = "full-width"))]
#[derive(Clone, Copy)]
struct Wide {
    m: u32,
    e: i32,
}

#[cfg(all(feature = "models", feature = "full-width"))]
impl Wide {
    /// `v·2^e`, rounded toward zero to 32 significant bits.
    #[inline(always)]
    fn new(v: u64, e: i32) -> Wide {
        if v == 0 {
            return Wide { m: 0, e: 0 };
        }
        let lz = leading_zeros(v);
        Wide {
            m: ((v << lz) >> 32) as u32,
            e: e + 32 - lz as i32,
        }
    }

    /// The product, rounded toward zero.
    #[inline(always)]
    fn mul(self, o: Wide) -> Wide {
        Wide::new(mul_uu(self.m, o.m), self.e + o.e)
    }
}

/// What a sphere light changes in `specular` and `normalized` (see `area`): the diffuse
/// cosine (F30) replaces `max(0, N·L)` in the diffuse term, and every lobe is widened by
/// the light's `spread = sin α` (F30). Without the `area-lights` feature it is never built.
#[cfg(feature = "full-width")]
#[derive(Clone, Copy)]
#[cfg_attr(not(feature = "area-lights"), allow(dead_code))]
pub(super) struct Area {
    diffuse_cos: u32,
    spread: u32,
}

/// A lobe (U1F31) times lobe `k`'s energy factor under a sphere light, if `area` is one.
#[cfg(feature = "full-width")]
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

/// `v·f` per channel for an F30 factor `f ≤ 1`.
#[cfg(all(feature = "area-lights", feature = "full-width"))]
#[inline(always)]
fn times(v: [u32; 3], f: u32) -> [u32; 3] {
    v.map(|c| (mul_uu(c, f) >> 30).min(u32::MAX as u64) as u32)
}

/// `acc += v` per channel, saturating.
#[cfg(feature = "full-width")]
#[inline(always)]
fn add(acc: &mut [u32; 3], v: [u32; 3]) {
    for (a, v) in acc.iter_mut().zip(v) {
        *a = a.saturating_add(v);
    }
}
