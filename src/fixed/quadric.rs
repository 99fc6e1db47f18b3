//! The narrow kernel's quadrics: a quadratic in a pixel's offsets from the centre of the
//! screen with exact integer coefficients, and its state along a row.
//!
//! The prepare makes them (`E′` per sphere, `G` per sphere and light, see
//! [`NarrowSphere`](super::prepare::NarrowSphere)); the narrow kernel steps them along a run
//! with two additions a pixel, and without the full-width kernel `outline` finds each row's
//! span from `E′`. Integer forward differences are exact, so a pixel's value does not depend
//! on where its run begins, and it is the same bits on every target.

use super::mul::mul_wide;

/// A quadratic in a pixel's half-pixel offsets `dx = 2x + 1 − w`, `dy = h − 2y − 1` from the
/// centre of the screen: `q = c₀₀ + c₁₀·dx + c₀₁·dy + c₂₀·dx² + c₁₁·dx·dy + c₀₂·dy²`, integer
/// coefficients. Evaluated exactly: along a row it is a quadratic in the column, which the
/// narrow kernel forward-differences with two additions per pixel.
///
/// The centre of the screen is the expansion point for every sphere. The coefficients'
/// rounding (each within one unit of the quadric's held scale, see [`NarrowSphere`](super::prepare::NarrowSphere))
/// then weighs with the square of a pixel's distance from it, at most the frame's size,
/// which no other point improves for a sphere that fills the frame; on the exponent series
/// the frame is the same bits as with each sphere's own middle as the point.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct Quadric {
    /// `[c₀₀, c₁₀, c₀₁, c₂₀, c₁₁, c₀₂]`.
    pub c: [i64; 6],
}

/// A quadric's state along a row at one column: its value, its step to the next column,
/// and the step's own step, so that `v += d; d += dd` moves it one pixel right.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Step {
    pub v: i64,
    pub d: i64,
    pub dd: i64,
}

impl Quadric {
    /// The quadric along the row at offset `y` (`dy`): `(e₀, e₁, e₂)` with
    /// `q = e₀ + e₁·x + e₂·x²`. Wrapping arithmetic: every partial sum is a value (or half a
    /// difference) of the quadric inside the frame, which its scale keeps within `2⁶²`. Out of
    /// line on ARMv6-M, for its flash: once per sphere and row.
    #[cfg_attr(not(shadeline_short_mul), inline(always))]
    #[cfg_attr(shadeline_short_mul, inline(never))]
    pub(crate) fn row(&self, y: i32) -> [i64; 3] {
        let [c00, c10, c01, c20, c11, c02] = self.c;
        let e0 = c00.wrapping_add(mul_wide(c01.wrapping_add(mul_wide(c02, y)), y));
        let e1 = c10.wrapping_add(mul_wide(c11, y));
        [e0, e1, c20]
    }

    /// The state at column offset `x` on the row `y` ([`row`](Self::row), then
    /// [`step_at`](Self::step_at)). Out of line on ARMv6-M, for its flash: once per run, sphere
    /// and quadric.
    #[cfg_attr(not(shadeline_short_mul), inline(always))]
    #[cfg_attr(shadeline_short_mul, inline(never))]
    pub(crate) fn step_at_cell(&self, y: i32, x: i32) -> Step {
        Self::step_at(self.row(y), x)
    }

    /// The state at column offset `x` of a row's `(e₀, e₁, e₂)`, stepping by two half pixels
    /// (one pixel) per column.
    #[inline(always)]
    pub(crate) fn step_at([e0, e1, e2]: [i64; 3], x: i32) -> Step {
        Step {
            v: e0.wrapping_add(mul_wide(e1.wrapping_add(mul_wide(e2, x)), x)),
            // q(x + 2) − q(x) = 2·e₁ + e₂·(4x + 4).
            d: e1
                .wrapping_mul(2)
                .wrapping_add(mul_wide(e2, x.wrapping_mul(4).wrapping_add(4))),
            dd: e2.wrapping_mul(8),
        }
    }
}
