//! shadeline built without the feature `full-width`: the fixed path holds only its narrow
//! kernel (distant and point lights, the classic and normalized models), and `PreparedFixed`
//! refuses each kind of frame that kernel does not take with
//! `RenderError::NeedsFullWidth` naming the first item and field that keep it from it, and
//! leaves the frame empty. Each test fails if the refusal does not fire, as it would in a
//! build with `full-width` on, where these frames render. The frames it does take are the
//! same bits as with the feature (`refusal.rs` checks the exponent series' CRC).

use shadeline::{
    exponent_series, Camera, Item, Light, LinearRgb, Material, Model, PreparedFixed, Render,
    RenderError, Rgb565, Scene, Specular, Sphere, Vec3,
};

fn camera(vfov_degrees: f32) -> Camera {
    Camera {
        position: Vec3::new(0.0, 0.0, 8.0),
        look_at: Vec3::new(0.0, 0.0, 0.0),
        up: Vec3::new(0.0, 1.0, 0.0),
        vfov_degrees,
    }
}

fn distant() -> Light {
    Light::Distant {
        direction: Vec3::new(-1.0, -1.0, -1.0),
        color: LinearRgb::new(1.0, 1.0, 1.0),
        intensity: 1.0,
    }
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

/// A scene of two Phong spheres and a distant light, which the narrow kernel takes, after
/// `change`.
fn scene(vfov: f32, change: impl FnOnce(&mut Scene<4, 2>)) -> Scene<4, 2> {
    let mut s = Scene::new(camera(vfov), LinearRgb::new(0.0, 0.0, 0.1)).unwrap();
    s.add_sphere(sphere(-1.5, Model::Phong)).unwrap();
    s.add_sphere(sphere(1.5, Model::Phong)).unwrap();
    s.add_light(distant()).unwrap();
    change(&mut s);
    s
}

fn refusal(s: &Scene<4, 2>) -> Option<RenderError> {
    PreparedFixed::new(s, 64, 48).err()
}

#[test]
fn the_narrow_frames_render() {
    let frame = PreparedFixed::new(&scene(40.0, |_| {}), 64, 48).unwrap();
    let mut line = [Rgb565::default(); 64];
    frame.render_line(24, &mut line).unwrap();
    assert_ne!(line[16], line[0], "a sphere, then the background");
    assert!(PreparedFixed::new(&exponent_series().unwrap(), 320, 240).is_ok());
}

#[test]
fn a_point_light_renders_without_the_full_width_kernel() {
    let lit = |s: &mut Scene<4, 2>| {
        s.add_light(Light::Point {
            position: Vec3::new(0.0, 4.0, 4.0),
            color: LinearRgb::new(1.0, 1.0, 1.0),
            intensity: 50.0,
            radius: 0.0,
        })
        .unwrap();
    };
    let (with, without) = (scene(40.0, lit), scene(40.0, |_| {}));
    let mut lines = [[Rgb565::default(); 64]; 2];
    for (s, line) in [&with, &without].into_iter().zip(&mut lines) {
        let frame = PreparedFixed::new(s, 64, 48).unwrap();
        frame.render_line(24, line).unwrap();
    }
    // The lamp above the spheres brightens them: the rows differ on the spheres only.
    assert_ne!(lines[0][16], lines[1][16]);
    assert_eq!(lines[0][0], lines[1][0]);
}

#[test]
fn a_normalized_sphere_renders_without_the_full_width_kernel() {
    // The two classic spheres at x = ±1.5 and a normalized one between them, in front.
    let s = scene(40.0, |s| {
        let mut normalized = sphere(0.0, Model::NormalizedPhong(Specular::default()));
        normalized.center = Vec3::new(0.0, 0.0, 2.0);
        normalized.radius = 0.5;
        s.add_sphere(normalized).unwrap();
    });
    let frame = PreparedFixed::new(&s, 64, 48).unwrap();
    let mut line = [Rgb565::default(); 64];
    frame.render_line(24, &mut line).unwrap();
    let plain = PreparedFixed::new(&scene(40.0, |_| {}), 64, 48).unwrap();
    let mut without = [Rgb565::default(); 64];
    plain.render_line(24, &mut without).unwrap();
    assert_ne!(line[32], without[32], "the normalized sphere at the centre");
    assert_eq!(line[0], without[0]);
}

/// Lambert takes the narrow kernel: a classic sphere with `kd·albedo/π` and no lobe.
#[test]
fn a_lambert_sphere_renders() {
    let s = scene(40.0, |s| {
        s.add_sphere(sphere(0.0, Model::Lambert)).unwrap();
    });
    assert_eq!(refusal(&s), None);
}

/// At 4:3 the corners' directions are `5/3·tan(vfov/2)` off the axis; the narrow kernel
/// takes them up to 1 (45°), a `vfov` up to 61.9°.
#[test]
fn a_wide_field_of_view_is_refused_at_vfov() {
    assert_eq!(refusal(&scene(61.0, |_| {})), None);
    assert_eq!(
        refusal(&scene(63.0, |_| {})),
        Some(RenderError::NeedsFullWidth {
            item: Item::Camera,
            field: "vfov"
        })
    );
}

#[test]
fn a_sphere_the_camera_is_inside_is_refused_at_its_center() {
    let s = scene(40.0, |s| {
        s.add_sphere(Sphere {
            center: Vec3::new(0.0, 0.0, 8.5),
            radius: 1.0,
            material: Material::default(),
        })
        .unwrap();
    });
    assert_eq!(
        refusal(&s),
        Some(RenderError::NeedsFullWidth {
            item: Item::Sphere(2),
            field: "center"
        })
    );
}

#[test]
fn a_refused_prepare_leaves_the_frame_empty() {
    let mut frame = PreparedFixed::<4, 2>::EMPTY;
    frame.prepare(&scene(40.0, |_| {}), 64, 48).unwrap();
    assert_eq!(frame.width(), 64);
    let refused = frame.prepare(&scene(120.0, |_| {}), 64, 48);
    assert!(matches!(refused, Err(RenderError::NeedsFullWidth { .. })));
    assert_eq!((frame.width(), frame.height()), (0, 0));
    let mut line = [Rgb565::default(); 64];
    assert!(frame.render_line(0, &mut line).is_err());
}

/// The floor scene (classic spheres resting on a floor sphere, distant lights) takes the
/// narrow kernel: spheres touching their casters need no other, and its shadows are there.
#[test]
fn the_floor_scene_renders_with_its_shadows() {
    let scene = shadeline::floor().unwrap();
    let (w, h) = shadeline::MATRIX_SIZE;
    let frame = PreparedFixed::new(&scene, w, h).expect("the narrow kernel takes the floor");
    assert_eq!(frame.kernel(), shadeline::Kernel::Narrow);
    let mut line = [shadeline::HitRecord::default(); 320];
    let mut shadowed = 0;
    for y in 0..h {
        frame.render_line(y, &mut line[..w as usize]).unwrap();
        shadowed += line.iter().filter(|r| r.shadowed != 0).count();
    }
    assert!(shadowed > 1000, "{shadowed} shadowed pixels");
}
