//! The prepare step of the fixed path: the scene converted to fixed point, once per frame.
//!
//! This is the only place the fixed path touches floating point: `f32` arithmetic (IEEE `+ − × ÷`,
//! exact power-of-two scaling), `libm`'s `sqrtf`/`floorf`/`ceilf` and the camera's tangent
//! (`Camera::tan_half_fov`), the same operations on every target, followed by exact conversions to
//! fixed bits ([`super::convert`]). So the prepared numbers, and with them every pixel, are the
//! same bits on a host, a Cortex-M0 and a RISC-V core.
//!
//! What it does, in order: check the size and the camera's plane scale; pick the scene's
//! power-of-two scale; convert and check every sphere, material and light (each refusal is
//! [`RenderError::OutOfFixedRange`] naming the item and field); compute each sphere's screen
//! rectangle (`spans`, with the full-width kernel); then, for a frame the narrow kernel
//! takes, its constants ([`super::narrow_prepare`]: the exact quadrics, the caster filters
//! and, without the full-width kernel, each sphere's rows and columns).

use super::convert::{fixed_bits, fixed_bits_i32, fixed_bits_u32};
use super::exact::Exact;
use super::mul::{dot_ii, mul_ii};
use super::quadric::Quadric;
#[cfg(feature = "full-width")]
use super::roots::inv_sqrt;
#[cfg(feature = "full-width")]
use super::spans::{Bounds, View};
use super::vector::{each3, Len, Unit, V3};
use crate::brdf::{Params, BLINN_PHONG, LOBES};
use crate::render::{Kernel, RenderError};
#[cfg(not(feature = "full-width"))]
use crate::scene::Model;
use crate::scene::{Item, Light, Scene, MORE_LOBES};
use crate::vec3::Vec3;
use crate::MAX_DIMENSION;
use fixed::types::{I16F48, I32F32, U16F16};

/// The scene is scaled by a power of two so that its extent is below `2^EXTENT_LOG2` units.
pub(crate) const EXTENT_LOG2: i32 = 13;
/// The largest scale, `2¹⁹`: keeps the ray epsilon (`10⁻⁴` for scenes smaller than one unit)
/// below 64 units.
pub(crate) const MAX_SCALE_LOG2: i32 = 19;

/// Smallest sphere radius after scaling, in units (`2¹⁶` raw I16F16 steps): normals then
/// carry at least 16 bits. In scene terms: a radius at least `2⁻¹³` of the scene's extent.
pub const MIN_SCALED_RADIUS: f32 = 1.0;
/// Largest `tan(vfov/2)·max(1, width/height)`: keeps primary-ray directions within ±256.
pub const MAX_PLANE_SCALE: f32 = 127.0;
/// Largest `kd·albedo`, `ks` and distant-light `colour·intensity` per channel: they are
/// U16F16 and two of them multiply and add without wrapping.
pub const MAX_LEVEL: f32 = 32_767.0;

/// The primary directions of a frame in narrow form: `D = forward + dy·step_y + dx·step_x`
/// with `dx = 2x + 1 − w` and `dy = h − 2y − 1`, integer vectors with `|D| < 2³⁰`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct NarrowView {
    pub forward: V3<i32>,
    pub step_x: V3<i32>,
    pub step_y: V3<i32>,
}

impl NarrowView {
    /// The quadrics' three directions `[forward, step_x, step_y]` (see [`super::quadric`]).
    pub(crate) fn dirs(&self) -> [V3<i32>; 3] {
        [self.forward, self.step_x, self.step_y]
    }
}

/// A sphere's narrow constants, the per-pixel ones first (see [`FixedSphere`]).
///
/// Its two quadrics (`e` here, `g` per light in [`NarrowLight`]) hold, for the direction `d`
/// of a pixel (`D/2²⁹`, length in `[1, √2]`) and `ô = (eye − centre)/r`:
///
/// - `E′ = |d|² − |ô × d|²`, the ray's discriminant times `|d|²/r²`: the ray hits iff
///   `E′ ≥ 0`, and then `N·V = √(E′/|d|²)`;
/// - `G = (ô × d)·(L × d)`, from which `N·L = (G − √E′·(d·L))/|d|²`.
///
/// `e` is held times `2^(29 + e_shift)` and `g` times `2^(29 + g_shift)`, the largest powers
/// that keep every value in the frame 16 times below `2⁶³` (`|E′| ≤ 2·max(1, |ô|²)`,
/// `|G| ≤ 2|ô|`), so a value shifted right by its shift is `E′` or `G` in Q29.
#[derive(Clone, Copy, Debug)]
#[repr(C)]
pub(crate) struct NarrowSphere {
    /// The largest fast lobe (U1F16) that is within half a level where `h ≤ ½`: 2¹⁶ or more
    /// if it is wherever the lobe is not 0, 0 if nowhere (see the narrow module).
    pub fast_lobe_max: u32,
    /// `1 − r²/(r + ε)²` in Q30: `(N·L)²` above it, with `N·L < 0`, is in the own shadow.
    pub shadow_limit: u32,
    /// `h` (Q31) from which the lobe is 0.
    pub cutoff: u32,
    /// `N` from `oc × D` (on demand, for caster tests): that product's bits from
    /// `cross_shift` on, `(oc × D) >> cross_shift`, are below `2¹⁶` on a hit; with
    /// `gain = 2^(L + 15)/r` (`L` the raw radius's bit length, `cross_shift = L + 14`).
    pub gain: u32,
    /// `c = |ô|² − 1` for the fast `t` (`narrow_hit`): `c·2^(30 − 2·c_shift)` with
    /// `c_shift` the least that makes `1 + c` at most `4^c_shift`, so that
    /// `((N·V)² + c)·2^(−2·c_shift)` is at most 1 in Q30.
    pub c_q30: u32,
    /// `r·c` (raw) as a 16-bit mantissa and a power of two (`t_exponent`):
    /// `t = r·c/(N·V + √((N·V)² + c))`.
    pub t_mantissa: u16,
    /// See the type's docs.
    pub e_shift: u8,
    pub g_shift: u8,
    /// See `gain`.
    pub cross_shift: u8,
    /// Whether `b = oc·D` grows along a row (`oc·step_x > 0`).
    pub b_rises: bool,
    /// A normalized model (not Lambert): every light is shaded with the full-width
    /// kernel's normalized terms (`narrow_terms`, `normalized_terms`).
    pub terms: bool,
    /// See `c_q30`.
    pub c_shift: u8,
    /// See `t_mantissa`.
    pub t_exponent: i8,
    /// `E′`, see above.
    pub e: Quadric,
    /// The rows and the columns on which `E′` can be at least 0, each `[start, end)` (see
    /// `outline`): the spans without the full-width kernel.
    #[cfg(not(feature = "full-width"))]
    pub rows: (u32, u32),
    #[cfg(not(feature = "full-width"))]
    pub columns: (u32, u32),
    /// The spheres within `4ε` of this one (bit `k` for sphere `k`; a sphere resting on a
    /// floor sphere, and the floor under it): only from these can a lifted point start
    /// inside a caster, which the caster test then checks for (`narrow_blocked`).
    pub touching: u32,
    /// The margin of the quick caster test (`narrow_blocked`) where this sphere receives a
    /// shadow, in that test's units ([`PreparedFixed::quick_shift`]): a bound on its
    /// rounding and on how far the exact test's `|oc|² − b² ≤ r²` reaches beyond the
    /// caster's cylinder, from the largest `|O − C_k|` the sphere's lifted points can have.
    /// `−1`: no quick test.
    pub quick_margin: i32,
}

