//! embedded-graphics support (feature `embedded-graphics`): draw a prepared frame into any
//! embedded-graphics `DrawTarget`, such as a `mipidsi` display, with few and large transfers,
//! and convert shadeline's pixel formats to and from embedded-graphics' colours.
//!
//! [`Drawing`] is a `Drawable` for any [`Render`] (every path, with its
//! [`Encoding`](crate::Encoding)). It draws row by row:
//!
//! - a row the spheres may touch ([`Render::row_coverage`] is `Some`) is one
//!   `DrawTarget::fill_contiguous` over the full-width one-row rectangle;
//! - a row of pure background that encodes to one colour is one `DrawTarget::fill_solid`
//!   over the same rectangle (a dithered background that is not exactly a level varies along
//!   the row and takes the contiguous fill instead).
//!
//! So a display driver gets one window command and one long pixel stream per row, and
//! background rows cost it no per-pixel iteration at all. Each pixel equals what
//! [`Render::render_line`] gives for the matching shadeline format, converted exactly. The
//! colours ([`EgColor`]), all in `embedded_graphics_core::pixelcolor`, and their formats:
//!
//! | embedded-graphics colour | shadeline format | conversion |
//! |---|---|---|
//! | `pixelcolor::Rgb565` | [`Rgb565`](crate::Rgb565) | the 5/6/5 levels |
//! | `pixelcolor::Bgr565` | [`Bgr565`](crate::Bgr565) | the 5/6/5 levels (blue in the high bits in both) |
//! | `pixelcolor::Rgb888` | [`Rgb888`](crate::Rgb888) | the 8-bit levels |
//! | `pixelcolor::Gray8` | [`Gray8`](crate::Gray8) | the 8-bit luma |
//!
//! Each pair converts both ways with `From` (the same levels, no rounding; for the 16-bit
//! formats also the same `u16`), so a shadeline pixel from [`Render::render_line`] goes
//! straight into embedded-graphics code and back:
//!
//! ```
//! use embedded_graphics_core::pixelcolor::{self, RgbColor};
//! let p = shadeline::Rgb565::pack(31, 0, 4);
//! let c = pixelcolor::Rgb565::from(p);
//! assert_eq!((c.r(), c.g(), c.b()), (31, 0, 4));
//! assert_eq!(shadeline::Rgb565::from(c), p);
//! ```
//!
//! No allocation and no width limit: the colours handed to `fill_contiguous` come from an
//! iterator that renders [`LINE_CHUNK`] pixels at a time into a stack buffer
//! (`LINE_CHUNK × 3` bytes at most), so stack use does not grow with the width. Rows are
//! rendered through [`Render::render_segment`], whose output does not depend on how a row is
//! cut. The frame is drawn at [`Drawing::at`]'s offset (the origin by default); the target
//! clips as embedded-graphics requires.
//!
//! ```
//! use embedded_graphics_core::{pixelcolor::Rgb565, prelude::*, primitives::Rectangle};
//! use shadeline::{eg::Drawing, exponent_series, Encoding, PreparedFixed, Render};
//!
//! # struct Display { pixels: [Rgb565; 64 * 48] }
//! # impl OriginDimensions for Display { fn size(&self) -> Size { Size::new(64, 48) } }
//! # impl DrawTarget for Display {
//! #     type Color = Rgb565;
//! #     type Error = core::convert::Infallible;
//! #     fn draw_iter<I: IntoIterator<Item = Pixel<Rgb565>>>(&mut self, it: I) -> Result<(), Self::Error> {
//! #         for Pixel(p, c) in it {
//! #             if let (Ok(x), Ok(y)) = (usize::try_from(p.x), usize::try_from(p.y)) {
//! #                 if x < 64 && y < 48 { self.pixels[y * 64 + x] = c; }
//! #             }
//! #         }
//! #         Ok(())
//! #     }
//! # }
//! # let mut display = Display { pixels: [Rgb565::BLACK; 64 * 48] };
//! let frame = PreparedFixed::new(&exponent_series()?, 64, 48)?
//!     .with_encoding(Encoding::LINEAR.dithered());
//! Drawing::new(&frame).draw(&mut display)?; // `display`: any DrawTarget<Color = Rgb565>
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use crate::pixel::BytePixel;
use crate::render::{Render, LINE_CHUNK};
use core::marker::PhantomData;
use embedded_graphics_core::draw_target::DrawTarget;
use embedded_graphics_core::geometry::{Point, Size};
use embedded_graphics_core::pixelcolor::{self, GrayColor, PixelColor, RgbColor};
use embedded_graphics_core::primitives::Rectangle;
use embedded_graphics_core::Drawable;

