//! The encode step, in one place: how a kernel's linear colour becomes a pixel's levels. Every
//! rounding rule of the crate is here: [`quantize`] (`f32`, and the same operations a packet
//! at a time for the SIMD paths), [`quantize_fixed`] (unsigned 16.16), the linear codes
//! ([`linear_code`], [`linear_code_fixed`]), the luma of [`Gray8`](crate::Gray8)
//! ([`luma_code`]), the sRGB transfer and ordered dithering ([`encode_levels`]). Pixel
//! formats only state their levels and pack them ([`crate::pixel`]).
//!
//! The default, [`Encoding::LINEAR`], is the lesson's rule: clamp to `[0, 1]` (NaN gives 0),
//! scale to the format's largest level, round to nearest ([`quantize`] in `f32`,
//! [`quantize_fixed`] in fixed point), the float paths a whole packet at a time. No gamma is
//! applied: the scene's numbers are written as they are. Every other encoding goes through
//! **one integer function** of the pixel's *linear code* and position, shared by every path:
//!
//! 1. **Linear code** `c` in `0..=65536` (unsigned 16.16, `65536` is 1.0) per channel:
//!    `⌊clamp(v, 0, 1)·65536 + ½⌋` from an `f32` (NaN gives 0; computed a packet at a time
//!    with the same operations at every lane width, so scalar and SIMD get the same codes), or
//!    `min(v, 65536)` from the fixed path's unsigned 16.16 colour. The two agree wherever the
//!    `f32` value is a 16.16 value, as the two `quantize` rules do.
//! 2. **Luma** (only [`Gray8`](crate::Gray8)): `(c_r·13933 + c_g·46871 + c_b·4732 + 2¹⁵) >> 16`
//!    on the clamped codes: the Rec. 709 weights `0.2126, 0.7152, 0.0722` rounded to 16-bit
//!    fractions that sum to exactly `65536` ([`LUMA_WEIGHTS`]), so white stays white.
//! 3. **Transfer**: [`Transfer::Linear`] keeps the code; [`Transfer::Srgb`] maps it through
//!    [`srgb_encode`]: a 4097-entry table of the sRGB curve at `i/4096` ([`SRGB_TABLE`],
//!    unsigned 1.15, evaluated at compile time), interpolated linearly with the code's low
//!    4 bits. The result is the encoded value `e` in `0..=65536`.
//! 4. **Quantize** to the channel's `max` level: `⌊(e·max + t) >> 16⌋` with threshold
//!    `t = 2¹⁵` (round to nearest) without dithering, or the 4×4 Bayer threshold of the
//!    pixel's position with it ([`dither_threshold`]).
//!
//! So with sRGB and dithering, the scalar and SIMD paths give the same bits (same codes, same
//! integers), and the fixed path differs from them only where its linear colour does (it
//! stays within its budget of two 8-bit levels of the f64 reference). The encoding is a pure
//! function of the colour and the pixel's `(x, y)`: rows stay independent and frames
//! deterministic.
//!
//! The default takes its own faster route, with no integer step: the float paths quantize
//! whole packets in `f32` ([`quantize`]'s operations), which the golden CRCs pin down.
//!
//! # Choosing one
//!
//! An encoding belongs to a prepared frame: [`Render::with_encoding`](crate::Render::with_encoding) wraps any path's frame in
//! [`Encoded`](crate::Encoded), which renders with it; or pass one per call with
//! [`Render::render_segment_with`](crate::Render::render_segment_with).
//!
//! ```
//! use shadeline::{exponent_series, Encoding, Prepared, Render, Rgb565, Simd8};
//! let frame = Prepared::<Simd8>::new(&exponent_series()?, 64, 48)?
//!     .with_encoding(Encoding::SRGB.dithered());
//! let mut line = [Rgb565::default(); 64];
//! frame.render_line(24, &mut line)?;
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! # Costs
//!
//! [`SRGB_TABLE`] is a `static` of 4097 `u16`: 8 KiB of read-only data, linked only into a
//! program that renders with an encoding other than the default: each path's row function
//! is instantiated apart for the default, with the encoding a constant there, and
//! [`Render::render_line`](crate::Render::render_line) on an unwrapped frame reaches only
//! that one. An sRGB-dithered frame costs the M0 demo the sRGB table and its code
//! (`docs/performance.md, "Choices measured"`; `.ci/firmware` checks that no demo links the table). Per pixel, a
//! non-default encoding costs per channel a table lookup (sRGB) and two integer
//! multiplications, on top of the default's packet-wide `f32` quantization.

