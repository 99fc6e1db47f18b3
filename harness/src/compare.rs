//! Measuring the paths against the `f64` reference: error statistics, the table, and the
//! side-by-side picture.
//!
//! Colour statistics are taken in 8-bit levels against the reference colour quantized with
//! the paths' own rounding ([`shadeline::reference::quantize`]). A pixel whose hit record
//! (sphere hit and shadowed lights) differs from the reference's is a different ray decision,
//! not a shading error: it is counted on its own and left out of the error maximum and the
//! within-one-level share. PSNR is over all pixels.

use crate::image::RgbImage;
use crate::rows::{render_rows, FrameError};
use crate::scene_file::FileScene;
use shadeline::reference::{quantize, shade_pixel, RefPixel};
use shadeline::{HitRecord, RenderError, Rgb888, MAX_DIMENSION};
use std::fmt::Write as _;

/// Difference images are `|path − reference|` per channel times this, clamped to 255.
pub const DIFF_GAIN: u32 = 32;

/// The bytes per pixel that `compare` holds at once with `paths` paths: the reference (colour
/// and hit record) and its 8-bit quantization, each path's 8-bit frame and one path's hit
/// records, and the picture (the reference and each path over their differences, with one
/// difference being built).
pub fn bytes_per_pixel(paths: usize) -> usize {
    let rgb = std::mem::size_of::<Rgb888>();
    std::mem::size_of::<RefPixel>()
        + rgb
        + paths * rgb
        + std::mem::size_of::<HitRecord>()
        + 2 * (paths + 1) * rgb
        + rgb
}

/// Renders the reference frame on `threads` threads (the same frame as
/// [`shadeline::reference::render_frame`], one row block per thread at a time).
pub fn render_reference(
    scene: &FileScene,
    width: u32,
    height: u32,
    threads: usize,
) -> Result<Vec<RefPixel>, FrameError> {
    if width > MAX_DIMENSION || height > MAX_DIMENSION {
        return Err(RenderError::BadSize { width, height }.into());
    }
    render_rows(width, height, threads, |y, row: &mut [RefPixel]| {
        for (x, px) in row.iter_mut().enumerate() {
            *px = shade_pixel(scene, width, height, x as u32, y);
        }
        Ok(())
    })
}

/// The reference quantized to 8 bits with the paths' rounding.
pub fn reference_rgb(reference: &[RefPixel]) -> Vec<Rgb888> {
    reference
        .iter()
        .map(|p| {
            let [r, g, b] = p.color.map(|c| quantize(c, 255.0) as u8);
            Rgb888 { r, g, b }
        })
        .collect()
}

/// How one path's frame compares with the reference.
#[derive(Clone, Debug, PartialEq)]
pub struct Stats {
    /// Largest channel difference in 8-bit levels over pixels whose hit record agrees.
    pub max_error: u8,
    /// Share (%) of pixels whose hit record agrees that are within 1 level on every channel.
    pub within_one: f64,
    /// Pixels whose hit record (sphere or shadowed lights) differs from the reference's.
    pub hit_differs: usize,
    /// The same as a share (%) of all pixels.
    pub hit_differs_percent: f64,
    /// Peak signal-to-noise ratio over all pixels and channels, in dB (∞ if identical).
    pub psnr: f64,
}

fn channels(p: Rgb888) -> [u8; 3] {
    [p.r, p.g, p.b]
}

/// Compares one path's colours and hit records with the reference (all row-major, one size).
pub fn stats(
    reference: &[RefPixel],
    ref_rgb: &[Rgb888],
    rgb: &[Rgb888],
    hits: &[HitRecord],
) -> Stats {
    let total = reference.len();
    let (mut max_error, mut within_one, mut agree, mut squared) = (0u8, 0usize, 0usize, 0u64);
    for (((r, q), p), hit) in reference.iter().zip(ref_rgb).zip(rgb).zip(hits) {
        let (q, p) = (channels(*q), channels(*p));
        let diffs: [u8; 3] = std::array::from_fn(|i| q[i].abs_diff(p[i]));
        squared += diffs
            .iter()
            .map(|&d| u64::from(d) * u64::from(d))
            .sum::<u64>();
        if *hit == r.hit {
            agree += 1;
            let worst = diffs.into_iter().max().unwrap_or(0);
            max_error = max_error.max(worst);
            within_one += usize::from(worst <= 1);
        }
    }
    let percent = |n: usize, of: usize| {
        if of == 0 {
            100.0
        } else {
            100.0 * n as f64 / of as f64
        }
    };
    let mse = squared as f64 / (3 * total.max(1)) as f64;
    Stats {
        max_error,
        within_one: percent(within_one, agree),
        hit_differs: total - agree,
        hit_differs_percent: 100.0 - percent(agree, total),
        psnr: 10.0 * (255.0f64 * 255.0 / mse).log10(),
    }
}

