//! Fuzz target `scene_file`: arbitrary bytes through the harness's TOML scene parser,
//! `shadeline_harness::parse_scene`.
//!
//! Proves: any UTF-8 text gives a scene or an error, never a panic; an error's line and column
//! lie inside the text (1-based, the column counted in characters) and it formats; a parsed
//! scene has a size the core accepts, and its middle row renders (at a width of at most 67)
//! to finite, non-negative colour.
#![no_main]

use libfuzzer_sys::fuzz_target;
use shadeline::{LinearRgb, Prepared, Render, Scalar, MAX_DIMENSION};
use shadeline_harness::parse_scene;
use shadeline_harness::scene_file::{MAX_LIGHTS, MAX_SPHERES};

fuzz_target!(|data: &[u8]| {
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
            let frame = Prepared::<Scalar, MAX_SPHERES, MAX_LIGHTS>::new(&file.scene, w, h)
                .expect("a parsed scene prepares");
            let mut row = vec![LinearRgb::default(); w as usize];
            frame.render_line(h / 2, &mut row).expect("renders");
            for c in &row {
                for v in [c.r, c.g, c.b] {
                    assert!(v.is_finite() && v >= 0.0, "{c:?}");
                }
            }
        }
    }
});
