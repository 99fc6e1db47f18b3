//! Scanline spans of the fixed path without its full-width kernel (a firmware's build, no
//! feature `full-width`): each sphere's span on a row holds exactly the columns where the
//! narrow kernel's hit test passes (on ARMv6-M, its columns on every row, see below), found
//! from the same integer quadric the kernel steps along the row, so there is no `f32`
//! outline to compute at prepare and no margin to allow for.
//!
//! The narrow kernel tests a pixel by the sign of `E′` (see `narrow`), a quadratic in the
//! pixel's half-pixel offsets `(dx, dy)` held with exact integer coefficients
//! ([`Quadric`]). Where the sphere's outline on the screen is an ellipse (the sphere is in
//! front of the camera and does not reach its side), `E′` is concave along every row and
//! every column, and the rows that reach `E′ ≥ 0` are one interval, as are the columns: the
//! prepare finds both once ([`outline_rows`], [`outline_columns`]: three exact `i128`
//! evaluations per sphere and a walk by forward differences, two `i128` additions a row or
//! column). A row outside the rows costs one comparison; on a row inside them,
//! [`outline_on_row`] walks in from the sphere's columns to the row's span. Elsewhere (a
//! hyperbola or parabola on the screen, which the narrow kernel's field of view allows only
//! for a sphere beside the camera) a sphere spans the whole frame, or the whole row. The
//! spans hold every pixel the hit test passes, so they change no pixel:
//! `checks/no-models/tests/spans.rs` renders frames with and without them.
//!
//! With `full-width`, the spans are `spans`' screen rectangles and `f32` row conics, which
//! the full-width kernel and the anti-aliased edges need.

use super::mul::mul_128;
use super::quadric::Quadric;
use crate::runs::Span;

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

/// The columns `[start, end)` of a frame `width` columns wide on which the sphere whose
/// narrow quadric is `e` can be hit: [`outline_rows`] of the same quadric with the two
/// offsets' roles exchanged. Column `x` is at offset `dx = 2x + 1 − w`, which is the row
/// offset of row `w − 1 − x` in a frame `w` rows high, so the rows found are the columns
/// mirrored.
#[inline(always)]
pub(crate) fn outline_columns(e: &Quadric, width: u32) -> (u32, u32) {
    let [c00, c10, c01, c20, c11, c02] = e.c;
    let across = Quadric {
        c: [c00, c01, c10, c02, c11, c20],
    };
    let (first, last) = outline_rows(&across, width);
    (width - last, width - first)
}

/// The columns of the row at offset `dy` (frame `width` columns wide) where `E′ ≥ 0`, within
/// the sphere's columns `[start, end)` ([`outline_columns`]): the narrow kernel's hit test,
/// so the span is exact. Where `E′` is concave along the row (`e₂ < 0`) its columns at or
/// above 0 are one interval, found by walking in from both ends of the sphere's columns,
/// one column at a time by the quadric's forward differences (two additions a column,
/// exact, as the kernel's own steps are); elsewhere the span is all of the sphere's
/// columns. The walks cross only the columns beside the outline, which the kernel would
/// otherwise test pixel by pixel.
///
/// On ARMv6-M the span is the sphere's columns as they are, and the kernel tests the
/// pixels beside the outline: there its miss at a pixel costs about what a step of the
/// walk does, so the walks would save no instructions and cost flash. Where a 32×32→64
/// product is one instruction (Cortex-M4, RV32IM, the host) the walks take instructions
/// off the demo's frame (`docs/performance.md, "Choices measured"`). Either way a pixel's colour does not
/// depend on the span (`checks/no-models/tests/spans.rs`, which also shows that the
/// columns hold every hit, since the walks start from them).
#[inline(always)]
pub(crate) fn outline_on_row(
    e: &Quadric,
    dy: i32,
    width: u32,
    columns: (u32, u32),
) -> Option<Span> {
    #[cfg(not(shadeline_short_mul))]
    let (start, end) = walk_in(e.row(dy), width, columns);
    #[cfg(shadeline_short_mul)]
    let ((start, end), _) = (columns, (e, dy, width));
    (start < end).then_some(Span { start, end })
}

/// The walks of [`outline_on_row`] on a row's `(e₀, e₁, e₂)`.
#[cfg(not(shadeline_short_mul))]
#[inline(always)]
fn walk_in(row: [i64; 3], width: u32, (mut start, mut end): (u32, u32)) -> (u32, u32) {
    if row[2] < 0 {
        let at = |column: u32| Quadric::step_at(row, 2 * column as i32 + 1 - width as i32);
        // `d` is E′(c + 1) − E′(c) at column c, and moves by `dd` a column.
        let mut s = at(start);
        while start < end && s.v < 0 {
            s.v = s.v.wrapping_add(s.d);
            s.d = s.d.wrapping_add(s.dd);
            start += 1;
        }
        let mut s = at(end.wrapping_sub(1));
        while start < end && s.v < 0 {
            s.d = s.d.wrapping_sub(s.dd);
            s.v = s.v.wrapping_sub(s.d);
            end -= 1;
        }
    }
    (start, end)
}
