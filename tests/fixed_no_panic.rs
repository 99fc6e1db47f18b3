//! The fixed path never panics: not in release, and not in this test build either, which
//! keeps debug assertions and overflow checks on (`[profile.test]` only raises the
//! optimization level), so a `fixed` multiplication that overflowed, an integer overflow, a
//! division by zero, a square root of a negative or an out-of-bounds index would abort it.
//!
//! 200 random valid scenes from the shared generator (100 classic, 100 with every model:
//! Lambert, normalized Phong and Blinn-Phong, metals, `ior`, several lobes), then 200 from a
//! generator that goes to the model's limits with every model too: coordinates up to 10⁶,
//! radii over eight decades, intensities up to 10¹², shininess (of every lobe) from 10⁻³ to
//! 10⁶, lobe weights up to 10³, `ior` from just above 1 to 10⁶, wide fields of view, cameras
//! inside spheres, point lights on surfaces and at sphere centres. Those may be refused with
//! `OutOfFixedRange`; any other outcome than a frame or that error fails. Every frame is
//! rendered in every format (Rgb565, Bgr565, Rgb888, Gray8, hit records, byte rows) with one
//! of the four encodings.

use crate::common;
use common::*;
use proptest::prelude::*;
use proptest::strategy::ValueTree;
use proptest::test_runner::{Config, RngSeed, TestRunner};
use shadeline::*;

const ENCODINGS: [Encoding; 4] = [
    Encoding::LINEAR,
    Encoding::LINEAR.dithered(),
    Encoding::SRGB,
    Encoding::SRGB.dithered(),
];

/// Every row of the byte rows of `r` in format `P`.
fn byte_rows<P: BytePixel, R: Render>(r: &R) {
    let mut bytes = vec![0u8; r.width() as usize * P::BYTES];
    for y in 0..r.height() {
        r.render_line_bytes::<P>(y, &mut bytes).expect("renders");
    }
}

fn render_all_formats<const S: usize, const L: usize>(
    scene: &Scene<S, L>,
    w: u32,
    h: u32,
    encoding: Encoding,
) -> Result<(), RenderError> {
    let f = PreparedFixed::<S, L>::new(scene, w, h)?;
    let _: Vec<HitRecord> = frame(&f);
    let _: Vec<Rgb888> = frame(&f.clone().with_spans(false));
    let e = f.with_encoding(encoding);
    let _: Vec<Rgb565> = frame(&e);
    let _: Vec<Bgr565> = frame(&e);
    let _: Vec<Gray8> = frame(&e);
    let _: Vec<Rgb888> = frame(&e);
    byte_rows::<Rgb565, _>(&e);
    byte_rows::<Gray8, _>(&e);
    Ok(())
}

#[test]
fn two_hundred_random_valid_scenes_render_without_panic() {
    let classic = random_scenes(100, 0x0a11_0c47);
    let every_model = random_scenes_all_models(100, 0x0a11_0c48);
    for (i, scene) in classic.iter().chain(&every_model).enumerate() {
        let (w, h) = (41 + (i as u32 % 23), 29 + (i as u32 % 7));
        render_all_formats(scene, w, h, ENCODINGS[i % 4])
            .unwrap_or_else(|e| panic!("scene {i} refused: {e}"));
    }
}

#[test]
fn frames_one_or_two_pixels_across_render_without_panic() {
    // A frame one pixel wide leaves the horizontal pixel step unbounded by the field of view
    // (the step is tan(vfov/2)/h, and w/h may be tiny): the narrow kernel's doubled step once
    // overflowed i32 here (found by the paths_agree fuzz target).
    let series = exponent_series().unwrap();
    for vfov in [5.0, 36.87, 90.0, 150.0, 179.0] {
        let camera = Camera {
            vfov_degrees: vfov,
            ..*series.camera()
        };
        let mut scene: Scene = Scene::new(camera, series.background()).unwrap();
        for s in series.spheres() {
            scene.add_sphere(*s).unwrap();
        }
        for l in series.lights() {
            scene.add_light(*l).unwrap();
        }
        for (w, h) in [
            (1, 1),
            (1, 2),
            (2, 1),
            (1, 3),
            (1, 240),
            (2, 1000),
            (1000, 1),
        ] {
            match render_all_formats(&scene, w, h, Encoding::LINEAR) {
                Ok(()) | Err(RenderError::OutOfFixedRange { .. }) => {}
                Err(e) => panic!("vfov {vfov}, {w}x{h}: {e}"),
            }
        }
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

/// Any model, with options at the limits: lobes of exponent 10⁻³ to 10⁶ and weight up to
/// 10³, an `ior` from just above 1 to 10⁶, any metal.
fn extreme_model() -> impl Strategy<Value = Model> {
    let lobe = || {
        (log_uniform(1e-3, 1e3), log_uniform(1e-3, 1e6))
            .prop_map(|(weight, shininess)| Lobe { weight, shininess })
    };
    let surface = prop_oneof![
        Just(Surface::Dielectric { ior: None }),
        log_uniform(1e-7, 1e6).prop_map(|d| Surface::Dielectric {
            ior: Some((1.0 + d).max(1.000_000_1))
        }),
        prop::sample::select(Metal::ALL.to_vec()).prop_map(Surface::Metal),
    ];
    model_from(surface, lobe().boxed())
}

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
                extreme_model(),
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
            for (k, (c, r, n, model, place)) in spheres.into_iter().enumerate() {
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
                    model,
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
                        radius: 0.0,
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
    let mut models = [0usize; 5];
    while rendered + refused < 200 {
        let Some(scene) = strategy.new_tree(&mut runner).unwrap().current() else {
            invalid += 1;
            continue;
        };
        for s in scene.spheres() {
            models[match s.material.model {
                Model::Phong => 0,
                Model::BlinnPhong => 1,
                Model::Lambert => 2,
                Model::NormalizedPhong(_) => 3,
                _ => 4,
            }] += 1;
        }
        let encoding = ENCODINGS[(rendered + refused) % 4];
        match render_all_formats(&scene, 37, 23, encoding) {
            Ok(()) => rendered += 1,
            Err(RenderError::OutOfFixedRange { .. }) => refused += 1,
            Err(e) => panic!("unexpected error {e}"),
        }
    }
    println!("extreme scenes: {rendered} rendered, {refused} refused as out of fixed range, {invalid} invalid for the scene model");
    println!("spheres per model (Phong, Blinn-Phong, Lambert, normalized Phong, normalized Blinn-Phong): {models:?}");
    assert!(models.iter().all(|&n| n >= 50), "{models:?}");
    assert!(
        rendered >= 100,
        "too few extreme scenes rendered: {rendered}"
    );
}
