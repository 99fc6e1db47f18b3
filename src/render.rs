//! The row driver: one row of pixels into the caller's slice.
//!
//! For row `y` it computes every sphere's [`Span`], merges them into covered runs,
//! fills everything outside the runs with the background pixel (encoded once per row, no
//! per-pixel work), and walks each run in packets of the path's lane count, handing the kernel
//! only the spheres whose spans touch the packet. The last packet of a run computes full lanes
//! and stores only the pixels that belong to the run: no per-lane branch in the math, no read
//! or write outside the caller's slice.
//!
//! A row is a pure function of the prepared frame and `y`: rows can be rendered in any order,
//! on any number of threads, or streamed to a display one line buffer at a time.

use crate::float_kernel::Packet;
use crate::lane::Lane;
use crate::pixel::{HitRecord, LinearRgb, Pixel, Shade};
use crate::prepare::{FloatPath, Prepared};
use crate::scene::Item;
use crate::spans::Span;
use core::fmt;

/// Why a row or frame could not be rendered. Nothing is written when one is returned.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum RenderError {
    /// A width or height of 0, or above [`MAX_DIMENSION`](crate::MAX_DIMENSION).
    BadSize {
        /// The requested width.
        width: u32,
        /// The requested height.
        height: u32,
    },
    /// The row slice's length is not the image width.
    LineLength {
        /// The image width.
        expected: usize,
        /// The slice's length.
        got: usize,
    },
    /// The frame slice's length is not width × height.
    FrameLength {
        /// width × height.
        expected: usize,
        /// The slice's length.
        got: usize,
    },
    /// The row index is not below the image height.
    RowOutOfRange {
        /// The requested row.
        y: u32,
        /// The image height.
        height: u32,
    },
    /// A number of the scene does not fit the fixed-point path's formats (see
    /// [`crate::fixed`]); only [`PreparedFixed::new`](crate::PreparedFixed::new) returns it.
    OutOfFixedRange {
        /// The item holding the number.
        item: Item,
        /// The field's name, as spelled in the scene file.
        field: &'static str,
    },
}

impl fmt::Display for RenderError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            RenderError::BadSize { width, height } => write!(
                f,
                "image size {width}x{height} is not supported (each side must be 1..={})",
                crate::MAX_DIMENSION
            ),
            RenderError::LineLength { expected, got } => write!(
                f,
                "row buffer holds {got} pixels, the image is {expected} pixels wide"
            ),
            RenderError::FrameLength { expected, got } => write!(
                f,
                "frame buffer holds {got} pixels, the image has {expected}"
            ),
            RenderError::RowOutOfRange { y, height } => {
                write!(f, "row {y} is outside an image {height} rows high")
            }
            RenderError::OutOfFixedRange { item, field } => write!(
                f,
                "{item}: `{field}` does not fit the fixed-point path's number formats"
            ),
        }
    }
}

impl core::error::Error for RenderError {}

/// Anything that renders rows: every path's prepared frame implements it.
///
/// ```
/// use shadeline::{Prepared, Render, Simd8, Rgb565, exponent_series};
/// let frame = Prepared::<Simd8>::new(&exponent_series()?, 32, 24)?;
/// let mut pixels = [Rgb565::default(); 32 * 24];
/// frame.render_frame(&mut pixels)?;
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub trait Render {
    /// The image width in pixels.
    fn width(&self) -> u32;
    /// The image height in pixels.
    fn height(&self) -> u32;
    /// Shades row `y` (0 = top) into `out`, which must be exactly `width` pixels long.
    fn render_line<P: Pixel>(&self, y: u32, out: &mut [P]) -> Result<(), RenderError>;
    /// Shades every row into `frame`, row-major, exactly `width × height` pixels long.
    fn render_frame<P: Pixel>(&self, frame: &mut [P]) -> Result<(), RenderError> {
        let w = self.width() as usize;
        let expected = w * self.height() as usize;
        if frame.len() != expected {
            return Err(RenderError::FrameLength {
                expected,
                got: frame.len(),
            });
        }
        for (y, row) in frame.chunks_exact_mut(w).enumerate() {
            self.render_line(y as u32, row)?;
        }
        Ok(())
    }
}

/// Checks a row request against an image size.
pub(crate) fn check_line(y: u32, len: usize, width: u32, height: u32) -> Result<(), RenderError> {
    if y >= height {
        return Err(RenderError::RowOutOfRange { y, height });
    }
    if len != width as usize {
        return Err(RenderError::LineLength {
            expected: width as usize,
            got: len,
        });
    }
    Ok(())
}

