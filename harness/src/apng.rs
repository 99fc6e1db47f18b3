//! Animated PNG (APNG) output, through the `png` crate's animation support: 8-bit RGB frames
//! of one size, encoded as they come into a buffer (so a long animation never holds more than
//! two frames and the compressed file), and read back as a viewer shows them.
//!
//! The first frame is the whole image (the `IDAT`, what a viewer without APNG shows). Each
//! later frame holds only the rectangle around the pixels that differ from the frame before
//! it, drawn over it (`dispose_op` none, `blend_op` source), which keeps a file of a moving
//! sphere or an orbiting light small; a frame equal to the one before is one unchanged
//! pixel.

use shadeline::Rgb888;
use std::io::{self, Cursor, Write};

/// A rectangle of a frame: `(x, y, width, height)`.
pub type Rect = (u32, u32, u32, u32);

/// An animated PNG being encoded into a writer (a `Vec<u8>`, say).
pub struct AnimatedPng<W: Write> {
    writer: png::Writer<W>,
    width: u32,
    height: u32,
    previous: Option<Vec<Rgb888>>,
}

impl<W: Write> std::fmt::Debug for AnimatedPng<W> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("AnimatedPng")
            .field("width", &self.width)
            .field("height", &self.height)
            .finish_non_exhaustive()
    }
}

impl<W: Write> AnimatedPng<W> {
    /// Starts a `width × height` animation of `frames` frames into `out`, each shown
    /// `1/fps` seconds, looping forever.
    pub fn new(out: W, width: u32, height: u32, frames: u32, fps: u16) -> io::Result<Self> {
        let mut encoder = png::Encoder::new(out, width, height);
        encoder.set_color(png::ColorType::Rgb);
        encoder.set_depth(png::BitDepth::Eight);
        encoder.set_compression(png::Compression::High);
        // So that `finish` refuses a file with fewer frames than it announces.
        encoder.validate_sequence(true);
        encoder.set_animated(frames, 0).map_err(io::Error::other)?;
        encoder.set_frame_delay(1, fps).map_err(io::Error::other)?;
        encoder
            .set_dispose_op(png::DisposeOp::None)
            .map_err(io::Error::other)?;
        encoder
            .set_blend_op(png::BlendOp::Source)
            .map_err(io::Error::other)?;
        let writer = encoder.write_header().map_err(io::Error::other)?;
        Ok(AnimatedPng {
            writer,
            width,
            height,
            previous: None,
        })
    }

    /// Adds the next frame (row-major, `width × height` pixels); returns the rectangle it
    /// stores (the whole frame first, then what changed).
    pub fn push(&mut self, frame: &[Rgb888]) -> io::Result<Rect> {
        let (w, h) = (self.width, self.height);
        if frame.len() != w as usize * h as usize {
            return Err(io::Error::other(format!(
                "{} pixels are not a {w}x{h} frame",
                frame.len()
            )));
        }
        let rect = match &self.previous {
            None => (0, 0, w, h),
            Some(previous) => changed(previous, frame, w).unwrap_or((0, 0, 1, 1)),
        };
        let (x, y, rw, rh) = rect;
        if self.previous.is_some() {
            // The first frame is the IDAT, always whole.
            self.writer
                .set_frame_dimension(rw, rh)
                .map_err(io::Error::other)?;
            self.writer
                .set_frame_position(x, y)
                .map_err(io::Error::other)?;
        }
        let mut bytes = Vec::with_capacity(rw as usize * rh as usize * 3);
        for row in frame
            .chunks_exact(w as usize)
            .skip(y as usize)
            .take(rh as usize)
        {
            for p in &row[x as usize..(x + rw) as usize] {
                bytes.extend_from_slice(&[p.r, p.g, p.b]);
            }
        }
        self.writer
            .write_image_data(&bytes)
            .map_err(io::Error::other)?;
        match &mut self.previous {
            Some(previous) => previous.copy_from_slice(frame),
            None => self.previous = Some(frame.to_vec()),
        }
        Ok(rect)
    }

    /// Ends the file: an error unless every frame announced was pushed.
    pub fn finish(self) -> io::Result<()> {
        self.writer.finish().map_err(io::Error::other)
    }
}

/// The smallest rectangle holding every pixel where `a` and `b` (two `width`-wide frames)
/// differ, or `None` where they are equal.
pub fn changed(a: &[Rgb888], b: &[Rgb888], width: u32) -> Option<Rect> {
    let w = width as usize;
    let (mut x0, mut y0, mut x1, mut y1) = (usize::MAX, usize::MAX, 0, 0);
    for (y, (ra, rb)) in a.chunks_exact(w).zip(b.chunks_exact(w)).enumerate() {
        let Some(first) = ra.iter().zip(rb).position(|(p, q)| p != q) else {
            continue;
        };
        let last = ra
            .iter()
            .zip(rb)
            .rposition(|(p, q)| p != q)
            .unwrap_or(first);
        x0 = x0.min(first);
        x1 = x1.max(last);
        y0 = y0.min(y);
        y1 = y;
    }
    (y0 != usize::MAX).then(|| {
        (
            x0 as u32,
            y0 as u32,
            (x1 - x0 + 1) as u32,
            (y1 - y0 + 1) as u32,
        )
    })
}

