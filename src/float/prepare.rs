//! The prepare step of the float paths: every per-frame constant, computed once.
//!
//! [`Prepared::new`] turns a validated [`Scene`] and an image size into the numbers the row
//! driver and the kernel read: the camera basis and pixel-to-plane scales, each sphere's offset
//! from the eye and `1/r` (so normals need no square root), each material's constants
//! ([`Params::of`]: `kd·albedo`, normalization factors, Fresnel's `F₀`), each light's arriving
//! colour. Nothing below this step allocates, panics or recomputes a per-frame
//! value per row or per pixel.
//!
//! The lane width is a type parameter ([`Scalar`], [`Simd4`], [`Simd8`]) and changes only how
//! many pixels one kernel call shades: the prepared numbers are the same at every width, which
//! is half of why the paths agree bit for bit (the other half is the lane trait, whose
//! operations are all exactly specified: see `lane`). It also holds the per-row constants
//! ([`Row`]) that the spans and the kernel's `ray` stage share.

use super::lane::{Lane, Rooted, SquareRoot};
use crate::brdf::Params;
use crate::pixel::LinearRgb;
use crate::render::{Kernel, RenderError, MAX_DIMENSION};
use crate::scene::{Item, Light, Model, Scene};
use crate::vec3::Vec3;
use core::cmp::Ordering;
use core::marker::PhantomData;

/// Arriving light is clamped to this, so that a point light sitting on a surface (distance
/// zero) gives a huge but finite value, never `inf·0 = NaN`.
pub(crate) const MAX_ARRIVING: f32 = 1.0e30;

/// A width of the float kernel: which [`Lane`] type one kernel call computes with.
pub trait FloatPath {
    /// The lane type: `f32`, `f32x4` or `f32x8`.
    type Lane: Lane;
}

/// The scalar float path: one pixel per kernel call, `f32`. The float reference of the crate.
#[derive(Clone, Copy, Debug, Default)]
pub struct Scalar;
/// The SIMD float path at 4 lanes ([`wide::f32x4`]): SSE, NEON, wasm simd128.
#[derive(Clone, Copy, Debug, Default)]
pub struct Simd4;
/// The SIMD float path at 8 lanes ([`wide::f32x8`]): one AVX register when built with AVX,
/// two 4-lane halves otherwise.
#[derive(Clone, Copy, Debug, Default)]
pub struct Simd8;

impl FloatPath for Scalar {
    type Lane = f32;
}
/// The scalar float path with the square roots of `Q` (a [`SquareRoot`]): for a firmware
/// on a core with a square-root instruction, such as a Cortex-M4F's `VSQRT.F32`. It renders
/// the frames [`Scalar`] renders, bit for bit, when `Q` is correctly rounded.
///
/// ```
/// use shadeline::{exponent_series, Prepared, Render, Rgb565, Scalar, ScalarWith, SquareRoot};
///
/// /// On a Cortex-M4F this would be one `vsqrt.f32` in inline assembly.
/// struct Hardware;
/// impl SquareRoot for Hardware {
///     fn sqrt(x: f32) -> f32 {
///         x.sqrt()
///     }
/// }
///
/// let scene = exponent_series()?;
/// let mut a = [Rgb565::default(); 64];
/// let mut b = [Rgb565::default(); 64];
/// Prepared::<Scalar>::new(&scene, 64, 48)?.render_line(20, &mut a)?;
/// Prepared::<ScalarWith<Hardware>>::new(&scene, 64, 48)?.render_line(20, &mut b)?;
/// assert_eq!(a, b);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub struct ScalarWith<Q>(PhantomData<Q>);

// By hand: derives would ask the same of `Q`, which is only a marker.
impl<Q> Clone for ScalarWith<Q> {
    fn clone(&self) -> Self {
        *self
    }
}
impl<Q> Copy for ScalarWith<Q> {}
impl<Q> Default for ScalarWith<Q> {
    fn default() -> Self {
        ScalarWith(PhantomData)
    }
}
impl<Q> core::fmt::Debug for ScalarWith<Q> {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str("ScalarWith")
    }
}

impl<Q: SquareRoot> FloatPath for ScalarWith<Q> {
    type Lane = Rooted<Q>;
}

impl FloatPath for Simd4 {
    type Lane = wide::f32x4;
}
impl FloatPath for Simd8 {
    type Lane = wide::f32x8;
}

