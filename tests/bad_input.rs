//! The bad-input catalogue: one named case per hostile number a caller can pass, each
//! asserting either the exact error or a defined, finite image.
//!
//! For a case that renders, every path renders the rows, and the test asserts that every
//! linear channel is finite and non-negative, that the float paths (scalar, 4 lanes, 8 lanes)
//! are bit-identical, also with every encoding (linear or sRGB, with or without dithering)
//! in Rgb565, Bgr565 and Gray8 and as display bytes, that the fixed-point path does what the
//! case says it does (stays within its budget of the scalar path, with at most 0.1 % of the
//! pixels' ray decisions differing; only renders, for ill-conditioned pixels; or refuses the
//! scene as out of its range), and a property showing the image is the defined one (which
//! sphere each pixel hits, which lights are blocked). The fuzz targets in `fuzz/` search the
//! same space at random; the regression cases at the end are inputs they found.

use shadeline::scene::{MAX_COORDINATE, MAX_INTENSITY, MAX_SHININESS, MAX_VALUE, MIN_RADIUS};
use shadeline::*;

type S = Scene;

fn camera() -> Camera {
    Camera {
        position: Vec3::new(0.0, 0.0, 5.0),
        look_at: Vec3::new(0.0, 0.0, 0.0),
        up: Vec3::new(0.0, 1.0, 0.0),
        vfov_degrees: 40.0,
    }
}

fn sphere() -> Sphere {
    Sphere {
        center: Vec3::new(0.0, 0.0, 0.0),
        radius: 1.0,
        material: Material::default(),
    }
}

fn distant() -> Light {
    Light::Distant {
        direction: Vec3::new(-1.0, -1.0, -1.0),
        color: LinearRgb::new(1.0, 1.0, 1.0),
        intensity: 2.0,
    }
}

fn point(position: Vec3) -> Light {
    Light::Point {
        position,
        color: LinearRgb::new(1.0, 1.0, 1.0),
        intensity: 50.0,
        radius: 0.0,
    }
}

fn empty_scene() -> S {
    S::new(camera(), LinearRgb::new(0.1, 0.2, 0.3)).unwrap()
}

/// One unit sphere at the origin under one distant light, seen from `z = 5`.
fn scene() -> S {
    let mut s = empty_scene();
    s.add_sphere(sphere()).unwrap();
    s.add_light(distant()).unwrap();
    s
}

fn invalid(item: Item, field: &'static str, problem: Problem) -> SceneError {
    SceneError::Invalid {
        item,
        field,
        problem,
    }
}

fn camera_error(c: Camera) -> SceneError {
    S::new(c, LinearRgb::default()).unwrap_err()
}

/// Adds `s` to a fresh scene: the error, after checking the scene did not change.
fn sphere_error(s: Sphere) -> SceneError {
    let mut scene = empty_scene();
    let err = scene.add_sphere(s).unwrap_err();
    assert!(scene.spheres().is_empty(), "a refused sphere was added");
    err
}

fn light_error(l: Light) -> SceneError {
    let mut scene = empty_scene();
    let err = scene.add_light(l).unwrap_err();
    assert!(scene.lights().is_empty(), "a refused light was added");
    err
}

/// A rendered row: linear colour and hit record per pixel.
struct Row {
    linear: Vec<LinearRgb>,
    hits: Vec<HitRecord>,
}

fn render<R: Render>(frame: &R, y: u32) -> Row {
    let w = frame.width() as usize;
    let mut linear = vec![LinearRgb::default(); w];
    let mut hits = vec![HitRecord::default(); w];
    frame.render_line(y, &mut linear).expect("row renders");
    frame.render_line(y, &mut hits).expect("row renders");
    Row { linear, hits }
}

fn bits(row: &Row) -> Vec<[u32; 3]> {
    row.linear
        .iter()
        .map(|c| [c.r.to_bits(), c.g.to_bits(), c.b.to_bits()])
        .collect()
}

/// The fixed-point path's budget against the scalar path, in 8-bit levels, on pixels whose
/// hit records agree.
const FIXED_LEVELS: i32 = 2;
/// Largest share of rendered pixels whose hit records (ray decisions) may differ between
/// the fixed and the scalar path: the fixed contract's 0.1 %.
const MAX_DIFFER: f64 = 0.001;

/// What a case expects of the fixed-point path.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Fixed {
    /// It renders within its budget of the scalar path: at most [`FIXED_LEVELS`] where the
    /// hit records agree, and at most [`MAX_DIFFER`] of the pixels with differing ones.
    Budget,
    /// It renders (ill-conditioned pixels, where a rounding of the hit point flips the
    /// answer and the budget does not apply).
    Renders,
    /// It refuses the scene as out of its range.
    Refused,
}

const ENCODINGS: [Encoding; 4] = [
    Encoding::LINEAR,
    Encoding::LINEAR.dithered(),
    Encoding::SRGB,
    Encoding::SRGB.dithered(),
];

/// Renders rows `ys` of `scene` at `w × h` in every path; asserts every channel is finite and
/// non-negative, hit records name existing spheres and lights, the float paths are
/// bit-identical (with every encoding too), and the fixed path is within its budget.
/// Returns the scalar rows.
fn rows<const SN: usize, const LN: usize>(
    scene: &Scene<SN, LN>,
    w: u32,
    h: u32,
    ys: &[u32],
) -> Vec<Row> {
    rows_checked(scene, w, h, ys, Fixed::Budget)
}

/// Row `y` of `r` with encoding `e` in Rgb565, Bgr565 and Gray8, and as their bytes.
fn encoded<R: Render + Clone>(
    r: &R,
    y: u32,
    e: Encoding,
) -> (Vec<Rgb565>, Vec<Bgr565>, Vec<Gray8>, Vec<u8>) {
    let r = r.clone().with_encoding(e);
    let w = r.width() as usize;
    let (mut a, mut b, mut c) = (
        vec![Rgb565::default(); w],
        vec![Bgr565::default(); w],
        vec![Gray8::default(); w],
    );
    r.render_line(y, &mut a).expect("row renders");
    r.render_line(y, &mut b).expect("row renders");
    r.render_line(y, &mut c).expect("row renders");
    let mut bytes = vec![0u8; 5 * w];
    let (b565, rest) = bytes.split_at_mut(2 * w);
    let (b_bgr, b_gray) = rest.split_at_mut(2 * w);
    r.render_line_bytes::<Rgb565>(y, b565).expect("row renders");
    r.render_line_bytes::<Bgr565>(y, b_bgr)
        .expect("row renders");
    r.render_line_bytes::<Gray8>(y, b_gray)
        .expect("row renders");
    (a, b, c, bytes)
}

