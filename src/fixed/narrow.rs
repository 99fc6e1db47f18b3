//! The narrow kernel: the fixed path's pixels in 16×16→32-bit products, for the frames that
//! allow it, with a 64-bit `h` only where a sharp highlight needs it.
//!
//! # Why it exists
//!
//! The full-width kernel (`kernel`, feature `full-width`) holds unit vectors in I2F30 and lengths
//! in I16F16, so nearly every product is 32×32→64 bits: one instruction on a Cortex-M4 or an RV32IM
//! core, but about twenty on ARMv6-M (Cortex-M0/M0+, RP2040), whose multiplier is 32×32→32, and a
//! lit pixel makes about 85 of them, on vectors that do not fit the M0's eight low registers. This
//! kernel shades a pixel from a few scalars instead, most of them forward-differenced along the
//! row, in 15- and 16-bit fractions where a product is one `MULS`.
//!
//! # When it applies
//!
//! A frame uses it (the prepare's `NarrowView`) when every light is distant or a point light
//! of radius 0, no sphere uses Oren–Nayar or GGX, the camera is outside every sphere, and
//! the image plane is narrow enough that every primary direction is within `√2` of the
//! central one in length (a field of view up to about 90° on the diagonal). Every other frame
//! renders with the full-width kernel alone. Lambert shades as a classic sphere of diffuse
//! weight `kd·albedo/π` and no lobe; the normalized models and the point lights take stages
//! of their own (below), in a pixel loop of their own (`PRECISE`), so that the other frames'
//! loop holds none of that code. The
//! conditions are frame-wide, so a pixel's result does not depend on which spheres' spans
//! cover it (turning spans off changes no pixel).
//!
//! # How a pixel is computed
//!
//! With `d = D/2²⁹` the pixel's unnormalized primary direction (`|d|` in `[1, √2]`),
//! `ô = (eye − centre)/r` and `L` a light's unit direction, the sphere's two quadrics
//! (`NarrowSphere`, `NarrowLight`) give
//!
//! ```text
//! E′ = |d|² − |ô × d|²        the hit: E′ ≥ 0 (and the sphere in front, b = ô·d < 0)
//! G  = (ô × d)·(L × d)
//! ```
//!
//! both exact quadratics in the pixel's column on a row (their coefficients are made once
//! per frame from the integer geometry in `i128`, see `Quadric`), so each is two 64-bit
//! additions per pixel (integer forward differences: no rounding accumulates, and a pixel's
//! values do not depend on where its run or segment starts). So are `|D|²` and, per light,
//! `D·L`, exactly. From them, with `σ = 1/|d|` (a 258-entry table of `|d|²` and linear
//! interpolation, within `2⁻¹⁹`):
//!
//! ```text
//! N·V = √(E′·σ²)              N·L = G·σ² − (N·V)·(L·D̂)        L·D̂ = (d·L)·σ
//! Phong: h = 1 − R·V = 1 − 2·(N·L)(N·V) − L·D̂
//! Blinn-Phong: h = 1 − N·H = 1 − (N·L + N·V)/√(2 − 2·L·D̂)
//! ```
//!
//! since `N = D̂ × u − (N·V)·D̂` with `u = (ô × D̂)`. No vector is formed: per pixel and light
//! that is a handful of `MULS`, per pixel one table-and-interpolation square root
//! (`narrow_roots`'s `SQRT_TABLE`) and the `σ` lookup shared by every light, and `E′` keeps its
//! precision up to the silhouette, where `N·V → 0` (the closest-approach form has no
//! cancellation: `|ô × d|² ≤ |d|²` on the sphere). The normal itself is formed only where a
//! shadow ray must be tested against another sphere (`narrow_normal`).
//!
//! The sphere's own shadow needs no ray: a ray lifted by ε off the surface meets the sphere
//! again iff `N·L < 0` and `(N·L)² > 1 − r²/(r + ε)²`. Another sphere is tested only where
//! the caster filter of `NarrowLight` (from `N·L` alone) lets it, exactly as the full-width
//! kernel's shadow ray would be, from the normal. A sphere resting on another needs nothing
//! more: the test is the full-width kernel's rule for a ray that starts inside a caster too.
//!
//! A floor's pixels pass that filter nearly everywhere (`N·L` is about the same over a
//! floor), and each exact test takes a dozen 32×32→64-bit products, calls on ARMv6-M. So
//! there, on a sphere four times the radius of each of its casters, a quick test goes first
//! (`quick_casters`): the lifted point's distance from each caster's axis along the light,
//! in two coordinates across the light (`PreparedFixed::across`) from 16×16-bit products.
//! Beyond the caster's radius plus a margin that bounds both tests' rounding
//! (`NarrowSphere::quick_margin`), no ray from the point meets the caster, and the exact
//! test is skipped; it never skips one the exact test would find blocking, so no pixel
//! changes (test `the_quick_caster_test_changes_no_pixel`, and the M0's and RV32's CRCs,
//! which match the host's, where the test is off). Only ARMv6-M and RV32 take it
//! (`QUICK_CASTER_TEST`).
//!
//! # Point lights and the normalized models
//!
//! A point light at `P` is, for the quadrics, a distant light along the unit vector `q̂` from
//! the eye toward it (`NarrowPoint`): `G` and `D·q̂` give `N·q̂` and `q̂·D̂` as above, and with
//! `Q = P − eye` and the hit at `X = eye + t·D̂`, `N·(P − X) = |Q|·(N·q̂) + t·(N·V)` and
//! `(P − X)·D̂ = |Q|·(q̂·D̂) − t`, so the distance, `N·L`, `L·D̂` and `1/d²` follow without a
//! vector. [`super::narrow_point`] takes them in 15- and 16-bit fractions where their error
//! bound lets it (nearly every pixel of an ordinary scene), and `precise_light`
//! ([`super::narrow_precise`]) in 30-bit fractions from the roots of [`super::roots`]
//! elsewhere. The shadow ray starts at `X` lifted by `ε`, toward the light as seen from `X`,
//! and counts a caster only before the light; the caster mask is the full-width kernel's
//! (`Scene::shadow_casters`), and the casters' cones and a distance test from the fast `X`
//! ([`super::narrow_point_shadow`]) settle most pixels before the precise ray.
//!
//! A sphere of a normalized model shades each light with the full-width kernel's terms (the
//! lobes' weighted sum times `N·L`, Schlick's `F` per channel from `L·H = |L + V|/2`, the
//! diffuse loss): [`super::narrow_terms`] from the fast cosines where the fast lobe serves,
//! `normalized_terms` from the precise ones elsewhere.
//!
//! The shadow test toward a distant light starts with the same distance test from the fast
//! `X` (`t = r·c/(N·V + √((N·V)² + c))`, see [`super::narrow_point`]); only the casters it
//! cannot settle take the normal and the exact ray below.
//!
//! # Where the lobe needs more bits
//!
//! The fast `h` is within `H_ERROR` (`6·2⁻¹⁵`; test `fast_h_within_its_bound` measures 4.2
//! on the exponent series and 115 random frames), so the lobe `(1 − h)ⁿ`, whose slope is at
//! most `n`, is within `n·H_ERROR`. The prepare turns that into two per-sphere numbers:
//!
//! - `cutoff`: above this `h` the lobe, times `ks` and the sum of the lights' intensities,
//!   is below `2⁻¹⁷` (half a U16F16 step), even allowing for the error of `h`: the lobe is 0;
//! - `fast_lobe_max`: where the fast lobe `λ` is within half an 8-bit level. Its error is
//!   `ks·ΣI·(n·H_ERROR·(1 − h)^(n−1) + 1.4·10⁻⁴)` (the second term a bound on the narrow
//!   `pow`'s own, held on `n ≤ 256`, where it measures `5.4·10⁻⁵`; above, the precise lobe
//!   serves); the slope `n·(1 − h)^(n−1)` is at most `n`, so if `ks·ΣI·n·H_ERROR`
//!   is within budget the fast lobe serves wherever the lobe is not 0; otherwise it is at
//!   most `2n·λ` where `h ≤ ½`, so the fast lobe serves where `λ` is below the bound that
//!   makes `2n·λ·H_ERROR` fit: the tails of the highlight, not its bright part.
//!
//! A pixel below the cutoff whose fast lobe is not within that (the bright part of a narrow
//! highlight), or a Blinn-Phong pixel whose `|L + V|` is below ¾ (where the half vector is
//! ill-conditioned and the fast `h` is not within its bound), takes `precise_lobe`: the same
//! formulas in 30-bit fractions, from the same exact `|D|²`, `E′`, `G` and `D·L`, with `σ` and
//! `√E′` from [`super::roots`] instead of the tables (`h` within `2⁻²⁴`, `2⁹` times closer than
//! the fast one), and the same `pow` as the fast lobe. It forms no vector either, so the
//! narrow kernel needs none of the full-width kernel's stages. On the exponent series that is
//! under 3% of the covered pixels (test `few_pixels_take_the_precise_lobe`).
//! Every other stage is the fast one, whatever the encoding: a pixel's linear colour does not
//! depend on the encoding.
//!
//! Every step is integer arithmetic with the same bits on every target; products are
//! 16×16→32 bits (`|x| ≤ 2¹⁶` operands) except in the row's set-up, the precise lobe, the
//! normal for caster tests and the per-channel scaling by the light's colour.

