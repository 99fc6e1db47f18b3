//! A [`Light`] of a scene, distant or point (a sphere light when it has a radius), its check,
//! and the test that keeps a sphere light clear of every scene sphere.
//!
//! A light is checked alone as it is added; the overlap test is apart from that check
//! because it compares a light with the spheres, whichever of the two the scene receives
//! last. Without the feature `area-lights` the check refuses a light with a radius, so a
//! scene then holds no sphere light and needs no overlap test.

use super::check::Check;
use super::error::{Item, Problem, SceneError};
use super::limits::{MAX_COORDINATE, MAX_INTENSITY};
#[cfg(feature = "area-lights")]
use super::sphere::Sphere;
use crate::pixel::LinearRgb;
use crate::vec3::Vec3;

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
        /// [`Scene::add_light`](crate::Scene::add_light) refuses it ([`Problem::SphereLightNotBuilt`]).
        radius: f32,
    },
}

impl Light {
    /// The same light moved, for animations: a distant light's `direction` through `turn`,
    /// a point light's `position` through `place`; its colour, intensity and radius kept.
    /// An orbit passes one rotation as `turn` and the same rotation about its centre as
    /// `place`. The result is checked as any light is, when it is added to a scene.
    ///
    /// ```
    /// use shadeline::{Light, LinearRgb, Vec3};
    /// let lamp = Light::Point {
    ///     position: Vec3::new(0.0, 4.0, 0.0),
    ///     color: LinearRgb::new(1.0, 1.0, 1.0),
    ///     intensity: 1000.0,
    ///     radius: 0.0,
    /// };
    /// let lifted = lamp.moved(|d| d, |p| p + Vec3::new(0.0, 1.0, 0.0));
    /// assert!(matches!(lifted, Light::Point { position, .. } if position.y == 5.0));
    /// ```
    pub fn moved(self, turn: impl FnOnce(Vec3) -> Vec3, place: impl FnOnce(Vec3) -> Vec3) -> Light {
        match self {
            Light::Distant {
                direction,
                color,
                intensity,
            } => Light::Distant {
                direction: turn(direction),
                color,
                intensity,
            },
            Light::Point {
                position,
                color,
                intensity,
                radius,
            } => Light::Point {
                position: place(position),
                color,
                intensity,
                radius,
            },
        }
    }

    pub(super) fn check(&self, item: Item) -> Result<(), SceneError> {
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
pub(super) fn light_clear_of(
    index: usize,
    light: &Light,
    sphere: &Sphere,
) -> Result<(), SceneError> {
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
