//! The narrow kernel: the fixed path's pixels in 16×16→32-bit products, for the frames that
//! allow it, with the full-width kernel ([`super::kernel`]) as its fallback per pixel.
//!
//! # Why it exists
//!
//! The full-width kernel holds unit vectors in I2F30 and lengths in I16F16, so nearly every
//! product is 32×32→64 bits: one instruction on a Cortex-M4 or an RV32IM core, but about
//! twenty on ARMv6-M (Cortex-M0/M0+, RP2040), whose multiplier is 32×32→32. A lit pixel makes
//! about 85 of them. Most of that precision only matters next to a narrow highlight; the
//! diffuse term, the silhouettes and the wide lobes need about 15 bits. This kernel computes
//! those in 15-bit fractions (Q15), where a product is one `MULS`, and hands a pixel to the
//! full-width kernel only where its error bound says the lobe needs more.
//!
//! # When it applies
//!
//! A frame uses it (the prepare's `NarrowView`) when every light is distant, every
//! sphere uses a classic model (Phong or Blinn-Phong, not normalized), every sphere is more
//! than `4ε` from each sphere that can shadow it ([`crate::Scene::shadow_casters`]), the
//! camera is outside every sphere, and the image plane is narrow enough that every primary direction is within
//! `√2` of the central one in length (a field of view up to about 90° on the diagonal).
//! Every other frame renders with the full-width kernel alone. The conditions are
//! frame-wide, so a pixel's result does not depend on which spheres' spans cover it (turning
//! spans off changes no pixel).
//!
//! # How a pixel is computed
//!
//! With `D` the unnormalized primary direction, `oc = eye − centre` and `r` the radius:
//!
//! - `w = oc × D` and `b = oc·D` are linear along a row: `w` advances by one exact 64-bit
//!   addition per pixel (`D` is an integer vector that advances by an integer step, so no
//!   rounding accumulates: a pixel's values do not depend on where its run or segment
//!   starts), and the columns where `b < 0` are one interval, found once per run, to which
//!   the sphere's span is narrowed (`b` itself is only computed again where two hits on one
//!   pixel are compared);
//! - `σ = |D₀|/|D|` (from `1/√|D|²`, see [`rsqrt`]) scales everything to unit length:
//!   `D̂ = D·σ/|D₀|` and `u = w·σ/(r·|D₀|) = (oc × D̂)/r`, both Q15;
//! - the ray hits the sphere iff `b < 0` (it is in front) and `|u| ≤ 1`. Then
//!   `N·V = √(1 − |u|²)`, and the normal is `N = D̂ × u − (N·V)·D̂`: the closest-approach
//!   vector from the cross product, with no subtraction of two large vectors, so it keeps
//!   15 bits however far the sphere is from the camera;
//! - per light: `N·L` (diffuse, and the sphere's own shadow: a ray lifted by ε off the
//!   surface meets the sphere again iff `N·L < 0` and `(N·L)² > 1 − r²/(r + ε)²`), and the
//!   lobe's `h = 1 − cos = ½|R − V|²` (Phong) or `½|N − H|²` (Blinn-Phong) from Q15
//!   components, which keeps relative precision at the highlight;
//! - the lobe itself is [`super::pow::lobe`] of that `h`, and `combine` is the full-width
//!   kernel's.
//!
//! # Where it hands over
//!
//! The components of `R − V` (and `N`) are within `δ = 2⁻¹⁰` of their exact values wherever
//! `N·V ≥ 0.3` (test `narrow_vectors_within_delta` measures the largest error on the exponent
//! series: 26 steps of `2⁻¹⁵` for `R − V`, 14 for `N`; toward the silhouette it grows as
//! `1/(N·V)`, as the geometry's own sensitivity does). So `h` is within about `|R − V|·δ`,
//! and the lobe `(1 − h)ⁿ` within about `√n·δ·0.61` (the maximum of `n·√(2h)·δ·e^(−nh)`,
//! at `h = 1/2n`). The prepare turns that into two per-sphere numbers:
//!
//! - `cutoff`: above this `h` the lobe, times `ks` and the sum of the lights' intensities,
//!   is below `2⁻¹⁷` (half a U16F16 step), even allowing for the error of `h`: the lobe is 0;
//! - `lobe_everywhere`: whether `ks·ΣI·√n·δ·0.61` is at most half an 8-bit level, so the
//!   narrow lobe can be used wherever it is not 0. For `n ≥ 32` this takes the smaller bound
//!   `DELTA_LOBE` that holds near the reflection, where that maximum lies.
//!
//! A pixel below the cutoff of a sphere without `lobe_everywhere` (the bright part of a
//! narrow highlight) is shaded by the full-width kernel. So is one where both `N·V` and
//! `|N·L|` are below 0.3 (near the silhouette, where `N`'s error grows, and dark), when the
//! encoding's transfer is sRGB, whose dark levels are about thirteen times finer than linear
//! ones: under the linear transfer those pixels stay within one level of the `f64`
//! reference from the narrow kernel (`tests/fixed_agreement.rs`, `tests/encodings.rs`), so
//! the transfer sets the rule, and a path's linear colour is the same under every encoding
//! of one transfer. On the exponent series at 320×240, 69 of 11,839 covered pixels (0.6%)
//! are handed over under the linear transfer and 303 (2.6%) under sRGB (test
//! `exponent_series_hands_few_pixels_over`).
//!
//! Every step is integer arithmetic with the same bits on every target; products are
//! 16×16→32 bits (`|x| ≤ 2¹⁵` operands) except in [`rsqrt`], the square root `N·V`, and the
//! per-channel scaling by the light's colour.

use super::exact::{shift_saturating, Exact};
use super::kernel::Shaded;
use super::mul::{mul_ii, mul_uu};
use super::pow::{EXP_TABLE, INV_LN2_F31, LOG_TABLE};
use super::prepare::{FixedLight, NarrowSphere, NarrowView, PreparedFixed};
use super::vector::{dot_len_unit, each3, length_sq, to_len, Unit, V3};
use crate::pixel::HitRecord;
use crate::runs::Span;

/// One, Q15.
const ONE: i32 = 1 << 15;

/// `N·V` and `|N·L|` below this (0.3, Q15) together hand a pixel over.
const GRAZING: i32 = 9830;