use super::mul::{dot_ii, mul_u32_u16};
use super::narrow_depth::DEPTH_ORDER;
use super::narrow_hit::fast_t;
use super::narrow_lobe::{fast_h, fast_lobe, precise_lobe};
use super::narrow_roots::{sigma_of, sqrt_q30};
use super::narrow_run::{activity, first, front_part, NarrowRun, Track};
use super::narrow_scale::{high_bits, mul_u16f16, scale_q15, scale_q16, scale_signed_q16, ONE};
use super::prepare::{
    FixedLight, FixedSphere, NarrowLight, NarrowSphere, NarrowView, PreparedFixed,
};
use super::quadric::Step;
use super::vector::{each3, V3};
use crate::pixel::HitRecord;
use crate::runs::Span;

/// Bound of each component of the narrow normal (Q15) in the caster test (`narrow_blocked`),
/// `2⁻⁸` above 1. The normal is within about `2⁻¹²` of unit length on a hit, so the clamp
/// never moves a real one; it bounds the test's arithmetic whatever the normal. After the
/// prepare's scaling every point of every sphere lies within `2²⁹` raw per component, so a
/// surface point lifted by `ε` (below `2¹⁶` raw) along a normal so bounded lies within
/// `2²⁹ + 2²²`, and its offset from another sphere's centre within `2³⁰ + 2²²`.
pub(super) const NORMAL_LIMIT: i32 = ONE + (ONE >> 8);

/// What a kernel (the narrow one, or the full-width one) found for one pixel: linear colour
/// in U16F16 (saturated) and the hit record (shadowed bits only when asked for).
pub(crate) struct Shaded {
    pub color: [u32; 3],
    pub hit: HitRecord,
}

/// What the narrow kernel made of a pixel.
pub(crate) enum Narrow {
    /// The pixel: `None` for the background.
    Done(Option<Shaded>),
    /// The full-width kernel must shade this pixel (only for data the prepare did not set
    /// up, which a narrow frame does not have).
    Precise,
}

/// What the fast point light made of a light at a pixel.
#[cfg(feature = "narrow-precise")]
pub(crate) enum PointSeen {
    /// The light's diffuse and specular sums (U16F16 per channel, before `kd·albedo` and
    /// `ks`).
    Lit([u32; 3], [u32; 3]),
    /// The light's diffuse sum alone: its specular sum is 0 (a Lambert sphere, or a pixel
    /// outside the lobe's cutoff).
    Matte([u32; 3]),
    /// The sphere's own shadow.
    Blocked,
    /// The light needs the precise path at this pixel (`precise_light`).
    Precise,
    /// The light needs the precise path for its lobe at this pixel, and its shadow ray need
    /// only test these casters (a mask): the fast filters cleared the others.
    PreciseLobe(u32),
}

/// Whether the frame's shadow rows (`NarrowSphere::shadows`, feature `shadow-rows`) can skip
/// casters: without the feature every pixel tests them, and the flag folds away.
const SHADOW_ROWS: bool = cfg!(feature = "shadow-rows");

/// Whether the shadow test toward a distant light starts with the distance test from the
/// fast `X` (`PreparedFixed::distant_casters`): on ARMv6-M, where it spares most pixels the
/// normal's six 32×32→64-bit products (calls there) and shortens the exponent series' frame
/// and the floor's; on cores with a widening multiply the normal and the exact ray cost less
/// than the test (`docs/performance.md`, "Choices measured"). The crate's own tests turn it
/// on everywhere, and hold it to the exact ray's decisions.
pub(crate) const DISTANCE_TEST: bool = cfg!(any(shadeline_short_mul, test));

/// Whether `narrow_lights`' loop of unknown length (`N = 0`) holds a distant light's
/// `diffuse` and `specular` stages written out ([`distant_light!`]) rather than as the
/// inlined [`PreparedFixed::distant_light`]: on RV32, where the pixel loop then spills fewer
/// registers (the floor 1.0% fewer instructions, three-lights 0.4%); not in the one-light
/// loop, where it made RV32's exponent series 1.1% dearer, and not on the other targets,
/// where it made the M0's floor and exponent series and the M4F's lamp dearer
/// (`docs/performance.md`, "Choices measured"). The crate's own tests take the stages
/// written out, so that both forms are tested (the other by the firmware's CRCs).
const DISTANT_LIGHT_WRITTEN_OUT: bool = cfg!(any(target_arch = "riscv32", test));

/// The `diffuse` and `specular` stages of an unshadowed distant light, as
/// [`PreparedFixed::distant_light`] takes them (its arguments by the same names), into the
/// [`Sums`] `sums`: one body for the function and for the loop that holds them written out
/// ([`DISTANT_LIGHT_WRITTEN_OUT`]).
macro_rules! distant_light {
    ($frame:expr, $surface:ident, ($sphere:ident, $ns:ident), $light_index:ident,
     ($nl:ident, $ld:ident), ($d:ident, $g:ident, $dl:ident), $sums:ident) => {
        let arriving = match $frame.lights.get($light_index) {
            Some(FixedLight::Distant { arriving, .. }) => arriving.map(|c| c.to_bits()),
            _ => [0; 3],
        };
        if $nl > 0 {
            $sums.diffuse = each3(|c| $sums.diffuse[c].saturating_add(scale_q15(arriving[c], $nl)));
            $sums.lit = true;
        }
        let (h, trusted) = fast_h($sphere.blinn(), $nl, $surface.nv, $ld);
        if h < $ns.cutoff {
            let lobe = match fast_lobe($ns, $sphere.shininess, h, trusted) {
                Some(lobe) => lobe,
                None => precise_lobe(
                    $sphere.blinn(),
                    $sphere.shininess,
                    $ns,
                    $surface.e,
                    $d,
                    ($g.v, $dl.v),
                ),
            };
            $sums.specular =
                each3(|c| $sums.specular[c].saturating_add(scale_q16(arriving[c], lobe)));
            $sums.glossy = true;
        }
    };
}

/// What the shadow filters found for a point light at a pixel.
pub(crate) enum Casters {
    /// A caster blocks the ray.
    Blocked,
    /// The casters that only the precise ray can decide (a mask, bit `k` for sphere `k`).
    Left(u32),
}

/// The surface under a pixel: the sphere and its track, `E′` as held, `N·V` (Q15), and
/// `σ = 1/|d|` (Q15) with `σ²` (Q16).
#[derive(Clone, Copy)]
pub(super) struct Surface {
    pub index: usize,
    pub track: usize,
    pub e: i64,
    pub nv: i32,
    pub sigma: i32,
    pub sigma2: u32,
    /// Whether the pixel's row lies in the sphere's shadow rows (`NarrowSphere::shadows`):
    /// outside them no caster is tested.
    pub shadows: bool,
}

/// `N·L` and `L·D̂` (both Q15) at a pixel: `D·L` as the run holds it, `σ` (Q15), `σ²`
/// (Q16) and `N·V` (Q15), and `G` as held with its shift.
#[inline(always)]
pub(super) fn fast_cosines(
    dl: i64,
    (sigma, sigma2, nv): (i32, u32, i32),
    g: i64,
    g_shift: u32,
) -> (i32, i32) {
    // L·D̂ = (d·L)·σ, Q15: the high word of D·L is d·L in Q27, |d·L| ≤ |d| ≤ √2.
    let ld = ((((dl >> 32) as i32) >> 12) * sigma) >> 15;
    // G (Q29: |G| ≤ |d|² on a hit) times σ², then N·L = G·σ² − (N·V)(L·D̂), Q15.
    let g29 = high_bits(g, g_shift);
    let nl = ((scale_signed_q16(g29, sigma2) << 1) - nv * ld) >> 15;
    (nl, ld)
}