use crate::real::Real;

/// The transfer function applied to linear colour before quantizing.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum Transfer {
    /// The scene's numbers as they are: level = linear value × max (the lesson's rule).
    #[default]
    Linear,
    /// The sRGB curve (IEC 61966-2-1): `12.92·v` up to `v = 0.0031308`, then
    /// `1.055·v^(1/2.4) − 0.055`; what most displays expect, with finer steps in the darks.
    Srgb,
}

/// How linear colour becomes a pixel's levels: a transfer function and optional ordered
/// dithering. See the [module docs](self) for the exact rule.
///
/// Applies to formats that store levels ([`Rgb888`](crate::Rgb888), [`Rgb565`](crate::Rgb565),
/// [`Bgr565`](crate::Bgr565), [`Gray8`](crate::Gray8)); [`LinearRgb`](crate::LinearRgb) and
/// [`HitRecord`](crate::HitRecord) store no levels. The codes a level format encodes are the
/// path's [`LinearRgb`](crate::LinearRgb) output, whatever the encoding.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub struct Encoding {
    /// The transfer function.
    pub transfer: Transfer,
    /// Ordered 4×4 Bayer dithering: each pixel's rounding threshold depends on `(x mod 4,
    /// y mod 4)`, which turns bands of one level into a fine pattern whose average is the
    /// exact colour. Deterministic: a function of position only.
    pub dither: bool,
}

impl Encoding {
    /// Linear, no dithering: the default (the lesson's rule).
    pub const LINEAR: Encoding = Encoding {
        transfer: Transfer::Linear,
        dither: false,
    };
    /// sRGB, no dithering.
    pub const SRGB: Encoding = Encoding {
        transfer: Transfer::Srgb,
        dither: false,
    };

    /// The same transfer function, with ordered dithering on.
    pub const fn dithered(self) -> Encoding {
        Encoding {
            dither: true,
            ..self
        }
    }

    /// Whether this is [`Encoding::LINEAR`], which keeps the packet-wide `f32` route.
    #[inline(always)]
    pub(crate) fn is_default(self) -> bool {
        matches!(self.transfer, Transfer::Linear) && !self.dither
    }
}

/// The 4×4 Bayer matrix, indexed `[y mod 4][x mod 4]`: each of `0..16` once, so every 4×4
/// block of pixels sees every threshold.
pub const BAYER_4X4: [[u8; 4]; 4] = [[0, 8, 2, 10], [12, 4, 14, 6], [3, 11, 1, 9], [15, 7, 13, 5]];

/// Rounding threshold without dithering: ½ in unsigned 0.16.
pub const ROUND_THRESHOLD: u32 = 1 << 15;

/// The dithering threshold of pixel `(x, y)` in unsigned 0.16: `(2·B + 1)/32` with `B` the
/// [`BAYER_4X4`] entry, so thresholds are `1/32, 3/32, …, 31/32` (centred, mean ½).
#[inline(always)]
pub const fn dither_threshold(x: u32, y: u32) -> u32 {
    let b = BAYER_4X4[(y & 3) as usize][(x & 3) as usize] as u32;
    (2 * b + 1) << 11
}

/// Rec. 709 luma weights for red, green and blue in unsigned 0.16, summing to `65536`:
/// `0.2126`, `0.7152`, `0.0722` rounded (`13933`, `46871`, `4732`).
pub const LUMA_WEIGHTS: [u32; 3] = [13_933, 46_871, 4_732];