/// A sphere's per-frame constants.
#[derive(Clone, Copy, Debug)]
pub(crate) struct PreparedSphere {
    pub center: Vec3,
    /// `eye − center`: the primary rays' origin offset.
    pub eye_offset: Vec3,
    pub radius_sq: f32,
    pub inv_radius: f32,
    /// The material's constants ([`Params::of`]): `kd·albedo`, `ks`, the exponents, the
    /// normalization factors and `F₀` of the normalized models.
    pub params: Params<f32>,
    /// A normalized model (or Lambert): the kernel selects its constants per lane only
    /// for such spheres, and computes their terms only in packets that show one.
    pub normalized: bool,
    /// Schlick's factor applies.
    pub schlick: bool,
    /// Lobe 1 or 2 has a weight.
    pub more_lobes: bool,
    /// Oren–Nayar diffuse.
    #[cfg(feature = "models")]
    pub oren_nayar: bool,
    /// GGX specular.
    #[cfg(feature = "models")]
    pub ggx: bool,
    /// The silhouette's constants for edge anti-aliasing (see `edges`).
    #[cfg(feature = "antialias")]
    pub outline: Outline,
    /// The narrow kernel's constants, if the frame takes it (see `narrow`).
    pub narrow: Option<NarrowSphere>,
}

#[cfg(feature = "antialias")]
/// A sphere's silhouette as the image-plane conic `F(x, y) = k·|u|² − (oc·u)² = 0`, with
/// `u = x·right + y·up + forward` and `oc = C − eye`: what the `edges` stage and the
/// anti-aliased spans read.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Outline {
    /// `k = |oc|² − r²`; not above 0 when the eye is inside or on the sphere (no silhouette).
    pub k: f32,
    /// `oc·right` and `oc·up`: with `k`, the gradient of `F`.
    pub oc_right: f32,
    pub oc_up: f32,
    /// `r²` of a sphere whose silhouette lies at least 1.5 pixels outside this one's: the
    /// anti-aliased frame's spans use it.
    pub spans_radius_sq: f32,
    /// `|oc|² − spans_radius_sq`: a pixel counts as near the outline only if its ray meets
    /// that larger sphere (`spans_k·|u|² ≤ (oc·u)²`), so every such pixel lies in the spans.
    pub spans_k: f32,
}

/// A light's per-frame constants.
#[derive(Clone, Copy, Debug)]
pub(crate) enum PreparedLight {
    /// `to_light`: unit vector toward the light; `arriving`: `color · intensity`.
    Distant { to_light: Vec3, arriving: Vec3 },
    /// `power`: `color · intensity / 4π`; arriving is `power / r²`.
    Point { position: Vec3, power: Vec3 },
    /// A sphere light: a point light with a `radius` (see `area`); `power` as for
    /// `Point`.
    #[cfg(feature = "area-lights")]
    Sphere {
        position: Vec3,
        power: Vec3,
        radius: f32,
    },
}

/// The largest `ks·ΣI·n` (`ΣI` the sum of the lights' brightest channels) a frame may have
/// for the narrow kernel, `2¹¹`. Sharper highlights go to the general kernel: a lobe
/// `cos^n` moves by up to `n` times its cosine's error, and this cap keeps the frames
/// `narrow_frames_agree_with_the_general_kernel` checks within a level of the general
/// kernel's and a tenth of a level of the `f64` reference.
pub(crate) const SHARPEST: f32 = 2048.0;

/// A sphere's constants for the narrow kernel (`super::narrow`).
#[derive(Clone, Copy, Debug)]
pub(crate) struct NarrowSphere {
    /// `ô = (eye − centre)/r`.
    pub o: Vec3,
    /// `ô × Sx`.
    pub o_sx: Vec3,
    /// The sphere's middle column as an offset `X₀` (half pixels): a pixel's quadrics are
    /// evaluated at `X − X₀`.
    pub origin: f32,
    /// `r`, for the distance key.
    pub radius: f32,
    /// `1 − r²/(r + ε)²`: `(N·L)²` above it, with `N·L < 0`, is in the own shadow.
    pub own_limit: f32,
    /// The lobe's weight: `ks`, or 0 for Lambert, which the narrow kernel shades as a
    /// classic sphere of diffuse weight `kd·albedo/π` and no lobe.
    pub ks: f32,
    /// The shadow rows `[first, end)` (feature `shadow-rows`, see `shadow_rows`): on other
    /// rows no caster can block a light on the sphere, and its pixels skip the casters'
    /// tests (their own shadow stays). Every row without the feature.
    pub shadows: (u16, u16),
}

/// A sphere's constants for one light: the caster filter (see the fixed path's
/// `NarrowLight`), in `N·L` and `(N·L)²`.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct NarrowLight {
    /// The spheres that can shadow the sphere from this light.
    pub casters: u32,
    /// `N·L` at or above this: no caster is ahead.
    pub ahead: f32,
    /// `(N·L)²` above this: no caster is within reach.
    pub reach: f32,
}