/// The surface of track `t` (at index `track`) at a hit of `E′` `e`, from `σ` and `σ²`
/// (`sigma_of`): `N·V` from `(N·V)² = E′·σ²`.
#[inline(always)]
fn track_surface<const L: usize>(
    t: &Track<L>,
    track: usize,
    e: i64,
    (sigma, sigma2): (i32, u32),
) -> Surface {
    // E′ ≤ |d|² ≤ 2 on a hit: about 2³⁰ at most in Q29.
    let e29 = (high_bits(e, u32::from(t.e_shift)) as u32).min(1 << 30);
    Surface {
        index: t.index,
        track,
        e,
        // (N·V)² = E′·σ², Q30.
        nv: sqrt_q30(scale_q16(e29 << 1, sigma2).min(1 << 30)),
        sigma,
        sigma2,
        shadows: !SHADOW_ROWS || t.shadows,
    }
}

/// The lights' sums at a pixel, as the `lights` stage adds them up: diffuse and specular
/// (U16F16 per channel, before `kd·albedo` and `ks`), whether either has a term (if not, it
/// is 0 and adds nothing), and the lights found blocked (bit `k` for light `k`, where asked).
#[derive(Default)]
struct Sums {
    diffuse: [u32; 3],
    specular: [u32; 3],
    lit: bool,
    glossy: bool,
    shadowed: u32,
}

impl Sums {
    /// Adds a light's diffuse and specular sums.
    #[inline(always)]
    #[cfg_attr(not(feature = "narrow-precise"), allow(dead_code))]
    fn add(&mut self, diffuse: [u32; 3], specular: [u32; 3]) {
        self.diffuse = each3(|c| self.diffuse[c].saturating_add(diffuse[c]));
        self.specular = each3(|c| self.specular[c].saturating_add(specular[c]));
        (self.lit, self.glossy) = (true, true);
    }

    /// Adds a light's diffuse sum, for a light whose specular sum is 0: `combine` then takes
    /// no `ks` product unless another light's lobe needs it.
    #[inline(always)]
    #[cfg_attr(not(feature = "narrow-precise"), allow(dead_code))]
    fn add_diffuse(&mut self, diffuse: [u32; 3]) {
        self.diffuse = each3(|c| self.diffuse[c].saturating_add(diffuse[c]));
        self.lit = true;
    }

    /// Records light `light_index` as blocked, if hits are recorded.
    #[inline(always)]
    fn shadow(&mut self, light_index: usize, record_hits: bool) {
        if record_hits && light_index < 32 {
            self.shadowed |= 1 << light_index;
        }
    }

    /// The `combine` stage: `kd·albedo` times the diffuse sum plus `ks` times the specular
    /// one, saturated, on sphere `index`.
    #[inline(always)]
    fn combine(&self, sphere: &FixedSphere, index: usize) -> Shaded {
        let diffuse = if self.lit {
            each3(|c| mul_u16f16(sphere.kd_albedo[c].to_bits(), self.diffuse[c]))
        } else {
            [0; 3]
        };
        Shaded {
            color: if self.glossy {
                each3(|c| {
                    let s = mul_u16f16(sphere.ks.to_bits(), self.specular[c]);
                    diffuse[c].saturating_add(s)
                })
            } else {
                diffuse
            },
            hit: HitRecord {
                sphere: Some(index as u16),
                shadowed: self.shadowed,
            },
        }
    }
}

impl<const S: usize, const L: usize> PreparedFixed<S, L> {
    /// The narrow direction of pixel `x` on row `y`. One routine on ARMv6-M, for its flash:
    /// the run set-up computes it at up to four columns.
    #[cfg_attr(not(shadeline_short_mul), inline(always))]
    #[cfg_attr(shadeline_short_mul, inline(never))]
    fn narrow_direction(view: &NarrowView, x: u32, y: u32, width: u32, height: u32) -> V3<i32> {
        let dy = height as i32 - 2 * y as i32 - 1;
        let dx = 2 * x as i32 + 1 - width as i32;
        each3(|i| view.forward[i] + dy * view.step_y[i] + dx * view.step_x[i])
    }

    /// Sets `run` to the narrow state at the first pixel `x` of a run on row `y` that ends
    /// before column `end`, in place; `false` (and `run` unchanged) if the frame does not use
    /// the narrow kernel. In place because a run holds a track per sphere, which a returned
    /// value would cost a `memcpy` or two per run. Only the spheres whose span meets the run
    /// get a track, each with its quadrics at its span's first column (`Quadric::row`,
    /// `Quadric::step_at_cell`: a handful of 64-bit products per track and light).
    /// Not inlined: once per run, and apart from the pixel loop's registers.
    #[inline(never)]
    pub(crate) fn narrow_run(
        &self,
        run: &mut NarrowRun<S, L>,
        x: u32,
        end: u32,
        y: u32,
        spans: &[Option<Span>],
    ) -> bool {
        let Some(view) = self.narrow.as_ref() else {
            return false;
        };
        run.tracks.clear();
        let dy = self.height as i32 - 2 * y as i32 - 1;
        let spheres = self.spheres.iter().zip(spans).zip(&self.narrow_lights);
        for (index, ((s, span), lights)) in spheres.enumerate() {
            let (Some(span), Some(n)) = (span, s.narrow.as_ref()) else {
                continue;
            };
            if span.end <= x || end <= span.start {
                continue;
            }
            let oc = s.eye_offset.map(|c| c.to_bits());
            let b_at = |column| {
                dot_ii(
                    oc,
                    Self::narrow_direction(view, column, y, self.width, self.height),
                )
            };
            let Some(span) = front_part(x.max(span.start), span.end, n.b_rises, b_at) else {
                continue;
            };
            let (y_offset, x_offset) = (dy, 2 * span.start as i32 + 1 - self.width as i32);
            let mut g = [Step::default(); L];
            for (g, light) in g.iter_mut().zip(lights).take(self.lights.len()) {
                *g = light.g.step_at_cell(y_offset, x_offset);
            }
            let (first, end) = n.shadows;
            let track = Track {
                index,
                #[cfg(feature = "depth-order")]
                rank: self.depth_rank.get(index).copied().unwrap_or(0),
                span,
                e: n.e.step_at_cell(y_offset, x_offset),
                e_shift: u16::from(n.e_shift),
                shadows: u32::from(first) <= y && y < u32::from(end),
                g,
            };
            // As many tracks as spheres: cannot fail.
            let pushed = run.tracks.push(track);
            debug_assert!(pushed.is_ok());
        }
        (run.active, run.changes_at) = activity(&run.tracks, x);
        run.x = x;
        let d = Self::narrow_direction(view, x, y, self.width, self.height);
        let step = view.step_x.map(|c| 2 * c);
        // |D + k·S|² = |D|² + k·2D·S + k²|S|²: the step from k to k + 1 is 2D·S + (2k + 1)|S|².
        let ss = dot_ii(step, step);
        run.a = Step {
            v: dot_ii(d, d),
            d: 2 * dot_ii(d, step) + ss,
            dd: 2 * ss,
        };
        for ((dl, light), point) in run.dl.iter_mut().zip(&self.lights).zip(&self.points) {
            let l = match light {
                FixedLight::Distant { to_light, .. } => to_light.map(|c| c.to_bits()),
                FixedLight::Point { .. } => point.dir,
                #[allow(unreachable_patterns)]
                _ => return false,
            };
            *dl = Step {
                v: dot_ii(d, l),
                d: dot_ii(step, l),
                dd: 0,
            };
        }
        run.d = d;
        run.step = step;
        true
    }