/// [`LUMA_WEIGHTS`] as `f32` (exact: each is an integer over `2¹⁶`), for the float paths'
/// default [`Gray8`](crate::Gray8) encoding: `clamp(r)·w_r + clamp(g)·w_g + clamp(b)·w_b`,
/// added left to right.
pub const LUMA_WEIGHTS_F32: [f32; 3] = [
    LUMA_WEIGHTS[0] as f32 / 65536.0,
    LUMA_WEIGHTS[1] as f32 / 65536.0,
    LUMA_WEIGHTS[2] as f32 / 65536.0,
];

/// Number of intervals of [`SRGB_TABLE`]: entries are at linear `i/4096`.
pub const SRGB_TABLE_STEPS: usize = 4096;

/// The sRGB curve at linear `i/4096`, `i` in `0..=4096`, in unsigned 1.15 (`32768` is 1.0),
/// rounded to nearest. Computed at compile time in `f64` (Newton's method for `v^(5/12)`,
/// only `+ − × ÷`, so the same bits whatever the target); a test checks every entry against
/// the formula evaluated with `powf`.
pub static SRGB_TABLE: [u16; SRGB_TABLE_STEPS + 1] = srgb_table();

/// `v^(1/2.4)` for `v` in `(0, 1]`: the root `y ≥ 0` of `y¹² = v⁵`, by Newton's method from
/// `y = 1` (from above, so it decreases monotonically to the root).
const fn pow_5_12(v: f64) -> f64 {
    let a = v * v * v * v * v;
    let mut y = 1.0f64;
    let mut i = 0;
    while i < 200 {
        let y2 = y * y;
        let y4 = y2 * y2;
        let y8 = y4 * y4;
        let y11 = y8 * y2 * y;
        let next = (11.0 * y + a / y11) / 12.0;
        if next >= y {
            break;
        }
        y = next;
        i += 1;
    }
    y
}

/// The sRGB encoding of linear `v` in `[0, 1]`, in `f64`.
const fn srgb_f64(v: f64) -> f64 {
    if v <= 0.003_130_8 {
        12.92 * v
    } else {
        1.055 * pow_5_12(v) - 0.055
    }
}

const fn srgb_table() -> [u16; SRGB_TABLE_STEPS + 1] {
    let mut t = [0u16; SRGB_TABLE_STEPS + 1];
    let mut i = 0;
    while i <= SRGB_TABLE_STEPS {
        let s = srgb_f64(i as f64 / SRGB_TABLE_STEPS as f64);
        let s = if s < 0.0 { 0.0 } else { s };
        let s = if s > 1.0 { 1.0 } else { s };
        t[i] = (s * 32768.0 + 0.5) as u16;
        i += 1;
    }
    t
}

/// `clamp(c, 0, 1)`, NaN giving 0: `if 0 < c { c } else { 0 }`, then `if c < 1 { c } else
/// { 1 }`, lane by lane, the same operations at every width.
#[inline(always)]
pub(crate) fn clamp_unit<T: Real>(c: T) -> T {
    let (zero, one) = (T::splat(0.0), T::splat(1.0));
    let c = T::select(zero.lt(c), c, zero);
    T::select(c.lt(one), c, one)
}

/// `clamp(c, 0, 1)·max + ½`, before truncation: the float rule of every level and code. A
/// packet truncates its lanes with `trunc_lanes`, a scalar with `as`; both give
/// `⌊clamp(c, 0, 1)·max + ½⌋`, round to nearest.
#[inline(always)]
pub(crate) fn quantize_lanes<T: Real>(c: T, max: f32) -> T {
    clamp_unit(c) * T::splat(max) + T::splat(0.5)
}

