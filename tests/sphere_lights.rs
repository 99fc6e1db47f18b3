//! Sphere lights (point lights with a radius) in the `f64` reference, and the fast paths'
//! refusal of them: the reference integrates the light's solid angle, so a sphere light
//! wholly above a diffuse surface's horizon lights it exactly as the point at its centre
//! does, a tiny one is the point light, highlights widen and shadows soften as it grows, and
//! the number of directions it takes is enough for half an 8-bit level.

use shadeline::reference::{shade_pixel, shade_pixel_with_strata, RefPixel, SPHERE_LIGHT_STRATA};
use shadeline::{
    Camera, Light, LinearRgb, Material, Model, Prepared, PreparedFixed, RenderError, Scalar, Scene,
    Sphere, Vec3,
};

const W: u32 = 64;
const H: u32 = 48;
const LIGHT: Vec3 = Vec3 {
    x: 2.0,
    y: 5.0,
    z: 1.0,
};
const BALL: Vec3 = Vec3 {
    x: 0.0,
    y: 0.7,
    z: 0.0,
};

/// A ball above a floor (a large sphere), lit by one light of radius `radius` above them;
/// `ball` false leaves the ball out. The ball's material is `ball_material`.
fn scene(radius: f32, ball: bool, ball_material: Material) -> Scene<2, 1> {
    let camera = Camera {
        position: Vec3::new(0.0, 2.5, 8.0),
        look_at: Vec3::new(0.0, 0.0, 0.0),
        up: Vec3::new(0.0, 1.0, 0.0),
        vfov_degrees: 40.0,
    };
    let mut s = Scene::new(camera, LinearRgb::new(0.0, 0.0, 0.0)).unwrap();
    s.add_sphere(Sphere {
        center: Vec3::new(0.0, -100.0, 0.0),
        radius: 99.5,
        material: Material {
            albedo: LinearRgb::new(0.8, 0.8, 0.8),
            kd: 1.0,
            ks: 0.0,
            shininess: 1.0,
            model: Model::Phong,
        },
    })
    .unwrap();
    if ball {
        s.add_sphere(Sphere {
            center: BALL,
            radius: 1.0,
            material: ball_material,
        })
        .unwrap();
    }
    let d2 = (LIGHT - BALL).dot(LIGHT - BALL);
    s.add_light(Light::Point {
        position: LIGHT,
        color: LinearRgb::new(1.0, 1.0, 1.0),
        // About 0.6 arriving at the ball.
        intensity: 4.0 * core::f32::consts::PI * d2 * 0.6,
        radius,
    })
    .unwrap();
    s
}

fn diffuse_ball() -> Material {
    Material {
        albedo: LinearRgb::new(0.9, 0.5, 0.2),
        kd: 1.0,
        ks: 0.0,
        shininess: 1.0,
        model: Model::Phong,
    }
}

fn shiny_ball() -> Material {
    Material {
        albedo: LinearRgb::new(0.0, 0.0, 0.0),
        kd: 0.0,
        ks: 1.0,
        shininess: 30.0,
        model: Model::Phong,
    }
}

fn frame(scene: &Scene<2, 1>, strata: usize) -> Vec<RefPixel> {
    let mut out = Vec::new();
    for y in 0..H {
        for x in 0..W {
            out.push(shade_pixel_with_strata(scene, W, H, x, y, strata));
        }
    }
    out
}

