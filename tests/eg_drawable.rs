//! The embedded-graphics `Drawable` against a recording `DrawTarget`: every pixel equals
//! `render_line`'s output (converted exactly), and the calls are the few large ones the
//! module promises: one `fill_contiguous` per row the spheres touch, one `fill_solid` per
//! pure background row, no `draw_iter`; and the `From` conversions between shadeline's
//! formats and embedded-graphics' colours, which keep every level (and the `u16` of the
//! 16-bit formats).
//!
//! Not behind `cfg(feature = "embedded-graphics")`: the crate's dev-dependency on itself turns
//! the feature on for every test build, so `cargo test --workspace` runs these tests, and a
//! build without the feature fails here instead of skipping them.

use crate::common;
use common::*;
use embedded_graphics_core::pixelcolor::{self, PixelColor};
use embedded_graphics_core::pixelcolor::{GrayColor, IntoStorage, RgbColor};
use embedded_graphics_core::prelude::*;
use embedded_graphics_core::primitives::Rectangle;
use shadeline::eg::{Drawing, EgColor};
use shadeline::{
    exponent_series, materials, Bgr565, Encoding, Gray8, Prepared, PreparedFixed, Render, Rgb565,
    Rgb888, Scalar, Simd4, Simd8,
};

/// A `DrawTarget` that records every pixel and counts its calls.
struct Recorder<C> {
    size: Size,
    pixels: Vec<Option<C>>,
    fill_contiguous: usize,
    fill_solid: usize,
    draw_iter: usize,
    /// Largest number of colours one call delivered.
    largest: usize,
}

impl<C: PixelColor> Recorder<C> {
    fn new(w: u32, h: u32) -> Self {
        Recorder {
            size: Size::new(w, h),
            pixels: vec![None; (w * h) as usize],
            fill_contiguous: 0,
            fill_solid: 0,
            draw_iter: 0,
            largest: 0,
        }
    }

    fn set(&mut self, p: Point, c: C) {
        if p.x >= 0 && p.y >= 0 && (p.x as u32) < self.size.width && (p.y as u32) < self.size.height
        {
            self.pixels[(p.y as u32 * self.size.width + p.x as u32) as usize] = Some(c);
        }
    }
}

impl<C: PixelColor> OriginDimensions for Recorder<C> {
    fn size(&self) -> Size {
        self.size
    }
}

impl<C: PixelColor> DrawTarget for Recorder<C> {
    type Color = C;
    type Error = core::convert::Infallible;

    fn draw_iter<I: IntoIterator<Item = Pixel<C>>>(
        &mut self,
        pixels: I,
    ) -> Result<(), Self::Error> {
        self.draw_iter += 1;
        for Pixel(p, c) in pixels {
            self.set(p, c);
        }
        Ok(())
    }

    fn fill_contiguous<I: IntoIterator<Item = C>>(
        &mut self,
        area: &Rectangle,
        colors: I,
    ) -> Result<(), Self::Error> {
        self.fill_contiguous += 1;
        let mut n = 0;
        for (p, c) in area.points().zip(colors) {
            self.set(p, c);
            n += 1;
        }
        assert_eq!(n, area.size.width * area.size.height, "short colour stream");
        assert_eq!(area.size.height, 1, "one-row rectangles");
        self.largest = self.largest.max(n as usize);
        Ok(())
    }

    fn fill_solid(&mut self, area: &Rectangle, color: C) -> Result<(), Self::Error> {
        self.fill_solid += 1;
        assert_eq!(area.size.height, 1, "one-row rectangles");
        for p in area.points() {
            self.set(p, color);
        }
        Ok(())
    }
}

