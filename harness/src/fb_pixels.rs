//! Writing a rendered frame into a Linux framebuffer's memory: the pixel formats of
//! `fbdev` (the channels' bit offsets and lengths of the var screen info, the line length of
//! the fixed one), the window a frame takes on the screen, and the copy itself, as pure
//! functions over a `&mut [u8]`, so they are tested on memory of any layout without a device
//! ([`crate::fb_device`] opens one and hands its mapped memory here).
//!
//! The colour levels come from the core's pixel formats: a 5-6-5 format is written from a
//! frame rendered as [`Rgb565`] (so its rounding and dithering are the core's), an 8-8-8 one
//! from [`Rgb888`]. Writing places each level at its channel's offset in a pixel value of
//! `bits_per_pixel` bits, stored in the machine's byte order (as fbdev drivers, fbtft's
//! among them, lay packed pixels out), and sets the alpha bits (`transp`), if any, to opaque.
//!
//! | format | bits per pixel | red, green, blue (offset:length) |
//! |---|---|---|
//! | RGB565 | 16 | 11:5, 5:6, 0:5 |
//! | BGR565 | 16 | 0:5, 5:6, 11:5 |
//! | XRGB8888 (ARGB8888 with `transp`) | 32 | 16:8, 8:8, 0:8 |
//! | XBGR8888 (ABGR8888) | 32 | 0:8, 8:8, 16:8 |
//! | RGBX8888, BGRX8888 | 32 | 24:8, 16:8, 8:8 and 8:8, 16:8, 24:8 |
//! | RGB888, BGR888 | 24 | 16:8, 8:8, 0:8 and 0:8, 8:8, 16:8 |
//!
//! Any other layout of 16, 24 or 32 bits whose channels are 5-6-5 or 8-8-8 bits and do not
//! overlap is written the same way. Refused ([`FormatError`]): other depths (8-bit
//! palettes, 1-bit mono, 30-bit 10-10-10), RGB555 and other channel lengths, and channels
//! that overlap or do not fit in the pixel.

use shadeline::{Pixel, Rgb565, Rgb888};
use std::fmt;

/// One colour channel of a framebuffer pixel: its lowest bit and its number of bits (an
/// `fb_bitfield` of the var screen info).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Channel {
    /// The channel's lowest bit in the pixel value.
    pub offset: u32,
    /// The channel's number of bits; 0 for a channel the format does not have.
    pub length: u32,
}

impl Channel {
    /// A channel of `length` bits from bit `offset`.
    pub const fn new(offset: u32, length: u32) -> Self {
        Channel { offset, length }
    }

    /// The channel's bits in a pixel value (`None` when it does not fit in 32 bits).
    fn mask(self) -> Option<u32> {
        let end = self.offset.checked_add(self.length)?;
        if end > 32 {
            return None;
        }
        let ones = if self.length == 32 {
            u32::MAX
        } else {
            (1u32 << self.length) - 1
        };
        Some(ones.checked_shl(self.offset).unwrap_or(0))
    }
}

/// How pixels lie in a framebuffer's memory.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct FbFormat {
    /// Bits per pixel: 16, 24 or 32 are written.
    pub bits_per_pixel: u32,
    /// The red channel.
    pub red: Channel,
    /// The green channel.
    pub green: Channel,
    /// The blue channel.
    pub blue: Channel,
    /// The alpha channel (`transp`), length 0 when there is none: written opaque.
    pub transp: Channel,
    /// Bytes from the start of one line to the start of the next (the fixed screen info's
    /// `line_length`): at least the width times the bytes per pixel, and often more (lines
    /// padded to an alignment). The stride is always this, never the width.
    pub line_length: usize,
}

/// The channel depths a framebuffer format takes, which say which of the core's pixel formats
/// the frame is rendered in.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Depth {
    /// 5-bit red, 6-bit green, 5-bit blue: render [`Rgb565`].
    Bits565,
    /// 8 bits each: render [`Rgb888`].
    Bits888,
}

/// Why a framebuffer format is not written.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FormatError {
    /// The pixel size is not 16, 24 or 32 bits.
    BitsPerPixel(FbFormat),
    /// The channels are not 5-6-5 or 8-8-8 bits.
    ChannelLengths(FbFormat),
    /// A channel does not fit in the pixel, or two channels share bits.
    Layout(FbFormat),
}

