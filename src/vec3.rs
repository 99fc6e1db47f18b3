//! `Vec3<T>`: one small vector type for every width.
//!
//! The scene is described with `Vec3<f32>`; the float kernel computes with `Vec3<L>` where
//! `L` is a lane type (`f32`, `f32x4`, `f32x8`), and the law tests with `Vec3<f64>`: every
//! number type is a [`Real`]. The operations are written once, so a dot
//! product is summed in the same order, `(x·x' + y·y') + z·z'`, at every width — one of the
//! reasons the scalar and SIMD paths agree bit for bit.

use crate::real::Real;
use core::ops::{Add, Mul, Neg, Sub};

/// `2^64`: multiplying by it is exact for every vector `normalized` lifts.
const TWO_POW_64: f32 = 18_446_744_073_709_551_616.0;

/// A 3-component vector: a point, a direction or an offset in scene units.
///
/// ```
/// use shadeline::Vec3;
/// let a = Vec3::new(1.0, 2.0, 2.0);
/// assert_eq!(a.dot(a), 9.0);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct Vec3<T = f32> {
    /// The x component (right in a default camera).
    pub x: T,
    /// The y component (up in a default camera).
    pub y: T,
    /// The z component (toward the viewer in a default camera).
    pub z: T,
}

impl<T> Vec3<T> {
    /// A vector from its three components.
    #[inline(always)]
    pub const fn new(x: T, y: T, z: T) -> Self {
        Vec3 { x, y, z }
    }
}

impl<T: Real> Vec3<T> {
    /// All three components set to lanes of `v`.
    #[inline(always)]
    pub fn splat(v: Vec3<f32>) -> Self {
        Vec3::new(T::splat(v.x), T::splat(v.y), T::splat(v.z))
    }
    /// The dot product, summed as `(x·x' + y·y') + z·z'`.
    #[cfg_attr(not(shadeline_short_mul), inline(always))]
    #[cfg_attr(shadeline_short_mul, inline(never))]
    pub fn dot(self, o: Self) -> T {
        self.x * o.x + self.y * o.y + self.z * o.z
    }
    /// Each component multiplied by `s`.
    #[cfg_attr(not(shadeline_short_mul), inline(always))]
    #[cfg_attr(shadeline_short_mul, inline(never))]
    pub fn scale(self, s: T) -> Self {
        Vec3::new(self.x * s, self.y * s, self.z * s)
    }
    /// The cross product `self × o` (right-handed).
    #[cfg_attr(not(shadeline_short_mul), inline(always))]
    #[cfg_attr(shadeline_short_mul, inline(never))]
    pub fn cross(self, o: Self) -> Self {
        Vec3::new(
            self.y * o.z - self.z * o.y,
            self.z * o.x - self.x * o.z,
            self.x * o.y - self.y * o.x,
        )
    }
    /// Per-lane choice between two vectors.
    #[inline(always)]
    pub fn select(mask: T::Mask, a: Self, b: Self) -> Self {
        Vec3::new(
            T::select(mask, a.x, b.x),
            T::select(mask, a.y, b.y),
            T::select(mask, a.z, b.z),
        )
    }
}

impl Vec3<f32> {
    /// The largest absolute component (the ∞-norm); NaN if a component is NaN.
    ///
    /// Compared as integers: with the sign bit cleared, the bits of non-negative `f32`s (NaN
    /// above infinity) are ordered as their values. Three masks and two integer
    /// comparisons, where `f32::max` is a soft-float call on cores without an FPU.
    pub fn max_abs(self) -> f32 {
        let magnitude = |c: f32| c.to_bits() & 0x7fff_ffff;
        f32::from_bits(
            magnitude(self.x)
                .max(magnitude(self.y))
                .max(magnitude(self.z)),
        )
    }
    /// True if every component is finite.
    pub fn is_finite(self) -> bool {
        self.x.is_finite() && self.y.is_finite() && self.z.is_finite()
    }
    /// The unit vector along `self`, or `None` for a zero or non-finite vector.
    ///
    /// The vector is first divided by its largest component, so the squared length neither
    /// overflows for huge inputs nor underflows for tiny ones. A vector whose largest
    /// component is below `1e-30` (subnormals included, where `1/m` would overflow to `inf`
    /// and give `0·inf = NaN`) is first scaled by `2^64`, which is exact.
    pub fn normalized(self) -> Option<Self> {
        let m = self.max_abs();
        if !(m > 0.0 && m.is_finite()) {
            return None;
        }
        let (v, m) = if m < 1.0e-30 {
            let lifted = self.scale(TWO_POW_64);
            (lifted, lifted.max_abs())
        } else {
            (self, m)
        };
        let s = v.scale(1.0 / m);
        let len = libm::sqrtf(s.dot(s));
        Some(s.scale(1.0 / len))
    }
}

impl<T: Real> Add for Vec3<T> {
    type Output = Self;
    #[cfg_attr(not(shadeline_short_mul), inline(always))]
    #[cfg_attr(shadeline_short_mul, inline(never))]
    fn add(self, o: Self) -> Self {
        Vec3::new(self.x + o.x, self.y + o.y, self.z + o.z)
    }
}

impl<T: Real> Sub for Vec3<T> {
    type Output = Self;
    #[cfg_attr(not(shadeline_short_mul), inline(always))]
    fn sub(self, o: Self) -> Self {
        Vec3::new(self.x - o.x, self.y - o.y, self.z - o.z)
    }
}

impl<T: Real> Neg for Vec3<T> {
    type Output = Self;
    #[inline(always)]
    fn neg(self) -> Self {
        Vec3::new(-self.x, -self.y, -self.z)
    }
}

impl<T: Real> Mul<T> for Vec3<T> {
    type Output = Self;
    #[inline(always)]
    fn mul(self, s: T) -> Self {
        self.scale(s)
    }
}

impl From<[f32; 3]> for Vec3<f32> {
    fn from(a: [f32; 3]) -> Self {
        Vec3::new(a[0], a[1], a[2])
    }
}

#[cfg(test)]
mod tests {
    use super::Vec3;

    #[test]
    fn max_abs_is_the_largest_magnitude() {
        let values = [
            0.0,
            -0.0,
            1.0e-45,
            -1.0e-40,
            0.5,
            -0.75,
            3.0,
            -1.0e30,
            f32::MAX,
            f32::INFINITY,
            f32::NEG_INFINITY,
        ];
        for &x in &values {
            for &y in &values {
                for &z in &values {
                    let expected = x.abs().max(y.abs()).max(z.abs());
                    let got = Vec3::new(x, y, z).max_abs();
                    assert_eq!(got.to_bits(), expected.to_bits(), "{x} {y} {z}");
                }
            }
        }
        assert!(Vec3::new(1.0, f32::NAN, 2.0).max_abs().is_nan());
    }
}