/// [`rows`], with what the fixed path must do.
fn rows_checked<const SN: usize, const LN: usize>(
    scene: &Scene<SN, LN>,
    w: u32,
    h: u32,
    ys: &[u32],
    fixed: Fixed,
) -> Vec<Row> {
    let scalar = Prepared::<Scalar, SN, LN>::new(scene, w, h).unwrap();
    let simd4 = Prepared::<Simd4, SN, LN>::new(scene, w, h).unwrap();
    let simd8 = Prepared::<Simd8, SN, LN>::new(scene, w, h).unwrap();
    let fixed_frame = match (PreparedFixed::<SN, LN>::new(scene, w, h), fixed) {
        (Ok(f), Fixed::Budget | Fixed::Renders) => Some(f),
        (Err(RenderError::OutOfFixedRange { .. }), Fixed::Refused) => None,
        (Ok(_), Fixed::Refused) => panic!("fixed path: accepted a scene it should refuse"),
        (Err(e), _) => panic!("fixed path: {e}"),
    };
    let lights = scene.lights().len();
    let (mut pixels, mut differ) = (0usize, 0usize);
    let out = ys
        .iter()
        .map(|&y| {
            let want = render(&scalar, y);
            for (x, (c, hit)) in want.linear.iter().zip(&want.hits).enumerate() {
                for v in [c.r, c.g, c.b] {
                    assert!(v.is_finite() && v >= 0.0, "({x},{y}): {c:?}");
                }
                if let Some(k) = hit.sphere {
                    assert!((k as usize) < scene.spheres().len(), "({x},{y}): {hit:?}");
                }
                assert_eq!(hit.shadowed >> lights, 0, "({x},{y}): {hit:?}");
            }
            for (name, got) in [("simd4", render(&simd4, y)), ("simd8", render(&simd8, y))] {
                assert!(
                    bits(&got) == bits(&want),
                    "{name} row {y} differs from scalar"
                );
                assert!(got.hits == want.hits, "{name} row {y}: hit records differ");
            }
            for e in ENCODINGS {
                let want = encoded(&scalar, y, e);
                assert!(encoded(&simd4, y, e) == want, "simd4 row {y}, {e:?}");
                assert!(encoded(&simd8, y, e) == want, "simd8 row {y}, {e:?}");
            }
            if let Some(f) = &fixed_frame {
                let got = render(f, y);
                for e in ENCODINGS {
                    encoded(f, y, e);
                }
                if fixed == Fixed::Renders {
                    return want;
                }
                let (a, b) = (rgb888(f, y), rgb888(&scalar, y));
                for x in 0..w as usize {
                    pixels += 1;
                    if got.hits[x] != want.hits[x] {
                        differ += 1;
                        continue;
                    }
                    let levels = [(a[x].r, b[x].r), (a[x].g, b[x].g), (a[x].b, b[x].b)]
                        .map(|(p, q)| (p as i32 - q as i32).abs());
                    assert!(
                        levels.iter().all(|&l| l <= FIXED_LEVELS),
                        "fixed ({x},{y}): {:?} vs scalar {:?}",
                        a[x],
                        b[x]
                    );
                }
            }
            want
        })
        .collect();
    assert!(
        differ as f64 <= MAX_DIFFER * pixels as f64,
        "fixed path: {differ} of {pixels} pixels' ray decisions differ from the scalar path's"
    );
    out
}

fn rgb888<R: Render>(frame: &R, y: u32) -> Vec<Rgb888> {
    let mut px = vec![Rgb888::default(); frame.width() as usize];
    frame.render_line(y, &mut px).expect("row renders");
    px
}

/// Every row of a small frame.
fn frame<const SN: usize, const LN: usize>(scene: &Scene<SN, LN>, w: u32, h: u32) -> Vec<Row> {
    rows(scene, w, h, &(0..h).collect::<Vec<_>>())
}

// ---------------------------------------------------------------------------------------------
// NaN and ±inf

const NON_FINITE: [f32; 3] = [f32::NAN, f32::INFINITY, f32::NEG_INFINITY];

/// The three vectors with `bad` in one component.
fn with_bad(v: Vec3, bad: f32) -> [Vec3; 3] {
    [
        Vec3::new(bad, v.y, v.z),
        Vec3::new(v.x, bad, v.z),
        Vec3::new(v.x, v.y, bad),
    ]
}

fn rgb_with_bad(c: LinearRgb, bad: f32) -> [LinearRgb; 3] {
    with_bad(Vec3::new(c.r, c.g, c.b), bad).map(|v| LinearRgb::new(v.x, v.y, v.z))
}

#[test]
fn nan_or_inf_in_any_camera_field_is_refused() {
    let want = |field| invalid(Item::Camera, field, Problem::NotFinite);
    for bad in NON_FINITE {
        let c = camera();
        for v in with_bad(c.position, bad) {
            let c = Camera { position: v, ..c };
            assert_eq!(camera_error(c), want("position"));
        }
        for v in with_bad(c.look_at, bad) {
            let c = Camera { look_at: v, ..c };
            assert_eq!(camera_error(c), want("look_at"));
        }
        for v in with_bad(c.up, bad) {
            let c = Camera { up: v, ..c };
            assert_eq!(camera_error(c), want("up"));
        }
        let c = Camera {
            vfov_degrees: bad,
            ..c
        };
        assert_eq!(camera_error(c), want("vfov"));
    }
}

#[test]
fn nan_or_inf_in_the_background_is_refused() {
    for bad in NON_FINITE {
        for c in rgb_with_bad(LinearRgb::new(0.1, 0.2, 0.3), bad) {
            assert_eq!(
                S::new(camera(), c).unwrap_err(),
                invalid(Item::Background, "background", Problem::NotFinite)
            );
        }
    }
}

#[test]
fn nan_or_inf_in_any_sphere_field_is_refused() {
    let want = |field| invalid(Item::Sphere(0), field, Problem::NotFinite);
    let m = Material::default();
    let with = |material| Sphere {
        material,
        ..sphere()
    };
    for bad in NON_FINITE {
        for v in with_bad(sphere().center, bad) {
            let s = Sphere {
                center: v,
                ..sphere()
            };
            assert_eq!(sphere_error(s), want("center"));
        }
        let s = Sphere {
            radius: bad,
            ..sphere()
        };
        assert_eq!(sphere_error(s), want("radius"));
        for albedo in rgb_with_bad(m.albedo, bad) {
            assert_eq!(sphere_error(with(Material { albedo, ..m })), want("albedo"));
        }
        assert_eq!(sphere_error(with(Material { kd: bad, ..m })), want("kd"));
        assert_eq!(sphere_error(with(Material { ks: bad, ..m })), want("ks"));
        let shininess = Material {
            shininess: bad,
            ..m
        };
        assert_eq!(sphere_error(with(shininess)), want("shininess"));
    }
}