/// An embedded-graphics colour that a shadeline format converts to exactly: the colours a
/// [`Drawing`] can draw (`pixelcolor::Rgb565`, `Bgr565`, `Rgb888` and `Gray8`).
pub trait EgColor: PixelColor {
    /// The shadeline format rendered for this colour.
    type Pixel: BytePixel + PartialEq;
    /// The colour of a rendered pixel (same levels, no rounding): the `From` conversion.
    fn from_pixel(p: Self::Pixel) -> Self;
}

/// The conversions both ways between a shadeline format and its embedded-graphics colour, and
/// [`EgColor`] for the colour.
macro_rules! colour_pair {
    ($name:ident, $to_eg:expr, $from_eg:expr) => {
        impl From<crate::$name> for pixelcolor::$name {
            /// The same levels as an embedded-graphics colour.
            #[inline]
            fn from(p: crate::$name) -> Self {
                $to_eg(p)
            }
        }

        impl From<pixelcolor::$name> for crate::$name {
            /// The same levels as a shadeline pixel.
            #[inline]
            fn from(c: pixelcolor::$name) -> Self {
                $from_eg(c)
            }
        }

        impl EgColor for pixelcolor::$name {
            type Pixel = crate::$name;
            #[inline]
            fn from_pixel(p: crate::$name) -> Self {
                Self::from(p)
            }
        }
    };
}

colour_pair!(
    Rgb565,
    |p: crate::Rgb565| {
        let (r, g, b) = p.levels();
        pixelcolor::Rgb565::new(r, g, b)
    },
    |c: pixelcolor::Rgb565| crate::Rgb565::pack(c.r().into(), c.g().into(), c.b().into())
);
colour_pair!(
    Bgr565,
    |p: crate::Bgr565| {
        let (r, g, b) = p.levels();
        pixelcolor::Bgr565::new(r, g, b)
    },
    |c: pixelcolor::Bgr565| crate::Bgr565::pack(c.r().into(), c.g().into(), c.b().into())
);
colour_pair!(
    Rgb888,
    |p: crate::Rgb888| pixelcolor::Rgb888::new(p.r, p.g, p.b),
    |c: pixelcolor::Rgb888| crate::Rgb888 {
        r: c.r(),
        g: c.g(),
        b: c.b(),
    }
);
colour_pair!(
    Gray8,
    |p: crate::Gray8| pixelcolor::Gray8::new(p.0),
    |c: pixelcolor::Gray8| crate::Gray8(c.luma())
);

/// A prepared frame as an embedded-graphics `Drawable` of colour `C` (see the
/// [module docs](self)). `C` is usually inferred from the target.
#[derive(Debug)]
pub struct Drawing<'a, R, C> {
    frame: &'a R,
    top_left: Point,
    color: PhantomData<C>,
}

impl<R, C> Clone for Drawing<'_, R, C> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<R, C> Copy for Drawing<'_, R, C> {}

impl<'a, R: Render, C: EgColor> Drawing<'a, R, C> {
    /// Draws `frame` with its top-left pixel at the target's origin.
    pub fn new(frame: &'a R) -> Self {
        Drawing {
            frame,
            top_left: Point::zero(),
            color: PhantomData,
        }
    }

