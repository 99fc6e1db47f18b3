//! A [`Sphere`] of a scene: its centre, its radius and its material, and their check.
//!
//! The radius has a lower bound as well as an upper one, so that its square and its
//! reciprocal stay normal, finite `f32`s for every path.

use super::check::Check;
use super::error::{Item, Problem, SceneError};
use super::limits::{MAX_COORDINATE, MIN_RADIUS};
use super::material::Material;
use crate::vec3::Vec3;

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

impl Sphere {
    pub(super) fn check(&self, item: Item) -> Result<(), SceneError> {
        let c = Check { item };
        c.point("center", self.center)?;
        c.positive("radius", self.radius, MAX_COORDINATE)?;
        if self.radius < MIN_RADIUS {
            return Err(c.err("radius", Problem::TooSmall));
        }
        self.material.check(item)
    }
}