    /// Shades the run's current pixel with the narrow kernel and moves the run one pixel
    /// right. `single` is the run's only active track while there is one (see
    /// [`NarrowRun::single`]), which spares the search for the nearest hit; the caller then
    /// stops at the column `single` gave and calls [`NarrowRun::refresh`].
    ///
    /// `N`: the frame's number of lights if it is known where the pixel loop is compiled
    /// (see [`Self::light_count`]), so that the loops over lights have a fixed length.
    /// `PRECISE`: whether the frame has point lights or normalized spheres, which take the
    /// precise cosines (`precise_light`); without it that code is not in the loop.
    #[inline(always)]
    pub(crate) fn narrow_shade<const N: usize, const PRECISE: bool>(
        &self,
        run: &mut NarrowRun<S, L>,
        single: Option<usize>,
        record_hits: bool,
    ) -> Narrow {
        let lights = self.light_count::<N>();
        let surface = match single {
            Some(track) => self.single_surface(run, track),
            None => self.narrow_surface(run),
        };
        // On ARMv6-M the surface is matched by reference: moved into a tuple with its track,
        // it is copied through a `memcpy` call per pixel there (the bytes after its flag).
        // Elsewhere the move is cheaper than the reference (`docs/performance.md`).
        #[cfg(shadeline_short_mul)]
        let shaded = match (
            &surface,
            surface.as_ref().and_then(|s| run.tracks.get(s.track)),
        ) {
            (Some(surface), Some(t)) => {
                self.narrow_lights::<N, PRECISE>(surface, &t.g, (run.d, &run.dl), record_hits)
            }
            _ => Narrow::Done(None),
        };
        #[cfg(not(shadeline_short_mul))]
        let shaded = match surface.and_then(|s| Some((s, run.tracks.get(s.track)?))) {
            Some((surface, t)) => {
                self.narrow_lights::<N, PRECISE>(&surface, &t.g, (run.d, &run.dl), record_hits)
            }
            None => Narrow::Done(None),
        };
        match single {
            Some(track) => {
                // The track's G, one pixel right (its E′ moved where it was read).
                if let Some(t) = run.tracks.get_mut(track) {
                    for g in first(&mut t.g, lights) {
                        g.v = g.v.wrapping_add(g.d);
                        g.d = g.d.wrapping_add(g.dd);
                    }
                }
                run.advance(lights);
                run.x += 1;
            }
            None => self.narrow_step(run, lights),
        }
        shaded
    }

    /// The number of lights: `N` if it is not 0, the frame's own count otherwise.
    #[inline(always)]
    pub(crate) fn light_count<const N: usize>(&self) -> usize {
        if N > 0 {
            N
        } else {
            self.lights.len()
        }
    }

    /// Moves `run` one pixel to the right after a pixel of several active tracks: each
    /// active track's `G` (its `E′` moved in the hit loop), the direction, and the set of
    /// active tracks where a span begins or ends.
    fn narrow_step(&self, run: &mut NarrowRun<S, L>, lights: usize) {
        for &i in &run.active {
            if let Some(t) = run.tracks.get_mut(i as usize) {
                for g in first(&mut t.g, lights) {
                    g.v = g.v.wrapping_add(g.d);
                    g.d = g.d.wrapping_add(g.dd);
                }
            }
        }
        run.advance(lights);
        run.x += 1;
        run.refresh();
    }

    /// The `hit` and `normal` stages where `track` is the only active track: its `E′`, moved
    /// one pixel right where it is read.
    #[inline(always)]
    fn single_surface(&self, run: &mut NarrowRun<S, L>, track: usize) -> Option<Surface> {
        let t = run.tracks.get_mut(track)?;
        let e = t.e.v;
        t.e.v = e.wrapping_add(t.e.d);
        t.e.d = t.e.d.wrapping_add(t.e.dd);
        if e < 0 {
            return None;
        }
        Some(track_surface(t, track, e, sigma_of(run.a.v)))
    }

    /// The `hit` and `normal` stages: the nearest sphere under the run's current pixel, with
    /// `N·V`; `None` for the background. Each active track's `E′` moves one pixel right
    /// where the loop reads it. Where two or more tracks hit, in a frame in depth order the
    /// first in that order wins ([`super::narrow_depth`]), and only its `N·V` is computed;
    /// otherwise their `t` are compared, the first hit winning a tie. A lone hit needs no
    /// `t` (such as a sphere's span corners over a floor).
    /// Out of line (only where spans overlap), except on ARMv6-M: there, inlined into the
    /// pixel loop, the loop is both smaller and faster; on the M4F and RV32 inlining costs
    /// instructions (`docs/performance.md, "Choices measured"`).
    #[cfg_attr(shadeline_short_mul, inline(always))]
    #[cfg_attr(not(shadeline_short_mul), inline(never))]
    fn narrow_surface(&self, run: &mut NarrowRun<S, L>) -> Option<Surface> {
        let sigmas = sigma_of(run.a.v);
        // The nearest hit so far, and its `t` once a second hit needs it (`i64::MAX` before:
        // a hit's `t` is below 2⁴⁸).
        let mut best: Option<Surface> = None;
        let mut nearest = i64::MAX;
        // In depth order: the rank of the frontmost hit so far.
        let mut front = u8::MAX;
        for &i in &run.active {
            let t = run.tracks.get_mut(i as usize);
            debug_assert!(t.is_some(), "track {i} of {}", run.tracks.len());
            let Some(t) = t else {
                continue;
            };
            debug_assert!(t.span.start <= run.x && run.x < t.span.end);
            let e = t.e.v;
            t.e.v = e.wrapping_add(t.e.d);
            t.e.d = t.e.d.wrapping_add(t.e.dd);
            if e < 0 {
                continue;
            }
            if DEPTH_ORDER && self.depth_ordered {
                if t.rank() >= front {
                    continue;
                }
                front = t.rank();
            }
            let surface = track_surface(t, i as usize, e, sigmas);
            // In depth order `best` is `None` here (the active tracks are in rank order, so
            // a later hit has a later rank); the flag is tested all the same, which the
            // pixel loops of every target compile to fewer instructions (`docs/performance.md`,
            // "Choices measured").
            if let (false, Some(first)) = (DEPTH_ORDER && self.depth_ordered, &best) {
                if nearest == i64::MAX {
                    nearest = self.narrow_t(first, run.d);
                }
                let t = self.narrow_t(&surface, run.d);
                if t >= nearest {
                    continue;
                }
                nearest = t;
            }
            best = Some(surface);
        }
        best
    }

    /// The `lights` and `combine` stages at `surface` (under the run's current pixel).
    #[inline(always)]
    fn narrow_lights<const N: usize, const PRECISE: bool>(
        &self,
        surface: &Surface,
        g: &[Step; L],
        (d, dl): (V3<i32>, &[Step; L]),
        record_hits: bool,
    ) -> Narrow {
        let index = surface.index;
        debug_assert!(index < self.spheres.len(), "hit on sphere {index}");
        let (Some(sphere), Some(lights)) = (self.spheres.get(index), self.narrow_lights.get(index))
        else {
            return Narrow::Done(None);
        };
        let Some(ns) = sphere.narrow.as_ref() else {
            return Narrow::Precise;
        };
        let mut sums = Sums::default();
        // The normal, for caster tests: made at the first that needs it.
        let mut normal: Option<V3<i32>> = None;
        // Indexed, not zipped: the bound `n ≤ L` lets every index go unchecked, where three
        // zipped iterators cost the M4F's pixel loop instructions.
        let n = self.light_count::<N>().min(L);
        for light_index in 0..n {
            let (light, g, dl) = (&lights[light_index], &g[light_index], &dl[light_index]);
            // Only in the frames with a point light or a normalized sphere: the others' loop
            // holds none of this (their registers are the fast path's).
            #[cfg(feature = "narrow-precise")]
            if PRECISE {
                let point = matches!(self.lights.get(light_index), Some(FixedLight::Point { .. }));
                if point || ns.terms {
                    let seen = self.point_or_terms_light(
                        surface,
                        (sphere, ns, light),
                        (light_index, point),
                        d,
                        (g.v, dl.v),
                    );
                    match seen {
                        PointSeen::Lit(dif, spec) => sums.add(dif, spec),
                        PointSeen::Matte(dif) => sums.add_diffuse(dif),
                        _ => sums.shadow(light_index, record_hits),
                    }
                    continue;
                }
            }
            let (nl, ld) = fast_cosines(
                dl.v,
                (surface.sigma, surface.sigma2, surface.nv),
                g.v,
                ns.g_shift as u32,
            );
            let at = (light_index, light);
            if self.distant_shadowed(surface, (sphere, ns), at, (nl, d), &mut normal) {
                sums.shadow(light_index, record_hits);
                continue;
            }
            if DISTANT_LIGHT_WRITTEN_OUT && N == 0 {
                distant_light!(
                    self,
                    surface,
                    (sphere, ns),
                    light_index,
                    (nl, ld),
                    (d, g, dl),
                    sums
                );
            } else {
                self.distant_light(
                    surface,
                    (sphere, ns),
                    light_index,
                    (nl, ld),
                    (d, g, dl),
                    &mut sums,
                );
            }
        }
        Narrow::Done(Some(sums.combine(sphere, index)))
    }