#[test]
fn nan_or_inf_in_any_light_field_is_refused() {
    let want = |field| invalid(Item::Light(0), field, Problem::NotFinite);
    let white = LinearRgb::new(1.0, 1.0, 1.0);
    for bad in NON_FINITE {
        for direction in with_bad(Vec3::new(-1.0, -1.0, -1.0), bad) {
            let l = Light::Distant {
                direction,
                color: white,
                intensity: 1.0,
            };
            assert_eq!(light_error(l), want("direction"));
        }
        for position in with_bad(Vec3::new(1.0, 2.0, 3.0), bad) {
            assert_eq!(light_error(point(position)), want("position"));
        }
        for color in rgb_with_bad(white, bad) {
            let distant = Light::Distant {
                direction: Vec3::new(0.0, -1.0, 0.0),
                color,
                intensity: 1.0,
            };
            let point = Light::Point {
                position: Vec3::new(0.0, 3.0, 0.0),
                color,
                intensity: 1.0,
                radius: 0.0,
            };
            assert_eq!(light_error(distant), want("color"));
            assert_eq!(light_error(point), want("color"));
        }
        let distant = Light::Distant {
            direction: Vec3::new(0.0, -1.0, 0.0),
            color: white,
            intensity: bad,
        };
        let point = Light::Point {
            position: Vec3::new(0.0, 3.0, 0.0),
            color: white,
            intensity: bad,
            radius: 0.0,
        };
        assert_eq!(light_error(distant), want("intensity"));
        assert_eq!(light_error(point), want("intensity"));
    }
}

// ---------------------------------------------------------------------------------------------
// Radius and shininess

fn radius_error(radius: f32) -> SceneError {
    sphere_error(Sphere { radius, ..sphere() })
}

fn shininess_error(shininess: f32) -> SceneError {
    sphere_error(Sphere {
        material: Material {
            shininess,
            ..Material::default()
        },
        ..sphere()
    })
}

#[test]
fn radius_zero_is_refused() {
    let want = invalid(Item::Sphere(0), "radius", Problem::NotPositive);
    assert_eq!(radius_error(0.0), want);
    assert_eq!(radius_error(-0.0), want);
}

#[test]
fn radius_negative_is_refused() {
    let want = invalid(Item::Sphere(0), "radius", Problem::NotPositive);
    assert_eq!(radius_error(-1.0), want);
    assert_eq!(radius_error(-1.0e-45), want);
    assert_eq!(radius_error(f32::MIN), want);
}

#[test]
fn radius_1e30_is_refused() {
    let want = invalid(Item::Sphere(0), "radius", Problem::TooLarge);
    assert_eq!(radius_error(1.0e30), want);
    assert_eq!(radius_error(f32::MAX), want);
    // The largest accepted radius renders: a sphere around the camera fills the frame.
    let mut s = empty_scene();
    s.add_sphere(Sphere {
        radius: MAX_COORDINATE,
        ..sphere()
    })
    .unwrap();
    s.add_light(point(Vec3::new(0.0, 0.0, 4.0))).unwrap();
    // A light inside the sphere around the camera: the fixed path's rounding puts it on
    // either side of nearby surfaces, so its shadow decisions are ill-conditioned.
    for row in rows_checked(&s, 9, 7, &(0..7).collect::<Vec<_>>(), Fixed::Renders) {
        assert!(row.hits.iter().all(|h| h.sphere == Some(0)));
    }
}

#[test]
fn shininess_zero_is_refused() {
    let want = invalid(Item::Sphere(0), "shininess", Problem::NotPositive);
    assert_eq!(shininess_error(0.0), want);
    assert_eq!(shininess_error(-0.0), want);
}

#[test]
fn shininess_negative_is_refused() {
    let want = invalid(Item::Sphere(0), "shininess", Problem::NotPositive);
    assert_eq!(shininess_error(-1.0), want);
    assert_eq!(shininess_error(-1.0e-45), want);
}

#[test]
fn shininess_1e6_gives_a_finite_pinpoint_highlight() {
    assert_eq!(MAX_SHININESS, 1.0e6);
    assert_eq!(
        shininess_error(1.000_000_1e6),
        invalid(Item::Sphere(0), "shininess", Problem::TooLarge)
    );
    for model in [Model::Phong, Model::BlinnPhong] {
        let mut s = empty_scene();
        let material = Material {
            shininess: 1.0e6,
            kd: 0.0,
            ks: 1.0,
            model,
            ..Material::default()
        };
        s.add_sphere(Sphere {
            material,
            ..sphere()
        })
        .unwrap();
        // Light from behind the camera: the highlight is at the sphere's centre pixel.
        s.add_light(Light::Distant {
            direction: Vec3::new(0.0, 0.0, -1.0),
            color: LinearRgb::new(1.0, 1.0, 1.0),
            intensity: 1.0,
        })
        .unwrap();
        let rows = frame(&s, 33, 33);
        let centre = rows[16].linear[16];
        assert!(
            centre.r > 0.9,
            "{model:?}: the highlight's centre is {centre:?}"
        );
        // At n = 1e6 the lobe is a pinpoint: one pixel off centre it is black.
        assert!(rows[16].linear[14].r < 1.0e-6, "{model:?}");
    }
}

// ---------------------------------------------------------------------------------------------
// Negative weights, zero directions, degenerate cameras

#[test]
fn negative_kd_ks_or_albedo_is_refused() {
    let m = Material::default();
    let with = |material| Sphere {
        material,
        ..sphere()
    };
    let want = |field| invalid(Item::Sphere(0), field, Problem::Negative);
    assert_eq!(sphere_error(with(Material { kd: -0.5, ..m })), want("kd"));
    assert_eq!(sphere_error(with(Material { ks: -1e-45, ..m })), want("ks"));
    for albedo in rgb_with_bad(m.albedo, -0.1) {
        assert_eq!(sphere_error(with(Material { albedo, ..m })), want("albedo"));
    }
    // Too large is refused too.
    let too_large = invalid(Item::Sphere(0), "kd", Problem::TooLarge);
    assert_eq!(
        sphere_error(with(Material {
            kd: MAX_VALUE * 2.0,
            ..m
        })),
        too_large
    );
}