/// Draws `r` into a recorder, checks every pixel against `render_line`, returns the counts
/// `(fill_contiguous, fill_solid)`.
fn draw_and_check<C, R>(r: &R, label: &str) -> (usize, usize)
where
    C: EgColor + core::fmt::Debug,
    C::Pixel: core::fmt::Debug,
    R: Render,
{
    let (w, h) = (r.width(), r.height());
    let mut target = Recorder::<C>::new(w, h);
    Drawing::<R, C>::new(r).draw(&mut target).unwrap();
    let mut line = vec![C::Pixel::default(); w as usize];
    for y in 0..h {
        r.render_line(y, &mut line).unwrap();
        for (x, p) in line.iter().enumerate() {
            let got = target.pixels[(y * w) as usize + x];
            assert_eq!(got, Some(C::from_pixel(*p)), "{label}: pixel ({x},{y})");
        }
    }
    assert_eq!(target.draw_iter, 0, "{label}: no per-pixel draw_iter");
    assert_eq!(
        target.fill_contiguous + target.fill_solid,
        h as usize,
        "{label}: one call per row"
    );
    assert!(target.fill_contiguous == 0 || target.largest == w as usize);
    (target.fill_contiguous, target.fill_solid)
}

fn covered_rows<R: Render>(r: &R) -> usize {
    (0..r.height())
        .filter(|y| r.row_coverage(*y).is_some())
        .count()
}

#[test]
fn exponent_series_frame_is_drawn_exactly_with_few_calls() {
    let series = exponent_series().unwrap();
    let (w, h) = (320, 240);
    let scalar = Prepared::<Scalar>::new(&series, w, h).unwrap();
    let simd = Prepared::<Simd8>::new(&series, w, h).unwrap();
    let fixed = PreparedFixed::new(&series, w, h).unwrap();
    let mut report = Vec::new();
    for e in [Encoding::LINEAR, Encoding::SRGB.dithered()] {
        macro_rules! each_color {
            ($r:expr, $name:expr) => {{
                let r = $r.clone().with_encoding(e);
                let label = format!("{} {e:?}", $name);
                let a = draw_and_check::<pixelcolor::Rgb565, _>(&r, &label);
                let b = draw_and_check::<pixelcolor::Rgb888, _>(&r, &label);
                let c = draw_and_check::<pixelcolor::Gray8, _>(&r, &label);
                let d = draw_and_check::<pixelcolor::Bgr565, _>(&r, &label);
                assert!(
                    a == b && b == c && c == d,
                    "{label}: calls depend on the colour type"
                );
                // Covered rows get fill_contiguous; background rows fill_solid unless the
                // dithered background varies.
                assert_eq!(a.0 + a.1, h as usize);
                assert!(a.0 >= covered_rows(&r));
                if e == Encoding::LINEAR {
                    assert_eq!(
                        a.0,
                        covered_rows(&r),
                        "{label}: one fill_contiguous per covered row"
                    );
                }
                report.push(format!(
                    "{label}: fill_contiguous {}, fill_solid {}",
                    a.0, a.1
                ));
                a
            }};
        }
        let s = each_color!(scalar, "scalar");
        let v = each_color!(simd, "simd8");
        let f = each_color!(fixed, "fixed");
        assert_eq!(s, v, "scalar and SIMD spans are the same");
        if e == Encoding::LINEAR {
            assert!(s.1 > 0 && f.1 > 0, "background rows are solid fills");
            // The figures of `docs/features.md` for the float paths.
            assert_eq!(s, (56, 184), "fills per frame on the float paths");
        }
        let _ = f;
    }
    for line in &report {
        println!("{line}");
    }
}

