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

use crate::pixel::LinearRgb;
use crate::vec3::Vec3;
use core::fmt;

/// The default sphere capacity `S` of [`Scene`], [`Prepared`](crate::Prepared) and
/// [`PreparedFixed`](crate::PreparedFixed): `Scene` alone is `Scene<16, 8>`, and so is every
/// built-in scene ([`crate::presets`]), so a preset goes straight into `Prepared::<Simd8>::new`.
pub const DEFAULT_SPHERES: usize = 16;
/// The default light capacity `L` of [`Scene`], [`Prepared`](crate::Prepared) and
/// [`PreparedFixed`](crate::PreparedFixed) (see [`DEFAULT_SPHERES`]).
pub const DEFAULT_LIGHTS: usize = 8;

/// Largest accepted magnitude of a coordinate component and of a radius, in scene units.
pub const MAX_COORDINATE: f32 = 1.0e6;
/// Smallest accepted radius: `r²` is then a normal `f32` and `1/r` is finite. Below it the
/// squared radius underflows to 0 and the normal `(P − C)·(1/r)` becomes `0·inf = NaN`.
pub const MIN_RADIUS: f32 = 1.0e-18;
/// Largest accepted colour component, albedo component, `kd` or `ks`.
pub const MAX_VALUE: f32 = 1.0e6;
/// Largest accepted light intensity.
pub const MAX_INTENSITY: f32 = 1.0e12;
/// Largest accepted Phong exponent.
pub const MAX_SHININESS: f32 = 1.0e6;
/// Smallest sine of the angle between the camera's up vector and its view direction.
pub const MIN_UP_SINE: f32 = 1.0e-3;

/// The pinhole camera: where it is, what it looks at, which way is up, how wide it sees.
///
/// The primary ray of pixel `(i, j)` of a `w × h` image goes through the pixel centre:
/// `x = (2(i + ½)/w − 1)·(w/h)·tan(vfov/2)`, `y = (1 − 2(j + ½)/h)·tan(vfov/2)`, direction
/// `normalize(x·right + y·up' + forward)`, where `forward` points at `look_at`,
/// `right = normalize(forward × up)` and `up' = right × forward` (right-handed).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    /// The eye point.
    pub position: Vec3,
    /// The point the camera looks at; must differ from `position`.
    pub look_at: Vec3,
    /// Which way is up; must not be parallel to the view direction. Need not be unit length.
    pub up: Vec3,
    /// Vertical field of view in degrees, in `(0, 180)`.
    pub vfov_degrees: f32,
}

/// Which reflection model a material uses. The formulas are in [`crate::brdf`].
///
/// The two classic models are the lesson's: empirical, not normalized, not energy
/// conserving (their highlight does not dim as it widens). The others are normalized BRDFs:
/// positive, reciprocal, and energy conserving when [`Material::is_energy_conserving`].
///
/// For every model `kd`, `albedo`, `ks` and `shininess` keep their meaning: the diffuse
/// weight and colour, and the weight and exponent of the first specular lobe.
///
/// [`Model::OrenNayar`] and [`Model::Ggx`] exist in every build, but render only with the
/// crate feature `models`, and [`Model::BlinnPhong`] and [`Model::NormalizedBlinnPhong`] only
/// with `blinn-phong` (both on by default): without it, [`Scene::add_sphere`] refuses them
/// with [`Problem::ModelNotBuilt`].
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum Model {
    /// Classic Phong: `ks·I·max(0, R·V)^n`, `R` the light's travel direction mirrored about `N`.
    Phong,
    /// Classic Blinn-Phong: `ks·I·max(0, N·H)^n` with `H = normalize(L + V)`. Feature
    /// `blinn-phong`.
    BlinnPhong,
    /// Lambert: the diffuse lobe `kd·albedo/π` alone; `ks` and `shininess` are not used.
    Lambert,
    /// Normalized (Lafortune–Willems modified) Phong:
    /// `kd·albedo/π + Σ wₖ·(nₖ + 2)/(2π)·max(0, R·V)^nₖ`.
    NormalizedPhong(Specular),
    /// Normalized Blinn-Phong: `kd·albedo/π + Σ wₖ·c(nₖ)·max(0, N·H)^nₖ` with the exact
    /// normalization `c(n) = (n + 2)(n + 4) / (8π(2^(−n/2) + n))`, which makes the lobe's
    /// directional albedo 1 at normal view (see [`crate::brdf`]). Feature `blinn-phong`.
    NormalizedBlinnPhong(Specular),
    /// Oren–Nayar rough diffuse (the qualitative model of Oren and Nayar, 1994):
    /// `kd·albedo/π·(A + B·max(0, cos(φᵢ − φₒ))·sin α·tan β)`, with `roughness` the standard
    /// deviation `σ` of the facet slopes in radians, `0 ≤ σ ≤` [`MAX_OREN_NAYAR_ROUGHNESS`].
    /// At `σ = 0` it is Lambert. `ks` and `shininess` are not used. Feature `models`.
    OrenNayar {
        /// `σ`, radians.
        roughness: f32,
    },
    /// Cook–Torrance microfacet specular with the GGX (Trowbridge–Reitz) distribution, Smith
    /// height-correlated masking-shadowing and Schlick Fresnel, weighted by `ks`, plus a
    /// Lambert lobe `kd·albedo/π` for dielectrics (see [`Microfacet`] and [`crate::brdf`]).
    /// `shininess` is not used. Feature `models`.
    Ggx(Microfacet),
}