impl fmt::Display for FormatError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let (why, format) = match self {
            FormatError::BitsPerPixel(format) => ("its pixel size", format),
            FormatError::ChannelLengths(format) => ("its channel lengths", format),
            FormatError::Layout(format) => ("its channels' layout", format),
        };
        write!(
            f,
            "shadeline does not write this pixel format ({why}): {} (it writes 16-bit \
             RGB565/BGR565, 24-bit RGB888/BGR888 and 32-bit XRGB8888/XBGR8888 and the like)",
            format.describe()
        )
    }
}

impl std::error::Error for FormatError {}

impl FbFormat {
    /// The format's name from the most significant bit down (`RGB565`, `XRGB8888`,
    /// `ABGR8888`; `X` for bits no channel uses), or for a format that is not written, its
    /// numbers.
    pub fn name(&self) -> String {
        if self.depth().is_err() {
            return self.describe();
        }
        let mut fields: Vec<(u32, char, u32)> = [
            ('R', self.red),
            ('G', self.green),
            ('B', self.blue),
            ('A', self.transp),
        ]
        .into_iter()
        .filter(|(_, c)| c.length > 0)
        .map(|(letter, c)| (c.offset, letter, c.length))
        .collect();
        // The bits no channel uses, as X fields.
        let mut used = vec![false; self.bits_per_pixel as usize];
        for &(offset, _, length) in &fields {
            used[offset as usize..(offset + length) as usize].fill(true);
        }
        let mut bit = 0;
        while bit < used.len() {
            if used[bit] {
                bit += 1;
                continue;
            }
            let start = bit;
            while bit < used.len() && !used[bit] {
                bit += 1;
            }
            fields.push((start as u32, 'X', (bit - start) as u32));
        }
        fields.sort_by_key(|f| std::cmp::Reverse(f.0));
        let letters: String = fields.iter().map(|f| f.1).collect();
        let lengths: String = fields.iter().map(|f| f.2.to_string()).collect();
        format!("{letters}{lengths}")
    }

    /// The format's numbers: `16 bits per pixel, red 10:5, green 5:5, blue 0:5`
    /// (offset:length), with `transp` when it has one.
    pub fn describe(&self) -> String {
        let c = |name: &str, c: Channel| format!("{name} {}:{}", c.offset, c.length);
        let mut text = format!(
            "{} bits per pixel, {}, {}, {}",
            self.bits_per_pixel,
            c("red", self.red),
            c("green", self.green),
            c("blue", self.blue)
        );
        if self.transp.length > 0 {
            text += &format!(", {}", c("transp", self.transp));
        }
        text
    }

    /// Bytes per pixel.
    pub fn bytes_per_pixel(&self) -> usize {
        self.bits_per_pixel as usize / 8
    }

    /// Whether the format is written, and if it is, which core pixel format its levels come
    /// from.
    pub fn depth(&self) -> Result<Depth, FormatError> {
        if !matches!(self.bits_per_pixel, 16 | 24 | 32) {
            return Err(FormatError::BitsPerPixel(*self));
        }
        let depth = match [self.red.length, self.green.length, self.blue.length] {
            [5, 6, 5] => Depth::Bits565,
            [8, 8, 8] => Depth::Bits888,
            _ => return Err(FormatError::ChannelLengths(*self)),
        };
        let mut used = 0u32;
        for channel in [self.red, self.green, self.blue, self.transp] {
            if channel.length == 0 {
                continue;
            }
            let fits = channel.offset + channel.length <= self.bits_per_pixel;
            match channel.mask() {
                Some(mask) if fits && used & mask == 0 => used |= mask,
                _ => return Err(FormatError::Layout(*self)),
            }
        }
        Ok(depth)
    }

    /// The pixel value of red, green and blue levels (each within its channel's length).
    fn value(&self, [r, g, b]: [u32; 3]) -> u32 {
        let alpha = self.transp.mask().unwrap_or(0);
        (r << self.red.offset) | (g << self.green.offset) | (b << self.blue.offset) | alpha
    }
}

/// A core pixel format whose levels a framebuffer format takes: [`Rgb565`] for the 5-6-5
/// formats, [`Rgb888`] for the 8-8-8 ones.
pub trait Levels: Pixel + Default + Send {
    /// The framebuffer depth these levels fill.
    const DEPTH: Depth;
    /// The red, green and blue levels.
    fn levels(self) -> [u32; 3];
}

impl Levels for Rgb565 {
    const DEPTH: Depth = Depth::Bits565;
    fn levels(self) -> [u32; 3] {
        let (r, g, b) = Rgb565::levels(self);
        [r, g, b].map(u32::from)
    }
}