/// A point light as the narrow kernel sees it from the eye: `Q = P − eye` as a unit vector
/// (I2F30 bits) and its length (raw). The kernel's quadrics for a point light are those of a
/// distant light along `Q/|Q|` (see module `narrow`), and the distance and direction to the
/// light at a hit `X = eye + t·D̂` follow from `Q − t·D̂`.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct NarrowPoint {
    pub dir: [i32; 3],
    #[cfg(feature = "narrow-precise")]
    pub distance: u32,
}

/// A sphere's narrow constants for one light: `G` (see [`NarrowSphere`]) and a filter in
/// front of the caster tests. For a point light, `G` is that of the direction from the eye
/// toward it ([`NarrowPoint`]), and the filter passes every pixel to the caster tests.
///
/// The filter holds for the lifted origin `O = C + (r + ε)·N` of any caster `k` of the
/// sphere: the shadow ray can meet the caster only if `O` is behind it along `L`
/// (`N·L < −(C − C_k)·L/(r + ε)`) and if `O` can come within `r_k` of the caster's axis,
/// `C_k + s·L`: at a given `N·L`, `N`'s part across `L` has length `√(1 − (N·L)²)`, so that
/// needs `(N·L)² ≤ 1 − ((|Δ⊥| − r_k)/(r + ε))²` with `Δ⊥` the part of `C − C_k` across `L`.
/// `ahead` and `reach` are the loosest of these over the casters, widened by the fast
/// `N·L`'s error; a pixel outside them skips every caster test for the light.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct NarrowLight {
    pub g: Quadric,
    /// The spheres that can shadow the sphere from this light (bit `k` for sphere `k`, see
    /// `PreparedFixed::narrow_casters`).
    pub casters: u32,
    /// `N·L` (Q15) at or above this: no caster is ahead.
    pub ahead: i32,
    /// `(N·L)²` (Q30) above this: no caster is within reach.
    pub reach: u32,
    /// The sphere's centre across the light from the eye, `(C − eye)·u` and `(C − eye)·v`
    /// in the quick caster test's units ([`PreparedFixed::quick_shift`]), `u` and `v` the
    /// light's [`PreparedFixed::across`]: the constants of the quick caster test and of the
    /// distance test's first stage (`PreparedFixed::distant_casters`).
    pub across: [i32; 2],
    /// For a point light, where the fast point light (`narrow_point`) shades this sphere:
    /// 0 nowhere; otherwise the fast lobe's limit, as `NarrowSphere::fast_lobe_max` is for
    /// the distant lights (`u16::MAX`: wherever the lobe is not 0).
    #[cfg(feature = "narrow-precise")]
    pub point_fast: u16,
    /// For a point light, the largest `(|Q|/|P − X|)²` (Q4) at which the fast point light
    /// serves on this sphere (see `narrow_point`), at most 255.
    #[cfg(feature = "narrow-precise")]
    pub point_ratio: u8,
    /// For a point light, the bound (Q15) of the error of the fast direction toward it on
    /// this sphere, for the shadow filters' margins (`narrow_point_shadow`).
    #[cfg(feature = "narrow-precise")]
    pub point_slack: u8,
    /// For a point light, this sphere as a caster: the unit vector from the light toward its
    /// centre (Q15) and the cosine (Q15, lowered by a margin) of the cone from the light that
    /// holds it. A shadow ray toward the light meets the sphere only from a point in that
    /// cone (`narrow_point`'s filter). A threshold of `i16::MIN` passes every point.
    #[cfg(feature = "narrow-precise")]
    pub cone: [i16; 4],
}

/// A sphere's per-frame constants, in scaled units.
///
/// `repr(C)` with the narrow kernel's per-pixel fields first: ARMv6-M's loads reach only
/// 124 bytes past a base register (62 for halfwords, 31 for bytes), and fields beyond that
/// cost the row loop an address computation each, which it keeps in stack slots.
#[derive(Clone, Copy, Debug)]
#[repr(C)]
pub(crate) struct FixedSphere {
    /// The narrow kernel's constants, if the frame uses it.
    pub narrow: Option<NarrowSphere>,
    pub kd_albedo: V3<U16F16>,
    pub ks: U16F16,
    pub shininess: Exact,
    pub blinn: bool,
    /// A normalized model (or Lambert): the kernel's `normalized` terms, not the classic ones.
    pub normalized: bool,
    /// Schlick's factor applies.
    pub schlick: bool,
    /// The diffuse lobe is multiplied by `1 − F`.
    pub diffuse_loss: bool,
    pub center: V3<Len>,
    /// `eye − centre`: the primary rays' origin offset.
    pub eye_offset: V3<Len>,
    pub radius_sq: I32F32,
    /// `1/r` of the raw radius bits, as [`inv_sqrt`] returns it: `y·2^-shift`. Only the
    /// full-width kernel reads it.
    #[cfg(feature = "full-width")]
    pub inv_radius: (u32, u32),
    /// Normalized models: each lobe's weight times its normalization factor, exact.
    pub weight: [Exact; LOBES],
    /// Exponents of lobes 1 and 2.
    pub more_shininess: [Exact; MORE_LOBES],
    /// `F₀` per channel, U2F30 (`1 << 30` is 1).
    pub f0: [u32; 3],
    /// The sphere's spans: its screen rectangle and its outline's row conic; `None` if the
    /// sphere is off screen. (Without the full-width kernel, the spans are the narrow
    /// quadric's, see `outline`.)
    #[cfg(feature = "full-width")]
    pub bounds: Option<Bounds>,
    /// Oren–Nayar's `A` and `B` (U2F30), if the diffuse lobe is Oren–Nayar's.
    #[cfg(feature = "models")]
    pub oren_nayar: Option<[u32; 2]>,
    /// GGX's constants, if the specular lobe is GGX.
    #[cfg(feature = "models")]
    pub ggx: Option<FixedGgx>,
    /// The scaled radius: for the narrow kernel's prepare (its square is `radius_sq`) and
    /// the soft shadows of sphere lights.
    pub radius: Len,
    /// Per lobe (`shininess`, then `more_shininess`), the constants of its energy factor
    /// under a sphere light (`area::lobe_widening`): `√(πn′/2)` in U16F16 and `n′/2` in
    /// U20F12, saturating.
    #[cfg(all(feature = "area-lights", feature = "full-width"))]
    pub widening: [[u32; 2]; LOBES],
}

