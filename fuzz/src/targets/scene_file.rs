//! Fuzz target `scene_file`: arbitrary bytes through the harness's TOML scene parser,
//! `shadeline_harness::parse_scene`, with every model and material key (`model`, `metal`,
//! `ior`, `lobes`, `roughness`) in its dictionary (`fuzz/scene_file.dict`) and seeds.
//!
//! Proves: any UTF-8 text gives a scene or an error, never a panic; an error's line and column
//! lie inside the text (1-based, the column counted in characters) and it formats; a parsed
//! scene has a size the core accepts, and its middle row renders (at a width of at most 67)
//! on the scalar, 8-lane and fixed paths (the fixed path may refuse it as out of its range,
//! or for an Oren–Nayar or GGX sphere)
//! to finite, non-negative colour, with the 8-lane path bit-identical to the scalar one, and
//! in every level format with one of the four encodings (the text's length modulo 4 picks
//! it), also as display bytes, again bit-identical between the float paths.

use crate::{render_row, ENCODINGS};
use shadeline::{LinearRgb, Prepared, PreparedFixed, RenderError, Scalar, Simd8, MAX_DIMENSION};
use shadeline_harness::parse_scene;
use shadeline_harness::scene_file::{MAX_LIGHTS, MAX_SPHERES};

fn check_finite(row: &[LinearRgb], what: &str) {
    for c in row {
        for v in [c.r, c.g, c.b] {
            assert!(v.is_finite() && v >= 0.0, "{what}: {c:?}");
        }
    }
}

/// The target's check of one input: panics on a failure, as libFuzzer needs.
pub fn check(data: &[u8]) {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    match parse_scene(text) {
        Err(e) => {
            let lines = text.split('\n').count();
            assert!(e.line >= 1 && e.line <= lines, "{e:?}");
            let line = text.split('\n').nth(e.line - 1).unwrap_or_default();
            assert!(
                e.column >= 1 && e.column <= line.chars().count() + 1,
                "{e:?}"
            );
            assert!(!e.to_string().is_empty());
        }
        Ok(file) => {
            assert!((1..=MAX_DIMENSION).contains(&file.width), "{}", file.width);
            assert!(
                (1..=MAX_DIMENSION).contains(&file.height),
                "{}",
                file.height
            );
            let (w, h) = (file.width.min(67), file.height.min(67));
            let y = h / 2;
            let encoding = ENCODINGS[data.len() % ENCODINGS.len()];
            let scalar = Prepared::<Scalar, MAX_SPHERES, MAX_LIGHTS>::new(&file.scene, w, h)
                .expect("a parsed scene prepares");
            let want = render_row(&scalar, y, encoding);
            check_finite(&want.linear, "scalar");
            let simd = Prepared::<Simd8, MAX_SPHERES, MAX_LIGHTS>::new(&file.scene, w, h)
                .expect("a parsed scene prepares");
            let got = render_row(&simd, y, encoding);
            let bits = |r: &[LinearRgb]| {
                r.iter()
                    .map(|c| [c.r.to_bits(), c.g.to_bits(), c.b.to_bits()])
                    .collect::<Vec<_>>()
            };
            assert_eq!(bits(&got.linear), bits(&want.linear), "simd8 vs scalar");
            assert_eq!(
                (
                    got.linear.len(),
                    &got.hits,
                    &got.enc_rgb565,
                    &got.enc_bgr565
                ),
                (
                    want.linear.len(),
                    &want.hits,
                    &want.enc_rgb565,
                    &want.enc_bgr565
                ),
                "simd8 vs scalar, {encoding:?}"
            );
            assert_eq!(
                got.enc_gray8, want.enc_gray8,
                "simd8 vs scalar, {encoding:?}"
            );
            assert_eq!(got.bytes, want.bytes, "simd8 vs scalar, {encoding:?}");
            match PreparedFixed::<MAX_SPHERES, MAX_LIGHTS>::new(&file.scene, w, h) {
                Ok(fixed) => check_finite(&render_row(&fixed, y, encoding).linear, "fixed"),
                Err(RenderError::OutOfFixedRange { .. }) => {}
                Err(e) => panic!("fixed: a parsed scene was refused: {e}"),
            }
        }
    }
}