/// A decoded animation: its size, its frame delay, and every frame as shown (each stored
/// rectangle drawn over the frame before).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Decoded {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// The frames the file announces (`acTL`).
    pub announced: u32,
    /// The frames, row-major RGB bytes each.
    pub frames: Vec<Vec<u8>>,
    /// The rectangle each frame stored.
    pub rects: Vec<Rect>,
}

/// Reads an 8-bit RGB animated PNG back, composing its frames as a viewer does (for
/// `dispose_op` none and `blend_op` source, the only ones [`AnimatedPng`] writes; others are
/// refused).
pub fn decode(bytes: &[u8]) -> io::Result<Decoded> {
    let mut reader = png::Decoder::new(Cursor::new(bytes))
        .read_info()
        .map_err(io::Error::other)?;
    let info = reader.info();
    let (width, height) = (info.width, info.height);
    if info.color_type != png::ColorType::Rgb || info.bit_depth != png::BitDepth::Eight {
        return Err(io::Error::other("not an 8-bit RGB PNG"));
    }
    let announced = info
        .animation_control
        .map(|a| a.num_frames)
        .ok_or_else(|| io::Error::other("not an animated PNG: no acTL chunk"))?;
    let stride = width as usize * 3;
    let mut canvas = vec![0u8; stride * height as usize];
    let mut buf = vec![0u8; reader.output_buffer_size().unwrap_or(canvas.len())];
    let (mut frames, mut rects) = (Vec::new(), Vec::new());
    for _ in 0..announced {
        let out = reader.next_frame(&mut buf).map_err(io::Error::other)?;
        let control = reader
            .info()
            .frame_control
            .ok_or_else(|| io::Error::other("a frame without fcTL"))?;
        if control.dispose_op != png::DisposeOp::None || control.blend_op != png::BlendOp::Source {
            return Err(io::Error::other(
                "a dispose or blend operation not written here",
            ));
        }
        let (x, y) = (control.x_offset as usize, control.y_offset as usize);
        let line = out.width as usize * 3;
        for (row, src) in buf[..out.buffer_size()].chunks_exact(line).enumerate() {
            let at = (y + row) * stride + x * 3;
            canvas[at..at + line].copy_from_slice(src);
        }
        rects.push((control.x_offset, control.y_offset, out.width, out.height));
        frames.push(canvas.clone());
    }
    Ok(Decoded {
        width,
        height,
        announced,
        frames,
        rects,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pixel(v: u32) -> Rgb888 {
        Rgb888 {
            r: v as u8,
            g: (v >> 8) as u8,
            b: (v * 7) as u8,
        }
    }

    #[test]
    fn frames_read_back_as_written_each_storing_what_changed() {
        let (w, h) = (7u32, 5u32);
        let first: Vec<Rgb888> = (0..w * h).map(pixel).collect();
        let mut second = first.clone();
        second[(w + 2) as usize] = pixel(1000); // (2, 1)
        second[(3 * w + 4) as usize] = pixel(2000); // (4, 3)
        let third = second.clone(); // unchanged
        let mut fourth = third.clone();
        fourth[(4 * w + 6) as usize] = pixel(3000); // the last pixel
        let frames = [&first, &second, &third, &fourth];
        let mut bytes = Vec::new();
        let mut png = AnimatedPng::new(&mut bytes, w, h, 4, 25).unwrap();
        let rects: Vec<Rect> = frames.iter().map(|f| png.push(f).unwrap()).collect();
        assert_eq!(
            rects,
            [(0, 0, 7, 5), (2, 1, 3, 3), (0, 0, 1, 1), (6, 4, 1, 1)]
        );
        png.finish().unwrap();
        let decoded = decode(&bytes).unwrap();
        assert_eq!(
            (decoded.width, decoded.height, decoded.announced),
            (w, h, 4)
        );
        assert_eq!(decoded.rects, rects);
        for (got, want) in decoded.frames.iter().zip(frames) {
            let want: Vec<u8> = want.iter().flat_map(|p| [p.r, p.g, p.b]).collect();
            assert_eq!(got, &want);
        }
    }

    #[test]
    fn fewer_frames_than_announced_or_a_wrong_length_is_an_error() {
        let frame = vec![pixel(3); 6];
        let mut png = AnimatedPng::new(Vec::new(), 3, 2, 2, 10).unwrap();
        assert!(png.push(&frame[..5]).is_err());
        png.push(&frame).unwrap();
        assert!(png.finish().is_err());
    }

    #[test]
    fn the_changed_rectangle_is_the_smallest_around_every_difference() {
        let a = vec![pixel(0); 12];
        let mut b = a.clone();
        assert_eq!(changed(&a, &b, 4), None);
        b[1] = pixel(9); // (1, 0)
        b[8] = pixel(9); // (0, 2)
        b[6] = pixel(9); // (2, 1)
        assert_eq!(changed(&a, &b, 4), Some((0, 0, 3, 3)));
    }
}
