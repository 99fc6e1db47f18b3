//! The scene of each frame of an animation: a light orbiting the scene's vertical axis, or a
//! sphere moving in a straight line.
//!
//! - [`Motion::OrbitLight`]: light `I` turns once around the axis through the camera's
//!   `look_at` along its `up` (the scene's vertical), counter-clockwise seen from above, by
//!   `360°·k/N` at frame `k` of `N`, so that the animation loops without a seam (frame `N`
//!   would be frame 0). A distant light's direction turns; a point light's position turns
//!   (its height along the axis and its distance from it stay).
//! - [`Motion::MoveSphere`]: sphere `I` moves at constant speed from its centre in the scene
//!   (frame 0) to the given point (the last frame): at frame `k` of `N` it is `k/(N−1)` of
//!   the way. No easing.
//!
//! The rest of the scene stays. A frame whose scene the core refuses (a sphere moved out of
//! range, or into a sphere light) is an error naming the frame.

use crate::scene_file::FileScene;
use shadeline::{SceneError, Vec3};
use std::fmt;

/// What moves.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Motion {
    /// Light `I` (from 0) orbits the vertical axis through the look-at point once.
    OrbitLight(usize),
    /// Sphere `sphere` (from 0) moves from its place to `to`.
    MoveSphere {
        /// The sphere's index.
        sphere: usize,
        /// Where it ends, at the last frame.
        to: Vec3,
    },
}

/// Why an animation's scenes cannot be made.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum AnimationError {
    /// The scene has no light `index`.
    NoSuchLight {
        /// The index asked for.
        index: usize,
        /// The scene's lights.
        lights: usize,
    },
    /// The scene has no sphere `index`.
    NoSuchSphere {
        /// The index asked for.
        index: usize,
        /// The scene's spheres.
        spheres: usize,
    },
    /// The core refused frame `frame`'s scene.
    Frame {
        /// The frame, from 0.
        frame: u32,
        /// Why.
        error: SceneError,
    },
}

impl fmt::Display for AnimationError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let plural = |n: usize| if n == 1 { "" } else { "s" };
        match *self {
            AnimationError::NoSuchLight { index, lights } => write!(
                f,
                "--orbit-light {index}: the scene has {lights} light{} (counted from 0)",
                plural(lights)
            ),
            AnimationError::NoSuchSphere { index, spheres } => write!(
                f,
                "--move-sphere {index}: the scene has {spheres} sphere{} (counted from 0)",
                plural(spheres)
            ),
            AnimationError::Frame { frame, error } => write!(f, "frame {frame}: {error}"),
        }
    }
}

impl std::error::Error for AnimationError {}

/// Checks that the motion's light or sphere exists in `scene`.
pub fn check(scene: &FileScene, motion: Motion) -> Result<(), AnimationError> {
    match motion {
        Motion::OrbitLight(index) if index >= scene.lights().len() => {
            Err(AnimationError::NoSuchLight {
                index,
                lights: scene.lights().len(),
            })
        }
        Motion::MoveSphere { sphere, .. } if sphere >= scene.spheres().len() => {
            Err(AnimationError::NoSuchSphere {
                index: sphere,
                spheres: scene.spheres().len(),
            })
        }
        _ => Ok(()),
    }
}

/// The scene of frame `frame` of `frames` (frame 0 is `scene` itself).
pub fn scene_at(
    scene: &FileScene,
    motion: Motion,
    frame: u32,
    frames: u32,
) -> Result<FileScene, AnimationError> {
    check(scene, motion)?;
    let refused = |error| AnimationError::Frame { frame, error };
    let mut out = FileScene::new(*scene.camera(), scene.background()).map_err(refused)?;
    let mut spheres = scene.spheres().to_vec();
    let mut lights = scene.lights().to_vec();
    match motion {
        Motion::OrbitLight(index) => {
            let angle = std::f64::consts::TAU * f64::from(frame) / f64::from(frames.max(1));
            let camera = scene.camera();
            let axis = unit(camera.up);
            let turn = |v: Vec3| rotate(v, axis, angle);
            lights[index] = lights[index].moved(turn, |position| {
                add(turn(sub(position, camera.look_at)), camera.look_at)
            });
        }
        Motion::MoveSphere { sphere, to } => {
            let t = if frames > 1 {
                f64::from(frame) / f64::from(frames - 1)
            } else {
                0.0
            };
            let from = spheres[sphere].center;
            spheres[sphere].center = lerp(from, to, t);
        }
    }
    for sphere in spheres {
        out.add_sphere(sphere).map_err(refused)?;
    }
    for light in lights {
        out.add_light(light).map_err(refused)?;
    }
    Ok(out)
}

fn f64s(v: Vec3) -> [f64; 3] {
    [f64::from(v.x), f64::from(v.y), f64::from(v.z)]
}

fn vec3([x, y, z]: [f64; 3]) -> Vec3 {
    Vec3::new(x as f32, y as f32, z as f32)
}

fn add(a: Vec3, b: Vec3) -> Vec3 {
    let (a, b) = (f64s(a), f64s(b));
    vec3([a[0] + b[0], a[1] + b[1], a[2] + b[2]])
}

fn sub(a: Vec3, b: Vec3) -> Vec3 {
    let (a, b) = (f64s(a), f64s(b));
    vec3([a[0] - b[0], a[1] - b[1], a[2] - b[2]])
}

fn lerp(a: Vec3, b: Vec3, t: f64) -> Vec3 {
    let (a, b) = (f64s(a), f64s(b));
    vec3([0, 1, 2].map(|i| a[i] + (b[i] - a[i]) * t))
}