/// The float luma of three channels: `clamp(r)·w_r + clamp(g)·w_g + clamp(b)·w_b` with
/// [`LUMA_WEIGHTS_F32`], added left to right (see [`Gray8`](crate::Gray8)).
#[inline(always)]
pub(crate) fn luma<T: Real>([r, g, b]: [T; 3]) -> T {
    let [wr, wg, wb] = LUMA_WEIGHTS_F32;
    clamp_unit(r) * T::splat(wr) + clamp_unit(g) * T::splat(wg) + clamp_unit(b) * T::splat(wb)
}

/// `⌊clamp(c, 0, 1)·max + ½⌋`: round to the nearest of `max + 1` levels. NaN gives 0.
#[inline(always)]
pub fn quantize(c: f32, max: f32) -> u16 {
    quantize_scaled(c, max) as u16
}

/// [`quantize_lanes`] of one `f32`, truncated: `⌊clamp(c, 0, 1)·max + ½⌋` for an integer
/// `max` in `[1, 2²⁴]`, computed as `min(⌊c·max + ½⌋, max)` with the saturating `as u32`
/// (negative values and NaN give 0, `+∞` gives `u32::MAX`). The same value for every `c`:
/// inside `(0, 1)` the float operations are the same; rounding is monotonic, so `c ≥ 1`
/// gives `c·max + ½ ≥ max + ½` and `c ≤ 0` gives `c·max + ½ ≤ ½`. A single-lane path clamps
/// so, after one float-to-integer conversion, instead of with two float compares and
/// selects: several instructions each on a core without `VSEL`, a call each in soft float.
#[inline(always)]
pub(crate) fn quantize_scaled(c: f32, max: f32) -> u32 {
    ((c * max + 0.5) as u32).min(max as u32)
}

/// The fixed-point twin of [`quantize`]: `⌊clamp(v, 0, 1)·max + ½⌋` for `v` in unsigned
/// 16.16, in integers only.
#[inline(always)]
pub fn quantize_fixed(v: u32, max: u32) -> u16 {
    let v = v.min(1 << 16);
    ((v * max + (1 << 15)) >> 16) as u16
}

/// [`quantize`] per channel to the largest levels `max`: the default encoding of an `f32`
/// colour for every format that stores levels.
#[inline(always)]
pub(crate) fn levels([r, g, b]: [f32; 3], max: [u16; 3]) -> [u16; 3] {
    [
        quantize(r, max[0] as f32),
        quantize(g, max[1] as f32),
        quantize(b, max[2] as f32),
    ]
}

/// [`quantize_fixed`] per channel to the largest levels `max`: the default encoding of a
/// fixed-path colour for every format that stores levels.
#[inline(always)]
pub(crate) fn levels_fixed([r, g, b]: [u32; 3], max: [u16; 3]) -> [u16; 3] {
    [
        quantize_fixed(r, max[0] as u32),
        quantize_fixed(g, max[1] as u32),
        quantize_fixed(b, max[2] as u32),
    ]
}

/// The linear code of an `f32` channel: `⌊clamp(v, 0, 1)·65536 + ½⌋`, NaN gives 0.
#[inline(always)]
pub fn linear_code(v: f32) -> u32 {
    quantize_lanes(v, 65536.0) as u32
}

/// The linear code of a fixed-path channel (unsigned 16.16): `min(v, 65536)`.
#[inline(always)]
pub fn linear_code_fixed(v: u32) -> u32 {
    v.min(1 << 16)
}

/// sRGB-encoded value in `0..=65536` of a linear code in `0..=65536` (larger codes are
/// treated as `65536`): [`SRGB_TABLE`] at `code >> 4`, interpolated with `code & 15`.
#[inline]
pub fn srgb_encode(code: u32) -> u32 {
    let code = code.min(1 << 16);
    let i = (code >> 4) as usize;
    let f = code & 15;
    // `i ≤ SRGB_TABLE_STEPS`; only the last entry has no successor, and there `f` is 0.
    debug_assert!(i < SRGB_TABLE.len() && (f == 0 || i + 1 < SRGB_TABLE.len()));
    let lo = SRGB_TABLE.get(i).copied().unwrap_or(32768) as u32;
    let hi = SRGB_TABLE.get(i + 1).copied().unwrap_or(32768) as u32;
    // In units of 2⁻¹⁹: lo·16 + (hi − lo)·f, the table being non-decreasing; then to 0.16.
    let v = lo * 16 + (hi - lo.min(hi)) * f;
    (v + 4) >> 3
}

