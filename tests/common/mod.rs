//! Shared test helpers: deterministic random scenes (proptest strategies run from a fixed
//! seed) and comparisons against the f64 reference.
#![allow(dead_code)]

use proptest::prelude::*;
use proptest::strategy::ValueTree;
use proptest::test_runner::{Config, RngSeed, TestRunner};
use shadeline::reference::{self, RefPixel};
use shadeline::*;

/// The random scenes' type: the default capacities, as the presets have (why the tests
/// keep to few capacities: `tests/all.rs`).
pub type TestScene = Scene;

fn vec3(range: f32) -> impl Strategy<Value = Vec3> {
    (-range..range, -range..range, -range..range).prop_map(|(x, y, z)| Vec3::new(x, y, z))
}

fn color(lo: f32, hi: f32) -> impl Strategy<Value = LinearRgb> {
    (lo..hi, lo..hi, lo..hi).prop_map(|(r, g, b)| LinearRgb::new(r, g, b))
}

fn material() -> impl Strategy<Value = Material> {
    (
        color(0.0, 1.0),
        0.0f32..1.0,
        0.0f32..1.0,
        0.0f32..3.3,
        any::<bool>(),
    )
        .prop_map(|(albedo, kd, ks, log_n, blinn)| Material {
            albedo,
            kd,
            ks,
            shininess: 10f32.powf(log_n),
            model: if blinn {
                Model::BlinnPhong
            } else {
                Model::Phong
            },
        })
}

fn sphere() -> impl Strategy<Value = Sphere> {
    (vec3(2.5), 0.3f32..1.8, material()).prop_map(|(center, radius, material)| Sphere {
        center,
        radius,
        material,
    })
}

fn light() -> impl Strategy<Value = Light> {
    prop_oneof![
        (vec3(1.0), color(0.2, 1.0), 0.5f32..4.0).prop_filter_map(
            "zero direction",
            |(direction, color, intensity)| (direction.dot(direction) > 1e-4).then_some(
                Light::Distant {
                    direction,
                    color,
                    intensity
                }
            )
        ),
        (vec3(8.0), color(0.2, 1.0), 0.5f32..3.0).prop_map(|(position, color, k)| {
            // Scale the power so that about `k` arrives at the origin.
            let d2 = position.dot(position).max(1.0);
            Light::Point {
                position,
                color,
                intensity: 4.0 * core::f32::consts::PI * d2 * k,
                radius: 0.0,
            }
        }),
    ]
}

/// A random valid scene: a camera 6–11 units from the origin looking near it, 1–6 spheres,
/// 1–3 lights (distant and point), any mix of Phong and Blinn-Phong materials.
pub fn scene_strategy() -> impl Strategy<Value = TestScene> {
    (
        (
            -1.0f32..1.0,
            -0.6f32..0.6,
            6.0f32..11.0,
            vec3(0.5),
            25.0f32..70.0,
        ),
        color(0.0, 1.0),
        prop::collection::vec(sphere(), 1..=6),
        prop::collection::vec(light(), 1..=3),
    )
        .prop_map(
            |((angle, elevation, dist, target, vfov), bg, spheres, lights)| {
                let a = angle * core::f32::consts::PI;
                let position = Vec3::new(
                    dist * a.sin() * (1.0 - elevation * elevation).sqrt(),
                    dist * elevation,
                    dist * a.cos() * (1.0 - elevation * elevation).sqrt(),
                );
                let camera = Camera {
                    position,
                    look_at: target,
                    up: Vec3::new(0.0, 1.0, 0.0),
                    vfov_degrees: vfov,
                };
                let mut scene = TestScene::new(camera, bg).expect("valid camera");
                for s in spheres {
                    scene.add_sphere(s).expect("valid sphere");
                }
                for l in lights {
                    scene.add_light(l).expect("valid light");
                }
                scene
            },
        )
}

/// `n` values of `strategy` from a fixed seed: the same on every run and every machine.
fn draw<T: Strategy>(strategy: T, n: usize, seed: u64) -> Vec<T::Value> {
    let config = Config {
        rng_seed: RngSeed::Fixed(seed),
        failure_persistence: None,
        ..Config::default()
    };
    let mut runner = TestRunner::new(config);
    (0..n)
        .map(|_| {
            strategy
                .new_tree(&mut runner)
                .expect("strategy generates")
                .current()
        })
        .collect()
}

/// `n` random scenes from a fixed seed: the same scenes on every run and every machine.
pub fn random_scenes(n: usize, seed: u64) -> Vec<TestScene> {
    draw(scene_strategy(), n, seed)
}

/// Renders a frame of any path into a pixel format.
pub fn frame<P: Pixel + Default, R: Render>(r: &R) -> Vec<P> {
    let mut out = vec![P::default(); r.width() as usize * r.height() as usize];
    r.render_frame(&mut out).expect("renders");
    out
}