/// Merged covered runs of a row: `[start, end)` pixel ranges, sorted, disjoint.
pub(crate) fn merge_runs<const S: usize>(spans: &[Option<Span>]) -> heapless::Vec<Span, S> {
    let mut runs: heapless::Vec<Span, S> = heapless::Vec::new();
    for span in spans.iter().flatten() {
        let _ = runs.push(*span);
    }
    // Insertion sort by start: S is small and this is once per row. Written with a slice
    // pattern instead of indexing so that no bounds check (and no panic path) is left for
    // the firmware's link-time panic proof to find.
    for i in 1..runs.len() {
        let mut j = i;
        while j > 0 {
            match runs.get_mut(j - 1..=j) {
                Some([a, b]) if a.start > b.start => core::mem::swap(a, b),
                _ => break,
            }
            j -= 1;
        }
    }
    let mut merged: heapless::Vec<Span, S> = heapless::Vec::new();
    for span in runs {
        match merged.last_mut() {
            Some(last) if span.start <= last.end => last.end = last.end.max(span.end),
            _ => {
                let _ = merged.push(span);
            }
        }
    }
    merged
}

impl<W: FloatPath, const S: usize, const L: usize> Prepared<W, S, L> {
    /// Turns the scanline spans on (the default) or off. Off, every packet tests every sphere:
    /// the naive per-pixel renderer, kept for benchmarks and for the test that spans change
    /// no pixel.
    pub fn with_spans(mut self, on: bool) -> Self {
        self.use_spans = on;
        self
    }

    fn background_pixel<P: Pixel>(&self) -> P {
        P::encode(&Shade {
            color: self.background,
            hit: HitRecord::default(),
        })
    }
}

impl<W: FloatPath, const S: usize, const L: usize> Render for Prepared<W, S, L> {
    fn width(&self) -> u32 {
        self.width
    }

    fn height(&self) -> u32 {
        self.height
    }

    fn render_line<P: Pixel>(&self, y: u32, out: &mut [P]) -> Result<(), RenderError> {
        check_line(y, out.len(), self.width, self.height)?;
        let lanes = W::Lane::LANES;
        let row = self.row(y);
        let spans = self.row_spans(y);
        let runs = merge_runs::<S>(&spans);
        let background = self.background_pixel::<P>();

        let mut x = 0usize;
        for run in &runs {
            let (start, end) = (run.start as usize, run.end as usize);
            if let Some(gap) = out.get_mut(x..start) {
                gap.fill(background);
            }
            x = end;
            let Some(run_pixels) = out.get_mut(start..end) else {
                continue;
            };
            for (chunk_index, chunk) in run_pixels.chunks_mut(lanes).enumerate() {
                let x0 = (start + chunk_index * lanes) as u32;
                let x1 = x0 + chunk.len() as u32;
                let mut candidates: heapless::Vec<u16, S> = heapless::Vec::new();
                for (k, span) in spans.iter().enumerate() {
                    if let Some(s) = span {
                        if s.start < x1 && x0 < s.end {
                            let _ = candidates.push(k as u16);
                        }
                    }
                }
                if candidates.is_empty() {
                    chunk.fill(background);
                    continue;
                }
                let packet = self.shade_packet(&row, x0, &candidates, P::NEEDS_HITS);
                store_packet(chunk, &packet);
            }
        }
        if let Some(tail) = out.get_mut(x..) {
            tail.fill(background);
        }
        Ok(())
    }
}

/// The encode stage of the float paths: writes the first `chunk.len()` lanes of a packet.
///
/// Formats with levels are quantized a packet at a time, with the rule of
/// [`quantize`](crate::pixel::quantize) (clamp with NaN to 0, `c·max + ½`, truncate), so every
/// width stores the bits the scalar path stores.
#[inline(always)]
fn store_packet<P: Pixel, T: Lane>(chunk: &mut [P], packet: &Packet<T>) {
    if let Some(max) = P::LEVELS {
        let zero = T::splat(0.0);
        let one = T::splat(1.0);
        let half = T::splat(0.5);
        let quantize = |c: T, max: u16| {
            let c = T::select(zero.lt(c), c, zero);
            let c = T::select(c.lt(one), c, one);
            (c * T::splat(max as f32) + half).trunc_lanes()
        };
        let r = quantize(packet.color.x, max[0]);
        let g = quantize(packet.color.y, max[1]);
        let b = quantize(packet.color.z, max[2]);
        for (px, ((r, g), b)) in chunk.iter_mut().zip(r.iter().zip(&g).zip(&b)) {
            *px = P::from_levels([*r as u16, *g as u16, *b as u16]);
        }
        return;
    }
    let (r, g, b) = (
        packet.color.x.to_lanes(),
        packet.color.y.to_lanes(),
        packet.color.z.to_lanes(),
    );
    let spheres = packet.sphere.to_lanes();
    let lanes = r.iter().zip(&g).zip(&b).zip(&spheres).zip(&packet.shadowed);
    for (px, ((((r, g), b), sphere), shadowed)) in chunk.iter_mut().zip(lanes) {
        let hit = *sphere >= 0.0;
        *px = P::encode(&Shade {
            color: LinearRgb::new(*r, *g, *b),
            hit: HitRecord {
                sphere: hit.then_some(*sphere as u16),
                shadowed: if hit { *shadowed } else { 0 },
            },
        });
    }
}