/// Smallest accepted GGX `roughness`: `α = roughness²` is then `2.5·10⁻³` and the
/// distribution's peak `1/(πα²)` is about `5·10⁴`, still a lobe some pixels wide on a sphere
/// of a few hundred pixels; a smaller one would be a mirror that pixels cannot resolve.
pub const MIN_GGX_ROUGHNESS: f32 = 0.05;

/// Largest accepted Oren–Nayar `σ`, in radians: facet slopes of 90° standard deviation
/// already make the surface as rough as the model describes.
pub const MAX_OREN_NAYAR_ROUGHNESS: f32 = core::f32::consts::FRAC_PI_2;

/// The options of the GGX model: the perceptual roughness and the surface.
///
/// ```
/// use shadeline::{Material, Metal, Microfacet, Model, Surface};
/// let brushed_gold = Material {
///     kd: 0.0,
///     ks: 1.0,
///     model: Model::Ggx(Microfacet { roughness: 0.4, surface: Surface::Metal(Metal::Gold) }),
///     ..Material::default()
/// };
/// assert!(brushed_gold.is_energy_conserving());
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Microfacet {
    /// Perceptual roughness `r`, [`MIN_GGX_ROUGHNESS`] `≤ r ≤ 1`; the distribution's width
    /// is `α = r²`.
    pub roughness: f32,
    /// Dielectric (a Lambert lobe under an untinted highlight; with `ior`, Schlick Fresnel
    /// and `1 − F` on the diffuse lobe; without, `F = 1`) or metal (tinted, no diffuse lobe).
    pub surface: Surface,
}

impl Default for Model {
    /// [`Model::Phong`], the lesson's classic model.
    fn default() -> Self {
        Model::Phong
    }
}

impl Model {
    /// The specular options of a normalized Phong or Blinn-Phong model (`None` for the
    /// others).
    pub fn specular(&self) -> Option<&Specular> {
        match self {
            Model::NormalizedPhong(s) | Model::NormalizedBlinnPhong(s) => Some(s),
            _ => None,
        }
    }

    /// Whether this is one of the lesson's two classic, unnormalized models.
    pub fn is_classic(&self) -> bool {
        matches!(self, Model::Phong | Model::BlinnPhong)
    }

    /// The surface of a model that has one (normalized Phong and Blinn-Phong, GGX).
    pub fn surface(&self) -> Option<Surface> {
        match self {
            Model::NormalizedPhong(s) | Model::NormalizedBlinnPhong(s) => Some(s.surface),
            Model::Ggx(m) => Some(m.surface),
            _ => None,
        }
    }
}

/// Specular options of the normalized models: what the surface is made of, and the lobes
/// after the first.
///
/// ```
/// use shadeline::{Material, Metal, Model, Specular, Surface, Lobe};
/// let gold = Material {
///     kd: 0.0,
///     ks: 0.6,
///     shininess: 400.0,
///     model: Model::NormalizedBlinnPhong(Specular {
///         surface: Surface::Metal(Metal::Gold),
///         more_lobes: [Lobe { weight: 0.3, shininess: 40.0 }, Lobe::NONE],
///     }),
///     ..Material::default()
/// };
/// assert!(gold.is_energy_conserving());
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Specular {
    /// Dielectric (untinted highlight, optionally with Schlick Fresnel) or metal (tinted).
    pub surface: Surface,
    /// Specular lobes 1 and 2 (lobe 0 is the material's `ks` and `shininess`). A lobe of
    /// weight 0 is absent: [`Lobe::NONE`]. In a scene file all lobes are written as
    /// `lobes = [{ weight = …, shininess = … }, …]`, lobe 0 first.
    pub more_lobes: [Lobe; MORE_LOBES],
}

/// Specular lobes a material may have besides lobe 0 (`ks`, `shininess`): three in all.
pub const MORE_LOBES: usize = 2;

/// One specular lobe: its weight and its exponent.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Lobe {
    /// Weight, `≥ 0`; 0 means the lobe is absent.
    pub weight: f32,
    /// Exponent `n > 0`.
    pub shininess: f32,
}

impl Lobe {
    /// No lobe: weight 0 (exponent 1, so it is still a valid lobe).
    pub const NONE: Lobe = Lobe {
        weight: 0.0,
        shininess: 1.0,
    };
}

impl Default for Lobe {
    /// [`Lobe::NONE`]: weight 0, exponent 1 (no lobe).
    fn default() -> Self {
        Lobe::NONE
    }
}