/// What the narrow kernel made of a pixel.
pub(crate) enum Narrow {
    /// The pixel: `None` for the background.
    Done(Option<Shaded>),
    /// The full-width kernel must shade this pixel.
    Precise,
}

/// One sphere along a run: its values at column `max(x, span.start)` of the run's current
/// column `x`, and what the hot loop needs of its constants.
///
/// `span` is the part of the sphere's span on the row where `b = oc·D` is negative (the
/// sphere is in front along the ray): `b` is linear along the row, so that part is one
/// interval, found once per run, and the hot loop neither advances `b` nor tests its sign.
#[derive(Clone, Copy)]
struct Track {
    index: usize,
    span: Span,
    /// `oc × D`, held shifted left by the sphere's `left`.
    w: V3<i64>,
    dw: V3<i64>,
    right: u32,
    gain: u32,
}

/// The state of the narrow kernel along one run of a row.
///
/// A run merges the spans of every sphere it crosses, but at one column only the tracks
/// whose span covers it take part: `active` lists them (indices into `tracks`), and is
/// rebuilt only at `changes_at`, the next column where a span begins or ends, so a pixel
/// pays nothing for the spheres of the run that are elsewhere on the row.
pub(crate) struct NarrowRun<const S: usize> {
    /// The current column and its direction.
    x: u32,
    d: V3<i32>,
    step: V3<i32>,
    tracks: heapless::Vec<Track, S>,
    active: heapless::Vec<u8, S>,
    changes_at: u32,
}

impl<const S: usize> NarrowRun<S> {
    /// A run of no tracks, for [`PreparedFixed::narrow_run`] to set.
    #[inline(always)]
    pub(crate) const fn new() -> Self {
        NarrowRun {
            x: 0,
            d: [0; 3],
            step: [0; 3],
            tracks: heapless::Vec::new(),
            active: heapless::Vec::new(),
            changes_at: 0,
        }
    }
}

/// The tracks whose span covers column `x` (indices into `tracks`), and the next column
/// where a span begins or ends. Not inlined: the pixel loop only calls it where a span
/// begins or ends.
#[inline(never)]
fn activity<const S: usize>(tracks: &[Track], x: u32) -> (heapless::Vec<u8, S>, u32) {
    let mut active = heapless::Vec::new();
    let mut changes_at = u32::MAX;
    for (i, t) in tracks.iter().enumerate() {
        if t.span.start <= x && x < t.span.end {
            // As many entries as tracks, and the prepare only sets up the narrow kernel for
            // at most 256 spheres, which `u8` indexes: cannot fail.
            let pushed = active.push(i as u8);
            debug_assert!(pushed.is_ok());
        }
        let next = if x < t.span.start {
            t.span.start
        } else {
            t.span.end
        };
        if x < next {
            changes_at = changes_at.min(next);
        }
    }
    (active, changes_at)
}

/// A hit: the sphere, `u`, `N·V`, and `t` in raw I16F16 once two hits are compared.
struct Hit {
    index: usize,
    u: V3<i32>,
    nv: i32,
    t: Option<i64>,
}

/// The surface under a pixel: the sphere, the unit ray direction and the normal (Q15).
#[derive(Clone, Copy)]
struct Surface {
    index: usize,
    dh: V3<i32>,
    n: V3<i32>,
    /// `N·V`, Q15.
    nv: i32,
}

/// Entries of [`RSQRT_TABLE`]: one per top-8-bit pattern of a `u32`.
const BINS: usize = 256;

/// `2¹⁵/√m` at the centre of each bin of `m` in `[¼, 1)`, Q15 (below `2¹⁶`), indexed by
/// the top 8 bits of `m` (`64..=255`); the entries below 64, which a normalized value never
/// reaches, repeat bin 64's, so every `u32` indexes it without a check.
static RSQRT_TABLE: [u16; BINS] = rsqrt_table();

const fn rsqrt_table() -> [u16; BINS] {
    let mut table = [0u16; BINS];
    let mut i = 0;
    while i < BINS {
        // Bin `64 + j` covers m in [(64 + j)/256, (65 + j)/256); its centre is
        // (2j + 129)/512, and 2¹⁵/√centre = √(2³⁹/(2j + 129)).
        let j = i.saturating_sub(64) as u64;
        table[i] = ((1u64 << 39) / (2 * j + 129)).isqrt() as u16;
        i += 1;
    }
    table
}

/// `1/√x` for `x > 0` as `(y, e)`: `1/√x ≈ y·2^-e`, `y` in about `[2¹⁵, 2¹⁶]`, within
/// `1.5·2⁻¹⁵` relative: a table lookup and one Newton step `y·(3 − m·y²)/2`.
#[inline(always)]
pub(crate) fn rsqrt(x: u32) -> (u32, u32) {
    let k = even_leading_zeros(x);
    (rsqrt_normalized(x << k), 31 - k / 2)
}

/// `2³¹/√m` for `m` in `[2³⁰, 2³²)`, within `1.5·2⁻¹⁵` relative (in about `[2¹⁵, 2¹⁶]`).
#[inline(always)]
fn rsqrt_normalized(m: u32) -> u32 {
    debug_assert!(m >= 1 << 30, "m = {m:#x} is not normalized");
    let y0 = RSQRT_TABLE
        .get((m >> 24) as usize)
        .copied()
        .unwrap_or(1 << 15) as u32;
    // m·y0² as Q30 from their top 16 bits (y0² Q30 → Q14, m Q32 → Q16): about 2³⁰.
    let p = ((y0 * y0 + (1 << 15)) >> 16) * (m.saturating_add(1 << 15) >> 16);
    let corr = (3u32 << 30).saturating_sub(p);
    // y0·corr/2³¹, rounded at both steps (y0 < 2¹⁶, corr < 3·2³⁰: no overflow).
    (y0 * ((corr + (1 << 15)) >> 16) + (1 << 14)) >> 15
}