impl NarrowLight {
    /// No caster (the default): nothing is tested.
    pub(crate) const NONE: NarrowLight = NarrowLight {
        casters: 0,
        ahead: 0.0,
        reach: 0.0,
    };
}

/// The frame's narrow constants: the directions' steps and each light's `L × Sx`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct NarrowView<const L: usize> {
    /// Half a pixel right and up on the image plane at distance 1: `Sx`, `Sy`.
    pub sx: Vec3,
    pub sy: Vec3,
    /// Per light: `L` and `L × Sx`.
    pub to_light: [Vec3; L],
    pub l_sx: [Vec3; L],
}

/// A scene prepared for rendering at one size on one float path (`W`).
///
/// ```
/// use shadeline::{Prepared, Render, Scalar, Simd8, Rgb888, exponent_series};
/// let scene = exponent_series()?;
/// let scalar = Prepared::<Scalar>::new(&scene, 64, 48)?;
/// let simd = Prepared::<Simd8>::new(&scene, 64, 48)?;
/// let (mut a, mut b) = ([Rgb888::default(); 64], [Rgb888::default(); 64]);
/// scalar.render_line(24, &mut a)?;
/// simd.render_line(24, &mut b)?;
/// assert_eq!(a, b);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug)]
pub struct Prepared<W: FloatPath = Scalar, const S: usize = 16, const L: usize = 8> {
    pub(crate) width: u32,
    pub(crate) height: u32,
    pub(crate) eye: Vec3,
    pub(crate) right: Vec3,
    pub(crate) up: Vec3,
    pub(crate) forward: Vec3,
    /// `(w/h)·tan(vfov/2)`: camera-plane x at the right edge.
    pub(crate) x_scale: f32,
    /// `tan(vfov/2)`: camera-plane y at the top edge.
    pub(crate) y_scale: f32,
    pub(crate) width_f: f32,
    pub(crate) height_f: f32,
    pub(crate) epsilon: f32,
    pub(crate) background: LinearRgb,
    pub(crate) spheres: heapless::Vec<PreparedSphere, S>,
    pub(crate) lights: heapless::Vec<PreparedLight, L>,
    /// Per sphere and light, the other spheres that can shadow it
    /// ([`Scene::shadow_casters`]).
    pub(crate) casters: heapless::Vec<[u32; L], S>,
    pub(crate) use_spans: bool,
    /// Whether silhouettes are anti-aliased (`Prepared::with_antialiasing`).
    #[cfg(feature = "antialias")]
    pub(crate) antialias: bool,
    /// The side of a pixel on the image plane (at distance 1 from the eye).
    #[cfg(feature = "antialias")]
    pub(crate) pixel: f32,
    /// Whether a light is a sphere light: the kernel's light loop has its sphere-light
    /// branch only in frames that need it.
    #[cfg(feature = "area-lights")]
    pub(crate) sphere_lights: bool,
    /// Whether a sphere has a normalized model (or Lambert): on the scalar paths, frames
    /// without one are shaded by a kernel that holds only the classic models' code (see
    /// `float::row`).
    pub(crate) normalized: bool,
    /// The kernel the rows take, with the reason if not the narrow one (`prepare_narrow`).
    pub(crate) kernel: Kernel,
    /// The narrow kernel's frame constants: `Some` exactly when `kernel` is
    /// [`Kernel::Narrow`] (both set by `prepare_narrow`; see `narrow`).
    pub(crate) narrow: Option<NarrowView<L>>,
    /// Per sphere and light, the narrow kernel's caster filter (set with `narrow`).
    pub(crate) narrow_lights: heapless::Vec<[NarrowLight; L], S>,
    _path: PhantomData<W>,
}