/// One row of the comparison table.
#[derive(Clone, Debug)]
pub struct Row {
    /// The path's name.
    pub name: &'static str,
    /// Its statistics.
    pub stats: Stats,
    /// Median time per frame (prepare and render), in milliseconds.
    pub millis: f64,
}

/// The comparison table, one line per path, with a header.
pub fn table(rows: &[Row]) -> String {
    let mut out = String::new();
    let _ = writeln!(
        out,
        "{:<8} {:>9} {:>10} {:>20} {:>10} {:>10}",
        "path", "max err", "within 1", "hit/miss differs", "PSNR", "ms/frame"
    );
    for row in rows {
        let s = &row.stats;
        let psnr = if s.psnr.is_finite() {
            format!("{:.2} dB", s.psnr)
        } else {
            "inf dB".to_string()
        };
        let differs = format!("{} ({:.4}%)", s.hit_differs, s.hit_differs_percent);
        let _ = writeln!(
            out,
            "{:<8} {:>9} {:>9.4}% {:>20} {:>10} {:>10.2}",
            row.name, s.max_error, s.within_one, differs, psnr, row.millis
        );
    }
    out
}

/// The amplified difference `min(255, |a − b|·DIFF_GAIN)` per channel.
pub fn difference(a: &[Rgb888], b: &[Rgb888]) -> Vec<Rgb888> {
    a.iter()
        .zip(b)
        .map(|(a, b)| {
            let d = |x: u8, y: u8| (u32::from(x.abs_diff(y)) * DIFF_GAIN).min(255) as u8;
            Rgb888 {
                r: d(a.r, b.r),
                g: d(a.g, b.g),
                b: d(a.b, b.b),
            }
        })
        .collect()
}

/// The picture: the reference and each path side by side on the top row, and under each
/// path its amplified difference from the reference (black under the reference).
pub fn picture(width: u32, height: u32, ref_rgb: &[Rgb888], paths: &[Vec<Rgb888>]) -> RgbImage {
    let mut image = RgbImage::new(width * (1 + paths.len() as u32), height * 2);
    image.paste(0, 0, width, ref_rgb);
    for (i, rgb) in paths.iter().enumerate() {
        let x = width * (1 + i as u32);
        image.paste(x, 0, width, rgb);
        image.paste(x, height, width, &difference(rgb, ref_rgb));
    }
    image
}

#[cfg(test)]
mod tests {
    use super::*;

    fn px(v: u8) -> Rgb888 {
        Rgb888 { r: v, g: v, b: v }
    }

    fn hit(sphere: Option<u16>) -> HitRecord {
        HitRecord {
            sphere,
            shadowed: 0,
        }
    }

    #[test]
    fn disagreeing_hits_are_counted_apart_from_the_colour_error() {
        let reference = [RefPixel {
            color: [0.0; 3],
            hit: hit(Some(0)),
        }; 4];
        let ref_rgb = reference_rgb(&reference);
        let rgb = [px(0), px(1), px(3), px(200)];
        let hits = [hit(Some(0)), hit(Some(0)), hit(Some(0)), hit(None)];
        let s = stats(&reference, &ref_rgb, &rgb, &hits);
        assert_eq!(s.max_error, 3);
        assert_eq!(s.hit_differs, 1);
        assert!((s.hit_differs_percent - 25.0).abs() < 1e-9);
        assert!((s.within_one - 200.0 / 3.0).abs() < 1e-9);
        let mse = (1.0 + 9.0 + 200.0 * 200.0) / 4.0;
        assert!((s.psnr - 10.0 * (65025.0f64 / mse).log10()).abs() < 1e-9);
    }

    #[test]
    fn identical_frames_have_infinite_psnr_and_a_black_difference() {
        let reference = [RefPixel {
            color: [0.5; 3],
            hit: hit(None),
        }; 2];
        let ref_rgb = reference_rgb(&reference);
        assert_eq!(ref_rgb[0], px(128));
        let s = stats(&reference, &ref_rgb, &ref_rgb, &[hit(None); 2]);
        assert_eq!((s.max_error, s.hit_differs), (0, 0));
        assert!(s.psnr.is_infinite());
        assert_eq!(
            difference(&ref_rgb, &[px(130), px(0)]),
            vec![px(64), px(255)]
        );
    }

    #[test]
    fn the_picture_puts_each_path_beside_the_reference_and_its_difference_below() {
        let image = picture(1, 1, &[px(10)], &[vec![px(11)], vec![px(10)]]);
        assert_eq!((image.width, image.height), (3, 2));
        assert_eq!(&image.bytes[..9], &[10, 10, 10, 11, 11, 11, 10, 10, 10]);
        assert_eq!(&image.bytes[9..], &[0, 0, 0, 32, 32, 32, 0, 0, 0]);
    }
}
