//! Writes the before/after crops of the gallery's encoding section (`docs/gallery.md`): the
//! dark side of a sphere of the exponent series in RGB565, linear and sRGB, each without and with ordered
//! dithering, magnified 6× (nearest neighbour) so single pixels show.
//!
//! ```sh
//! cargo run -p shadeline-harness --example encoding_crops -- [OUT_DIR] [--full]
//! ```
//!
//! Writes `encoding-linear.png`, `encoding-linear-dithered.png`, `encoding-srgb.png` and
//! `encoding-srgb-dithered.png` into `OUT_DIR` (default `docs`); `--full` also writes each
//! whole frame, to choose the crop.

mod shared;

use shadeline::{exponent_series, Encoding, Prepared, Render, Rgb565, Rgb888, Scalar};
use shadeline_harness::image::RgbImage;

/// The frame rendered, and the crop taken from it: `(x, y, width, height)` in pixels.
const FRAME: (u32, u32) = (640, 480);
const CROP: (u32, u32, u32, u32) = (CROP_X, CROP_Y, 48, 48);
const CROP_X: u32 = 56;
const CROP_Y: u32 = 200;
/// Magnification of the crop.
const ZOOM: u32 = 6;

/// An RGB565 pixel widened to 8 bits per channel by bit replication (exact for 0 and max).
fn widen(p: Rgb565) -> Rgb888 {
    let (r, g, b) = p.levels();
    Rgb888 {
        r: (r << 3) | (r >> 2),
        g: (g << 2) | (g >> 4),
        b: (b << 3) | (b >> 2),
    }
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let (dir, full) = shared::output_dir_and_full();
    let scene = exponent_series()?;
    let (w, h) = FRAME;
    let frame = Prepared::<Scalar>::new(&scene, w, h)?;
    for (name, encoding) in [
        ("encoding-linear", Encoding::LINEAR),
        ("encoding-linear-dithered", Encoding::LINEAR.dithered()),
        ("encoding-srgb", Encoding::SRGB),
        ("encoding-srgb-dithered", Encoding::SRGB.dithered()),
    ] {
        let encoded = frame.clone().with_encoding(encoding);
        let mut pixels = vec![Rgb565::default(); (w * h) as usize];
        encoded.render_frame(&mut pixels)?;
        let wide: Vec<Rgb888> = pixels.iter().map(|p| widen(*p)).collect();
        if full {
            let path = dir.join(format!("{name}-full.png"));
            RgbImage::from_pixels(w, h, &wide).write_png(&path)?;
        }
        let crop = RgbImage::zoomed_crop(&wide, w, CROP, ZOOM);
        let path = dir.join(format!("{name}.png"));
        crop.write_png(&path)?;
        println!("wrote {}", path.display());
    }
    Ok(())
}
