//! What every path's prepared frame offers: the [`Render`] trait, its errors
//! ([`RenderError`]) and the size limits.
//!
//! A path implements two methods: [`Render::render_segment_with`] (any run of pixels of one
//! row, with an explicit [`Encoding`]) and [`Render::row_coverage`] (which part of a row the
//! spheres may cover, so sinks can skip background rows). The sinks are built on them once,
//! for every path: [`Render::render_line`], [`Render::render_frame`],
//! [`Render::render_line_bytes`] and, with the `embedded-graphics` feature, `eg::Drawing`.
//! The row drivers themselves are `src/float/row.rs` and `src/fixed/row.rs`.
//!
//! A row is a pure function of the prepared frame and `y`: rows can be rendered in any order,
//! on any number of threads, or streamed to a display one line buffer at a time.

use crate::encoding::Encoding;
use crate::pixel::{BytePixel, Pixel};
use crate::runs::Span;
use crate::scene::Item;
use core::fmt;

/// Largest accepted image width or height, in pixels, on every path.
///
/// Pixel indices stay exact in `f32` far beyond this; the limit keeps `width × height`
/// within `u32` and matches what a 16-bit display controller can address.
pub const MAX_DIMENSION: u32 = 65_535;

/// Why a row or frame could not be rendered. Nothing is written when one is returned.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum RenderError {
    /// A width or height of 0, or above [`MAX_DIMENSION`].
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
        /// For a sphere's `radius` below `2⁻¹³` of the scene's extent: the index of the
        /// scene's largest sphere (a floor sphere, say), when its size sets the extent, which
        /// shrinking would let the small one fit. `None` for a number out of range on its
        /// own, or when the camera's distance sets the extent.
        beside: Option<u16>,
    },
    /// A point light has a radius (a sphere light), and this build renders point lights of
    /// radius 0 only on this path: the fixed path with the crate feature `area-lights` but
    /// without `full-width`. (Without `area-lights` a scene holds no sphere light:
    /// [`Scene::add_light`](crate::Scene::add_light) refuses one.) The `f64`
    /// [`reference`](crate::reference) renders sphere lights.
    SphereLight {
        /// The light's index.
        light: usize,
    },
    /// The frame needs the fixed path's full-width kernel, which this build leaves out
    /// (crate feature `full-width`): the narrow kernel takes distant and point lights (of
    /// radius 0), every model but Oren–Nayar and GGX, a field of view up to about 90° on the
    /// diagonal, and spheres the camera is clearly outside of (see [`crate::fixed`]);
    /// only [`PreparedFixed::new`](crate::PreparedFixed::new) returns it.
    NeedsFullWidth {
        /// The first item the narrow kernel does not take.
        item: Item,
        /// Its field that keeps it from the narrow kernel, as spelled in the scene file
        /// (`model`, `vfov`, `center`, `radius`).
        field: &'static str,
    },
    /// The frame has a point light or a sphere of a normalized model, whose stages of the
    /// fixed path's narrow kernel this build leaves out (crate feature `narrow-precise`), and
    /// no full-width kernel either; only [`PreparedFixed::new`](crate::PreparedFixed::new)
    /// returns it.
    NeedsNarrowPrecise {
        /// The first point light or normalized sphere.
        item: Item,
        /// `type` for a point light, `model` for a sphere.
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
            RenderError::OutOfFixedRange {
                item,
                field,
                beside: Some(large),
            } => write!(
                f,
                "{item}: `{field}` is below 1/8192 of the scene's extent, which sphere {large} \
                 sets, and does not fit the fixed-point path's number formats beside it: make \
                 sphere {large} smaller (a floor sphere 1,000 times the radius of the spheres on it looks as \
                 flat as one 10,000 times) or {item} larger"
            ),
            RenderError::OutOfFixedRange { item, field, .. } => write!(
                f,
                "{item}: `{field}` does not fit the fixed-point path's number formats"
            ),
            RenderError::SphereLight { light } => write!(
                f,
                "light {light}: `radius` is not 0, and this path renders point lights of radius 0 only"
            ),
            RenderError::NeedsFullWidth { item, field } => write!(
                f,
                "{item}: `{field}` needs the fixed path's full-width kernel, which this build \
                 leaves out (crate feature `full-width`)"
            ),
            RenderError::NeedsNarrowPrecise { item, field } => write!(
                f,
                "{item}: `{field}` needs the fixed narrow kernel's point-light and \
                 normalized-model stages, which this build leaves out (crate feature \
                 `narrow-precise`)"
            ),
        }
    }
}

