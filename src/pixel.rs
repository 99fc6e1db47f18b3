//! Pixel formats: what each one stores and how it packs its levels.
//!
//! The kernels produce linear RGB (and, for the diagnostic [`HitRecord`] format, which sphere
//! was hit and which lights were blocked). A format with levels states its largest level per
//! channel ([`Pixel::LEVELS`]) and packs levels into its storage ([`Pixel::from_levels`]);
//! how a colour becomes levels (clamp, round to nearest, optional sRGB and dithering, the
//! luma of [`Gray8`]) is [`crate::encoding`]'s, one rule for every path.
//!
//! | format | storage | channels |
//! |---|---|---|
//! | [`Rgb888`] | 3 bytes `R, G, B` | 8 bits each, `0..=255` |
//! | [`Rgb565`] | native `u16`, red high | 5/6/5 bits |
//! | [`Bgr565`] | native `u16`, blue high | 5/6/5 bits |
//! | [`Gray8`] | 1 byte | 8-bit Rec. 709 luma |
//! | [`LinearRgb`] | 3 × `f32` | the kernel's linear colour, unclamped |
//! | [`HitRecord`] | sphere index and shadow bits | what the kernel decided |
//!
//! For a display's byte layout (RGB565 big-endian) see [`BytePixel`] and
//! [`Render::render_line_bytes`](crate::Render::render_line_bytes).

use crate::encoding::{
    encode_levels, levels, levels_fixed, luma, luma_code, quantize, quantize_fixed, Encoding,
};

/// A linear RGB triple: a colour in the scene, and the unclamped `f32` output format.
///
/// As an output format it receives the kernel's colour bit for bit (no clamp, no rounding),
/// which is what the path-agreement tests compare.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct LinearRgb {
    /// Red, linear.
    pub r: f32,
    /// Green, linear.
    pub g: f32,
    /// Blue, linear.
    pub b: f32,
}

impl LinearRgb {
    /// A colour from its three linear channels.
    pub const fn new(r: f32, g: f32, b: f32) -> Self {
        LinearRgb { r, g, b }
    }
}

/// 8 bits per channel, in memory order R, G, B (3 bytes, no padding).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, Hash)]
#[repr(C)]
pub struct Rgb888 {
    /// Red level, 0..=255.
    pub r: u8,
    /// Green level, 0..=255.
    pub g: u8,
    /// Blue level, 0..=255.
    pub b: u8,
}

/// 5-6-5 bits packed in a native-endian `u16`: red in bits 15..11, green 10..5, blue 4..0.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, Hash)]
#[repr(transparent)]
pub struct Rgb565(pub u16);

impl Rgb565 {
    /// The 5-bit red, 6-bit green and 5-bit blue levels.
    pub fn levels(self) -> (u8, u8, u8) {
        (
            (self.0 >> 11) as u8,
            ((self.0 >> 5) & 0x3f) as u8,
            (self.0 & 0x1f) as u8,
        )
    }
}

/// What the kernel decided for a pixel, instead of its colour: which sphere the primary ray
/// hit and which lights were blocked there. An object-ID buffer (for picking), and the record
/// the tests use to compare ray decisions between paths and the f64 reference.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, Hash)]
pub struct HitRecord {
    /// Index of the nearest sphere hit, or `None` for background.
    pub sphere: Option<u16>,
    /// Bit `k` is set if light `k` (`k < 32`) is blocked by a shadow ray; 0 on background.
    pub shadowed: u32,
}

/// Everything the kernel knows about one pixel, handed to [`Pixel::encode`].
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct Shade {
    /// The linear colour, unclamped.
    pub color: LinearRgb,
    /// The hit record; filled in only for formats whose [`Pixel::NEEDS_HITS`] is true.
    pub hit: HitRecord,
}