impl<W: FloatPath, const S: usize, const L: usize> Prepared<W, S, L> {
    /// Prepares `scene` for a `width × height` image.
    ///
    /// Fails with [`RenderError::BadSize`] if a dimension is 0 or above [`MAX_DIMENSION`].
    pub fn new(scene: &Scene<S, L>, width: u32, height: u32) -> Result<Self, RenderError> {
        if width == 0 || height == 0 || width > MAX_DIMENSION || height > MAX_DIMENSION {
            return Err(RenderError::BadSize { width, height });
        }
        // Refused up front, with the size: after this nothing fails, and the frame is built
        // where it is returned. (A scene holds a sphere light only with `area-lights`, which
        // renders it.)
        let camera = scene.camera();
        let (right, up, forward) = scene.camera_basis();
        let tan = camera.tan_half_fov();
        let width_f = width as f32;
        let height_f = height as f32;
        let eye = camera.position;
        // The side of a pixel on the image plane at distance 1 (pixels are square).
        let pixel = 2.0 * tan / height_f;

        // The stages fill vectors this function owns: returning theirs, they take the prepare
        // more instructions on the M4F (`docs/performance.md, "Choices measured"`).
        let mut spheres = heapless::Vec::new();
        Self::prepare_spheres(&mut spheres, scene, eye, (right, up, pixel));
        let mut lights = heapless::Vec::new();
        Self::prepare_lights(&mut lights, scene);
        let mut casters = heapless::Vec::new();
        Self::prepare_casters(&mut casters, scene);
        #[cfg(feature = "area-lights")]
        let sphere_lights = lights
            .iter()
            .any(|l| matches!(l, PreparedLight::Sphere { .. }));
        let normalized = spheres.iter().any(|s| s.normalized);
        let mut frame = Prepared {
            width,
            height,
            eye,
            right,
            up,
            forward,
            x_scale: (width_f / height_f) * tan,
            y_scale: tan,
            width_f,
            height_f,
            epsilon: scene.ray_epsilon(),
            background: scene.background(),
            spheres,
            lights,
            casters,
            use_spans: true,
            #[cfg(feature = "antialias")]
            antialias: false,
            #[cfg(feature = "antialias")]
            pixel,
            #[cfg(feature = "area-lights")]
            sphere_lights,
            normalized,
            kernel: Kernel::Narrow,
            narrow: None,
            narrow_lights: heapless::Vec::new(),
            _path: PhantomData,
        };
        frame.kernel = match frame.prepare_narrow(scene) {
            Ok(()) => Kernel::Narrow,
            Err((item, field)) => Kernel::General { item, field },
        };
        Ok(frame)
    }

    /// Pushes each sphere's constants onto `spheres`, in scene order: its offset from the
    /// `eye`, `r²` and `1/r`, its material's constants ([`Params::of`]) and which optional
    /// parts of the models they use, and with `antialias` its silhouette (`Outline::of`, from
    /// `view`: the camera's right and up and the side of a pixel on the image plane).
    #[inline(always)]
    fn prepare_spheres(
        spheres: &mut heapless::Vec<PreparedSphere, S>,
        scene: &Scene<S, L>,
        eye: Vec3,
        view: (Vec3, Vec3, f32),
    ) {
        #[cfg(feature = "antialias")]
        let (right, up, pixel) = view;
        #[cfg(not(feature = "antialias"))]
        let _ = view;
        for s in scene.spheres() {
            let params = Params::<f32>::of(&s.material);
            let p = PreparedSphere {
                center: s.center,
                eye_offset: eye - s.center,
                radius_sq: s.radius * s.radius,
                inv_radius: 1.0 / s.radius,
                params,
                normalized: params.normalized > 0.0,
                schlick: params.schlick > 0.0,
                more_lobes: params.weight[1..].iter().any(|&w| w > 0.0),
                #[cfg(feature = "models")]
                oren_nayar: params.oren_nayar > 0.0,
                #[cfg(feature = "models")]
                ggx: params.ggx > 0.0,
                #[cfg(feature = "antialias")]
                outline: Outline::of(s.center - eye, s.radius, pixel, right, up),
                narrow: None,
            };
            // Same capacity as the scene: cannot fail.
            let pushed = spheres.push(p);
            debug_assert!(pushed.is_ok(), "more spheres than the scene holds");
        }
    }

    /// Pushes each light's constants onto `lights`, in scene order: a distant light's unit
    /// direction toward it and arriving colour, a point light's position and power
    /// (`color · intensity / 4π`), and with `area-lights` a point light with a radius as a
    /// sphere light.
    #[inline(always)]
    fn prepare_lights(lights: &mut heapless::Vec<PreparedLight, L>, scene: &Scene<S, L>) {
        for l in scene.lights() {
            let p = match *l {
                Light::Distant {
                    direction,
                    color,
                    intensity,
                } => PreparedLight::Distant {
                    to_light: {
                        // Validated: a scene's light direction is finite and not zero.
                        let unit = direction.normalized();
                        debug_assert!(unit.is_some(), "light direction {direction:?}");
                        -unit.unwrap_or_default()
                    },
                    arriving: Vec3::new(color.r, color.g, color.b).scale(intensity),
                },
                #[cfg(feature = "area-lights")]
                Light::Point {
                    position,
                    color,
                    intensity,
                    radius,
                } if radius > 0.0 => PreparedLight::Sphere {
                    position,
                    power: Vec3::new(color.r, color.g, color.b)
                        .scale(intensity / (4.0 * core::f32::consts::PI)),
                    radius,
                },
                Light::Point {
                    position,
                    color,
                    intensity,
                    ..
                } => PreparedLight::Point {
                    position,
                    power: Vec3::new(color.r, color.g, color.b)
                        .scale(intensity / (4.0 * core::f32::consts::PI)),
                },
            };
            // Same capacity as the scene: cannot fail.
            let pushed = lights.push(p);
            debug_assert!(pushed.is_ok(), "more lights than the scene holds");
        }
    }

