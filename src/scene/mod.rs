//! The scene a caller describes: a camera, spheres with materials, lights and a background.
//!
//! A [`Scene`] can only hold valid items: [`Scene::new`], [`Scene::add_sphere`] and
//! [`Scene::add_light`] check every number as it comes in and return a [`SceneError`] that
//! names the item and the field, so nothing downstream (prepare, the kernels, the row driver)
//! ever sees a NaN, a zero-length direction or a degenerate camera. Capacities are const
//! generics backed by `heapless::Vec`, so a scene lives on the stack or in a `static`, and
//! exceeding a capacity is an error, not an allocation.
//!
//! The models Oren–Nayar and GGX, and the two Blinn-Phong models, are part of the API in
//! every build, but the kernels hold them only with the crate features `models` and
//! `blinn-phong` (both on by default). Without the feature, a sphere of such a material is
//! refused as it is added, with [`Problem::ModelNotBuilt`] on its `model`: a scene never
//! holds a model the kernels leave out, and never renders another in its place. Sphere lights
//! (point lights with a radius) likewise need the feature `area-lights`: without it
//! [`Scene::add_light`] refuses one with [`Problem::SphereLightNotBuilt`] on its `radius`.
//!
//! The files hold one concept each, and each uses only the files listed above it:
//!
//! | file | what it holds |
//! |---|---|
//! | `limits` | the accepted ranges (below), and the bound an error's message quotes |
//! | `error` | [`SceneError`] with its [`Item`], [`ItemKind`] and [`Problem`], and their messages |
//! | `check` | the field-level checks every item runs, as integer tests on the numbers' bits |
//! | `camera` | the [`Camera`], its check and basis, and `tan(vfov/2)` |
//! | `material` | the [`Material`] and its [`Model`], with the [`Lobe`]s, the [`Surface`], the [`Metal`] presets and the GGX [`Microfacet`] |
//! | `sphere` | the [`Sphere`] and its check |
//! | `light` | the [`Light`], its check, and the test that keeps a sphere light clear of the spheres |
//! | `mod` | the [`Scene`]: its items as they are added, and the geometry the paths prepare from (shadow casters, the ray epsilon, the extent) |
//!
//! # Ranges
//!
//! Every number is finite and bounded, so that geometry never overflows (squared distances
//! stay below `1e13`) and no `NaN` can arise: a point light's `1/r²` and its arriving light are
//! capped (at `f32::MAX` and `1e30`), and the shaded colour saturates at `f32::MAX`, so a
//! very bright pixel is huge but finite, never `inf`:
//!
//! | quantity | accepted |
//! |---|---|
//! | coordinates (camera, centres, point lights) | `\|v\| ≤` [`MAX_COORDINATE`] per component |
//! | radius | [`MIN_RADIUS`] `≤ r ≤` [`MAX_COORDINATE`] |
//! | colours, albedo, `kd`, `ks` | `0 ≤ v ≤` [`MAX_VALUE`] |
//! | light intensity | `0 ≤ i ≤` [`MAX_INTENSITY`] |
//! | point light radius | `0 ≤ R ≤` [`MAX_COORDINATE`], the light's sphere clear of every scene sphere |
//! | shininess `n` (every lobe) | `0 < n ≤` [`MAX_SHININESS`] |
//! | lobe weights (`ks`, `lobes[k].weight`) | `0 ≤ w ≤` [`MAX_VALUE`] |
//! | index of refraction `ior` | `1 < ior ≤` [`MAX_VALUE`]: at 1 there is no interface to reflect, and below 1 Schlick's form would need total internal reflection |
//! | Oren–Nayar `roughness` `σ` (radians) | `0 ≤ σ ≤` [`MAX_OREN_NAYAR_ROUGHNESS`] |
//! | GGX `roughness` `r` | [`MIN_GGX_ROUGHNESS`] `≤ r ≤ 1` |
//! | directions (camera up, distant light) | finite, not zero; only the direction is used |
//! | vertical field of view | `0° < vfov < 180°` |

mod camera;
mod check;
mod error;
mod light;
mod limits;
mod material;
mod sphere;

pub use camera::Camera;
pub use error::{Item, ItemKind, Problem, SceneError};
pub use light::Light;
pub use limits::{
    MAX_COORDINATE, MAX_INTENSITY, MAX_OREN_NAYAR_ROUGHNESS, MAX_SHININESS, MAX_VALUE,
    MIN_GGX_ROUGHNESS, MIN_RADIUS, MIN_UP_SINE,
};
pub use material::{Lobe, Material, Metal, Microfacet, Model, Specular, Surface, MORE_LOBES};
pub use sphere::Sphere;

