//! Built-in scenes, available without a scene file (firmware has no file system).
//!
//! [`exponent_series`] is the lesson's scene, number for number the same as
//! `scenes/exponent-series.toml` (the harness tests that the two agree); [`materials`] is
//! the gallery of models, the same as `scenes/materials.toml`; [`microfacets`] sets GGX and
//! Oren–Nayar next to their normalized counterparts (`scenes/microfacets.toml`), and
//! [`full_moon`] shows why Oren–Nayar exists (`scenes/full-moon.toml`). Those two need the
//! crate feature `models`: without it they return the scene's refusal of their first such
//! sphere ([`Problem::ModelNotBuilt`](crate::Problem::ModelNotBuilt)), and so do
//! [`materials`] and [`area_lights`] without the feature `blinn-phong` (their normalized
//! Blinn-Phong spheres). [`area_lights`] shows a sphere light's soft shadows and wider
//! highlights. [`covered_sphere`] of each of
//! [`model_samples`] is a frame of one reflection model alone, for measuring its cost.
//!
//! The scene matrix, [`floor`], [`lamp`] and [`three_lights`] at [`MATRIX_SIZE`], is what a
//! user draws first: spheres resting on a floor sphere under distant lights, a point light,
//! or both, with classic, Lambert and normalized materials. The firmware measures each
//! path's cost on them.

use crate::pixel::LinearRgb;
use crate::scene::{
    Camera, Light, Lobe, Material, Metal, Microfacet, Model, Scene, SceneError, Specular, Sphere,
    Surface,
};
use crate::vec3::Vec3;

/// The exponent series' image size in the scene file: 1024 × 747.
pub const EXPONENT_SERIES_SIZE: (u32, u32) = (1024, 747);

/// Five grey spheres, Phong exponent `n` = 2, 10, 50, 250, 1250 with `ks` rising from 0.04 to
/// 0.2, lit by one distant light of intensity 5 over a blue background: the highlights get
/// smaller and tighter as `n` grows, but not dimmer (classic Phong is not normalized).
///
/// Returns a `Result` rather than panicking, so firmware that links it keeps no panic path;
/// with these numbers it is always `Ok`.
///
/// The scene has the default capacities ([`DEFAULT_SPHERES`](crate::scene::DEFAULT_SPHERES),
/// [`DEFAULT_LIGHTS`](crate::scene::DEFAULT_LIGHTS)), as every built-in scene has.
pub fn exponent_series() -> Result<Scene, SceneError> {
    exponent_series_with_capacity()
}