/// Luma code of three clamped linear codes, with [`LUMA_WEIGHTS`]: `0..=65536`.
#[inline]
pub fn luma_code([r, g, b]: [u32; 3]) -> u32 {
    let [wr, wg, wb] = LUMA_WEIGHTS;
    let sum = r.min(1 << 16) as u64 * wr as u64
        + g.min(1 << 16) as u64 * wg as u64
        + b.min(1 << 16) as u64 * wb as u64;
    ((sum + (1 << 15)) >> 16) as u32
}

/// Quantizes an encoded value `e` in `0..=65536` to `0..=max` with threshold `t` in
/// `0..65536`: `(e·max + t) >> 16`.
#[inline(always)]
pub fn quantize_code(e: u32, max: u16, t: u32) -> u16 {
    let e = e.min(1 << 16);
    ((e * max as u32 + t) >> 16) as u16
}

/// The levels of a pixel with linear codes `codes` at `(x, y)` under `encoding`, for a format
/// with [`Pixel::LEVELS`](crate::Pixel::LEVELS) `levels` (and [`Pixel::GRAY`](crate::Pixel::GRAY) `gray`): steps 2–4 of the module rule.
#[inline]
pub fn encode_levels(
    codes: [u32; 3],
    levels: [u16; 3],
    gray: bool,
    encoding: Encoding,
    x: u32,
    y: u32,
) -> [u16; 3] {
    let t = if encoding.dither {
        dither_threshold(x, y)
    } else {
        ROUND_THRESHOLD
    };
    let transfer = |c: u32| match encoding.transfer {
        Transfer::Linear => c.min(1 << 16),
        Transfer::Srgb => srgb_encode(c),
    };
    if gray {
        let l = quantize_code(transfer(luma_code(codes)), levels[0], t);
        return [l, l, l];
    }
    let [r, g, b] = codes;
    [
        quantize_code(transfer(r), levels[0], t),
        quantize_code(transfer(g), levels[1], t),
        quantize_code(transfer(b), levels[2], t),
    ]
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;

    /// `quantize_scaled` (clamp after the conversion) against the rule as the wide lanes
    /// compute it (`quantize_lanes`: clamp first, then truncate), for every format's `max`,
    /// on the special values and on every 4099th bit pattern of `f32` (about a million).
    #[test]
    fn quantize_scaled_is_the_rule_for_every_f32() {
        let special = [
            0.0,
            -0.0,
            1.0,
            -1.0,
            f32::MIN_POSITIVE,
            f32::from_bits(1),
            1.0 - f32::EPSILON / 2.0,
            1.0 + f32::EPSILON,
            f32::MAX,
            f32::MIN,
            f32::INFINITY,
            f32::NEG_INFINITY,
            f32::NAN,
            -f32::NAN,
        ];
        let sweep = (0..=u32::MAX / 4099).map(|i| f32::from_bits(i * 4099));
        for max in [1.0, 31.0, 63.0, 255.0, 65535.0, 65536.0] {
            for c in special.into_iter().chain(sweep.clone()) {
                let rule = quantize_lanes(c, max) as u32;
                assert_eq!(
                    quantize_scaled(c, max),
                    rule,
                    "c = {c:e} ({:#x}), max = {max}",
                    c.to_bits()
                );
            }
        }
    }

    #[test]
    fn srgb_table_matches_the_formula() {
        for (i, &got) in SRGB_TABLE.iter().enumerate() {
            let v = i as f64 / 4096.0;
            let s = if v <= 0.003_130_8 {
                12.92 * v
            } else {
                1.055 * v.powf(1.0 / 2.4) - 0.055
            };
            let want = (s.clamp(0.0, 1.0) * 32768.0 + 0.5) as u16;
            assert_eq!(got, want, "entry {i}");
        }
        assert_eq!(SRGB_TABLE[0], 0);
        assert_eq!(SRGB_TABLE[4096], 32768);
        assert!(SRGB_TABLE.windows(2).all(|w| w[0] <= w[1]));
    }

    #[test]
    fn srgb_encode_is_within_a_tenth_of_an_8_bit_level() {
        for code in 0..=65536u32 {
            let v = code as f64 / 65536.0;
            let s = if v <= 0.003_130_8 {
                12.92 * v
            } else {
                1.055 * v.powf(1.0 / 2.4) - 0.055
            };
            let got = srgb_encode(code) as f64 / 65536.0;
            assert!((got - s).abs() * 255.0 < 0.01, "code {code}: {got} vs {s}");
        }
        assert_eq!(srgb_encode(0), 0);
        assert_eq!(srgb_encode(65536), 65536);
        assert_eq!(srgb_encode(u32::MAX), 65536);
    }

    #[test]
    fn dither_thresholds_cover_each_sixteenth_once() {
        let mut seen = [false; 16];
        for y in 0..4 {
            for x in 0..4 {
                let t = dither_threshold(x, y);
                assert_eq!(t % 4096, 2048);
                seen[(t / 4096) as usize] = true;
                assert_eq!(dither_threshold(x + 4, y + 8), t);
            }
        }
        assert!(seen.iter().all(|s| *s));
    }

    #[test]
    fn dithering_averages_to_the_value_and_keeps_black_and_white() {
        for e in (0..=65536u32).step_by(257) {
            let sum: u32 = (0..16)
                .map(|i| quantize_code(e, 31, dither_threshold(i % 4, i / 4)) as u32)
                .sum();
            let mean = sum as f64 / 16.0;
            assert!((mean - e as f64 * 31.0 / 65536.0).abs() <= 1.0 / 32.0 + 1e-9);
        }
        for i in 0..16 {
            assert_eq!(quantize_code(0, 31, dither_threshold(i % 4, i / 4)), 0);
            assert_eq!(quantize_code(65536, 31, dither_threshold(i % 4, i / 4)), 31);
        }
    }

    #[test]
    fn luma_weights_sum_to_one_and_match_rec_709() {
        assert_eq!(LUMA_WEIGHTS.iter().sum::<u32>(), 65536);
        for (w, want) in LUMA_WEIGHTS.iter().zip([0.2126, 0.7152, 0.0722]) {
            assert!((*w as f64 / 65536.0 - want).abs() < 1e-5);
        }
        assert_eq!(luma_code([65536; 3]), 65536);
        assert_eq!(luma_code([u32::MAX; 3]), 65536);
        assert_eq!(luma_code([0; 3]), 0);
    }

    #[test]
    fn linear_codes_agree_between_f32_and_fixed() {
        for raw in 0..=65536u32 {
            assert_eq!(linear_code(raw as f32 / 65536.0), linear_code_fixed(raw));
        }
        assert_eq!(linear_code(f32::NAN), 0);
        assert_eq!(linear_code(-1.0), 0);
        assert_eq!(linear_code(7.0), 65536);
    }

    #[test]
    fn without_dithering_linear_codes_round_like_quantize() {
        // The integer route, with the linear transfer, rounds like the default route.
        for raw in (0..=65536u32).step_by(13) {
            let v = raw as f32 / 65536.0;
            let got = encode_levels([raw; 3], [31, 63, 255], false, Encoding::LINEAR, 0, 0);
            assert_eq!(
                got,
                [quantize(v, 31.0), quantize(v, 63.0), quantize(v, 255.0)]
            );
        }
    }
}
