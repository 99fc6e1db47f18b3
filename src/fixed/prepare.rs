//! The prepare step of the fixed path: the scene converted to fixed point, once per frame.
//!
//! This is the only place the fixed path touches floating point: `f32` arithmetic (IEEE
//! `+ − × ÷`, exact power-of-two scaling) and `libm`'s `tanf`/`sqrtf`/`floorf`/`ceilf`, the
//! same operations on every target, followed by the `fixed` crate's exact `from_num`
//! conversions. So the prepared numbers, and with them every pixel, are the same bits on a
//! host, a Cortex-M0 and a RISC-V core.
//!
//! What it does, in order: check the size and the camera's plane scale; pick the scene's
//! power-of-two scale; convert and check every sphere, material and light (each refusal is
//! [`RenderError::OutOfFixedRange`] naming the item and field); compute each sphere's screen
//! rectangle ([`super::spans`]).

use super::exact::Exact;
use super::mul::mul_ii;
use super::roots::inv_sqrt;
use super::spans::{Bounds, View};
use super::vector::{each3, normalize, Len, Unit, V3};
use crate::brdf::{Params, LOBES};
use crate::render::RenderError;
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
/// Largest `kd·albedo`, `ks`, colour, and distant-light `colour·intensity` per channel:
/// they are U16F16 and two of them multiply and add without wrapping.
pub const MAX_LEVEL: f32 = 32_767.0;

/// The narrow kernel's error bound (module `narrow`): the largest error of a component of
/// `R − V` (or `N − H`) where `N·V ≥ 0.3`, `2⁻¹⁰`. Checked by the narrow module's
/// `narrow_vectors_within_delta` (the largest seen is 26 steps of `2⁻¹⁵`).
pub(crate) const DELTA: f32 = 1.0 / 1024.0;

/// The same bound near the reflection, where `h = ½|R − V|² < 1/8` (`N·V ≥ 0.3`):
/// `20·2⁻¹⁵` (the largest seen is 17.9 steps, checked by `narrow_vectors_within_delta`).
/// The lobe's error bound, which decides whether a sphere's highlight needs the full-width
/// kernel, uses it for `n ≥ 32`: the lobe's slope `n·√(2h)·e^(−nh)`, which turns an error
/// of `R − V` into an error of the lobe, peaks at `h = 1/(2n)` and is below a tenth of its
/// peak from `h = 4/n ≤ 1/8` on, where [`DELTA`] bounds the error.
pub(crate) const DELTA_LOBE: f32 = 20.0 / 32768.0;

/// The primary directions of a frame in narrow form: `D = forward + dy·step_y + dx·step_x`
/// with `dx = 2x + 1 − w` and `dy = h − 2y − 1`, integer vectors with `|D| < 2³⁰`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct NarrowView {
    pub forward: V3<i32>,
    pub step_x: V3<i32>,
    pub step_y: V3<i32>,
}

/// A sphere's narrow constants, the per-pixel ones first (see [`FixedSphere`]).
#[derive(Clone, Copy, Debug)]
#[repr(C)]
pub(crate) struct NarrowSphere {
    /// Whether the narrow lobe is within a quarter level wherever it is not 0.
    pub lobe_everywhere: bool,
    /// `1 − r²/(r + ε)²` in Q30: `(N·L)²` above it, with `N·L < 0`, is in the own shadow.
    pub shadow_limit: u32,
    /// `h` (Q31) from which the lobe is 0.
    pub cutoff: u32,
    /// The high word of the held `w`, shifted right by this, is `w16` (`|w16| < 2¹⁶` on a hit).
    pub right: u32,
    /// `2^(L + 15)/r` with `L` the bit length of the raw radius: in `(2¹⁵, 2¹⁶]`.
    pub gain: u32,
    /// The radius, raw I16F16.
    pub radius: u32,
    /// The first caster the 32-bit filter covers, if any.
    pub fast: Option<FastCaster>,
    /// `w` is held shifted left by this (0 or 1), so its high word is `w >> (32 − left)`.
    pub left: u32,
    /// `w` per pixel step: `oc × 2·step_x`, held shifted like `w`.
    pub dw: V3<i64>,
    /// Whether `b = oc·D` grows along a row (`oc·step_x > 0`).
    pub b_rises: bool,
}

