//! The fixed path's row driver and prepare step: spans change no pixel, rows of any size and
//! in any order give the same frame, bad requests and out-of-range scenes are refused with
//! the same typed errors as the float path.

use crate::common;
use common::*;
use shadeline::*;

/// A pixel format that keeps everything the fixed kernel produced: the raw U16F16 colour and
/// the hit record.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
struct Raw(FixedShade);

impl Pixel for Raw {
    const NEEDS_HITS: bool = true;
    fn encode(_: &Shade) -> Self {
        Raw::default()
    }
    fn encode_fixed(shade: &FixedShade) -> Self {
        Raw(*shade)
    }
}

fn assert_spans_change_nothing<const S: usize, const L: usize>(
    scene: &Scene<S, L>,
    w: u32,
    h: u32,
    what: &str,
) {
    let naive = PreparedFixed::<S, L>::new(scene, w, h)
        .unwrap()
        .with_spans(false);
    let spans = PreparedFixed::<S, L>::new(scene, w, h).unwrap();
    let want: Vec<Raw> = frame(&naive);
    let got: Vec<Raw> = frame(&spans);
    if let Some(i) = got.iter().zip(&want).position(|(a, b)| a != b) {
        panic!(
            "{what}: pixel {i} differs with spans: {:?} vs {:?}",
            got[i], want[i]
        );
    }
}

#[test]
fn spans_change_no_pixel() {
    let scene = exponent_series().unwrap();
    for (w, h) in [(320, 240), (1, 1), (7, 5), (67, 3), (3, 67)] {
        assert_spans_change_nothing(&scene, w, h, &format!("exponent series {w}x{h}"));
    }
    for (i, scene) in random_scenes(64, 0x5eed_0002).iter().enumerate() {
        let (w, h) = (93 + (i as u32 % 9), 61);
        assert_spans_change_nothing(scene, w, h, &format!("random scene {i}"));
    }
}

#[test]
fn spans_change_no_pixel_with_spheres_near_and_around_the_camera() {
    // Spheres reaching the camera's side plane, containing the eye, or behind it: the
    // rectangles must fall back to the whole frame or stay conservative.
    let camera = Camera {
        position: Vec3::new(0.0, 0.0, 3.0),
        look_at: Vec3::new(0.0, 0.0, 0.0),
        up: Vec3::new(0.0, 1.0, 0.0),
        vfov_degrees: 90.0,
    };
    let mut scene: Scene = Scene::new(camera, LinearRgb::new(0.1, 0.1, 0.1)).unwrap();
    for (c, r) in [
        (Vec3::new(1.5, 0.0, 2.5), 1.0),
        (Vec3::new(0.0, 0.0, 3.2), 0.5),
        (Vec3::new(-2.0, 1.0, 4.0), 0.7),
        (Vec3::new(0.0, -1.2, 1.0), 1.1),
        (Vec3::new(0.3, 0.2, 0.0), 0.4),
    ] {
        scene
            .add_sphere(Sphere {
                center: c,
                radius: r,
                material: Material::default(),
            })
            .unwrap();
    }
    scene
        .add_light(Light::Point {
            position: Vec3::new(0.0, 3.0, 3.0),
            color: LinearRgb::new(1.0, 1.0, 1.0),
            intensity: 200.0,
            radius: 0.0,
        })
        .unwrap();
    for (w, h) in [(160, 120), (97, 203)] {
        assert_spans_change_nothing(&scene, w, h, &format!("near spheres {w}x{h}"));
    }
}

