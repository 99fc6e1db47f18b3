//! Writing 8-bit RGB images as PNG.

use shadeline::Rgb888;
use std::fs::File;
use std::io::{self, BufWriter};
use std::path::Path;

/// An 8-bit RGB image, row-major, 3 bytes per pixel.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct RgbImage {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// `width × height × 3` bytes: R, G, B.
    pub bytes: Vec<u8>,
}

impl RgbImage {
    /// A black image.
    pub fn new(width: u32, height: u32) -> Self {
        RgbImage {
            width,
            height,
            bytes: vec![0; width as usize * height as usize * 3],
        }
    }

    /// An image from a row-major frame of pixels.
    pub fn from_pixels(width: u32, height: u32, pixels: &[Rgb888]) -> Self {
        let bytes = pixels.iter().flat_map(|p| [p.r, p.g, p.b]).collect();
        RgbImage {
            width,
            height,
            bytes,
        }
    }

    /// Copies `pixels` (a `w`-wide frame) into this image with its top-left corner at `(x, y)`.
    pub fn paste(&mut self, x: u32, y: u32, w: u32, pixels: &[Rgb888]) {
        let stride = self.width as usize * 3;
        for (row, line) in pixels.chunks_exact(w as usize).enumerate() {
            let start = (y as usize + row) * stride + x as usize * 3;
            let dest = &mut self.bytes[start..start + line.len() * 3];
            for (d, p) in dest.chunks_exact_mut(3).zip(line) {
                d.copy_from_slice(&[p.r, p.g, p.b]);
            }
        }
    }

    /// Writes the image as an 8-bit RGB PNG.
    pub fn write_png(&self, path: &Path) -> io::Result<()> {
        let file = BufWriter::new(File::create(path)?);
        let mut encoder = png::Encoder::new(file, self.width, self.height);
        encoder.set_color(png::ColorType::Rgb);
        encoder.set_depth(png::BitDepth::Eight);
        let mut writer = encoder.write_header().map_err(io::Error::other)?;
        writer
            .write_image_data(&self.bytes)
            .map_err(io::Error::other)?;
        writer.finish().map_err(io::Error::other)
    }
}