    /// The `shadow` stage of a distant light at `surface`, whose fast `N·L` is `nl`: the
    /// sphere's own shadow, then the casters the filter of `light` (the sphere's constants for
    /// light `light_index`) lets through, by the distance test where it serves
    /// ([`DISTANCE_TEST`]) and the exact ray from the normal (made once per pixel, in
    /// `normal`) for those it leaves.
    #[inline(always)]
    pub(super) fn distant_shadowed(
        &self,
        surface: &Surface,
        (sphere, ns): (&FixedSphere, &NarrowSphere),
        (light_index, light): (usize, &NarrowLight),
        (nl, d): (i32, V3<i32>),
        normal: &mut Option<V3<i32>>,
    ) -> bool {
        let Surface {
            index, nv, sigma, ..
        } = *surface;
        let mut blocked = ns.self_shadowed(nl);
        #[cfg(test)]
        if !blocked {
            let n = self.narrow_normal(sphere, ns, d, sigma, nv);
            self.assert_separated_clear(index, n, light_index, light);
        }
        if !blocked && light.casters_may_block(nl) {
            let got = if !surface.shadows {
                Casters::Left(0)
            } else if DISTANCE_TEST {
                self.distant_casters(light_index, light.casters, (fast_t(ns, nv), d, sigma))
            } else {
                Casters::Left(light.casters)
            };
            blocked = match got {
                Casters::Blocked => true,
                Casters::Left(0) => false,
                Casters::Left(left) => {
                    let n = match normal {
                        Some(n) => *n,
                        None => *normal.insert(self.narrow_normal(sphere, ns, d, sigma, nv)),
                    };
                    self.narrow_blocked(index, n, light_index, left)
                }
            };
            #[cfg(test)]
            {
                let n = self.narrow_normal(sphere, ns, d, sigma, nv);
                let exact = self.narrow_blocked(index, n, light_index, light.casters);
                assert_eq!(blocked, exact, "the distance test disagrees with the ray");
            }
        }
        blocked
    }

    /// The `diffuse` and `specular` stages of an unshadowed distant light at `surface`, from
    /// its fast `N·L` and `L·D̂`, into `sums`: the fast lobe where it serves, the precise one
    /// elsewhere, nothing above the sphere's cutoff.
    #[inline(always)]
    fn distant_light(
        &self,
        surface: &Surface,
        (sphere, ns): (&FixedSphere, &NarrowSphere),
        light_index: usize,
        (nl, ld): (i32, i32),
        (d, g, dl): (V3<i32>, &Step, &Step),
        sums: &mut Sums,
    ) {
        distant_light!(
            self,
            surface,
            (sphere, ns),
            light_index,
            (nl, ld),
            (d, g, dl),
            sums
        );
    }

    /// `t` of a hit in raw I16F16 on the narrow direction `d`, for choosing the nearer of
    /// two: `−b/|D| − r·(N·V)`. Only pixels where spans overlap need it. On ARMv6-M, whose
    /// 64-bit products are calls of shared routines, it is out of line: smaller there.
    #[cfg_attr(shadeline_short_mul, inline(never))]
    #[cfg_attr(not(shadeline_short_mul), inline(always))]
    fn narrow_t(&self, hit: &Surface, d: V3<i32>) -> i64 {
        let sphere = self.spheres.get(hit.index);
        let radius = sphere.map_or(0, |s| s.radius.to_bits() as u32);
        let b = sphere.map_or(0, |s| dot_ii(s.eye_offset.map(|c| c.to_bits()), d));
        // −b·σ/2⁴⁴ (1/|D| is σ/2⁴⁴): on a hit −2⁶¹ < b < 0, so (−b) >> 30 fits 31 bits; σ
        // and N·V (Q15) fit 16 bits.
        let along = (mul_u32_u16(((-b) >> 30) as u32, hit.sigma as u32) >> 14) as i64;
        along - (mul_u32_u16(radius, hit.nv as u32) >> 15) as i64
    }
}

#[cfg(test)]
pub(super) mod tests {
    use super::*;
    use crate::fixed::exact::Exact;
    use crate::fixed::narrow_lobe::{narrow_lobe, precise_h};
    use crate::test_scenes::uniform;

    extern crate std;
    use crate::runs::merge_runs;
    use std::vec::Vec;

    /// A narrow surface with what the light stage reads: the direction and each light's `G`.
    pub(crate) struct Seen {
        pub surface: Surface,
        pub d: V3<i32>,
        pub g: [Step; 8],
        pub dl: [Step; 8],
    }

    /// Every narrow surface of `frame`, through the general (several-track) path.
    pub(crate) fn surfaces(frame: &PreparedFixed<16, 8>) -> Vec<Seen> {
        let mut out = Vec::new();
        for y in 0..frame.height {
            let spans = frame.row_spans(y);
            for run in merge_runs::<16>(&spans) {
                let mut state = NarrowRun::new();
                assert!(frame.narrow_run(&mut state, run.start, run.end, y, &spans));
                for _ in run.start..run.end {
                    let (d, dl) = (state.d, state.dl);
                    if let Some(surface) = frame.narrow_surface(&mut state) {
                        let g = state.tracks[surface.track].g;
                        out.push(Seen { surface, d, g, dl });
                    }
                    frame.narrow_step(&mut state, frame.lights.len());
                }
            }
        }
        out
    }

    /// The exact cosines of a narrow ray's hit, in `f64`: `(N·L, N·V, L·D̂)` per light.
    fn exact_cosines(frame: &PreparedFixed<16, 8>, seen: &Seen) -> Option<Vec<(f64, f64, f64)>> {
        let s = &frame.spheres[seen.surface.index];
        let d = seen.d.map(|c| c as f64);
        let len = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
        let dh = d.map(|c| c / len);
        let oc = s.eye_offset.map(|c| c.to_bits() as f64);
        let r = (s.radius_sq.to_bits() as f64).sqrt();
        let b = oc[0] * dh[0] + oc[1] * dh[1] + oc[2] * dh[2];
        let disc = b * b - (oc[0] * oc[0] + oc[1] * oc[1] + oc[2] * oc[2]) + r * r;
        if disc < 0.0 {
            return None; // a silhouette pixel the narrow test rounds inside
        }
        let t = -b - disc.sqrt();
        let n = each3(|i| (oc[i] + t * dh[i]) / r);
        let nv = -(n[0] * dh[0] + n[1] * dh[1] + n[2] * dh[2]);
        Some(
            frame
                .lights
                .iter()
                .map(|l| {
                    let FixedLight::Distant { to_light, .. } = l else {
                        panic!("a narrow frame has distant lights only");
                    };
                    let l = to_light.map(|c| c.to_bits() as f64 / (1u64 << 30) as f64);
                    let nl = n[0] * l[0] + n[1] * l[1] + n[2] * l[2];
                    let ld = l[0] * dh[0] + l[1] * dh[1] + l[2] * dh[2];
                    (nl, nv, ld)
                })
                .collect(),
        )
    }

    /// Random narrow frames (one to three distant lights, up to six Phong and Blinn-Phong
    /// spheres that may overlap and shadow each other), from `seed`.
    fn random_frames(seed: u64, count: usize) -> Vec<PreparedFixed<16, 8>> {
        use crate::test_scenes::random_classic_scene;
        let mut next = uniform(seed);
        let draw = crate::test_scenes::NARROW_DRAW;
        let mut out = Vec::new();
        for _ in 0..count {
            let scene = random_classic_scene::<16, 8>(&mut next, &draw);
            if let Ok(frame) = PreparedFixed::new(&scene, 96, 72) {
                if frame.narrow.is_some() {
                    out.push(frame);
                }
            }
        }
        out
    }