impl FixedSphere {
    /// Whether the lobe is Blinn-Phong's: always `false` in a build without the feature
    /// `blinn-phong` ([`BLINN_PHONG`]), whose scenes hold no such sphere, so that the kernels'
    /// half-vector code is left out.
    #[inline(always)]
    pub(crate) fn blinn(&self) -> bool {
        BLINN_PHONG && self.blinn
    }
}

/// A GGX sphere's constants (`α = roughness²`).
#[cfg(feature = "models")]
#[derive(Clone, Copy, Debug)]
#[cfg_attr(not(feature = "full-width"), allow(dead_code))]
pub(crate) struct FixedGgx {
    /// `α²`, U1F31.
    pub alpha2: u32,
    /// `1 − α²`, U1F31.
    pub one_minus_alpha2: u32,
    /// `ks·α²/(2π)`, the `f32` value exactly.
    pub scale: Exact,
    /// `α`, U1F31, for the widening under a sphere light.
    #[cfg(all(feature = "area-lights", feature = "full-width"))]
    pub alpha: u32,
}

/// A light's per-frame constants.
#[derive(Clone, Copy, Debug)]
pub(crate) enum FixedLight {
    /// `to_light`: unit vector toward the light; `arriving`: `colour·intensity`.
    Distant {
        to_light: V3<Unit>,
        arriving: V3<U16F16>,
    },
    /// `power`: `colour·intensity/4π` times the scale squared, per channel, exact; arriving
    /// is `power/d²` in scaled units ([`super::exact::arriving`]).
    Point { position: V3<Len>, power: V3<Exact> },
    /// A sphere light (a point light with a radius, see `area`): `position` and `power` as
    /// for `Point`, and its scaled radius.
    #[cfg(all(feature = "area-lights", feature = "full-width"))]
    Sphere {
        position: V3<Len>,
        power: V3<Exact>,
        radius: Len,
    },
}

/// A scene prepared for the fixed-point path at one size: integers only per row and pixel.
///
/// ```
/// use shadeline::{exponent_series, PreparedFixed, Render, Rgb565};
/// let frame = PreparedFixed::new(&exponent_series()?, 64, 48)?;
/// let mut line = [Rgb565::default(); 64];
/// frame.render_line(24, &mut line)?;
/// assert_ne!(line[20], line[0]); // a sphere, then the background
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug)]
pub struct PreparedFixed<const S: usize = 16, const L: usize = 8> {
    pub(crate) width: u32,
    pub(crate) height: u32,
    pub(crate) eye: V3<Len>,
    /// Half a pixel to the right on the image plane `z = 1`: `right·tan(vfov/2)/h`.
    pub(crate) step_x: V3<I16F48>,
    /// Half a pixel up: `up·tan(vfov/2)/h`.
    pub(crate) step_y: V3<I16F48>,
    pub(crate) forward: V3<I16F48>,
    pub(crate) epsilon: Len,
    pub(crate) background: [u32; 3],
    pub(crate) spheres: heapless::Vec<FixedSphere, S>,
    pub(crate) lights: heapless::Vec<FixedLight, L>,
    /// Per sphere and light, the other spheres that can shadow it
    /// ([`Scene::shadow_casters`]), for the full-width kernel (the narrow kernel's are in
    /// `narrow_lights`).
    #[cfg(feature = "full-width")]
    pub(crate) casters: heapless::Vec<[u32; L], S>,
    /// The kernel the rows take, with the reason if not the narrow one
    /// (`prepare_narrow_or_refuse`). Without the full-width kernel every frame is a narrow
    /// one, and [`PreparedFixed::kernel`] says so without a field.
    #[cfg(feature = "full-width")]
    pub(crate) kernel: Kernel,
    /// The primary directions in the narrow kernel's form, if the frame uses it: `Some`
    /// exactly when the kernel is [`Kernel::Narrow`] (in a prepared frame).
    pub(crate) narrow: Option<NarrowView>,
    /// Per sphere and light, the narrow kernel's constants (set with `narrow`).
    pub(crate) narrow_lights: heapless::Vec<[NarrowLight; L], S>,
    /// Per distant light, two unit vectors `u`, `v` (Q15) across it, `L`, `u`, `v` an
    /// orthonormal basis up to rounding: the quick caster test measures a lifted point's
    /// distance from a caster's axis along the light in them (set with `narrow`).
    pub(crate) across: [[[i16; 3]; 2]; L],
    /// Per point light, its direction and distance from the eye (set with `narrow`).
    pub(crate) points: [NarrowPoint; L],
    /// Whether some pixels take the narrow kernel's precise cosines (a point light, or a
    /// sphere of a normalized model): the row driver's choice of pixel loop (set with
    /// `narrow`).
    pub(crate) precise_pixels: bool,
    /// The quick caster test's unit of length, `2^quick_shift` raw: the smallest that
    /// takes every sphere's `r + ε` below `2¹⁶` units (set with `narrow`).
    pub(crate) quick_shift: u32,
    pub(crate) use_spans: bool,
    /// Whether silhouettes are anti-aliased ([`PreparedFixed::with_antialiasing`]).
    #[cfg(all(feature = "antialias", feature = "full-width"))]
    pub(crate) antialias: bool,
}

