//! The kernel each path chooses for a frame (`Prepared::kernel`, `PreparedFixed::kernel`),
//! and the reason it gives when the frame needs the slower one: the float paths agree at
//! every width, the reason names an item the scene has and the first one that keeps the
//! frame from the narrow kernel, and the scenes a user draws first get the reasons below.

use crate::common;
use shadeline::*;

/// Every path's kernel for `scene` at `w × h`: scalar, simd4, simd8, fixed.
fn kernels<const S: usize, const L: usize>(scene: &Scene<S, L>, w: u32, h: u32) -> [Kernel; 4] {
    [
        Prepared::<Scalar, S, L>::new(scene, w, h).unwrap().kernel(),
        Prepared::<Simd4, S, L>::new(scene, w, h).unwrap().kernel(),
        Prepared::<Simd8, S, L>::new(scene, w, h).unwrap().kernel(),
        PreparedFixed::<S, L>::new(scene, w, h).unwrap().kernel(),
    ]
}

/// The reason names an existing item, with a field the docs list.
fn assert_reason_exists<const S: usize, const L: usize>(scene: &Scene<S, L>, kernel: Kernel) {
    if let Kernel::General { item, field } = kernel {
        match item {
            Item::Sphere(i) => assert!(i < scene.spheres().len(), "{kernel}"),
            Item::Light(i) => assert!(i < scene.lights().len(), "{kernel}"),
            Item::Camera => {}
            Item::Background => panic!("the background never keeps a frame from a kernel"),
        }
        let fields = ["type", "model", "shininess", "vfov", "center", "radius"];
        assert!(fields.contains(&field), "{kernel}");
    }
}

#[test]
fn the_float_widths_agree_and_every_reason_names_an_item() {
    let scenes = common::random_scenes_all_models(32, 0x6b65_726e);
    let mut general = 0;
    for (n, scene) in scenes.iter().enumerate() {
        let scalar = Prepared::<Scalar>::new(scene, 48, 32).unwrap().kernel();
        let simd4 = Prepared::<Simd4>::new(scene, 48, 32).unwrap().kernel();
        let simd8 = Prepared::<Simd8>::new(scene, 48, 32).unwrap().kernel();
        assert_eq!(simd4, scalar, "random scene {n}");
        assert_eq!(simd8, scalar, "random scene {n}");
        assert_reason_exists(scene, scalar);
        // The fixed path may refuse a random scene (a number out of its formats).
        if let Ok(fixed) = PreparedFixed::new(scene, 48, 32) {
            assert_reason_exists(scene, fixed.kernel());
        }
        general += usize::from(scalar != Kernel::Narrow);
    }
    assert!(general > 0, "no random scene needed the general kernel");
}

#[test]
fn the_exponent_series_takes_the_narrow_kernel_on_every_path() {
    let scene = exponent_series().unwrap();
    assert_eq!(kernels(&scene, 320, 240), [Kernel::Narrow; 4]);
}

#[test]
fn the_first_point_light_or_normalized_sphere_is_named() {
    // One point light: every float path names it, whichever the materials; the fixed path's
    // narrow kernel takes point lights and the normalized models.
    let point = Kernel::General {
        item: Item::Light(0),
        field: "type",
    };
    for scene in [lamp().unwrap(), three_lights().unwrap()] {
        assert_eq!(
            kernels(&scene, 320, 240),
            [point, point, point, Kernel::Narrow]
        );
    }
    // Distant lights only: the first sphere that is not classic, on the float paths; the
    // fixed path's first Oren–Nayar or GGX sphere.
    let scene = microfacets().unwrap();
    let first = |keep: fn(&Model) -> bool| Kernel::General {
        item: Item::Sphere(
            scene
                .spheres()
                .iter()
                .position(|s| keep(&s.material.model))
                .expect("the gallery has such a sphere"),
        ),
        field: "model",
    };
    let float = first(|m| !m.is_classic());
    let fixed = first(|m| matches!(m, Model::OrenNayar { .. } | Model::Ggx(_)));
    assert_eq!(kernels(&scene, 160, 90), [float, float, float, fixed]);
    // The gallery of every other model: the fixed path takes it with its narrow kernel.
    assert_eq!(kernels(&materials().unwrap(), 160, 90)[3], Kernel::Narrow);
}

#[test]
fn spheres_resting_on_a_floor_take_the_narrow_kernel_on_every_path() {
    // The floor under the spheres resting on it touches each of them; no path needs its
    // general kernel for that (a build without `full-width` renders the frame too,
    // `checks/no-models/tests/narrow_only.rs`).
    assert_eq!(kernels(&floor().unwrap(), 320, 240), [Kernel::Narrow; 4]);
}

#[test]
fn classic_spheres_under_a_point_light_take_the_fixed_narrow_kernel() {
    // The floor scene with its key light a lamp: the float paths name the lamp, the fixed
    // path takes its narrow kernel.
    let distant = floor().unwrap();
    let mut scene = Scene::<6, 3>::new(*distant.camera(), distant.background()).unwrap();
    for s in distant.spheres() {
        scene.add_sphere(*s).unwrap();
    }
    scene
        .add_light(Light::Point {
            position: Vec3::new(1.5, 3.0, 2.0),
            color: LinearRgb::new(1.0, 0.95, 0.9),
            intensity: 60.0,
            radius: 0.0,
        })
        .unwrap();
    let point = Kernel::General {
        item: Item::Light(0),
        field: "type",
    };
    assert_eq!(
        kernels(&scene, 320, 240),
        [point, point, point, Kernel::Narrow]
    );
}

/// A Lambert floor under distant lights takes the narrow kernel on every path (a classic
/// sphere with no lobe), and every path stays within its budget of the reference there: the
/// float paths within one level, the fixed path within two, with at most 0.1% of the ray
/// decisions differing.
#[test]
fn a_lambert_floor_takes_the_narrow_kernel_within_budget() {
    let floor = floor().unwrap();
    let mut scene = MatrixScene::new(*floor.camera(), floor.background()).unwrap();
    for (i, s) in floor.spheres().iter().enumerate() {
        let mut s = *s;
        if i == 0 {
            s.material.model = Model::Lambert;
            s.material.kd = 1.0;
        }
        scene.add_sphere(s).unwrap();
    }
    for l in floor.lights() {
        scene.add_light(*l).unwrap();
    }
    let (w, h) = (160, 120);
    assert_eq!(kernels(&scene, w, h), [Kernel::Narrow; 4]);
    let reference = common::reference_frame(&scene, w, h);
    let scalar = common::agreement(
        &Prepared::<Scalar, 6, 3>::new(&scene, w, h).unwrap(),
        &reference,
    );
    let fixed = common::agreement(
        &PreparedFixed::<6, 3>::new(&scene, w, h).unwrap(),
        &reference,
    );
    println!("Lambert floor: scalar {scalar:?}, fixed {fixed:?}");
    assert!(
        scalar.max_levels <= 1 && scalar.decisions_differ == 0,
        "{scalar:?}"
    );
    assert!(
        fixed.max_levels <= 2 && fixed.within_one_share() >= 0.99,
        "{fixed:?}"
    );
    assert!(fixed.differ_share() <= 0.001, "{fixed:?}");
}