    /// Draws with the frame's top-left pixel at `top_left` (target coordinates, pixels).
    pub fn at(self, top_left: Point) -> Self {
        Drawing { top_left, ..self }
    }

    /// The colour of every pixel of background row `y`, if they are all the same (not the
    /// case for a dithered background that is not exactly a level).
    fn solid_background(&self, y: u32) -> Option<C> {
        let mut px = [C::Pixel::default(); 4];
        let n = (self.frame.width() as usize).min(4);
        let px = px.get_mut(..n)?;
        // Cannot fail: `y` is a row of the frame and the segment starts at its left edge.
        let rendered = self.frame.render_segment(y, 0, px);
        debug_assert!(rendered.is_ok(), "row {y}: {rendered:?}");
        rendered.ok()?;
        let first = *px.first()?;
        px.iter().all(|p| *p == first).then(|| C::from_pixel(first))
    }
}

impl<R: Render, C: EgColor> Drawable for Drawing<'_, R, C> {
    type Color = C;
    type Output = ();

    fn draw<D: DrawTarget<Color = C>>(&self, target: &mut D) -> Result<(), D::Error> {
        let width = self.frame.width();
        for y in 0..self.frame.height() {
            let area = Rectangle::new(self.top_left + Point::new(0, y as i32), Size::new(width, 1));
            if self.frame.row_coverage(y).is_none() {
                if let Some(color) = self.solid_background(y) {
                    target.fill_solid(&area, color)?;
                    continue;
                }
            }
            target.fill_contiguous(&area, RowColors::<R, C>::new(self.frame, y))?;
        }
        Ok(())
    }
}

/// The colours of one row, rendered [`LINE_CHUNK`] pixels at a time on demand.
struct RowColors<'a, R, C: EgColor> {
    frame: &'a R,
    y: u32,
    /// First column of the next chunk.
    next_x: u32,
    chunk: [C::Pixel; LINE_CHUNK],
    /// Pixels of `chunk` already handed out, and pixels it holds.
    used: usize,
    filled: usize,
}

impl<'a, R: Render, C: EgColor> RowColors<'a, R, C> {
    fn new(frame: &'a R, y: u32) -> Self {
        RowColors {
            frame,
            y,
            next_x: 0,
            chunk: [C::Pixel::default(); LINE_CHUNK],
            used: 0,
            filled: 0,
        }
    }

    fn remaining(&self) -> usize {
        (self.frame.width() - self.next_x) as usize + (self.filled - self.used)
    }
}

impl<R: Render, C: EgColor> Iterator for RowColors<'_, R, C> {
    type Item = C;

    fn next(&mut self) -> Option<C> {
        if self.used == self.filled {
            let n = ((self.frame.width() - self.next_x) as usize).min(LINE_CHUNK);
            if n == 0 {
                return None;
            }
            let pixels = self.chunk.get_mut(..n)?;
            // Cannot fail: the row and the segment are inside the frame. Were it to, the
            // chunk would hold default pixels rather than stop the stream short.
            let rendered = self.frame.render_segment(self.y, self.next_x, pixels);
            debug_assert!(rendered.is_ok(), "row {}: {rendered:?}", self.y);
            if rendered.is_err() {
                pixels.fill(C::Pixel::default());
            }
            self.next_x += n as u32;
            self.used = 0;
            self.filled = n;
        }
        // `used < filled ≤ LINE_CHUNK`: cannot fail.
        debug_assert!(self.used < self.filled && self.filled <= LINE_CHUNK);
        let p = *self.chunk.get(self.used)?;
        self.used += 1;
        Some(C::from_pixel(p))
    }

    fn size_hint(&self) -> (usize, Option<usize>) {
        let n = self.remaining();
        (n, Some(n))
    }
}

impl<R: Render, C: EgColor> ExactSizeIterator for RowColors<'_, R, C> {}
