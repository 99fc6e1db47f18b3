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

use crate::encoding::{quantize_lanes, quantize_scaled};
use crate::real::{bool_mask_methods, Real};
use core::marker::PhantomData;
use core::ops::{Add, Div, Mul, Neg, Sub};
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
    /// Each lane's level `⌊clamp(c, 0, 1)·max + ½⌋` (the rule of
    /// [`quantize`](crate::encoding::quantize)), padded with zeros to 8, for an integer `max`
    /// in `[1, 2²⁴]`.
    #[inline(always)]
    fn quantize_lanes(self, max: f32) -> [i32; 8] {
        quantize_lanes(self, max).trunc_lanes()
    }
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
    fn quantize_lanes(self, max: f32) -> [i32; 8] {
        [quantize_scaled(self, max) as i32, 0, 0, 0, 0, 0, 0, 0]
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

/// A correctly rounded `f32` square root (IEEE 754 `squareRoot`, round to nearest even):
/// what the scalar path [`ScalarWith<Q>`](super::ScalarWith) takes its square roots from.
///
/// The float kernel's other operations are single instructions on an FPU, but `core` has no
/// `f32::sqrt` on stable Rust and the crate forbids `unsafe`, so the default scalar path
/// ([`Scalar`](super::Scalar)) calls [`libm::sqrtf`], a routine of about fifty integer
/// instructions on a Cortex-M4F. A firmware on a core with a square-root instruction (the
/// M4F's `VSQRT.F32`, RISC-V's `fsqrt.s`) implements this trait with it (one line of inline
/// assembly in the firmware) and renders with `Prepared<ScalarWith<ItsSqrt>>`.
///
/// The implementation must return the correctly rounded square root for every input,
/// `−0.0` for `−0.0` and NaN for negative inputs: any IEEE 754 hardware square root does. The
/// frames are then bit-identical to [`Scalar`](super::Scalar)'s and the SIMD paths'; an
/// approximation would break that, and the one-level agreement with the `f64` reference.
pub trait SquareRoot {
    /// The correctly rounded square root of `x`.
    fn sqrt(x: f32) -> f32;
}

/// [`libm::sqrtf`]: the square root of [`Scalar`](super::Scalar).
#[derive(Clone, Copy, Debug, Default)]
pub struct Libm;

impl SquareRoot for Libm {
    #[inline(always)]
    fn sqrt(x: f32) -> f32 {
        libm::sqrtf(x)
    }
}

/// The lane of [`ScalarWith<Q>`](super::ScalarWith): one `f32` whose square root is `Q`'s.
/// Every other operation is `f32`'s.
#[doc(hidden)]
#[repr(transparent)]
pub struct Rooted<Q>(f32, PhantomData<Q>);

impl<Q> Rooted<Q> {
    #[inline(always)]
    const fn new(v: f32) -> Self {
        Rooted(v, PhantomData)
    }
}

impl<Q> Clone for Rooted<Q> {
    #[inline(always)]
    fn clone(&self) -> Self {
        *self
    }
}
impl<Q> Copy for Rooted<Q> {}

macro_rules! rooted_op {
    ($tr:ident, $f:ident, $op:tt) => {
        impl<Q> $tr for Rooted<Q> {
            type Output = Self;
            #[inline(always)]
            fn $f(self, rhs: Self) -> Self {
                Rooted::new(self.0 $op rhs.0)
            }
        }
    };
}
rooted_op!(Add, add, +);
rooted_op!(Sub, sub, -);
rooted_op!(Mul, mul, *);
rooted_op!(Div, div, /);

impl<Q> Neg for Rooted<Q> {
    type Output = Self;
    #[inline(always)]
    fn neg(self) -> Self {
        Rooted::new(-self.0)
    }
}

impl<Q: SquareRoot> Real for Rooted<Q> {
    type Mask = bool;
    #[inline(always)]
    fn splat(v: f32) -> Self {
        Rooted::new(v)
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        Rooted::new(Q::sqrt(self.0))
    }
    #[inline(always)]
    fn lt(self, rhs: Self) -> bool {
        self.0 < rhs.0
    }
    #[inline(always)]
    fn le(self, rhs: Self) -> bool {
        self.0 <= rhs.0
    }
    bool_mask_methods!();
}

impl<Q: SquareRoot> Lane for Rooted<Q> {
    const LANES: usize = 1;

    #[inline(always)]
    fn ramp(start: f32) -> Self {
        Rooted::new(start)
    }
    #[inline(always)]
    fn to_lanes(self) -> [f32; 8] {
        self.0.to_lanes()
    }
    #[inline(always)]
    fn trunc_lanes(self) -> [i32; 8] {
        self.0.trunc_lanes()
    }
    #[inline(always)]
    fn quantize_lanes(self, max: f32) -> [i32; 8] {
        self.0.quantize_lanes(max)
    }
    #[inline(always)]
    fn bitmask(mask: bool) -> u32 {
        mask as u32
    }
    #[inline(always)]
    fn split_exponent(self) -> (Self, Self) {
        let (m, e) = self.0.split_exponent();
        (Rooted::new(m), Rooted::new(e))
    }
    #[inline(always)]
    fn pow2i(k: Self) -> Self {
        Rooted::new(f32::pow2i(k.0))
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
        check_exact::<Rooted<Libm>>();
    }
}
