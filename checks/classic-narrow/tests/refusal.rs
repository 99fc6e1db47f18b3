//! shadeline built with no features: the fixed path's narrow kernel without its
//! point-light and normalized-model stages (`narrow-precise`) and no full-width kernel.
//! `PreparedFixed` refuses a frame with a point light or a normalized sphere with
//! `RenderError::NeedsNarrowPrecise` naming the first one, and renders the classic frames.
//! Each refusal test fails in a build with `narrow-precise` on, where those frames render.

use shadeline::{
    exponent_series, Camera, Item, Light, LinearRgb, Material, Model, PreparedFixed, Render,
    RenderError, Rgb565, Scene, Specular, Sphere, Vec3,
};

/// Two Phong spheres under a distant light, which this build's narrow kernel takes.
fn classic() -> Scene<4, 2> {
    let camera = Camera {
        position: Vec3::new(0.0, 0.0, 8.0),
        look_at: Vec3::new(0.0, 0.0, 0.0),
        up: Vec3::new(0.0, 1.0, 0.0),
        vfov_degrees: 40.0,
    };
    let mut s = Scene::new(camera, LinearRgb::new(0.0, 0.0, 0.1)).unwrap();
    for x in [-1.5, 1.5] {
        s.add_sphere(Sphere {
            center: Vec3::new(x, 0.0, 0.0),
            radius: 1.0,
            material: Material::default(),
        })
        .unwrap();
    }
    s.add_light(Light::Distant {
        direction: Vec3::new(-1.0, -1.0, -1.0),
        color: LinearRgb::new(1.0, 1.0, 1.0),
        intensity: 1.0,
    })
    .unwrap();
    s
}

#[test]
fn the_classic_frames_render() {
    let frame = PreparedFixed::new(&classic(), 64, 48).unwrap();
    let mut line = [Rgb565::default(); 64];
    frame.render_line(24, &mut line).unwrap();
    assert_ne!(line[16], line[0], "a sphere, then the background");
    assert!(PreparedFixed::new(&exponent_series().unwrap(), 320, 240).is_ok());
}

#[test]
fn a_point_light_is_refused_at_its_type() {
    let mut s = classic();
    s.add_light(Light::Point {
        position: Vec3::new(0.0, 4.0, 4.0),
        color: LinearRgb::new(1.0, 1.0, 1.0),
        intensity: 50.0,
        radius: 0.0,
    })
    .unwrap();
    let refused = PreparedFixed::new(&s, 64, 48).err();
    assert_eq!(
        refused,
        Some(RenderError::NeedsNarrowPrecise {
            item: Item::Light(1),
            field: "type"
        })
    );
    let message = refused.map(|e| e.to_string()).unwrap_or_default();
    assert!(
        message.contains("light 1") && message.contains("narrow-precise"),
        "{message}"
    );
}

#[test]
fn a_normalized_sphere_is_refused_at_its_model() {
    let mut s = classic();
    s.add_sphere(Sphere {
        center: Vec3::new(0.0, 0.0, 2.0),
        radius: 0.5,
        material: Material {
            model: Model::NormalizedPhong(Specular::default()),
            ..Material::default()
        },
    })
    .unwrap();
    assert_eq!(
        PreparedFixed::new(&s, 64, 48).err(),
        Some(RenderError::NeedsNarrowPrecise {
            item: Item::Sphere(2),
            field: "model"
        })
    );
}

#[test]
fn a_lambert_sphere_renders() {
    let mut s = classic();
    s.add_sphere(Sphere {
        center: Vec3::new(0.0, 0.0, 2.0),
        radius: 0.5,
        material: Material {
            model: Model::Lambert,
            ..Material::default()
        },
    })
    .unwrap();
    assert_eq!(PreparedFixed::new(&s, 64, 48).err(), None);
}
