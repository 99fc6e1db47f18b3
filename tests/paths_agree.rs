//! The float paths agree bit for bit: scalar, f32x4 and f32x8 give the same `f32` linear
//! colour and the same hit record for every pixel, and the scanline spans change no pixel
//! compared with testing every sphere at every pixel, on the default target CPU (x86-64-v3).
//! The same contract on the other instruction sets (the SSE2 baseline, the native CPU,
//! aarch64 and wasm32) is `checks/bit-identity`'s (`.ci/bit-identity`).

use crate::common;
use common::*;
use shadeline::*;

fn bits(frame: &[LinearRgb]) -> Vec<[u32; 3]> {
    frame
        .iter()
        .map(|c| [c.r.to_bits(), c.g.to_bits(), c.b.to_bits()])
        .collect()
}

/// Asserts every width, with and without spans, equals the scalar path without spans (the
/// scalar path with spans, and both SIMD widths either way; the reference itself is not
/// compared with itself).
fn assert_all_paths_identical<const S: usize, const L: usize>(
    scene: &Scene<S, L>,
    w: u32,
    h: u32,
    what: &str,
) {
    let naive = Prepared::<Scalar, S, L>::new(scene, w, h)
        .unwrap()
        .with_spans(false);
    let want_color = bits(&frame::<LinearRgb, _>(&naive));
    let want_hits: Vec<HitRecord> = frame(&naive);

    fn check<R: Render>(r: &R, want_color: &[[u32; 3]], want_hits: &[HitRecord], label: &str) {
        let got = bits(&frame::<LinearRgb, _>(r));
        if let Some(i) = got.iter().zip(want_color).position(|(a, b)| a != b) {
            panic!(
                "{label}: pixel {i} differs: {:?} vs {:?}",
                got[i], want_color[i]
            );
        }
        let hits: Vec<HitRecord> = frame(r);
        assert!(hits == want_hits, "{label}: hit records differ");
        // The packet-wide encode stage stores what the per-pixel definition gives.
        let linear: Vec<LinearRgb> = frame(r);
        let shade = |c: &LinearRgb| Shade {
            color: *c,
            hit: HitRecord::default(),
        };
        let want_888: Vec<Rgb888> = linear.iter().map(|c| Rgb888::encode(&shade(c))).collect();
        assert!(
            frame::<Rgb888, _>(r) == want_888,
            "{label}: Rgb888 encode differs"
        );
        let want_565: Vec<Rgb565> = linear.iter().map(|c| Rgb565::encode(&shade(c))).collect();
        assert!(
            frame::<Rgb565, _>(r) == want_565,
            "{label}: Rgb565 encode differs"
        );
    }
    check(
        &Prepared::<Scalar, S, L>::new(scene, w, h).unwrap(),
        &want_color,
        &want_hits,
        &format!("{what}: scalar, spans true"),
    );
    check(
        &Prepared::<ScalarWith<HostSqrt>, S, L>::new(scene, w, h).unwrap(),
        &want_color,
        &want_hits,
        &format!("{what}: scalar with the host's square root, spans true"),
    );
    for spans in [false, true] {
        let label = |p: &str| format!("{what}: {p}, spans {spans}");
        check(
            &Prepared::<Simd4, S, L>::new(scene, w, h)
                .unwrap()
                .with_spans(spans),
            &want_color,
            &want_hits,
            &label("simd4"),
        );
        check(
            &Prepared::<Simd8, S, L>::new(scene, w, h)
                .unwrap()
                .with_spans(spans),
            &want_color,
            &want_hits,
            &label("simd8"),
        );
    }
}

/// The host's `f32::sqrt`: the hardware's correctly rounded square root (`sqrtss`, NEON's
/// `fsqrt`, wasm's `f32.sqrt`), as a firmware supplies `VSQRT.F32`.
struct HostSqrt;
impl SquareRoot for HostSqrt {
    fn sqrt(x: f32) -> f32 {
        x.sqrt()
    }
}

/// A square root one ulp too large: not correctly rounded.
struct OneUlpHigh;
impl SquareRoot for OneUlpHigh {
    fn sqrt(x: f32) -> f32 {
        f32::from_bits(x.sqrt().to_bits() + 1)
    }
}