/// A caster of a sphere, for the 32-bit filter in front of the narrow kernel's exact caster
/// test (`narrow_blocked`). Lengths are in units of the sphere's radius `r`, Q11.
///
/// The shadow ray leaves `O = C + (r + ε)·N`. With `ĉ = (C_k − C)/r`, `d = N − ĉ` and
/// `t = N·L − ĉ·L`, the ray moves toward the caster only if `t < 0`, and passes within
/// `√(|d|² − t²)` of its centre (up to the lift's `ε/r`). The filter skips the exact test
/// where `t` is clearly not negative or that distance clearly exceeds the caster's radius:
/// the margins cover the rounding of `N`, `ĉ`, `ĉ·L` and `N·L` to Q11 and the lift's `ε/r`,
/// so it only skips tests that the exact one fails too, and a frame keeps its bits.
#[derive(Clone, Copy, Debug)]
pub(crate) struct FastCaster {
    /// The caster's index and the light's.
    pub sphere: u8,
    pub light: u8,
    /// `ĉ`, `|ĉ| ≤ 8`.
    pub c: [i16; 3],
    /// `ĉ·L`.
    pub g: i16,
    /// `N·L` (Q11) at or above this: `t ≥ 0`, the caster is behind the ray.
    pub ahead: i16,
    /// Q22: `|d|² − t²` above this, the ray passes outside the caster.
    pub reach2: i32,
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
    /// `1/r` of the raw radius bits, as [`inv_sqrt`] returns it: `y·2^-shift`.
    pub inv_radius: (u32, u32),
    /// Normalized models: each lobe's weight times its normalization factor, exact.
    pub weight: [Exact; LOBES],
    /// Exponents of lobes 1 and 2.
    pub more_shininess: [Exact; MORE_LOBES],
    /// `F₀` per channel, U2F30 (`1 << 30` is 1).
    pub f0: [u32; 3],
    /// The screen rectangle, or `None` if the sphere is off screen.
    pub bounds: Option<Bounds>,
    /// Oren–Nayar's `A` and `B` (U2F30), if the diffuse lobe is Oren–Nayar's.
    #[cfg(feature = "models")]
    pub oren_nayar: Option<[u32; 2]>,
    /// GGX's constants, if the specular lobe is GGX.
    #[cfg(feature = "models")]
    pub ggx: Option<FixedGgx>,
}

/// A GGX sphere's constants (`α = roughness²`).
#[cfg(feature = "models")]
#[derive(Clone, Copy, Debug)]
pub(crate) struct FixedGgx {
    /// `α²`, U1F31.
    pub alpha2: u32,
    /// `1 − α²`, U1F31.
    pub one_minus_alpha2: u32,
    /// `ks·α²/(2π)`, the `f32` value exactly.
    pub scale: Exact,
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
    /// is `power/d²` in scaled units.
    Point { position: V3<Len>, power: V3<Exact> },
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
    /// ([`Scene::shadow_casters`]).
    pub(crate) casters: heapless::Vec<[u32; L], S>,
    /// The primary directions in the narrow kernel's form, if the frame uses it.
    pub(crate) narrow: Option<NarrowView>,
    pub(crate) use_spans: bool,
}

fn out_of_range(item: Item, field: &'static str) -> RenderError {
    RenderError::OutOfFixedRange { item, field }
}

fn to_len(v: Vec3, scale: f32, item: Item, field: &'static str) -> Result<V3<Len>, RenderError> {
    let c = [v.x, v.y, v.z].map(|c| Len::checked_from_num(c * scale));
    match c {
        [Some(x), Some(y), Some(z)] => Ok([x, y, z]),
        _ => Err(out_of_range(item, field)),
    }
}