    /// Pushes onto `casters`, per sphere and light, the other spheres that can shadow it
    /// ([`Scene::shadow_casters`]).
    #[inline(always)]
    fn prepare_casters(casters: &mut heapless::Vec<[u32; L], S>, scene: &Scene<S, L>) {
        for i in 0..scene.spheres().len() {
            let mut per_light = [0u32; L];
            for (mask, light) in per_light.iter_mut().zip(scene.lights()) {
                *mask = scene.shadow_casters(i, light);
            }
            // Same capacity as the scene: cannot fail.
            let pushed = casters.push(per_light);
            debug_assert!(pushed.is_ok(), "more caster masks than spheres");
        }
    }

    /// Sets up the narrow kernel (see `narrow`) if the frame meets its conditions: every
    /// light distant, every sphere classic with `ks·ΣI·n` within [`SHARPEST`], the camera
    /// clearly outside every sphere; otherwise names the first item and field that keeps the
    /// frame from it.
    fn prepare_narrow(&mut self, scene: &Scene<S, L>) -> Result<(), (Item, &'static str)> {
        let mut to_light = [Vec3::default(); L];
        let mut intensity = 0.0f32;
        for (k, (t, l)) in to_light.iter_mut().zip(&self.lights).enumerate() {
            let PreparedLight::Distant { to_light, arriving } = *l else {
                return Err((Item::Light(k), "type"));
            };
            *t = to_light;
            intensity += arriving.x.max(arriving.y).max(arriving.z);
        }
        let lambert = |i: usize| {
            scene
                .spheres()
                .get(i)
                .is_some_and(|s| matches!(s.material.model, Model::Lambert))
        };
        if let Some(i) = (0..self.spheres.len())
            .find(|&i| self.spheres.get(i).is_some_and(|s| s.normalized) && !lambert(i))
        {
            return Err((Item::Sphere(i), "model"));
        }
        let sx = self.right.scale(self.x_scale / self.width_f);
        let sy = self.up.scale(self.y_scale / self.height_f);
        let eps = self.epsilon;
        let mut narrow_lights = heapless::Vec::new();
        for i in 0..self.spheres.len() {
            let Some(s) = self.spheres.get(i).copied() else {
                return Err((Item::Sphere(i), "center"));
            };
            let r = 1.0 / s.inv_radius;
            let oc = s.eye_offset;
            let ks = if lambert(i) { 0.0 } else { s.params.ks };
            // A NaN sharpness takes the general kernel.
            let sharp = ks * intensity * s.params.shininess;
            let within = matches!(
                sharp.partial_cmp(&SHARPEST),
                Some(Ordering::Less | Ordering::Equal)
            );
            if oc.dot(oc) <= (r + 2.0 * eps) * (r + 2.0 * eps) {
                return Err((Item::Sphere(i), "center"));
            }
            if !within {
                return Err((Item::Sphere(i), "shininess"));
            }
            let o = oc.scale(s.inv_radius);
            let narrow = NarrowSphere {
                o,
                o_sx: o.cross(sx),
                origin: self.middle_column(oc),
                radius: r,
                own_limit: eps * (2.0 * r + eps) / ((r + eps) * (r + eps)),
                ks,
                // Every row until `prepare_shadow_rows`.
                shadows: (0, self.height as u16),
            };
            let mut lights = [NarrowLight::default(); L];
            for (k, (nl, t)) in lights.iter_mut().zip(&to_light).enumerate() {
                *nl = self.narrow_filter(scene, i, k, *t);
            }
            if narrow_lights.push(lights).is_err() {
                return Err((Item::Sphere(i), "center"));
            }
            if let Some(sphere) = self.spheres.get_mut(i) {
                sphere.narrow = Some(narrow);
            }
        }
        self.narrow_lights = narrow_lights;
        self.narrow = Some(NarrowView {
            sx,
            sy,
            to_light,
            l_sx: to_light.map(|l| l.cross(sx)),
        });
        self.prepare_shadow_rows(scene, sy);
        Ok(())
    }