#[test]
fn zero_length_light_direction_is_refused() {
    for direction in [Vec3::new(0.0, 0.0, 0.0), Vec3::new(-0.0, 0.0, -0.0)] {
        let l = Light::Distant {
            direction,
            color: LinearRgb::new(1.0, 1.0, 1.0),
            intensity: 1.0,
        };
        assert_eq!(
            light_error(l),
            invalid(Item::Light(0), "direction", Problem::ZeroLength)
        );
    }
    let c = Camera {
        up: Vec3::new(0.0, 0.0, 0.0),
        ..camera()
    };
    assert_eq!(
        camera_error(c),
        invalid(Item::Camera, "up", Problem::ZeroLength)
    );
}

#[test]
fn look_at_equal_to_position_is_refused() {
    for p in [Vec3::new(0.0, 0.0, 5.0), Vec3::new(1.0e6, -1.0e6, 0.0)] {
        let c = Camera {
            position: p,
            look_at: p,
            ..camera()
        };
        assert_eq!(
            camera_error(c),
            invalid(Item::Camera, "look_at", Problem::LookAtEqualsPosition)
        );
    }
}

#[test]
fn up_parallel_to_the_view_is_refused() {
    // The camera looks along −z; up along ±z (any length) is parallel.
    for up in [
        Vec3::new(0.0, 0.0, 1.0),
        Vec3::new(0.0, 0.0, -3.0),
        Vec3::new(1.0e-4, 0.0, 1.0), // sine 1e-4, below MIN_UP_SINE
    ] {
        let c = Camera { up, ..camera() };
        assert_eq!(
            camera_error(c),
            invalid(Item::Camera, "up", Problem::UpParallelToView)
        );
    }
}

#[test]
fn camera_inside_a_sphere_sees_only_that_sphere() {
    let mut s = empty_scene();
    s.add_sphere(Sphere {
        center: Vec3::new(0.0, 0.0, 5.0),
        radius: 2.0,
        ..sphere()
    })
    .unwrap();
    // A sphere outside, in front of the camera: hidden by the one around it.
    s.add_sphere(sphere()).unwrap();
    s.add_light(point(Vec3::new(0.0, 0.5, 5.0))).unwrap();
    // Every pixel sees the inside of sphere 0 (whose outward normals face away from the eye,
    // so it is dark: the model has no two-sided surfaces).
    for row in frame(&s, 17, 11) {
        assert!(
            row.hits.iter().all(|h| h.sphere == Some(0)),
            "{:?}",
            row.hits
        );
    }
}

#[test]
fn light_inside_an_opaque_sphere_lights_nothing_outside() {
    let mut s = empty_scene();
    // The light sits at the centre of sphere 1; sphere 0 is outside it.
    s.add_sphere(Sphere {
        center: Vec3::new(-1.2, 0.0, 0.0),
        ..sphere()
    })
    .unwrap();
    s.add_sphere(Sphere {
        center: Vec3::new(1.2, 0.0, 0.0),
        ..sphere()
    })
    .unwrap();
    s.add_light(point(Vec3::new(1.2, 0.0, 0.0))).unwrap();
    let mut seen = [0usize; 2];
    // Ill-conditioned for the fixed path: the light is inside a sphere, where its rounding
    // decides which side of the surface the light is on.
    for row in rows_checked(&s, 31, 15, &(0..15).collect::<Vec<_>>(), Fixed::Renders) {
        for (c, h) in row.linear.iter().zip(&row.hits) {
            match h.sphere {
                Some(0) => {
                    assert_eq!(h.shadowed, 1, "sphere 0 must be shadowed from the light");
                    seen[0] += 1;
                }
                Some(1) => seen[1] += 1,
                _ => continue,
            }
            // Outside the light's sphere everything is dark: blocked, or facing away.
            assert_eq!(*c, LinearRgb::new(0.0, 0.0, 0.0), "{h:?}");
        }
    }
    assert!(seen[0] > 20 && seen[1] > 20, "{seen:?}");
}

#[test]
fn point_light_exactly_at_a_hit_point_is_finite() {
    // The centre pixel of an odd-sized frame looks straight down −z and hits the unit sphere
    // at exactly (0, 0, 1): the light sits there, at distance zero.
    let mut s = empty_scene();
    s.add_sphere(sphere()).unwrap();
    s.add_light(point(Vec3::new(0.0, 0.0, 1.0))).unwrap();
    // The fixed path rounds the hit point to 2^-16 units, which puts the light a hair above
    // the surface, fully lit and saturated: ill-conditioned, so only "renders" is asserted.
    let rows = rows_checked(&s, 9, 9, &(0..9).collect::<Vec<_>>(), Fixed::Renders);
    assert_eq!(rows[4].hits[4].sphere, Some(0));
    // Zero distance: no direction to the light, so no diffuse or specular term (not NaN).
    assert_eq!(rows[4].linear[4], LinearRgb::new(0.0, 0.0, 0.0));
}

#[test]
fn brightest_point_light_on_a_surface_saturates_without_overflow() {
    // The largest accepted weights, and the brightest light one f32 step above the surface:
    // kd·albedo·arriving exceeds f32::MAX unless the kernel bounds it.
    let mut s = empty_scene();
    let material = Material {
        albedo: LinearRgb::new(MAX_VALUE, MAX_VALUE, MAX_VALUE),
        kd: MAX_VALUE,
        ks: MAX_VALUE,
        shininess: 1.0,
        model: Model::Phong,
    };
    s.add_sphere(Sphere {
        material,
        ..sphere()
    })
    .unwrap();
    for _ in 0..4 {
        s.add_light(Light::Point {
            position: Vec3::new(0.0, 0.0, 1.000_000_1),
            color: LinearRgb::new(MAX_VALUE, MAX_VALUE, MAX_VALUE),
            intensity: MAX_INTENSITY,
            radius: 0.0,
        })
        .unwrap();
    }
    // kd·albedo is far above the fixed path's largest level: it refuses the scene.
    let rows = rows_checked(&s, 9, 9, &(0..9).collect::<Vec<_>>(), Fixed::Refused);
    let centre = rows[4].linear[4];
    assert!(centre.r > 1.0e30, "{centre:?}");
    let mut px = [Rgb888::default(); 9];
    Prepared::<Scalar>::new(&s, 9, 9)
        .unwrap()
        .render_line(4, &mut px)
        .unwrap();
    assert_eq!(
        px[4],
        Rgb888 {
            r: 255,
            g: 255,
            b: 255
        }
    );
}

// ---------------------------------------------------------------------------------------------
// The models' options: metal, ior, lobes

fn spec(surface: Surface, more_lobes: [Lobe; MORE_LOBES]) -> Specular {
    Specular {
        surface,
        more_lobes,
    }
}

fn normalized_sphere(blinn: bool, spec: Specular, kd: f32, ks: f32, shininess: f32) -> Sphere {
    let model = if blinn {
        Model::NormalizedBlinnPhong(spec)
    } else {
        Model::NormalizedPhong(spec)
    };
    Sphere {
        material: Material {
            albedo: LinearRgb::new(0.6, 0.3, 0.2),
            kd,
            ks,
            shininess,
            model,
        },
        ..sphere()
    }
}