/// A lobe's constants for `area::lobe_widening`, from its exponent `n` (`n′ = n`, or `n/4`
/// for Blinn-Phong): `[√(πn′/2)` in U16F16, `n′/2` in U20F12`]`, saturating (0 for `n = 0`).
#[cfg(all(feature = "area-lights", feature = "full-width"))]
fn widening(n: f32, blinn: bool) -> [u32; 2] {
    let n = if blinn { n * 0.25 } else { n };
    let a = libm::sqrtf(core::f32::consts::FRAC_PI_2 * n);
    [fixed_bits_u32(a, 16), fixed_bits_u32(0.5 * n, 12)].map(|b| b.unwrap_or(u32::MAX))
}

fn out_of_range(item: Item, field: &'static str) -> RenderError {
    RenderError::OutOfFixedRange {
        item,
        field,
        beside: None,
    }
}

/// The refusal of sphere `sphere`, whose radius is below `2⁻¹³` of the scene's extent: it also
/// names the largest sphere (a floor sphere, say) when that is another and reaches at least
/// half as far as the camera, so that its size is what sets the extent. In integers: a
/// finite `f32`'s magnitude orders as its bits, and doubling it adds `2²³` to them. Out of
/// line: only refused scenes reach it.
#[inline(never)]
fn small_beside_extent<const S: usize, const L: usize>(
    scene: &Scene<S, L>,
    sphere: usize,
) -> RenderError {
    let magnitude = |v: f32| v.to_bits() & 0x7fff_ffff;
    let eye = scene.camera().position;
    let camera = magnitude(eye.x).max(magnitude(eye.y)).max(magnitude(eye.z));
    let (mut largest, mut beside) = (0, None);
    for (i, s) in scene.spheres().iter().enumerate() {
        if magnitude(s.radius) > largest {
            largest = magnitude(s.radius);
            beside = u16::try_from(i).ok();
        }
    }
    if beside.map(usize::from) == Some(sphere) || largest + (1 << 23) < camera {
        beside = None;
    }
    RenderError::OutOfFixedRange {
        item: Item::Sphere(sphere),
        field: "radius",
        beside,
    }
}

/// `v·scale` per component in fixed point with `frac` fraction bits ([`fixed_bits`]), if
/// each is within `lo..=hi`. Out of line: every point, colour and direction of the prepare
/// goes through it.
#[inline(never)]
fn scaled_bits(v: [f32; 3], scale: f32, frac: u32, (lo, hi): (i64, i64)) -> Option<[i64; 3]> {
    let mut out = [0i64; 3];
    for (o, c) in out.iter_mut().zip(v) {
        *o = fixed_bits(c * scale, frac).filter(|b| (lo..=hi).contains(b))?;
    }
    Some(out)
}

fn to_len(v: Vec3, scale: f32, item: Item, field: &'static str) -> Result<V3<Len>, RenderError> {
    let range = (i32::MIN as i64, i32::MAX as i64);
    scaled_bits([v.x, v.y, v.z], scale, 16, range)
        .map(|b| b.map(|c| Len::from_bits(c as i32)))
        .ok_or(out_of_range(item, field))
}

fn to_wide(v: Vec3, scale: f32) -> Result<V3<I16F48>, RenderError> {
    scaled_bits([v.x, v.y, v.z], scale, 48, (i64::MIN, i64::MAX))
        .map(|b| b.map(I16F48::from_bits))
        .ok_or(out_of_range(Item::Camera, "vfov"))
}

/// The I2F30 unit vector of `d`, a unit vector in `f32` (within `2⁻²³` of unit length):
/// its components rounded to 30 bits (each at most about 1, which I2F30 holds: no
/// saturation is needed, and a component that did not convert, which no unit vector has,
/// would read as 0), then one Newton step toward unit length, `v·(1 − ε/2)` for
/// `|v|² = 1 + ε`, which leaves it within `2⁻⁴⁰` of unit length before the components'
/// rounding. Exact integer arithmetic after the conversion, so the same bits on every
/// target; a few products instead of the general normalization, for a vector already
/// within a few ulps of unit length. Inlined on ARMv6-M, where its caller is too (see
/// `prepare_fields`): smaller there.
#[cfg_attr(shadeline_short_mul, inline(always))]
#[cfg_attr(not(shadeline_short_mul), inline(never))]
fn unit_q30(d: Vec3) -> V3<Unit> {
    let v = [d.x, d.y, d.z].map(|c| fixed_bits_i32(c, 30).unwrap_or(0));
    let len2 = dot_ii(v, v);
    // ε = |v|² − 1 in Q60 (|ε| < 2⁻²¹: the f32 vector's rounding and the 30-bit one), then
    // ε/2 in Q51, which holds |ε| < 2⁻²⁰ in an i32; c·ε/2 is then below 2⁶⁰.
    let half_eps = ((len2 - (1 << 60)) >> 10).clamp(-(1 << 30), 1 << 30) as i32;
    // |c·ε/2| < 2¹⁰ and |c| ≤ 2³⁰: the difference fits I2F30.
    v.map(|c| Unit::from_bits(c - (mul_ii(c, half_eps) >> 51) as i32))
}

/// Per-channel levels checked against [`MAX_LEVEL`]: U16F16 bits up to `MAX_LEVEL·2¹⁶`,
/// which is where the `f32` levels up to `MAX_LEVEL` round to (the next `f32` above it,
/// `MAX_LEVEL + 2⁻⁹`, rounds above). A scene's colours and factors are checked
/// non-negative, and so are their products; a negative level is refused all the same,
/// unless it rounds to zero.
fn to_levels(c: [f32; 3], item: Item, field: &'static str) -> Result<V3<U16F16>, RenderError> {
    const MAX_BITS: i64 = (MAX_LEVEL as i64) << 16;
    scaled_bits(c, 1.0, 16, (0, MAX_BITS))
        .map(|b| b.map(|c| U16F16::from_bits(c as u32)))
        .ok_or(out_of_range(item, field))
}

/// `2^k` as an `f32`, for `k` in `-126..=127`.
fn pow2(k: i32) -> f32 {
    f32::from_bits(((k + 127).clamp(1, 254) as u32) << 23)
}