    /// A sphere's middle column for the narrow kernel (`NarrowSphere::origin`), from its
    /// offset `oc = eye − centre`: the centre's projection, as a whole number of half pixels
    /// from the image centre, within the frame's width on either side (0 if not finite).
    fn middle_column(&self, oc: Vec3) -> f32 {
        let c = -oc;
        let (cx, cz) = (c.dot(self.right), c.dot(self.forward));
        let origin = (cx / cz * (self.width_f / self.x_scale)).clamp(-self.width_f, self.width_f);
        let origin = libm::roundf(origin);
        if origin.is_finite() {
            origin
        } else {
            0.0
        }
    }

    /// Sets each narrow sphere's shadow rows (`NarrowSphere::shadows`) with the feature
    /// `shadow-rows` ([`super::shadow_rows`], on the narrow view's step `sy` up); without
    /// it every sphere keeps every row.
    fn prepare_shadow_rows(&mut self, scene: &Scene<S, L>, sy: Vec3) {
        #[cfg(feature = "shadow-rows")]
        for i in 0..self.spheres.len() {
            let rows = self.shadow_rows(scene, i, sy);
            if let Some(n) = self.spheres.get_mut(i).and_then(|s| s.narrow.as_mut()) {
                n.shadows = rows;
            }
        }
        #[cfg(not(feature = "shadow-rows"))]
        let _ = (scene, sy);
    }

    /// Sphere `i`'s caster filter for distant light `k` toward `to_light` (see the fixed
    /// path's `NarrowLight`: the loosest of `N·L < −Δ·L/(r + ε)` and
    /// `(N·L)² ≤ 1 − ((|Δ⊥| − r_c)/(r + ε))²` over the casters `c`, `Δ = C − C_c`),
    /// widened by `2⁻¹⁶`, far above the narrow `N·L`'s error. With no caster nothing passes.
    ///
    /// A caster a plane keeps off every ray the sphere's lit pixels cast
    /// ([`plane_keeps_off`]: the floor under a sphere resting on it, lit from above), or
    /// that every such ray moves away from and never leaves beyond `ε` ([`recedes`]: the
    /// same floor lit from lower), leaves the mask: [`Scene::shadow_casters`]' mask keeps
    /// it, since it touches the sphere, and every lit pixel would test it.
    fn narrow_filter(
        &self,
        scene: &Scene<S, L>,
        i: usize,
        k: usize,
        to_light: Vec3,
    ) -> NarrowLight {
        let mask = scene
            .lights()
            .get(k)
            .map_or(0, |light| scene.shadow_casters(i, light));
        let Some(own) = self.spheres.get(i) else {
            return NarrowLight::default();
        };
        let lift = 1.0 / own.inv_radius + self.epsilon;
        // The narrow N·L's error, |ô|·2⁻¹⁸, doubled and more, for the plane's rule.
        let eye_radii = libm::sqrtf(own.eye_offset.dot(own.eye_offset)) * own.inv_radius;
        let widen = 1.0 / 256.0 + eye_radii / 65536.0;
        let mut mask = mask;
        let (mut ahead, mut reach) = (f32::NEG_INFINITY, f32::NEG_INFINITY);
        for (c, other) in self.spheres.iter().enumerate() {
            if c == i || c >= 32 || mask & (1 << c) == 0 {
                continue;
            }
            let delta = own.center - other.center;
            let radii = (
                1.0 / own.inv_radius,
                libm::sqrtf(other.radius_sq),
                self.epsilon,
            );
            if plane_keeps_off(radii, delta, to_light, widen)
                || recedes(radii, delta, to_light, widen)
            {
                mask &= !(1 << c);
                continue;
            }
            let along = delta.dot(to_light);
            let across = delta - to_light.scale(along);
            let gap = libm::sqrtf(across.dot(across)) - libm::sqrtf(other.radius_sq);
            ahead = ahead.max(-along / lift);
            reach = reach.max(if gap <= 0.0 {
                1.0
            } else {
                1.0 - (gap / lift) * (gap / lift)
            });
        }
        if mask == 0 || ahead == f32::NEG_INFINITY {
            return NarrowLight {
                casters: mask,
                ahead: f32::NEG_INFINITY,
                reach: f32::NEG_INFINITY,
            };
        }
        let margin = 1.0 / 65536.0;
        NarrowLight {
            casters: mask,
            ahead: ahead + margin,
            reach: reach + 2.0 * margin,
        }
    }

    /// Turns the scanline spans on (the default) or off. Off, every packet tests every sphere:
    /// the naive per-pixel renderer, kept for benchmarks and for the test that spans change
    /// no pixel.
    pub fn with_spans(mut self, on: bool) -> Self {
        self.use_spans = on;
        self
    }

