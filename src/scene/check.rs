//! The field-level checks every item runs as it enters a scene: finite, in range, of
//! non-zero length.
//!
//! Each check returns the first problem of one field as a [`SceneError`] naming the item and
//! the field, so the items' own checks read as one line per field and every refusal says
//! where it is. The tests on the numbers are integer comparisons of their bits ([`Check`]
//! says why).

use super::error::{Item, Problem, SceneError};
use super::limits::{MAX_COORDINATE, MAX_VALUE};
use crate::pixel::LinearRgb;
use crate::vec3::Vec3;

/// Field-level checks, each returning the first problem found.
///
/// The comparisons are on the numbers' IEEE 754 bits: a finite `f32` has an exponent field
/// below all ones, and finite non-negative values order as their bits do, so each test is
/// one integer comparison. The results are those of the float comparisons (`-0.0` counts
/// as zero); on a core without an FPU each would otherwise be a call into the soft-float
/// routines.
pub(super) struct Check {
    pub(super) item: Item,
}

/// `|x|`'s bits: the sign cleared.
fn magnitude(x: f32) -> u32 {
    x.to_bits() & !(1 << 31)
}

/// Whether `x` is finite: its exponent field is not all ones.
fn finite_bits(x: f32) -> bool {
    magnitude(x) < f32::INFINITY.to_bits()
}

/// Whether `x < 0.0`: the sign set and the magnitude not zero (`-0.0` is zero).
fn below_zero(x: f32) -> bool {
    x.to_bits() > 1 << 31
}

/// Whether `x ≤ 0.0` for a finite `x`: zero of either sign, or the sign set.
fn not_positive(x: f32) -> bool {
    x.to_bits() as i32 <= 0
}

/// Whether the finite `x` is above the finite, non-negative `max`.
fn above(x: f32, max: f32) -> bool {
    !below_zero(x) && magnitude(x) > max.to_bits()
}

impl Check {
    pub(super) fn err(&self, field: &'static str, problem: Problem) -> SceneError {
        SceneError::Invalid {
            item: self.item,
            field,
            problem,
        }
    }
    pub(super) fn finite(&self, field: &'static str, v: &[f32]) -> Result<(), SceneError> {
        if v.iter().all(|&x| finite_bits(x)) {
            Ok(())
        } else {
            Err(self.err(field, Problem::NotFinite))
        }
    }
    /// Finite, `0 ≤ v ≤ max` for every component.
    pub(super) fn non_negative(
        &self,
        field: &'static str,
        v: &[f32],
        max: f32,
    ) -> Result<(), SceneError> {
        self.finite(field, v)?;
        if v.iter().any(|&x| below_zero(x)) {
            return Err(self.err(field, Problem::Negative));
        }
        if v.iter().any(|&x| above(x, max)) {
            return Err(self.err(field, Problem::TooLarge));
        }
        Ok(())
    }
    /// Finite, `0 < v ≤ max`.
    pub(super) fn positive(&self, field: &'static str, v: f32, max: f32) -> Result<(), SceneError> {
        self.finite(field, &[v])?;
        if not_positive(v) {
            return Err(self.err(field, Problem::NotPositive));
        }
        if above(v, max) {
            return Err(self.err(field, Problem::TooLarge));
        }
        Ok(())
    }
    pub(super) fn point(&self, field: &'static str, p: Vec3) -> Result<(), SceneError> {
        self.finite(field, &[p.x, p.y, p.z])?;
        if [p.x, p.y, p.z]
            .iter()
            .any(|&x| magnitude(x) > MAX_COORDINATE.to_bits())
        {
            return Err(self.err(field, Problem::TooLarge));
        }
        Ok(())
    }
    pub(super) fn direction(&self, field: &'static str, d: Vec3) -> Result<Vec3, SceneError> {
        self.finite(field, &[d.x, d.y, d.z])?;
        d.normalized()
            .ok_or_else(|| self.err(field, Problem::ZeroLength))
    }
    pub(super) fn color(&self, field: &'static str, c: LinearRgb) -> Result<(), SceneError> {
        self.non_negative(field, &[c.r, c.g, c.b], MAX_VALUE)
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::{above, below_zero, finite_bits, not_positive};
    use crate::scene::{MAX_COORDINATE, MAX_SHININESS};

    /// The checks' bit tests against the float comparisons they stand for, on the edge cases
    /// (zeros, subnormals, the limits and their neighbours, infinities, NaNs of either sign)
    /// and on 2²⁰ bit patterns spread over every exponent.
    #[test]
    fn bit_tests_are_the_float_comparisons() {
        let limits = [
            0.0,
            f32::MIN_POSITIVE,
            1.0,
            MAX_COORDINATE,
            MAX_SHININESS,
            f32::MAX,
        ];
        let mut values = std::vec![
            0.0,
            -0.0,
            f32::from_bits(1),
            -f32::from_bits(1),
            f32::INFINITY,
            f32::NEG_INFINITY,
            f32::NAN,
            -f32::NAN,
            f32::MAX,
            f32::MIN,
        ];
        for m in limits {
            for v in [m, -m] {
                values.extend([v, f32::from_bits(v.to_bits() + 1)]);
                if v.to_bits() & !(1 << 31) != 0 {
                    values.push(f32::from_bits(v.to_bits() - 1));
                }
            }
        }
        values.extend((0..1u32 << 20).map(|k| f32::from_bits(k.wrapping_mul(0x9e37_79b9))));
        for x in values {
            assert_eq!(
                finite_bits(x),
                x.is_finite(),
                "finite {x:e} ({:#x})",
                x.to_bits()
            );
            if !x.is_finite() {
                continue;
            }
            assert_eq!(
                below_zero(x),
                x < 0.0,
                "below zero {x:e} ({:#x})",
                x.to_bits()
            );
            assert_eq!(
                not_positive(x),
                x <= 0.0,
                "not positive {x:e} ({:#x})",
                x.to_bits()
            );
            for max in limits {
                assert_eq!(above(x, max), x > max, "{x:e} above {max:e}");
            }
        }
    }
}
