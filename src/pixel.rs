//! Pixel formats and the encode stage: how a shaded sample becomes the caller's pixel.
//!
//! The kernels produce linear RGB (and, for the diagnostic [`HitRecord`] format, which sphere
//! was hit and which lights were blocked). The encode stage is the same for every path that
//! produces `f32`: clamp each channel to `[0, 1]`, scale to the format's largest level and
//! round to nearest (`⌊c·max + ½⌋`). No gamma is applied: the scene's numbers are written
//! as-is, as in the lesson. NaN cannot reach this stage (the scene model rules it out), but the
//! clamp is written so that it would encode as 0, never as garbage.

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

/// A pixel format the row renderers can write.
///
/// Implemented for [`Rgb888`], [`Rgb565`], [`LinearRgb`] and [`HitRecord`].
pub trait Pixel: Copy {
    /// Whether [`Shade::hit`] must be filled in; formats that only store colour leave it
    /// `false` so the kernel skips the bookkeeping.
    const NEEDS_HITS: bool = false;
    /// Encodes one shaded sample.
    fn encode(shade: &Shade) -> Self;
}

/// `⌊clamp(c, 0, 1)·max + ½⌋`: round to the nearest of `max + 1` levels. NaN gives 0.
#[inline(always)]
pub fn quantize(c: f32, max: f32) -> u16 {
    let c = if c > 0.0 { c } else { 0.0 };
    let c = if c < 1.0 { c } else { 1.0 };
    (c * max + 0.5) as u16
}

impl Pixel for Rgb888 {
    #[inline(always)]
    fn encode(s: &Shade) -> Self {
        Rgb888 {
            r: quantize(s.color.r, 255.0) as u8,
            g: quantize(s.color.g, 255.0) as u8,
            b: quantize(s.color.b, 255.0) as u8,
        }
    }
}

impl Pixel for Rgb565 {
    #[inline(always)]
    fn encode(s: &Shade) -> Self {
        let r = quantize(s.color.r, 31.0);
        let g = quantize(s.color.g, 63.0);
        let b = quantize(s.color.b, 31.0);
        Rgb565((r << 11) | (g << 5) | b)
    }
}

impl Pixel for LinearRgb {
    #[inline(always)]
    fn encode(s: &Shade) -> Self {
        s.color
    }
}

impl Pixel for HitRecord {
    const NEEDS_HITS: bool = true;
    #[inline(always)]
    fn encode(s: &Shade) -> Self {
        s.hit
    }
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
    }

    #[test]
    fn rgb565_packs_in_the_documented_order() {
        let px = Rgb565::encode(&Shade {
            color: LinearRgb::new(1.0, 0.0, 1.0),
            hit: HitRecord::default(),
        });
        assert_eq!(px.0, 0b11111_000000_11111);
        assert_eq!(px.levels(), (31, 0, 31));
    }
}
