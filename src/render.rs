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

use crate::encoding::{linear_code, pixel_from_codes, Encoded, Encoding};
use crate::float_kernel::Packet;
use crate::lane::Lane;
use crate::pixel::{BytePixel, HitRecord, LinearRgb, Pixel, Shade};
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
    /// A segment of a row reaches past the image width.
    SegmentOutOfRange {
        /// The segment's first pixel.
        x: u32,
        /// The segment's length in pixels.
        len: usize,
        /// The image width.
        width: u32,
    },
    /// A byte row's length is not the image width times the format's bytes per pixel.
    ByteLength {
        /// width × bytes per pixel.
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
            RenderError::SegmentOutOfRange { x, len, width } => write!(
                f,
                "a segment of {len} pixels at x = {x} does not fit a row {width} pixels wide"
            ),
            RenderError::ByteLength { expected, got } => write!(
                f,
                "byte row holds {got} bytes, the image row needs {expected}"
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
/// A path implements [`render_segment_with`](Render::render_segment_with) (any run of pixels
/// of one row, with an explicit [`Encoding`]) and, to let sinks skip background rows,
/// [`row_coverage`](Render::row_coverage); everything else is built on those.
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

    /// Shades pixels `x .. x + out.len()` of row `y` (0 = top) into `out`, with `encoding`
    /// instead of the frame's own. A pixel's value depends only on the frame, its `(x, y)` and
    /// the encoding, never on how a row is cut into segments.
    ///
    /// Fails with [`RenderError::RowOutOfRange`] or [`RenderError::SegmentOutOfRange`]
    /// (nothing written).
    fn render_segment_with<P: Pixel>(
        &self,
        y: u32,
        x: u32,
        out: &mut [P],
        encoding: Encoding,
    ) -> Result<(), RenderError>;

    /// The encoding [`render_line`](Render::render_line) and the other sinks use:
    /// [`Encoding::LINEAR`] unless the frame was wrapped by
    /// [`with_encoding`](Render::with_encoding).
    fn encoding(&self) -> Encoding {
        Encoding::LINEAR
    }

    /// The pixel range `[start, end)` of row `y` that the spheres may cover, or `None` if
    /// every pixel of the row is background (then the row is the background colour encoded
    /// at each position). Conservative: a covered pixel is never outside it. The default
    /// says the whole row may be covered.
    fn row_coverage(&self, y: u32) -> Option<Span> {
        let _ = y;
        Some(Span {
            start: 0,
            end: self.width(),
        })
    }

    /// Shades pixels `x .. x + out.len()` of row `y` with the frame's
    /// [`encoding`](Render::encoding).
    fn render_segment<P: Pixel>(&self, y: u32, x: u32, out: &mut [P]) -> Result<(), RenderError> {
        self.render_segment_with(y, x, out, self.encoding())
    }

    /// Shades row `y` (0 = top) into `out`, which must be exactly `width` pixels long
    /// ([`RenderError::LineLength`] otherwise).
    fn render_line<P: Pixel>(&self, y: u32, out: &mut [P]) -> Result<(), RenderError> {
        check_line(y, out.len(), self.width(), self.height())?;
        self.render_segment(y, 0, out)
    }

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

    /// Shades row `y` into `bytes` in the byte layout of format `P` (see [`BytePixel`]:
    /// RGB565 and BGR565 big-endian, as SPI display controllers take them), ready for a DMA
    /// transfer. `bytes` must be exactly `width × P::BYTES` long ([`RenderError::ByteLength`]
    /// otherwise; nothing is written on an error).
    ///
    /// The row is rendered [`LINE_CHUNK`] pixels at a time into a stack buffer of `P` and
    /// copied out as bytes: no allocation, no `unsafe` cast of the byte slice, and a stack
    /// cost of `LINE_CHUNK × size_of::<P>()` bytes whatever the width.
    ///
    /// ```
    /// use shadeline::{exponent_series, Prepared, Render, Rgb565, Scalar};
    /// let frame = Prepared::<Scalar>::new(&exponent_series()?, 40, 30)?;
    /// let mut bytes = [0u8; 40 * 2];
    /// frame.render_line_bytes::<Rgb565>(15, &mut bytes)?;
    /// let mut line = [Rgb565::default(); 40];
    /// frame.render_line(15, &mut line)?;
    /// assert_eq!(bytes[..2], line[0].0.to_be_bytes());
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    fn render_line_bytes<P: BytePixel>(&self, y: u32, bytes: &mut [u8]) -> Result<(), RenderError> {
        let expected = self.width() as usize * P::BYTES;
        if y >= self.height() {
            return Err(RenderError::RowOutOfRange {
                y,
                height: self.height(),
            });
        }
        if bytes.len() != expected {
            return Err(RenderError::ByteLength {
                expected,
                got: bytes.len(),
            });
        }
        let mut chunk = [P::default(); LINE_CHUNK];
        for (i, out) in bytes.chunks_mut(LINE_CHUNK * P::BYTES).enumerate() {
            let n = out.len() / P::BYTES;
            let Some(pixels) = chunk.get_mut(..n) else {
                break;
            };
            self.render_segment(y, (i * LINE_CHUNK) as u32, pixels)?;
            for (dst, px) in out.chunks_exact_mut(P::BYTES).zip(pixels.iter()) {
                for (d, s) in dst.iter_mut().zip(px.to_bytes().as_ref()) {
                    *d = *s;
                }
            }
        }
        Ok(())
    }

    /// This frame, rendering with `encoding` from now on (see [`crate::encoding`]).
    ///
    /// ```
    /// use shadeline::{exponent_series, Encoding, PreparedFixed, Render, Gray8};
    /// let frame = PreparedFixed::new(&exponent_series()?, 64, 48)?
    ///     .with_encoding(Encoding::SRGB.dithered());
    /// let mut line = [Gray8::default(); 64];
    /// frame.render_line(24, &mut line)?;
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    fn with_encoding(self, encoding: Encoding) -> Encoded<Self>
    where
        Self: Sized,
    {
        Encoded::new(self, encoding)
    }
}

/// Pixels per stack chunk of the byte and embedded-graphics sinks.
pub const LINE_CHUNK: usize = 64;

/// Checks a segment request against an image size.
pub(crate) fn check_segment(
    y: u32,
    x: u32,
    len: usize,
    width: u32,
    height: u32,
) -> Result<(), RenderError> {
    if y >= height {
        return Err(RenderError::RowOutOfRange { y, height });
    }
    if x as usize + len > width as usize {
        return Err(RenderError::SegmentOutOfRange { x, len, width });
    }
    Ok(())
}

/// The covered hull of a row's spans: from the smallest start to the largest end.
pub(crate) fn coverage_of(spans: &[Option<Span>]) -> Option<Span> {
    spans.iter().flatten().fold(None, |acc: Option<Span>, s| {
        Some(match acc {
            None => *s,
            Some(a) => Span {
                start: a.start.min(s.start),
                end: a.end.max(s.end),
            },
        })
    })
}

/// The background of one row, encoded: one pixel, or four (`x mod 4`) when dithering.
pub(crate) struct Background<P> {
    pixels: [P; 4],
    dither: bool,
}

impl<P: Pixel> Background<P> {
    /// `pixel(x)` encodes the background at column `x` (called for `x` in `0..4`, or once
    /// with 0 when not dithering).
    #[inline(always)]
    pub(crate) fn new(encoding: Encoding, pixel: impl Fn(u32) -> P) -> Self {
        let first = pixel(0);
        if encoding.dither && P::LEVELS.is_some() {
            Background {
                pixels: [first, pixel(1), pixel(2), pixel(3)],
                dither: true,
            }
        } else {
            Background {
                pixels: [first; 4],
                dither: false,
            }
        }
    }

    /// The pixel at column `x`.
    #[inline(always)]
    pub(crate) fn at(&self, x: usize) -> P {
        self.pixels[x & 3]
    }

    /// Fills `out`, whose first pixel is column `x`.
    ///
    /// The first pixels (one period of the pattern: 1, or 4 when dithering) are written one
    /// by one, the rest by doubling copies of what is already there: `[P]::fill` is a loop
    /// per element for 3-byte pixels, while a copy is a `memcpy`. The dither pattern has
    /// period 4 and every copy lands a multiple of 4 pixels further on, so it stays in phase.
    #[inline(always)]
    pub(crate) fn fill(&self, out: &mut [P], x: usize) {
        let period = if self.dither { 4 } else { 1 };
        for (px, x) in out.iter_mut().zip(x..).take(period) {
            *px = self.at(x);
        }
        let mut filled = period;
        while filled < out.len() {
            let (head, tail) = out.split_at_mut(filled);
            let n = head.len().min(tail.len());
            if let (Some(dst), Some(src)) = (tail.get_mut(..n), head.get(..n)) {
                dst.copy_from_slice(src);
            }
            filled += n;
        }
    }
}

/// The walk both row drivers share over the segment of a row that starts at column
/// `seg_start` and fills `out`: the background everywhere outside the covered `runs` (sorted,
/// disjoint), and `shade(first_column, pixels)` on each run's part inside the segment. Every
/// slice is reached through `get_mut`, so nothing here can panic.
#[inline(always)]
pub(crate) fn walk_runs<P: Pixel>(
    out: &mut [P],
    seg_start: usize,
    runs: &[Span],
    background: &Background<P>,
    mut shade: impl FnMut(usize, &mut [P]),
) {
    let seg_end = seg_start + out.len();
    let mut x = seg_start;
    for run in runs {
        let start = (run.start as usize).max(seg_start);
        let end = (run.end as usize).min(seg_end);
        if start >= end {
            continue;
        }
        if let Some(gap) = out.get_mut(x - seg_start..start - seg_start) {
            background.fill(gap, x);
        }
        x = end;
        if let Some(run_pixels) = out.get_mut(start - seg_start..end - seg_start) {
            shade(start, run_pixels);
        }
    }
    if let Some(tail) = out.get_mut(x - seg_start..) {
        background.fill(tail, x);
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

    fn background_pixel<P: Pixel>(&self, encoding: Encoding, x: u32, y: u32) -> P {
        if !encoding.is_default() {
            let c = self.background;
            let codes = [linear_code(c.r), linear_code(c.g), linear_code(c.b)];
            if let Some(px) = pixel_from_codes(codes, encoding, x, y) {
                return px;
            }
        }
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

    fn row_coverage(&self, y: u32) -> Option<Span> {
        coverage_of(&self.row_spans(y))
    }

    fn render_segment_with<P: Pixel>(
        &self,
        y: u32,
        x: u32,
        out: &mut [P],
        encoding: Encoding,
    ) -> Result<(), RenderError> {
        check_segment(y, x, out.len(), self.width, self.height)?;
        let lanes = W::Lane::LANES;
        let row = self.row(y);
        let spans = self.row_spans(y);
        let runs = merge_runs::<S>(&spans);
        let background = Background::new(encoding, |x| self.background_pixel::<P>(encoding, x, y));
        walk_runs(out, x as usize, &runs, &background, |start, run_pixels| {
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
                    background.fill(chunk, x0 as usize);
                    continue;
                }
                let packet = self.shade_packet(&row, x0, &candidates, P::NEEDS_HITS);
                store_packet(chunk, &packet, encoding, x0, y);
            }
        });
        Ok(())
    }
}

/// The encode stage of the float paths: writes the first `chunk.len()` lanes of a packet
/// whose first pixel is `(x0, y)`.
///
/// With [`Encoding::LINEAR`], formats with levels are quantized a packet at a time, with the
/// rule of [`quantize`](crate::pixel::quantize) (clamp with NaN to 0, `c·max + ½`, truncate;
/// [`Gray8`](crate::Gray8) on the luma), so every width stores the bits the scalar path stores.
/// Other encodings compute the linear codes a packet at a time
/// ([`linear_code`]'s operations) and then apply the encoding's integer rule per pixel
/// ([`crate::encoding`]).
#[inline(always)]
fn store_packet<P: Pixel, T: Lane>(
    chunk: &mut [P],
    packet: &Packet<T>,
    encoding: Encoding,
    x0: u32,
    y: u32,
) {
    if let Some(max) = P::LEVELS {
        let zero = T::splat(0.0);
        let one = T::splat(1.0);
        let half = T::splat(0.5);
        let clamp = |c: T| {
            let c = T::select(zero.lt(c), c, zero);
            T::select(c.lt(one), c, one)
        };
        let quantize = |c: T, max: f32| (clamp(c) * T::splat(max) + half).trunc_lanes();
        if encoding.is_default() {
            if P::GRAY {
                let [wr, wg, wb] = crate::encoding::LUMA_WEIGHTS_F32;
                let luma = clamp(packet.color.x) * T::splat(wr)
                    + clamp(packet.color.y) * T::splat(wg)
                    + clamp(packet.color.z) * T::splat(wb);
                let l = quantize(luma, max[0] as f32);
                for (px, l) in chunk.iter_mut().zip(&l) {
                    *px = P::from_levels([*l as u16; 3]);
                }
                return;
            }
            let r = quantize(packet.color.x, max[0] as f32);
            let g = quantize(packet.color.y, max[1] as f32);
            let b = quantize(packet.color.z, max[2] as f32);
            for (px, ((r, g), b)) in chunk.iter_mut().zip(r.iter().zip(&g).zip(&b)) {
                *px = P::from_levels([*r as u16, *g as u16, *b as u16]);
            }
            return;
        }
        let r = quantize(packet.color.x, 65536.0);
        let g = quantize(packet.color.y, 65536.0);
        let b = quantize(packet.color.z, 65536.0);
        let codes = r.iter().zip(&g).zip(&b);
        for ((px, ((r, g), b)), x) in chunk.iter_mut().zip(codes).zip(x0..) {
            if let Some(p) = pixel_from_codes([*r as u32, *g as u32, *b as u32], encoding, x, y) {
                *px = p;
            }
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