/// [`exponent_series`] built straight into a scene of capacities `S` spheres and `L` lights,
/// for firmware that sizes its scene and prepared frame to what it draws (at least 5 and 1;
/// smaller capacities give [`SceneError`] naming the sphere or light that does not fit).
///
/// ```
/// use shadeline::{exponent_series_with_capacity, PreparedFixed, Scene};
/// let scene: Scene<5, 1> = exponent_series_with_capacity()?;
/// let frame = PreparedFixed::new(&scene, 320, 240)?;
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn exponent_series_with_capacity<const S: usize, const L: usize>(
) -> Result<Scene<S, L>, SceneError> {
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

/// The materials gallery's image size: 768 × 432.
pub const MATERIALS_SIZE: (u32, u32) = (768, 432);

/// The materials gallery: ten spheres in two rows under a white key light and a dim warm
/// fill light, over a near-black background.
///
/// Top row, left to right: a red plastic (normalized Phong, dielectric: its highlight is
/// white, not red), gold, copper and bronze (normalized Blinn-Phong metals: no diffuse lobe,
/// the reflection tinted by the metal's `F₀`, whitening toward grazing angles), and a blue
/// multi-lobe lacquer (one diffuse lobe and three specular lobes, `n` = 800, 60 and 8).
/// Bottom row: the exponent series under normalized Phong, `kd = ks = 0.5` and
/// `n` = 2, 10, 50, 250, 1250, as in the classic series: unlike it, the highlight dims as it widens.
/// Every material is energy conserving ([`Material::is_energy_conserving`]). The same
/// numbers are in `scenes/materials.toml`.
///
/// Like [`exponent_series`], it returns a scene of the default capacities
/// ([`DEFAULT_SPHERES`](crate::scene::DEFAULT_SPHERES),
/// [`DEFAULT_LIGHTS`](crate::scene::DEFAULT_LIGHTS)), so either preset goes into the same
/// prepared type:
///
/// ```
/// use shadeline::{exponent_series, materials, Prepared, Render, Rgb565, Simd8};
/// for scene in [exponent_series()?, materials()?] {
///     let frame = Prepared::<Simd8>::new(&scene, 32, 24)?;
///     frame.render_line(12, &mut [Rgb565::default(); 32])?;
/// }
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn materials() -> Result<Scene, SceneError> {
    materials_with_capacity()
}

/// [`materials`] built straight into a scene of capacities `S` spheres and `L` lights (at
/// least 10 and 2; smaller capacities give [`SceneError`] naming the sphere or light that
/// does not fit).
pub fn materials_with_capacity<const S: usize, const L: usize>() -> Result<Scene<S, L>, SceneError>
{
    use crate::scene::{Lobe, Metal, Specular, Surface};
    let mut scene = gallery_stage(13.0)?;
    let dielectric = Specular::default();
    let metal = |m: Metal| Material {
        albedo: LinearRgb::new(0.0, 0.0, 0.0),
        kd: 0.0,
        ks: 1.0,
        shininess: 40.0,
        model: Model::NormalizedBlinnPhong(Specular {
            surface: Surface::Metal(m),
            ..Specular::default()
        }),
    };
    let top = [
        Material {
            albedo: LinearRgb::new(0.7, 0.1, 0.08),
            kd: 0.7,
            ks: 0.3,
            shininess: 200.0,
            model: Model::NormalizedPhong(dielectric),
        },
        metal(Metal::Gold),
        metal(Metal::Copper),
        metal(Metal::Bronze),
        Material {
            albedo: LinearRgb::new(0.05, 0.15, 0.5),
            kd: 0.6,
            ks: 0.25,
            shininess: 800.0,
            model: Model::NormalizedBlinnPhong(Specular {
                surface: Surface::Dielectric { ior: None },
                more_lobes: [
                    Lobe {
                        weight: 0.1,
                        shininess: 60.0,
                    },
                    Lobe {
                        weight: 0.05,
                        shininess: 8.0,
                    },
                ],
            }),
        },
    ];
    let columns = [-4.4, -2.2, 0.0, 2.2, 4.4];
    for (x, material) in columns.into_iter().zip(top) {
        scene.add_sphere(Sphere {
            center: Vec3::new(x, 1.1, 0.0),
            radius: 0.95,
            material,
        })?;
    }
    for (x, n) in columns.into_iter().zip([2.0, 10.0, 50.0, 250.0, 1250.0]) {
        scene.add_sphere(Sphere {
            center: Vec3::new(x, -1.1, 0.0),
            radius: 0.95,
            material: Material {
                albedo: LinearRgb::new(0.18, 0.18, 0.18),
                kd: 0.5,
                ks: 0.5,
                shininess: n,
                model: Model::NormalizedPhong(dielectric),
            },
        })?;
    }
    Ok(scene)
}

/// The microfacet gallery's image size: 960 × 480.
pub const MICROFACETS_SIZE: (u32, u32) = (960, 480);

/// The GGX roughnesses of the microfacet gallery's columns.
pub const MICROFACET_ROUGHNESS: [f32; 3] = [0.25, 0.5, 0.75];

/// The normalized Blinn-Phong exponent that matches a GGX roughness `r`: `n = 2/α² − 2`,
/// `α = r²`, the usual correspondence of the two distributions' peaks (Walter et al.,
/// *Microfacet models for refraction through rough surfaces*, 2007, for Beckmann; for GGX
/// too, the two lobes have the same height at `N·H = 1`). 510, 30 and 4.3 for the gallery's
/// 0.25, 0.5 and 0.75.
pub fn blinn_phong_exponent(roughness: f32) -> f32 {
    let alpha = roughness * roughness;
    2.0 / (alpha * alpha) - 2.0
}

/// The microfacet gallery: sixteen spheres in three rows, under the materials gallery's
/// white key light and warm fill, over a near-black background.
///
/// Top row: a red plastic (a dielectric with `ior` 1.5, `kd` 0.7, `ks` 0.3) as GGX at
/// roughness 0.25, 0.5 and 0.75, each followed by its normalized Blinn-Phong counterpart of
/// exponent [`blinn_phong_exponent`] (same surface and weights). Middle row: the same pairs
/// for metals, gold at 0.25, copper at 0.5, bronze at 0.75. Bottom row: a Lambert sphere,
/// then Oren–Nayar with `σ` = 0.3, 0.6 and 1.0 radians, of the same grey albedo: the rougher,
/// the darker in the middle and the brighter toward the rim on the side of the light. GGX's
/// highlight has a longer tail than Blinn-Phong's at the same peak, and the rough metals
/// lose the energy single scattering does not count. Every material is energy conserving.
/// The same numbers are in `scenes/microfacets.toml`.
///
/// Without the feature `models` this returns [`SceneError::Invalid`] for sphere 0's `model`
/// ([`Problem::ModelNotBuilt`](crate::Problem::ModelNotBuilt)).
pub fn microfacets() -> Result<Scene, SceneError> {
    microfacets_with_capacity()
}

/// [`microfacets`] built straight into a scene of capacities `S` spheres and `L` lights (at
/// least 16 and 2).
pub fn microfacets_with_capacity<const S: usize, const L: usize>() -> Result<Scene<S, L>, SceneError>
{
    use crate::scene::{Metal, Microfacet, Specular, Surface};
    let mut scene = gallery_stage(17.0)?;
    let columns = [-6.25, -3.75, -1.25, 1.25, 3.75, 6.25];
    let red = LinearRgb::new(0.7, 0.1, 0.08);
    let black = LinearRgb::new(0.0, 0.0, 0.0);
    let plastic = Surface::Dielectric { ior: Some(1.5) };
    let metals = [Metal::Gold, Metal::Copper, Metal::Bronze];
    for (row, y) in [2.5f32, 0.0].into_iter().enumerate() {
        for (k, roughness) in MICROFACET_ROUGHNESS.into_iter().enumerate() {
            let (surface, albedo, kd, ks) = if row == 0 {
                (plastic, red, 0.7, 0.3)
            } else {
                (Surface::Metal(metals[k]), black, 0.0, 1.0)
            };
            // GGX does not use `shininess`: 1, as a scene file leaves it.
            let base = Material {
                albedo,
                kd,
                ks,
                shininess: 1.0,
                model: Model::Ggx(Microfacet { roughness, surface }),
            };
            let blinn = Material {
                shininess: blinn_phong_exponent(roughness),
                model: Model::NormalizedBlinnPhong(Specular {
                    surface,
                    ..Specular::default()
                }),
                ..base
            };
            for (x, material) in columns[2 * k..].iter().zip([base, blinn]) {
                scene.add_sphere(Sphere {
                    center: Vec3::new(*x, y, 0.0),
                    radius: 1.1,
                    material,
                })?;
            }
        }
    }
    let grey = Material {
        albedo: LinearRgb::new(0.8, 0.8, 0.8),
        kd: 1.0,
        ks: 0.0,
        shininess: 1.0,
        model: Model::Lambert,
    };
    let bottom = [
        Model::Lambert,
        Model::OrenNayar { roughness: 0.3 },
        Model::OrenNayar { roughness: 0.6 },
        Model::OrenNayar { roughness: 1.0 },
    ];
    for (x, model) in [-5.0, -1.667, 1.667, 5.0].into_iter().zip(bottom) {
        scene.add_sphere(Sphere {
            center: Vec3::new(x, -2.5, 0.0),
            radius: 1.1,
            material: Material { model, ..grey },
        })?;
    }
    Ok(scene)
}

/// The full-moon scene's image size: 640 × 320.
pub const FULL_MOON_SIZE: (u32, u32) = (640, 320);

/// Two grey spheres lit from behind the viewer (a distant light along the view direction),
/// as the sun lights the full moon: on the left Lambert, bright in the middle and dark at
/// the rim (`N·L` falls to 0 there); on the right Oren–Nayar with `σ` = 1.0 radian, whose
/// brightness is `A·cos θ + B·sin²θ` (times `ρ/π`) and never falls below `B/A` ≈ 0.66 of
/// its centre's, reached at the rim: a flat disc, like the moon. Same albedo and weights; the Oren–Nayar
/// sphere is darker in the middle (`A` ≈ 0.62). The same numbers are in
/// `scenes/full-moon.toml`.
///
/// Without the feature `models` this returns [`SceneError::Invalid`] for sphere 1's `model`
/// ([`Problem::ModelNotBuilt`](crate::Problem::ModelNotBuilt)).
pub fn full_moon() -> Result<Scene<2, 1>, SceneError> {
    let camera = Camera {
        position: Vec3::new(0.0, 0.0, 10.0),
        look_at: Vec3::new(0.0, 0.0, 0.0),
        up: Vec3::new(0.0, 1.0, 0.0),
        vfov_degrees: 25.0,
    };
    let mut scene = Scene::new(camera, LinearRgb::new(0.0, 0.0, 0.0))?;
    scene.add_light(Light::Distant {
        direction: Vec3::new(0.0, 0.0, -1.0),
        color: LinearRgb::new(1.0, 1.0, 1.0),
        intensity: 3.0,
    })?;
    for (x, model) in [
        (-2.0, Model::Lambert),
        (2.0, Model::OrenNayar { roughness: 1.0 }),
    ] {
        scene.add_sphere(Sphere {
            center: Vec3::new(x, 0.0, 0.0),
            radius: 1.7,
            material: Material {
                albedo: LinearRgb::new(0.8, 0.8, 0.8),
                kd: 1.0,
                ks: 0.0,
                shininess: 1.0,
                model,
            },
        })?;
    }
    Ok(scene)
}

/// The area-lights scene's image size: 640 × 320.
pub const AREA_LIGHTS_SIZE: (u32, u32) = (640, 320);

/// The radius of [`area_lights`]'s sphere light.
pub const AREA_LIGHT_RADIUS: f32 = 1.5;

/// Four spheres on a row on a grey floor (a sphere of radius 100), lit from the right and
/// above by one sphere light of radius `light_radius` ([`AREA_LIGHT_RADIUS`] in the scene
/// file; 0 is the point light at its centre, for comparison): each sphere casts its shadow
/// onto its left neighbour and the floor, with a penumbra that widens away from the caster.
/// Left to right, normalized Blinn-Phong plastics of exponent 20, 100, 500 and 2,500: the
/// shinier, the more the sphere light widens the highlight over the point light's (for a
/// lobe narrower than the light, the highlight is the light's reflected image). The same
/// numbers are in `scenes/area-lights.toml`.
///
/// A radius above 0 needs the feature `area-lights` (without it the scene refuses the light,
/// [`Problem::SphereLightNotBuilt`](crate::Problem::SphereLightNotBuilt)), and on the fixed
/// path `full-width` too.
pub fn area_lights(light_radius: f32) -> Result<Scene<5, 1>, SceneError> {
    let camera = Camera {
        position: Vec3::new(0.0, 2.5, 10.0),
        look_at: Vec3::new(0.0, 0.6, 0.0),
        up: Vec3::new(0.0, 1.0, 0.0),
        vfov_degrees: 24.0,
    };
    let mut scene = Scene::new(camera, LinearRgb::new(0.02, 0.02, 0.03))?;
    scene.add_light(Light::Point {
        position: Vec3::new(8.0, 5.0, 3.0),
        color: LinearRgb::new(1.0, 1.0, 1.0),
        intensity: 3000.0,
        radius: light_radius,
    })?;
    scene.add_sphere(Sphere {
        center: Vec3::new(0.0, -100.0, 0.0),
        radius: 100.0,
        material: Material {
            albedo: LinearRgb::new(0.5, 0.5, 0.5),
            kd: 1.0,
            ks: 0.0,
            shininess: 1.0,
            model: Model::Lambert,
        },
    })?;
    for (x, n, albedo) in [
        (-3.3, 20.0, LinearRgb::new(0.7, 0.12, 0.1)),
        (-1.1, 100.0, LinearRgb::new(0.12, 0.5, 0.15)),
        (1.1, 500.0, LinearRgb::new(0.1, 0.2, 0.7)),
        (3.3, 2500.0, LinearRgb::new(0.6, 0.5, 0.1)),
    ] {
        scene.add_sphere(Sphere {
            center: Vec3::new(x, 0.9, 0.0),
            radius: 0.9,
            material: Material {
                albedo,
                kd: 0.8,
                ks: 0.2,
                shininess: n,
                model: Model::NormalizedBlinnPhong(crate::scene::Specular::default()),
            },
        })?;
    }
    Ok(scene)
}

/// The galleries' stage: a camera on the `z` axis at `distance`, looking at the origin with a
/// 28° field of view, a near-black background, a white key light from the upper right and a
/// warm fill from the left.
fn gallery_stage<const S: usize, const L: usize>(distance: f32) -> Result<Scene<S, L>, SceneError> {
    let camera = Camera {
        position: Vec3::new(0.0, 0.0, distance),
        look_at: Vec3::new(0.0, 0.0, 0.0),
        up: Vec3::new(0.0, 1.0, 0.0),
        vfov_degrees: 28.0,
    };
    let mut scene = Scene::new(camera, LinearRgb::new(0.02, 0.02, 0.03))?;
    scene.add_light(Light::Distant {
        direction: Vec3::new(0.45, -0.55, -0.7),
        color: LinearRgb::new(1.0, 1.0, 1.0),
        intensity: 2.5,
    })?;
    scene.add_light(Light::Distant {
        direction: Vec3::new(-0.6, -0.2, -0.75),
        color: LinearRgb::new(1.0, 0.85, 0.7),
        intensity: 0.6,
    })?;
    Ok(scene)
}

/// One material per reflection model, named as the `model/*` benchmarks and the M4F
/// firmware's per-model runs name them: a red plastic (`kd` 0.7, `ks` 0.3) as classic Phong
/// (`n` = 30), normalized Blinn-Phong with a dielectric's Fresnel (`ior` 1.5), Oren–Nayar
/// (`σ` = 0.5), GGX (roughness 0.5, `ior` 1.5), and GGX gold (roughness 0.5, no diffuse).
/// With [`covered_sphere`], each is a frame whose every pixel is that model's.
///
/// The Oren–Nayar and GGX materials need the crate feature `models` to render, and the
/// normalized Blinn-Phong one `blinn-phong`: without them a scene refuses them ([`Problem::ModelNotBuilt`](crate::Problem::ModelNotBuilt)).
pub fn model_samples() -> [(&'static str, Material); 5] {
    let plastic = Material {
        albedo: LinearRgb::new(0.7, 0.1, 0.08),
        kd: 0.7,
        ks: 0.3,
        shininess: 30.0,
        model: Model::Phong,
    };
    let fresnel = Surface::Dielectric { ior: Some(1.5) };
    let ggx = |surface| {
        Model::Ggx(Microfacet {
            roughness: 0.5,
            surface,
        })
    };
    [
        ("phong", plastic),
        (
            "normalized-blinn-phong",
            Material {
                model: Model::NormalizedBlinnPhong(Specular {
                    surface: fresnel,
                    ..Specular::default()
                }),
                ..plastic
            },
        ),
        (
            "oren-nayar",
            Material {
                model: Model::OrenNayar { roughness: 0.5 },
                ..plastic
            },
        ),
        (
            "ggx",
            Material {
                model: ggx(fresnel),
                ..plastic
            },
        ),
        (
            "ggx-gold",
            Material {
                kd: 0.0,
                ks: 1.0,
                model: ggx(Surface::Metal(Metal::Gold)),
                ..plastic
            },
        ),
    ]
}

/// One sphere of `material` that covers every pixel of a frame up to 4:3 (radius 1.5, seen
/// from 2.2 away with a 40° vertical field of view), lit by two white distant lights from
/// the upper left and right: the frame that measures a material's cost per pixel, with no
/// background and no silhouette (the `model/*` benchmarks, the M4F firmware's per-model
/// runs).
///
/// Fails as [`Scene::add_sphere`] fails for `material` (an Oren–Nayar or GGX material
/// without the feature `models`, a Blinn-Phong one without `blinn-phong`, a value out of
/// range).
pub fn covered_sphere(material: Material) -> Result<Scene<1, 2>, SceneError> {
    let camera = Camera {
        position: Vec3::new(0.0, 0.0, 2.2),
        look_at: Vec3::new(0.0, 0.0, 0.0),
        up: Vec3::new(0.0, 1.0, 0.0),
        vfov_degrees: 40.0,
    };
    let mut scene = Scene::new(camera, LinearRgb::new(0.0, 0.0, 0.0))?;
    scene.add_sphere(Sphere {
        center: Vec3::new(0.0, 0.0, 0.0),
        radius: 1.5,
        material,
    })?;
    for direction in [
        Vec3::new(1.0, -1.0, -1.0),
        Vec3::new(0.764_842_2, -1.0, -0.355_782_3),
    ] {
        scene.add_light(Light::Distant {
            direction,
            color: LinearRgb::new(1.0, 1.0, 1.0),
            intensity: 1.0,
        })?;
    }
    Ok(scene)
}

/// The size of the scene matrix's frames ([`floor`], [`lamp`], [`three_lights`]): 320 × 240,
/// the SPI display a firmware author ships.
pub const MATRIX_SIZE: (u32, u32) = (320, 240);

/// The capacities of the scene matrix's scenes: six spheres, three lights.
pub type MatrixScene = Scene<6, 3>;

/// Where the matrix's four spheres rest: `(x, y)` of each centre, radius
/// [`MATRIX_SPHERE_RADIUS`], on the floor sphere of radius 100 centred 100 below the origin
/// (each `y` puts the sphere's lowest point on the floor's surface, to `f32`).
const RESTING: [(f32, f32); 4] = [(-2.7, 0.7638), (-0.9, 0.796), (0.9, 0.796), (2.7, 0.7638)];

/// The radius of the scene matrix's four spheres.
pub const MATRIX_SPHERE_RADIUS: f32 = 0.8;

/// The matrix's stage: a camera a little above the floor looking at the row of spheres with a
/// 40° vertical field of view, a dark blue background.
fn matrix_stage() -> Result<MatrixScene, SceneError> {
    let camera = Camera {
        position: Vec3::new(0.0, 1.8, 7.0),
        look_at: Vec3::new(0.0, 0.6, 0.0),
        up: Vec3::new(0.0, 1.0, 0.0),
        vfov_degrees: 40.0,
    };
    Scene::new(camera, LinearRgb::new(0.05, 0.06, 0.1))
}

/// The matrix's floor: a sphere of radius 100 whose top is the plane `y = 0`.
fn floor_sphere(material: Material) -> Sphere {
    Sphere {
        center: Vec3::new(0.0, -100.0, 0.0),
        radius: 100.0,
        material,
    }
}

/// A key light from the upper right and a cool fill from the left, both distant.
const KEY: Light = Light::Distant {
    direction: Vec3::new(-0.5, -1.0, -0.6),
    color: LinearRgb::new(1.0, 1.0, 1.0),
    intensity: 2.0,
};
const FILL: Light = Light::Distant {
    direction: Vec3::new(0.8, -0.4, -0.3),
    color: LinearRgb::new(0.6, 0.7, 1.0),
    intensity: 0.5,
};

/// Adds the matrix's four spheres of `materials`, left to right, resting on its floor.
fn rest_on_floor(scene: &mut MatrixScene, materials: [Material; 4]) -> Result<(), SceneError> {
    for (&(x, y), material) in RESTING.iter().zip(materials) {
        scene.add_sphere(Sphere {
            center: Vec3::new(x, y, 0.0),
            radius: MATRIX_SPHERE_RADIUS,
            material,
        })?;
    }
    Ok(())
}

/// The colours and specular exponents of the matrix's four spheres in [`floor`] and
/// [`lamp`], left to right.
const SERIES: [(LinearRgb, f32); 4] = [
    (ALBEDOS[0], 10.0),
    (ALBEDOS[1], 40.0),
    (ALBEDOS[2], 150.0),
    (ALBEDOS[3], 600.0),
];

/// The colours of the matrix's four spheres, left to right.
const ALBEDOS: [LinearRgb; 4] = [
    LinearRgb::new(0.7, 0.12, 0.1),
    LinearRgb::new(0.12, 0.5, 0.15),
    LinearRgb::new(0.1, 0.2, 0.7),
    LinearRgb::new(0.6, 0.5, 0.1),
];

/// `floor` of the scene matrix: four classic Phong spheres (exponents 10, 40, 150 and 600)
/// resting on a classic Phong floor sphere of radius 100, under two distant lights: the
/// ordinary scene of a user's first minutes, its spheres touching the floor and shadowing
/// it. The same numbers are in `scenes/floor.toml`.
pub fn floor() -> Result<MatrixScene, SceneError> {
    let mut scene = matrix_stage()?;
    scene.add_light(KEY)?;
    scene.add_light(FILL)?;
    scene.add_sphere(floor_sphere(Material {
        albedo: LinearRgb::new(0.5, 0.5, 0.5),
        kd: 0.8,
        ks: 0.1,
        shininess: 8.0,
        model: Model::Phong,
    }))?;
    rest_on_floor(
        &mut scene,
        SERIES.map(|(albedo, shininess)| Material {
            albedo,
            kd: 0.7,
            ks: 0.3,
            shininess,
            model: Model::Phong,
        }),
    )?;
    Ok(scene)
}

/// The point light of [`lamp`] and [`three_lights`]: up and to the right of the spheres,
/// bringing about 1.85 to the floor 4.5 below it (`intensity = 4π·d²·E`).
const LAMP: Light = Light::Point {
    position: Vec3::new(2.0, 4.5, 2.0),
    color: LinearRgb::new(1.0, 0.95, 0.85),
    intensity: 471.0,
    radius: 0.0,
};

/// `lamp` of the scene matrix: the [`floor`] scene's spheres as normalized Blinn-Phong
/// plastics (a dielectric's Fresnel, `ior` 1.5; exponents 10, 40, 150 and 600) on a Lambert
/// floor, under one point light. The same numbers are in `scenes/lamp.toml`. Needs the
/// feature `blinn-phong`.
pub fn lamp() -> Result<MatrixScene, SceneError> {
    let mut scene = matrix_stage()?;
    scene.add_light(LAMP)?;
    scene.add_sphere(floor_sphere(Material {
        albedo: LinearRgb::new(0.5, 0.5, 0.5),
        kd: 1.0,
        ks: 0.0,
        shininess: 1.0,
        model: Model::Lambert,
    }))?;
    let plastic = Model::NormalizedBlinnPhong(Specular {
        surface: Surface::Dielectric { ior: Some(1.5) },
        ..Specular::default()
    });
    rest_on_floor(
        &mut scene,
        SERIES.map(|(albedo, shininess)| Material {
            albedo,
            kd: 0.8,
            ks: 0.2,
            shininess,
            model: plastic,
        }),
    )?;
    Ok(scene)
}

/// `three-lights` of the scene matrix: a point light and two distant lights over mixed
/// models on a Lambert floor: left to right a classic Phong plastic, a Lambert clay, a
/// normalized Phong plastic with Fresnel and two lobes (a coat), and normalized Blinn-Phong
/// gold. The same numbers are in `scenes/three-lights.toml`. Needs the feature
/// `blinn-phong`.
pub fn three_lights() -> Result<MatrixScene, SceneError> {
    let mut scene = matrix_stage()?;
    scene.add_light(LAMP)?;
    scene.add_light(KEY)?;
    scene.add_light(FILL)?;
    scene.add_sphere(floor_sphere(Material {
        albedo: LinearRgb::new(0.45, 0.45, 0.4),
        kd: 1.0,
        ks: 0.0,
        shininess: 1.0,
        model: Model::Lambert,
    }))?;
    let mut coat = [Lobe::NONE; crate::scene::MORE_LOBES];
    coat[0] = Lobe {
        weight: 0.1,
        shininess: 1000.0,
    };
    let plastic = |albedo, model| Material {
        albedo,
        kd: 0.7,
        ks: 0.3,
        shininess: 60.0,
        model,
    };
    let materials = [
        plastic(ALBEDOS[0], Model::Phong),
        // Lambert uses neither `ks` nor `shininess`: the scene file leaves them out.
        Material {
            ks: 0.0,
            shininess: 1.0,
            ..plastic(ALBEDOS[1], Model::Lambert)
        },
        plastic(
            ALBEDOS[2],
            Model::NormalizedPhong(Specular {
                surface: Surface::Dielectric { ior: Some(1.5) },
                more_lobes: coat,
            }),
        ),
        // A metal has no diffuse lobe: no `albedo` or `kd`.
        Material {
            albedo: LinearRgb::new(0.0, 0.0, 0.0),
            kd: 0.0,
            ks: 1.0,
            ..plastic(
                ALBEDOS[3],
                Model::NormalizedBlinnPhong(Specular {
                    surface: Surface::Metal(Metal::Gold),
                    ..Specular::default()
                }),
            )
        },
    ];
    rest_on_floor(&mut scene, materials)?;
    Ok(scene)
}