#[test]
fn outline_spans_hold_every_pixel_on_wide_and_tall_frames() {
    // The outline spans are computed in f32 at prepare and evaluated in integers per row:
    // against frames where every sphere is tested at every pixel, and against the f64
    // reference's own hits (an outline computed independently of both kernels), on frames
    // wide, tall, large and thin.
    let sizes = [(320, 240), (240, 320), (400, 37), (37, 400), (129, 128)];
    for (i, scene) in random_scenes(60, 0x5eed_0c0e).iter().enumerate() {
        let (w, h) = sizes[i % sizes.len()];
        assert_spans_change_nothing(scene, w, h, &format!("random scene {i} at {w}x{h}"));
        let f = PreparedFixed::new(scene, w, h).unwrap();
        let reference = reference_frame(scene, w, h);
        for y in 0..h {
            let spans = f.row_spans(y);
            for x in 0..w {
                let Some(k) = reference[(y * w + x) as usize].hit.sphere else {
                    continue;
                };
                let inside = spans
                    .get(k as usize)
                    .copied()
                    .flatten()
                    .is_some_and(|s| s.start <= x && x < s.end);
                assert!(
                    inside,
                    "random scene {i} at {w}x{h}: the reference hits sphere {k} at ({x},{y}), \
                     outside its span {:?}",
                    spans.get(k as usize)
                );
            }
        }
    }
}

#[test]
fn spans_skip_work_without_losing_pixels() {
    let scene = exponent_series().unwrap();
    let f = PreparedFixed::new(&scene, 320, 240).unwrap();
    let hits: Vec<Raw> = frame(&f);
    let mut covered = 0usize;
    for y in 0..240u32 {
        for (k, span) in f.row_spans(y).iter().enumerate() {
            for x in 0..320u32 {
                let inside = span.is_some_and(|s| s.start <= x && x < s.end);
                if hits[(y * 320 + x) as usize].0.hit.sphere == Some(k as u16) {
                    assert!(inside, "pixel ({x},{y}) hits sphere {k} outside its span");
                }
                covered += inside as usize;
            }
        }
    }
    let hit = hits.iter().filter(|h| h.0.hit.sphere.is_some()).count();
    println!(
        "spans cover {covered} sphere-pixels for {hit} hit pixels, of {}",
        320 * 240
    );
    // The outline spans test 1.16 sphere-pixels per hit pixel here (rectangles: 1.56).
    assert!(
        covered * 100 < hit * 125,
        "spans are loose: {covered} for {hit} hits"
    );
}

#[test]
fn rows_in_any_order_and_every_pixel_format_agree() {
    let scene = exponent_series().unwrap();
    let f = PreparedFixed::new(&scene, 67, 31).unwrap();
    let whole: Vec<Rgb565> = frame(&f);
    let mut line = vec![Rgb565::default(); 67];
    for y in (0..31).rev() {
        f.render_line(y, &mut line).unwrap();
        assert_eq!(&line[..], &whole[(y as usize * 67)..(y as usize + 1) * 67]);
    }
    // Rgb888 and Rgb565 are the raw 16.16 colour clamped to [0, 1] and rounded to the
    // nearest level, the default encoding's rule, written out here from its definition.
    let level = |v: u32, max: u64| ((v.min(1 << 16) as u64 * max + (1 << 15)) >> 16) as u8;
    let raw: Vec<Raw> = frame(&f);
    let rgb: Vec<Rgb888> = frame(&f);
    let rgb565: Vec<Rgb565> = frame(&f);
    // Many levels: the rule is exercised over a range, not on a flat frame.
    let mut reds: Vec<u8> = rgb.iter().map(|c| c.r).collect();
    reds.sort_unstable();
    reds.dedup();
    assert!(reds.len() > 20, "{} red levels", reds.len());
    for ((r, c), p) in raw.iter().zip(&rgb).zip(&rgb565) {
        let [red, green, blue] = r.0.color;
        assert_eq!(
            [c.r, c.g, c.b],
            [level(red, 255), level(green, 255), level(blue, 255)]
        );
        assert_eq!(
            p.levels(),
            (level(red, 31), level(green, 63), level(blue, 31))
        );
    }
}