impl core::error::Error for RenderError {}

/// The kernel a prepared frame's rows take: each path chooses it once per frame, in its
/// prepare, says it through [`Render::kernel`], and its row driver dispatches on it with one
/// `match`.
///
/// ```
/// use shadeline::{exponent_series, lamp, Item, Kernel, Prepared, Render, Scalar};
/// let series = Prepared::<Scalar, _, _>::new(&exponent_series()?, 64, 48)?;
/// assert_eq!(series.kernel(), Kernel::Narrow);
/// let lamp = Prepared::<Scalar, _, _>::new(&lamp()?, 64, 48)?;
/// assert_eq!(lamp.kernel(), Kernel::General { item: Item::Light(0), field: "type" });
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kernel {
    /// The narrow kernel: classic Phong, Blinn-Phong and Lambert under distant lights (and, on the fixed path, point lights of radius 0), shaded from
    /// per-row quadrics of the column, on every sphere the camera is clearly outside of.
    Narrow,
    /// The path's general kernel (on the fixed path, the full-width one), because the
    /// narrow kernel does not take `item`'s `field`: the first such item found.
    General {
        /// The first item the narrow kernel does not take.
        item: Item,
        /// Its field, as spelled in the scene file: `type` (a point light, on the float
        /// paths), `radius` (a sphere light, or a number out of the narrow kernel's formats), `model`,
        /// `shininess`, `vfov`, `center` (the camera close to the sphere, or a sphere close
        /// to its casters).
        field: &'static str,
    },
}

impl fmt::Display for Kernel {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Kernel::Narrow => f.write_str("narrow"),
            Kernel::General { item, field } => write!(f, "general, for {item}: `{field}`"),
        }
    }
}

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
    /// The kernel this frame's rows take, chosen once in the path's prepare, and why if it
    /// is not the narrow one (see [`Kernel`]).
    fn kernel(&self) -> Kernel;

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
            // `out` holds at most LINE_CHUNK pixels' bytes: cannot fail.
            debug_assert!(n <= LINE_CHUNK, "{n} pixels in a chunk");
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

/// A prepared frame together with the [`Encoding`] it renders with; built by
/// [`Render::with_encoding`].
///
/// It implements [`Render`] (so [`render_line`](Render::render_line),
/// [`render_frame`](Render::render_frame) and the byte and embedded-graphics sinks all use the
/// encoding); the frame itself stays reachable with [`Encoded::frame`].
///
/// Why a wrapper and not a field of each path's prepared frame: the encoding is the same
/// concern for every path, and the wrapper makes it one type that works with any [`Render`].
#[derive(Clone, Debug)]
pub struct Encoded<R> {
    frame: R,
    encoding: Encoding,
}

impl<R: Render> Encoded<R> {
    /// `frame` rendering with `encoding`.
    pub fn new(frame: R, encoding: Encoding) -> Self {
        Encoded { frame, encoding }
    }

    /// The wrapped frame.
    pub fn frame(&self) -> &R {
        &self.frame
    }

    /// The wrapped frame, unwrapped.
    pub fn into_frame(self) -> R {
        self.frame
    }
}

impl<R: Render> Render for Encoded<R> {
    fn width(&self) -> u32 {
        self.frame.width()
    }

    fn height(&self) -> u32 {
        self.frame.height()
    }

    fn encoding(&self) -> Encoding {
        self.encoding
    }

    fn render_segment_with<P: Pixel>(
        &self,
        y: u32,
        x: u32,
        out: &mut [P],
        encoding: Encoding,
    ) -> Result<(), RenderError> {
        self.frame.render_segment_with(y, x, out, encoding)
    }

    fn row_coverage(&self, y: u32) -> Option<Span> {
        self.frame.row_coverage(y)
    }

    fn kernel(&self) -> Kernel {
        self.frame.kernel()
    }
}