impl Default for Specular {
    /// A dielectric without Fresnel (`Surface::Dielectric { ior: None }`: an untinted
    /// highlight of constant weight) and no lobes besides lobe 0 (both `more_lobes` are
    /// [`Lobe::NONE`]).
    ///
    /// ```
    /// use shadeline::{Lobe, Specular, Surface};
    /// let s = Specular::default();
    /// assert_eq!(s.surface, Surface::Dielectric { ior: None });
    /// assert_eq!(s.more_lobes, [Lobe::NONE; 2]);
    /// assert_eq!(Surface::default(), s.surface);
    /// ```
    fn default() -> Self {
        Specular {
            surface: Surface::default(),
            more_lobes: [Lobe::NONE; MORE_LOBES],
        }
    }
}

/// What a normalized material's surface is: it decides the highlight's colour.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Surface {
    /// An insulator (plastic, paint, wood, glass): the highlight is never tinted by the
    /// surface colour. Without `ior` the specular weights are constant; with it, they are
    /// multiplied by Schlick's Fresnel factor `F = F₀ + (1 − F₀)(1 − L·H)⁵`,
    /// `F₀ = ((ior − 1)/(ior + 1))²`, which rises toward grazing angles, and the diffuse lobe
    /// by `1 − F` (light reflected at the surface does not enter it).
    Dielectric {
        /// Index of refraction, finite and `> 1` (`1.5` for most plastics and glass).
        ior: Option<f32>,
    },
    /// A conductor: no diffuse lobe (`kd` and `albedo` are not used), and the specular lobes
    /// are tinted per channel by Schlick's factor with the metal's coloured `F₀`.
    Metal(Metal),
}

impl Default for Surface {
    /// `Surface::Dielectric { ior: None }`: an insulator without Fresnel, whose highlight is
    /// untinted and of constant weight.
    fn default() -> Self {
        Surface::Dielectric { ior: None }
    }
}

/// The metal presets, by their reflectance at normal incidence `F₀` (linear RGB).
///
/// | metal | `F₀` (linear RGB) | source |
/// |---|---|---|
/// | gold | (1.00, 0.71, 0.29) | the commonly used value (Hoffman, *Physics and Math of Shading*, SIGGRAPH 2015 course; Unreal's and Disney's tables agree within 0.01) |
/// | copper | (0.95, 0.64, 0.54) | the same tables |
/// | bronze | (0.80, 0.55, 0.32) | no standard table lists it; a ~88 % copper, ~12 % tin alloy is less red and less reflective than copper and browner than gold: we take copper's red lowered by the tin's grey (~0.6) share and a hue between copper's and gold's. An artistic value, not a measurement |
///
/// Metals use Schlick's approximation with this coloured `F₀`: the reflection is the
/// metal's colour head-on and whitens toward grazing angles.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum Metal {
    /// Gold.
    Gold,
    /// Copper.
    Copper,
    /// Bronze.
    Bronze,
}

impl Metal {
    /// Every preset, in the order of the table above.
    pub const ALL: [Metal; 3] = [Metal::Gold, Metal::Copper, Metal::Bronze];

    /// Reflectance at normal incidence, linear RGB, each channel in `[0, 1]`.
    pub fn f0(self) -> LinearRgb {
        match self {
            Metal::Gold => LinearRgb::new(1.00, 0.71, 0.29),
            Metal::Copper => LinearRgb::new(0.95, 0.64, 0.54),
            Metal::Bronze => LinearRgb::new(0.80, 0.55, 0.32),
        }
    }

    /// The name used in scene files: `"gold"`, `"copper"`, `"bronze"`.
    pub fn name(self) -> &'static str {
        match self {
            Metal::Gold => "gold",
            Metal::Copper => "copper",
            Metal::Bronze => "bronze",
        }
    }

    /// The preset called `name` (as in [`Metal::name`]), if there is one.
    pub fn from_name(name: &str) -> Option<Metal> {
        Metal::ALL.into_iter().find(|m| m.name() == name)
    }
}

/// How a sphere's surface reflects light.
///
/// `Material` is `Copy` and fixed-size whatever the model: up to three specular lobes (lobe
/// 0 here, lobes 1 and 2 in [`Specular::more_lobes`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Material {
    /// Diffuse colour, linear RGB, each component `≥ 0`.
    pub albedo: LinearRgb,
    /// Weight of the diffuse term, `≥ 0`.
    pub kd: f32,
    /// Weight of the (first) specular lobe, `≥ 0`. A dielectric's highlight is never tinted
    /// by `albedo`.
    pub ks: f32,
    /// Specular exponent `n > 0` of the first lobe: larger is a smaller, tighter highlight.
    pub shininess: f32,
    /// The reflection model.
    pub model: Model,
}

/// A sphere: centre and radius in scene units, and its material.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sphere {
    /// The centre.
    pub center: Vec3,
    /// The radius, in `[MIN_RADIUS, MAX_COORDINATE]`.
    pub radius: f32,
    /// The surface.
    pub material: Material,
}

