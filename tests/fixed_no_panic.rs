//! The fixed path never panics: not in release, and not in this test build either, which
//! keeps debug assertions and overflow checks on (`[profile.test]` only raises the
//! optimization level), so a `fixed` multiplication that overflowed, an integer overflow, a
//! division by zero, a square root of a negative or an out-of-bounds index would abort it.
//!
//! 200 random valid scenes from the shared generator, then 200 from a generator that goes to
//! the model's limits: coordinates up to 10⁶, radii over eight decades, intensities up to
//! 10¹², shininess from 10⁻³ to 10⁶, wide fields of view, cameras inside spheres, point
//! lights on surfaces and at sphere centres. Those may be refused with `OutOfFixedRange`;
//! any other outcome than a frame or that error fails.

mod common;
use common::*;
use proptest::prelude::*;
use proptest::strategy::ValueTree;
use proptest::test_runner::{Config, RngSeed, TestRunner};
use shadeline::*;

fn render_all_formats<const S: usize, const L: usize>(
    scene: &Scene<S, L>,
    w: u32,
    h: u32,
) -> Result<(), RenderError> {
    let f = PreparedFixed::<S, L>::new(scene, w, h)?;
    let _: Vec<Rgb565> = frame(&f);
    let _: Vec<HitRecord> = frame(&f);
    let _: Vec<Rgb888> = frame(&f.clone().with_spans(false));
    Ok(())
}

#[test]
fn two_hundred_random_valid_scenes_render_without_panic() {
    for (i, scene) in random_scenes(200, 0x0a11_0c47).iter().enumerate() {
        let (w, h) = (41 + (i as u32 % 23), 29 + (i as u32 % 7));
        render_all_formats(scene, w, h).unwrap_or_else(|e| panic!("scene {i} refused: {e}"));
    }
}

fn log_uniform(lo: f32, hi: f32) -> impl Strategy<Value = f32> {
    (lo.log10()..hi.log10()).prop_map(|e| 10f32.powf(e))
}

fn signed(mag: impl Strategy<Value = f32>) -> impl Strategy<Value = f32> {
    (mag, any::<bool>()).prop_map(|(m, neg)| if neg { -m } else { m })
}

fn point(scale: f32) -> impl Strategy<Value = Vec3> {
    (
        signed(log_uniform(1e-3, scale)),
        signed(log_uniform(1e-3, scale)),
        signed(log_uniform(1e-3, scale)),
    )
        .prop_map(|(x, y, z)| Vec3::new(x, y, z))
}

type Extreme = Scene<6, 3>;

/// Scenes at the edges of what the scene model accepts.
fn extreme_scene() -> impl Strategy<Value = Option<Extreme>> {
    (
        log_uniform(1e-2, 1e5), // scene scale
        point(1.0),
        1.0f32..179.0,
        prop::collection::vec(
            (
                point(1.0),
                log_uniform(1e-4, 2.0),
                log_uniform(1e-3, 1e6),
                any::<bool>(),
                0u8..3,
            ),
            1..=6,
        ),
        prop::collection::vec(
            (point(1.0), log_uniform(1e-3, 1e12), any::<bool>(), 0u8..4),
            1..=3,
        ),
    )
        .prop_map(|(scale, cam, vfov, spheres, lights)| {
            let camera = Camera {
                position: cam.scale(scale * 3.0),
                look_at: Vec3::new(0.0, 0.0, 0.0),
                up: Vec3::new(0.3, 1.0, 0.1),
                vfov_degrees: vfov,
            };
            let mut scene = Extreme::new(camera, LinearRgb::new(0.2, 0.3, 2.0)).ok()?;
            let mut centers = Vec::new();
            for (k, (c, r, n, blinn, place)) in spheres.into_iter().enumerate() {
                // Some spheres around the camera, some huge, most ordinary.
                let center = if place == 0 && k > 0 {
                    camera.position
                } else {
                    c.scale(scale)
                };
                let radius = (r * scale).min(1e6);
                let material = Material {
                    albedo: LinearRgb::new(1.0, 0.5, 0.0),
                    kd: 0.9,
                    ks: 1.0,
                    shininess: n,
                    model: if blinn {
                        Model::BlinnPhong
                    } else {
                        Model::Phong
                    },
                };
                scene
                    .add_sphere(Sphere {
                        center,
                        radius,
                        material,
                    })
                    .ok()?;
                centers.push((center, radius));
            }
            for (p, intensity, distant, place) in lights {
                let light = if distant {
                    Light::Distant {
                        direction: p,
                        color: LinearRgb::new(1.0, 1.0, 1.0),
                        intensity: intensity.min(3e4),
                    }
                } else {
                    // On a sphere's surface, at its centre, or anywhere.
                    let (c, r) = centers[place as usize % centers.len()];
                    let position = match place {
                        0 => c + Vec3::new(r, 0.0, 0.0),
                        1 => c,
                        _ => p.scale(scale),
                    };
                    Light::Point {
                        position,
                        color: LinearRgb::new(1.0, 0.8, 0.6),
                        intensity,
                    }
                };
                scene.add_light(light).ok()?;
            }
            Some(scene)
        })
}

#[test]
fn two_hundred_extreme_scenes_render_or_are_refused_without_panic() {
    let mut runner = TestRunner::new(Config {
        rng_seed: RngSeed::Fixed(0xed6e_5ca1),
        failure_persistence: None,
        ..Config::default()
    });
    let strategy = extreme_scene();
    let (mut rendered, mut refused, mut invalid) = (0, 0, 0);
    while rendered + refused < 200 {
        let Some(scene) = strategy.new_tree(&mut runner).unwrap().current() else {
            invalid += 1;
            continue;
        };
        match render_all_formats(&scene, 37, 23) {
            Ok(()) => rendered += 1,
            Err(RenderError::OutOfFixedRange { .. }) => refused += 1,
            Err(e) => panic!("unexpected error {e}"),
        }
    }
    println!("extreme scenes: {rendered} rendered, {refused} refused as out of fixed range, {invalid} invalid for the scene model");
    assert!(
        rendered >= 100,
        "too few extreme scenes rendered: {rendered}"
    );
}