use crate::pixel::LinearRgb;
use crate::vec3::Vec3;
use check::Check;
#[cfg(feature = "area-lights")]
use light::light_clear_of;

/// The default sphere capacity `S` of [`Scene`], [`Prepared`](crate::Prepared) and
/// [`PreparedFixed`](crate::PreparedFixed): `Scene` alone is `Scene<16, 8>`, and so is every
/// built-in scene ([`crate::presets`]), so a preset goes straight into `Prepared::<Simd8>::new`.
pub const DEFAULT_SPHERES: usize = 16;
/// The default light capacity `L` of [`Scene`], [`Prepared`](crate::Prepared) and
/// [`PreparedFixed`](crate::PreparedFixed) (see [`DEFAULT_SPHERES`]).
pub const DEFAULT_LIGHTS: usize = 8;

/// A validated scene holding up to `S` spheres and `L` lights.
///
/// Without capacities, `Scene` is `Scene<`[`DEFAULT_SPHERES`]`, `[`DEFAULT_LIGHTS`]`>`, the
/// capacities of the built-in scenes and the defaults of the prepared frames. A scene of other
/// capacities is prepared with them inferred: `Prepared::<Scalar, _, _>::new(&scene, w, h)`
/// or `PreparedFixed::new(&scene, w, h)`. (`Prepared::<Scalar>` alone means the defaults.)
///
/// ```
/// use shadeline::{Scene, Sphere, Material, Light, Camera, Vec3, LinearRgb};
/// let camera = Camera {
///     position: Vec3::new(0.0, 0.0, 5.0),
///     look_at: Vec3::new(0.0, 0.0, 0.0),
///     up: Vec3::new(0.0, 1.0, 0.0),
///     vfov_degrees: 40.0,
/// };
/// let mut scene: Scene<4, 2> = Scene::new(camera, LinearRgb::new(0.1, 0.2, 0.3))?;
/// scene.add_sphere(Sphere { center: Vec3::new(0.0, 0.0, 0.0), radius: 1.0, material: Material::default() })?;
/// scene.add_light(Light::Distant {
///     direction: Vec3::new(-1.0, -1.0, -1.0),
///     color: LinearRgb::new(1.0, 1.0, 1.0),
///     intensity: 3.0,
/// })?;
/// assert_eq!(scene.spheres().len(), 1);
/// # Ok::<(), shadeline::SceneError>(())
/// ```
#[derive(Clone, Debug)]
pub struct Scene<const S: usize = DEFAULT_SPHERES, const L: usize = DEFAULT_LIGHTS> {
    camera: Camera,
    /// The camera's orthonormal `(right, up, forward)`, derived once when it is checked.
    basis: (Vec3, Vec3, Vec3),
    background: LinearRgb,
    spheres: heapless::Vec<Sphere, S>,
    lights: heapless::Vec<Light, L>,
}

impl<const S: usize, const L: usize> Scene<S, L> {
    /// An empty scene (no spheres, no lights) seen through `camera` over `background`.
    pub fn new(camera: Camera, background: LinearRgb) -> Result<Self, SceneError> {
        let basis = camera.basis()?;
        Check {
            item: Item::Background,
        }
        .color("background", background)?;
        Ok(Scene {
            camera,
            basis,
            background,
            spheres: heapless::Vec::new(),
            lights: heapless::Vec::new(),
        })
    }

    /// Adds a sphere after checking it; returns its index.
    #[inline(never)]
    pub fn add_sphere(&mut self, sphere: Sphere) -> Result<usize, SceneError> {
        let index = self.spheres.len();
        sphere.check(Item::Sphere(index))?;
        #[cfg(feature = "area-lights")]
        for (k, light) in self.lights.iter().enumerate() {
            light_clear_of(k, light, &sphere)?;
        }
        self.spheres
            .push(sphere)
            .map_err(|_| SceneError::CapacityExceeded {
                kind: ItemKind::Sphere,
                capacity: S,
            })?;
        Ok(index)
    }

    /// Adds a light after checking it; returns its index.
    pub fn add_light(&mut self, light: Light) -> Result<usize, SceneError> {
        let index = self.lights.len();
        light.check(Item::Light(index))?;
        #[cfg(feature = "area-lights")]
        for sphere in &self.spheres {
            light_clear_of(index, &light, sphere)?;
        }
        self.lights
            .push(light)
            .map_err(|_| SceneError::CapacityExceeded {
                kind: ItemKind::Light,
                capacity: L,
            })?;
        Ok(index)
    }

    /// The index of the first sphere light (a point light with a radius), if any.
    pub fn sphere_light(&self) -> Option<usize> {
        self.lights
            .iter()
            .position(|l| matches!(*l, Light::Point { radius, .. } if radius > 0.0))
    }