/// A light source. Colour and intensity multiply; colour is linear RGB.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Light {
    /// Light arriving from infinitely far away along one direction, undimmed.
    Distant {
        /// The direction the light *travels* (from the light toward the scene); any length.
        direction: Vec3,
        /// Linear RGB colour.
        color: LinearRgb,
        /// What arrives at every point, at any distance: `color·intensity` is the `I` of the
        /// model.
        intensity: f32,
    },
    /// Light from a point, falling off with distance: arriving `color·intensity / (4π r²)`.
    ///
    /// `intensity` is a power, spread over the sphere of radius `r` around the light. To
    /// light a surface at distance `d` as brightly as a [`Light::Distant`] of intensity `E`
    /// does, choose
    ///
    /// ```text
    /// intensity = 4π · d² · E
    /// ```
    ///
    /// For example, `E = 5` (the exponent series' distant light) at `d = 10` scene units
    /// takes `4π · 100 · 5 ≈ 6283`. The same light is 4 times brighter at half that distance
    /// and 4 times dimmer at twice it. [`MAX_INTENSITY`] bounds it.
    ///
    /// ```
    /// use shadeline::{Light, LinearRgb, Vec3};
    /// let (e, d) = (5.0_f32, 10.0_f32);
    /// let intensity = 4.0 * core::f32::consts::PI * d * d * e;
    /// assert!((intensity - 6283.2).abs() < 0.1);
    /// // What arrives at distance d is e again:
    /// assert!((intensity / (4.0 * core::f32::consts::PI * d * d) - e).abs() < 1e-4);
    /// let lamp = Light::Point {
    ///     position: Vec3::new(0.0, d, 0.0), // d above a sphere at the origin
    ///     color: LinearRgb::new(1.0, 1.0, 1.0),
    ///     intensity,
    ///     radius: 0.0,
    /// };
    /// # let _ = lamp;
    /// ```
    Point {
        /// Where the light is.
        position: Vec3,
        /// Linear RGB colour.
        color: LinearRgb,
        /// Power: what arrives at distance `r` is `intensity / (4π r²)`, so for a wanted
        /// brightness `E` at distance `d`, `intensity = 4π·d²·E` (see [`Light::Point`]).
        intensity: f32,
        /// The radius of the light's sphere: 0 is a point. A sphere light emits the same
        /// power evenly from its surface (radiance `colour·intensity/(4π²·radius²)`), so
        /// wherever it is wholly above a surface's horizon and unblocked, the surface gets
        /// what the point at its centre would give; its highlights are wider and its shadows
        /// soft. In `[0, MAX_COORDINATE]`, and the sphere may not overlap a scene sphere.
        /// Above 0 only with the crate feature `area-lights` (on by default): without it
        /// [`Scene::add_light`] refuses it ([`Problem::SphereLightNotBuilt`]).
        radius: f32,
    },
}

/// Which item of a scene an error is about.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Item {
    /// The camera.
    Camera,
    /// The background colour.
    Background,
    /// The sphere with this index (in the order they were added, from 0).
    Sphere(usize),
    /// The light with this index (in the order they were added, from 0).
    Light(usize),
}

/// What kind of item a capacity is about.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ItemKind {
    /// Spheres.
    Sphere,
    /// Lights.
    Light,
}

/// What is wrong with a field.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum Problem {
    /// NaN or infinite.
    NotFinite,
    /// Must be greater than zero.
    NotPositive,
    /// Must not be negative.
    Negative,
    /// Larger than the accepted range (see the module docs).
    TooLarge,
    /// Positive, but smaller than the accepted range (see the module docs).
    TooSmall,
    /// Must be greater than 1 (an index of refraction).
    NotAboveOne,
    /// A direction of zero length.
    ZeroLength,
    /// The camera looks at its own position.
    LookAtEqualsPosition,
    /// The camera's up vector is parallel to its view direction.
    UpParallelToView,
    /// The field of view is not inside `(0°, 180°)`.
    FieldOfViewOutOfRange,
    /// A sphere light overlaps a scene sphere (reported on the light's `radius`, whichever
    /// of the two was added last): every shaded point must see the light from outside.
    LightOverlapsSphere,
    /// The material's model is one this build of the crate leaves out: Oren–Nayar and GGX
    /// need the feature `models`, the Blinn-Phong models `blinn-phong` (both on by default;
    /// the firmware builds turn them off). Reported on the sphere's `model`. Never returned
    /// with both features on.
    ModelNotBuilt,
    /// A point light has a radius (a sphere light), and this build of the crate leaves
    /// sphere lights out (feature `area-lights`, on by default; the firmware builds turn it
    /// off). Reported on the light's `radius`. Never returned with the feature on.
    SphereLightNotBuilt,
}

/// Why a scene was refused: the item, the field (named as in the scene file) and the problem.
///
/// ```
/// use shadeline::{Scene, Sphere, Material, Camera, Vec3, LinearRgb, SceneError, Item, Problem};
/// let camera = Camera { position: Vec3::new(0.0, 0.0, 5.0), look_at: Vec3::new(0.0, 0.0, 0.0),
///                       up: Vec3::new(0.0, 1.0, 0.0), vfov_degrees: 40.0 };
/// let mut scene: Scene = Scene::new(camera, LinearRgb::new(0.0, 0.0, 0.0)).unwrap();
/// let bad = Sphere { center: Vec3::new(0.0, 0.0, 0.0), radius: -1.0, material: Material::default() };
/// assert_eq!(
///     scene.add_sphere(bad),
///     Err(SceneError::Invalid { item: Item::Sphere(0), field: "radius", problem: Problem::NotPositive })
/// );
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum SceneError {
    /// A field of an item holds a value the model cannot use.
    Invalid {
        /// The item.
        item: Item,
        /// The field's name, as spelled in the scene file (`"radius"`, `"look_at"`, …).
        field: &'static str,
        /// What is wrong with it.
        problem: Problem,
    },
    /// More items than the scene's capacity.
    CapacityExceeded {
        /// What was being added.
        kind: ItemKind,
        /// The capacity (the const generic of [`Scene`]).
        capacity: usize,
    },
}