/// `√x` of a Q30 value in `[0, 2³⁰]`, as Q15.
#[inline(always)]
fn sqrt_q30(x: u32) -> i32 {
    if x == 0 {
        return 0;
    }
    // N·V's argument is mostly in [2²⁶, 2³⁰]: there two comparisons give the even count.
    let k = if x >= 1 << 28 {
        if x >= 1 << 30 {
            0
        } else {
            2
        }
    } else if x >= 1 << 26 {
        4
    } else {
        even_leading_zeros(x)
    };
    debug_assert_eq!(k, even_leading_zeros(x));
    let y = rsqrt_normalized(x << k);
    // √x = (x·2^k)·y·2^(−31)·2^(−k/2)
    let scaled = (((x << k).saturating_add(1 << 15) >> 16) * y) >> 14; // < 2¹⁹
    ((scaled + (1 << (k / 2))) >> (1 + k / 2)) as i32
}

/// The number of leading zeros of `x > 0`, rounded down to even: the shift that brings `x`
/// into `[2³⁰, 2³²)` by a power of four. `CLZ` where the core has it; on ARMv6-M, which
/// has not, the binary search of [`super::mul`].
#[inline(always)]
fn even_leading_zeros(x: u32) -> u32 {
    #[cfg(shadeline_short_mul)]
    {
        super::mul::search_leading_zeros32(x) & !1
    }
    #[cfg(not(shadeline_short_mul))]
    {
        x.leading_zeros().min(30) & !1
    }
}

/// `a·b/2¹⁶` for `b` in `[0, 2¹⁶]`, exact (rounded down), saturating: two 16×16 products
/// on ARMv6-M, one widening product elsewhere.
#[inline(always)]
fn scale_q16(a: u32, b: u32) -> u32 {
    #[cfg(shadeline_short_mul)]
    {
        let high = (a >> 16) * b; // ≤ 2³²− 2¹⁶
        let low = ((a & 0xffff) * b) >> 16;
        high.saturating_add(low)
    }
    #[cfg(not(shadeline_short_mul))]
    {
        u32::try_from(mul_uu(a, b) >> 16).unwrap_or(u32::MAX)
    }
}

/// `k·v/2¹⁶`, rounded down, saturating: [`scale_q16`] when `k ≤ 1` (U16F16), which
/// `kd·albedo` and `ks` nearly always are, a full product otherwise.
#[inline(always)]
fn mul_u16f16(k: u32, v: u32) -> u32 {
    if k <= 1 << 16 {
        scale_q16(v, k)
    } else {
        u32::try_from(mul_uu(k, v) >> 16).unwrap_or(u32::MAX)
    }
}

/// `a·b/2¹⁵` for `b` in `[0, 2¹⁵]`, exact (rounded down), saturating: two 16×16 products
/// on ARMv6-M, one widening product elsewhere.
#[inline(always)]
fn scale_q15(a: u32, b: i32) -> u32 {
    let b = b.clamp(0, ONE) as u32;
    #[cfg(shadeline_short_mul)]
    {
        let high = (a >> 16) * b; // < 2³¹
        let low = ((a & 0xffff) * b) >> 15;
        high.checked_mul(2)
            .and_then(|h| h.checked_add(low))
            .unwrap_or(u32::MAX)
    }
    #[cfg(not(shadeline_short_mul))]
    {
        u32::try_from(mul_uu(a, b) >> 15).unwrap_or(u32::MAX)
    }
}

#[inline(always)]
fn dot(a: V3<i32>, b: V3<i32>) -> i32 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

impl<const S: usize, const L: usize> PreparedFixed<S, L> {
    /// The narrow direction of pixel `x` on row `y`.
    #[inline(always)]
    fn narrow_direction(view: &NarrowView, x: u32, y: u32, width: u32, height: u32) -> V3<i32> {
        let dy = height as i32 - 2 * y as i32 - 1;
        let dx = 2 * x as i32 + 1 - width as i32;
        each3(|i| view.forward[i] + dy * view.step_y[i] + dx * view.step_x[i])
    }

    /// Sets `run` to the narrow state at the first pixel `x` of a run on row `y` that ends
    /// before column `end`, in place; `false` (and `run` unchanged) if the frame does not use
    /// the narrow kernel. In place because a run holds a track per sphere: at the default
    /// capacity about 1.4 KB, which a returned value would cost a `memcpy` or two per run
    /// (10% of a frame on RV32). Only the spheres whose span meets the run get a track.
    /// Not inlined: once per run, and apart from the pixel loop's registers.
    #[inline(never)]
    pub(crate) fn narrow_run(
        &self,
        run: &mut NarrowRun<S>,
        x: u32,
        end: u32,
        y: u32,
        spans: &[Option<Span>],
    ) -> bool {
        let Some(view) = self.narrow.as_ref() else {
            return false;
        };
        run.tracks.clear();
        for (index, (s, span)) in self.spheres.iter().zip(spans).enumerate() {
            let (Some(span), Some(n)) = (span, s.narrow.as_ref()) else {
                continue;
            };
            if span.end <= x || end <= span.start {
                continue;
            }
            let oc = s.eye_offset.map(|c| c.to_bits());
            let b_at = |column| {
                narrow_b(
                    oc,
                    Self::narrow_direction(view, column, y, self.width, self.height),
                )
            };
            let Some(span) = front_part(x.max(span.start), span.end, n.b_rises, b_at) else {
                continue;
            };
            let d = Self::narrow_direction(view, span.start, y, self.width, self.height);
            let cross = [
                mul_ii(oc[1], d[2]) - mul_ii(oc[2], d[1]),
                mul_ii(oc[2], d[0]) - mul_ii(oc[0], d[2]),
                mul_ii(oc[0], d[1]) - mul_ii(oc[1], d[0]),
            ];
            let track = Track {
                index,
                span,
                w: cross.map(|c| c << n.left),
                dw: n.dw,
                right: n.right,
                gain: n.gain,
            };
            // As many tracks as spheres: cannot fail.
            let pushed = run.tracks.push(track);
            debug_assert!(pushed.is_ok());
        }
        (run.active, run.changes_at) = activity(&run.tracks, x);
        run.x = x;
        run.d = Self::narrow_direction(view, x, y, self.width, self.height);
        run.step = view.step_x.map(|c| 2 * c);
        true
    }

    /// Moves `run` one pixel to the right, once its active tracks have moved: the direction,
    /// and the set of active tracks where a span begins or ends.
    #[inline(always)]
    fn narrow_step(run: &mut NarrowRun<S>) {
        for (c, s) in run.d.iter_mut().zip(run.step) {
            *c += s;
        }
        run.x += 1;
        if run.x >= run.changes_at {
            (run.active, run.changes_at) = activity(&run.tracks, run.x);
        }
    }