/// The unit normal where the primary ray of pixel `(x, y)` meets the ball, if it does.
fn ball_normal(scene: &Scene<2, 1>, x: u32, y: u32) -> Option<[f64; 3]> {
    let c = scene.camera();
    let sub = |a: Vec3, b: Vec3| [(a.x - b.x) as f64, (a.y - b.y) as f64, (a.z - b.z) as f64];
    let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let unit = |a: [f64; 3]| {
        let l = dot(a, a).sqrt();
        a.map(|v| v / l)
    };
    let cross = |a: [f64; 3], b: [f64; 3]| {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    };
    let forward = unit(sub(c.look_at, c.position));
    let right = unit(cross(
        forward,
        [c.up.x as f64, c.up.y as f64, c.up.z as f64],
    ));
    let up = cross(right, forward);
    let tan = ((c.vfov_degrees as f64).to_radians() / 2.0).tan();
    let (w, h) = (W as f64, H as f64);
    let px = (2.0 * (x as f64 + 0.5) / w - 1.0) * (w / h) * tan;
    let py = (1.0 - 2.0 * (y as f64 + 0.5) / h) * tan;
    let d = unit([0, 1, 2].map(|i| right[i] * px + up[i] * py + forward[i]));
    let oc = sub(c.position, BALL);
    let b = dot(oc, d);
    let disc = b * b - (dot(oc, oc) - 1.0);
    if disc < 0.0 {
        return None;
    }
    let t = -b - disc.sqrt();
    let p = [0, 1, 2].map(|i| oc[i] + t * d[i]);
    Some(unit(p))
}

#[test]
fn a_sphere_light_above_the_horizon_lights_a_diffuse_surface_as_its_centre_does() {
    let radius = 0.8f32;
    let area = scene(radius, true, diffuse_ball());
    let point = scene(0.0, true, diffuse_ball());
    let (mut checked, mut worst) = (0, 0.0f64);
    for y in 0..H {
        for x in 0..W {
            let Some(n) = ball_normal(&area, x, y) else {
                continue;
            };
            // The whole cone above the horizon at the hit point `P = C + N` (radius 1),
            // with a margin for the lift of the shadow rays' origin.
            let to_light = [
                LIGHT.x as f64 - BALL.x as f64 - n[0],
                LIGHT.y as f64 - BALL.y as f64 - n[1],
                LIGHT.z as f64 - BALL.z as f64 - n[2],
            ];
            let d =
                (to_light[0] * to_light[0] + to_light[1] * to_light[1] + to_light[2] * to_light[2])
                    .sqrt();
            let sin_a = radius as f64 / d;
            let cos_axis = (n[0] * to_light[0] + n[1] * to_light[1] + n[2] * to_light[2]) / d;
            if cos_axis < sin_a + 0.01 {
                continue;
            }
            let a = shade_pixel(&area, W, H, x, y);
            let p = shade_pixel(&point, W, H, x, y);
            assert_eq!(a.hit.sphere, Some(1));
            for c in 0..3 {
                let rel = (a.color[c] - p.color[c]).abs() / p.color[c];
                worst = worst.max(rel);
            }
            checked += 1;
        }
    }
    println!("{checked} ball pixels, largest relative difference {worst:.2e}");
    assert!(checked > 50, "{checked} pixels checked");
    assert!(worst < 1e-6, "relative difference {worst}");
}

#[test]
fn a_tiny_sphere_light_is_the_point_light() {
    let tiny = frame(&scene(1.0e-3, true, diffuse_ball()), SPHERE_LIGHT_STRATA);
    let point = frame(&scene(0.0, true, diffuse_ball()), SPHERE_LIGHT_STRATA);
    // Away from the shadow's edge: the pixel and its four neighbours have the same hit
    // record under the point light.
    let record = |x: i64, y: i64| {
        (x >= 0 && y >= 0 && x < W as i64 && y < H as i64)
            .then(|| point[(y * W as i64 + x) as usize].hit)
    };
    let (mut inside, mut worst, mut decisions) = (0, 0.0f64, 0);
    for y in 0..H as i64 {
        for x in 0..W as i64 {
            let i = (y * W as i64 + x) as usize;
            let (t, p) = (&tiny[i], &point[i]);
            if t.hit != p.hit {
                decisions += 1;
            }
            let edge = [(1, 0), (-1, 0), (0, 1), (0, -1)]
                .iter()
                .any(|(dx, dy)| record(x + dx, y + dy).is_some_and(|h| h != p.hit));
            if edge {
                continue;
            }
            inside += 1;
            for c in 0..3 {
                worst = worst.max((t.color[c] - p.color[c]).abs());
            }
        }
    }
    println!("{inside} pixels off the edges: largest difference {worst:.2e}; {decisions} hit records differ");
    assert!(
        inside > (W * H) as usize * 9 / 10,
        "{inside} pixels off the edges"
    );
    assert!(worst < 1e-6, "differs by {worst}");
    assert_eq!(decisions, 0);
}