    /// The fast `N·L` and `h` against the exact ones at every narrow surface of the
    /// exponent series and of random narrow frames: `h` within [`H_ERROR`] (which the
    /// prepare's cutoff and lobe test rely on), `N·L` within `8·2⁻¹⁵`.
    #[test]
    fn fast_h_within_its_bound() {
        use crate::fixed::narrow_prepare::H_ERROR;
        let mut frames = random_frames(0x853c_49e6_748f_ea9b, 200);
        frames.push(PreparedFixed::new(&crate::exponent_series().unwrap(), 320, 240).unwrap());
        let (mut worst_h, mut worst_nl, mut count) = (0.0f64, 0.0f64, 0usize);
        let mut by = [0.0f64; 16];
        let mut untrusted = 0usize;
        for frame in &frames {
            for seen in surfaces(frame) {
                let Some(exact) = exact_cosines(frame, &seen) else {
                    continue;
                };
                let Surface {
                    index,
                    nv,
                    sigma,
                    sigma2,
                    ..
                } = seen.surface;
                let sphere = &frame.spheres[index];
                let ns = sphere.narrow.as_ref().unwrap();
                for (k, &(nl_x, nv_x, ld_x)) in exact.iter().enumerate() {
                    let (nl, ld) = fast_cosines(
                        seen.dl[k].v,
                        (sigma, sigma2, nv),
                        seen.g[k].v,
                        ns.g_shift as u32,
                    );
                    worst_nl = worst_nl.max((nl as f64 / 32768.0 - nl_x).abs());
                    let h_x = if sphere.blinn {
                        let len = (2.0 - 2.0 * ld_x).sqrt();
                        if len < 1e-3 {
                            continue;
                        }
                        1.0 - (nl_x + nv_x) / len
                    } else {
                        1.0 - 2.0 * nl_x * nv_x - ld_x
                    };
                    let (h, trusted) = fast_h(sphere.blinn, nl, nv, ld);
                    if !trusted {
                        // Only where the half vector is ill-conditioned, and then the lobe
                        // is never dropped.
                        assert!(2.0 - 2.0 * ld_x < 0.6, "|L + V|² = {}", 2.0 - 2.0 * ld_x);
                        assert!(h == 0 || nl_x + nv_x <= 1e-3, "dropped a lobe");
                        untrusted += 1;
                        continue;
                    }
                    // Only h < 1 matters (the lobe is 0 from there on, and h saturates).
                    if h_x < 1.0 {
                        let h = h as f64 / (1u64 << 31) as f64;
                        let err = (h - h_x.max(0.0)).abs();
                        let key = if sphere.blinn {
                            1 + ((2.0 - 2.0 * ld_x).sqrt() * 4.0) as usize
                        } else {
                            0
                        };
                        if err > by[key] {
                            by[key] = err;
                        }
                        worst_h = worst_h.max(err);
                        count += 1;
                    }
                }
            }
        }
        std::println!(
            "{count} lit terms in {} frames: |Δh| ≤ {:.2}, |Δ(N·L)| ≤ {:.2} steps of 2⁻¹⁵ \
             (H_ERROR is {} steps)",
            frames.len(),
            worst_h * 32768.0,
            worst_nl * 32768.0,
            H_ERROR * 32768.0
        );
        std::println!(
            "largest |Δh| in steps, Phong then Blinn-Phong by |L + V| in quarters: {:?}; \
             {untrusted} Blinn-Phong terms left to the precise h",
            by.map(|e| (e * 32768.0 * 10.0).round() / 10.0)
        );
        assert!(count > 20_000, "{count} terms");
        assert!(worst_h <= H_ERROR as f64, "h off by {worst_h}");
        assert!(worst_nl <= 8.0 / 32768.0, "N·L off by {worst_nl}");
    }

    /// The precise `h` against the exact one at every narrow surface and light of the
    /// exponent series and of random narrow frames (Phong and Blinn-Phong): within `2⁻²⁴`,
    /// and for Blinn-Phong within `2⁻²⁴/|L + V|` (the half vector's conditioning), where
    /// `h < 1` (from 1 on the lobe is 0). The largest errors are at Blinn-Phong terms far
    /// from the highlight (`h` above ½) on spheres several radii from the eye.
    #[test]
    fn precise_h_within_its_bound() {
        let mut frames = random_frames(0x2f69_3c4d_91e5_a7b3, 200);
        frames.push(PreparedFixed::new(&crate::exponent_series().unwrap(), 320, 240).unwrap());
        let (mut worst, mut count, mut blinn) = (0.0f64, 0usize, 0usize);
        for frame in &frames {
            for seen in surfaces(frame) {
                let Some(exact) = exact_cosines(frame, &seen) else {
                    continue;
                };
                let sphere = &frame.spheres[seen.surface.index];
                let ns = sphere.narrow.as_ref().unwrap();
                for (k, &(nl_x, nv_x, ld_x)) in exact.iter().enumerate() {
                    let len = (2.0 - 2.0 * ld_x).max(0.0).sqrt();
                    let h_x = if sphere.blinn {
                        if len < 1e-3 {
                            continue;
                        }
                        1.0 - (nl_x + nv_x) / len
                    } else {
                        1.0 - 2.0 * nl_x * nv_x - ld_x
                    };
                    if h_x >= 1.0 {
                        continue;
                    }
                    let terms = (seen.g[k].v, seen.dl[k].v);
                    let h = precise_h(sphere.blinn, ns, seen.surface.e, seen.d, terms)
                        .expect("a half vector where |L + V| > 0");
                    let h = h as f64 / (1u64 << 61) as f64;
                    let weight = if sphere.blinn { len.min(1.0) } else { 1.0 };
                    worst = worst.max((h - h_x.max(0.0)).abs() * weight);
                    count += 1;
                    blinn += sphere.blinn as usize;
                }
            }
        }
        std::println!(
            "{count} lit terms ({blinn} Blinn-Phong): |Δh| ≤ {:.2} steps of 2⁻³⁰",
            worst * (1u64 << 30) as f64
        );
        assert!(
            count > 50_000 && blinn > 5_000,
            "{count} terms, {blinn} Blinn-Phong"
        );
        assert!(worst <= 1.0 / (1u64 << 24) as f64, "h off by {worst}");
    }

    #[test]
    fn spheres_resting_on_a_floor_agree_with_the_reference() {
        let mut next = uniform(0x003e_d9e5);
        floors_agree_with_the_reference(|| crate::test_scenes::random_floor_scene(&mut next));
    }

    #[test]
    fn floors_under_point_lights_agree_with_the_reference() {
        let mut next = uniform(0x1a3b_5c7d);
        floors_agree_with_the_reference(|| crate::test_scenes::random_lamp_scene(&mut next));
    }

    /// Sixteen frames of `draw` at 160×120 take the narrow kernel and agree with the
    /// reference: within 2 levels, ray decisions differing on at most 0.1% of the pixels, and
    /// over 5% of the pixels shadowed (so the shadows are tested).
    fn floors_agree_with_the_reference(mut draw: impl FnMut() -> crate::Scene<8, 4>) {
        use crate::reference::{quantize, render_frame, RefPixel};
        use crate::Render;
        let (w, h) = (160u32, 120u32);
        let (mut pixels, mut differ, mut shadowed, mut worst) = (0, 0, 0, 0);
        let mut within_one = 0;
        for i in 0..16 {
            let scene = draw();
            let frame = PreparedFixed::<8, 4>::new(&scene, w, h).unwrap();
            assert!(frame.narrow.is_some(), "scene {i} takes the narrow kernel");
            let mut reference = std::vec![RefPixel::default(); (w * h) as usize];
            render_frame(&scene, w, h, &mut reference).unwrap();
            let mut colors = std::vec![crate::Rgb888::default(); w as usize];
            let mut hits = std::vec![HitRecord::default(); w as usize];
            for y in 0..h {
                frame.render_line(y, &mut colors).unwrap();
                frame.render_line(y, &mut hits).unwrap();
                let want = &reference[(y * w) as usize..((y + 1) * w) as usize];
                for ((c, hit), want) in colors.iter().zip(&hits).zip(want) {
                    pixels += 1;
                    shadowed += usize::from(want.hit.shadowed != 0);
                    if *hit != want.hit {
                        differ += 1;
                        continue;
                    }
                    let mut off = 0;
                    for (got, c) in [c.r, c.g, c.b].into_iter().zip(want.color) {
                        let level = quantize(c, 255.0) as i32;
                        off = off.max((got as i32 - level).abs());
                    }
                    worst = worst.max(off);
                    within_one += usize::from(off <= 1);
                }
            }
        }
        std::println!(
            "{pixels} pixels, {shadowed} shadowed, {differ} decisions differ, worst {worst}, \
             {within_one} within 1"
        );
        assert!(
            within_one * 100 >= (pixels - differ) * 99,
            "{within_one} within 1"
        );
        // Shadows of spheres on the floor and of the floor on them, at every contact.
        assert!(shadowed > pixels / 20, "{shadowed} shadowed of {pixels}");
        assert!(
            differ * 1000 <= pixels,
            "{differ} of {pixels} decisions differ"
        );
        assert!(worst <= 2, "{worst} levels");
    }