    /// Shades pixel `x` of `run` with the narrow kernel, or says it needs the full-width one,
    /// and moves `run` one pixel to the right. `precise_darks`: hand over the dark pixels
    /// near the silhouette (see [`Self::narrow_lights`]).
    #[inline(always)]
    pub(crate) fn narrow_shade(
        &self,
        run: &mut NarrowRun<S>,
        record_hits: bool,
        precise_darks: bool,
    ) -> Narrow {
        let Some(surface) = self.narrow_surface(run) else {
            return Narrow::Done(None);
        };
        self.narrow_lights(&surface, record_hits, precise_darks)
    }

    /// The `hit` and `normal` stages: the nearest sphere under the run's current pixel, with
    /// `D̂` and `N` in Q15, `None` for the background; and `run` moved one pixel to the
    /// right (each active track's `w` advances where the loop reads it).
    #[inline(always)]
    fn narrow_surface(&self, run: &mut NarrowRun<S>) -> Option<Surface> {
        let x = run.x;
        let d16 = run.d.map(|c| c >> 15);
        // |D16| < 2¹⁵·√2·…: a < 2³¹.
        let a = dot(d16, d16) as u32;
        // σ = 2²⁹/√a, Q15 (|D₀| is 2¹⁴ in D16 units); a is in [2²⁶, 2³⁰], so 1/√a is
        // 2³¹/√(a·4^k)·2^(k − 16) with k = 0, 1 or 2.
        let sigma = if a >= 1 << 30 {
            rsqrt_normalized(a) >> 2
        } else if a >= 1 << 28 {
            rsqrt_normalized(a << 2) >> 1
        } else {
            rsqrt_normalized(a << 4)
        };
        let sigma = sigma.min(ONE as u32) as i32;

        let d = run.d;
        let mut best: Option<Hit> = None;
        for &i in &run.active {
            let t = run.tracks.get_mut(i as usize);
            debug_assert!(t.is_some(), "track {i} of {}", run.tracks.len());
            let Some(t) = t else {
                continue;
            };
            debug_assert!(t.span.start <= x && x < t.span.end);
            let w = t.w;
            t.w = each3(|k| w[k] + t.dw[k]);
            let t = &*t;
            let high = w.map(|c| (c >> 32) as i32 >> t.right);
            if (high[0].unsigned_abs() | high[1].unsigned_abs() | high[2].unsigned_abs()) >= 1 << 16
            {
                continue;
            }
            let mu = ((sigma as u32 * t.gain) >> 16) as i32; // ≤ 2¹⁵
            let u = high.map(|c| (c * mu) >> 14);
            if (u[0].unsigned_abs() | u[1].unsigned_abs() | u[2].unsigned_abs()) > ONE as u32 {
                continue;
            }
            let uu = (u[0] * u[0]) as u32 + (u[1] * u[1]) as u32 + (u[2] * u[2]) as u32;
            if uu > 1 << 30 {
                continue;
            }
            let nv = sqrt_q30((1 << 30) - uu);
            let mut hit = Hit {
                index: t.index,
                u,
                nv,
                t: None,
            };
            best = match best {
                None => Some(hit),
                Some(mut prev) => {
                    // Two hits on one pixel: the nearer wins (the first on a tie).
                    let t_prev = prev.t.unwrap_or_else(|| self.narrow_t(&prev, sigma, d));
                    prev.t = Some(t_prev);
                    let t_new = self.narrow_t(&hit, sigma, d);
                    hit.t = Some(t_new);
                    Some(if t_new < t_prev { hit } else { prev })
                }
            };
        }
        Self::narrow_step(run);
        let hit = best?;
        // D̂ (Q15) and N = D̂ × u − (N·V)·D̂.
        let dh = d16.map(|c| (c * sigma) >> 14);
        let u = hit.u;
        let cross = [
            dh[1] * u[2] - dh[2] * u[1],
            dh[2] * u[0] - dh[0] * u[2],
            dh[0] * u[1] - dh[1] * u[0],
        ];
        let n = each3(|i| (cross[i] - hit.nv * dh[i]) >> 15);
        Some(Surface {
            index: hit.index,
            dh,
            n,
            nv: hit.nv,
        })
    }

    /// The `lights` and `combine` stages at `surface`, or [`Narrow::Precise`] where the lobe
    /// needs the full-width kernel, and, if `precise_darks`, where the pixel is both near the
    /// silhouette and near the terminator (for the sRGB transfer's fine dark levels).
    #[inline(always)]
    fn narrow_lights(&self, surface: &Surface, record_hits: bool, precise_darks: bool) -> Narrow {
        let Surface { index, dh, n, nv } = *surface;
        debug_assert!(index < self.spheres.len(), "hit on sphere {index}");
        let Some(sphere) = self.spheres.get(index) else {
            return Narrow::Done(None);
        };
        let Some(ns) = sphere.narrow.as_ref() else {
            return Narrow::Precise;
        };
        let mut diffuse = [0u32; 3];
        let mut specular = [0u32; 3];
        // Whether a term was added to `diffuse` or a lobe to `specular`: if not, it is 0 and
        // adds nothing.
        let (mut lit, mut glossy) = (false, false);
        let mut shadowed = 0u32;
        for (light_index, light) in self.lights.iter().enumerate() {
            let FixedLight::Distant { to_light, arriving } = *light else {
                return Narrow::Precise;
            };
            let l = to_light.map(|c| c.to_bits() >> 15);
            let nl = dot(n, l) >> 15;
            // Toward the silhouette N's error grows as 1/(N·V); where it also lies near the
            // terminator, the diffuse term is dark, where an sRGB level is smallest: there
            // the full-width kernel shades, for the sRGB transfer. Linear levels are as wide
            // in the darks as anywhere, and these pixels stay within a level of the
            // reference without it (`tests/fixed_agreement.rs`).
            if precise_darks && nv < GRAZING && nl.abs() < GRAZING {
                return Narrow::Precise;
            }
            let own = nl < 0 && (nl * nl) as u32 > ns.shadow_limit;
            let casters = self.casters(index, light_index);
            let blocked =
                || self.narrow_blocked(index, ns, n, (light_index, to_light, nl), casters);
            if own || (casters != 0 && blocked()) {
                if record_hits && light_index < 32 {
                    shadowed |= 1 << light_index;
                }
                continue;
            }
            let arriving = arriving.map(|c| c.to_bits());
            if nl > 0 {
                for (acc, i) in diffuse.iter_mut().zip(arriving) {
                    *acc = acc.saturating_add(scale_q15(i, nl));
                }
                lit = true;
            }
            let h = if sphere.blinn {
                // H = (L + V)/|L + V| with V = −D̂; none where L = −V.
                let lv = each3(|i| l[i] - dh[i]);
                let len2 = dot(lv.map(|c| c >> 1), lv.map(|c| c >> 1)) as u32; // Q28
                if len2 == 0 {
                    continue;
                }
                let (y, e) = rsqrt(len2);
                // 1/|L + V| = y·2^-e·2¹⁴ (len2 is Q28): H = lv·y·2^(14 − e), Q15.
                let shift = (e - 14).min(63);
                let hv = lv.map(|c| (mul_ii(c, y as i32) >> shift) as i32);
                half_h(each3(|i| n[i] - hv[i]))
            } else {
                let r = each3(|i| ((nl * n[i]) >> 14) - l[i]);
                half_h(each3(|i| r[i] + dh[i]))
            };
            if h >= ns.cutoff {
                continue;
            }
            if !ns.lobe_everywhere {
                return Narrow::Precise;
            }
            let lobe = narrow_lobe(h, sphere.shininess);
            for (acc, i) in specular.iter_mut().zip(arriving) {
                *acc = acc.saturating_add(scale_q16(i, lobe));
            }
            glossy = true;
        }
        let diffuse = if lit {
            each3(|c| mul_u16f16(sphere.kd_albedo[c].to_bits(), diffuse[c]))
        } else {
            [0; 3]
        };
        Narrow::Done(Some(Shaded {
            color: if glossy {
                each3(|c| {
                    let s = mul_u16f16(sphere.ks.to_bits(), specular[c]);
                    diffuse[c].saturating_add(s)
                })
            } else {
                diffuse
            },
            hit: HitRecord {
                sphere: Some(index as u16),
                shadowed,
            },
        }))
    }