#[test]
fn bad_rows_and_buffers_are_refused_like_the_float_path() {
    let scene = exponent_series().unwrap();
    let fixed = PreparedFixed::new(&scene, 16, 8).unwrap();
    let float = Prepared::<Scalar>::new(&scene, 16, 8).unwrap();
    let mut short = [Rgb565::default(); 15];
    let mut ok = [Rgb565::default(); 16];
    assert_eq!(
        fixed.render_line(0, &mut short),
        float.render_line(0, &mut short)
    );
    assert!(matches!(
        fixed.render_line(0, &mut short),
        Err(RenderError::LineLength {
            expected: 16,
            got: 15
        })
    ));
    assert_eq!(
        fixed.render_line(8, &mut ok),
        Err(RenderError::RowOutOfRange { y: 8, height: 8 })
    );
    let mut frame_buf = [Rgb565::default(); 16 * 7];
    assert_eq!(
        fixed.render_frame(&mut frame_buf),
        Err(RenderError::FrameLength {
            expected: 128,
            got: 112
        })
    );
    for (w, h) in [(0, 1), (1, 0), (MAX_DIMENSION + 1, 1)] {
        assert_eq!(
            PreparedFixed::new(&scene, w, h).err(),
            Some(RenderError::BadSize {
                width: w,
                height: h
            })
        );
    }
}

#[test]
fn prepared_in_place_is_the_same_frame_and_an_error_leaves_it_empty() {
    let series = exponent_series().unwrap();
    let mut frame = PreparedFixed::<16, 8>::EMPTY;
    let mut line = [Rgb565::default(); 64];
    assert!(
        frame.render_line(0, &mut line).is_err(),
        "an empty frame renders nothing"
    );
    // Prepared in place, again over a frame already prepared at another size and spans off.
    frame.prepare(&series, 40, 30).unwrap();
    let mut frame = frame.with_spans(false);
    frame.prepare(&series, 64, 48).unwrap();
    let fresh = PreparedFixed::new(&series, 64, 48).unwrap();
    let (got, want): (Vec<Raw>, Vec<Raw>) = (frame_of(&frame), frame_of(&fresh));
    assert!(got == want, "prepared in place differs from new");
    // A scene the fixed path refuses: an error naming the field, and an empty frame.
    let mut tiny = base_scene();
    tiny.add_sphere(Sphere {
        center: Vec3::new(2.0, 0.0, 0.0),
        radius: 1.0e-4,
        material: Material::default(),
    })
    .unwrap();
    let mut small: PreparedFixed = PreparedFixed::EMPTY;
    small.prepare(&base_scene(), 32, 32).unwrap();
    assert_eq!(
        small.prepare(&tiny, 32, 32),
        Err(RenderError::OutOfFixedRange {
            item: Item::Sphere(1),
            field: "radius",
            beside: None,
        })
    );
    let mut row = [Rgb565::default(); 32];
    assert!(
        small.render_line(0, &mut row).is_err(),
        "a refused prepare leaves it empty"
    );
    assert_eq!((small.width(), small.height()), (0, 0));
}

fn frame_of<R: Render>(r: &R) -> Vec<Raw> {
    frame(r)
}

fn base_scene() -> Scene {
    let mut s: Scene = Scene::new(camera(), LinearRgb::new(0.0, 0.0, 0.0)).unwrap();
    s.add_sphere(Sphere {
        center: Vec3::new(0.0, 0.0, 0.0),
        radius: 1.0,
        material: Material::default(),
    })
    .unwrap();
    s
}

fn camera() -> Camera {
    Camera {
        position: Vec3::new(0.0, 0.0, 10.0),
        look_at: Vec3::new(0.0, 0.0, 0.0),
        up: Vec3::new(0.0, 1.0, 0.0),
        vfov_degrees: 40.0,
    }
}

fn refused(scene: &Scene, w: u32, h: u32) -> Option<(Item, &'static str)> {
    match PreparedFixed::new(scene, w, h) {
        Err(RenderError::OutOfFixedRange { item, field, .. }) => Some((item, field)),
        Err(e) => panic!("unexpected error {e}"),
        Ok(_) => None,
    }
}