    /// Turns analytic anti-aliasing of the spheres' silhouettes on or off (off by default).
    ///
    /// With it on, a pixel the outline of its front sphere crosses gets that sphere's
    /// coverage of the pixel, from the outline's conic, and blends the sphere's colour with
    /// what lies behind it (the background, or a sphere further away). Pixels away from every
    /// outline are shaded as without it, bit for bit. The scalar and SIMD paths stay
    /// bit-identical; see `src/float/edges.rs` for the rule.
    ///
    /// ```
    /// use shadeline::{exponent_series, Prepared, Render, Rgb888, Scalar};
    ///
    /// let scene = exponent_series()?;
    /// let sharp = Prepared::<Scalar, _, _>::new(&scene, 64, 48)?;
    /// let smooth = sharp.clone().with_antialiasing(true);
    /// let (mut a, mut b) = ([Rgb888::default(); 64], [Rgb888::default(); 64]);
    /// sharp.render_line(24, &mut a)?;
    /// smooth.render_line(24, &mut b)?;
    /// assert_ne!(a, b); // the silhouettes on the row are blended
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    #[cfg(feature = "antialias")]
    pub fn with_antialiasing(mut self, on: bool) -> Self {
        self.antialias = on;
        self
    }

    /// The per-row constants of row `j`: camera-plane `y` is `(1 − 2(j + ½)/h)·tan(vfov/2)`.
    #[inline]
    pub(crate) fn row(&self, j: u32) -> Row {
        let yc = (1.0 - (2.0 * (j as f32 + 0.5)) / self.height_f) * self.y_scale;
        Row {
            #[cfg(feature = "antialias")]
            y: yc,
            base: self.up.scale(yc) + self.forward,
        }
    }
}

/// Per-row constants: the camera-plane `y` term of every primary direction on row `j`.
#[derive(Clone, Copy)]
pub(crate) struct Row {
    /// `y_j`, the row's image-plane coordinate.
    #[cfg(feature = "antialias")]
    pub y: f32,
    /// `y_j·up + forward`.
    pub base: Vec3,
}

#[cfg(feature = "antialias")]
impl Outline {
    /// The outline of a sphere of radius `r` at `oc = C − eye`, for pixels of side `pixel` on
    /// the image plane and the camera's `right` and `up`.
    ///
    /// The spans' radius: the silhouette is the cone of half-angle `θ = asin(r/|oc|)` around
    /// `oc`, and a pixel subtends at most `pixel` radians anywhere on the image plane (the
    /// gnomonic projection only stretches angles), so the sphere of half-angle
    /// `θ + 1.5·pixel` has its outline at least 1.5 pixels outside this one's, beyond the
    /// half-pixel ramp of the edges. Past a half-angle of 90° the cone has no silhouette:
    /// `r² = |oc|²`, which the spans take as the whole row.
    pub(crate) fn of(oc: Vec3, r: f32, pixel: f32, right: Vec3, up: Vec3) -> Outline {
        let d2 = oc.dot(oc);
        let k = d2 - r * r;
        let spans_radius_sq = if k > 0.0 {
            let d = libm::sqrtf(d2);
            let angle = libm::asinf((r / d).min(1.0)) + 1.5 * pixel;
            if angle < core::f32::consts::FRAC_PI_2 {
                let s = libm::sinf(angle) * d;
                s * s
            } else {
                d2
            }
        } else {
            r * r
        };
        Outline {
            k,
            oc_right: oc.dot(right),
            oc_up: oc.dot(up),
            spans_radius_sq,
            spans_k: d2 - spans_radius_sq,
        }
    }
}

/// Whether the plane across `Δ` (a sphere's centre less a caster's) keeps the caster off
/// every shadow ray toward the distant light `L` that the narrow kernel casts from the
/// sphere's pixels: `radii` is the sphere's radius `r`, the caster's `r_c` and the lift
/// `ε`; `widen` bounds the error of the `N·L` the own-shadow test reads.
/// [`crate::caster_plane::clearance`] with `δ = Δ·L/|Δ|`, above a margin of `ε` and `2⁻¹²`
/// of the distance `|Δ| + r + ε`, thousands of times the rounding of
/// [`super::intersect::meets`] at that distance.
fn plane_keeps_off(radii: (f32, f32, f32), delta: Vec3, to_light: Vec3, widen: f32) -> bool {
    let (r, _, eps) = radii;
    let len = libm::sqrtf(delta.dot(delta));
    let clearance = crate::caster_plane::clearance(radii, len, delta.dot(to_light) / len, widen);
    clearance.is_some_and(|c| c > eps + (len + r + eps) / 4096.0)
}

