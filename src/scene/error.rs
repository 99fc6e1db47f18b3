//! Why a scene refuses an item: [`SceneError`], which names the item ([`Item`]), the field
//! and the [`Problem`], and their messages.
//!
//! An error is plain `Copy` data with a `&'static str` field name, so that it needs no
//! allocation, compares with `==` in tests, and prints (through `Display`) the field as a
//! scene file spells it together with the bound it broke.

use super::limits::{limit_of, MIN_GGX_ROUGHNESS, MIN_RADIUS};
use core::fmt;

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
        /// The capacity (the const generic of [`Scene`](crate::Scene)).
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