/// What an integer-only path knows about one pixel, handed to [`Pixel::encode_fixed`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct FixedShade {
    /// Linear colour per channel as unsigned 16.16 fixed point (`65536` is 1.0), saturated.
    pub color: [u32; 3],
    /// The hit record; filled in only for formats whose [`Pixel::NEEDS_HITS`] is true.
    pub hit: HitRecord,
}

/// A pixel format the row renderers can write.
///
/// Implemented for [`Rgb888`], [`Rgb565`], [`Bgr565`], [`Gray8`], [`LinearRgb`] and
/// [`HitRecord`]. The [`Encoding`] of a frame applies to the formats with
/// [`Pixel::LEVELS`]; the others store the kernel's output as it is.
pub trait Pixel: Copy {
    /// Whether [`Shade::hit`] must be filled in; formats that only store colour leave it
    /// `false` so the kernel skips the bookkeeping.
    const NEEDS_HITS: bool = false;
    /// For formats that store rounded levels: the largest level of each channel (255 for
    /// 8 bits). The float paths then quantize a whole packet at once with exactly the rule
    /// of [`quantize`] and build pixels with [`Pixel::from_levels`]. `None` for formats that
    /// store something else; they get [`Pixel::encode`] per pixel.
    const LEVELS: Option<[u16; 3]> = None;
    /// Whether the format stores one grey level instead of three channels: the encode stage
    /// then quantizes the luma of the clamped channels (weights
    /// [`LUMA_WEIGHTS`](crate::encoding::LUMA_WEIGHTS)) with `LEVELS[0]` and passes it to
    /// [`Pixel::from_levels`] as all three levels. Only meaningful with `LEVELS`.
    const GRAY: bool = false;
    /// Builds a pixel from channel levels in `0..=LEVELS[c]`; only called when
    /// [`Pixel::LEVELS`] is `Some`. The default ignores the levels (for formats without them).
    #[inline(always)]
    fn from_levels(levels: [u16; 3]) -> Self {
        let _ = levels;
        Self::encode(&Shade::default())
    }
    /// Encodes one sample shaded in `f32`.
    fn encode(shade: &Shade) -> Self;
    /// Encodes one sample shaded in fixed point, with integer arithmetic only (except for
    /// [`LinearRgb`], a host-side test format, which converts to `f32`).
    fn encode_fixed(shade: &FixedShade) -> Self;
}

const RGB888_MAX: [u16; 3] = [255, 255, 255];
const RGB565_MAX: [u16; 3] = [31, 63, 31];

impl Pixel for Rgb888 {
    const LEVELS: Option<[u16; 3]> = Some(RGB888_MAX);
    #[inline(always)]
    fn from_levels([r, g, b]: [u16; 3]) -> Self {
        Rgb888 {
            r: r as u8,
            g: g as u8,
            b: b as u8,
        }
    }
    #[inline(always)]
    fn encode(s: &Shade) -> Self {
        Self::from_levels(levels([s.color.r, s.color.g, s.color.b], RGB888_MAX))
    }
    #[inline(always)]
    fn encode_fixed(s: &FixedShade) -> Self {
        Self::from_levels(levels_fixed(s.color, RGB888_MAX))
    }
}

impl Rgb565 {
    /// Packs 5-bit red, 6-bit green and 5-bit blue levels.
    #[inline(always)]
    pub fn pack(r: u16, g: u16, b: u16) -> Self {
        Rgb565(((r & 0x1f) << 11) | ((g & 0x3f) << 5) | (b & 0x1f))
    }
}

impl Pixel for Rgb565 {
    const LEVELS: Option<[u16; 3]> = Some(RGB565_MAX);
    #[inline(always)]
    fn from_levels([r, g, b]: [u16; 3]) -> Self {
        Rgb565::pack(r, g, b)
    }
    #[inline(always)]
    fn encode(s: &Shade) -> Self {
        Self::from_levels(levels([s.color.r, s.color.g, s.color.b], RGB565_MAX))
    }
    #[inline(always)]
    fn encode_fixed(s: &FixedShade) -> Self {
        Self::from_levels(levels_fixed(s.color, RGB565_MAX))
    }
}

