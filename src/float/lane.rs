//! The lane trait the float kernel is written in: [`Real`] (the numbers every formula uses)
//! plus the operations only lanes have, implemented for `f32` (one pixel), `wide::f32x4`
//! and `wide::f32x8` (four or eight consecutive pixels of a row).
//!
//! The scalar and SIMD paths are bit-identical because they run *the same kernel code* at
//! different widths. That only holds if every rounding operation has the same IEEE-754 result
//! in every implementation, so [`Real`] and this trait offer only operations whose results
//! are exactly specified:
//!
//! | operation | scalar `f32` | `wide` lanes | why it is identical |
//! |---|---|---|---|
//! | `+ - * /` | IEEE | IEEE (`addps`, `divps`, …) | correctly rounded both ways |
//! | `sqrt` ([`Real`]) | `libm::sqrtf` | `wide` `sqrt` (`sqrtps`) | both correctly rounded |
//! | `min`, `max` ([`Real`]) | compare + select | compare + select | defined by the same select, NaN and signed zeros included |
//! | [`Lane::split_exponent`], [`Lane::pow2i`] | bit manipulation | integer lane ops | exact: no rounding at all |
//!
//! What is *not* here, on purpose: `mul_add` (fuses only with `+fma`, so it changes bits
//! between builds), `recip`/`recip_sqrt` (≈12-bit approximations on x86), and any
//! transcendental from `wide` or `micromath` (their algorithms differ from any scalar
//! one). The one transcendental the kernel needs, the specular `pow`, is built from these
//! primitives in `math`, once, for every width.

use crate::real::Real;
use wide::{f32x4, f32x8, i32x4, i32x8};

/// A vector of `LANES` `f32` values processed together: one pixel per lane.
///
/// Implemented for `f32`, [`wide::f32x4`] and [`wide::f32x8`]. Every method must give, lane
/// for lane, the bits the `f32` implementation gives; the tests in `tests/paths_agree.rs`
/// check that on whole frames.
pub trait Lane: Real {
    /// How many pixels one value holds.
    const LANES: usize;

    /// Lane `i` holds `start + i` (exact for the pixel indices a frame can have).
    fn ramp(start: f32) -> Self;
    /// The lanes in order, padded with zeros to 8 (the widest lane type).
    fn to_lanes(self) -> [f32; 8];
    /// Each lane truncated toward zero to an integer, padded with zeros to 8. Lanes must hold
    /// values in `i32` range (the encode step passes `[0.5, 65536.5]`).
    fn trunc_lanes(self) -> [i32; 8];
    /// Lane `i`'s value (`i` taken modulo the lane count).
    #[inline(always)]
    fn lane(self, i: usize) -> f32 {
        self.to_lanes()[i % Self::LANES]
    }
    /// Lane `i` of the mask is bit `i` of the result.
    fn bitmask(mask: Self::Mask) -> u32;
    /// Splits a positive, normal `self` into `(m, e)` with `self = m · 2^e`, `m` in `[1, 2)`,
    /// `e` an integer held as `f32`. Exact. Lanes that are zero, negative, subnormal or not
    /// finite give unspecified (but finite, deterministic) values; callers mask them.
    fn split_exponent(self) -> (Self, Self);
    /// `2^k` for integer-valued `k` in `[-126, 127]`. Exact. Other lanes: unspecified but
    /// deterministic.
    fn pow2i(k: Self) -> Self;
}

const EXP_BIAS: i32 = 127;
const MANTISSA_MASK: u32 = 0x007f_ffff;
const ONE_BITS: u32 = 0x3f80_0000;

impl Lane for f32 {
    const LANES: usize = 1;