/// Whether every shadow ray toward the distant light `L` from the sphere's pixels that test
/// casters moves away from the caster's centre and, where it starts inside the caster,
/// leaves it within `ε`, so that [`super::intersect::meets`] never finds it blocking:
/// [`crate::caster_plane::recession`] and [`crate::caster_plane::leaves_within`], with
/// `radii`, `delta` and `widen` as [`plane_keeps_off`] takes them. The margins: `2⁻¹⁶` of
/// the distance `|Δ| + r + ε` off `b` and off `|O − C_c|`, and `2⁻¹⁸` of `r_c²` for `meets`'
/// `r_c² − |O − C_c|²` (from `disc` and `b²`), each many times the `f32` rounding of the
/// lifted point and of `meets` at that distance.
fn recedes(radii: (f32, f32, f32), delta: Vec3, to_light: Vec3, widen: f32) -> bool {
    let (r, rc, eps) = radii;
    let len = libm::sqrtf(delta.dot(delta));
    let along = delta.dot(to_light) / len - 1.0 / 1_048_576.0;
    let Some((b, x)) = crate::caster_plane::recession((r, eps), len, along, widen) else {
        return false;
    };
    let margin = (len + r + eps) / 65536.0;
    let slack = rc * rc / 262_144.0;
    crate::caster_plane::leaves_within(rc, eps, (b - margin, x - margin), slack)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// [`plane_keeps_off`] against the geometry in `f64`, over random pairs of spheres (the
    /// caster up to 200 times the radius, a floor) and lights: wherever it leaves a caster
    /// out, no shadow ray from a lifted point of the sphere that tests casters (`N·L` at or
    /// above minus the own-shadow limit, widened by `2⁻¹¹`) comes within the caster's radius
    /// and `2⁻¹⁴` of the distance, at the worst such point and at random ones.
    #[test]
    fn left_out_casters_meet_no_ray() {
        use crate::test_scenes::{uniform64, PlanePair};
        let mut next = uniform64(0x9e37_79b9_7f4a_7c15);
        let mut left_out = 0;
        for _ in 0..20_000 {
            let pair = PlanePair::random(&mut next, 1.0);
            let PlanePair { r, rc, eps, d, l } = pair;
            let (df, lf) = (d.map(|c| c as f32), l.map(|c| c as f32));
            let delta = Vec3::new(df[0], df[1], df[2]);
            let to_light = Vec3::new(lf[0], lf[1], lf[2]);
            if !plane_keeps_off(
                (r as f32, rc as f32, eps as f32),
                delta,
                to_light,
                1.0 / 256.0,
            ) {
                continue;
            }
            left_out += 1;
            let s = (1.0 - (r / (r + eps)).powi(2)).sqrt() + 1.0 / 2048.0;
            let len = pair.len_and_delta().0;
            pair.assert_no_ray_within(&mut next, s, rc + (len + r + eps) / 16384.0);
        }
        assert!(left_out > 3000, "only {left_out} casters left out");
    }

    /// [`recedes`] against the geometry in `f64`, over random pairs as above (half of them
    /// touching): wherever it leaves a caster out, every shadow ray from a lifted point of
    /// the sphere that tests casters moves away from the caster's centre and leaves it
    /// within `ε` where it starts inside it, at the lifted point nearest the caster and at
    /// random ones; and it leaves out pairs the plane keeps in.
    #[test]
    fn receding_casters_are_never_met() {
        use crate::test_scenes::{uniform64, PlanePair};
        let mut next = uniform64(0x6a09_e667_f3bc_c908);
        let (mut dropped, mut beyond_plane) = (0, 0);
        for _ in 0..40_000 {
            let mut pair = PlanePair::random(&mut next, 1.0);
            if next(0.0, 1.0) < 0.5 {
                pair = pair.touching(1.0);
            }
            let PlanePair { r, rc, eps, d, l } = pair;
            let (df, lf) = (d.map(|c| c as f32), l.map(|c| c as f32));
            let delta = Vec3::new(df[0], df[1], df[2]);
            let to_light = Vec3::new(lf[0], lf[1], lf[2]);
            let radii = (r as f32, rc as f32, eps as f32);
            if !recedes(radii, delta, to_light, 1.0 / 256.0) {
                continue;
            }
            dropped += 1;
            beyond_plane += !plane_keeps_off(radii, delta, to_light, 1.0 / 256.0) as u32;
            let s = (1.0 - (r / (r + eps)).powi(2)).sqrt() + 1.0 / 2048.0;
            pair.assert_rays_recede(&mut next, s);
        }
        assert!(
            dropped > 3000 && beyond_plane > 100,
            "{dropped} left out, {beyond_plane} of them kept by the plane"
        );
    }
}
