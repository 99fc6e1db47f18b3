//! The numbers the formulas are written in: one trait, [`Real`], implemented for `f32` and
//! `f64` and for the float kernel's SIMD lanes (`wide::f32x4`, `wide::f32x8`).
//!
//! [`Vec3`](crate::Vec3) and the reflection models ([`crate::brdf`]) are written once over it,
//! so the scene, the prepare step, the kernel at every lane width and the `f64` law tests use
//! the same spelling of every formula. The float kernel adds the operations only lanes have
//! (width, ramps, bit masks, exact exponent tricks) in its own trait, `float::Lane`, on top.
//!
//! Every operation here is exactly specified by IEEE 754 (`+ − × ÷`, a correctly rounded
//! square root, comparisons, selects), so an `f32` lane and a SIMD lane give the same bits:
//! that is what keeps the scalar and SIMD paths bit-identical. `min` and `max` are defined by
//! one compare and select at every width, NaN and signed zeros included. What is not here, on
//! purpose: `mul_add` (it fuses only with `+fma`, so it would change bits between builds) and
//! approximate reciprocals.
//!
//! `core` has no `f32::sqrt` on stable, and `micromath`'s `sqrt` is an approximation (percent-level
//! relative error), which would break the one-level agreement with the `f64`
//! reference; `libm::sqrtf` and `libm::sqrt` are correctly rounded, so the scalars use them.

use core::ops::{Add, Div, Mul, Neg, Sub};

/// A real number, or a vector of `f32` lanes processed together: the numeric vocabulary of
/// [`Vec3`](crate::Vec3) and [`crate::brdf`].
///
/// Every method must give, lane for lane, the bits the `f32` implementation gives (for the
/// lane types; `tests/paths_agree.rs` checks that on whole frames).
pub trait Real:
    Copy
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
{
    /// A per-lane boolean: `bool` for scalars, an all-ones/all-zeros bit mask for SIMD.
    type Mask: Copy;

    /// Every lane set to `v` (exact for `f64`).
    fn splat(v: f32) -> Self;
    /// π in this type's precision.
    #[inline(always)]
    fn pi() -> Self {
        Self::splat(core::f32::consts::PI)
    }
    /// Correctly rounded square root.
    fn sqrt(self) -> Self;
    /// Per-lane `self < rhs` (false if either is NaN).
    fn lt(self, rhs: Self) -> Self::Mask;
    /// Per-lane `self <= rhs` (false if either is NaN).
    fn le(self, rhs: Self) -> Self::Mask;
    /// Per-lane choice: `if_true` where `mask` is set, else `if_false`.
    fn select(mask: Self::Mask, if_true: Self, if_false: Self) -> Self;
    /// Lane-wise AND of two masks.
    fn and(a: Self::Mask, b: Self::Mask) -> Self::Mask;
    /// Lane-wise OR of two masks.
    fn or(a: Self::Mask, b: Self::Mask) -> Self::Mask;
    /// Lane-wise AND-NOT: set where `a` is set and `b` is not.
    fn and_not(a: Self::Mask, b: Self::Mask) -> Self::Mask;
    /// True if any lane of `mask` is set.
    fn any(mask: Self::Mask) -> bool;

    /// Per-lane minimum, defined as `if rhs < self { rhs } else { self }` at every width.
    #[inline(always)]
    fn min(self, rhs: Self) -> Self {
        Self::select(rhs.lt(self), rhs, self)
    }
    /// Per-lane maximum, defined as `if self < rhs { rhs } else { self }` at every width.
    #[inline(always)]
    fn max(self, rhs: Self) -> Self {
        Self::select(self.lt(rhs), rhs, self)
    }
}

macro_rules! scalar_real {
    ($t:ty, $sqrt:path, $pi:expr) => {
        impl Real for $t {
            type Mask = bool;
            #[inline(always)]
            fn splat(v: f32) -> Self {
                v as $t
            }
            #[inline(always)]
            fn pi() -> Self {
                $pi
            }
            #[inline(always)]
            fn sqrt(self) -> Self {
                $sqrt(self)
            }
            #[inline(always)]
            fn lt(self, rhs: Self) -> bool {
                self < rhs
            }
            #[inline(always)]
            fn le(self, rhs: Self) -> bool {
                self <= rhs
            }
            bool_mask_methods!();
        }
    };
}

/// The methods of [`Real`] for a one-lane type whose mask is `bool`: `select` is an `if`,
/// the mask operations are `bool`'s. Shared by `f32`, `f64` and the scalar lane of the
/// float kernel (`float::lane::Rooted`).
macro_rules! bool_mask_methods {
    () => {
        #[inline(always)]
        fn select(mask: bool, if_true: Self, if_false: Self) -> Self {
            if mask {
                if_true
            } else {
                if_false
            }
        }
        #[inline(always)]
        fn and(a: bool, b: bool) -> bool {
            a & b
        }
        #[inline(always)]
        fn or(a: bool, b: bool) -> bool {
            a | b
        }
        #[inline(always)]
        fn and_not(a: bool, b: bool) -> bool {
            a & !b
        }
        #[inline(always)]
        fn any(mask: bool) -> bool {
            mask
        }
    };
}
pub(crate) use bool_mask_methods;

scalar_real!(f32, libm::sqrtf, core::f32::consts::PI);
scalar_real!(f64, libm::sqrt, core::f64::consts::PI);

macro_rules! wide_real {
    ($t:ty) => {
        impl Real for $t {
            type Mask = $t;
            #[inline(always)]
            fn splat(v: f32) -> Self {
                <$t>::splat(v)
            }
            #[inline(always)]
            fn sqrt(self) -> Self {
                <$t>::sqrt(self)
            }
            #[inline(always)]
            fn lt(self, rhs: Self) -> Self {
                self.simd_lt(rhs)
            }
            #[inline(always)]
            fn le(self, rhs: Self) -> Self {
                self.simd_le(rhs)
            }
            #[inline(always)]
            fn select(mask: Self, if_true: Self, if_false: Self) -> Self {
                mask.select(if_true, if_false)
            }
            #[inline(always)]
            fn and(a: Self, b: Self) -> Self {
                a & b
            }
            #[inline(always)]
            fn or(a: Self, b: Self) -> Self {
                a | b
            }
            #[inline(always)]
            fn and_not(a: Self, b: Self) -> Self {
                a & !b
            }
            #[inline(always)]
            fn any(mask: Self) -> bool {
                mask.any()
            }
        }
    };
}

wide_real!(wide::f32x4);
wide_real!(wide::f32x8);
