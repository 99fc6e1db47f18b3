//! Measuring anti-aliased silhouettes against a supersampled truth.
//!
//! The truth of a pixel is the box filter of a `16 × 16` grid of samples: the scene rendered
//! without anti-aliasing at 16 times the width and the height (the SIMD path, which gives the
//! scalar path's bits), each sample's linear colour clamped to `[0, 1]` (what a display
//! shows), averaged, and quantized to 8 bits with the paths' rounding. A *silhouette pixel*
//! is one whose samples do not all show the same sphere (or all the background): those are
//! the only pixels anti-aliasing is about, and the statistics are over them alone. Plain
//! supersampling (`4 × 4`, the same box filter) is measured the same way, as the yardstick
//! the analytic edges must beat.
//!
//! The truth is built one output row at a time (16 sample rows, two renders each: colours and
//! hit records), so its memory is one row of samples per thread, whatever the image size.

use crate::rows::{render_rows, FrameError};
use crate::scene_file::{FileScene, MAX_LIGHTS, MAX_SPHERES};
use shadeline::reference::quantize;
use shadeline::{HitRecord, LinearRgb, Prepared, Render, RenderError, Rgb888, Simd8};

/// Samples per pixel side of the truth.
pub const TRUTH_SAMPLES: u32 = 16;
/// Samples per pixel side of the supersampling the analytic edges are compared with.
pub const SUPERSAMPLES: u32 = 4;

/// A pixel of a box-filtered frame.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Filtered {
    /// The mean of the samples' clamped linear colours, quantized to 8 bits.
    pub color: Rgb888,
    /// Whether the samples show more than one sphere (or a sphere and the background).
    pub silhouette: bool,
}

/// `scene` rendered at `factor` times `width × height` without anti-aliasing and box-filtered
/// back to `width × height`, on `threads` threads.
pub fn box_filtered(
    scene: &FileScene,
    width: u32,
    height: u32,
    factor: u32,
    threads: usize,
) -> Result<Vec<Filtered>, FrameError> {
    let (wide, high) = match (width.checked_mul(factor), height.checked_mul(factor)) {
        (Some(w), Some(h)) => (w, h),
        _ => {
            return Err(RenderError::BadSize {
                width: u32::MAX,
                height: u32::MAX,
            }
            .into())
        }
    };
    let frame = Prepared::<Simd8, MAX_SPHERES, MAX_LIGHTS>::new(scene, wide, high)?;
    let f = factor as usize;
    render_rows(width, height, threads, |y, row: &mut [Filtered]| {
        let mut colors = vec![LinearRgb::default(); wide as usize];
        let mut hits = vec![HitRecord::default(); wide as usize];
        let mut sums = vec![[0.0f64; 3]; row.len()];
        let mut first = vec![None; row.len()];
        let mut mixed = vec![false; row.len()];
        for sy in 0..factor {
            let sample_row = y * factor + sy;
            frame.render_line(sample_row, &mut colors)?;
            frame.render_line(sample_row, &mut hits)?;
            for (sx, (c, h)) in colors.iter().zip(&hits).enumerate() {
                let x = sx / f;
                for (sum, v) in sums[x].iter_mut().zip([c.r, c.g, c.b]) {
                    *sum += f64::from(v.clamp(0.0, 1.0));
                }
                match first[x] {
                    None => first[x] = Some(h.sphere),
                    Some(s) if s != h.sphere => mixed[x] = true,
                    Some(_) => {}
                }
            }
        }
        let n = (f * f) as f64;
        for ((px, sum), mixed) in row.iter_mut().zip(&sums).zip(&mixed) {
            let [r, g, b] = sum.map(|s| quantize(s / n, 255.0) as u8);
            *px = Filtered {
                color: Rgb888 { r, g, b },
                silhouette: *mixed,
            };
        }
        Ok(())
    })
}

/// How close a frame's silhouette pixels come to the truth, in 8-bit levels (the largest
/// channel difference per pixel).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EdgeStats {
    /// Silhouette pixels in the frame.
    pub pixels: usize,
    /// The largest error.
    pub max: u8,
    /// The mean error.
    pub mean: f64,
    /// The share of silhouette pixels within 8 levels, in percent.
    pub within_8: f64,
}

/// `frame`'s errors against `truth` over the truth's silhouette pixels (`None` if it has
/// none, or the lengths differ).
pub fn edge_stats(truth: &[Filtered], frame: &[Rgb888]) -> Option<EdgeStats> {
    if truth.len() != frame.len() {
        return None;
    }
    let errors: Vec<u8> = truth
        .iter()
        .zip(frame)
        .filter(|(t, _)| t.silhouette)
        .map(|(t, p)| {
            let t = t.color;
            [t.r.abs_diff(p.r), t.g.abs_diff(p.g), t.b.abs_diff(p.b)]
                .into_iter()
                .max()
                .unwrap_or(0)
        })
        .collect();
    let max = *errors.iter().max()?;
    let n = errors.len();
    Some(EdgeStats {
        pixels: n,
        max,
        mean: errors.iter().map(|&e| f64::from(e)).sum::<f64>() / n as f64,
        within_8: 100.0 * errors.iter().filter(|&&e| e <= 8).count() as f64 / n as f64,
    })
}

/// One line of the silhouette table: a method and its statistics.
#[derive(Clone, Debug)]
pub struct EdgeRow {
    /// What was measured (`analytic (scalar)`, `4×4 supersampling`, …).
    pub method: String,
    /// Its statistics.
    pub stats: EdgeStats,
}

/// The silhouette table, in Markdown.
pub fn edge_table(rows: &[EdgeRow]) -> String {
    let mut out = String::from(
        "| silhouette pixels vs 16×16 truth | pixels | max levels | mean levels | within 8 |\n\
         |---|---|---|---|---|\n",
    );
    for r in rows {
        let s = r.stats;
        out.push_str(&format!(
            "| {} | {} | {} | {:.2} | {:.2}% |\n",
            r.method, s.pixels, s.max, s.mean, s.within_8
        ));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn px(v: u8, silhouette: bool) -> Filtered {
        Filtered {
            color: Rgb888 { r: v, g: v, b: v },
            silhouette,
        }
    }

    #[test]
    fn statistics_count_only_silhouette_pixels() {
        let truth = [px(10, true), px(10, false), px(100, true), px(0, true)];
        let frame = [
            Rgb888 {
                r: 10,
                g: 19,
                b: 10,
            },
            Rgb888 { r: 200, g: 0, b: 0 }, // not a silhouette: ignored
            Rgb888 {
                r: 100,
                g: 100,
                b: 100,
            },
            Rgb888 { r: 0, g: 0, b: 8 },
        ];
        let s = edge_stats(&truth, &frame).unwrap();
        assert_eq!(s.pixels, 3);
        assert_eq!(s.max, 9);
        assert!((s.mean - 17.0 / 3.0).abs() < 1e-12);
        assert!((s.within_8 - 200.0 / 3.0).abs() < 1e-9);
        assert_eq!(edge_stats(&truth[..1], &frame), None);
        assert_eq!(edge_stats(&[px(1, false)], &frame[..1]), None);
    }
}