impl Levels for Rgb888 {
    const DEPTH: Depth = Depth::Bits888;
    fn levels(self) -> [u32; 3] {
        [self.r, self.g, self.b].map(u32::from)
    }
}

/// A rectangle of a frame and where it goes in a framebuffer's memory.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Window {
    /// The rectangle's top-left pixel in the frame.
    pub from: (u32, u32),
    /// Where that pixel goes: a pixel of the framebuffer's virtual screen (the visible
    /// area's offset included).
    pub to: (u32, u32),
    /// The rectangle's width and height in pixels.
    pub size: (u32, u32),
}

/// The window that centres a `frame` (width, height) on a `screen` (the visible width and
/// height) whose top-left pixel is `origin` in the virtual screen: a smaller frame sits in the
/// middle, a larger one shows its middle part.
pub fn centred(frame: (u32, u32), screen: (u32, u32), origin: (u32, u32)) -> Window {
    let axis = |frame: u32, screen: u32, origin: u32| {
        let size = frame.min(screen);
        let from = (frame - size) / 2;
        let to = origin + (screen - size) / 2;
        (from, to, size)
    };
    let (fx, tx, w) = axis(frame.0, screen.0, origin.0);
    let (fy, ty, h) = axis(frame.1, screen.1, origin.1);
    Window {
        from: (fx, fy),
        to: (tx, ty),
        size: (w, h),
    }
}

/// Why a frame was not written into framebuffer memory (nothing was written).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum WriteError {
    /// The format is not written.
    Format(FormatError),
    /// The frame was rendered in levels of the other depth (an [`Rgb888`] frame for a 5-6-5
    /// format, say).
    Depth {
        /// What the format takes.
        format: Depth,
        /// What the frame holds.
        frame: Depth,
    },
    /// The window is not inside the frame, or the frame's length is not a whole number of
    /// rows of its width.
    Frame {
        /// The frame's width.
        width: u32,
        /// The frame's length in pixels.
        pixels: usize,
    },
    /// The window does not fit in a line or in the memory.
    Memory {
        /// The bytes the window's last line ends at (or a line's end, past `line_length`).
        needed: usize,
        /// What there is: the memory's length, or the line length.
        available: usize,
    },
}

impl fmt::Display for WriteError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            WriteError::Format(e) => e.fmt(f),
            WriteError::Depth { format, frame } => write!(
                f,
                "the framebuffer takes {format:?} levels, the frame holds {frame:?}"
            ),
            WriteError::Frame { width, pixels } => write!(
                f,
                "the window is not inside the frame ({pixels} pixels, {width} wide)"
            ),
            WriteError::Memory { needed, available } => write!(
                f,
                "the window needs {needed} bytes of the framebuffer, which has {available}"
            ),
        }
    }
}

impl std::error::Error for WriteError {}

impl From<FormatError> for WriteError {
    fn from(e: FormatError) -> Self {
        WriteError::Format(e)
    }
}