/// The power of two `k` such that the scene's extent times `2^k` is below `2^EXTENT_LOG2`
/// units, as large as possible up to [`MAX_SCALE_LOG2`].
fn scale_log2<const S: usize, const L: usize>(scene: &Scene<S, L>) -> i32 {
    let extent = scene.extent();
    // extent = f·2^e with f in [½, 1): extent·2^(EXTENT_LOG2 − e) < 2^EXTENT_LOG2.
    let (_, e) = libm::frexpf(extent);
    (EXTENT_LOG2 - e).min(MAX_SCALE_LOG2)
}

impl<const S: usize, const L: usize> PreparedFixed<S, L> {
    /// Prepares `scene` for a `width × height` image on the fixed path.
    ///
    /// Fails with [`RenderError::BadSize`] like [`Prepared::new`](crate::Prepared::new), and
    /// with [`RenderError::OutOfFixedRange`] if a number does not fit the fixed formats (see
    /// the [module table](crate::fixed)): a sphere smaller than `2⁻¹³` of the scene's extent
    /// (`radius`), a field of view or aspect ratio with `tan(vfov/2)·max(1, w/h)` above
    /// [`MAX_PLANE_SCALE`] (`vfov`), and `kd·albedo`, `ks`, or a distant light's
    /// `colour·intensity` above [`MAX_LEVEL`] in a channel (`kd`, `ks`, `intensity`).
    pub fn new(scene: &Scene<S, L>, width: u32, height: u32) -> Result<Self, RenderError> {
        let mut frame = Self::EMPTY;
        frame.prepare(scene, width, height)?;
        Ok(frame)
    }

    /// A frame with no size and no spheres, to [`prepare`](Self::prepare) into: a constant,
    /// so that a firmware can keep its prepared frame in a `static` and prepare it there.
    /// Rendering it fails with a typed error: it has no rows.
    pub const EMPTY: Self = Self {
        width: 0,
        height: 0,
        eye: [Len::ZERO; 3],
        step_x: [I16F48::ZERO; 3],
        step_y: [I16F48::ZERO; 3],
        forward: [I16F48::ZERO; 3],
        epsilon: Len::ZERO,
        background: [0; 3],
        spheres: heapless::Vec::new(),
        lights: heapless::Vec::new(),
        #[cfg(feature = "full-width")]
        casters: heapless::Vec::new(),
        #[cfg(feature = "full-width")]
        kernel: Kernel::Narrow,
        narrow: None,
        narrow_lights: heapless::Vec::new(),
        across: [[[0; 3]; 2]; L],
        points: [NarrowPoint {
            dir: [0; 3],
            #[cfg(feature = "narrow-precise")]
            distance: 0,
        }; L],
        precise_pixels: false,
        quick_shift: 0,
        use_spans: true,
        #[cfg(all(feature = "antialias", feature = "full-width"))]
        antialias: false,
    };

    /// Prepares `scene` for a `width × height` image into `self`, in place: what [`new`](Self::new)
    /// returns, without the prepared frame ever being on the stack (the M0 firmware prepares its
    /// `static` frame this way). Fails like `new`; on an error
    /// `self` is left [`EMPTY`](Self::EMPTY), never half prepared. Spans are on, whatever
    /// [`with_spans`](Self::with_spans) set before.
    ///
    /// ```
    /// use shadeline::{exponent_series_with_capacity, PreparedFixed, Render, Rgb565, Scene};
    /// // In a firmware this is a `static`, prepared again whenever the scene moves.
    /// let mut frame = PreparedFixed::<5, 1>::EMPTY;
    /// let scene: Scene<5, 1> = exponent_series_with_capacity()?;
    /// frame.prepare(&scene, 64, 48)?;
    /// let mut line = [Rgb565::default(); 64];
    /// frame.render_line(24, &mut line)?;
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn prepare(
        &mut self,
        scene: &Scene<S, L>,
        width: u32,
        height: u32,
    ) -> Result<(), RenderError> {
        // Two calls in turn, not one inside the other: the narrow set-up's stack does not
        // add to the conversion's (the M0 firmware's peak stack is the prepare's).
        let result = self
            .prepare_fields(scene, width, height)
            .and_then(|corners| self.prepare_narrow_or_refuse(scene, corners));
        if result.is_err() {
            self.clear();
        }
        result
    }

    /// Resets `self` to [`EMPTY`](Self::EMPTY) field by field (no temporary frame).
    fn clear(&mut self) {
        self.width = 0;
        self.height = 0;
        self.spheres.clear();
        self.lights.clear();
        #[cfg(feature = "full-width")]
        self.casters.clear();
        #[cfg(feature = "full-width")]
        {
            self.kernel = Kernel::Narrow;
        }
        self.narrow = None;
        self.narrow_lights.clear();
        self.precise_pixels = false;
        self.use_spans = true;
        #[cfg(all(feature = "antialias", feature = "full-width"))]
        {
            self.antialias = false;
        }
    }