/// The reference frame.
pub fn reference_frame<const S: usize, const L: usize>(
    scene: &Scene<S, L>,
    w: u32,
    h: u32,
) -> Vec<RefPixel> {
    let mut out = vec![RefPixel::default(); w as usize * h as usize];
    reference::render_frame(scene, w, h, &mut out).expect("reference renders");
    out
}

/// How a path's 8-bit frame compares to the reference.
#[derive(Debug, Default, Clone, Copy)]
pub struct Agreement {
    /// Pixels in the frame.
    pub pixels: usize,
    /// Pixels whose ray decisions (sphere hit, lights blocked) differ from the reference.
    pub decisions_differ: usize,
    /// Largest channel error in levels, over pixels whose decisions agree.
    pub max_levels: u16,
    /// Pixels (whose decisions agree) with every channel within one level.
    pub within_one: usize,
}

impl Agreement {
    /// Share of the frame whose decisions differ.
    pub fn differ_share(&self) -> f64 {
        self.decisions_differ as f64 / self.pixels as f64
    }
    /// Share of agreeing pixels within one level.
    pub fn within_one_share(&self) -> f64 {
        self.within_one as f64 / (self.pixels - self.decisions_differ).max(1) as f64
    }
}

/// Compares a path (its 8-bit colour and its hit records) with the reference.
pub fn agreement<R: Render>(r: &R, reference: &[RefPixel]) -> Agreement {
    let colors: Vec<Rgb888> = frame(r);
    let hits: Vec<HitRecord> = frame(r);
    let mut a = Agreement {
        pixels: colors.len(),
        ..Agreement::default()
    };
    for ((c, h), want) in colors.iter().zip(&hits).zip(reference) {
        if *h != want.hit {
            a.decisions_differ += 1;
            continue;
        }
        let levels = [c.r, c.g, c.b]
            .iter()
            .zip(want.color)
            .map(|(&got, w)| {
                (got as i32 - reference::quantize(w, 255.0) as i32).unsigned_abs() as u16
            })
            .max()
            .unwrap_or(0);
        a.max_levels = a.max_levels.max(levels);
        if levels <= 1 {
            a.within_one += 1;
        }
    }
    a
}

/// Three spheres, two Blinn-Phong and one Phong (a large one as the floor), lit by two
/// coloured point lights (one close enough to clip its highlight) and a dim distant light;
/// the spheres shadow the floor.
pub fn point_lights_blinn_phong() -> Result<Scene, SceneError> {
    let camera = Camera {
        position: Vec3::new(1.0, 2.5, 9.0),
        look_at: Vec3::new(0.0, 0.5, 0.0),
        up: Vec3::new(0.0, 1.0, 0.0),
        vfov_degrees: 45.0,
    };
    let mut scene = Scene::new(camera, LinearRgb::new(0.02, 0.02, 0.05))?;
    let spheres = [
        (
            Vec3::new(-1.8, 0.8, 0.0),
            1.2,
            LinearRgb::new(0.8, 0.2, 0.1),
            30.0,
            Model::BlinnPhong,
        ),
        (
            Vec3::new(1.2, 0.6, -0.5),
            1.0,
            LinearRgb::new(0.1, 0.6, 0.9),
            600.0,
            Model::BlinnPhong,
        ),
        (
            Vec3::new(0.0, -100.0, 0.0),
            99.5,
            LinearRgb::new(0.5, 0.5, 0.5),
            7.5,
            Model::Phong,
        ),
    ];
    for (center, radius, albedo, shininess, model) in spheres {
        scene.add_sphere(Sphere {
            center,
            radius,
            material: Material {
                albedo,
                kd: 0.9,
                ks: 0.6,
                shininess,
                model,
            },
        })?;
    }
    scene.add_light(Light::Point {
        position: Vec3::new(-3.0, 5.0, 4.0),
        color: LinearRgb::new(1.0, 0.9, 0.7),
        intensity: 900.0,
        radius: 0.0,
    })?;
    scene.add_light(Light::Point {
        position: Vec3::new(2.5, 1.2, 1.2),
        color: LinearRgb::new(0.4, 0.6, 1.0),
        intensity: 60.0,
        radius: 0.0,
    })?;
    scene.add_light(Light::Distant {
        direction: Vec3::new(0.3, -1.0, -0.6),
        color: LinearRgb::new(1.0, 1.0, 1.0),
        intensity: 0.2,
    })?;
    Ok(scene)
}

