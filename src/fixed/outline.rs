//! Scanline spans of the fixed path without its full-width kernel (a firmware's build, no
//! feature `full-width`): each sphere's span on a row is exactly the columns where the narrow
//! kernel's hit test passes, found from the same integer quadric the kernel steps along the
//! row, so there is no `f32` outline to compute at prepare and no margin to allow for.
//!
//! The narrow kernel tests a pixel by the sign of `E′` (see `narrow`), a quadratic in the
//! pixel's half-pixel offsets `(dx, dy)` held with exact integer coefficients
//! ([`Quadric`]). Where the sphere's outline on the screen is an ellipse (the sphere is in
//! front of the camera and does not reach its side), `E′` is concave along every row and the
//! rows that reach `E′ ≥ 0` are one interval: the prepare finds that interval once
//! ([`outline_rows`]: three exact `i128` evaluations per sphere and a walk down the rows by
//! forward differences, two `i128` additions a row), and each row in it
//! its columns ([`outline_on_row`]: a binary search for the row's largest value, then the
//! quadric's forward differences out to the span's ends). A row
//! outside the interval costs one comparison. Elsewhere (a hyperbola or parabola on the
//! screen, which the narrow kernel's field of view allows only for a sphere beside the
//! camera) a sphere spans the whole frame, or the whole row. The spans are the hit test's
//! own, so they change no pixel: `checks/no-models/tests/spans.rs` renders frames with and
//! without them.
//!
//! With `full-width`, the spans are `spans`' screen rectangles and `f32` row conics, which
//! the full-width kernel and the anti-aliased edges need.

use super::mul::mul_128;
use super::quadric::{Quadric, Step};
use crate::runs::Span;

/// The first `k` in `[lo, hi)` for which `pred(k)` holds, or `hi` if none does, for a
/// `pred` that is false up to some point and true from there on: a binary search.
#[inline(always)]
fn first(mut lo: u32, mut hi: u32, pred: impl Fn(u32) -> bool) -> u32 {
    while lo < hi {
        let mid = lo + (hi - lo) / 2;
        if pred(mid) {
            hi = mid;
        } else {
            lo = mid + 1;
        }
    }
    lo
}

/// Largest magnitude of `c₂₀` (every row's `e₂`) for which [`outline_rows`] bounds the
/// rows: then `4e₂` fits `i64`, and with `e₀`, `e₁` below `2⁶²` (values of the quadric in
/// the frame, or half a difference of two, see [`Quadric::row`]) `e₁²` and `4e₂e₀` are
/// below `2¹²⁵`, so their difference fits `i128`.
const ROW_TEST_LIMIT: u64 = 1 << 61;

/// `e₁² − 4e₂e₀` of `E′` on row `y` of a frame `height` rows high: with `e₂ < 0`, at
/// least 0 exactly where the row's chord of `E′` reaches `E′ ≥ 0` for some real `dx`, in
/// the frame or not. Exact in `i128` where [`ROW_TEST_LIMIT`] bounds `e₂`.
#[inline(never)]
fn row_reach(e: &Quadric, y: u32, height: u32) -> i128 {
    let [e0, e1, e2] = e.row(height as i32 - 2 * y as i32 - 1);
    mul_128(e1, e1) - mul_128(4 * e2, e0)
}

/// The rows `[start, end)` of a frame `height` rows high on which the sphere whose narrow
/// quadric is `e` can be hit, found once per frame; the whole frame where `E′` is not an
/// ellipse on the screen (the sphere reaches the side of the camera) or `c₂₀` is too large
/// for the exact test ([`ROW_TEST_LIMIT`]).
///
/// On the row at `dy`, `E′ = e₀ + e₁·dx + e₂·dx²` with `e₂ = c₂₀`: for `c₂₀ < 0` its
/// largest value over real `dx` is `e₀ − e₁²/4e₂`, which is at least 0 iff
/// `R(dy) = e₁² − 4e₂e₀ ≥ 0` ([`row_reach`]). `R` is a quadratic in `dy` with leading
/// coefficient `c₁₁² − 4c₂₀c₀₂`; where that is negative, `R` is concave along the rows, so
/// its rows at or above 0 are one interval, which a walk down the rows finds: `R` by its
/// forward differences from its first three rows, two `i128` additions a row. They wrap,
/// but every row's `R` in the frame fits `i128`, so each is exact (the differences are
/// exact modulo `2¹²⁸`; in a frame of fewer than three rows the rows beyond it feed only
/// values that are never read). So no row with a hit is left out, and the walk stops at
/// the interval's end.
pub(crate) fn outline_rows(e: &Quadric, height: u32) -> (u32, u32) {
    let [_, _, _, c20, c11, c02] = e.c;
    // c₁₁² and 4c₂₀c₀₂ are below 2¹²⁶: compared, not subtracted.
    if c20 >= 0
        || c20.unsigned_abs() >= ROW_TEST_LIMIT
        || mul_128(c11, c11) >= mul_128(4 * c20, c02)
    {
        return (0, height);
    }
    let [r0, r1, r2] = [0, 1, 2].map(|y| row_reach(e, y, height));
    let mut reach = r0;
    let mut step = r1.wrapping_sub(r0);
    let bend = r2.wrapping_sub(r1).wrapping_sub(step);
    let mut start = None;
    for y in 0..height {
        match (start, reach >= 0) {
            (None, true) => start = Some(y),
            (Some(first), false) => return (first, y),
            _ => {}
        }
        reach = reach.wrapping_add(step);
        step = step.wrapping_add(bend);
    }
    start.map_or((0, 0), |first| (first, height))
}

/// The columns of the row at offset `dy` (frame `width` columns wide) where `E′ ≥ 0`: the
/// narrow kernel's hit test, so the span is exact. `E′` is concave along the row where
/// `e₂ < 0` (otherwise the span is the whole row): a binary search on the sign of its
/// forward difference finds its largest column, and from there the span's ends are walked
/// to, one column at a time by the quadric's forward differences (two additions a column,
/// exact, as the kernel's own steps are). On the exponent series' rows that is cheaper
/// than two more binary searches, each step of which evaluates the quadric with two 32×32→64
/// products (calls on ARMv6-M); a sphere as wide as the frame walks at most its width.
pub(crate) fn outline_on_row(e: &Quadric, dy: i32, width: u32) -> Option<Span> {
    let row = e.row(dy);
    if row[2] >= 0 {
        return Some(Span {
            start: 0,
            end: width,
        });
    }
    let at = |column: u32| Quadric::step_at(row, 2 * column as i32 + 1 - width as i32);
    let top = first(0, width.saturating_sub(1), |c| at(c).d <= 0);
    // `d` is E′(c + 1) − E′(c) at column c, and moves by `dd` a column.
    let Step { v, d, dd } = at(top);
    if v < 0 {
        return None;
    }
    let (mut start, mut value, mut diff) = (top, v, d);
    while start > 0 {
        let before = diff.wrapping_sub(dd);
        value = value.wrapping_sub(before);
        if value < 0 {
            break;
        }
        diff = before;
        start -= 1;
    }
    let (mut end, mut value, mut diff) = (top + 1, v, d);
    while end < width {
        value = value.wrapping_add(diff);
        if value < 0 {
            break;
        }
        diff = diff.wrapping_add(dd);
        end += 1;
    }
    Some(Span { start, end })
}