fn ior_error(ior: f32) -> SceneError {
    let s = spec(
        Surface::Dielectric { ior: Some(ior) },
        [Lobe::NONE; MORE_LOBES],
    );
    sphere_error(normalized_sphere(false, s, 0.5, 0.5, 20.0))
}

/// A sphere with lobe `k` (1 or 2) replaced by `lobe`.
fn lobe_error(k: usize, lobe: Lobe) -> SceneError {
    let mut more = [Lobe::NONE; MORE_LOBES];
    more[k - 1] = lobe;
    let s = spec(Surface::Dielectric { ior: None }, more);
    sphere_error(normalized_sphere(true, s, 0.5, 0.3, 20.0))
}

/// One sphere with the model of `s` under a light from behind the camera.
fn model_scene(s: Sphere) -> S {
    let mut scene = empty_scene();
    scene.add_sphere(s).unwrap();
    scene
        .add_light(Light::Distant {
            direction: Vec3::new(0.2, -0.3, -1.0),
            color: LinearRgb::new(1.0, 1.0, 1.0),
            intensity: 1.5,
        })
        .unwrap();
    scene
}

#[test]
fn ior_nan_or_inf_is_refused() {
    for bad in NON_FINITE {
        assert_eq!(
            ior_error(bad),
            invalid(Item::Sphere(0), "ior", Problem::NotFinite)
        );
    }
}

#[test]
fn ior_of_one_or_below_is_refused() {
    let want = invalid(Item::Sphere(0), "ior", Problem::NotAboveOne);
    for ior in [1.0, 0.999_999_94, 0.5, 0.0, -0.0, -1.5, f32::MIN] {
        assert_eq!(ior_error(ior), want, "ior {ior}");
    }
}

#[test]
fn ior_above_max_value_is_refused() {
    let want = invalid(Item::Sphere(0), "ior", Problem::TooLarge);
    assert_eq!(ior_error(1.000_000_1e6), want);
    assert_eq!(ior_error(f32::MAX), want);
}

#[test]
fn ior_just_above_one_or_at_the_limit_renders() {
    // Just above 1 (F₀ ≈ 0: the highlight vanishes at normal incidence) and at MAX_VALUE
    // (F₀ ≈ 1: a mirror-like highlight and no diffuse light left).
    for ior in [1.000_000_1, MAX_VALUE] {
        for blinn in [false, true] {
            let s = spec(
                Surface::Dielectric { ior: Some(ior) },
                [Lobe::NONE; MORE_LOBES],
            );
            let scene = model_scene(normalized_sphere(blinn, s, 0.5, 0.5, 40.0));
            let rows = frame(&scene, 17, 17);
            assert_eq!(rows[8].hits[8].sphere, Some(0));
        }
    }
}

#[test]
fn lobe_weight_negative_is_refused() {
    for (k, field) in [(1, "lobes[1].weight"), (2, "lobes[2].weight")] {
        for weight in [-1.0e-45, -0.5, f32::MIN] {
            let lobe = Lobe {
                weight,
                shininess: 10.0,
            };
            assert_eq!(
                lobe_error(k, lobe),
                invalid(Item::Sphere(0), field, Problem::Negative)
            );
        }
    }
}

#[test]
fn lobe_weight_nan_inf_or_too_large_is_refused() {
    for bad in NON_FINITE {
        let lobe = Lobe {
            weight: bad,
            shininess: 10.0,
        };
        assert_eq!(
            lobe_error(2, lobe),
            invalid(Item::Sphere(0), "lobes[2].weight", Problem::NotFinite)
        );
    }
    let lobe = Lobe {
        weight: MAX_VALUE * 2.0,
        shininess: 10.0,
    };
    assert_eq!(
        lobe_error(1, lobe),
        invalid(Item::Sphere(0), "lobes[1].weight", Problem::TooLarge)
    );
}

#[test]
fn lobe_shininess_nan_zero_negative_or_too_large_is_refused() {
    let field = "lobes[1].shininess";
    let cases = [
        (f32::NAN, Problem::NotFinite),
        (f32::INFINITY, Problem::NotFinite),
        (0.0, Problem::NotPositive),
        (-0.0, Problem::NotPositive),
        (-3.0, Problem::NotPositive),
        (1.000_000_1e6, Problem::TooLarge),
    ];
    for (shininess, problem) in cases {
        let lobe = Lobe {
            weight: 0.2,
            shininess,
        };
        assert_eq!(
            lobe_error(1, lobe),
            invalid(Item::Sphere(0), field, problem),
            "shininess {shininess}"
        );
    }
    // An absent lobe (weight 0) is still checked: its exponent must be valid too.
    let absent = Lobe {
        weight: 0.0,
        shininess: f32::NAN,
    };
    assert_eq!(
        lobe_error(2, absent),
        invalid(Item::Sphere(0), "lobes[2].shininess", Problem::NotFinite)
    );
}

#[test]
fn lobes_with_extreme_exponents_render() {
    // Three lobes at once: n = 10⁻³ (nearly constant over the hemisphere), 1 and 10⁶ (a
    // pinpoint), with the largest weight: finite, saturated where it is bright.
    let more = [
        Lobe {
            weight: MAX_VALUE,
            shininess: 1.0e-3,
        },
        Lobe {
            weight: 1.0,
            shininess: MAX_SHININESS,
        },
    ];
    for blinn in [false, true] {
        let s = spec(Surface::Dielectric { ior: None }, more);
        let scene = model_scene(normalized_sphere(blinn, s, 0.2, 1.0, 1.0));
        // Ill-conditioned: a lobe of n = 10⁻³ has an infinite slope at cos = 0, where a
        // rounding of the hit point moves the pixel by many levels.
        let rows = rows_checked(&scene, 15, 15, &(0..15).collect::<Vec<_>>(), Fixed::Renders);
        assert!(rows[7].linear[7].r > 1.0, "{:?}", rows[7].linear[7]);
    }
}