fn to_wide(v: Vec3, scale: f32) -> Result<V3<I16F48>, RenderError> {
    let c = [v.x, v.y, v.z].map(|c| I16F48::checked_from_num(c * scale));
    match c {
        [Some(x), Some(y), Some(z)] => Ok([x, y, z]),
        _ => Err(out_of_range(Item::Camera, "vfov")),
    }
}

/// Per-channel levels checked against [`MAX_LEVEL`].
fn to_levels(c: [f32; 3], item: Item, field: &'static str) -> Result<V3<U16F16>, RenderError> {
    let mut out = [U16F16::ZERO; 3];
    for (o, v) in out.iter_mut().zip(c) {
        if !(0.0..=MAX_LEVEL).contains(&v) {
            return Err(out_of_range(item, field));
        }
        *o = U16F16::checked_from_num(v).ok_or(out_of_range(item, field))?;
    }
    Ok(out)
}

/// `2^k` as an `f32`, for `k` in `-126..=127`.
fn pow2(k: i32) -> f32 {
    f32::from_bits(((k + 127).clamp(1, 254) as u32) << 23)
}

/// The power of two `k` such that the scene's extent times `2^k` is below `2^EXTENT_LOG2`
/// units, as large as possible up to [`MAX_SCALE_LOG2`].
fn scale_log2<const S: usize, const L: usize>(scene: &Scene<S, L>) -> i32 {
    let mut extent = scene.camera().position.max_abs();
    for s in scene.spheres() {
        extent = extent.max(s.center.max_abs() + s.radius);
    }
    for l in scene.lights() {
        if let Light::Point { position, .. } = l {
            extent = extent.max(position.max_abs());
        }
    }
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
    /// `colour·intensity` above [`MAX_LEVEL`] in a channel (`albedo`/`kd`, `ks`,
    /// `color`/`intensity`).
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
        casters: heapless::Vec::new(),
        narrow: None,
        use_spans: true,
    };

    /// Prepares `scene` for a `width × height` image into `self`, in place: what
    /// [`new`](Self::new) returns, without the prepared frame ever being on the stack (the
    /// M0 firmware's peak stack is 3.4 KB this way, 5.7 KB when `new`'s frame is moved into
    /// its `static`). Fails like `new`;
    /// on an error `self` is left [`EMPTY`](Self::EMPTY), never half prepared. Spans are on,
    /// whatever [`with_spans`](Self::with_spans) set before.
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
        let result = self.prepare_fields(scene, width, height);
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
        self.casters.clear();
        self.narrow = None;
        self.use_spans = true;
    }

    fn prepare_fields(
        &mut self,
        scene: &Scene<S, L>,
        width: u32,
        height: u32,
    ) -> Result<(), RenderError> {
        self.clear();
        if width == 0 || height == 0 || width > MAX_DIMENSION || height > MAX_DIMENSION {
            return Err(RenderError::BadSize { width, height });
        }
        if let Some(light) = scene.sphere_light() {
            return Err(RenderError::SphereLight { light });
        }
        let camera = scene.camera();
        let (right, up, forward) = scene.camera_basis();
        let tan = libm::tanf(camera.vfov_degrees * (core::f32::consts::PI / 360.0));
        let (width_f, height_f) = (width as f32, height as f32);
        let x_scale = (width_f / height_f) * tan;
        if !(tan <= MAX_PLANE_SCALE && x_scale <= MAX_PLANE_SCALE) {
            return Err(out_of_range(Item::Camera, "vfov"));
        }
        let half_pixel = tan / height_f;

        let k = scale_log2(scene);
        let scale = pow2(k);
        let eye = to_len(camera.position, scale, Item::Camera, "position")?;
        let epsilon = Len::checked_from_num(scene.ray_epsilon() * scale)
            .ok_or(out_of_range(Item::Camera, "position"))?;
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
            let radius = Len::checked_from_num(s.radius * scale)
                .filter(|r| *r >= MIN_SCALED_RADIUS)
                .ok_or(out_of_range(item, "radius"))?;
            let radius_raw = radius.to_bits() as i64;
            let inv_radius =
                inv_sqrt((radius_raw * radius_raw) as u64).ok_or(out_of_range(item, "radius"))?;
            to_levels([m.albedo.r, m.albedo.g, m.albedo.b], item, "albedo")?;
            // The float paths' constants (`kd·albedo`, or `kd·albedo/π`; `ks`, or 1 for the
            // normalized models; normalization factors; F₀), converted to fixed formats.
            let params = Params::<f32>::of(m);
            let kd_albedo = params.kd_albedo;
            let kd_albedo = to_levels([kd_albedo.x, kd_albedo.y, kd_albedo.z], item, "kd")?;
            let [ks, _, _] = to_levels([params.ks, 0.0, 0.0], item, "ks")?;
            let unit = |v: f32| (v.clamp(0.0, 1.0) * (1u32 << 30) as f32) as u32;
            let sphere = FixedSphere {
                center,
                eye_offset: each3(|c| eye[c] - center[c]),
                radius_sq: I32F32::from_bits(radius_raw * radius_raw),
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
                    }
                }),
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
                    to_levels([color.r, color.g, color.b], item, "color")?;
                    let arriving = Vec3::new(color.r, color.g, color.b).scale(intensity);
                    // Validated: a scene's light direction is finite and not zero.
                    let d = (-direction).normalized();
                    debug_assert!(d.is_some(), "light direction {direction:?}");
                    let d = d.unwrap_or_default();
                    // `saturating_from_num` panics on NaN; this is the same saturation for
                    // every other input, with no panic path for the firmware's link proof.
                    let d = [d.x, d.y, d.z].map(|c| {
                        let saturated = if c < 0.0 { Unit::MIN } else { Unit::MAX };
                        Unit::checked_from_num(c).unwrap_or(saturated).to_bits() as i64
                    });
                    FixedLight::Distant {
                        to_light: normalize(d).ok_or(out_of_range(item, "direction"))?,
                        arriving: to_levels(
                            [arriving.x, arriving.y, arriving.z],
                            item,
                            "intensity",
                        )?,
                    }
                }
                Light::Point {
                    position,
                    color,
                    intensity,
                    ..
                } => {
                    let power = Vec3::new(color.r, color.g, color.b)
                        .scale(intensity / (4.0 * core::f32::consts::PI))
                        .scale(pow2(2 * k));
                    let power = [power.x, power.y, power.z];
                    if !power.iter().all(|p| p.is_finite()) {
                        return Err(out_of_range(item, "intensity"));
                    }
                    FixedLight::Point {
                        position: to_len(position, scale, item, "position")?,
                        power: power.map(Exact::from_f32),
                    }
                }
            };
            // Same capacity as the scene: cannot fail.
            let pushed = self.lights.push(light);
            debug_assert!(pushed.is_ok(), "light {i} beyond the prepared capacity");
        }

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
            U16F16::checked_from_num(c).unwrap_or(saturated).to_bits()
        });
        self.prepare_narrow(scene);
        Ok(())
    }

    /// Whether every sphere is more than `4ε` from the surface of each sphere that can shadow
    /// it (the narrow kernel's caster test assumes its shadow rays start outside them).
    fn casters_apart(&self) -> bool {
        let eps = self.epsilon.to_bits() as i64;
        let radius = |s: &FixedSphere| (s.radius_sq.to_bits().max(0) as u64).isqrt() as i64;
        self.spheres.iter().zip(&self.casters).all(|(s, masks)| {
            let mask = masks.iter().fold(0, |a, m| a | m);
            self.spheres.iter().enumerate().all(|(k, c)| {
                if k >= 32 || mask & (1 << k) == 0 {
                    return k < 32 || core::ptr::eq(s, c);
                }
                let d = each3(|i| s.center[i].to_bits() as i64 - c.center[i].to_bits() as i64);
                let apart = radius(s) + radius(c) + 4 * eps;
                d.iter().map(|&v| v * v).sum::<i64>() > apart * apart
            })
        })
    }

    /// The first caster of sphere `i` (over every light) that [`FastCaster`]'s filter can
    /// take: one within eight radii of it, both with narrow constants.
    fn fast_caster(&self, i: usize) -> Option<FastCaster> {
        let own = self.spheres.get(i)?;
        let ns = own.narrow.as_ref()?;
        // The raw radius's bit length (see `NarrowSphere::right`): x/r in Q11 is
        // x·gain >> (bits + 4).
        let shift = ns.right + 18 - ns.left + 4;
        let (gain, r) = (ns.gain as i64, ns.radius as i64);
        let q11 = |x: i64| (x * gain) >> shift;
        let eps = q11(self.epsilon.to_bits() as i64) as i32 + 1;
        for (light_index, light) in self.lights.iter().enumerate().take(256) {
            let FixedLight::Distant { to_light, .. } = *light else {
                continue;
            };
            let casters = self
                .casters
                .get(i)
                .and_then(|c| c.get(light_index))
                .copied();
            let casters = casters.unwrap_or(0);
            for (k, s) in self.spheres.iter().enumerate().take(32) {
                if k == i || casters & (1 << k) == 0 {
                    continue;
                }
                let Some(kn) = s.narrow.as_ref() else {
                    continue;
                };
                let c = each3(|j| s.center[j].to_bits() as i64 - own.center[j].to_bits() as i64);
                if c.iter().any(|v| v.unsigned_abs() > 8 * r as u64) {
                    continue;
                }
                let c = c.map(q11); // |ĉ| ≤ 8·2¹¹ + 1 per component
                let c_len2 = c.iter().map(|&v| v * v).sum::<i64>();
                if c_len2 > 64 << 22 {
                    continue;
                }
                let g = c
                    .iter()
                    .zip(to_light)
                    .map(|(&v, l)| v * l.to_bits() as i64)
                    .sum::<i64>()
                    >> 30;
                // Steps of error: N, ĉ and N·L truncated to Q11 (one each per component),
                // ĉ·L (two), the lift's ε/r; the squares add twice the largest |d| and |t|
                // (at most |ĉ| + 1) times the error of each.
                let margin = 8 + 2 * eps as i64;
                let reach = q11(kn.radius as i64) + margin;
                let d_max = (c_len2 as u64).isqrt() as i64 + (1 << 11) + margin;
                return Some(FastCaster {
                    sphere: k as u8,
                    light: light_index as u8,
                    c: c.map(|v| v as i16),
                    g: g as i16,
                    ahead: (g + 4 + eps as i64).min(i16::MAX as i64) as i16,
                    reach2: (reach * reach + 4 * d_max * margin).min(i32::MAX as i64) as i32,
                });
            }
        }
        None
    }

    /// Sets up the narrow kernel ([`super::narrow`]) if the frame meets its conditions.
    fn prepare_narrow(&mut self, scene: &Scene<S, L>) {
        let all_distant = self
            .lights
            .iter()
            .all(|l| matches!(l, FixedLight::Distant { .. }));
        let classic = self.spheres.iter().all(|s| !s.normalized);
        // The narrow run indexes its tracks by `u8`.
        if !(all_distant && classic && S <= 256 && self.casters_apart()) {
            return;
        }
        // D = forward + dy·step_y + dx·step_x at 2²⁹ for the unit forward vector.
        let narrow = |v: V3<I16F48>| v.map(|c| (c.to_bits().saturating_add(1 << 18)) >> 19);
        // Steps below 2²⁸ (so `2·step` fits; a one-pixel-wide image leaves `step_x` unbounded
        // by the corner test below).
        let fits = |v: [i64; 3]| v.iter().all(|c| c.unsigned_abs() < 1 << 28);
        let (forward, step_x, step_y) = (
            narrow(self.forward),
            narrow(self.step_x),
            narrow(self.step_y),
        );
        if !(fits(step_x) && fits(step_y) && forward.iter().all(|c| c.unsigned_abs() < 1 << 30)) {
            return;
        }
        let view = NarrowView {
            forward: forward.map(|c| c as i32),
            step_x: step_x.map(|c| c as i32),
            step_y: step_y.map(|c| c as i32),
        };
        // Every direction within √2 of the central one in length (the corners are the
        // longest): then |D| < 2³⁰ and every narrow format holds.
        let (w, h) = (self.width as i64 - 1, self.height as i64 - 1);
        let len2 = |d: [i64; 3]| d.iter().map(|&c| (c >> 8) * (c >> 8)).sum::<i64>();
        let centre = len2(view.forward.map(|c| c as i64));
        for (dx, dy) in [(-w, -h), (-w, h), (w, -h), (w, h)] {
            let d = each3(|i| {
                view.forward[i] as i64 + dy * view.step_y[i] as i64 + dx * view.step_x[i] as i64
            });
            if len2(d) > 2 * centre {
                return;
            }
        }
        let eps = self.epsilon.to_bits() as i64;
        let step2 = view.step_x.map(|c| 2 * c);
        let intensity: f32 = self
            .lights
            .iter()
            .map(|l| match l {
                FixedLight::Distant { arriving, .. } => arriving
                    .iter()
                    .map(|c| c.to_num::<f32>())
                    .fold(0.0, f32::max),
                FixedLight::Point { .. } => 0.0,
            })
            .sum();
        // A sphere's constants are only read once the frame's view is set, at the end.
        for (s, m) in self.spheres.iter_mut().zip(scene.spheres()) {
            let oc = s.eye_offset.map(|c| c.to_bits());
            let r = (s.radius_sq.to_bits().max(0) as u64).isqrt() as i64;
            let outside = oc.iter().map(|&c| c as i64 * c as i64).sum::<i64>();
            if outside <= (r + 2 * eps) * (r + 2 * eps) {
                return;
            }
            let bits = 64 - r.leading_zeros();
            let shift = bits + 14;
            let left = 32u32.saturating_sub(shift);
            let cross = [
                mul_ii(oc[1], step2[2]) - mul_ii(oc[2], step2[1]),
                mul_ii(oc[2], step2[0]) - mul_ii(oc[0], step2[2]),
                mul_ii(oc[0], step2[1]) - mul_ii(oc[1], step2[0]),
            ];
            let (rf, ef) = (r as f32, eps as f32);
            let ks_intensity = s.ks.to_num::<f32>() * intensity;
            let n = m.material.shininess;
            // Below τ (half a U16F16 step) the lobe is invisible.
            let tau = 1.0 / 131_072.0;
            let cutoff = if ks_intensity <= tau {
                0
            } else {
                let h = 1.0 - libm::powf(tau / ks_intensity, 1.0 / n);
                // Saturates at 2: above 1 the lobe is 0 anyway.
                ((h + 2.5 * DELTA) * (1u64 << 31) as f32) as u32
            };
            let delta = if n >= 32.0 { DELTA_LOBE } else { DELTA };
            let lobe_error = ks_intensity * 255.0 * libm::sqrtf(n) * delta * 0.61;
            s.narrow = Some(NarrowSphere {
                left,
                right: shift + left - 32,
                radius: r as u32,
                gain: (1u64 << (bits + 15)).checked_div(r as u64).unwrap_or(0) as u32,
                dw: cross.map(|c| c << left),
                b_rises: mul_ii(oc[0], step2[0])
                    + mul_ii(oc[1], step2[1])
                    + mul_ii(oc[2], step2[2])
                    > 0,
                shadow_limit: (ef * (2.0 * rf + ef) / ((rf + ef) * (rf + ef)) * (1u64 << 30) as f32)
                    as u32,
                cutoff,
                lobe_everywhere: lobe_error <= 0.5 && n <= 256.0,
                fast: None,
            });
        }
        for i in 0..self.spheres.len() {
            let fast = self.fast_caster(i);
            if let Some(ns) = self.spheres.get_mut(i).and_then(|s| s.narrow.as_mut()) {
                ns.fast = fast;
            }
        }
        self.narrow = Some(view);
    }

    /// Turns the screen-rectangle spans on (the default) or off. Off, every pixel tests every
    /// sphere: kept for the test that spans change no pixel, and for benchmarks.
    pub fn with_spans(mut self, on: bool) -> Self {
        self.use_spans = on;
        self
    }
}
