//! Analytic anti-aliasing of the silhouettes (`with_antialiasing`): the scalar and SIMD paths
//! give the same bits with it on, it changes only pixels next to an outline, and it blends
//! them between the colours on either side. Its accuracy against a supersampled truth is
//! measured by the harness (`shadeline compare`, `harness/tests/edges.rs`).

#![cfg(feature = "antialias")]

mod common;

use common::{frame, random_scenes, random_scenes_all_models};
use shadeline::*;

/// Frames of a scene at a size with anti-aliasing on, on the three float widths.
fn float_frames<const S: usize, const L: usize>(
    scene: &Scene<S, L>,
    w: u32,
    h: u32,
) -> [Vec<LinearRgb>; 3] {
    let scalar = Prepared::<Scalar, S, L>::new(scene, w, h).unwrap();
    let simd4 = Prepared::<Simd4, S, L>::new(scene, w, h).unwrap();
    let simd8 = Prepared::<Simd8, S, L>::new(scene, w, h).unwrap();
    [
        frame(&scalar.with_antialiasing(true)),
        frame(&simd4.with_antialiasing(true)),
        frame(&simd8.with_antialiasing(true)),
    ]
}

fn bits(frame: &[LinearRgb]) -> Vec<[u32; 3]> {
    frame
        .iter()
        .map(|c| [c.r.to_bits(), c.g.to_bits(), c.b.to_bits()])
        .collect()
}

#[test]
fn scalar_and_simd_are_bit_identical_with_antialiasing() {
    let [s, s4, s8] = float_frames(&exponent_series().unwrap(), 160, 117);
    assert_eq!(bits(&s), bits(&s4), "exponent series, simd4");
    assert_eq!(bits(&s), bits(&s8), "exponent series, simd8");
    let [s, s4, s8] = float_frames(&materials().unwrap(), 97, 61);
    assert_eq!(bits(&s), bits(&s4), "materials, simd4");
    assert_eq!(bits(&s), bits(&s8), "materials, simd8");
    for (i, scene) in random_scenes(12, 0xa11a5)
        .iter()
        .chain(&random_scenes_all_models(12, 0xa11a6))
        .enumerate()
    {
        let [s, s4, s8] = float_frames(scene, 53, 41);
        assert_eq!(bits(&s), bits(&s4), "random scene {i}, simd4");
        assert_eq!(bits(&s), bits(&s8), "random scene {i}, simd8");
    }
}

/// Whether pixel `i`'s 3×3 neighbourhood shows more than one sphere (or a sphere and the
/// background) in `hits`, or reaches past the frame (an outline can pass just outside it):
/// the pixels an outline can cross.
fn near_outline(hits: &[HitRecord], w: usize, i: usize) -> bool {
    let (x, y) = ((i % w) as i64, (i / w) as i64);
    let h = (hits.len() / w) as i64;
    let mut seen = None;
    for dy in -1..=1 {
        for dx in -1..=1 {
            let (nx, ny) = (x + dx, y + dy);
            if nx < 0 || ny < 0 || nx >= w as i64 || ny >= h {
                return true;
            }
            let s = hits[(ny * w as i64 + nx) as usize].sphere;
            match seen {
                None => seen = Some(s),
                Some(t) if t != s => return true,
                Some(_) => {}
            }
        }
    }
    false
}

/// Checks that every pixel anti-aliasing changes is next to an outline; returns how many
/// changed.
fn changed_pixels<const S: usize, const L: usize>(scene: &Scene<S, L>, what: &str) -> usize {
    let (w, h) = (61, 47);
    let plain = Prepared::<Simd8, S, L>::new(scene, w, h).unwrap();
    let hits: Vec<HitRecord> = frame(&plain);
    let sharp: Vec<LinearRgb> = frame(&plain);
    let smooth: Vec<LinearRgb> = frame(&plain.clone().with_antialiasing(true));
    let mut changed = 0;
    for (k, (a, b)) in sharp.iter().zip(&smooth).enumerate() {
        if bits(&[*a]) != bits(&[*b]) {
            changed += 1;
            assert!(
                near_outline(&hits, w as usize, k),
                "{what}: pixel ({}, {}) changed away from every outline: {a:?} -> {b:?}",
                k % w as usize,
                k / w as usize
            );
        }
    }
    changed
}

#[test]
fn only_pixels_next_to_an_outline_change_and_some_do() {
    let mut changed = changed_pixels(&exponent_series().unwrap(), "exponent series");
    changed += changed_pixels(&materials().unwrap(), "materials");
    for (i, scene) in random_scenes(16, 0xed6e).iter().enumerate() {
        changed += changed_pixels(scene, &format!("random scene {i}"));
    }
    assert!(changed > 500, "only {changed} pixels anti-aliased");
}

#[test]
fn an_edge_pixel_lies_between_the_sphere_and_the_background() {
    // One white diffuse sphere lit by a distant light from behind the eye, on a black
    // background: every pixel lies between black and the brightest colour the sphere shows,
    // and along a row the colour grows toward the centre (coverage, then N·L).
    let camera = Camera {
        position: Vec3::new(0.0, 0.0, 10.0),
        look_at: Vec3::new(0.0, 0.0, 0.0),
        up: Vec3::new(0.0, 1.0, 0.0),
        vfov_degrees: 30.0,
    };
    let mut scene: Scene<1, 1> = Scene::new(camera, LinearRgb::new(0.0, 0.0, 0.0)).unwrap();
    scene
        .add_sphere(Sphere {
            center: Vec3::new(0.0, 0.0, 0.0),
            radius: 2.0,
            material: Material {
                albedo: LinearRgb::new(1.0, 1.0, 1.0),
                kd: 1.0,
                ks: 0.0,
                shininess: 1.0,
                model: Model::Phong,
            },
        })
        .unwrap();
    scene
        .add_light(Light::Distant {
            direction: Vec3::new(0.0, 0.0, -1.0),
            color: LinearRgb::new(1.0, 1.0, 1.0),
            intensity: 1.0,
        })
        .unwrap();
    let (w, h) = (80u32, 80u32);
    let frame_aa: Vec<LinearRgb> = frame(
        &Prepared::<Scalar, 1, 1>::new(&scene, w, h)
            .unwrap()
            .with_antialiasing(true),
    );
    let sharp: Vec<LinearRgb> = frame(&Prepared::<Scalar, 1, 1>::new(&scene, w, h).unwrap());
    let brightest = sharp.iter().map(|c| c.r).fold(0.0f32, f32::max);
    // Row through the centre, from the left edge inward: 0 … partial … the sphere.
    let y = (h / 2) as usize;
    let row = &frame_aa[y * w as usize..(y + 1) * w as usize];
    let partial: Vec<f32> = row
        .iter()
        .map(|c| c.r)
        .take(w as usize / 2)
        .filter(|&r| r > 0.0 && r < brightest)
        .collect();
    assert!(!partial.is_empty(), "no partial pixel on the row");
    for c in &frame_aa {
        assert!(
            (0.0..=brightest).contains(&c.r),
            "{c:?} beyond [0, {brightest}]"
        );
        assert!(c.r == c.g && c.g == c.b, "{c:?} is not grey");
    }
    // Along the left half of the row the colour never decreases (coverage then shading grow).
    for pair in row[..w as usize / 2].windows(2) {
        assert!(pair[0].r <= pair[1].r, "{:?} then {:?}", pair[0], pair[1]);
    }
}
