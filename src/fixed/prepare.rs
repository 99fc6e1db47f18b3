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
//! and, without the full-width kernel, each sphere's rows and columns). The stages are
//! `Plane::of` (`prepare_plane`), `fixed_sphere` and `fixed_light` (with the checked
//! conversions of `prepare_convert` and GGX's constants in `prepare_ggx`), and
//! `prepare_casters`.

use super::convert::{fixed_bits_i32, fixed_bits_u32};
use super::exact::Exact;
use super::prepare_convert::MIN_SCALED_RADIUS;
use super::prepare_convert::{
    out_of_range, pow2, scale_log2, small_beside_extent, to_len, to_levels, to_wide, unit_q30,
};
#[cfg(feature = "models")]
use super::prepare_ggx::FixedGgx;
use super::prepare_plane::Plane;
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
use crate::scene::{Item, Light, Material, Scene, Sphere, MORE_LOBES};
use crate::vec3::Vec3;
use fixed::types::{I16F48, I32F32, U16F16};

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
    /// `outline`): the spans without the full-width kernel. 16 bits, as a frame is at most
    /// `MAX_DIMENSION` each way: the per-pixel fields after them stay within reach of one
    /// base register on ARMv6-M.
    #[cfg(not(feature = "full-width"))]
    pub rows: (u16, u16),
    #[cfg(not(feature = "full-width"))]
    pub columns: (u16, u16),
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
    /// The rows of this sphere's pixels where a caster can block a light (`[start, end)`;
    /// empty if it has no caster): outside them the shadow stages skip the casters
    /// ([`super::narrow_shadow_rows`]).
    pub shadows: (u16, u16),
}

impl NarrowSphere {
    /// Whether the sphere shadows itself at a pixel of `N·L` (Q15) `nl`: the light is behind
    /// the surface by more than the shadow ray's lift clears (see [`Self::shadow_limit`]).
    #[inline(always)]
    pub(crate) fn self_shadowed(&self, nl: i32) -> bool {
        nl < 0 && (nl * nl) as u32 > self.shadow_limit
    }
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
    /// The shift that brings `distance` below `2¹⁵` (`bit_length − 15`, at least 0): the fast
    /// point light's shift wherever the other lengths it takes are shorter (see
    /// `narrow_point::point_cosines`), so that those pixels need no count of leading zeros.
    #[cfg(feature = "narrow-precise")]
    pub distance_shift: u32,
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
    /// For a point light, the fast point light's constants on this sphere.
    #[cfg(feature = "narrow-precise")]
    pub point: PointConstants,
    /// Under test, the spheres a plane keeps off every ray toward the light, which the mask
    /// leaves out (`narrow_caster_prepare::separated`): the shadow stages assert that none
    /// of them blocks a ray they cast.
    #[cfg(test)]
    pub separated: u32,
}

impl NarrowLight {
    /// Whether a pixel of `N·L` (Q15) `nl` passes the filter: the sphere has casters for the
    /// light and one can be ahead and within reach (`ahead`, `reach`).
    #[inline(always)]
    pub(crate) fn casters_may_block(&self, nl: i32) -> bool {
        self.casters != 0 && nl < self.ahead && (nl * nl) as u32 <= self.reach
    }
}

/// A sphere's constants for a point light's fast stages (`narrow_point`,
/// `narrow_point_shadow`; feature `narrow-precise`), made by `narrow_point_prepare`.
#[cfg(feature = "narrow-precise")]
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct PointConstants {
    /// Where the fast point light shades this sphere: 0 nowhere; otherwise the fast lobe's
    /// limit, as `NarrowSphere::fast_lobe_max` is for the distant lights (`u16::MAX`:
    /// wherever the lobe is not 0).
    pub fast: u16,
    /// The largest `(|Q|/|P − X|)²` (Q4) at which the fast point light serves on this
    /// sphere (see `narrow_point`), at most 255.
    pub ratio: u8,
    /// The bound (Q15) of the error of the fast direction toward the light on this sphere,
    /// for the shadow filters' margins (`narrow_point_shadow`).
    pub slack: u8,
    /// This sphere as a caster: the unit vector from the light toward its centre (Q15) and
    /// the cosine (Q15, lowered by a margin) of the cone from the light that holds it. A
    /// shadow ray toward the light meets the sphere only from a point in that cone
    /// (`narrow_point_shadow`'s filter). A threshold of `i16::MIN` passes every point.
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
    /// Per sphere, its place front to back among the spheres wherever a ray meets two of
    /// them, if `depth_ordered`: a pixel over several takes the first it hits (set with
    /// `narrow`, see [`super::narrow_depth`]).
    pub(crate) depth_rank: [u8; S],
    /// Whether no two spheres overlap, so that `depth_rank` orders them.
    pub(crate) depth_ordered: bool,
    /// The quick caster test's unit of length, `2^quick_shift` raw: the smallest that
    /// takes every sphere's `r + ε` below `2¹⁶` units (set with `narrow`).
    pub(crate) quick_shift: u32,
    pub(crate) use_spans: bool,
    /// Whether silhouettes are anti-aliased ([`PreparedFixed::with_antialiasing`]).
    #[cfg(all(feature = "antialias", feature = "full-width"))]
    pub(crate) antialias: bool,
}

