//! Analytic anti-aliasing of the silhouettes (`with_antialiasing`): the scalar and SIMD paths
//! give the same bits with it on, it changes only pixels next to an outline, and it blends
//! them between the colours on either side. Its accuracy against a supersampled truth is
//! measured by the harness (`shadeline compare`, `harness/tests/edges.rs`).

#![cfg(feature = "antialias")]

use crate::common;

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

/// One white diffuse sphere lit by a distant light from behind the eye, on a black
/// background, and the image size for it.
fn grey_sphere() -> (Scene, u32, u32) {
    let camera = Camera {
        position: Vec3::new(0.0, 0.0, 10.0),
        look_at: Vec3::new(0.0, 0.0, 0.0),
        up: Vec3::new(0.0, 1.0, 0.0),
        vfov_degrees: 30.0,
    };
    let mut scene: Scene = Scene::new(camera, LinearRgb::new(0.0, 0.0, 0.0)).unwrap();
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
    (scene, 80, 80)
}

/// On [`grey_sphere`]'s frame with and without anti-aliasing (red channel): every pixel lies
/// between black and the brightest colour the sphere shows, the row through the centre has
/// partial pixels, and along it the colour grows toward the centre (coverage, then `N·L`).
fn assert_edges_between_sphere_and_background<T: PartialOrd + Copy + Default + core::fmt::Debug>(
    smooth: &[T],
    sharp: &[T],
    w: usize,
) {
    let brightest = sharp
        .iter()
        .copied()
        .fold(T::default(), |a, b| if b > a { b } else { a });
    let y = smooth.len() / w / 2;
    let row = &smooth[y * w..(y + 1) * w];
    assert!(
        row[..w / 2]
            .iter()
            .any(|&r| r > T::default() && r < brightest),
        "no partial pixel on the row"
    );
    for &c in smooth {
        assert!(
            c >= T::default() && c <= brightest,
            "{c:?} beyond {brightest:?}"
        );
    }
    for pair in row[..w / 2].windows(2) {
        assert!(pair[0] <= pair[1], "{:?} then {:?}", pair[0], pair[1]);
    }
}

#[test]
fn an_edge_pixel_lies_between_the_sphere_and_the_background() {
    let (scene, w, h) = grey_sphere();
    let frame_aa: Vec<LinearRgb> = frame(
        &Prepared::<Scalar>::new(&scene, w, h)
            .unwrap()
            .with_antialiasing(true),
    );
    let sharp: Vec<LinearRgb> = frame(&Prepared::<Scalar>::new(&scene, w, h).unwrap());
    for c in &frame_aa {
        assert!(c.r == c.g && c.g == c.b, "{c:?} is not grey");
    }
    let red = |f: &[LinearRgb]| f.iter().map(|c| c.r).collect::<Vec<f32>>();
    assert_edges_between_sphere_and_background(&red(&frame_aa), &red(&sharp), w as usize);
}

/// The fixed path's anti-aliasing (features `antialias` and `full-width`): only pixels next
/// to an outline change, the blends agree with the float paths' within a budget, and an
/// anti-aliased frame has the same bits on every target (a golden CRC here, and
/// `checks/bit-identity`'s anti-aliased fixed frames on x86-64, aarch64 and wasm32).
#[cfg(feature = "full-width")]
mod fixed {
    use super::common::{frame, random_scenes, random_scenes_all_models};
    use super::{assert_edges_between_sphere_and_background, grey_sphere, near_outline};
    use shadeline::*;

    /// `scene`'s fixed frame at `w × h`: sharp, its hit records, and anti-aliased.
    fn frames<const S: usize, const L: usize>(
        scene: &Scene<S, L>,
        w: u32,
        h: u32,
    ) -> (Vec<Rgb888>, Vec<HitRecord>, Vec<Rgb888>) {
        let f = PreparedFixed::<S, L>::new(scene, w, h).unwrap();
        (frame(&f), frame(&f), frame(&f.with_antialiasing(true)))
    }

    #[test]
    fn only_pixels_next_to_an_outline_change_and_some_do() {
        let (w, h) = (61, 47);
        let mut all = vec![
            (
                "exponent series".to_string(),
                frames(&exponent_series().unwrap(), w, h),
            ),
            ("materials".to_string(), frames(&materials().unwrap(), w, h)),
        ];
        for (i, scene) in random_scenes(16, 0xed6e).iter().enumerate() {
            all.push((format!("random scene {i}"), frames(scene, w, h)));
        }
        let mut changed = 0;
        for (what, (sharp, hits, smooth)) in &all {
            for (k, (a, b)) in sharp.iter().zip(smooth).enumerate() {
                if a != b {
                    changed += 1;
                    assert!(
                        near_outline(hits, w as usize, k),
                        "{what}: pixel ({}, {}) changed away from every outline: {a:?} -> {b:?}",
                        k % w as usize,
                        k / w as usize
                    );
                }
            }
        }
        assert!(changed > 500, "only {changed} pixels anti-aliased");
    }

    #[test]
    fn an_edge_pixel_lies_between_the_sphere_and_the_background() {
        let (scene, w, h) = grey_sphere();
        let (sharp, _, smooth) = frames(&scene, w, h);
        for c in &smooth {
            assert!(c.r == c.g && c.g == c.b, "{c:?} is not grey");
        }
        let red = |f: &[Rgb888]| f.iter().map(|c| c.r).collect::<Vec<u8>>();
        assert_edges_between_sphere_and_background(&red(&smooth), &red(&sharp), w as usize);
    }

