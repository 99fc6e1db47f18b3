//! Scanline spans: which pixels of a row each sphere can cover, computed analytically.
//!
//! A sphere seen from a pinhole projects to a conic, so on one row the set of camera-plane
//! `x` whose primary ray meets the sphere is where a quadratic is non-positive. With `O` the
//! eye, `C` the centre, `oc = C − O`, `k = |oc|² − r²`, row base `B = y·up + forward` and the
//! unnormalized ray direction `d = x·right + B` (`right ⟂ B`, `|right| = 1`):
//!
//! ```text
//! ray line meets sphere  ⇔  |oc × d|² ≤ r²|d|²  ⇔  (k − a²)x² − 2ab·x + (kβ − b²) ≤ 0
//! a = oc·right,  b = oc·B,  β = B·B
//! ```
//!
//! The test is on the whole line, so it also admits spheres behind the eye: that only makes
//! spans larger, never smaller. The span is then widened so it stays **conservative** — no
//! pixel the per-pixel test would hit is ever left out (tested on random scenes against the
//! brute-force renderer, bit for bit):
//!
//! - the discriminant gets a slack of `1e-4` relative to the size of the terms it is computed
//!   from (not to its own size: on a row tangent to the sphere the exact value is 0 and the
//!   computed one is all rounding), which also opens a small span on rows that graze the top
//!   or bottom of the silhouette;
//! - the pixel range is widened by two pixels on each side;
//! - if the eye is inside or on the sphere (`k ≤ 0`), or the conic is not an ellipse
//!   across the row (`k − a² ≤ 1e-6·k`: the sphere reaches the camera's side plane), the span
//!   is the whole row.
//!
//! All of it is per row and per sphere in `f32`: a few dozen operations, against thousands
//! per pixel row.

use super::prepare::{FloatPath, Prepared};
use crate::runs::Span;
use crate::vec3::Vec3;

/// Pixels of widening on each side of an analytic span.
const MARGIN_PIXELS: f32 = 2.0;
/// Relative slack on the discriminant.
const DISC_SLACK: f32 = 1.0e-4;

/// The span of a sphere on a row, or `None` if the sphere cannot cover any pixel of it.
///
/// `eye_offset` is `eye − centre`, `base` the row base `y·up + forward`; `x_scale` and `width`
/// map camera-plane `x` to pixel indices as the primary rays do.
// `!(a > b)` on purpose below: a NaN must take the conservative branch (the whole row).
#[allow(clippy::neg_cmp_op_on_partial_ord)]
pub(crate) fn sphere_span(
    eye_offset: Vec3,
    radius_sq: f32,
    right: Vec3,
    base: Vec3,
    x_scale: f32,
    width: u32,
) -> Option<Span> {
    let full = Some(Span {
        start: 0,
        end: width,
    });
    let oc = -eye_offset;
    let oc2 = oc.dot(oc);
    let k = oc2 - radius_sq;
    if !(k > 0.0) {
        return full;
    }
    let a = oc.dot(right);
    let b = oc.dot(base);
    let beta = base.dot(base);
    let quad = k - a * a;
    if !(quad > 1.0e-6 * k) {
        return full;
    }
    let ab = a * b;
    let c = k * beta - b * b;
    let disc = ab * ab - quad * c;
    // `c` cancels `kβ` against `b²` (and `k` cancels `|oc|²` against `r²`): the slack scales
    // with those terms, so a row whose exact `c` is 0 (tangent to the sphere) keeps its span.
    let slack = DISC_SLACK * (ab * ab + quad * ((oc2 + radius_sq) * beta + b * b));
    if disc < -slack {
        return None;
    }
    let half = libm::sqrtf(disc.max(0.0) + slack) / quad;
    let mid = ab / quad;
    // Camera-plane x to (fractional) pixel index: i = (x/x_scale + 1)·w/2 − ½.
    let w = width as f32;
    let to_pixel = |x: f32| (x / x_scale + 1.0) * (0.5 * w) - 0.5;
    let lo = to_pixel(mid - half) - MARGIN_PIXELS;
    let hi = to_pixel(mid + half) + MARGIN_PIXELS;
    if !(lo.is_finite() && hi.is_finite()) {
        return full;
    }
    if hi < 0.0 || lo >= w {
        return None;
    }
    // Both are finite and clamped into [0, w], so the casts are exact and in range.
    let start = lo.max(0.0) as u32;
    let end = (hi.min(w - 1.0) as u32 + 1).min(width);
    if start >= end {
        return None;
    }
    Some(Span { start, end })
}

impl<W: FloatPath, const S: usize, const L: usize> Prepared<W, S, L> {
    /// The span of every sphere on row `y`, in scene order (`None`: not on this row).
    ///
    /// With spans turned off ([`Prepared::with_spans`]) every sphere spans the whole row. With
    /// anti-aliasing on (`Prepared::with_antialiasing`, with the `antialias` feature) a span
    /// also holds every pixel the sphere's outline partly covers.
    pub fn row_spans(&self, y: u32) -> heapless::Vec<Option<Span>, S> {
        let row = self.row(y);
        let mut out = heapless::Vec::new();
        for s in &self.spheres {
            let span = if self.use_spans {
                // Anti-aliased: a radius whose outline lies beyond the edges' ramp.
                #[cfg(feature = "antialias")]
                let radius_sq = if self.antialias {
                    s.outline.spans_radius_sq
                } else {
                    s.radius_sq
                };
                #[cfg(not(feature = "antialias"))]
                let radius_sq = s.radius_sq;
                sphere_span(
                    s.eye_offset,
                    radius_sq,
                    self.right,
                    row.base,
                    self.x_scale,
                    self.width,
                )
            } else {
                Some(Span {
                    start: 0,
                    end: self.width,
                })
            };
            // Same capacity as the sphere list: cannot fail.
            let pushed = out.push(span);
            debug_assert!(pushed.is_ok(), "more spans than spheres");
        }
        out
    }
}