/// Sphere `i` of `scene`, `s`, converted and checked, pushed onto `spheres`: its centre and
/// radius times `scale`, its offset from the scaled `eye`, its material's constants and,
/// with the full-width kernel, its spans in `view`. Pushed here, not returned in a `Result`
/// for the caller to push: on ARMv6-M, where the whole prepare is inlined, that return is a
/// copy of the sphere, more code than the push.
#[inline]
fn fixed_sphere<const S: usize, const L: usize>(
    scene: &Scene<S, L>,
    i: usize,
    s: &Sphere,
    scale: f32,
    eye: V3<Len>,
    #[cfg(feature = "full-width")] view: &View,
    spheres: &mut heapless::Vec<FixedSphere, S>,
) -> Result<(), RenderError> {
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
    let params = material_params(m, item)?;
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
        oren_nayar: (params.oren_nayar > 0.0).then(|| [unit(params.on_a), unit(params.on_b)]),
        #[cfg(feature = "models")]
        ggx: (params.ggx > 0.0).then(|| FixedGgx::of(&params)),
        radius,
        #[cfg(all(feature = "area-lights", feature = "full-width"))]
        widening: widenings(m.shininess, &params),
    };
    // Same capacity as the scene: cannot fail.
    let pushed = spheres.push(sphere);
    debug_assert!(pushed.is_ok(), "sphere {i} beyond the prepared capacity");
    Ok(())
}

/// The float paths' constants of material `m` (`kd·albedo`, or `kd·albedo/π`; `ks`, or 1
/// for the normalized models; normalization factors; F₀), which the fixed formats are
/// converted from.
#[cfg(feature = "full-width")]
#[inline(always)]
fn material_params(m: &Material, _item: Item) -> Result<Params<f32>, RenderError> {
    Ok(Params::<f32>::of(m))
}

/// The float paths' constants of material `m`, as with the full-width kernel, for the
/// classic models only: without it the others are refused here, before their constants
/// are computed (and their code is linked).
#[cfg(not(feature = "full-width"))]
#[inline(always)]
fn material_params(m: &Material, item: Item) -> Result<Params<f32>, RenderError> {
    match m.model {
        Model::OrenNayar { .. } | Model::Ggx(_) => Err(RenderError::NeedsFullWidth {
            item,
            field: "model",
        }),
        _ => Ok(Params::<f32>::of(m)),
    }
}

/// Light `item` of the scene, `l`, converted and checked: a distant light's direction and
/// arriving levels, a point light's position times `scale = 2^k` and its power times the
/// scale squared, and with `area-lights` a sphere light's scaled radius.
#[inline]
fn fixed_light(item: Item, l: &Light, scale: f32, k: i32) -> Result<FixedLight, RenderError> {
    Ok(match *l {
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
                arriving: to_levels([arriving.x, arriving.y, arriving.z], item, "intensity")?,
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
                return Ok(FixedLight::Sphere {
                    position,
                    power,
                    radius,
                });
            }
            let _ = radius;
            FixedLight::Point { position, power }
        }
    })
}