/// Writes the `window` of a row-major `frame` of `frame_width` pixels into framebuffer
/// `memory` of `format`: row `y` of the window starts at byte
/// `(to.1 + y)·line_length + to.0·bytes_per_pixel`, and no other byte is touched (the
/// padding at the end of each line, the pixels outside the window). Everything is checked
/// before the first byte is written.
pub fn write_frame<P: Levels>(
    memory: &mut [u8],
    format: &FbFormat,
    frame: &[P],
    frame_width: u32,
    window: Window,
) -> Result<(), WriteError> {
    let depth = format.depth()?;
    if depth != P::DEPTH {
        return Err(WriteError::Depth {
            format: depth,
            frame: P::DEPTH,
        });
    }
    let (w, h) = (window.size.0 as usize, window.size.1 as usize);
    let fw = frame_width as usize;
    let bad_frame = WriteError::Frame {
        width: frame_width,
        pixels: frame.len(),
    };
    let frame_rows = if fw == 0 || !frame.len().is_multiple_of(fw) {
        return Err(bad_frame);
    } else {
        frame.len() / fw
    };
    let (fx, fy) = (window.from.0 as usize, window.from.1 as usize);
    if fx + w > fw || fy + h > frame_rows {
        return Err(bad_frame);
    }
    if w == 0 || h == 0 {
        return Ok(());
    }
    let bpp = format.bytes_per_pixel();
    let (tx, ty) = (window.to.0 as usize, window.to.1 as usize);
    let line_end = (tx + w) * bpp;
    if line_end > format.line_length {
        return Err(WriteError::Memory {
            needed: line_end,
            available: format.line_length,
        });
    }
    let needed = (ty + h - 1) * format.line_length + line_end;
    if needed > memory.len() {
        return Err(WriteError::Memory {
            needed,
            available: memory.len(),
        });
    }
    for row in 0..h {
        let src = &frame[(fy + row) * fw + fx..][..w];
        let start = (ty + row) * format.line_length + tx * bpp;
        let dst = &mut memory[start..start + w * bpp];
        for (out, &pixel) in dst.chunks_exact_mut(bpp).zip(src) {
            let bytes = format.value(pixel.levels()).to_ne_bytes();
            // The value's low `bpp` bytes, in the machine's order.
            let low = if cfg!(target_endian = "little") {
                &bytes[..bpp]
            } else {
                &bytes[4 - bpp..]
            };
            out.copy_from_slice(low);
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use shadeline::Bgr565;

    const RGB565: FbFormat = format(16, [(11, 5), (5, 6), (0, 5)], (0, 0));
    const BGR565: FbFormat = format(16, [(0, 5), (5, 6), (11, 5)], (0, 0));
    const XRGB8888: FbFormat = format(32, [(16, 8), (8, 8), (0, 8)], (0, 0));
    const ARGB8888: FbFormat = format(32, [(16, 8), (8, 8), (0, 8)], (24, 8));
    const XBGR8888: FbFormat = format(32, [(0, 8), (8, 8), (16, 8)], (0, 0));
    const RGBX8888: FbFormat = format(32, [(24, 8), (16, 8), (8, 8)], (0, 0));
    const RGB888: FbFormat = format(24, [(16, 8), (8, 8), (0, 8)], (0, 0));
    const BGR888: FbFormat = format(24, [(0, 8), (8, 8), (16, 8)], (0, 0));

    const fn format(bits: u32, rgb: [(u32, u32); 3], transp: (u32, u32)) -> FbFormat {
        FbFormat {
            bits_per_pixel: bits,
            red: Channel::new(rgb[0].0, rgb[0].1),
            green: Channel::new(rgb[1].0, rgb[1].1),
            blue: Channel::new(rgb[2].0, rgb[2].1),
            transp: Channel::new(transp.0, transp.1),
            line_length: 0,
        }
    }

    /// A frame whose every pixel differs from its neighbours.
    fn frame888(w: u32, h: u32) -> Vec<Rgb888> {
        (0..w * h)
            .map(|i| Rgb888 {
                r: (i * 37 + 1) as u8,
                g: (i * 11 + 100) as u8,
                b: (i * 29 + 7) as u8,
            })
            .collect()
    }

    fn frame565(w: u32, h: u32) -> Vec<Rgb565> {
        (0..w * h)
            .map(|i| Rgb565::pack((i * 7) as u16, (i * 13 + 3) as u16, (31 - i % 32) as u16))
            .collect()
    }

    /// The pixel value at byte `at` of `memory`, read back in the machine's order.
    fn read(memory: &[u8], at: usize, bpp: usize) -> u32 {
        let mut bytes = [0u8; 4];
        if cfg!(target_endian = "little") {
            bytes[..bpp].copy_from_slice(&memory[at..at + bpp]);
        } else {
            bytes[4 - bpp..].copy_from_slice(&memory[at..at + bpp]);
        }
        u32::from_ne_bytes(bytes)
    }

    /// A channel's level in a pixel value.
    fn level(value: u32, c: Channel) -> u32 {
        (value >> c.offset) & ((1 << c.length) - 1)
    }

    const PAD: u8 = 0xa5;

    /// Writes `frame` (`w × h`) at `(x, y)` of a `lines`-line memory padded by `pad` bytes
    /// after `screen_w` pixels, and checks every pixel's levels and that every other byte is
    /// still the pad.
    fn check_write<P: Levels + std::fmt::Debug>(
        mut format: FbFormat,
        frame: &[P],
        (w, h): (u32, u32),
        (screen_w, lines): (u32, u32),
        (x, y): (u32, u32),
        pad: usize,
    ) {
        let bpp = format.bytes_per_pixel();
        format.line_length = screen_w as usize * bpp + pad;
        let mut memory = vec![PAD; format.line_length * lines as usize];
        let window = Window {
            from: (0, 0),
            to: (x, y),
            size: (w, h),
        };
        write_frame(&mut memory, &format, frame, w, window).unwrap();
        let mut written = vec![false; memory.len()];
        for row in 0..h as usize {
            for col in 0..w as usize {
                let at = (y as usize + row) * format.line_length + (x as usize + col) * bpp;
                written[at..at + bpp].fill(true);
                let value = read(&memory, at, bpp);
                let pixel = frame[row * w as usize + col];
                let got = [format.red, format.green, format.blue].map(|c| level(value, c));
                assert_eq!(got, pixel.levels(), "{} ({col}, {row})", format.name());
                if format.transp.length > 0 {
                    assert_eq!(level(value, format.transp), (1 << format.transp.length) - 1);
                } else {
                    // The bits no channel uses are zero.
                    let used = [format.red, format.green, format.blue]
                        .iter()
                        .fold(0, |m, c| m | c.mask().unwrap());
                    assert_eq!(value & !used, 0, "{}", format.name());
                }
            }
        }
        for (i, (&byte, &w)) in memory.iter().zip(&written).enumerate() {
            if !w {
                assert_eq!(byte, PAD, "{}: byte {i} touched", format.name());
            }
        }
    }

    #[test]
    fn every_format_is_written_at_its_offsets_and_padding_stays_untouched() {
        let (w, h) = (5, 3);
        for format in [XRGB8888, ARGB8888, XBGR8888, RGBX8888, RGB888, BGR888] {
            assert_eq!(format.depth(), Ok(Depth::Bits888), "{}", format.name());
            // Odd strides: 1, 3 and 7 bytes of padding after a 7-pixel line; the frame in a
            // corner and inside.
            for (pad, at) in [(1, (0, 0)), (3, (2, 1)), (7, (1, 2))] {
                check_write(format, &frame888(w, h), (w, h), (7, 6), at, pad);
            }
        }
        for format in [RGB565, BGR565] {
            assert_eq!(format.depth(), Ok(Depth::Bits565), "{}", format.name());
            for (pad, at) in [(1, (0, 0)), (3, (2, 1)), (7, (1, 2))] {
                check_write(format, &frame565(w, h), (w, h), (7, 6), at, pad);
            }
        }
    }

    #[test]
    fn the_565_formats_hold_the_core_crates_pixels_in_native_order() {
        let frame = frame565(4, 1);
        let mut rgb = RGB565;
        rgb.line_length = 9; // one odd byte of padding
        let mut bgr = BGR565;
        bgr.line_length = 9;
        let window = centred((4, 1), (4, 1), (0, 0));
        let (mut a, mut b) = (vec![0u8; 9], vec![0u8; 9]);
        write_frame(&mut a, &rgb, &frame, 4, window).unwrap();
        write_frame(&mut b, &bgr, &frame, 4, window).unwrap();
        for (i, p) in frame.iter().enumerate() {
            assert_eq!(a[2 * i..2 * i + 2], p.0.to_ne_bytes());
            let (r, g, b5) = p.levels();
            let bgr = Bgr565::pack(r.into(), g.into(), b5.into());
            assert_eq!(b[2 * i..2 * i + 2], bgr.0.to_ne_bytes());
        }
    }

    #[test]
    fn formats_are_named_from_the_top_bit_down() {
        let names = [
            (RGB565, "RGB565"),
            (BGR565, "BGR565"),
            (XRGB8888, "XRGB8888"),
            (ARGB8888, "ARGB8888"),
            (XBGR8888, "XBGR8888"),
            (RGBX8888, "RGBX8888"),
            (RGB888, "RGB888"),
            (BGR888, "BGR888"),
        ];
        for (format, name) in names {
            assert_eq!(format.name(), name);
        }
    }

    #[test]
    fn formats_shadeline_does_not_write_are_refused_naming_their_numbers() {
        let rgb555 = format(16, [(10, 5), (5, 5), (0, 5)], (0, 0));
        let palette = format(8, [(0, 8), (0, 8), (0, 8)], (0, 0));
        let deep = format(32, [(20, 10), (10, 10), (0, 10)], (0, 0));
        let overlapping = format(32, [(16, 8), (12, 8), (0, 8)], (0, 0));
        let outside = format(24, [(24, 8), (8, 8), (0, 8)], (0, 0));
        let alpha_over_red = format(32, [(16, 8), (8, 8), (0, 8)], (16, 8));
        let cases = [
            (rgb555, FormatError::ChannelLengths(rgb555)),
            (palette, FormatError::BitsPerPixel(palette)),
            (deep, FormatError::ChannelLengths(deep)),
            (overlapping, FormatError::Layout(overlapping)),
            (outside, FormatError::Layout(outside)),
            (alpha_over_red, FormatError::Layout(alpha_over_red)),
        ];
        for (format, error) in cases {
            assert_eq!(format.depth(), Err(error));
            let mut memory = vec![PAD; 64];
            let written = write_frame(
                &mut memory,
                &format,
                &frame888(2, 2),
                2,
                Window {
                    from: (0, 0),
                    to: (0, 0),
                    size: (2, 2),
                },
            );
            assert_eq!(written, Err(WriteError::Format(error)));
            assert!(memory.iter().all(|&b| b == PAD));
        }
        assert_eq!(
            FormatError::ChannelLengths(rgb555).to_string(),
            "shadeline does not write this pixel format (its channel lengths): 16 bits per \
             pixel, red 10:5, green 5:5, blue 0:5 (it writes 16-bit RGB565/BGR565, 24-bit \
             RGB888/BGR888 and 32-bit XRGB8888/XBGR8888 and the like)"
        );
        assert_eq!(
            rgb555.name(),
            "16 bits per pixel, red 10:5, green 5:5, blue 0:5"
        );
    }

    #[test]
    fn a_frame_is_centred_and_cropped_to_the_screen() {
        // Smaller: in the middle, offset by the visible area's origin.
        assert_eq!(
            centred((4, 2), (10, 7), (0, 240)),
            Window {
                from: (0, 0),
                to: (3, 242),
                size: (4, 2)
            }
        );
        // Larger: its middle part.
        assert_eq!(
            centred((12, 9), (8, 4), (0, 0)),
            Window {
                from: (2, 2),
                to: (0, 0),
                size: (8, 4)
            }
        );
        // A larger frame's middle lands on every pixel of a small screen, with padding kept.
        let (w, h) = (9u32, 7u32);
        let frame = frame888(w, h);
        let mut fmt = XRGB8888;
        fmt.line_length = 4 * 4 + 5;
        let mut memory = vec![PAD; fmt.line_length * 3];
        let window = centred((w, h), (4, 3), (0, 0));
        write_frame(&mut memory, &fmt, &frame, w, window).unwrap();
        for row in 0..3usize {
            for col in 0..4usize {
                let value = read(&memory, row * fmt.line_length + col * 4, 4);
                let pixel = frame[(row + 2) * w as usize + col + 2];
                assert_eq!(
                    [fmt.red, fmt.green, fmt.blue].map(|c| level(value, c)),
                    pixel.levels()
                );
            }
            assert!(memory[row * fmt.line_length + 16..][..5]
                .iter()
                .all(|&b| b == PAD));
        }
    }

    #[test]
    fn a_window_past_the_memory_a_line_or_the_frame_writes_nothing() {
        let frame = frame565(4, 4);
        let mut fmt = RGB565;
        fmt.line_length = 10; // 5 pixels
        let mut memory = vec![PAD; 10 * 4 - 1]; // the last line one byte short
        let whole = Window {
            from: (0, 0),
            to: (0, 0),
            size: (4, 4),
        };
        let cases = [
            // One pixel to the right, the last line ends at 3·10 + (1 + 4)·2 = 40 bytes.
            (
                Window {
                    to: (1, 0),
                    ..whole
                },
                WriteError::Memory {
                    needed: 40,
                    available: 39,
                },
            ),
            // Two to the right, a line ends at 12 bytes, past the line length.
            (
                Window {
                    to: (2, 0),
                    ..whole
                },
                WriteError::Memory {
                    needed: 12,
                    available: 10,
                },
            ),
            // A window one column past the frame's right edge.
            (
                Window {
                    from: (1, 0),
                    ..whole
                },
                WriteError::Frame {
                    width: 4,
                    pixels: 16,
                },
            ),
        ];
        for (window, error) in cases {
            assert_eq!(
                write_frame(&mut memory, &fmt, &frame, 4, window),
                Err(error)
            );
            assert!(memory.iter().all(|&b| b == PAD));
        }
        // An Rgb888 frame for a 5-6-5 format is refused too.
        let got = write_frame(&mut memory, &fmt, &frame888(4, 4), 4, whole);
        assert_eq!(
            got,
            Err(WriteError::Depth {
                format: Depth::Bits565,
                frame: Depth::Bits888
            })
        );
        // And the same window at (0, 0) fits: 3·10 + 8 = 38 bytes.
        write_frame(&mut memory, &fmt, &frame, 4, whole).unwrap();
        assert_eq!(memory[38], PAD);
    }
}