/// Any model, with random specular options: classic Phong and Blinn-Phong, Lambert, and the
/// normalized models as dielectrics (with or without `ior`) or metals, with one to three
/// lobes. Weights may sum above 1 (accepted, only flagged).
pub fn any_model() -> impl Strategy<Value = Model> {
    let lobe = (0.0f32..1.0, 0.0f32..3.3).prop_map(|(weight, log_n)| Lobe {
        weight,
        shininess: 10f32.powf(log_n),
    });
    let surface = prop_oneof![
        Just(Surface::Dielectric { ior: None }),
        (1.01f32..3.0).prop_map(|ior| Surface::Dielectric { ior: Some(ior) }),
        prop::sample::select(Metal::ALL.to_vec()).prop_map(Surface::Metal),
    ];
    model_from(surface, lobe)
}

/// Any of the five models from a surface strategy and a lobe strategy: the classic models,
/// Lambert, or a normalized model with that surface and zero to two more lobes.
pub fn model_from(
    surface: impl Strategy<Value = Surface>,
    lobe: impl Strategy<Value = Lobe> + Clone,
) -> impl Strategy<Value = Model> {
    let lobes = (0usize..=2, lobe.clone(), lobe).prop_map(|(count, a, b)| {
        let mut more = [Lobe::NONE; MORE_LOBES];
        for (slot, l) in more.iter_mut().zip([a, b]).take(count) {
            *slot = l;
        }
        more
    });
    (0u8..5, surface, lobes).prop_map(|(kind, surface, more_lobes)| {
        let spec = Specular {
            surface,
            more_lobes,
        };
        match kind {
            0 => Model::Phong,
            1 => Model::BlinnPhong,
            2 => Model::Lambert,
            3 => Model::NormalizedPhong(spec),
            _ => Model::NormalizedBlinnPhong(spec),
        }
    })
}

fn any_material() -> impl Strategy<Value = Material> {
    (
        color(0.0, 1.0),
        0.0f32..1.0,
        0.0f32..1.0,
        0.0f32..3.3,
        any_model(),
    )
        .prop_map(|(albedo, kd, ks, log_n, model)| Material {
            albedo,
            kd,
            ks,
            shininess: 10f32.powf(log_n),
            model,
        })
}

/// Like [`scene_strategy`], but the spheres' materials use every model ([`any_model`]).
pub fn all_models_scene_strategy() -> impl Strategy<Value = TestScene> {
    (scene_strategy(), prop::collection::vec(any_material(), 6)).prop_map(|(scene, materials)| {
        let mut out = TestScene::new(*scene.camera(), scene.background()).expect("valid");
        for (s, material) in scene.spheres().iter().zip(materials) {
            out.add_sphere(Sphere { material, ..*s })
                .expect("valid sphere");
        }
        for l in scene.lights() {
            out.add_light(*l).expect("valid light");
        }
        out
    })
}

/// Oren–Nayar (σ from 0 to π/2) or GGX (roughness over its whole range, with every surface).
pub fn rough_model() -> impl Strategy<Value = Model> {
    let surface = prop_oneof![
        Just(Surface::Dielectric { ior: None }),
        (1.01f32..3.0).prop_map(|ior| Surface::Dielectric { ior: Some(ior) }),
        prop::sample::select(Metal::ALL.to_vec()).prop_map(Surface::Metal),
    ];
    prop_oneof![
        (0.0f32..=std::f32::consts::FRAC_PI_2).prop_map(|roughness| Model::OrenNayar { roughness }),
        (MIN_GGX_ROUGHNESS..=1.0f32, surface)
            .prop_map(|(roughness, surface)| Model::Ggx(Microfacet { roughness, surface })),
    ]
}

/// Like [`scene_strategy`], with every sphere's material Oren–Nayar or GGX ([`rough_model`])
/// except one in three, which keeps a model of [`any_model`].
pub fn rough_models_scene_strategy() -> impl Strategy<Value = TestScene> {
    let material = (
        color(0.0, 1.0),
        0.0f32..1.0,
        0.0f32..1.0,
        rough_model(),
        any_model(),
    );
    (scene_strategy(), prop::collection::vec(material, 6)).prop_map(|(scene, materials)| {
        let mut out = TestScene::new(*scene.camera(), scene.background()).expect("valid");
        for (i, (s, (albedo, kd, ks, rough, other))) in
            scene.spheres().iter().zip(materials).enumerate()
        {
            let model = if i % 3 == 2 { other } else { rough };
            let material = Material {
                albedo,
                kd,
                ks,
                model,
                ..s.material
            };
            out.add_sphere(Sphere { material, ..*s })
                .expect("valid sphere");
        }
        for l in scene.lights() {
            out.add_light(*l).expect("valid light");
        }
        out
    })
}

/// `n` random scenes whose spheres are mostly Oren–Nayar and GGX, from a fixed seed.
pub fn random_scenes_rough_models(n: usize, seed: u64) -> Vec<TestScene> {
    draw(rough_models_scene_strategy(), n, seed)
}