    /// Converts the scene into `self`'s fields (all but the narrow kernel's), and says
    /// whether every primary direction is within `√2` of the central one in length and the
    /// steps below ½, which the narrow kernel needs (see [`Self::prepare_narrow`]).
    /// Inlined into [`Self::prepare`] on ARMv6-M, where that is smaller at the same peak
    /// stack; out of line elsewhere: inlined, it is copied to every place a firmware prepares
    /// a frame (`docs/performance.md, "Choices measured"`).
    #[cfg_attr(shadeline_short_mul, inline(always))]
    #[cfg_attr(not(shadeline_short_mul), inline(never))]
    fn prepare_fields(
        &mut self,
        scene: &Scene<S, L>,
        width: u32,
        height: u32,
    ) -> Result<bool, RenderError> {
        self.clear();
        if width == 0 || height == 0 || width > MAX_DIMENSION || height > MAX_DIMENSION {
            return Err(RenderError::BadSize { width, height });
        }
        // A scene holds a sphere light only with `area-lights`; the fixed path shades it in
        // its full-width kernel.
        #[cfg(all(feature = "area-lights", not(feature = "full-width")))]
        if let Some(light) = scene.sphere_light() {
            return Err(RenderError::SphereLight { light });
        }
        let camera = scene.camera();
        let (right, up, forward) = scene.camera_basis();
        let tan = camera.tan_half_fov();
        let (width_f, height_f) = (width as f32, height as f32);
        let x_scale = (width_f / height_f) * tan;
        if !(tan <= MAX_PLANE_SCALE && x_scale <= MAX_PLANE_SCALE) {
            return Err(out_of_range(Item::Camera, "vfov"));
        }
        let half_pixel = tan / height_f;
        // The narrow kernel's view (see `prepare_narrow`). The corners' directions are the
        // longest: `|d|² = 1 + (dx² + dy²)·half_pixel²` for the orthonormal basis, at the
        // half-pixel offsets `dx = w − 1`, `dy = h − 1`. At most 2 less `2⁻⁸`: the steps'
        // rounding to Q29 (within `2⁻³⁰`, times offsets up to `2¹⁶`) and the basis' and this
        // sum's `f32` rounding move the narrow kernel's integer `|d|²` by less than `2⁻¹⁰`,
        // so it stays below 2. And the steps below ½ (a one-pixel-wide image leaves
        // `step_x` unbounded by the corners), so that in Q29 each component of a step, at
        // most `half_pixel` (`1 + 2⁻²²` with the basis' rounding), and twice it fit `i32`.
        let (dx, dy) = (width_f - 1.0, height_f - 1.0);
        let corners = (dx * dx + dy * dy) * half_pixel * half_pixel <= 1.0 - 1.0 / 256.0
            && half_pixel < 0.499;

        let k = scale_log2(scene);
        let scale = pow2(k);
        let eye = to_len(camera.position, scale, Item::Camera, "position")?;
        let epsilon = fixed_bits_i32(scene.ray_epsilon() * scale, 16)
            .map(Len::from_bits)
            .ok_or(out_of_range(Item::Camera, "position"))?;
        #[cfg(feature = "full-width")]
        let view = View {
            eye: camera.position,
            right,
            up,
            forward,
            half_pixel,
            width,
            height,
        };

        for (i, s) in scene.spheres().iter().enumerate() {
            let item = Item::Sphere(i);
            let m = &s.material;
            let center = to_len(s.center, scale, item, "center")?;
            let radius = fixed_bits_i32(s.radius * scale, 16)
                .map(Len::from_bits)
                .ok_or(out_of_range(item, "radius"))?;
            if radius < MIN_SCALED_RADIUS {
                return Err(small_beside_extent(scene, i));
            }
            let radius_raw = radius.to_bits() as i64;
            #[cfg(feature = "full-width")]
            let inv_radius =
                inv_sqrt((radius_raw * radius_raw) as u64).ok_or(out_of_range(item, "radius"))?;
            // The float paths' constants (`kd·albedo`, or `kd·albedo/π`; `ks`, or 1 for the
            // normalized models; normalization factors; F₀), converted to fixed formats.
            // Without the full-width kernel only the classic models render: the others are
            // refused here, before their constants are computed (and their code is linked).
            #[cfg(feature = "full-width")]
            let params = Params::<f32>::of(m);
            #[cfg(not(feature = "full-width"))]
            let params = match m.model {
                Model::OrenNayar { .. } | Model::Ggx(_) => {
                    return Err(RenderError::NeedsFullWidth {
                        item,
                        field: "model",
                    })
                }
                _ => Params::<f32>::of(m),
            };
            let kd_albedo = params.kd_albedo;
            let kd_albedo = to_levels([kd_albedo.x, kd_albedo.y, kd_albedo.z], item, "kd")?;
            let [ks, _, _] = to_levels([params.ks, 0.0, 0.0], item, "ks")?;
            let unit = |v: f32| (v.clamp(0.0, 1.0) * (1u32 << 30) as f32) as u32;
            let sphere = FixedSphere {
                center,
                eye_offset: each3(|c| eye[c] - center[c]),
                radius_sq: I32F32::from_bits(radius_raw * radius_raw),
                #[cfg(feature = "full-width")]
                inv_radius,
                kd_albedo,
                ks,
                shininess: Exact::from_f32(m.shininess),
                blinn: params.blinn > 0.0,
                normalized: params.normalized > 0.0,
                weight: params.weight.map(Exact::from_f32),
                more_shininess: params.more_shininess.map(Exact::from_f32),
                f0: [params.f0.x, params.f0.y, params.f0.z].map(unit),
                schlick: params.schlick > 0.0,
                diffuse_loss: params.diffuse_loss > 0.0,
                #[cfg(feature = "full-width")]
                bounds: view.bounds(s.center, s.radius),
                narrow: None,
                #[cfg(feature = "models")]
                oren_nayar: (params.oren_nayar > 0.0)
                    .then(|| [unit(params.on_a), unit(params.on_b)]),
                #[cfg(feature = "models")]
                ggx: (params.ggx > 0.0).then(|| {
                    let u1f31 = |v: f32| (v.clamp(0.0, 1.0) * (1u64 << 31) as f32) as u32;
                    FixedGgx {
                        alpha2: u1f31(params.alpha2),
                        one_minus_alpha2: u1f31(1.0 - params.alpha2),
                        scale: Exact::from_f32(
                            params.weight[0] * params.alpha2 / (2.0 * core::f32::consts::PI),
                        ),
                        #[cfg(all(feature = "area-lights", feature = "full-width"))]
                        alpha: u1f31(libm::sqrtf(params.alpha2)),
                    }
                }),
                radius,
                #[cfg(all(feature = "area-lights", feature = "full-width"))]
                widening: {
                    let exponents = [
                        m.shininess,
                        params.more_shininess[0],
                        params.more_shininess[1],
                    ];
                    exponents.map(|e| widening(e, params.blinn > 0.0))
                },
            };
            // Same capacity as the scene: cannot fail.
            let pushed = self.spheres.push(sphere);
            debug_assert!(pushed.is_ok(), "sphere {i} beyond the prepared capacity");
        }

        for (i, l) in scene.lights().iter().enumerate() {
            let item = Item::Light(i);
            let light = match *l {
                Light::Distant {
                    direction,
                    color,
                    intensity,
                } => {
                    let arriving = Vec3::new(color.r, color.g, color.b).scale(intensity);
                    // Validated: a scene's light direction is finite and not zero.
                    let d = (-direction)
                        .normalized()
                        .ok_or(out_of_range(item, "direction"))?;
                    FixedLight::Distant {
                        to_light: unit_q30(d),
                        arriving: to_levels(
                            [arriving.x, arriving.y, arriving.z],
                            item,
                            "intensity",
                        )?,
                    }
                }
                // The narrow kernel renders point lights of radius 0 only.
                #[cfg(not(feature = "full-width"))]
                Light::Point { radius, .. } if radius > 0.0 => {
                    return Err(RenderError::NeedsFullWidth {
                        item,
                        field: "radius",
                    })
                }
                Light::Point {
                    position,
                    color,
                    intensity,
                    radius,
                } => {
                    let power = Vec3::new(color.r, color.g, color.b)
                        .scale(intensity / (4.0 * core::f32::consts::PI))
                        .scale(pow2(2 * k));
                    let power = [power.x, power.y, power.z];
                    if !power.iter().all(|p| p.is_finite()) {
                        return Err(out_of_range(item, "intensity"));
                    }
                    let position = to_len(position, scale, item, "position")?;
                    let power = power.map(Exact::from_f32);
                    #[cfg(feature = "area-lights")]
                    if radius > 0.0 {
                        let radius = fixed_bits_i32(radius * scale, 16)
                            .filter(|r| *r > 0)
                            .map(Len::from_bits)
                            .ok_or(out_of_range(item, "radius"))?;
                        let pushed = self.lights.push(FixedLight::Sphere {
                            position,
                            power,
                            radius,
                        });
                        debug_assert!(pushed.is_ok(), "light {i} beyond the prepared capacity");
                        continue;
                    }
                    let _ = radius;
                    FixedLight::Point { position, power }
                }
            };
            // Same capacity as the scene: cannot fail.
            let pushed = self.lights.push(light);
            debug_assert!(pushed.is_ok(), "light {i} beyond the prepared capacity");
        }

        #[cfg(feature = "full-width")]
        for i in 0..scene.spheres().len() {
            let mut per_light = [0u32; L];
            for (mask, light) in per_light.iter_mut().zip(scene.lights()) {
                *mask = scene.shadow_casters(i, light);
            }
            // Same capacity as the scene: cannot fail.
            let pushed = self.casters.push(per_light);
            debug_assert!(
                pushed.is_ok(),
                "casters of sphere {i} beyond the prepared capacity"
            );
        }

        let bg = scene.background();
        self.step_x = to_wide(right, half_pixel)?;
        self.step_y = to_wide(up, half_pixel)?;
        self.forward = to_wide(forward, 1.0)?;
        self.width = width;
        self.height = height;
        self.eye = eye;
        self.epsilon = epsilon;
        // Saturating, like `saturating_from_num`, but without its panic on NaN.
        self.background = [bg.r, bg.g, bg.b].map(|c| {
            let saturated = if c < 0.0 { U16F16::MIN } else { U16F16::MAX };
            fixed_bits_u32(c, 16)
                .map_or(saturated, U16F16::from_bits)
                .to_bits()
        });
        Ok(corners)
    }

