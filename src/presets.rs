//! Built-in scenes, available without a scene file (firmware has no file system).
//!
//! [`exponent_series`] is the lesson's scene, number for number the same as
//! `scenes/exponent-series.toml` (the harness tests that the two agree).

use crate::pixel::LinearRgb;
use crate::scene::{Camera, Light, Material, Model, Scene, SceneError, Sphere};
use crate::vec3::Vec3;

/// The exponent series' image size in the scene file: 1024 × 747.
pub const EXPONENT_SERIES_SIZE: (u32, u32) = (1024, 747);

/// Five grey spheres, Phong exponent `n` = 2, 10, 50, 250, 1250 with `ks` rising from 0.04 to
/// 0.2, lit by one distant light of intensity 5 over a blue background: the highlights get
/// smaller and tighter as `n` grows, but not dimmer (classic Phong is not normalized).
///
/// Returns a `Result` rather than panicking, so firmware that links it keeps no panic path;
/// with these numbers it is always `Ok`.
pub fn exponent_series() -> Result<Scene, SceneError> {
    let camera = Camera {
        position: Vec3::new(0.0, 1.0, 12.0),
        look_at: Vec3::new(0.0, 1.0, 0.0),
        up: Vec3::new(0.0, 1.0, 0.0),
        vfov_degrees: 36.87,
    };
    let background = LinearRgb::new(0.235294, 0.67451, 0.843137);
    let mut scene = Scene::new(camera, background)?;
    scene.add_light(Light::Distant {
        direction: Vec3::new(-0.4347962, -0.8416416, 0.3202994),
        color: LinearRgb::new(1.0, 1.0, 1.0),
        intensity: 5.0,
    })?;
    let series = [
        (-4.0, 0.04, 2.0),
        (-2.0, 0.08, 10.0),
        (0.0, 0.1, 50.0),
        (2.0, 0.15, 250.0),
        (4.0, 0.2, 1250.0),
    ];
    for (x, ks, n) in series {
        scene.add_sphere(Sphere {
            center: Vec3::new(x, 1.0, 0.0),
            radius: 0.9,
            material: Material {
                albedo: LinearRgb::new(0.18, 0.18, 0.18),
                kd: 0.8,
                ks,
                shininess: n,
                model: Model::Phong,
            },
        })?;
    }
    Ok(scene)
}
