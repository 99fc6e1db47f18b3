//! Writing 8-bit RGB images as PNG.

use shadeline::Rgb888;
use std::fs::{File, OpenOptions};
use std::io::{self, BufWriter, Seek, Write};
use std::path::{Path, PathBuf};

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

    /// The `(x, y, w, h)` crop of a `width`-wide row-major frame, each pixel magnified to a
    /// `zoom × zoom` block (nearest neighbour), so single pixels show in a document. The crop
    /// must lie inside the frame.
    pub fn zoomed_crop(
        pixels: &[Rgb888],
        width: u32,
        (x, y, w, h): (u32, u32, u32, u32),
        zoom: u32,
    ) -> Self {
        let mut image = RgbImage::new(w * zoom, h * zoom);
        for row in 0..h * zoom {
            let src = ((y + row / zoom) * width + x) as usize;
            let line: Vec<Rgb888> = (0..w * zoom)
                .map(|col| pixels[src + (col / zoom) as usize])
                .collect();
            image.paste(0, row, w * zoom, &line);
        }
        image
    }

    /// Writes the image as an 8-bit RGB PNG.
    pub fn write_png(&self, path: &Path) -> io::Result<()> {
        let mut file = BufWriter::new(File::create(path)?);
        write_rgb_png(&mut file, self.width, self.height, |y, row| {
            let stride = self.width as usize * 3;
            row.copy_from_slice(&self.bytes[y * stride..][..stride]);
        })?;
        file.flush()
    }
}

/// Writes a `width × height` 8-bit RGB PNG whose row `y` (`width × 3` bytes) `row(y, buf)`
/// fills in, one row at a time: no copy of the whole image is made.
fn write_rgb_png<W: Write>(
    out: W,
    width: u32,
    height: u32,
    row: impl Fn(usize, &mut [u8]),
) -> io::Result<()> {
    let mut encoder = png::Encoder::new(out, width, height);
    encoder.set_color(png::ColorType::Rgb);
    encoder.set_depth(png::BitDepth::Eight);
    let mut writer = encoder.write_header().map_err(io::Error::other)?;
    let mut stream = writer.stream_writer().map_err(io::Error::other)?;
    let mut buf = vec![0u8; width as usize * 3];
    for y in 0..height as usize {
        row(y, &mut buf);
        stream.write_all(&buf)?;
    }
    stream.finish().map_err(io::Error::other)?;
    writer.finish().map_err(io::Error::other)
}

/// A PNG output file, opened before the long part of a command, so that an output path that
/// cannot be written is reported before rendering rather than after it.
///
/// An existing file keeps its contents until [`PngFile::write_pixels`] or
/// [`PngFile::write_image`] replaces them; a file that [`PngFile::open`] created is removed
/// again if it is dropped without being written (the command failed).
#[derive(Debug)]
pub struct PngFile {
    path: PathBuf,
    file: Option<File>,
    created: bool,
}

impl PngFile {
    /// Opens `path` for writing, creating it if it does not exist.
    pub fn open(path: &Path) -> io::Result<Self> {
        let (file, created) = match OpenOptions::new().write(true).create_new(true).open(path) {
            Ok(file) => (file, true),
            Err(e) if e.kind() == io::ErrorKind::AlreadyExists => {
                (OpenOptions::new().write(true).open(path)?, false)
            }
            Err(e) => return Err(e),
        };
        Ok(PngFile {
            path: path.to_path_buf(),
            file: Some(file),
            created,
        })
    }

    /// Replaces the file's contents with a row-major `width × height` frame as an 8-bit RGB PNG.
    pub fn write_pixels(self, width: u32, height: u32, pixels: &[Rgb888]) -> io::Result<()> {
        let w = width as usize;
        if pixels.len() != w * height as usize {
            return Err(io::Error::other(format!(
                "{} pixels are not a {width}x{height} frame",
                pixels.len()
            )));
        }
        self.write_with(width, height, |y, row| {
            for (d, p) in row.chunks_exact_mut(3).zip(&pixels[y * w..][..w]) {
                d.copy_from_slice(&[p.r, p.g, p.b]);
            }
        })
    }