    /// The camera.
    pub fn camera(&self) -> &Camera {
        &self.camera
    }

    /// The camera's orthonormal basis `(right, up, forward)`, as defined on [`Camera`].
    pub fn camera_basis(&self) -> (Vec3, Vec3, Vec3) {
        self.basis
    }

    /// The background colour, seen where no sphere is hit.
    pub fn background(&self) -> LinearRgb {
        self.background
    }

    /// The spheres, in the order they were added.
    pub fn spheres(&self) -> &[Sphere] {
        &self.spheres
    }

    /// The lights, in the order they were added.
    pub fn lights(&self) -> &[Light] {
        &self.lights
    }

    /// The spheres other than sphere `i` that can shadow any point of it from `light`: bit `j`
    /// for sphere `j < 32` (the paths never leave out spheres from 32 on, nor sphere `i`).
    ///
    /// A shadow ray starts within `r + ε` of sphere `i`'s centre `C` and runs toward the light:
    /// along the direction `u` to a distant light, or up to a point light at `P`. So every point
    /// where it can be blocked lies within `r + ε` of the half-line `C + t·u, t ≥ 0`, or of the
    /// segment `[C, P]`, and sphere `j` can block it only if its centre is within
    /// `r + rⱼ + ε` of that half-line or segment. The test adds a margin of `4ε + 10⁻³(r + rⱼ)`,
    /// far above the rounding of this `f32` test and of the paths' own hit tests, so leaving a
    /// sphere out never changes a pixel (the golden and agreement tests render with the masks;
    /// each path's own test is the same arithmetic as without them). A
    /// number that is not finite keeps the sphere in. Both paths prepare these masks once per
    /// frame, so a shadow ray tests the sphere it starts on and the masked spheres only.
    // `!(a >= b)` on purpose: a NaN keeps the sphere (conservative).
    #[allow(clippy::neg_cmp_op_on_partial_ord)]
    pub(crate) fn shadow_casters(&self, i: usize, light: &Light) -> u32 {
        let spheres = self.spheres();
        // Prepare asks about its own spheres only.
        debug_assert!(i < spheres.len(), "sphere {i} of {}", spheres.len());
        let Some(own) = spheres.get(i) else {
            return 0;
        };
        let eps = self.ray_epsilon();
        // The half-line or segment `C + t·s`: `t ≥ 0` toward a distant light (`|s| = 1`),
        // `0 ≤ t ≤ 1` up to a point light.
        let (s, t_max) = match *light {
            Light::Distant { direction, .. } => {
                // Validated: finite and not zero.
                let unit = (-direction).normalized();
                debug_assert!(unit.is_some(), "light direction {direction:?}");
                (unit.unwrap_or_default(), f32::INFINITY)
            }
            Light::Point { position, .. } => (position - own.center, 1.0),
        };
        let ss = s.dot(s);
        let mut mask = 0u32;
        for (j, other) in spheres.iter().enumerate().take(32) {
            if j == i {
                continue;
            }
            let v = other.center - own.center;
            // The point of the half-line or segment closest to the other centre.
            let t = if ss > 0.0 {
                (v.dot(s) / ss).clamp(0.0, t_max)
            } else {
                0.0
            };
            let closest = s.scale(t);
            let w = v - closest;
            let radii = own.radius + other.radius;
            let reach = radii + eps + 4.0 * eps + 1.0e-3 * radii;
            if !(w.dot(w) >= reach * reach) {
                mask |= 1 << j;
            }
        }
        mask
    }

    /// The scene's ray epsilon, in scene units: primary and shadow hits closer than this are
    /// ignored, and shadow rays start this far out along the normal (the lesson's `bias`).
    ///
    /// It is `1e-4 · max(1, extent)`, where `extent` is the largest coordinate magnitude in
    /// the scene (camera, sphere centre plus radius, point light): about 800 `f32` ulps of
    /// the coordinates, so a shadow ray never re-hits its own surface through rounding, yet
    /// small enough not to lift contact shadows visibly. Every path and the f64 reference
    /// use this same number.
    pub fn ray_epsilon(&self) -> f32 {
        1.0e-4 * self.extent().max(1.0)
    }

    /// The largest coordinate magnitude in the scene: camera, sphere centre plus radius,
    /// point light. [`Self::ray_epsilon`] and the fixed path's scale both start from it; one
    /// copy, out of line, for a firmware's flash.
    #[inline(never)]
    pub(crate) fn extent(&self) -> f32 {
        let mut extent = self.camera.position.max_abs();
        for s in &self.spheres {
            extent = extent.max(s.center.max_abs() + s.radius);
        }
        for l in &self.lights {
            if let Light::Point { position, .. } = l {
                extent = extent.max(position.max_abs());
            }
        }
        extent
    }
}