/// Per lobe of a material of shininess `shininess` (then `more_shininess`), the constants
/// of its energy factor under a sphere light, for `area::lobe_widening`: from its exponent
/// `n` (`n′ = n`, or `n/4` for Blinn-Phong), `[√(πn′/2)` in U16F16, `n′/2` in U20F12`]`,
/// saturating (0 for `n = 0`).
#[cfg(all(feature = "area-lights", feature = "full-width"))]
#[inline(always)]
fn widenings(shininess: f32, params: &Params<f32>) -> [[u32; 2]; LOBES] {
    let exponents = [
        shininess,
        params.more_shininess[0],
        params.more_shininess[1],
    ];
    exponents.map(|n| {
        let n = if params.blinn > 0.0 { n * 0.25 } else { n };
        let a = libm::sqrtf(core::f32::consts::FRAC_PI_2 * n);
        [fixed_bits_u32(a, 16), fixed_bits_u32(0.5 * n, 12)].map(|b| b.unwrap_or(u32::MAX))
    })
}

impl<const S: usize, const L: usize> PreparedFixed<S, L> {
    /// Prepares `scene` for a `width × height` image on the fixed path.
    ///
    /// Fails with [`RenderError::BadSize`] like [`Prepared::new`](crate::Prepared::new), and
    /// with [`RenderError::OutOfFixedRange`] if a number does not fit the fixed formats (see
    /// the [module table](crate::fixed)): a sphere smaller than `2⁻¹³` of the scene's extent
    /// (`radius`), a field of view or aspect ratio with `tan(vfov/2)·max(1, w/h)` above
    /// [`MAX_PLANE_SCALE`](super::MAX_PLANE_SCALE) (`vfov`), and `kd·albedo`, `ks`, or a
    /// distant light's `colour·intensity` above [`MAX_LEVEL`](super::MAX_LEVEL) in a channel
    /// (`kd`, `ks`, `intensity`).
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
            #[cfg(feature = "narrow-precise")]
            distance_shift: 0,
        }; L],
        precise_pixels: false,
        depth_rank: [0; S],
        depth_ordered: false,
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
        self.depth_ordered = false;
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
    /// a frame (`docs/performance.md, "Choices measured"`). Its stages are inlined into it.
    #[cfg_attr(shadeline_short_mul, inline(always))]
    #[cfg_attr(not(shadeline_short_mul), inline(never))]
    fn prepare_fields(
        &mut self,
        scene: &Scene<S, L>,
        width: u32,
        height: u32,
    ) -> Result<bool, RenderError> {
        self.clear();
        // The scale first: it refuses nothing, and taken before the plane's checks it leaves
        // less code on ARMv6-M.
        let k = scale_log2(scene);
        let scale = pow2(k);
        let plane = Plane::of(scene, width, height)?;
        let camera = scene.camera();
        let eye = to_len(camera.position, scale, Item::Camera, "position")?;
        let epsilon = fixed_bits_i32(scene.ray_epsilon() * scale, 16)
            .map(Len::from_bits)
            .ok_or(out_of_range(Item::Camera, "position"))?;
        #[cfg(feature = "full-width")]
        let view = View {
            eye: camera.position,
            right: plane.right,
            up: plane.up,
            forward: plane.forward,
            half_pixel: plane.half_pixel,
            width,
            height,
        };

        for (i, s) in scene.spheres().iter().enumerate() {
            #[cfg(feature = "full-width")]
            fixed_sphere(scene, i, s, scale, eye, &view, &mut self.spheres)?;
            #[cfg(not(feature = "full-width"))]
            fixed_sphere(scene, i, s, scale, eye, &mut self.spheres)?;
        }
        for (i, l) in scene.lights().iter().enumerate() {
            let light = fixed_light(Item::Light(i), l, scale, k)?;
            // Same capacity as the scene: cannot fail.
            let pushed = self.lights.push(light);
            debug_assert!(pushed.is_ok(), "light {i} beyond the prepared capacity");
        }
        #[cfg(feature = "full-width")]
        self.prepare_casters(scene);

        let bg = scene.background();
        self.step_x = to_wide(plane.right, plane.half_pixel)?;
        self.step_y = to_wide(plane.up, plane.half_pixel)?;
        self.forward = to_wide(plane.forward, 1.0)?;
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
        Ok(plane.corners)
    }

    /// Per sphere and light, the spheres that can shadow it ([`Scene::shadow_casters`]),
    /// for the full-width kernel.
    #[cfg(feature = "full-width")]
    #[inline(always)]
    fn prepare_casters(&mut self, scene: &Scene<S, L>) {
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