    #[test]
    fn few_pixels_take_the_precise_lobe() {
        let scene = crate::exponent_series().unwrap();
        let frame = PreparedFixed::<16, 8>::new(&scene, 320, 240).unwrap();
        let all = surfaces(&frame);
        let precise = all
            .iter()
            .filter(|seen| {
                let Surface {
                    index,
                    nv,
                    sigma,
                    sigma2,
                    ..
                } = seen.surface;
                let sphere = &frame.spheres[index];
                let ns = sphere.narrow.as_ref().unwrap();
                let (nl, ld) = fast_cosines(
                    seen.dl[0].v,
                    (sigma, sigma2, nv),
                    seen.g[0].v,
                    ns.g_shift as u32,
                );
                let (h, trusted) = fast_h(sphere.blinn, nl, nv, ld);
                h < ns.cutoff && fast_lobe(ns, sphere.shininess, h, trusted).is_none()
            })
            .count();
        std::println!(
            "of {} covered pixels, {precise} take the precise lobe",
            all.len()
        );
        assert!(all.len() > 11_000);
        assert!(
            (precise as f64) < 0.03 * all.len() as f64,
            "{precise} precise lobes"
        );
    }

    /// The one-track loop and the general one shade every pixel of a frame the same: the
    /// exponent series (one track at nearly every column) and random frames whose spheres
    /// overlap on screen.
    #[test]
    fn one_track_loop_matches_the_general_one() {
        let mut frames = random_frames(0xda94_2042_e4dd_58b5, 40);
        frames.push(PreparedFixed::new(&crate::exponent_series().unwrap(), 320, 240).unwrap());
        let mut single = 0usize;
        for frame in &frames {
            for y in 0..frame.height {
                let spans = frame.row_spans(y);
                for run in merge_runs::<16>(&spans) {
                    let (mut a, mut b) = (NarrowRun::new(), NarrowRun::new());
                    assert!(frame.narrow_run(&mut a, run.start, run.end, y, &spans));
                    assert!(frame.narrow_run(&mut b, run.start, run.end, y, &spans));
                    for _ in run.start..run.end {
                        let general = frame.narrow_shade::<0, true>(&mut a, None, true);
                        let fast = match b.single() {
                            Some((track, _)) => {
                                single += 1;
                                let shaded =
                                    frame.narrow_shade::<0, true>(&mut b, Some(track), true);
                                b.refresh();
                                shaded
                            }
                            None => frame.narrow_shade::<0, true>(&mut b, None, true),
                        };
                        let key = |n: Narrow| match n {
                            Narrow::Done(s) => Some(s.map(|s| (s.color, s.hit))),
                            Narrow::Precise => None,
                        };
                        assert_eq!(key(general), key(fast), "row {y}");
                    }
                }
            }
        }
        assert!(
            single > 20_000,
            "{single} pixels through the one-track loop"
        );
    }

    /// Random frames the narrow kernel takes against the `f64` reference: the fixed path's
    /// budget, and most frames must use the kernel.
    #[test]
    fn random_narrow_frames_within_budget() {
        use crate::reference::{self, RefPixel};
        use crate::test_scenes::{random_classic_scene, Draw};
        use crate::vec3::Vec3;
        use crate::{HitRecord, Render, Rgb888};
        let mut next = uniform(0x2545_f491_4f6c_dd1du64);
        let (w, h) = (160u32, 120u32);
        let (mut narrow_frames, mut worst, mut differ) = (0, 0u16, 0usize);
        let (mut pixels, mut within_one) = (0usize, 0usize);
        let draw = Draw {
            half_extent: Vec3::new(3.0, 2.0, 3.0),
            radius: (0.3, 1.5),
            varied: true,
        };
        for _ in 0..24 {
            let scene = random_classic_scene::<8, 4>(&mut next, &draw);
            let Ok(frame) = PreparedFixed::new(&scene, w, h) else {
                continue;
            };
            narrow_frames += frame.narrow.is_some() as usize;
            let mut want = std::vec![RefPixel::default(); (w * h) as usize];
            reference::render_frame(&scene, w, h, &mut want).unwrap();
            let mut colors = std::vec![Rgb888::default(); (w * h) as usize];
            let mut hits = std::vec![HitRecord::default(); (w * h) as usize];
            frame.render_frame(&mut colors).unwrap();
            frame.render_frame(&mut hits).unwrap();
            let mut frame_differ = 0;
            for ((c, hit), want) in colors.iter().zip(&hits).zip(&want) {
                pixels += 1;
                if *hit != want.hit {
                    frame_differ += 1;
                    continue;
                }
                let levels = [c.r, c.g, c.b]
                    .iter()
                    .zip(want.color)
                    .map(|(&g, v)| (g as i32 - reference::quantize(v, 255.0) as i32).unsigned_abs())
                    .max()
                    .unwrap_or(0) as u16;
                worst = worst.max(levels);
                within_one += (levels <= 1) as usize;
            }
            assert!(
                frame_differ * 1000 <= (w * h) as usize,
                "{frame_differ} decisions differ"
            );
            differ += frame_differ;
        }
        std::println!(
            "{narrow_frames} of 24 frames narrow; max {worst} levels, {:.3}% within 1, {differ} decisions differ",
            100.0 * within_one as f64 / (pixels - differ) as f64
        );
        assert!(
            narrow_frames >= 10,
            "only {narrow_frames} frames use the narrow kernel"
        );
        assert!(worst <= 2, "{worst} levels");
        assert!(within_one as f64 >= 0.99 * (pixels - differ) as f64);
    }

    /// [`narrow_lobe`] against `f64` `powf` of the same `h`, over the fast path's exponents
    /// and the precise path's (up to `10⁴`, the top of the range the fixed budget is held
    /// on, and `10⁶`, the largest), `h` dense near 0, where a large `n`'s lobe lives, and
    /// across `(0, 1)`. Printed with `-- --nocapture`, per `n`.
    #[test]
    fn narrow_lobe_matches_powf() {
        for n in [
            0.5f32, 1.0, 2.0, 7.5, 10.0, 50.0, 100.0, 256.0, 1250.0, 10_000.0, 1e6,
        ] {
            let exact = Exact::from_f32(n);
            let mut worst = (0.0f64, 0.0);
            for k in 0..40_000u64 {
                let h = if k < 20_000 {
                    // Cubic spacing, h = (k/20 000)³·2⁻⁴, and a few Q31 units more.
                    ((k * k * k) as f64 / 8e12 * (1u64 << 27) as f64) as u32 + (k as u32 & 3)
                } else {
                    ((k - 20_000) * (1 << 31) / 20_000) as u32
                };
                let got = narrow_lobe(h, exact) as f64 / 65536.0;
                let want = (1.0 - h as f64 / (1u64 << 31) as f64).powf(n as f64);
                let err = (got - want).abs();
                if err > worst.0 {
                    worst = (err, h as f64 / (1u64 << 31) as f64);
                }
            }
            std::println!(
                "narrow lobe, n = {n}: max abs error {:.2e} (at h = {:.3e})",
                worst.0,
                worst.1
            );
            // Up to n = 10⁴ the lobe's own arithmetic (5·10⁻⁵, about three U1F16 steps);
            // beyond, `g`'s last bit (`2⁻²⁷`) times n, as for `h`'s.
            let bound = if n > 1e4 { 1e-2 } else { 8e-5 };
            assert!(worst.0 < bound, "n = {n}: {worst:?}");
        }
    }