    #[inline(always)]
    fn ramp(start: f32) -> Self {
        start
    }
    #[inline(always)]
    fn to_lanes(self) -> [f32; 8] {
        [self, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0]
    }
    #[inline(always)]
    fn trunc_lanes(self) -> [i32; 8] {
        [self as i32, 0, 0, 0, 0, 0, 0, 0]
    }
    #[inline(always)]
    fn bitmask(mask: bool) -> u32 {
        mask as u32
    }
    #[inline(always)]
    fn split_exponent(self) -> (Self, Self) {
        let bits = self.to_bits();
        let e = ((bits >> 23) & 0xff) as i32 - EXP_BIAS;
        let m = f32::from_bits((bits & MANTISSA_MASK) | ONE_BITS);
        (m, e as f32)
    }
    #[inline(always)]
    fn pow2i(k: Self) -> Self {
        // `as` saturates, so any input gives a defined bit pattern.
        let biased = (k as i32).wrapping_add(EXP_BIAS) & 0xff;
        f32::from_bits((biased as u32) << 23)
    }
}

macro_rules! wide_lane {
    ($t:ty, $i:ty, $n:expr, $from_int:ident) => {
        impl Lane for $t {
            const LANES: usize = $n;

            #[inline(always)]
            fn ramp(start: f32) -> Self {
                // `start + i` is exact for pixel indices (integers + ½ far below 2^23), so
                // one lane-wise add gives the scalar path's values.
                let mut offsets = [0.0f32; $n];
                for (i, o) in offsets.iter_mut().enumerate() {
                    *o = i as f32;
                }
                <$t>::splat(start) + <$t>::new(offsets)
            }
            #[inline(always)]
            fn to_lanes(self) -> [f32; 8] {
                let mut out = [0.0f32; 8];
                for (o, v) in out.iter_mut().zip(self.to_array()) {
                    *o = v;
                }
                out
            }
            #[inline(always)]
            fn trunc_lanes(self) -> [i32; 8] {
                let mut out = [0i32; 8];
                for (o, v) in out.iter_mut().zip(self.trunc_int().to_array()) {
                    *o = v;
                }
                out
            }
            #[inline(always)]
            fn bitmask(mask: Self) -> u32 {
                mask.to_bitmask()
            }
            #[inline(always)]
            fn split_exponent(self) -> (Self, Self) {
                let bits: $i = wide::bytemuck::cast(self);
                let e = ((bits >> 23) & <$i>::splat(0xff)) - <$i>::splat(EXP_BIAS);
                let m_bits =
                    (bits & <$i>::splat(MANTISSA_MASK as i32)) | <$i>::splat(ONE_BITS as i32);
                (wide::bytemuck::cast(m_bits), <$t>::$from_int(e))
            }
            #[inline(always)]
            fn pow2i(k: Self) -> Self {
                let biased = (k.trunc_int() + <$i>::splat(EXP_BIAS)) & <$i>::splat(0xff);
                wide::bytemuck::cast(biased << 23)
            }
        }
    };
}

wide_lane!(f32x4, i32x4, 4, from_i32x4);
wide_lane!(f32x8, i32x8, 8, from_i32x8);
#[cfg(test)]
mod tests {
    use super::*;

    fn check_exact<L: Lane>() {
        for &x in &[
            1.0f32,
            1.5,
            0.75,
            3.0e-20,
            7.5e30,
            0.999_999_94,
            1.000_000_1,
        ] {
            let (m, e) = L::splat(x).split_exponent();
            let (ms, es) = x.split_exponent();
            assert_eq!(m.lane(0).to_bits(), ms.to_bits(), "mantissa of {x}");
            assert_eq!(e.lane(L::LANES - 1), es, "exponent of {x}");
            assert_eq!(ms * f32::powi(2.0, es as i32), x);
        }
        for k in -126..=127 {
            let p = L::pow2i(L::splat(k as f32)).lane(0);
            assert_eq!(p, f32::powi(2.0, k), "2^{k}");
        }
        let r = L::ramp(10.5);
        for i in 0..L::LANES {
            assert_eq!(r.lane(i), 10.5 + i as f32);
        }
        // min/max share one definition, NaN included.
        let nan = L::splat(f32::NAN);
        assert!(L::splat(1.0).max(nan).lane(0) == 1.0);
        assert!(nan.max(L::splat(1.0)).lane(0).is_nan());
    }

    #[test]
    fn exact_helpers_agree_at_every_width() {
        check_exact::<f32>();
        check_exact::<f32x4>();
        check_exact::<f32x8>();
    }
}