#[test]
fn random_scenes_small_sizes_and_an_offset() {
    for (i, scene) in random_scenes(6, 0x5eed_e600).iter().enumerate() {
        for (w, h) in [(1, 1), (3, 2), (67, 41), (130, 9)] {
            let label = format!("random scene {i} {w}x{h}");
            let f = Prepared::<Simd4>::new(scene, w, h).unwrap();
            draw_and_check::<pixelcolor::Rgb565, _>(&f, &label);
            let f = PreparedFixed::new(scene, w, h)
                .unwrap()
                .with_encoding(Encoding::LINEAR.dithered());
            draw_and_check::<pixelcolor::Gray8, _>(&f, &label);
        }
    }
    // Drawn at an offset, into a target smaller than the frame: clipped, never out of bounds.
    let series = exponent_series().unwrap();
    let f = PreparedFixed::new(&series, 64, 48).unwrap();
    let mut target = Recorder::<pixelcolor::Rgb888>::new(40, 30);
    Drawing::new(&f)
        .at(Point::new(-10, -5))
        .draw(&mut target)
        .unwrap();
    let mut line = vec![Rgb888::default(); 64];
    f.render_line(5 + 7, &mut line).unwrap();
    assert_eq!(
        target.pixels[7 * 40 + 3],
        Some(pixelcolor::Rgb888::from_pixel(line[13]))
    );
}

#[test]
fn the_16_bit_formats_convert_both_ways_with_the_same_levels_and_bits() {
    for bits in 0..=u16::MAX {
        let p = Rgb565(bits);
        let c = pixelcolor::Rgb565::from(p);
        assert_eq!(c.into_storage(), bits);
        assert_eq!(p.levels(), (c.r(), c.g(), c.b()));
        assert_eq!(Rgb565::from(c), p);
        assert_eq!(pixelcolor::Rgb565::from_pixel(p), c);

        let p = Bgr565(bits);
        let c = pixelcolor::Bgr565::from(p);
        assert_eq!(c.into_storage(), bits);
        assert_eq!(p.levels(), (c.r(), c.g(), c.b()));
        assert_eq!(Bgr565::from(c), p);
        assert_eq!(pixelcolor::Bgr565::from_pixel(p), c);
    }
    // Not the same colour type under another name: red is in the low bits of Bgr565.
    assert_eq!(
        pixelcolor::Bgr565::from(Bgr565::pack(31, 0, 0)),
        pixelcolor::Bgr565::RED
    );
    assert_eq!(Bgr565::pack(31, 0, 0).0, 0x001f);
    assert_eq!(Rgb565::from(pixelcolor::Rgb565::RED).0, 0xf800);
}

#[test]
fn the_8_bit_formats_convert_both_ways_with_the_same_levels() {
    for v in 0..=u8::MAX {
        let w = v.wrapping_mul(37).wrapping_add(11);
        let p = Rgb888 { r: v, g: w, b: !v };
        let c = pixelcolor::Rgb888::from(p);
        assert_eq!((c.r(), c.g(), c.b()), (v, w, !v));
        assert_eq!(Rgb888::from(c), p);

        let c = pixelcolor::Gray8::from(Gray8(v));
        assert_eq!(c.luma(), v);
        assert_eq!(Gray8::from(c), Gray8(v));
    }
}

#[test]
fn a_bgr565_target_gets_the_same_colours_as_an_rgb565_one() {
    let scene = materials().unwrap();
    let frame = Prepared::<Simd8>::new(&scene, 96, 54)
        .unwrap()
        .with_encoding(Encoding::SRGB.dithered());
    let mut rgb = Recorder::<pixelcolor::Rgb565>::new(96, 54);
    let mut bgr = Recorder::<pixelcolor::Bgr565>::new(96, 54);
    Drawing::new(&frame).draw(&mut rgb).unwrap();
    Drawing::new(&frame).draw(&mut bgr).unwrap();
    let mut distinct = std::collections::HashSet::new();
    for (a, b) in rgb.pixels.iter().zip(&bgr.pixels) {
        let (a, b) = (a.unwrap(), b.unwrap());
        assert_eq!((a.r(), a.g(), a.b()), (b.r(), b.g(), b.b()));
        distinct.insert(a.into_storage());
    }
    // A frame of many colours, red and blue unequal in most: a swap would show.
    assert!(distinct.len() > 100, "{}", distinct.len());
    draw_and_check::<pixelcolor::Bgr565, _>(&frame, "materials Bgr565");
}
