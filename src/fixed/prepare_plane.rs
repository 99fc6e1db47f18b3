//! The camera's image plane at the frame's size, the prepare's first stage: the size and
//! plane-scale checks, half a pixel's step, and the narrow kernel's corner test.
//!
//! Everything after it (the scale, the spheres' spans, the primary-ray steps) reads the
//! plane, and the corner test decides whether the narrow kernel may take the frame at all, so
//! it is computed once here, in `f32`, before any item is converted.

use super::prepare_convert::{out_of_range, MAX_PLANE_SCALE};
use crate::render::RenderError;
use crate::scene::{Item, Scene};
use crate::vec3::Vec3;
use crate::MAX_DIMENSION;

/// The camera's image plane at one size: its basis, half a pixel's step on the plane
/// `z = 1`, and whether the narrow kernel's corner test passes.
pub(super) struct Plane {
    pub(super) right: Vec3,
    pub(super) up: Vec3,
    pub(super) forward: Vec3,
    pub(super) half_pixel: f32,
    pub(super) corners: bool,
}

impl Plane {
    /// Checks the size and the camera's plane scale (and without the full-width kernel
    /// refuses a sphere light), then computes the plane.
    #[inline(always)]
    pub(super) fn of<const S: usize, const L: usize>(
        scene: &Scene<S, L>,
        width: u32,
        height: u32,
    ) -> Result<Plane, RenderError> {
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
        Ok(Plane {
            right,
            up,
            forward,
            half_pixel,
            corners,
        })
    }
}