impl fmt::Display for Item {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Item::Camera => f.write_str("camera"),
            Item::Background => f.write_str("background"),
            Item::Sphere(i) => write!(f, "sphere {i}"),
            Item::Light(i) => write!(f, "light {i}"),
        }
    }
}

impl fmt::Display for Problem {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Problem::NotFinite => "must be a finite number (not NaN or infinite)",
            Problem::NotPositive => "must be greater than zero",
            Problem::Negative => "must not be negative",
            Problem::TooLarge => "is larger than the accepted range",
            Problem::TooSmall => "is smaller than the accepted range",
            Problem::NotAboveOne => "must be greater than 1",
            Problem::ZeroLength => "must not be a zero-length vector",
            Problem::LookAtEqualsPosition => "must differ from the camera position",
            Problem::UpParallelToView => "must not be parallel to the view direction",
            Problem::FieldOfViewOutOfRange => "must be between 0 and 180 degrees, exclusive",
            Problem::LightOverlapsSphere => "makes the light's sphere overlap a scene sphere",
            Problem::ModelNotBuilt => {
                "is a model this build of shadeline leaves out (feature `models` for oren-nayar and \
                 ggx, `blinn-phong` for the blinn-phong models)"
            }
            Problem::SphereLightNotBuilt => {
                "makes a sphere light, which this build of shadeline leaves out (feature \
                 `area-lights`)"
            }
        })
    }
}

impl fmt::Display for SceneError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SceneError::Invalid {
                item,
                field,
                problem,
            } => {
                write!(f, "{item}: `{field}` {problem}")?;
                if *problem == Problem::TooLarge && *field == "roughness" {
                    write!(f, " (at most π/2 for oren-nayar, 1 for ggx)")?;
                } else if *problem == Problem::TooLarge {
                    write!(f, " (at most {:e})", limit_of(field))?;
                }
                if *problem == Problem::TooSmall {
                    let least = if *field == "roughness" {
                        MIN_GGX_ROUGHNESS
                    } else {
                        MIN_RADIUS
                    };
                    write!(f, " (at least {least:e})")?;
                }
                Ok(())
            }
            SceneError::CapacityExceeded { kind, capacity } => {
                let what = match kind {
                    ItemKind::Sphere => "spheres",
                    ItemKind::Light => "lights",
                };
                write!(f, "too many {what}: this scene holds at most {capacity}")
            }
        }
    }
}

impl core::error::Error for SceneError {}

fn limit_of(field: &str) -> f32 {
    match field {
        "intensity" => MAX_INTENSITY,
        "shininess" | "lobes[1].shininess" | "lobes[2].shininess" => MAX_SHININESS,
        "albedo" | "color" | "kd" | "ks" | "background" | "ior" => MAX_VALUE,
        "lobes[1].weight" | "lobes[2].weight" => MAX_VALUE,
        _ => MAX_COORDINATE,
    }
}

/// Field-level checks, each returning the first problem found.
///
/// The comparisons are on the numbers' IEEE 754 bits: a finite `f32` has an exponent field
/// below all ones, and finite non-negative values order as their bits do, so each test is
/// one integer comparison. The results are those of the float comparisons (`-0.0` counts
/// as zero); on a core without an FPU each would otherwise be a call into the soft-float
/// routines.
struct Check {
    item: Item,
}

/// `|x|`'s bits: the sign cleared.
fn magnitude(x: f32) -> u32 {
    x.to_bits() & !(1 << 31)
}

/// Whether `x` is finite: its exponent field is not all ones.
fn finite_bits(x: f32) -> bool {
    magnitude(x) < f32::INFINITY.to_bits()
}

/// Whether `x < 0.0`: the sign set and the magnitude not zero (`-0.0` is zero).
fn below_zero(x: f32) -> bool {
    x.to_bits() > 1 << 31
}

/// Whether `x ≤ 0.0` for a finite `x`: zero of either sign, or the sign set.
fn not_positive(x: f32) -> bool {
    x.to_bits() as i32 <= 0
}

/// Whether the finite `x` is above the finite, non-negative `max`.
fn above(x: f32, max: f32) -> bool {
    !below_zero(x) && magnitude(x) > max.to_bits()
}

