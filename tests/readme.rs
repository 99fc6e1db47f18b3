//! Claims of the README and of `docs/model.md` that no other test holds: the model's
//! formulas as `docs/model.md` states them (an untinted highlight, a point light's
//! `colour·intensity / (4π r²)`), what the pictures of the exponent series and the materials
//! gallery show, and the facts the README repeats from `Cargo.toml`.

use crate::common;
use common::*;
use shadeline::*;

fn grey_box_camera(z: f32, vfov_degrees: f32) -> Camera {
    Camera {
        position: Vec3::new(0.0, 0.0, z),
        look_at: Vec3::new(0.0, 0.0, 0.0),
        up: Vec3::new(0.0, 1.0, 0.0),
        vfov_degrees,
    }
}

/// "The specular term is never tinted by the albedo": a pure red sphere on black, lit by
/// white light, has green and blue only from its highlight, and there they are equal.
#[test]
fn the_highlight_is_never_tinted_by_the_albedo() {
    let specular = Specular::default();
    for model in [
        Model::Phong,
        Model::BlinnPhong,
        Model::NormalizedPhong(specular),
        Model::NormalizedBlinnPhong(specular),
    ] {
        let mut scene: Scene =
            Scene::new(grey_box_camera(6.0, 40.0), LinearRgb::new(0.0, 0.0, 0.0)).unwrap();
        let material = Material {
            albedo: LinearRgb::new(1.0, 0.0, 0.0),
            kd: 0.5,
            ks: 0.5,
            shininess: 20.0,
            model,
        };
        scene
            .add_sphere(Sphere {
                center: Vec3::new(0.0, 0.0, 0.0),
                radius: 1.5,
                material,
            })
            .unwrap();
        scene
            .add_light(Light::Distant {
                direction: Vec3::new(-0.3, -0.4, -1.0),
                color: LinearRgb::new(1.0, 1.0, 1.0),
                intensity: 2.0,
            })
            .unwrap();
        let (w, h) = (64, 48);
        let scalar: Vec<LinearRgb> = frame(&Prepared::<Scalar>::new(&scene, w, h).unwrap());
        let reference = reference_frame(&scene, w, h);
        for (i, (p, q)) in scalar.iter().zip(&reference).enumerate() {
            assert_eq!(p.g, p.b, "{model:?}: pixel {i}: {p:?}");
            assert_eq!(q.color[1], q.color[2], "{model:?}: reference pixel {i}");
        }
        // The highlight is there (green above 0) and white on a red diffuse lobe.
        let brightest = scalar.iter().fold(0.0f32, |m, p| m.max(p.g));
        assert!(brightest > 0.05, "{model:?}: no highlight ({brightest})");
        let centre = reference.iter().map(|q| q.color[1]).fold(0.0, f64::max);
        assert!(
            centre > 0.05,
            "{model:?}: no reference highlight ({centre})"
        );
    }
}

/// "A point light delivers `colour · intensity / (4π r²)`": a one-pixel frame looks straight
/// at a classic Phong sphere with `ks = 0`, the light on the same axis, so `N·L = 1` and the
/// pixel is `kd · albedo · colour · intensity / (4π r²)`, `r` the light's distance from the
/// surface.
#[test]
fn a_point_light_delivers_colour_times_intensity_over_four_pi_r_squared() {
    let (albedo, kd, color, intensity) = ([0.9, 0.6, 0.3], 0.8, [1.0, 0.5, 0.25], 10.0);
    for light_z in [1.5f32, 2.0, 3.0, 5.0] {
        let mut scene: Scene =
            Scene::new(grey_box_camera(10.0, 30.0), LinearRgb::new(0.0, 0.0, 0.0)).unwrap();
        scene
            .add_sphere(Sphere {
                center: Vec3::new(0.0, 0.0, 0.0),
                radius: 1.0,
                material: Material {
                    albedo: LinearRgb::new(albedo[0], albedo[1], albedo[2]),
                    kd,
                    ks: 0.0,
                    shininess: 10.0,
                    model: Model::Phong,
                },
            })
            .unwrap();
        scene
            .add_light(Light::Point {
                position: Vec3::new(0.0, 0.0, light_z),
                color: LinearRgb::new(color[0], color[1], color[2]),
                intensity,
                radius: 0.0,
            })
            .unwrap();
        let r = f64::from(light_z) - 1.0;
        let want: Vec<f64> = (0..3)
            .map(|c| {
                f64::from(kd) * f64::from(albedo[c]) * f64::from(color[c]) * f64::from(intensity)
                    / (4.0 * core::f64::consts::PI * r * r)
            })
            .collect();
        let scalar: Vec<LinearRgb> = frame(&Prepared::<Scalar>::new(&scene, 1, 1).unwrap());
        let got = [scalar[0].r, scalar[0].g, scalar[0].b];
        let reference = reference_frame(&scene, 1, 1)[0].color;
        for c in 0..3 {
            let rel = (f64::from(got[c]) - want[c]).abs() / want[c];
            assert!(
                rel < 1e-4,
                "light at z = {light_z}, channel {c}: {got:?} vs {want:?}"
            );
            let rel = (reference[c] - want[c]).abs() / want[c];
            assert!(
                rel < 1e-6,
                "reference, light at z = {light_z}: {reference:?} vs {want:?}"
            );
        }
    }
}

