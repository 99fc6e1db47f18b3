//! Every way to render with shadeline, exported from one `no_std` binary for
//! `.ci/no-alloc-check`, which lists the symbols of the `thumbv6m-none-eabi` build and fails
//! if any allocator symbol is among them:
//!
//! - `shadeline_prepare_*`: the presets, and preparing them for the scalar, SIMD and fixed
//!   paths;
//! - `shadeline_*_row`: a row of each path into every pixel format, with an encoding, as
//!   display bytes, and as a segment;
//! - `shadeline_eg_draw`: the embedded-graphics `Drawable` into a `DrawTarget`.
//!
//! Its sibling binary, `alloc_probe` (`src/bin/alloc_probe.rs`), allocates on purpose: the
//! check must find the allocator symbols there, or it is broken.
#![no_std]
#![no_main]

use core::panic::PanicInfo;
use embedded_graphics_core::pixelcolor;
use embedded_graphics_core::prelude::{DrawTarget, OriginDimensions, Pixel, Size};
use embedded_graphics_core::Drawable;
use shadeline::eg::Drawing;
use shadeline::{
    exponent_series_with_capacity, materials_with_capacity, Bgr565, Encoding, Gray8, HitRecord,
    LinearRgb, Prepared, PreparedFixed, Render, Rgb565, Rgb888, Scalar, Scene, Simd4, Simd8,
};

/// The scene every prepared frame below is made from.
type Frame<W> = Prepared<W, 16, 4>;

/// The exponent series, prepared for the scalar path (`None` if refused).
#[no_mangle]
pub fn shadeline_prepare_scalar(w: u32, h: u32, out: &mut Option<Frame<Scalar>>) {
    *out = exponent_series_with_capacity::<16, 4>()
        .ok()
        .and_then(|s| Prepared::new(&s, w, h).ok());
}

/// The materials gallery, prepared for both SIMD widths.
#[no_mangle]
pub fn shadeline_prepare_simd(
    w: u32,
    h: u32,
    four: &mut Option<Frame<Simd4>>,
    eight: &mut Option<Frame<Simd8>>,
) {
    let scene: Option<Scene<16, 4>> = materials_with_capacity().ok();
    *four = scene.as_ref().and_then(|s| Prepared::new(s, w, h).ok());
    *eight = scene.as_ref().and_then(|s| Prepared::new(s, w, h).ok());
}

/// The materials gallery, prepared for the fixed path.
#[no_mangle]
pub fn shadeline_prepare_fixed(w: u32, h: u32, out: &mut Option<PreparedFixed<16, 4>>) {
    *out = materials_with_capacity()
        .ok()
        .and_then(|s: Scene<16, 4>| PreparedFixed::new(&s, w, h).ok());
}

/// Row `y` of `r` into every pixel format, with sRGB and dithering, as display bytes and as
/// a segment; `false` if any call was refused.
fn every_sink<R: Render + Clone>(r: &R, y: u32, line: &mut [u8]) -> bool {
    let n = r.width() as usize;
    let mut ok = true;
    let mut rgb888 = [Rgb888::default(); 16];
    let mut rgb565 = [Rgb565::default(); 16];
    let mut bgr565 = [Bgr565::default(); 16];
    let mut gray = [Gray8::default(); 16];
    let mut linear = [LinearRgb::default(); 16];
    let mut hits = [HitRecord::default(); 16];
    let m = n.min(16);
    let srgb = r.clone().with_encoding(Encoding::SRGB.dithered());
    ok &= r.render_segment(y, 0, &mut rgb888[..m]).is_ok();
    ok &= srgb.render_segment(y, 0, &mut rgb565[..m]).is_ok();
    ok &= srgb.render_segment(y, 0, &mut bgr565[..m]).is_ok();
    ok &= srgb.render_segment(y, 0, &mut gray[..m]).is_ok();
    ok &= r.render_segment(y, 0, &mut linear[..m]).is_ok();
    ok &= r.render_segment(y, 0, &mut hits[..m]).is_ok();
    ok &= srgb.render_line_bytes::<Rgb565>(y, line).is_ok();
    ok &= r.render_line_bytes::<Rgb888>(y, line).is_ok();
    ok
}

/// Every sink on the scalar path.
#[no_mangle]
pub fn shadeline_scalar_row(r: &Frame<Scalar>, y: u32, line: &mut [u8]) -> bool {
    every_sink(r, y, line)
}

/// Every sink on the 4-lane path.
#[no_mangle]
pub fn shadeline_simd4_row(r: &Frame<Simd4>, y: u32, line: &mut [u8]) -> bool {
    every_sink(r, y, line)
}

/// Every sink on the 8-lane path.
#[no_mangle]
pub fn shadeline_simd8_row(r: &Frame<Simd8>, y: u32, line: &mut [u8]) -> bool {
    every_sink(r, y, line)
}

/// Every sink on the fixed path.
#[no_mangle]
pub fn shadeline_fixed_row(r: &PreparedFixed<16, 4>, y: u32, line: &mut [u8]) -> bool {
    every_sink(r, y, line)
}

/// A display of `width × height` RGB565 pixels in a caller's buffer.
pub struct Display<'a> {
    width: u32,
    pixels: &'a mut [pixelcolor::Rgb565],
}

impl OriginDimensions for Display<'_> {
    fn size(&self) -> Size {
        let height = self.pixels.len() as u32 / self.width.max(1);
        Size::new(self.width, height)
    }
}

impl DrawTarget for Display<'_> {
    type Color = pixelcolor::Rgb565;
    type Error = core::convert::Infallible;

    fn draw_iter<I: IntoIterator<Item = Pixel<Self::Color>>>(
        &mut self,
        pixels: I,
    ) -> Result<(), Self::Error> {
        for Pixel(p, c) in pixels {
            if let (Ok(x), Ok(y)) = (u32::try_from(p.x), u32::try_from(p.y)) {
                if x < self.width {
                    if let Some(px) = self.pixels.get_mut((y * self.width + x) as usize) {
                        *px = c;
                    }
                }
            }
        }
        Ok(())
    }
}

/// The embedded-graphics `Drawable` of both float widths and the fixed path.
#[no_mangle]
pub fn shadeline_eg_draw(
    scalar: &Frame<Scalar>,
    simd: &Frame<Simd8>,
    fixed: &PreparedFixed<16, 4>,
    pixels: &mut [pixelcolor::Rgb565],
) {
    let mut display = Display {
        width: scalar.width(),
        pixels,
    };
    let _ = Drawing::new(scalar).draw(&mut display);
    let _ = Drawing::new(simd).draw(&mut display);
    let _ = Drawing::new(fixed).draw(&mut display);
}

#[panic_handler]
fn panic(_: &PanicInfo) -> ! {
    loop {}
}