#[test]
fn no_specular_lobe_at_all_is_the_diffuse_lobe_alone() {
    // ks = 0 and lobes 1 and 2 absent: normalized Phong is Lambert, bit for bit.
    let s = spec(Surface::Dielectric { ior: None }, [Lobe::NONE; MORE_LOBES]);
    let phong = normalized_sphere(false, s, 0.8, 0.0, 50.0);
    let lambert = Sphere {
        material: Material {
            model: Model::Lambert,
            ..phong.material
        },
        ..phong
    };
    // Under a point light both take the general kernel, whose normalized formulas this
    // holds; under distant lights Lambert takes the narrow kernel, as a classic sphere with
    // no lobe (`tests/kernel_choice.rs` holds that one to the reference).
    let lit = |s: Sphere| {
        let mut scene = empty_scene();
        scene.add_sphere(s).unwrap();
        scene
            .add_light(Light::Point {
                position: Vec3::new(2.0, 3.0, 6.0),
                color: LinearRgb::new(1.0, 1.0, 1.0),
                intensity: 150.0,
                radius: 0.0,
            })
            .unwrap();
        scene
    };
    let (a, b) = (frame(&lit(phong), 13, 13), frame(&lit(lambert), 13, 13));
    let lit_pixel =
        |r: &Row| (r.hits.iter().zip(&r.linear)).any(|(h, c)| h.sphere.is_some() && c.r > 0.0);
    assert!(a.iter().any(lit_pixel), "the sphere is lit");
    for (ra, rb) in a.iter().zip(&b) {
        assert!(bits(ra) == bits(rb));
    }
}

#[test]
fn lambert_ignores_ks_and_shininess() {
    let with = |ks, shininess| {
        let s = Sphere {
            material: Material {
                albedo: LinearRgb::new(0.5, 0.4, 0.3),
                kd: 0.9,
                ks,
                shininess,
                model: Model::Lambert,
            },
            ..sphere()
        };
        frame(&model_scene(s), 11, 11)
    };
    let (a, b) = (with(0.0, 1.0), with(MAX_VALUE, 1.0e-3));
    for (ra, rb) in a.iter().zip(&b) {
        assert!(bits(ra) == bits(rb));
    }
}

#[test]
fn a_metal_ignores_kd_and_albedo_and_tints_its_highlight() {
    for metal in Metal::ALL {
        let s = spec(Surface::Metal(metal), [Lobe::NONE; MORE_LOBES]);
        let dark = normalized_sphere(true, s, 0.0, 1.0, 30.0);
        let bright = Sphere {
            material: Material {
                albedo: LinearRgb::new(MAX_VALUE, MAX_VALUE, MAX_VALUE),
                kd: MAX_VALUE,
                ..dark.material
            },
            ..dark
        };
        let a = frame(&model_scene(dark), 21, 21);
        // kd and albedo far above the fixed path's levels: a metal's diffuse level is 0,
        // so that path takes it too, within its budget.
        let b = rows_checked(
            &model_scene(bright),
            21,
            21,
            &(0..21).collect::<Vec<_>>(),
            Fixed::Budget,
        );
        for (ra, rb) in a.iter().zip(&b) {
            assert!(
                bits(ra) == bits(rb),
                "{metal:?}: kd or albedo changed a pixel"
            );
        }
        // The brightest pixel is in the metal's colour: its channels in F₀'s order.
        let top = a
            .iter()
            .flat_map(|r| r.linear.iter())
            .max_by(|p, q| p.g.total_cmp(&q.g))
            .unwrap();
        let f0 = metal.f0();
        assert!(top.r >= top.g && top.g >= top.b, "{metal:?}: {top:?}");
        assert!(f0.r >= f0.g && f0.g >= f0.b);
    }
}

#[test]
fn weights_far_above_energy_conservation_saturate_finitely() {
    // kd + Σ w = 3·10⁶: accepted (only flagged), finite, white where lit.
    let more = [
        Lobe {
            weight: MAX_VALUE,
            shininess: 2.0,
        },
        Lobe {
            weight: MAX_VALUE,
            shininess: 10.0,
        },
    ];
    let s = spec(Surface::Dielectric { ior: Some(1.5) }, more);
    let sphere = Sphere {
        material: Material {
            albedo: LinearRgb::new(1.0, 1.0, 1.0),
            ..normalized_sphere(false, s, MAX_VALUE, MAX_VALUE, 5.0).material
        },
        ..sphere()
    };
    assert!(!sphere.material.is_energy_conserving());
    let scene = model_scene(sphere);
    let rows = rows_checked(&scene, 9, 9, &(0..9).collect::<Vec<_>>(), Fixed::Refused);
    assert!(rows[4].linear[4].r > 1.0e5);
    let mut px = [Gray8::default(); 9];
    Prepared::<Simd8>::new(&scene, 9, 9)
        .unwrap()
        .with_encoding(Encoding::SRGB.dithered())
        .render_line(4, &mut px)
        .unwrap();
    assert_eq!(px[4], Gray8(255));
}