    #[test]
    fn turning_it_off_and_preparing_again_give_the_sharp_frame() {
        let scene = exponent_series().unwrap();
        let (sharp, _, smooth) = frames(&scene, 64, 48);
        assert_ne!(sharp, smooth);
        let frame_off = PreparedFixed::new(&scene, 64, 48)
            .unwrap()
            .with_antialiasing(true)
            .with_antialiasing(false);
        assert_eq!(frame::<Rgb888, _>(&frame_off), sharp);
        let mut again = PreparedFixed::EMPTY;
        again.prepare(&scene, 64, 48).unwrap();
        again.set_antialiasing(true);
        assert_eq!(frame::<Rgb888, _>(&again), smooth);
        again.prepare(&scene, 64, 48).unwrap();
        assert_eq!(frame::<Rgb888, _>(&again), sharp, "prepare turns it off");
    }

    /// The edges stage tests only the columns near each sphere's outline (a band per row
    /// from the spans' conic): with spans off it tests every pixel, and finds the same edges.
    #[test]
    fn the_outline_bands_leave_out_no_edge() {
        let check = |name: &str, sharp: PreparedFixed| {
            let with: Vec<Rgb888> = frame(&sharp.clone().with_antialiasing(true));
            let without: Vec<Rgb888> = frame(&sharp.with_spans(false).with_antialiasing(true));
            assert!(
                with == without,
                "{name}: the bands changed the anti-aliased frame"
            );
        };
        let series = exponent_series().unwrap();
        check(
            "exponent series",
            PreparedFixed::new(&series, 96, 70).unwrap(),
        );
        for (i, scene) in random_scenes(16, 0xba2d).iter().enumerate() {
            check(
                &format!("random scene {i}"),
                PreparedFixed::new(scene, 61, 47).unwrap(),
            );
        }
    }

    /// The largest channel difference in levels, and the share of pixels more than two levels
    /// apart, between the fixed and the scalar anti-aliased frames of `scene`.
    fn against_float<const S: usize, const L: usize>(
        scene: &Scene<S, L>,
        w: u32,
        h: u32,
    ) -> (u8, f64) {
        let float: Vec<Rgb888> = frame(
            &Prepared::<Scalar, S, L>::new(scene, w, h)
                .unwrap()
                .with_antialiasing(true),
        );
        let (_, _, fixed) = frames(scene, w, h);
        let diffs: Vec<u8> = float
            .iter()
            .zip(&fixed)
            .map(|(a, b)| {
                a.r.abs_diff(b.r)
                    .max(a.g.abs_diff(b.g))
                    .max(a.b.abs_diff(b.b))
            })
            .collect();
        let max = diffs.iter().copied().max().unwrap_or(0);
        let over = diffs.iter().filter(|&&d| d > 2).count() as f64 / diffs.len() as f64;
        (max, over)
    }

    /// The budget of the fixed anti-aliased frames against the scalar ones: at most this
    /// many levels in any channel (one pixel where the two paths decide an edge differently
    /// can be 10 levels apart: a random scene of the wasm32 run, whose random scenes are not
    /// x86-64's)…
    const MAX_LEVELS: u8 = 16;
    /// …and at most this share of a frame's pixels more than two levels apart.
    const MAX_SHARE_OVER_TWO: f64 = 0.0025;

    #[test]
    fn fixed_edges_agree_with_the_float_edges() {
        let mut rows = vec![
            (
                "exponent series".to_string(),
                against_float(&exponent_series().unwrap(), 160, 117),
            ),
            (
                "materials".to_string(),
                against_float(&materials().unwrap(), 97, 61),
            ),
        ];
        for (i, scene) in random_scenes(12, 0xa11a5)
            .iter()
            .chain(&random_scenes_all_models(12, 0xa11a6))
            .enumerate()
        {
            rows.push((format!("random scene {i}"), against_float(scene, 53, 41)));
        }
        println!("scene | max levels | more than 2 levels apart");
        for (name, (max, over)) in &rows {
            println!("{name} | {max} | {:.3} %", 100.0 * over);
        }
        for (name, (max, over)) in &rows {
            assert!(
                *max <= MAX_LEVELS && *over <= MAX_SHARE_OVER_TWO,
                "{name}: {max} levels, {:.3} % over 2",
                100.0 * over
            );
        }
    }

    /// CRC32 of an anti-aliased fixed frame of the exponent series at 160×120, `Rgb565`:
    /// the same on every target.
    const GOLDEN_AA_160X120: u32 = 0xdb0f_a1b3;

    #[test]
    fn an_antialiased_fixed_frame_has_the_same_bits_everywhere() {
        let f = PreparedFixed::new(&exponent_series().unwrap(), 160, 120)
            .unwrap()
            .with_antialiasing(true);
        let pixels: Vec<Rgb565> = frame(&f);
        let bytes: Vec<u8> = pixels.iter().flat_map(|p| p.0.to_le_bytes()).collect();
        let crc = crc32fast::hash(&bytes);
        assert_eq!(crc, GOLDEN_AA_160X120, "CRC {crc:#010x}");
    }
}