#[test]
fn scalar_with_takes_every_square_root_from_its_parameter() {
    // The square roots of `ScalarWith<Q>` are `Q`'s: one ulp off in each changes the frame
    // (while `HostSqrt` gives `Scalar`'s bits, in `assert_all_paths_identical`).
    let scene = exponent_series().unwrap();
    let (w, h) = EXPONENT_SERIES_SIZE;
    let exact = bits(&frame::<LinearRgb, _>(
        &Prepared::<ScalarWith<HostSqrt>>::new(&scene, w, h).unwrap(),
    ));
    let off = bits(&frame::<LinearRgb, _>(
        &Prepared::<ScalarWith<OneUlpHigh>>::new(&scene, w, h).unwrap(),
    ));
    let differ = exact.iter().zip(&off).filter(|(a, b)| a != b).count();
    assert!(
        differ > 1000,
        "only {differ} pixels changed with a square root one ulp off"
    );
}

#[test]
fn exponent_series_is_bit_identical_across_widths_and_spans() {
    let scene = exponent_series().unwrap();
    let (w, h) = EXPONENT_SERIES_SIZE;
    assert_all_paths_identical(&scene, w, h, "exponent series");
    // Small and odd sizes exercise the row tails and partial packets.
    for (w, h) in [(320, 240), (1, 1), (7, 5), (9, 13), (67, 3)] {
        assert_all_paths_identical(&scene, w, h, &format!("exponent series {w}x{h}"));
    }
}

#[test]
fn random_scenes_are_bit_identical_across_widths_and_spans() {
    for (i, scene) in random_scenes(64, 0x5eed_0002).iter().enumerate() {
        // Widths that are not multiples of 4 or 8.
        let (w, h) = (93 + (i as u32 % 9), 61);
        assert_all_paths_identical(scene, w, h, &format!("random scene {i}"));
    }
}

#[cfg(feature = "area-lights")]
#[test]
fn sphere_lights_are_bit_identical_across_widths_and_spans() {
    for factor in [0.05f32, 0.2, 0.5, 1.0] {
        let scene = spheres_in_a_row(factor * ROW_RADIUS).unwrap();
        assert!(scene.sphere_light().is_some());
        for (w, h) in [(96, 64), (7, 5), (67, 3)] {
            assert_all_paths_identical(&scene, w, h, &format!("row, light {factor}r, {w}x{h}"));
        }
    }
    // Every model, under sphere lights of several sizes.
    let mut lit = 0;
    for (i, scene) in random_scenes_all_models(24, 0x5eed_a4ea).iter().enumerate() {
        let radius = [0.05f32, 0.3, 1.0][i % 3];
        let scene = with_sphere_lights(scene, radius);
        lit += scene.sphere_light().is_some() as usize;
        assert_all_paths_identical(
            &scene,
            61,
            43,
            &format!("random scene {i}, lights {radius}"),
        );
    }
    assert!(lit >= 10, "only {lit} scenes with a sphere light");
}

#[test]
fn spans_skip_work_without_losing_pixels() {
    // The spans must actually exclude something on the exponent series, or the test above
    // proves nothing about them.
    let scene = exponent_series().unwrap();
    let frame = Prepared::<Scalar>::new(&scene, 320, 240).unwrap();
    let hits: Vec<HitRecord> = common::frame(&frame);
    let mut covered = 0usize;
    for y in 0..240u32 {
        let spans = frame.row_spans(y);
        for (k, span) in spans.iter().enumerate() {
            for x in 0..320u32 {
                let inside = span.is_some_and(|s| s.start <= x && x < s.end);
                if hits[(y * 320 + x) as usize].sphere == Some(k as u16) {
                    assert!(inside, "pixel ({x},{y}) hits sphere {k} outside its span");
                }
                covered += inside as usize;
            }
        }
    }
    let hit = hits.iter().filter(|h| h.sphere.is_some()).count();
    println!(
        "spans cover {covered} sphere-pixels for {hit} hit pixels, of {}",
        320 * 240
    );
    assert!(covered < 320 * 240, "spans cover the whole frame");
    assert!(
        covered < hit * 2,
        "spans are loose: {covered} for {hit} hits"
    );
}