    /// Whether one of the `casters` (a mask as [`PreparedFixed::casters`] gives it) blocks
    /// the ray toward the distant light `to_light` from the point of sphere `index` with
    /// normal `n`, lifted by ε: the shadow stage's caster test, from the narrow normal.
    ///
    /// The prepare only sets up the narrow kernel when every sphere is more than `4ε` away
    /// from each of its casters, so the lifted point is outside them: a caster blocks iff
    /// the ray moves toward its centre (`b = (O − C)·L < 0`) and passes within its radius
    /// (`|O − C|² − b² ≤ r²`), and no square root is needed.
    ///
    /// The sphere's [`FastCaster`] (`ns.fast`), if it has one, is first put through a 32-bit
    /// filter; the exact test runs only where the filter cannot decide. `light` is the
    /// light's index, `L` and `N·L` (Q15).
    #[inline(always)]
    fn narrow_blocked(
        &self,
        index: usize,
        ns: &NarrowSphere,
        n: V3<i32>,
        light: (usize, V3<Unit>, i32),
        casters: u32,
    ) -> bool {
        debug_assert!(index < self.spheres.len(), "hit on sphere {index}");
        let Some(own) = self.spheres.get(index) else {
            return false;
        };
        let (light_index, to_light, nl) = light;
        let mut origin: Option<V3<i64>> = None;
        for (k, s) in self.spheres.iter().enumerate() {
            if k == index || (k < 32 && casters & (1 << k) == 0) {
                continue;
            }
            if let Some(f) = ns
                .fast
                .as_ref()
                .filter(|f| f.sphere as usize == k && f.light as usize == light_index)
            {
                let nl11 = nl >> 4;
                if nl11 >= f.ahead as i32 {
                    continue;
                }
                let d = each3(|i| (n[i] >> 4) - f.c[i] as i32);
                let t = nl11 - f.g as i32;
                if d[0] * d[0] + d[1] * d[1] + d[2] * d[2] - t * t > f.reach2 {
                    continue;
                }
            }
            let origin = *origin.get_or_insert_with(|| {
                let lift = (ns.radius as i64 + self.epsilon.to_bits() as i64).min(i32::MAX as i64);
                each3(|i| own.center[i].to_bits() as i64 + (mul_ii(lift as i32, n[i]) >> 15))
            });
            let oc = each3(|i| to_len(origin[i] - s.center[i].to_bits() as i64));
            let b = dot_len_unit(oc, to_light);
            if b >= 0 {
                continue;
            }
            let b = to_len(b).to_bits();
            let miss = length_sq(oc.map(|c| c.to_bits() as i64)).saturating_sub(mul_ii(b, b));
            if miss <= s.radius_sq.to_bits() {
                return true;
            }
        }
        false
    }

    /// `t` of a hit in raw I16F16 on the narrow direction `d`, for choosing the nearer of
    /// two: `−b/|D| − r·(N·V)`. Only pixels with two hits need it; on ARMv6-M, whose 64-bit
    /// products are long inline sequences, it is not inlined, which keeps them out of the
    /// pixel loop's code and registers.
    #[cfg_attr(shadeline_short_mul, inline(never))]
    #[cfg_attr(not(shadeline_short_mul), inline(always))]
    fn narrow_t(&self, hit: &Hit, sigma: i32, d: V3<i32>) -> i64 {
        let sphere = self.spheres.get(hit.index);
        let narrow = sphere.and_then(|s| s.narrow.as_ref());
        // Only frames whose every sphere has narrow data take the narrow kernel.
        debug_assert!(narrow.is_some(), "sphere {} has no narrow data", hit.index);
        let radius = narrow.map_or(0, |n| n.radius);
        let b = sphere.map_or(0, |s| narrow_b(s.eye_offset.map(|c| c.to_bits()), d));
        // −b·σ/2⁴⁴ (1/|D| is σ/2⁴⁴): on a hit −2⁶¹ < b < 0, so (−b) >> 30 fits 31 bits.
        let along = (mul_uu(((-b) >> 30) as u32, sigma as u32) >> 14) as i64;
        along - (mul_uu(radius, hit.nv as u32) >> 15) as i64
    }
}

