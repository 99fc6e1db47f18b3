//! Fuzz target `scene`: arbitrary numbers — NaN, ±inf, subnormals, huge and tiny values mixed
//! with everyday ones — through the scene builder and its validation, with every reflection
//! model (classic Phong and Blinn-Phong, Lambert, normalized Phong and Blinn-Phong as
//! dielectrics with or without `ior` and as metals, with up to three lobes, Oren–Nayar, GGX
//! with every surface), then, for every
//! scene that validates, a few rows at widths 1..=67 and any height in every path, every
//! pixel format and one of the four encodings (linear or sRGB, with or without dithering),
//! also as display bytes.
//!
//! Proves, for every input: validation refuses exactly what the documented ranges refuse, with
//! the exact error, and never panics; every accepted scene prepares at every accepted size and
//! refuses bad sizes, rows and slices with the exact error; no row panics; linear colour is
//! finite and non-negative; hit records name existing spheres and lights; 8-bit and 5-6-5
//! pixels are the quantized linear colour; Rgb888, Rgb565, Bgr565 and Gray8 with the encoding
//! are the encoding rule applied to the linear colour, and byte rows are their bytes; a row
//! rendered twice is the same.

use crate::{
    build_scene, check_bad_sizes, check_refusals, check_row, for_each_path, render_row, FuzzScene,
    PathVisitor, SceneInput,
};
use shadeline::{Encoding, Render, RenderError};

struct Rows<'a> {
    scene: &'a FuzzScene,
    rows: [u32; 3],
    encoding: Encoding,
}

impl PathVisitor for Rows<'_> {
    fn visit<R: Render + Clone>(&mut self, name: &'static str, prepared: Result<R, RenderError>) {
        let frame = match prepared {
            Ok(frame) => frame,
            // A path with a narrower number range may refuse a scene, with its own error.
            Err(RenderError::OutOfFixedRange { .. }) if name == "fixed" => return,
            Err(e) => panic!("{name}: a valid scene was refused: {e}"),
        };
        for y in self.rows {
            let row = render_row(&frame, y, self.encoding);
            check_row(
                self.scene,
                &row,
                y,
                &format!("{name} row {y}"),
                name != "fixed",
            );
            let again = render_row(&frame, y, self.encoding);
            assert_eq!(row, again, "{name} row {y}: not repeatable");
        }
        check_refusals(&frame);
    }
}

/// The target's check of one input: panics on a failure, as libFuzzer needs.
pub fn check(input: &SceneInput) {
    let Some(scene) = build_scene(input) else {
        return;
    };
    let (width, height) = input.size();
    let mut visitor = Rows {
        scene: &scene,
        rows: input.rows(height),
        encoding: input.encoding(),
    };
    for_each_path(&scene, width, height, &mut visitor);
    check_bad_sizes(&scene, width, height);
}