impl Check {
    fn err(&self, field: &'static str, problem: Problem) -> SceneError {
        SceneError::Invalid {
            item: self.item,
            field,
            problem,
        }
    }
    fn finite(&self, field: &'static str, v: &[f32]) -> Result<(), SceneError> {
        if v.iter().all(|&x| finite_bits(x)) {
            Ok(())
        } else {
            Err(self.err(field, Problem::NotFinite))
        }
    }
    /// Finite, `0 ≤ v ≤ max` for every component.
    fn non_negative(&self, field: &'static str, v: &[f32], max: f32) -> Result<(), SceneError> {
        self.finite(field, v)?;
        if v.iter().any(|&x| below_zero(x)) {
            return Err(self.err(field, Problem::Negative));
        }
        if v.iter().any(|&x| above(x, max)) {
            return Err(self.err(field, Problem::TooLarge));
        }
        Ok(())
    }
    /// Finite, `0 < v ≤ max`.
    fn positive(&self, field: &'static str, v: f32, max: f32) -> Result<(), SceneError> {
        self.finite(field, &[v])?;
        if not_positive(v) {
            return Err(self.err(field, Problem::NotPositive));
        }
        if above(v, max) {
            return Err(self.err(field, Problem::TooLarge));
        }
        Ok(())
    }
    fn point(&self, field: &'static str, p: Vec3) -> Result<(), SceneError> {
        self.finite(field, &[p.x, p.y, p.z])?;
        if [p.x, p.y, p.z]
            .iter()
            .any(|&x| magnitude(x) > MAX_COORDINATE.to_bits())
        {
            return Err(self.err(field, Problem::TooLarge));
        }
        Ok(())
    }
    fn direction(&self, field: &'static str, d: Vec3) -> Result<Vec3, SceneError> {
        self.finite(field, &[d.x, d.y, d.z])?;
        d.normalized()
            .ok_or_else(|| self.err(field, Problem::ZeroLength))
    }
    fn color(&self, field: &'static str, c: LinearRgb) -> Result<(), SceneError> {
        self.non_negative(field, &[c.r, c.g, c.b], MAX_VALUE)
    }
}

impl Camera {
    /// `tan(vfov/2)` for the checked field of view `0° < vfov < 180°`, within
    /// 2.8 ulp of the exact tangent of the `f32` input (`tests::tangent_within_its_bound`).
    ///
    /// Why not `libm::tanf(vfov·π/360)`: its general argument reduction (`rem_pio2`, for any
    /// `f32`) is about 3.9 KB of an M0 firmware's flash, and rounding the argument to radians
    /// first costs up to 2,846 ulp as `vfov` nears 180°, where the tangent's slope is steep.
    /// Here the half angle stays in degrees until it is folded into `0..=45°` (`90° − a`, exact
    /// for `a ≥ 45°`), and one polynomial in `x²` (a least-squares minimax fit of
    /// `(tan x − x)/x³` on `[0, π/4]`, 1.8·10⁻⁸ relative) does the rest; `tan a = 1/tan(90° − a)`
    /// above 45°.
    pub(crate) fn tan_half_fov(&self) -> f32 {
        const P: [f32; 6] = [
            0.333_331_56,
            0.133_388,
            0.053_411_21,
            0.024_430_39,
            0.003_119_519,
            0.009_385_638,
        ];
        let half = self.vfov_degrees * 0.5;
        let folded = half > 45.0;
        let a = if folded { 90.0 - half } else { half };
        let x = a * (core::f32::consts::PI / 180.0);
        let s = x * x;
        let mut p = P[5];
        for c in [P[4], P[3], P[2], P[1], P[0]] {
            p = p * s + c;
        }
        let t = x + x * (s * p);
        if folded {
            1.0 / t
        } else {
            t
        }
    }

    /// Checks the camera and returns its orthonormal basis `(right, up, forward)`.
    pub(crate) fn basis(&self) -> Result<(Vec3, Vec3, Vec3), SceneError> {
        let c = Check { item: Item::Camera };
        c.point("position", self.position)?;
        c.point("look_at", self.look_at)?;
        let up = c.direction("up", self.up)?;
        c.finite("vfov", &[self.vfov_degrees])?;
        if !(self.vfov_degrees > 0.0 && self.vfov_degrees < 180.0) {
            return Err(c.err("vfov", Problem::FieldOfViewOutOfRange));
        }
        let forward = (self.look_at - self.position)
            .normalized()
            .ok_or_else(|| c.err("look_at", Problem::LookAtEqualsPosition))?;
        let side = forward.cross(up);
        if libm::sqrtf(side.dot(side)) < MIN_UP_SINE {
            return Err(c.err("up", Problem::UpParallelToView));
        }
        // `side` is at least MIN_UP_SINE long, so it normalizes.
        let right = side
            .normalized()
            .ok_or_else(|| c.err("up", Problem::UpParallelToView))?;
        let true_up = right.cross(forward);
        Ok((right, true_up, forward))
    }
}

/// The field names of lobes 1 and 2, as a scene file spells them.
const LOBE_FIELDS: [(&str, &str); MORE_LOBES] = [
    ("lobes[1].weight", "lobes[1].shininess"),
    ("lobes[2].weight", "lobes[2].shininess"),
];