/// The brightest pixel of each of `spheres`, by the sum of its channels.
fn peaks<const S: usize, const L: usize>(
    scene: &Scene<S, L>,
    (w, h): (u32, u32),
    spheres: &[u16],
) -> Vec<f32> {
    let f = Prepared::<Scalar, S, L>::new(scene, w, h).unwrap();
    let colours: Vec<LinearRgb> = frame(&f);
    let hits: Vec<HitRecord> = frame(&f);
    spheres
        .iter()
        .map(|s| {
            colours
                .iter()
                .zip(&hits)
                .filter(|(_, hit)| hit.sphere == Some(*s))
                .map(|(p, _)| p.r + p.g + p.b)
                .fold(0.0, f32::max)
        })
        .collect()
}

/// The README's first picture: as the classic Phong exponent grows (spheres 0 to 4, `n` = 2
/// to 1250) the highlight gets tighter "but not dimmer".
#[test]
fn exponent_series_highlights_are_not_dimmer_as_n_grows() {
    let scene = exponent_series().unwrap();
    let n: Vec<f32> = scene
        .spheres()
        .iter()
        .map(|s| s.material.shininess)
        .collect();
    assert!(n.windows(2).all(|w| w[0] < w[1]), "{n:?}");
    let p = peaks(&scene, EXPONENT_SERIES_SIZE, &[0, 1, 2, 3, 4]);
    println!("exponent series, brightest pixel per sphere: {p:?}");
    assert!(p.windows(2).all(|w| w[0] <= w[1]), "{p:?}");
}

/// The materials gallery's bottom row (spheres 5 to 9): the same exponents under normalized
/// Phong, where "the highlight dims as it widens", so the brightest pixel falls as `n` falls.
#[test]
fn normalized_phong_highlights_dim_as_they_widen() {
    let scene = materials().unwrap();
    let row = &scene.spheres()[5..10];
    assert!(row
        .iter()
        .all(|s| matches!(s.material.model, Model::NormalizedPhong(_))));
    assert!(row
        .windows(2)
        .all(|w| w[0].material.shininess < w[1].material.shininess));
    let p = peaks(&scene, MATERIALS_SIZE, &[5, 6, 7, 8, 9]);
    println!("materials bottom row, brightest pixel per sphere: {p:?}");
    assert!(p.windows(2).all(|w| w[0] < w[1]), "{p:?}");
}

/// The MSRV the README and the crate docs state is `rust-version` in `Cargo.toml`, which
/// `.ci/msrv` builds with.
#[test]
fn the_documented_msrv_is_the_manifests() {
    let msrv = env!("CARGO_PKG_RUST_VERSION");
    assert!(!msrv.is_empty());
    let readme = include_str!("../README.md");
    assert!(
        readme.contains(&format!("MSRV: Rust {msrv} (")),
        "README: MSRV is not {msrv}"
    );
    let lib = include_str!("../src/lib.rs");
    assert!(
        lib.contains(&format!("Rust {msrv} or later")),
        "src/lib.rs: MSRV is not {msrv}"
    );
}

/// "Depends only on `embedded-graphics-core` 0.4": the feature turns on that one optional
/// dependency, and the manifest asks for 0.4.
#[test]
fn the_embedded_graphics_feature_adds_only_embedded_graphics_core_0_4() {
    let manifest = include_str!("../Cargo.toml");
    let feature: Vec<&str> = manifest
        .lines()
        .filter(|l| l.starts_with("embedded-graphics ="))
        .collect();
    assert_eq!(
        feature,
        ["embedded-graphics = [\"dep:embedded-graphics-core\"]"]
    );
    let dependency: Vec<&str> = manifest
        .lines()
        .filter(|l| l.starts_with("embedded-graphics-core ="))
        .collect();
    assert_eq!(
        dependency,
        ["embedded-graphics-core = { version = \"0.4\", optional = true }"]
    );
}