#[test]
fn scenes_that_do_not_fit_are_refused_naming_the_field() {
    let base = base_scene;
    assert_eq!(refused(&base(), 32, 32), None);

    // A sphere below 2^-13 of the scene's extent.
    let mut s = base();
    s.add_sphere(Sphere {
        center: Vec3::new(2.0, 0.0, 0.0),
        radius: 1.0e-4,
        material: Material::default(),
    })
    .unwrap();
    assert_eq!(refused(&s, 32, 32), Some((Item::Sphere(1), "radius")));

    // The same ratio is fine at any absolute size: scaling is by powers of two.
    let mut s: Scene = Scene::new(
        Camera {
            position: Vec3::new(0.0, 0.0, 1.0e5),
            ..camera()
        },
        LinearRgb::new(0.0, 0.0, 0.0),
    )
    .unwrap();
    s.add_sphere(Sphere {
        center: Vec3::new(0.0, 0.0, 0.0),
        radius: 1.0e4,
        material: Material::default(),
    })
    .unwrap();
    assert_eq!(refused(&s, 32, 32), None);

    // A field of view (or aspect ratio) whose image plane is wider than ±127.
    let mut s: Scene = Scene::new(
        Camera {
            vfov_degrees: 179.9,
            ..camera()
        },
        LinearRgb::new(0.0, 0.0, 0.0),
    )
    .unwrap();
    s.add_sphere(Sphere {
        center: Vec3::new(0.0, 0.0, 0.0),
        radius: 1.0,
        material: Material::default(),
    })
    .unwrap();
    assert_eq!(refused(&s, 32, 32), Some((Item::Camera, "vfov")));
    assert_eq!(refused(&base(), 60_000, 10), Some((Item::Camera, "vfov")));

    // Material weights and distant-light levels above MAX_LEVEL.
    let heavy = |kd: f32, ks: f32| {
        let mut s = base();
        let material = Material {
            kd,
            ks,
            albedo: LinearRgb::new(1.0, 1.0, 1.0),
            ..Material::default()
        };
        s.add_sphere(Sphere {
            center: Vec3::new(3.0, 0.0, 0.0),
            radius: 1.0,
            material,
        })
        .unwrap();
        s
    };
    assert_eq!(
        refused(&heavy(1.0e5, 0.1), 8, 8),
        Some((Item::Sphere(1), "kd"))
    );
    assert_eq!(
        refused(&heavy(0.1, 1.0e5), 8, 8),
        Some((Item::Sphere(1), "ks"))
    );
    let mut s = base();
    s.add_light(Light::Distant {
        direction: Vec3::new(0.0, -1.0, 0.0),
        color: LinearRgb::new(1.0, 1.0, 1.0),
        intensity: 1.0e6,
    })
    .unwrap();
    assert_eq!(refused(&s, 8, 8), Some((Item::Light(0), "intensity")));

    // The kernels use kd·albedo and colour·intensity: an albedo or a colour above MAX_LEVEL
    // alone is taken where the product is within it, and the product's field is named
    // where it is not.
    let bright = |albedo: f32, kd: f32, color: f32, intensity: f32| {
        let mut s = base();
        s.add_sphere(Sphere {
            center: Vec3::new(3.0, 0.0, 0.0),
            radius: 1.0,
            material: Material {
                kd,
                albedo: LinearRgb::new(albedo, 0.5, 0.5),
                ..Material::default()
            },
        })
        .unwrap();
        s.add_light(Light::Distant {
            direction: Vec3::new(0.0, -1.0, 0.0),
            color: LinearRgb::new(0.5, color, 0.5),
            intensity,
        })
        .unwrap();
        s
    };
    assert_eq!(refused(&bright(1.0e5, 0.01, 1.0, 1.0), 8, 8), None);
    assert_eq!(refused(&bright(1.0, 1.0, 1.0e5, 0.01), 8, 8), None);
    assert_eq!(
        refused(&bright(1.0e5, 1.0, 1.0, 1.0), 8, 8),
        Some((Item::Sphere(1), "kd"))
    );
    assert_eq!(
        refused(&bright(1.0, 1.0, 1.0e5, 1.0), 8, 8),
        Some((Item::Light(0), "intensity"))
    );

    // A very bright point light is not refused: arriving light saturates per pixel.
    let mut s = base();
    s.add_light(Light::Point {
        position: Vec3::new(0.0, 0.0, 1.0),
        color: LinearRgb::new(1.0, 1.0, 1.0),
        intensity: 1.0e12,
        radius: 0.0,
    })
    .unwrap();
    assert_eq!(refused(&s, 8, 8), None);

    let e = RenderError::OutOfFixedRange {
        item: Item::Sphere(3),
        field: "radius",
        beside: None,
    };
    assert_eq!(
        e.to_string(),
        "sphere 3: `radius` does not fit the fixed-point path's number formats"
    );
}