/// `v` normalized, in `f64` (the camera's `up` is checked non-zero by the core).
fn unit(v: Vec3) -> [f64; 3] {
    let v = f64s(v);
    let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    v.map(|c| c / n)
}

/// `v` turned by `angle` radians about the unit `axis` (Rodrigues' formula), right-handed:
/// counter-clockwise seen from where `axis` points.
fn rotate(v: Vec3, k: [f64; 3], angle: f64) -> Vec3 {
    let v = f64s(v);
    let (s, c) = angle.sin_cos();
    let cross = [
        k[1] * v[2] - k[2] * v[1],
        k[2] * v[0] - k[0] * v[2],
        k[0] * v[1] - k[1] * v[0],
    ];
    let dot = k[0] * v[0] + k[1] * v[1] + k[2] * v[2];
    vec3([0, 1, 2].map(|i| v[i] * c + cross[i] * s + k[i] * dot * (1.0 - c)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene_file::preset;
    use shadeline::Light;

    fn close(a: Vec3, b: [f32; 3]) -> bool {
        (a.x - b[0]).abs() < 1e-4 && (a.y - b[1]).abs() < 1e-4 && (a.z - b[2]).abs() < 1e-4
    }

    #[test]
    fn a_quarter_turn_about_y_takes_x_to_minus_z() {
        let v = rotate(
            Vec3::new(1.0, 2.0, 0.0),
            [0.0, 1.0, 0.0],
            std::f64::consts::FRAC_PI_2,
        );
        assert!(close(v, [0.0, 2.0, -1.0]), "{v:?}");
    }

    #[test]
    fn an_orbit_turns_the_light_about_the_look_at_point_and_closes_the_loop() {
        let scene = preset("lamp").unwrap().unwrap().scene;
        let index = (scene.lights().iter())
            .position(|l| matches!(l, Light::Point { .. }))
            .expect("the lamp scene has a point light");
        let Light::Point { position: p0, .. } = scene.lights()[index] else {
            unreachable!()
        };
        let camera = *scene.camera();
        let up = unit(camera.up);
        let along = |p: Vec3| {
            let d = f64s(sub(p, camera.look_at));
            let h = d[0] * up[0] + d[1] * up[1] + d[2] * up[2];
            let r2 = d.iter().map(|c| c * c).sum::<f64>() - h * h;
            (h, r2.sqrt())
        };
        let (h0, r0) = along(p0);
        let frames = 8;
        let mut moved = false;
        for k in 0..=frames {
            let s = scene_at(&scene, Motion::OrbitLight(index), k, frames).unwrap();
            let Light::Point { position, .. } = s.lights()[index] else {
                panic!("still a point light")
            };
            // Height along the axis and distance from it stay.
            let (h, r) = along(position);
            assert!((h - h0).abs() < 1e-3 && (r - r0).abs() < 1e-3, "frame {k}");
            moved |= !close(position, [p0.x, p0.y, p0.z]);
            if k == 0 || k == frames {
                assert!(
                    close(position, [p0.x, p0.y, p0.z]),
                    "frame {k}: {position:?}"
                );
            }
            // Nothing else changed.
            assert_eq!(s.spheres(), scene.spheres());
        }
        assert!(moved);
    }

    #[test]
    fn a_distant_lights_direction_turns() {
        let scene = preset("floor").unwrap().unwrap().scene;
        let s = scene_at(&scene, Motion::OrbitLight(0), 1, 2).unwrap();
        let (Light::Distant { direction: a, .. }, Light::Distant { direction: b, .. }) =
            (scene.lights()[0], s.lights()[0])
        else {
            panic!("the floor scene's light 0 is distant")
        };
        // Half a turn about the vertical: the horizontal part flips, the vertical stays.
        let up = unit(scene.camera().up);
        let (a, b) = (f64s(a), f64s(b));
        let dot = |v: [f64; 3]| v[0] * up[0] + v[1] * up[1] + v[2] * up[2];
        assert!((dot(a) - dot(b)).abs() < 1e-5);
        for i in 0..3 {
            let (ha, hb) = (a[i] - dot(a) * up[i], b[i] - dot(b) * up[i]);
            assert!((ha + hb).abs() < 1e-5, "{a:?} {b:?}");
        }
    }

    #[test]
    fn a_sphere_moves_linearly_from_its_place_to_the_target() {
        let scene = preset("floor").unwrap().unwrap().scene;
        let last = scene.spheres().len() - 1;
        let from = scene.spheres()[last].center;
        let to = Vec3::new(from.x + 3.0, from.y, from.z - 1.5);
        let motion = Motion::MoveSphere { sphere: last, to };
        let at = |k| scene_at(&scene, motion, k, 4).unwrap().spheres()[last].center;
        assert!(close(at(0), [from.x, from.y, from.z]));
        assert!(close(at(1), [from.x + 1.0, from.y, from.z - 0.5]));
        assert!(close(at(3), [to.x, to.y, to.z]));
    }

    #[test]
    fn a_missing_item_or_a_refused_frame_is_named() {
        let scene = preset("floor").unwrap().unwrap().scene;
        let lights = scene.lights().len();
        assert_eq!(
            scene_at(&scene, Motion::OrbitLight(lights), 0, 3).unwrap_err(),
            AnimationError::NoSuchLight {
                index: lights,
                lights
            }
        );
        let far = Vec3::new(1e9, 0.0, 0.0);
        let e = scene_at(&scene, Motion::MoveSphere { sphere: 0, to: far }, 2, 3).unwrap_err();
        assert!(matches!(e, AnimationError::Frame { frame: 2, .. }), "{e}");
        assert!(e.to_string().starts_with("frame 2: "), "{e}");
    }
}