/// 5-6-5 bits packed in a native-endian `u16` with blue in the high bits: blue in bits
/// 15..11, green 10..5, red 4..0 (the "BGR" order some panels are wired for, e.g. with an
/// ST7789/ILI9341 whose `MADCTL` BGR bit is set).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, Hash)]
#[repr(transparent)]
pub struct Bgr565(pub u16);

impl Bgr565 {
    /// Packs 5-bit red, 6-bit green and 5-bit blue levels (blue in the high bits).
    #[inline(always)]
    pub fn pack(r: u16, g: u16, b: u16) -> Self {
        Bgr565(((b & 0x1f) << 11) | ((g & 0x3f) << 5) | (r & 0x1f))
    }

    /// The 5-bit red, 6-bit green and 5-bit blue levels.
    pub fn levels(self) -> (u8, u8, u8) {
        (
            (self.0 & 0x1f) as u8,
            ((self.0 >> 5) & 0x3f) as u8,
            (self.0 >> 11) as u8,
        )
    }
}

impl Pixel for Bgr565 {
    const LEVELS: Option<[u16; 3]> = Some(RGB565_MAX);
    #[inline(always)]
    fn from_levels([r, g, b]: [u16; 3]) -> Self {
        Bgr565::pack(r, g, b)
    }
    #[inline(always)]
    fn encode(s: &Shade) -> Self {
        Self::from_levels(levels([s.color.r, s.color.g, s.color.b], RGB565_MAX))
    }
    #[inline(always)]
    fn encode_fixed(s: &FixedShade) -> Self {
        Self::from_levels(levels_fixed(s.color, RGB565_MAX))
    }
}

/// An 8-bit grey level, `0..=255`: the luma of the linear colour with the Rec. 709 weights
/// `0.2126, 0.7152, 0.0722` as 16-bit fractions ([`LUMA_WEIGHTS`](crate::encoding::LUMA_WEIGHTS)).
///
/// The rule, per path: the float paths clamp each channel to `[0, 1]`, form
/// `r·w_r + g·w_g + b·w_b` in `f32` (left to right, the weights exact in `f32`) and round it
/// like [`quantize`]; the fixed path forms the same sum in integers
/// ([`luma_code`]) and rounds it like [`quantize_fixed`]. With a
/// non-default [`Encoding`] both take the integer route from linear codes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, Hash)]
#[repr(transparent)]
pub struct Gray8(pub u8);

impl Pixel for Gray8 {
    const LEVELS: Option<[u16; 3]> = Some([255, 255, 255]);
    const GRAY: bool = true;
    #[inline(always)]
    fn from_levels([l, _, _]: [u16; 3]) -> Self {
        Gray8(l as u8)
    }
    #[inline(always)]
    fn encode(s: &Shade) -> Self {
        Gray8(quantize(luma([s.color.r, s.color.g, s.color.b]), 255.0) as u8)
    }
    #[inline(always)]
    fn encode_fixed(s: &FixedShade) -> Self {
        Gray8(quantize_fixed(luma_code(s.color), 255) as u8)
    }
}

/// A format with a byte layout a display controller takes as it is, for
/// [`Render::render_line_bytes`](crate::Render::render_line_bytes).
///
/// | format | bytes per pixel | byte order |
/// |---|---|---|
/// | [`Rgb565`] | 2 | big-endian: `RRRRRGGG GGGBBBBB` (what SPI panels such as the ST7789 and ILI9341 read in their 16-bit mode) |
/// | [`Bgr565`] | 2 | big-endian: `BBBBBGGG GGGRRRRR` |
/// | [`Rgb888`] | 3 | `R, G, B` |
/// | [`Gray8`] | 1 | the level |
pub trait BytePixel: Pixel + Default {
    /// Bytes per pixel.
    const BYTES: usize;
    /// The bytes, `BYTES` long.
    type Bytes: AsRef<[u8]>;
    /// The pixel as the display takes it.
    fn to_bytes(self) -> Self::Bytes;
}