    /// [`Self::prepare_narrow`], and without the full-width kernel the refusal of a frame the
    /// narrow kernel does not take.
    fn prepare_narrow_or_refuse(
        &mut self,
        scene: &Scene<S, L>,
        corners: bool,
    ) -> Result<(), RenderError> {
        // Without `narrow-precise` the narrow kernel has no stages for point lights and the
        // normalized models: such a frame takes the full-width kernel, or is refused.
        #[cfg(not(feature = "narrow-precise"))]
        if let Some((item, field)) = needs_precise_stages(scene) {
            #[cfg(not(feature = "full-width"))]
            return Err(RenderError::NeedsNarrowPrecise { item, field });
            #[cfg(feature = "full-width")]
            {
                self.kernel = Kernel::General { item, field };
                return Ok(());
            }
        }
        let narrow = self.prepare_narrow(scene, corners);
        #[cfg(not(feature = "full-width"))]
        if let Err((item, field)) = narrow {
            return Err(RenderError::NeedsFullWidth { item, field });
        }
        #[cfg(feature = "full-width")]
        {
            self.kernel = match narrow {
                Ok(()) => Kernel::Narrow,
                Err((item, field)) => Kernel::General { item, field },
            };
        }
        Ok(())
    }

    /// [`Render::kernel`](crate::Render::kernel) of this frame: without the feature
    /// `full-width` always [`Kernel::Narrow`], every other frame being refused.
    #[inline(always)]
    pub(crate) fn chosen_kernel(&self) -> Kernel {
        #[cfg(feature = "full-width")]
        return self.kernel;
        #[cfg(not(feature = "full-width"))]
        Kernel::Narrow
    }

    /// Turns the spans on (the default) or off. Off, every pixel tests every
    /// sphere: kept for the test that spans change no pixel, and for benchmarks.
    pub fn with_spans(mut self, on: bool) -> Self {
        self.use_spans = on;
        self
    }

    /// Turns analytic anti-aliasing of the silhouettes on or off (off by default, and after
    /// every [`prepare`](Self::prepare)): a pixel an outline crosses blends the front
    /// sphere's colour with what lies behind it by the sphere's coverage of the pixel, in
    /// integers, by the float paths' rule; other pixels keep their bits. Needs the features
    /// `antialias` and `full-width` (the edge pixels are shaded by the full-width kernel);
    /// see `src/fixed/edges.rs`.
    ///
    /// ```
    /// use shadeline::{exponent_series, PreparedFixed, Render, Rgb888};
    /// let sharp = PreparedFixed::new(&exponent_series()?, 96, 64)?;
    /// let smooth = sharp.clone().with_antialiasing(true);
    /// let (mut a, mut b) = ([Rgb888::default(); 96], [Rgb888::default(); 96]);
    /// sharp.render_line(32, &mut a)?;
    /// smooth.render_line(32, &mut b)?;
    /// assert_ne!(a, b); // the row crosses the spheres' outlines
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    #[cfg(all(feature = "antialias", feature = "full-width"))]
    pub fn with_antialiasing(mut self, on: bool) -> Self {
        self.set_antialiasing(on);
        self
    }

