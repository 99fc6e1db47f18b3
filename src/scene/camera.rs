//! The pinhole [`Camera`], its check and its orthonormal basis, and `tan(vfov/2)` for the
//! primary rays.
//!
//! The camera is checked once, as the scene is made, and the check returns the basis, so the
//! paths start from a basis that exists (the camera does not look at its own position, its up
//! vector is not parallel to the view). Both paths' prepares take `tan(vfov/2)` from here: a
//! short polynomial in degrees rather than `libm::tanf`, for its flash size and its accuracy
//! near 180° (see `Camera::tan_half_fov`).

use super::check::Check;
use super::error::{Item, Problem, SceneError};
use super::limits::MIN_UP_SINE;
use crate::vec3::Vec3;

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

impl Camera {
    /// `tan(vfov/2)` for the checked field of view `0° < vfov < 180°`, within
    /// 2.8 ulp of the exact tangent of the `f32` input (`tests::tangent_within_its_bound`).
    ///
    /// Why not `libm::tanf(vfov·π/360)`: its general argument reduction (`rem_pio2`, for any
    /// `f32`) costs an M0 firmware kilobytes of flash, and rounding the argument to radians
    /// first costs thousands of ulp as `vfov` nears 180°, where the tangent's slope is steep.
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

#[cfg(test)]
mod tests {
    extern crate std;
    use super::Camera;
    use crate::vec3::Vec3;

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