impl BytePixel for Rgb565 {
    const BYTES: usize = 2;
    type Bytes = [u8; 2];
    #[inline(always)]
    fn to_bytes(self) -> [u8; 2] {
        self.0.to_be_bytes()
    }
}

impl BytePixel for Bgr565 {
    const BYTES: usize = 2;
    type Bytes = [u8; 2];
    #[inline(always)]
    fn to_bytes(self) -> [u8; 2] {
        self.0.to_be_bytes()
    }
}

impl BytePixel for Rgb888 {
    const BYTES: usize = 3;
    type Bytes = [u8; 3];
    #[inline(always)]
    fn to_bytes(self) -> [u8; 3] {
        [self.r, self.g, self.b]
    }
}

impl BytePixel for Gray8 {
    const BYTES: usize = 1;
    type Bytes = [u8; 1];
    #[inline(always)]
    fn to_bytes(self) -> [u8; 1] {
        [self.0]
    }
}

impl Pixel for LinearRgb {
    #[inline(always)]
    fn encode(s: &Shade) -> Self {
        s.color
    }
    fn encode_fixed(s: &FixedShade) -> Self {
        let [r, g, b] = s.color;
        let f = |v: u32| v as f32 / 65536.0;
        LinearRgb::new(f(r), f(g), f(b))
    }
}

impl Pixel for HitRecord {
    const NEEDS_HITS: bool = true;
    #[inline(always)]
    fn encode(s: &Shade) -> Self {
        s.hit
    }
    #[inline(always)]
    fn encode_fixed(s: &FixedShade) -> Self {
        s.hit
    }
}

/// A pixel of a levels format from its linear codes, position and encoding
/// ([`encode_levels`]); `None` for formats without levels.
#[inline]
pub(crate) fn pixel_from_codes<P: Pixel>(
    codes: [u32; 3],
    encoding: Encoding,
    x: u32,
    y: u32,
) -> Option<P> {
    let levels = P::LEVELS?;
    Some(P::from_levels(encode_levels(
        codes,
        levels,
        P::GRAY,
        encoding,
        x,
        y,
    )))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quantize_rounds_to_nearest_and_clamps() {
        assert_eq!(quantize(-1.0, 255.0), 0);
        assert_eq!(quantize(f32::NAN, 255.0), 0);
        assert_eq!(quantize(2.0, 255.0), 255);
        assert_eq!(quantize(f32::INFINITY, 31.0), 31);
        assert_eq!(quantize(0.5 / 255.0 - 1e-6, 255.0), 0);
        assert_eq!(quantize(0.5 / 255.0 + 1e-6, 255.0), 1);
        assert_eq!(quantize(1.0, 63.0), 63);
        assert_eq!(quantize_fixed(u32::MAX, 255), 255);
        assert_eq!(quantize_fixed(0, 255), 0);
        assert_eq!(quantize_fixed(128, 255), 0); // 0.00195 < half a level
        assert_eq!(quantize_fixed(129, 255), 1);
        // Both rules agree wherever the f32 value is exactly a 16.16 value.
        for raw in (0..=65536u32).step_by(97) {
            assert_eq!(
                quantize_fixed(raw, 255),
                quantize(raw as f32 / 65536.0, 255.0)
            );
            assert_eq!(
                quantize_fixed(raw, 31),
                quantize(raw as f32 / 65536.0, 31.0)
            );
        }
    }

    #[test]
    fn rgb565_packs_in_the_documented_order() {
        let px = Rgb565::encode(&Shade {
            color: LinearRgb::new(1.0, 0.0, 1.0),
            hit: HitRecord::default(),
        });
        assert_eq!(px.0, 0xf81f); // red 11111, green 000000, blue 11111
        assert_eq!(px.levels(), (31, 0, 31));
    }
}