    /// [`with_antialiasing`](Self::with_antialiasing) in place, for a frame kept in a
    /// `static` and prepared there.
    #[cfg(all(feature = "antialias", feature = "full-width"))]
    pub fn set_antialiasing(&mut self, on: bool) {
        self.antialias = on;
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;

    /// The light's unit vector, for directions all around the sphere (a xorshift stream)
    /// and along the axes and diagonals: each component within one step of 2⁻³⁰ of the
    /// exact (`f64`) unit vector along the same 30-bit components (the general
    /// normalization, `vector::normalize`, is within 1.94 steps on the same inputs), so of
    /// unit length within `2⁻²⁸`. Both keep the `f32` unit vector's own direction, within
    /// about `2⁻²⁴` of the scene's.
    #[test]
    fn unit_q30_is_the_unit_vector_to_a_step() {
        let mut x = 0x2545_f491_4f6c_dd1du64;
        let mut next = move || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            (x >> 40) as f32 / (1u64 << 23) as f32 - 1.0
        };
        let mut dirs: std::vec::Vec<Vec3> = (0..20_000)
            .map(|_| Vec3::new(next(), next(), next()))
            .collect();
        for (a, b, c) in [
            (1.0, 0.0, 0.0),
            (0.0, -1.0, 0.0),
            (1.0, 1.0, 1.0),
            (-1.0, 1e-6, 0.5),
        ] {
            dirs.push(Vec3::new(a, b, c));
        }
        let (mut worst_len, mut worst_step) = (0i64, 0.0f64);
        for d in dirs {
            let Some(unit) = d.normalized() else {
                continue;
            };
            let got = unit_q30(unit);
            let len2: i64 = got.iter().map(|c| mul_ii(c.to_bits(), c.to_bits())).sum();
            worst_len = worst_len.max((len2 - (1 << 60)).abs());
            let q30 = [unit.x, unit.y, unit.z].map(|c| fixed_bits_i32(c, 30).unwrap() as f64);
            let len = (q30[0] * q30[0] + q30[1] * q30[1] + q30[2] * q30[2]).sqrt();
            for (g, c) in got.iter().zip(q30) {
                let want = c / len * (1u64 << 30) as f64;
                worst_step = worst_step.max((g.to_bits() as f64 - want).abs());
            }
        }
        assert!(worst_step <= 1.0, "a component {worst_step} steps off");
        assert!(worst_len <= 1 << 32, "|v|² off by {worst_len} in Q60");
    }

    /// The prepare's `f32` corner test keeps every narrow direction's integer `|D|²` within
    /// `2·2⁵⁸` (`|d|² ≤ 2`) and the steps below ½, and takes every frame whose corners are
    /// within `2 − 2⁻⁷` (computed in `f64` from the camera) and whose half pixel is below
    /// 0.49: random sizes from 1×1 up to the largest, aspect ratios, orientations and
    /// fields of view about the limit.
    #[test]
    fn the_corner_test_keeps_every_direction_within_root_two() {
        use crate::scene::Camera;
        use crate::test_scenes::uniform;
        use crate::LinearRgb;
        let mut draw = uniform(0x2545_f491_4f6c_dd1d);
        let mut next = |lo: f64, hi: f64| draw(lo as f32, hi as f32) as f64;
        let (mut taken, mut near) = (0, 0);
        for round in 0..3000 {
            let (w, h) = if round % 3 == 0 {
                (next(1.0, 65_535.0) as u32, next(1.0, 65_535.0) as u32)
            } else if round % 5 == 0 {
                (next(1.0, 4.0) as u32, next(1.0, 4.0) as u32)
            } else {
                (next(1.0, 800.0) as u32, next(1.0, 800.0) as u32)
            };
            // The field of view at which the corners reach |d|² = 2, and about it.
            let corner = ((w as f64 - 1.0).powi(2) + (h as f64 - 1.0).powi(2)).sqrt();
            let limit = 2.0 * (h as f64 / corner.max(1.0)).atan().to_degrees();
            let vfov = if w < 4 && h < 4 {
                next(1.0, 179.0)
            } else {
                (limit * next(0.97, 1.03)).min(179.0)
            };
            let camera = Camera {
                position: Vec3::new(next(-9.0, 9.0) as f32, next(-9.0, 9.0) as f32, 20.0),
                look_at: Vec3::new(next(-1.0, 1.0) as f32, next(-1.0, 1.0) as f32, 0.0),
                up: Vec3::new(next(-0.3, 0.3) as f32, 1.0, next(-0.3, 0.3) as f32),
                vfov_degrees: vfov as f32,
            };
            let Ok(scene) = Scene::<1, 1>::new(camera, LinearRgb::new(0.0, 0.0, 0.0)) else {
                continue;
            };
            let Ok(frame) = PreparedFixed::<1, 1>::new(&scene, w, h) else {
                continue;
            };
            let tan = (vfov.to_radians() / 2.0).tan();
            let want = 1.0 + corner * corner * (tan / h as f64).powi(2);
            let Some(view) = frame.narrow else {
                let steep = tan / h as f64 > 0.49;
                assert!(
                    want > 2.0 - 1.0 / 128.0 || steep,
                    "{w}x{h} at {vfov}°: |d|² {want} refused"
                );
                continue;
            };
            taken += 1;
            // Each step's components below ½ (2⁴⁷ in I16F48): twice them fit Q29 in `i32`.
            for c in frame.step_x.iter().chain(&frame.step_y) {
                assert!(c.to_bits().unsigned_abs() < 1 << 47, "{w}x{h} at {vfov}°");
            }
            near += (want > 2.0 - 1.0 / 64.0) as u32;
            let (dx, dy) = (w as i64 - 1, h as i64 - 1);
            for (sx, sy) in [(-dx, -dy), (-dx, dy), (dx, -dy), (dx, dy)] {
                let len2: i128 = (0..3)
                    .map(|i| {
                        let c = view.forward[i] as i128
                            + sy as i128 * view.step_y[i] as i128
                            + sx as i128 * view.step_x[i] as i128;
                        c * c
                    })
                    .sum();
                assert!(len2 <= 2 << 58, "{w}x{h} at {vfov}°: |D|² {len2}");
            }
        }
        assert!(
            taken > 1000 && near > 100,
            "{taken} frames taken, {near} near the limit"
        );
    }
}

/// The first point light (`type`) or sphere of a normalized model (`model`) of `scene`: what
/// the narrow kernel takes only with the feature `narrow-precise`.
#[cfg(not(feature = "narrow-precise"))]
fn needs_precise_stages<const S: usize, const L: usize>(
    scene: &Scene<S, L>,
) -> Option<(Item, &'static str)> {
    use crate::scene::Model;
    if let Some(i) = scene
        .lights()
        .iter()
        .position(|l| matches!(l, Light::Point { .. }))
    {
        return Some((Item::Light(i), "type"));
    }
    scene
        .spheres()
        .iter()
        .position(|s| {
            !matches!(
                s.material.model,
                Model::Phong | Model::BlinnPhong | Model::Lambert
            )
        })
        .map(|i| (Item::Sphere(i), "model"))
}