/// A floor sphere of radius 10,000 under spheres of radius 1: the refusal names the small
/// sphere and the floor that sets the scene's extent, and says what to change; a floor of
/// radius 1,000 renders.
#[test]
fn a_huge_floor_is_named_in_the_refusal() {
    let on_floor = |floor: f32| {
        let mut s: Scene = Scene::new(camera(), LinearRgb::new(0.0, 0.0, 0.0)).unwrap();
        s.add_sphere(Sphere {
            center: Vec3::new(0.0, -floor, 0.0),
            radius: floor,
            material: Material::default(),
        })
        .unwrap();
        s.add_sphere(Sphere {
            center: Vec3::new(0.0, 1.0, 0.0),
            radius: 1.0,
            material: Material::default(),
        })
        .unwrap();
        s
    };
    let e = PreparedFixed::new(&on_floor(10_000.0), 32, 24).unwrap_err();
    assert_eq!(
        e,
        RenderError::OutOfFixedRange {
            item: Item::Sphere(1),
            field: "radius",
            beside: Some(0),
        }
    );
    let text = e.to_string();
    assert!(
        text.starts_with("sphere 1: `radius`") && text.contains("which sphere 0 sets"),
        "{text}"
    );
    assert!(text.contains("make sphere 0 smaller"), "{text}");
    assert!(PreparedFixed::new(&on_floor(1_000.0), 32, 24).is_ok());
}

/// `scene` in units `2^j` times as large: every coordinate and radius scaled, point lights'
/// intensities by `4^j` so that the light arriving at the scaled surfaces is the same.
fn scaled<const S: usize, const L: usize>(scene: &Scene<S, L>, j: i32) -> Scene<S, L> {
    let f = 2f32.powi(j);
    let c = scene.camera();
    let camera = Camera {
        position: c.position.scale(f),
        look_at: c.look_at.scale(f),
        ..*c
    };
    let mut out = Scene::new(camera, scene.background()).unwrap();
    for s in scene.spheres() {
        out.add_sphere(Sphere {
            center: s.center.scale(f),
            radius: s.radius * f,
            material: s.material,
        })
        .unwrap();
    }
    for l in scene.lights() {
        out.add_light(match *l {
            Light::Point {
                position,
                color,
                intensity,
                radius,
            } => Light::Point {
                position: position.scale(f),
                color,
                intensity: intensity * f * f,
                radius: radius * f,
            },
            distant => distant,
        })
        .unwrap();
    }
    out
}

/// The module docs' scaling: prepare brings every scene to the same extent by a power of
/// two (and scales the point lights' power and the ray epsilon with it), so the fixed
/// formats get the same precision whatever the units: the same scene in other units is
/// the same frame, bit for bit, hit records included.
#[test]
fn the_units_of_a_scene_change_no_bit_of_the_fixed_frame() {
    let series = exponent_series().unwrap();
    let want: Vec<Raw> = frame(&PreparedFixed::new(&series, 160, 120).unwrap());
    for j in [-3, -1, 1, 4, 10] {
        let got: Vec<Raw> = frame(&PreparedFixed::new(&scaled(&series, j), 160, 120).unwrap());
        assert!(got == want, "exponent series in units of 2^{j}");
    }
    let lamps = point_lights_blinn_phong().unwrap();
    let want: Vec<Raw> = frame(&PreparedFixed::new(&lamps, 160, 120).unwrap());
    assert!(
        want.iter().any(|p| p.0.hit.shadowed != 0),
        "no shadow in the frame"
    );
    for j in [-7, -3, 2, 6, 12] {
        let got: Vec<Raw> = frame(&PreparedFixed::new(&scaled(&lamps, j), 160, 120).unwrap());
        assert!(got == want, "point-light scene in units of 2^{j}");
    }
}
