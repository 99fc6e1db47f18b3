//! shadeline built without the features `models`, `blinn-phong` and `area-lights`: the
//! `Model` variants still exist, but a scene refuses a sphere that uses one of their models,
//! with [`Problem::ModelNotBuilt`] on that sphere's `model`, never a panic and never another
//! model in its place; a sphere light (a point light with a radius) is refused the same way,
//! with [`Problem::SphereLightNotBuilt`] on the light's `radius`; and the frames of the other
//! models are the same bits as with the features (the firmware's CRCs). Each test fails if
//! the refusal does not fire, as it would in a build with the feature on.

use shadeline::{
    area_lights, exponent_series, full_moon, materials, microfacets, Camera, Item, Light,
    LinearRgb, Material, Metal, Microfacet, Model, Prepared, PreparedFixed, Problem, Render,
    Rgb565, Scalar, Scene, SceneError, Simd8, Specular, Sphere, Surface, Vec3,
};

// The firmware's frame and CRCs; the counts and the microfacet gallery's are not used here.
#[allow(dead_code)]
mod expected {
    include!("../../../firmware/expected.rs");
}

fn scene() -> Scene<4, 1> {
    let camera = Camera {
        position: Vec3::new(0.0, 0.0, 8.0),
        look_at: Vec3::new(0.0, 0.0, 0.0),
        up: Vec3::new(0.0, 1.0, 0.0),
        vfov_degrees: 40.0,
    };
    Scene::new(camera, LinearRgb::new(0.0, 0.0, 0.0)).expect("valid camera")
}

fn sphere(x: f32, model: Model) -> Sphere {
    Sphere {
        center: Vec3::new(x, 0.0, 0.0),
        radius: 1.0,
        material: Material {
            model,
            ..Material::default()
        },
    }
}

fn refused(index: usize) -> SceneError {
    SceneError::Invalid {
        item: Item::Sphere(index),
        field: "model",
        problem: Problem::ModelNotBuilt,
    }
}

#[test]
fn oren_nayar_and_ggx_spheres_are_refused_by_index() {
    let mut s = scene();
    assert_eq!(s.add_sphere(sphere(-2.0, Model::Phong)), Ok(0));
    let rough = Model::OrenNayar { roughness: 0.5 };
    assert_eq!(s.add_sphere(sphere(0.0, rough)), Err(refused(1)));
    let gold = Model::Ggx(Microfacet {
        roughness: 0.4,
        surface: Surface::Metal(Metal::Gold),
    });
    assert_eq!(s.add_sphere(sphere(0.0, gold)), Err(refused(1)));
    // Refused spheres are not added: the next one still gets index 1.
    assert_eq!(s.spheres().len(), 1);
    assert_eq!(s.add_sphere(sphere(2.0, Model::Lambert)), Ok(1));
    // The model is refused before its roughness is read: no range error for a number the
    // kernels would never see.
    let bad = Model::OrenNayar {
        roughness: f32::NAN,
    };
    assert_eq!(s.add_sphere(sphere(0.0, bad)), Err(refused(2)));
}

#[test]
fn blinn_phong_spheres_are_refused_by_index() {
    let mut s = scene();
    assert_eq!(s.add_sphere(sphere(-2.0, Model::Phong)), Ok(0));
    assert_eq!(
        s.add_sphere(sphere(0.0, Model::BlinnPhong)),
        Err(refused(1))
    );
    let normalized = Model::NormalizedBlinnPhong(Specular::default());
    assert_eq!(s.add_sphere(sphere(0.0, normalized)), Err(refused(1)));
    assert_eq!(s.spheres().len(), 1);
    // Normalized Phong, the same lobes about `R` instead of `H`, is in every build.
    let phong = Model::NormalizedPhong(Specular::default());
    assert_eq!(s.add_sphere(sphere(2.0, phong)), Ok(1));
}

#[test]
fn sphere_lights_are_refused_as_they_are_added() {
    let light = |radius: f32| Light::Point {
        position: Vec3::new(0.0, 4.0, 0.0),
        color: LinearRgb::new(1.0, 1.0, 1.0),
        intensity: 100.0,
        radius,
    };
    let mut s = scene();
    assert_eq!(s.add_sphere(sphere(0.0, Model::Phong)), Ok(0));
    let refusal = SceneError::Invalid {
        item: Item::Light(0),
        field: "radius",
        problem: Problem::SphereLightNotBuilt,
    };
    assert_eq!(s.add_light(light(0.5)), Err(refusal));
    assert_eq!(
        refusal.to_string(),
        "light 0: `radius` makes a sphere light, which this build of shadeline leaves out \
         (feature `area-lights`)"
    );
    // Its range is checked first, as with the feature; a refused light is not added, and a
    // point light of radius 0 is taken.
    let not_finite = SceneError::Invalid {
        item: Item::Light(0),
        field: "radius",
        problem: Problem::NotFinite,
    };
    assert_eq!(s.add_light(light(f32::NAN)), Err(not_finite));
    assert!(s.lights().is_empty());
    assert_eq!(s.add_light(light(0.0)), Ok(0));
    assert_eq!(s.sphere_light(), None);
}

#[test]
fn the_error_names_the_sphere_the_field_and_the_feature() {
    let text = refused(3).to_string();
    assert_eq!(
        text,
        "sphere 3: `model` is a model this build of shadeline leaves out (feature `models` for \
         oren-nayar and ggx, `blinn-phong` for the blinn-phong models)"
    );
}

#[test]
fn presets_of_the_models_return_the_refusal() {
    assert_eq!(microfacets().map(|_| ()), Err(refused(0)));
    assert_eq!(full_moon().map(|_| ()), Err(refused(1)));
    // Gold, the second sphere, is the first of normalized Blinn-Phong; the area-lights
    // preset's ground is Lambert, its spheres normalized Blinn-Phong.
    assert_eq!(materials().map(|_| ()), Err(refused(1)));
    assert_eq!(area_lights(0.0).map(|_| ()), Err(refused(1)));
    // The exponent series holds no such model.
    assert!(exponent_series().is_ok());
}

/// CRC32/IEEE over the pixels as little-endian `u16` bytes, row-major: the firmware's rule.
fn rgb565_crc32(pixels: &[Rgb565]) -> u32 {
    let mut crc = !0u32;
    for byte in pixels.iter().flat_map(|px| px.0.to_le_bytes()) {
        crc ^= u32::from(byte);
        for _ in 0..8 {
            crc = if crc & 1 != 0 {
                (crc >> 1) ^ 0xedb8_8320
            } else {
                crc >> 1
            };
        }
    }
    !crc
}

fn crc<R: Render>(path: &R) -> u32 {
    let mut pixels = vec![Rgb565::default(); (path.width() * path.height()) as usize];
    path.render_frame(&mut pixels).expect("frame renders");
    rgb565_crc32(&pixels)
}

#[test]
fn the_exponent_series_is_the_same_frame_without_the_models() {
    let scene = exponent_series().expect("built-in scene is valid");
    let (w, h) = (expected::WIDTH, expected::HEIGHT);
    let scalar = Prepared::<Scalar>::new(&scene, w, h).unwrap();
    let simd = Prepared::<Simd8>::new(&scene, w, h).unwrap();
    let fixed = PreparedFixed::new(&scene, w, h).unwrap();
    assert_eq!(crc(&scalar), expected::SCALAR_RGB565_CRC32);
    assert_eq!(crc(&simd), expected::SCALAR_RGB565_CRC32);
    assert_eq!(crc(&fixed), expected::FIXED_RGB565_CRC32);
}