/// `n` random scenes using every model, from a fixed seed.
pub fn random_scenes_all_models(n: usize, seed: u64) -> Vec<TestScene> {
    draw(all_models_scene_strategy(), n, seed)
}

/// Five spheres in a row on a floor (a large sphere), lit from low along the row by one
/// point light of radius `light_radius` (0: a point light) and a dim distant light from
/// above, so that each sphere shadows the next and the floor: two classic Phong spheres
/// (one shiny), a classic Blinn-Phong, a normalized Phong dielectric with an `ior` and a
/// Lambert sphere. The row's spheres have radius [`ROW_RADIUS`].
pub fn spheres_in_a_row(light_radius: f32) -> Result<Scene, SceneError> {
    let camera = Camera {
        position: Vec3::new(0.5, 2.4, 7.5),
        look_at: Vec3::new(0.0, 0.0, 0.0),
        up: Vec3::new(0.0, 1.0, 0.0),
        vfov_degrees: 38.0,
    };
    let mut scene = Scene::new(camera, LinearRgb::new(0.02, 0.03, 0.05))?;
    scene.add_sphere(Sphere {
        center: Vec3::new(0.0, -100.0 - ROW_RADIUS, 0.0),
        radius: 100.0,
        material: Material {
            albedo: LinearRgb::new(0.7, 0.7, 0.65),
            kd: 0.9,
            ks: 0.1,
            shininess: 8.0,
            model: Model::Phong,
        },
    })?;
    let classic = |albedo, ks, shininess, model| Material {
        albedo,
        kd: 0.8,
        ks,
        shininess,
        model,
    };
    let materials = [
        classic(LinearRgb::new(0.8, 0.2, 0.1), 0.6, 60.0, Model::Phong),
        classic(LinearRgb::new(0.2, 0.7, 0.3), 0.3, 10.0, Model::Phong),
        classic(LinearRgb::new(0.1, 0.4, 0.9), 0.6, 200.0, Model::BlinnPhong),
        Material {
            albedo: LinearRgb::new(0.9, 0.8, 0.2),
            kd: 0.7,
            ks: 0.3,
            shininess: 80.0,
            model: Model::NormalizedPhong(Specular {
                surface: Surface::Dielectric { ior: Some(1.5) },
                ..Specular::default()
            }),
        },
        Material {
            albedo: LinearRgb::new(0.8, 0.8, 0.8),
            kd: 1.0,
            ks: 0.0,
            shininess: 1.0,
            model: Model::Lambert,
        },
    ];
    for (i, material) in materials.into_iter().enumerate() {
        scene.add_sphere(Sphere {
            center: Vec3::new(-2.6 + 1.3 * i as f32, 0.0, 0.4 * (i % 2) as f32),
            radius: ROW_RADIUS,
            material,
        })?;
    }
    let position = Vec3::new(6.0, 1.6, 1.5);
    let d2 = (position - Vec3::new(2.6, 0.0, 0.0)).dot(position - Vec3::new(2.6, 0.0, 0.0));
    scene.add_light(Light::Point {
        position,
        color: LinearRgb::new(1.0, 0.95, 0.85),
        // About 0.8 arriving at the nearest sphere.
        intensity: 4.0 * core::f32::consts::PI * d2 * 0.8,
        radius: light_radius,
    })?;
    scene.add_light(Light::Distant {
        direction: Vec3::new(-0.2, -1.0, -0.3),
        color: LinearRgb::new(0.6, 0.7, 1.0),
        intensity: 0.15,
    })?;
    Ok(scene)
}

/// The radius of the spheres of [`spheres_in_a_row`].
pub const ROW_RADIUS: f32 = 0.5;

/// `scene` with every point light given the radius `radius`, or the largest of `radius/2`,
/// `radius/4`, … (down to `radius/64`) that keeps it clear of the spheres, or 0.
pub fn with_sphere_lights<const S: usize, const L: usize>(
    scene: &Scene<S, L>,
    radius: f32,
) -> Scene<S, L> {
    let mut out = Scene::<S, L>::new(*scene.camera(), scene.background()).expect("valid camera");
    for s in scene.spheres() {
        out.add_sphere(*s).expect("valid sphere");
    }
    for light in scene.lights() {
        let mut r = radius;
        loop {
            let l = match *light {
                Light::Point {
                    position,
                    color,
                    intensity,
                    ..
                } => Light::Point {
                    position,
                    color,
                    intensity,
                    radius: r,
                },
                other => other,
            };
            if out.add_light(l).is_ok() {
                break;
            }
            r = if r > radius / 64.0 { r / 2.0 } else { 0.0 };
        }
    }
    out
}
