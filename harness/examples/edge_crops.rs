//! Writes the crops of the gallery's anti-aliasing section (`docs/gallery.md`): a
//! silhouette of the exponent series at the size of a 320×240 display, sharp, with analytic anti-aliasing, and the 16×16
//! supersampled truth it is measured against, magnified 8× (nearest neighbour) so single
//! pixels show.
//!
//! ```sh
//! cargo run --release -p shadeline-harness --example edge_crops -- [OUT_DIR] [--full]
//! ```
//!
//! Writes `edges-sharp.png`, `edges-analytic.png` and `edges-supersampled.png` into `OUT_DIR`
//! (default `docs`); `--full` also writes each whole frame, to choose the crop.

mod shared;

use shadeline::{Prepared, Render, Rgb888, Scalar};
use shadeline_harness::edges::{box_filtered, TRUTH_SAMPLES};
use shadeline_harness::image::RgbImage;
use shadeline_harness::scene_file::{builtin_scene, MAX_LIGHTS, MAX_SPHERES};

/// The frame rendered, and the crop taken from it: `(x, y, width, height)` in pixels.
const FRAME: (u32, u32) = (320, 240);
const CROP: (u32, u32, u32, u32) = (100, 88, 40, 30);
/// Magnification of the crop.
const ZOOM: u32 = 8;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let (dir, full) = shared::output_dir_and_full();
    let file = builtin_scene()?;
    let (w, h) = FRAME;
    let frame = Prepared::<Scalar, MAX_SPHERES, MAX_LIGHTS>::new(&file.scene, w, h)?;
    let mut sharp = vec![Rgb888::default(); (w * h) as usize];
    frame.render_frame(&mut sharp)?;
    let mut analytic = sharp.clone();
    frame.with_antialiasing(true).render_frame(&mut analytic)?;
    let truth: Vec<Rgb888> = box_filtered(&file.scene, w, h, TRUTH_SAMPLES, 2)?
        .iter()
        .map(|p| p.color)
        .collect();
    for (name, pixels) in [
        ("edges-sharp", &sharp),
        ("edges-analytic", &analytic),
        ("edges-supersampled", &truth),
    ] {
        if full {
            let path = dir.join(format!("{name}-full.png"));
            RgbImage::from_pixels(w, h, pixels).write_png(&path)?;
        }
        let crop = RgbImage::zoomed_crop(pixels, w, CROP, ZOOM);
        let path = dir.join(format!("{name}.png"));
        crop.write_png(&path)?;
        println!("wrote {}", path.display());
    }
    Ok(())
}