impl Material {
    fn check(&self, item: Item) -> Result<(), SceneError> {
        let c = Check { item };
        c.color("albedo", self.albedo)?;
        c.non_negative("kd", &[self.kd], MAX_VALUE)?;
        c.non_negative("ks", &[self.ks], MAX_VALUE)?;
        c.positive("shininess", self.shininess, MAX_SHININESS)?;
        // A model the build leaves out, refused before its own numbers are read.
        let left_out = (!cfg!(feature = "blinn-phong")
            && matches!(
                self.model,
                Model::BlinnPhong | Model::NormalizedBlinnPhong(_)
            ))
            || (!cfg!(feature = "models")
                && matches!(self.model, Model::OrenNayar { .. } | Model::Ggx(_)));
        if left_out {
            return Err(c.err("model", Problem::ModelNotBuilt));
        }
        if let Some(spec) = self.model.specular() {
            for (lobe, (weight, shininess)) in spec.more_lobes.iter().zip(LOBE_FIELDS) {
                c.non_negative(weight, &[lobe.weight], MAX_VALUE)?;
                c.positive(shininess, lobe.shininess, MAX_SHININESS)?;
            }
        }
        match self.model {
            #[cfg(feature = "models")]
            Model::OrenNayar { roughness } => {
                c.non_negative("roughness", &[roughness], MAX_OREN_NAYAR_ROUGHNESS)?;
            }
            #[cfg(feature = "models")]
            Model::Ggx(m) => {
                c.finite("roughness", &[m.roughness])?;
                if m.roughness < MIN_GGX_ROUGHNESS {
                    return Err(c.err("roughness", Problem::TooSmall));
                }
                if m.roughness > 1.0 {
                    return Err(c.err("roughness", Problem::TooLarge));
                }
            }
            _ => {}
        }
        if let Some(Surface::Dielectric { ior: Some(ior) }) = self.model.surface() {
            c.finite("ior", &[ior])?;
            if ior <= 1.0 {
                return Err(c.err("ior", Problem::NotAboveOne));
            }
            if ior > MAX_VALUE {
                return Err(c.err("ior", Problem::TooLarge));
            }
        }
        Ok(())
    }

    /// Whether this material cannot reflect more light than it receives, by construction:
    /// a normalized model (or Lambert, or GGX) whose diffuse weight times its brightest albedo
    /// channel plus the sum of its specular weights is at most 1 (for a metal, which has no
    /// diffuse lobe, the specular weights alone). For Oren–Nayar, the diffuse weight times
    /// the brightest albedo channel times the model's largest directional albedo `A + B/2`
    /// (reached at grazing light; it exceeds 1 by up to 1.5 % near `σ = 0.2`, see
    /// [`crate::brdf`]) is at most 1. The classic models never are: they are
    /// not normalized (see `tests/brdf_laws.rs` for by how much they can exceed 1).
    ///
    /// Materials that are not energy conserving are still accepted: this is a flag, not a
    /// validation rule.
    ///
    /// ```
    /// use shadeline::{Material, Model, Specular};
    /// let m = Material { kd: 0.7, ks: 0.3, model: Model::NormalizedPhong(Specular::default()),
    ///                    ..Material::default() };
    /// assert!(m.is_energy_conserving());
    /// assert!(!Material { ks: 0.9, ..m }.is_energy_conserving());
    /// assert!(!Material::default().is_energy_conserving()); // classic Phong
    /// ```
    pub fn is_energy_conserving(&self) -> bool {
        let a = self.albedo;
        let diffuse = self.kd * a.r.max(a.g).max(a.b);
        match self.model {
            Model::Phong | Model::BlinnPhong => false,
            Model::Lambert => diffuse <= 1.0,
            Model::NormalizedPhong(spec) | Model::NormalizedBlinnPhong(spec) => {
                let specular = self.ks + spec.more_lobes.iter().map(|l| l.weight).sum::<f32>();
                match spec.surface {
                    Surface::Metal(_) => specular <= 1.0,
                    Surface::Dielectric { .. } => diffuse + specular <= 1.0,
                }
            }
            Model::OrenNayar { roughness } => {
                // Oren–Nayar's `A` and `B` (the kernels' `brdf::oren_nayar_ab`, which this
                // module, below `brdf`, does not call).
                let s2 = roughness * roughness;
                let a = 1.0 - 0.5 * s2 / (s2 + 0.33);
                let b = 0.45 * s2 / (s2 + 0.09);
                diffuse * (a + b / 2.0) <= 1.0
            }
            Model::Ggx(m) => match m.surface {
                Surface::Metal(_) => self.ks <= 1.0,
                Surface::Dielectric { .. } => diffuse + self.ks <= 1.0,
            },
        }
    }
}

impl Default for Material {
    /// A mid-grey plastic: albedo 0.18, `kd` 0.8, `ks` 0.2, `n` 50, classic Phong.
    fn default() -> Self {
        Material {
            albedo: LinearRgb::new(0.18, 0.18, 0.18),
            kd: 0.8,
            ks: 0.2,
            shininess: 50.0,
            model: Model::Phong,
        }
    }
}

impl Sphere {
    fn check(&self, item: Item) -> Result<(), SceneError> {
        let c = Check { item };
        c.point("center", self.center)?;
        c.positive("radius", self.radius, MAX_COORDINATE)?;
        if self.radius < MIN_RADIUS {
            return Err(c.err("radius", Problem::TooSmall));
        }
        self.material.check(item)
    }
}