    /// Replaces the file's contents with `image` as an 8-bit RGB PNG.
    pub fn write_image(self, image: &RgbImage) -> io::Result<()> {
        let stride = image.width as usize * 3;
        self.write_with(image.width, image.height, |y, row| {
            row.copy_from_slice(&image.bytes[y * stride..][..stride]);
        })
    }

    /// Replaces the file's contents with an encoded PNG (an animated one from
    /// [`crate::apng::AnimatedPng`], say).
    pub fn write_encoded(self, bytes: &[u8]) -> io::Result<()> {
        self.replace(|out| out.write_all(bytes))
    }

    fn write_with(self, width: u32, height: u32, row: impl Fn(usize, &mut [u8])) -> io::Result<()> {
        self.replace(|out| write_rgb_png(out, width, height, row))
    }

    /// Empties the file and lets `write` fill it; a file this created is removed again if
    /// that fails.
    fn replace(
        mut self,
        write: impl FnOnce(&mut BufWriter<&mut File>) -> io::Result<()>,
    ) -> io::Result<()> {
        let Some(mut file) = self.file.take() else {
            return Err(io::Error::other("the PNG file was already written"));
        };
        let fill = || {
            // A regular file is emptied first; a pipe or a device (`-o /dev/stdout`) cannot be.
            if file.metadata()?.is_file() {
                file.set_len(0)?;
                file.rewind()?;
            }
            let mut out = BufWriter::new(&mut file);
            write(&mut out)?;
            out.flush()
        };
        let result = fill();
        if result.is_err() && self.created {
            let _ = std::fs::remove_file(&self.path);
        }
        result
    }
}

impl Drop for PngFile {
    fn drop(&mut self) {
        if self.file.take().is_some() && self.created {
            let _ = std::fs::remove_file(&self.path);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn temp(name: &str) -> PathBuf {
        std::env::temp_dir().join(format!("shadeline-image-{}-{name}", std::process::id()))
    }

    fn decode(path: &Path) -> (u32, u32, Vec<u8>) {
        let file = io::BufReader::new(File::open(path).unwrap());
        let mut reader = png::Decoder::new(file).read_info().unwrap();
        let mut buf = vec![0; reader.output_buffer_size().unwrap()];
        let info = reader.next_frame(&mut buf).unwrap();
        buf.truncate(info.buffer_size());
        (info.width, info.height, buf)
    }

    #[test]
    fn a_png_file_replaces_what_was_there_and_an_unwritten_new_one_is_removed() {
        let path = temp("replace.png");
        std::fs::write(&path, vec![7u8; 100_000]).unwrap();
        let pixels: Vec<Rgb888> = (0..6u8)
            .map(|i| Rgb888 {
                r: i,
                g: 2 * i,
                b: 3 * i,
            })
            .collect();
        let file = PngFile::open(&path).unwrap();
        // Opening an existing file does not touch it.
        assert_eq!(std::fs::read(&path).unwrap(), vec![7u8; 100_000]);
        file.write_pixels(3, 2, &pixels).unwrap();
        let (w, h, bytes) = decode(&path);
        assert_eq!((w, h), (3, 2));
        assert_eq!(
            bytes,
            [0, 0, 0, 1, 2, 3, 2, 4, 6, 3, 6, 9, 4, 8, 12, 5, 10, 15]
        );
        // Dropped unwritten: an existing file stays, a new one goes.
        drop(PngFile::open(&path).unwrap());
        assert!(path.exists());
        std::fs::remove_file(&path).unwrap();
        drop(PngFile::open(&path).unwrap());
        assert!(!path.exists());
        // A frame of the wrong length is refused, not written short.
        assert!(PngFile::open(&path)
            .unwrap()
            .write_pixels(4, 2, &pixels)
            .is_err());
        assert!(!path.exists());
    }

    #[test]
    fn an_image_is_written_row_by_row_as_it_is() {
        let path = temp("image.png");
        let mut image = RgbImage::new(2, 3);
        image
            .bytes
            .iter_mut()
            .enumerate()
            .for_each(|(i, b)| *b = i as u8);
        PngFile::open(&path).unwrap().write_image(&image).unwrap();
        assert_eq!(decode(&path), (2, 3, image.bytes.clone()));
        image.write_png(&path).unwrap();
        assert_eq!(decode(&path), (2, 3, image.bytes.clone()));
        std::fs::remove_file(&path).unwrap();
    }
}