    /// The hit records of frame `a` at `w × h` if `b` renders the same colours (8-bit) and
    /// hit records, `None` otherwise.
    fn same_frames<const S: usize, const L: usize>(
        a: &PreparedFixed<S, L>,
        b: &PreparedFixed<S, L>,
        (w, h): (u32, u32),
    ) -> Option<Vec<crate::HitRecord>> {
        use crate::{HitRecord, Render, Rgb888};
        let mut ca = std::vec![Rgb888::default(); (w * h) as usize];
        let mut cb = ca.clone();
        a.render_frame(&mut ca).unwrap();
        b.render_frame(&mut cb).unwrap();
        let mut ha = std::vec![HitRecord::default(); (w * h) as usize];
        let mut hb = ha.clone();
        a.render_frame(&mut ha).unwrap();
        b.render_frame(&mut hb).unwrap();
        (ca == cb && ha == hb).then_some(ha)
    }

    /// The floor of the `floor` and `three-lights` presets leaves the casters of the spheres
    /// resting on it for every distant light (under the fill light, 24° to 27° above the
    /// floor, by the receding rule of `narrow_caster_prepare`, the plane's not holding
    /// there), and that changes no pixel: the frame is the same with the floor back in
    /// each of those masks and no caster filter or shadow rows to skip its tests.
    #[test]
    fn the_matrix_floors_leave_the_resting_spheres_casters() {
        let (w, h) = (160u32, 120u32);
        for scene in [crate::floor(), crate::three_lights()] {
            let scene = scene.unwrap();
            let with = PreparedFixed::new(&scene, w, h).unwrap();
            assert!(with.narrow.is_some());
            let floor = (0..with.spheres.len())
                .max_by_key(|&i| with.spheres[i].radius.to_bits())
                .unwrap();
            let mut without = with.clone();
            let mut left_out = 0;
            for (i, lights) in without.narrow_lights.iter_mut().enumerate() {
                if i == floor {
                    continue;
                }
                for (l, light) in lights.iter_mut().enumerate().take(with.lights.len()) {
                    if !matches!(with.lights[l], FixedLight::Distant { .. }) {
                        continue;
                    }
                    assert_eq!(light.casters & (1 << floor), 0, "sphere {i}, light {l}");
                    left_out += 1;
                    light.casters |= 1 << floor;
                    (light.ahead, light.reach) = (i32::MAX, u32::MAX);
                }
            }
            for s in without.spheres.iter_mut() {
                if let Some(n) = s.narrow.as_mut() {
                    n.shadows = (0, h as u16);
                }
            }
            assert_eq!(left_out, 8, "four spheres, two distant lights");
            assert!(
                same_frames(&with, &without, (w, h)).is_some(),
                "the floor back among the casters changed a pixel"
            );
        }
    }

    /// The quick caster test only clears casters the exact test finds clear: on random
    /// frames of spheres resting on floor spheres of radius 20 to 150 (whose shadows fall
    /// across the floor, and whose floor is a caster of each) and of spheres close enough
    /// to shadow each other, every pixel's colour and hit record is the same with the quick
    /// test and without it.
    #[test]
    fn the_quick_caster_test_changes_no_pixel() {
        use crate::test_scenes::{random_classic_scene, random_floor_scene, Draw};
        use crate::vec3::Vec3;
        let mut next = uniform(0x1f83_d9ab_fb41_bd6b);
        let draw = Draw {
            half_extent: Vec3::new(1.5, 1.0, 1.5),
            radius: (0.2, 0.9),
            varied: true,
        };
        let (w, h) = (96u32, 72u32);
        let (mut frames, mut shadowed_pixels) = (0, 0usize);
        for n in 0..160 {
            let scene: crate::Scene<8, 4> = if n % 2 == 0 {
                random_floor_scene(&mut next)
            } else {
                random_classic_scene(&mut next, &draw)
            };
            let Ok(with) = PreparedFixed::new(&scene, w, h) else {
                continue;
            };
            let quick = with
                .spheres
                .iter()
                .any(|s| s.narrow.as_ref().is_some_and(|n| n.quick_margin >= 0));
            let has_casters = with.narrow_lights.iter().flatten().any(|l| l.casters != 0);
            if with.narrow.is_none() || !has_casters || !quick {
                continue;
            }
            frames += 1;
            let mut without = with.clone();
            for s in without.spheres.iter_mut() {
                if let Some(n) = s.narrow.as_mut() {
                    n.quick_margin = -1;
                }
            }
            let hits = same_frames(&with, &without, (w, h))
                .unwrap_or_else(|| panic!("the quick caster test changed a pixel (scene {n})"));
            shadowed_pixels += hits.iter().filter(|h| h.shadowed != 0).count();
        }
        std::println!("{frames} frames with the quick test, {shadowed_pixels} shadowed pixels");
        assert!(frames >= 60 && shadowed_pixels > 10_000);
    }

    /// The caster filter only skips tests the exact one fails: on random frames of spheres
    /// close enough to shadow each other, every pixel's colour and hit record is the same
    /// with the filter and without it.
    #[test]
    fn the_caster_filter_changes_no_pixel() {
        use crate::scene::{Camera, Light, Material, Model, Scene, Sphere};
        use crate::vec3::Vec3;
        use crate::LinearRgb;
        let mut next = uniform(0x9e37_79b9_7f4a_7c15u64);
        let (w, h) = (96u32, 72u32);
        let (mut filtered, mut shadowed_pixels) = (0, 0usize);
        for _ in 0..150 {
            let angle = next(-3.1, 3.1);
            let camera = Camera {
                position: Vec3::new(8.0 * angle.sin(), next(-2.0, 4.0), 8.0 * angle.cos()),
                look_at: Vec3::new(0.0, 0.0, 0.0),
                up: Vec3::new(0.0, 1.0, 0.0),
                vfov_degrees: next(30.0, 60.0),
            };
            let mut scene: Scene<8, 4> = Scene::new(camera, LinearRgb::new(0.1, 0.1, 0.2)).unwrap();
            for _ in 0..(next(2.0, 7.99) as usize) {
                scene
                    .add_sphere(Sphere {
                        center: Vec3::new(next(-2.0, 2.0), next(-1.5, 1.5), next(-2.0, 2.0)),
                        radius: next(0.2, 0.9),
                        material: Material {
                            albedo: LinearRgb::new(0.8, 0.6, 0.4),
                            kd: 0.8,
                            ks: 0.3,
                            shininess: next(2.0, 300.0),
                            model: Model::Phong,
                        },
                    })
                    .unwrap();
            }
            for _ in 0..(next(1.0, 2.99) as usize) {
                scene
                    .add_light(Light::Distant {
                        direction: Vec3::new(next(-1.0, 1.0), next(-1.0, -0.2), next(-1.0, 1.0)),
                        color: LinearRgb::new(1.0, 1.0, 1.0),
                        intensity: 1.5,
                    })
                    .unwrap();
            }
            let Ok(with) = PreparedFixed::new(&scene, w, h) else {
                continue;
            };
            let has_casters = with.narrow_lights.iter().flatten().any(|l| l.casters != 0);
            if with.narrow.is_none() || !has_casters {
                continue;
            }
            filtered += 1;
            let mut without = with.clone();
            for l in without.narrow_lights.iter_mut().flatten() {
                l.ahead = i32::MAX;
                l.reach = u32::MAX;
            }
            let hits =
                same_frames(&with, &without, (w, h)).expect("the caster filter changed a pixel");
            shadowed_pixels += hits.iter().filter(|h| h.shadowed != 0).count();
        }
        std::println!(
            "{filtered} frames with a filtered caster, {shadowed_pixels} shadowed pixels"
        );
        assert!(filtered >= 20 && shadowed_pixels > 3000);
    }

    #[test]
    fn scale_q15_is_exact() {
        for a in [0u32, 1, 65535, 65536, 1 << 20, u32::MAX / 3] {
            for b in [0, 1, 12345, ONE] {
                let want = ((a as u64 * b as u64) >> 15).min(u32::MAX as u64) as u32;
                assert_eq!(scale_q15(a, b), want, "{a}·{b}");
            }
        }
    }
}