impl Light {
    fn check(&self, item: Item) -> Result<(), SceneError> {
        let c = Check { item };
        let (color, intensity) = match *self {
            Light::Distant {
                direction,
                color,
                intensity,
            } => {
                c.direction("direction", direction)?;
                (color, intensity)
            }
            Light::Point {
                position,
                color,
                intensity,
                radius,
            } => {
                c.point("position", position)?;
                c.non_negative("radius", &[radius], MAX_COORDINATE)?;
                // Without the feature no kernel holds sphere lights: refused here, so that a
                // scene never holds one (and needs no overlap test for one).
                if !cfg!(feature = "area-lights") && radius > 0.0 {
                    return Err(c.err("radius", Problem::SphereLightNotBuilt));
                }
                (color, intensity)
            }
        };
        c.color("color", color)?;
        c.non_negative("intensity", &[intensity], MAX_INTENSITY)
    }
}

/// Whether light `index` (a sphere light) lies clear of `sphere`: the two spheres do not
/// overlap (touching is allowed). Only with `area-lights`: without it a scene holds no
/// sphere light.
#[cfg(feature = "area-lights")]
#[inline(never)]
fn light_clear_of(index: usize, light: &Light, sphere: &Sphere) -> Result<(), SceneError> {
    let Light::Point {
        position, radius, ..
    } = *light
    else {
        return Ok(());
    };
    if radius <= 0.0 {
        return Ok(());
    }
    // In `f32`: the squares stay below 1e13 (the coordinate range), and a tie within rounding
    // may go either way.
    let d = position - sphere.center;
    let reach = radius + sphere.radius;
    if d.dot(d) < reach * reach {
        return Err(SceneError::Invalid {
            item: Item::Light(index),
            field: "radius",
            problem: Problem::LightOverlapsSphere,
        });
    }
    Ok(())
}

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

#[cfg(test)]
mod tests {
    extern crate std;
    use super::{
        above, below_zero, finite_bits, not_positive, Camera, MAX_COORDINATE, MAX_SHININESS,
    };
    use crate::vec3::Vec3;

    /// The checks' bit tests against the float comparisons they stand for, on the edge cases
    /// (zeros, subnormals, the limits and their neighbours, infinities, NaNs of either sign)
    /// and on 2²⁰ bit patterns spread over every exponent.
    #[test]
    fn bit_tests_are_the_float_comparisons() {
        let limits = [
            0.0,
            f32::MIN_POSITIVE,
            1.0,
            MAX_COORDINATE,
            MAX_SHININESS,
            f32::MAX,
        ];
        let mut values = std::vec![
            0.0,
            -0.0,
            f32::from_bits(1),
            -f32::from_bits(1),
            f32::INFINITY,
            f32::NEG_INFINITY,
            f32::NAN,
            -f32::NAN,
            f32::MAX,
            f32::MIN,
        ];
        for m in limits {
            for v in [m, -m] {
                values.extend([v, f32::from_bits(v.to_bits() + 1)]);
                if v.to_bits() & !(1 << 31) != 0 {
                    values.push(f32::from_bits(v.to_bits() - 1));
                }
            }
        }
        values.extend((0..1u32 << 20).map(|k| f32::from_bits(k.wrapping_mul(0x9e37_79b9))));
        for x in values {
            assert_eq!(
                finite_bits(x),
                x.is_finite(),
                "finite {x:e} ({:#x})",
                x.to_bits()
            );
            if !x.is_finite() {
                continue;
            }
            assert_eq!(
                below_zero(x),
                x < 0.0,
                "below zero {x:e} ({:#x})",
                x.to_bits()
            );
            assert_eq!(
                not_positive(x),
                x <= 0.0,
                "not positive {x:e} ({:#x})",
                x.to_bits()
            );
            for max in limits {
                assert_eq!(above(x, max), x > max, "{x:e} above {max:e}");
            }
        }
    }

    /// The distance from `got` to `exact` in units of the `f32` spacing at `exact`.
    fn ulps(got: f32, exact: f64) -> f64 {
        let e = exact as f32;
        let spacing = f32::from_bits(e.to_bits() + 1) - e;
        (got as f64 - exact).abs() / spacing as f64
    }

    #[test]
    fn tangent_within_its_bound() {
        let mut worst = (0.0f64, 0.0f32);
        // Every 2⁻¹⁰ of a degree, and the ends of the range.
        let grid = (1..180 * 1024).map(|k| k as f32 / 1024.0);
        let ends = [
            1.0e-3,
            f32::MIN_POSITIVE,
            90.0,
            179.999,
            f32::from_bits(180.0f32.to_bits() - 1),
        ];
        for vfov in grid.chain(ends) {
            let exact = libm::tan(vfov as f64 * 0.5 * core::f64::consts::PI / 180.0);
            let camera = Camera {
                position: Vec3::new(0.0, 0.0, 0.0),
                look_at: Vec3::new(0.0, 0.0, -1.0),
                up: Vec3::new(0.0, 1.0, 0.0),
                vfov_degrees: vfov,
            };
            let e = ulps(camera.tan_half_fov(), exact);
            if e > worst.0 {
                worst = (e, vfov);
            }
        }
        assert!(worst.0 <= 2.8, "{} ulp at vfov = {}°", worst.0, worst.1);
    }
}