/// Pixels of the ball whose specular term exceeds 1%.
fn highlight_pixels(radius: f32) -> usize {
    frame(&scene(radius, true, shiny_ball()), 24)
        .iter()
        .filter(|p| p.hit.sphere == Some(1) && p.color[0] > 0.01)
        .count()
}

#[test]
fn the_highlight_widens_as_the_light_grows() {
    let counts = [0.0f32, 0.6, 1.5].map(highlight_pixels);
    println!("highlight pixels at radius 0, 0.6, 1.5: {counts:?}");
    assert!(counts[0] > 0, "no highlight at all");
    assert!(counts[0] < counts[1] && counts[1] < counts[2], "{counts:?}");
}

/// Floor pixels in the penumbra: lit to between 2% and 98% of what they get with no ball.
fn penumbra_pixels(radius: f32) -> usize {
    let with = frame(&scene(radius, true, diffuse_ball()), 24);
    let without = frame(&scene(radius, false, diffuse_ball()), 24);
    with.iter()
        .zip(&without)
        .filter(|(w, o)| w.hit.sphere == Some(0) && o.color[0] > 1e-3)
        .filter(|(w, o)| {
            let ratio = w.color[0] / o.color[0];
            ratio > 0.02 && ratio < 0.98
        })
        .count()
}

#[test]
fn shadows_soften_as_the_light_grows() {
    let counts = [0.0f32, 0.3, 1.0].map(penumbra_pixels);
    println!("penumbra pixels at radius 0, 0.3, 1.0: {counts:?}");
    assert_eq!(counts[0], 0, "a point light casts a penumbra");
    assert!(counts[0] < counts[1] && counts[1] < counts[2], "{counts:?}");
}

#[test]
fn the_umbra_bit_is_set_only_where_the_whole_light_is_blocked() {
    let f = frame(&scene(1.0, true, diffuse_ball()), 24);
    let umbra: Vec<_> = f
        .iter()
        .filter(|p| p.hit.sphere == Some(0) && p.hit.shadowed & 1 == 1)
        .collect();
    assert!(!umbra.is_empty(), "no umbra on the floor");
    assert!(
        umbra.iter().all(|p| p.color == [0.0; 3]),
        "a lit pixel in the umbra"
    );
}

#[test]
fn the_reference_takes_enough_directions_for_half_a_level() {
    let s = scene(1.0, true, diffuse_ball());
    let (fine, coarse) = (
        frame(&s, 2 * SPHERE_LIGHT_STRATA),
        frame(&s, SPHERE_LIGHT_STRATA),
    );
    let worst = fine
        .iter()
        .zip(&coarse)
        .flat_map(|(f, c)| (0..3).map(move |i| (f.color[i] - c.color[i]).abs()))
        .fold(0.0f64, f64::max);
    println!(
        "{} against {} strata: largest difference {:.3} of an 8-bit level",
        SPHERE_LIGHT_STRATA,
        2 * SPHERE_LIGHT_STRATA,
        worst * 255.0
    );
    assert!(worst * 255.0 < 0.5, "{} levels", worst * 255.0);
}

#[test]
fn the_fast_paths_refuse_a_sphere_light_and_take_radius_zero() {
    let area = scene(0.5, true, diffuse_ball());
    assert_eq!(
        Prepared::<Scalar, 2, 1>::new(&area, W, H).err(),
        Some(RenderError::SphereLight { light: 0 })
    );
    assert_eq!(
        PreparedFixed::new(&area, W, H).err(),
        Some(RenderError::SphereLight { light: 0 })
    );
    let message = RenderError::SphereLight { light: 0 }.to_string();
    assert!(
        message.contains("light 0") && message.contains("radius"),
        "{message}"
    );
    let point = scene(0.0, true, diffuse_ball());
    assert!(Prepared::<Scalar, 2, 1>::new(&point, W, H).is_ok());
    assert!(PreparedFixed::new(&point, W, H).is_ok());
}