/// `b = oc·D` of the raw eye offset `oc` and a narrow direction `D`, exact.
#[inline(always)]
fn narrow_b(oc: V3<i32>, d: V3<i32>) -> i64 {
    mul_ii(oc[0], d[0]) + mul_ii(oc[1], d[1]) + mul_ii(oc[2], d[2])
}

/// The columns of `[start, end)` where `b_at(column)` is negative, `None` if there are none.
/// `b` is linear in the column (growing if `rises`, otherwise not), so they are one
/// interval: the first column is tested, the last one too unless the first one's sign and
/// the slope's settle it, and where the sign changes between them a binary search finds
/// the column where it does.
#[inline(always)]
fn front_part(start: u32, end: u32, rises: bool, b_at: impl Fn(u32) -> i64) -> Option<Span> {
    if start >= end {
        return None;
    }
    let first = b_at(start) < 0;
    if first != rises {
        // Negative and not growing, or not negative and growing: the sign stays.
        return first.then_some(Span { start, end });
    }
    let last = b_at(end - 1) < 0;
    if first == last {
        return first.then_some(Span { start, end });
    }
    // The sign at `lo` is `first`'s, the sign at `hi` is `last`'s.
    let (mut lo, mut hi) = (start, end - 1);
    while hi - lo > 1 {
        let mid = lo + (hi - lo) / 2;
        if (b_at(mid) < 0) == first {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    Some(if first {
        Span { start, end: hi }
    } else {
        Span { start: hi, end }
    })
}

/// `½|c|²` of a Q15 difference of two unit vectors: the lobe's `h` in Q31, saturating (any
/// value from `2³¹` on is `h ≥ 1`, a lobe of 0).
#[inline(always)]
fn half_h(c: V3<i32>) -> u32 {
    if (c[0].unsigned_abs() | c[1].unsigned_abs() | c[2].unsigned_abs()) < 1 << 15 {
        // Σc² is |c|² in Q30 (< 3·2³⁰), which is h in Q31.
        (c[0] * c[0]) as u32 + (c[1] * c[1]) as u32 + (c[2] * c[2]) as u32
    } else {
        // h ≥ ½: two bits fewer are plenty.
        let [x, y, z] = c.map(|v| ((v >> 1) * (v >> 1)) as u32);
        (x + y + z).saturating_mul(4)
    }
}

/// The lobe `(1 − h)ⁿ` in U1F16 (`1 << 16` is 1) for `h` in Q31, in 32-bit arithmetic.
///
/// The same route as [`super::pow::lobe`] with fewer bits: `g = −log2(1 − h)` in Q27 (by
/// its series `h·(1 + h/2 + h²/3)/ln 2` for `h < 2⁻⁵`, otherwise from a power of two, the
/// shared 64-entry table of `log2 m₀` and `ln(1 + δ) ≈ δ − δ²/2 + δ³/3`), `y = n·g` in Q16
/// (one 32×32→64 product), and `2^-y` from the shared table of `2^(−i/64)` and
/// `e^(−r·ln 2) ≈ 1 − a + a²/2`. Its absolute error in `y` grows as `n·2⁻²¹`, so the kernel
/// uses it only for `n ≤ 256`, where the lobe is within `1.4·10⁻⁴` of `powf` (test
/// `narrow_lobe_matches_powf`: 1.3·10⁻⁴ at `n` = 256). About 60 instructions on ARMv6-M,
/// against about 300 for the 64-bit [`super::pow::lobe`].
#[inline(always)]
fn narrow_lobe(h: u32, n: Exact) -> u32 {
    const ONE_Q31: u32 = 1 << 31;
    if h >= ONE_Q31 {
        return 0;
    }
    let g = if h < 1 << 26 {
        // p = 1 + h/2 + h²/3 in Q30; (h>>11)² is h² in Q40.
        let h2 = ((h >> 11) * (h >> 11)) >> 10;
        let p = (1 << 30) + (h >> 2) + (((h2 >> 4) * 21_845) >> 12);
        // q = p/ln 2 in Q31 (< 1.5·2³¹), then g = h·q in Q27.
        let q = (p >> 14) * ((INV_LN2_F31 >> 16) as u32);
        ((h >> 10) * (q >> 16)) >> 9
    } else {
        let c = ONE_Q31 - h; // 1 − h in Q31, > 0
        let e = c.leading_zeros(); // ≥ 1
        let m = c << e; // m₀·(1 + δ) in U1F31
        let (inv_m0, log2_m0) = LOG_TABLE
            .get(((m >> 25) & 63) as usize)
            .copied()
            .unwrap_or((1 << 31, 0));
        // δ = (m − m₀)/m₀ in Q31 (< 2²⁵): (m − m₀) < 2²⁵ in Q31, taken as Q22.
        let delta = ((((m & ((1 << 25) - 1)) >> 9) * (inv_m0 >> 15)) >> 7) as i32;
        let d10 = delta >> 10; // Q21, |d10| < 2¹⁵
        let d2 = (d10 * d10) >> 11; // δ² in Q31
        let d3 = ((((d2 >> 9) * d10) >> 12) * 21_845) >> 16; // δ³/3 in Q31 (|δ³| < 2¹³)
        let ln = delta - (d2 >> 1) + d3; // ln(1 + δ), Q31
        let log2_1p = ((ln >> 9) * ((INV_LN2_F31 >> 17) as i32)) >> 9; // Q27
        let log2_m = (log2_m0 >> 5) as i64 + log2_1p as i64; // Q27, in [0, 1)
        (((e as i64) << 27) - log2_m).clamp(0, u32::MAX as i64) as u32
    };
    let y = shift_saturating(mul_uu(n.mantissa, g), n.exponent - 11); // Q16
    let k = y >> 16;
    if k >= 17 {
        return 0;
    }
    let f = y & 0xffff;
    debug_assert!(((f >> 10) as usize) < EXP_TABLE.len());
    let base = EXP_TABLE.get((f >> 10) as usize).copied().unwrap_or(0) >> 15; // Q16, ≤ 2¹⁶
    let a = ((f & 1023) * 45_426) >> 16; // r·ln 2 in Q16, < 2¹⁰
    let e = (1 << 16) - a + ((a * a) >> 17); // e^(−a), Q16
    let v = (base * (e >> 1)) >> 15; // ≤ 2¹⁶
    (v + ((1 << k) >> 1)) >> k
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fixed::prepare::{DELTA, DELTA_LOBE};

    #[test]
    fn rsqrt_within_one_and_a_half_steps_of_two_to_the_minus_15() {
        let mut worst = 0.0f64;
        let mut x = 1u64;
        while x <= u32::MAX as u64 {
            for v in [x, x + x / 3, x + x / 2, x + 7 * x / 9] {
                let Ok(v) = u32::try_from(v) else {
                    continue;
                };
                let (y, e) = rsqrt(v);
                let got = y as f64 / (e as f64).exp2();
                let want = 1.0 / (v as f64).sqrt();
                worst = worst.max((got / want - 1.0).abs());
            }
            x = x * 2 + 1;
        }
        assert!(worst <= 1.5 / 32768.0, "relative error {worst}");
    }

    #[test]
    fn sqrt_q30_within_one_step() {
        for k in 0..=1000u64 {
            let x = ((k << 30) / 1000) as u32;
            let want = ((x as f64) / (1u64 << 30) as f64).sqrt() * 32768.0;
            let got = sqrt_q30(x) as f64;
            assert!((got - want).abs() <= 1.5, "{x}: {got} vs {want}");
        }
    }

    extern crate std;
    use crate::runs::merge_runs;
    use std::vec::Vec;

    /// Every narrow surface of the exponent series at 320×240, with the run it came from.
    fn surfaces(frame: &PreparedFixed<16, 8>) -> Vec<(Surface, V3<i32>)> {
        let mut out = Vec::new();
        for y in 0..frame.height {
            let spans = frame.row_spans(y);
            for run in merge_runs::<16>(&spans) {
                let mut state = NarrowRun::new();
                assert!(frame.narrow_run(&mut state, run.start, run.end, y, &spans));
                for _ in run.start..run.end {
                    let d = state.d;
                    if let Some(surface) = frame.narrow_surface(&mut state) {
                        out.push((surface, d));
                    }
                }
            }
        }
        out
    }

    #[test]
    fn narrow_vectors_within_delta() {
        const NV_MIN: f64 = 0.3;
        let scene = crate::exponent_series().unwrap();
        let frame = PreparedFixed::<16, 8>::new(&scene, 320, 240).unwrap();
        let FixedLight::Distant { to_light, .. } = frame.lights[0] else {
            panic!("the exponent series has one distant light");
        };
        let l = to_light.map(|c| c.to_bits() as f64 / (1u64 << 30) as f64);
        let (mut worst_n, mut worst_rv, mut count) = (0.0f64, 0.0f64, 0);
        let (mut worst_lobe, mut lit) = (0.0f64, 0);
        for (surface, d) in surfaces(&frame) {
            let s = &frame.spheres[surface.index];
            // The exact hit of the narrow ray, in f64.
            let d = d.map(|c| c as f64);
            let len = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
            let dh = d.map(|c| c / len);
            let oc = s.eye_offset.map(|c| c.to_bits() as f64);
            let r = (s.radius_sq.to_bits() as f64).sqrt();
            let b = oc[0] * dh[0] + oc[1] * dh[1] + oc[2] * dh[2];
            let disc = b * b - (oc[0] * oc[0] + oc[1] * oc[1] + oc[2] * oc[2]) + r * r;
            if disc < 0.0 {
                continue; // a silhouette pixel the narrow test rounds inside
            }
            let t = -b - disc.sqrt();
            let n = each3(|i| (oc[i] + t * dh[i]) / r);
            let nl = n[0] * l[0] + n[1] * l[1] + n[2] * l[2];
            let rv = each3(|i| 2.0 * nl * n[i] - l[i] + dh[i]);
            // The same from the narrow values.
            let got_n = surface.n.map(|c| c as f64 / 32768.0);
            let l15 = to_light.map(|c| c.to_bits() >> 15);
            let nl15 = dot(surface.n, l15) >> 15;
            let got_rv = each3(|i| {
                (((nl15 * surface.n[i]) >> 14) - l15[i] + surface.dh[i]) as f64 / 32768.0
            });
            // At the silhouette N·V = √(1 − |u|²) amplifies the error of u without bound
            // (the geometry itself is that sensitive there): measure where N·V ≥ 0.1.
            let nv = -(n[0] * dh[0] + n[1] * dh[1] + n[2] * dh[2]);
            if nv < NV_MIN {
                continue;
            }
            for i in 0..3 {
                worst_n = worst_n.max((got_n[i] - n[i]).abs());
                worst_rv = worst_rv.max((got_rv[i] - rv[i]).abs());
            }
            count += 1;
            // DELTA_LOBE's region: h < 1/8, every sphere. For n ≥ 32 it holds h < 4/n,
            // where the lobe's slope n·√(2h)·e^(−nh) is above a tenth of its peak.
            let h = 0.5 * (rv[0] * rv[0] + rv[1] * rv[1] + rv[2] * rv[2]);
            if nl > 0.0 && h < 0.125 {
                for i in 0..3 {
                    worst_lobe = worst_lobe.max((got_rv[i] - rv[i]).abs());
                }
                lit += 1;
            }
        }
        std::println!(
            "{count} surfaces: |ΔN| ≤ {:.2} steps, |Δ(R − V)| ≤ {:.2} steps of 2⁻¹⁵ (DELTA is {} steps)",
            worst_n * 32768.0,
            worst_rv * 32768.0,
            DELTA * 32768.0
        );
        std::println!(
            "{lit} where h < 1/8: |Δ(R − V)| ≤ {:.2} steps (DELTA_LOBE is {} steps)",
            worst_lobe * 32768.0,
            DELTA_LOBE * 32768.0
        );
        assert!(count > 10_000, "{count} surfaces");
        assert!(lit > 500, "{lit} surfaces in lit lobes");
        assert!(
            worst_lobe <= DELTA_LOBE as f64,
            "R − V off by {worst_lobe} in a lobe"
        );
        assert!(worst_rv <= DELTA as f64, "R − V off by {worst_rv}");
        assert!(worst_n <= DELTA as f64, "N off by {worst_n}");
    }

    #[test]
    fn exponent_series_hands_few_pixels_over() {
        let scene = crate::exponent_series().unwrap();
        let frame = PreparedFixed::<16, 8>::new(&scene, 320, 240).unwrap();
        let all = surfaces(&frame);
        let precise = |precise_darks| {
            all.iter()
                .filter(|(s, _)| {
                    matches!(
                        frame.narrow_lights(s, false, precise_darks),
                        Narrow::Precise
                    )
                })
                .count()
        };
        let (srgb, linear) = (precise(true), precise(false));
        std::println!(
            "of {} covered pixels, {srgb} use the full-width kernel under sRGB, {linear} under \
             the linear transfer",
            all.len()
        );
        assert!(
            (srgb as f64) < 0.03 * all.len() as f64,
            "{srgb} handed over under sRGB"
        );
        // The dark silhouette pixels are most of those handed over; linear levels keep them.
        assert!(
            2 * linear < srgb,
            "{linear} under linear, {srgb} under sRGB"
        );
    }

    #[test]
    fn narrow_lobe_matches_powf() {
        let mut worst = (0.0f64, 0.0, 0.0);
        for n in [0.5f32, 1.0, 2.0, 7.5, 10.0, 50.0, 100.0, 256.0] {
            let exact = Exact::from_f32(n);
            for k in 0..20_000u32 {
                // h dense near 0, where the lobe of a large n lives, and across (0, 1).
                let h = if k < 10_000 {
                    (k as u64 * k as u64 * (1 << 31) / 100_000_000 / 64) as u32
                } else {
                    ((k - 10_000) as u64 * (1 << 31) / 10_000) as u32
                };
                let got = narrow_lobe(h, exact) as f64 / 65536.0;
                let want = (1.0 - h as f64 / (1u64 << 31) as f64).powf(n as f64);
                let err = (got - want).abs();
                if err > worst.0 {
                    worst = (err, n as f64, h as f64 / (1u64 << 31) as f64);
                }
            }
        }
        std::println!(
            "narrow lobe: max abs error {:.2e} (n = {}, h = {:.3e})",
            worst.0,
            worst.1,
            worst.2
        );
        assert!(worst.0 < 2e-4, "{worst:?}");
    }

    /// A xorshift generator of uniform numbers in `[lo, hi)`, from `seed`.
    fn uniform(seed: u64) -> impl FnMut(f32, f32) -> f32 {
        let mut state = seed;
        move |lo: f32, hi: f32| {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            lo + (hi - lo) * ((state >> 40) as f32 / (1u64 << 24) as f32)
        }
    }

    /// Random frames the narrow kernel takes (one to three distant lights, up to six
    /// Phong and Blinn-Phong spheres that may overlap and shadow each other) against the
    /// `f64` reference: the fixed path's budget, and most frames must use the kernel.
    #[test]
    fn random_narrow_frames_within_budget() {
        use crate::reference::{self, RefPixel};
        use crate::scene::{Camera, Light, Material, Model, Scene, Sphere};
        use crate::vec3::Vec3;
        use crate::{HitRecord, LinearRgb, Render, Rgb888};
        let mut next = uniform(0x2545_f491_4f6c_dd1du64);
        let (w, h) = (160u32, 120u32);
        let (mut narrow_frames, mut worst, mut differ) = (0, 0u16, 0usize);
        let (mut pixels, mut within_one) = (0usize, 0usize);
        for _ in 0..24 {
            let angle = next(-3.1, 3.1);
            let camera = Camera {
                position: Vec3::new(9.0 * angle.sin(), next(-3.0, 3.0), 9.0 * angle.cos()),
                look_at: Vec3::new(0.0, 0.0, 0.0),
                up: Vec3::new(0.0, 1.0, 0.0),
                vfov_degrees: next(25.0, 60.0),
            };
            let mut scene: Scene<8, 4> =
                Scene::new(camera, LinearRgb::new(next(0.0, 0.3), 0.1, 0.2)).unwrap();
            for _ in 0..(next(1.0, 6.99) as usize) {
                let model = if next(0.0, 1.0) < 0.5 {
                    Model::Phong
                } else {
                    Model::BlinnPhong
                };
                scene
                    .add_sphere(Sphere {
                        center: Vec3::new(next(-3.0, 3.0), next(-2.0, 2.0), next(-3.0, 3.0)),
                        radius: next(0.3, 1.5),
                        material: Material {
                            albedo: LinearRgb::new(next(0.0, 1.0), next(0.0, 1.0), next(0.0, 1.0)),
                            kd: next(0.2, 0.9),
                            ks: next(0.0, 0.6),
                            shininess: libm::powf(2.0, next(0.0, 11.0)),
                            model,
                        },
                    })
                    .unwrap();
            }
            for _ in 0..(next(1.0, 3.99) as usize) {
                scene
                    .add_light(Light::Distant {
                        direction: Vec3::new(next(-1.0, 1.0), next(-1.0, 0.2), next(-1.0, 1.0)),
                        color: LinearRgb::new(1.0, next(0.7, 1.0), next(0.7, 1.0)),
                        intensity: next(0.5, 2.0),
                    })
                    .unwrap();
            }
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

    /// The caster filter only skips tests the exact one fails: on random frames of spheres
    /// close enough to shadow each other (most within eight radii, the filter's reach), every
    /// pixel's colour and hit record is the same with the filter and without it.
    #[test]
    fn the_caster_filter_changes_no_pixel() {
        use crate::scene::{Camera, Light, Material, Model, Scene, Sphere};
        use crate::vec3::Vec3;
        use crate::{HitRecord, LinearRgb, Render, Rgb888};
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
            if with.narrow.is_none()
                || with
                    .spheres
                    .iter()
                    .all(|s| s.narrow.as_ref().is_none_or(|n| n.fast.is_none()))
            {
                continue;
            }
            filtered += 1;
            let mut without = with.clone();
            for s in without.spheres.iter_mut() {
                if let Some(n) = s.narrow.as_mut() {
                    n.fast = None;
                }
            }
            let mut a = std::vec![Rgb888::default(); (w * h) as usize];
            let mut b = a.clone();
            with.render_frame(&mut a).unwrap();
            without.render_frame(&mut b).unwrap();
            let mut ha = std::vec![HitRecord::default(); (w * h) as usize];
            let mut hb = ha.clone();
            with.render_frame(&mut ha).unwrap();
            without.render_frame(&mut hb).unwrap();
            assert!(a == b && ha == hb, "the caster filter changed a pixel");
            shadowed_pixels += hb.iter().filter(|h| h.shadowed != 0).count();
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