#[test]
fn black_stays_black_and_white_stays_white_in_every_encoding() {
    // Dithering must not lift an exact 0 or lower an exact 1 (or more), in any format.
    for (bg, want) in [
        (0.0, [0u8, 0, 0]),
        (1.0, [255, 255, 255]),
        (MAX_VALUE, [255, 255, 255]),
    ] {
        let scene = S::new(camera(), LinearRgb::new(bg, bg, bg)).unwrap();
        let f = Prepared::<Simd4>::new(&scene, 13, 6).unwrap();
        let fixed = PreparedFixed::new(&scene, 13, 6);
        for e in ENCODINGS {
            for y in 0..6 {
                let (a, b, c, _) = encoded(&f, y, e);
                assert!(
                    a.iter().all(|p| p.to_bytes()
                        == Rgb565::pack(
                            want[0] as u16 >> 3,
                            want[1] as u16 >> 2,
                            want[2] as u16 >> 3
                        )
                        .to_bytes()),
                    "{bg} {e:?}"
                );
                assert!(b.iter().all(|p| p.levels() == a[0].levels()), "{bg} {e:?}");
                assert!(c.iter().all(|p| p.0 == want[0]), "{bg} {e:?}");
                if let Ok(fixed) = &fixed {
                    assert!(encoded(fixed, y, e).0 == a, "fixed {bg} {e:?}");
                }
            }
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Field of view

fn vfov_scene(vfov_degrees: f32) -> Result<S, SceneError> {
    let mut s = S::new(
        Camera {
            vfov_degrees,
            ..camera()
        },
        LinearRgb::new(0.1, 0.2, 0.3),
    )?;
    s.add_sphere(sphere())?;
    s.add_light(distant())?;
    Ok(s)
}

#[test]
fn vfov_0_is_refused() {
    let want = invalid(Item::Camera, "vfov", Problem::FieldOfViewOutOfRange);
    assert_eq!(vfov_scene(0.0).unwrap_err(), want);
    assert_eq!(vfov_scene(-0.0).unwrap_err(), want);
    assert_eq!(vfov_scene(-10.0).unwrap_err(), want);
}

#[test]
fn vfov_180_is_refused() {
    let want = invalid(Item::Camera, "vfov", Problem::FieldOfViewOutOfRange);
    assert_eq!(vfov_scene(180.0).unwrap_err(), want);
    assert_eq!(vfov_scene(360.0).unwrap_err(), want);
}

#[test]
fn vfov_1e_6_zooms_into_the_sphere() {
    let s = vfov_scene(1.0e-6).unwrap();
    // A millionth of a degree: every pixel sees the middle of the sphere.
    for row in frame(&s, 9, 7) {
        assert!(row.hits.iter().all(|h| h.sphere == Some(0)));
    }
}

#[test]
fn vfov_179_999_sees_the_sphere_as_a_dot_in_the_middle() {
    for vfov in [179.999, 179.999_98] {
        let s = vfov_scene(vfov).unwrap();
        let (w, h) = (65, 65);
        // tan(vfov/2) is beyond the fixed path's camera-plane range: it refuses.
        let rows = rows_checked(&s, w, h, &(0..h).collect::<Vec<_>>(), Fixed::Refused);
        // tan(vfov/2) is above 1e5: the sphere covers the centre pixel and nothing else.
        for (y, row) in rows.iter().enumerate() {
            for (x, hit) in row.hits.iter().enumerate() {
                let centre = x == 32 && y == 32;
                assert_eq!(hit.sphere.is_some(), centre, "vfov {vfov}: ({x},{y})");
            }
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Sizes, rows and slices

#[test]
fn width_or_height_0_is_refused() {
    let s = scene();
    for (w, h) in [
        (0, 10),
        (10, 0),
        (0, 0),
        (MAX_DIMENSION + 1, 10),
        (10, u32::MAX),
    ] {
        let want = RenderError::BadSize {
            width: w,
            height: h,
        };
        assert_eq!(Prepared::<Scalar>::new(&s, w, h).unwrap_err(), want);
        assert_eq!(Prepared::<Simd4>::new(&s, w, h).unwrap_err(), want);
        assert_eq!(Prepared::<Simd8>::new(&s, w, h).unwrap_err(), want);
    }
}

#[test]
fn width_1_renders_the_centre_column() {
    let rows = frame(&scene(), 1, 9);
    let hit: Vec<bool> = rows.iter().map(|r| r.hits[0].sphere.is_some()).collect();
    // The sphere is in the middle: the centre row hits, the top and bottom rows miss.
    assert!(hit[4] && !hit[0] && !hit[8], "{hit:?}");
}

/// Widths around the 8-lane packet: every tail length of a row.
fn check_width(w: u32) {
    let h = 9;
    let rows = frame(&scene(), w, h);
    let centre = &rows[4];
    assert_eq!(centre.hits[(w / 2) as usize].sphere, Some(0), "width {w}");
    assert_eq!(centre.hits[0].sphere, None, "width {w}");
    assert_eq!(centre.hits[w as usize - 1].sphere, None, "width {w}");
}

#[test]
fn width_7_renders() {
    check_width(7);
}

#[test]
fn width_8_renders() {
    check_width(8);
}

#[test]
fn width_9_renders() {
    check_width(9);
}

#[test]
fn width_65535_renders_a_few_rows() {
    let (w, h) = (MAX_DIMENSION, 3);
    // The frame is 65535 wide and 3 high, so the sphere is a small disc in the middle.
    // The fixed path refuses so wide a frame: tan(vfov/2)·w/h is beyond its range.
    let rows = rows_checked(&scene(), w, h, &[0, 1, 2], Fixed::Refused);
    let hit = rows[1].hits.iter().filter(|h| h.sphere.is_some()).count();
    assert!(hit > 0 && hit < 100, "{hit} pixels hit");
    assert_eq!(rows[1].hits[(w / 2) as usize].sphere, Some(0));
    // A tall one too.
    rows_of_a_tall_frame();
}

fn rows_of_a_tall_frame() {
    let h = MAX_DIMENSION;
    let rows = rows(&scene(), 3, h, &[0, h / 2, h - 1]);
    assert_eq!(rows[1].hits[1].sphere, Some(0));
    assert_eq!(rows[0].hits[1].sphere, None);
    assert_eq!(rows[2].hits[1].sphere, None);
}

fn all_paths_refuse(w: u32, y: u32, len: usize, want: RenderError) {
    fn check<R: Render>(r: &R, y: u32, len: usize, want: RenderError) {
        let mut px = vec![Rgb888::default(); len];
        assert_eq!(r.render_line(y, &mut px), Err(want));
        assert!(px.iter().all(|p| *p == Rgb888::default()), "written");
        let mut hits = vec![HitRecord::default(); len];
        assert_eq!(r.render_line(y, &mut hits), Err(want));
        let mut linear = vec![LinearRgb::default(); len];
        assert_eq!(r.render_line(y, &mut linear), Err(want));
    }
    let s = scene();
    check(&Prepared::<Scalar>::new(&s, w, 5).unwrap(), y, len, want);
    check(&Prepared::<Simd4>::new(&s, w, 5).unwrap(), y, len, want);
    check(&Prepared::<Simd8>::new(&s, w, 5).unwrap(), y, len, want);
}

#[test]
fn row_slice_one_pixel_short_is_refused() {
    for w in [1, 8, 9] {
        let want = RenderError::LineLength {
            expected: w as usize,
            got: w as usize - 1,
        };
        all_paths_refuse(w, 0, w as usize - 1, want);
    }
}

#[test]
fn row_slice_one_pixel_long_is_refused() {
    for w in [1, 8, 9] {
        let want = RenderError::LineLength {
            expected: w as usize,
            got: w as usize + 1,
        };
        all_paths_refuse(w, 0, w as usize + 1, want);
    }
}

#[test]
fn y_out_of_range_is_refused() {
    for y in [5, 6, u32::MAX] {
        all_paths_refuse(8, y, 8, RenderError::RowOutOfRange { y, height: 5 });
    }
}

#[test]
fn frame_slice_of_the_wrong_length_is_refused() {
    let f = Prepared::<Simd8>::new(&scene(), 8, 5).unwrap();
    for len in [39, 41, 0] {
        let mut px = vec![Rgb565::default(); len];
        assert_eq!(
            f.render_frame(&mut px),
            Err(RenderError::FrameLength {
                expected: 40,
                got: len
            })
        );
    }
}

#[test]
fn capacity_overflow_is_refused() {
    let mut s: Scene<2, 1> = Scene::new(camera(), LinearRgb::default()).unwrap();
    s.add_sphere(sphere()).unwrap();
    s.add_sphere(sphere()).unwrap();
    assert_eq!(
        s.add_sphere(sphere()),
        Err(SceneError::CapacityExceeded {
            kind: ItemKind::Sphere,
            capacity: 2
        })
    );
    s.add_light(distant()).unwrap();
    assert_eq!(
        s.add_light(distant()),
        Err(SceneError::CapacityExceeded {
            kind: ItemKind::Light,
            capacity: 1
        })
    );
    assert_eq!((s.spheres().len(), s.lights().len()), (2, 1));
    // A scene with no capacity at all still renders its background.
    let empty: Scene<0, 0> = Scene::new(camera(), LinearRgb::new(0.5, 0.5, 0.5)).unwrap();
    let mut none: Scene<0, 0> = empty.clone();
    assert!(none.add_sphere(sphere()).is_err());
    for row in frame(&empty, 9, 3) {
        assert!(row
            .linear
            .iter()
            .all(|c| *c == LinearRgb::new(0.5, 0.5, 0.5)));
    }
}

// ---------------------------------------------------------------------------------------------
// Regressions found by the fuzz targets

#[test]
fn subnormal_light_direction_is_a_direction_not_nan() {
    // `Vec3::normalized` scaled by 1/max_abs, which overflows to inf for a subnormal largest
    // component: 0·inf = NaN, and the light turned every lit pixel into NaN.
    let mut s = empty_scene();
    s.add_sphere(sphere()).unwrap();
    s.add_light(Light::Distant {
        direction: Vec3::new(-1.0e-45, 0.0, -1.0e-45),
        color: LinearRgb::new(1.0, 1.0, 1.0),
        intensity: 2.0,
    })
    .unwrap();
    let rows = frame(&s, 9, 9);
    // Light travelling toward −x and −z lights the right half of the disc.
    assert!(rows[4].linear[6].r > rows[4].linear[2].r);
    assert_eq!(
        Vec3::new(1.0e-45, 0.0, 0.0).normalized(),
        Some(Vec3::new(1.0, 0.0, 0.0))
    );
}

#[test]
fn subnormal_camera_up_gives_an_upright_camera() {
    let c = Camera {
        up: Vec3::new(0.0, 1.0e-40, 0.0),
        ..camera()
    };
    let s = S::new(c, LinearRgb::default()).unwrap();
    let (right, up, forward) = s.camera_basis();
    assert_eq!(right, Vec3::new(1.0, 0.0, 0.0));
    assert_eq!(up, Vec3::new(0.0, 1.0, 0.0));
    assert_eq!(forward, Vec3::new(0.0, 0.0, -1.0));
}

#[test]
fn radius_below_min_radius_is_refused() {
    // A subnormal radius passed as positive: r² underflowed to 0, 1/r overflowed to inf, and a
    // ray through the centre shaded (P − C)·inf = NaN; tiny radii also made the scanline
    // spans miss pixels the per-pixel test hit through rounding.
    let want = invalid(Item::Sphere(0), "radius", Problem::TooSmall);
    for r in [
        1.0e-45,
        1.0e-39,
        f32::MIN_POSITIVE,
        1.0e-20,
        MIN_RADIUS * 0.99,
    ] {
        assert_eq!(radius_error(r), want, "radius {r:e}");
    }
    assert_eq!(
        want.to_string(),
        "sphere 0: `radius` is smaller than the accepted range (at least 1e-18)"
    );
    // The smallest accepted radius renders: finite, and the centre ray hits it.
    let mut s = empty_scene();
    s.add_sphere(Sphere {
        radius: MIN_RADIUS,
        ..sphere()
    })
    .unwrap();
    s.add_light(distant()).unwrap();
    // r² of the smallest radius is below the fixed path's resolution: it refuses.
    rows_checked(&s, 9, 9, &(0..9).collect::<Vec<_>>(), Fixed::Refused);
}

#[test]
fn row_tangent_to_a_sphere_keeps_its_span() {
    // The camera row's plane touches the sphere at the look_at point, and the centre pixel's
    // ray grazes it there. The span's slack was relative to the discriminant's own size,
    // which is all rounding on such a row, so the span was dropped and the pixel the
    // per-pixel test (and the f64 reference) hits was filled with the background.
    let c = Camera {
        position: Vec3::new(0.25, 4.25, 0.0),
        look_at: Vec3::new(0.0, 0.0, 0.0),
        up: Vec3::new(0.0, 0.0, -0.25),
        vfov_degrees: 6.25,
    };
    let mut s = S::new(c, LinearRgb::new(6.25, 0.0, 0.0)).unwrap();
    s.add_sphere(Sphere {
        center: Vec3::new(0.0, 0.0, 6.25),
        radius: 6.25,
        ..sphere()
    })
    .unwrap();
    for (w, h) in [(1, 1), (3, 3), (9, 9)] {
        let (x, y) = (w / 2, h / 2);
        let want = reference::shade_pixel(&s, w, h, x, y).hit;
        let spans = Prepared::<Scalar>::new(&s, w, h).unwrap();
        let naive = spans.clone().with_spans(false);
        assert_eq!(render(&naive, y).hits[x as usize], want, "{w}x{h}");
        assert_eq!(render(&spans, y).hits[x as usize], want, "{w}x{h}");
        let (a, b) = (render(&spans, y), render(&naive, y));
        assert!(bits(&a) == bits(&b) && a.hits == b.hits, "{w}x{h}");
        // The ray grazes the sphere: which side of the tangent the fixed path's rounding
        // puts it is ill-conditioned, so the fixed path is only required to render.
        rows_checked(&s, w, h, &[y], Fixed::Renders);
    }
}

#[test]
fn point_light_a_hair_from_the_hit_points_with_a_black_channel_is_not_nan() {
    // Found by the `scene` fuzz target. A field of view of 1.6e-19 degrees puts the hit points
    // of a row within 1e-19 of a point light sitting on the surface: d² is subnormal, 1/d²
    // overflowed to inf, and the light's black red channel gave 0·inf = NaN.
    let c = Camera {
        vfov_degrees: 1.643_243_9e-19,
        ..camera()
    };
    let mut s = S::new(c, LinearRgb::new(0.1, 0.2, 0.3)).unwrap();
    s.add_sphere(sphere()).unwrap();
    s.add_light(Light::Point {
        position: Vec3::new(0.0, 0.0, 1.0),
        color: LinearRgb::new(0.0, 40.0, 0.1),
        intensity: 0.2,
        radius: 0.0,
    })
    .unwrap();
    let rows = rows_checked(&s, 36, 58982, &[39322, 29491], Fixed::Renders);
    for row in &rows {
        assert!(row.hits.iter().all(|h| h.sphere == Some(0)));
        // No red arrives; green and blue are lit or black, never NaN (checked in `rows`).
        assert!(row.linear.iter().all(|c| c.r == 0.0));
    }
}
