//! Scanline spans of the fixed path: a conservative screen rectangle per sphere, computed
//! once per frame at prepare, so that no row needs any arithmetic beyond two comparisons.
//!
//! The float path solves a quadratic per row and sphere in `f32`; doing that in integers
//! would need a square root and a division per row and sphere, and would have to be proven
//! conservative against the fixed hit test's own rounding. A rectangle is free per row and
//! easy to prove: it costs about `4/π` more tested pixels than the ellipse inside it, and a
//! tested pixel that misses costs nine multiplications.
//!
//! # The rectangle
//!
//! In camera coordinates (`right`, `up`, `forward`) let the centre be at `(cx, cy, cz)` from
//! the eye and `k = cz² − r²`. The planes through the eye that contain the `up` axis and touch
//! the sphere cut the image plane `z = 1` at
//!
//! ```text
//! x = (cx·cz ± r·√(cx² + k)) / k
//! ```
//!
//! (and likewise `y` with `cy`), which bound the sphere's projection exactly when the sphere
//! is entirely in front of the eye. The pixel range is then widened by two pixels plus
//! `10⁻⁴` of the coordinate on each side, so rounding in this `f32` computation and in the
//! fixed hit test cannot leave a hit pixel out. A sphere that is not clearly in front
//! (`cz ≤ 1.05·r`: it contains the eye, or reaches the camera's side plane, or the
//! quadratic is ill-conditioned) spans the whole frame. `tests/fixed_render.rs` checks
//! that spans change no pixel against testing every sphere at every pixel.

use crate::runs::Span;
use crate::vec3::Vec3;

/// Pixels of widening on each side.
const MARGIN_PIXELS: f32 = 2.0;
/// Relative widening on each side.
const MARGIN_RELATIVE: f32 = 1.0e-4;
/// Spheres with `cz ≤ NEAR·r` span the whole frame.
const NEAR: f32 = 1.05;

/// The rows and columns a sphere can cover, both half-open.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Bounds {
    /// First row and one past the last.
    pub rows: (u32, u32),
    /// The columns, as a row span.
    pub cols: Span,
}

impl Bounds {
    /// The span on row `y`, if the rectangle reaches it.
    #[inline(always)]
    pub(crate) fn on_row(&self, y: u32) -> Option<Span> {
        (self.rows.0 <= y && y < self.rows.1).then_some(self.cols)
    }
}

/// The camera as the rectangle needs it: eye, basis and the image plane's pixel step.
pub(crate) struct View {
    pub eye: Vec3,
    pub right: Vec3,
    pub up: Vec3,
    pub forward: Vec3,
    /// `tan(vfov/2)/height`: half a pixel on the image plane `z = 1`.
    pub half_pixel: f32,
    pub width: u32,
    pub height: u32,
}

// `!(a > b)` on purpose below: a NaN must take the conservative branch (the whole frame).
#[allow(clippy::neg_cmp_op_on_partial_ord)]
impl View {
    /// The rectangle of the sphere `(center, radius)`, or `None` if it is off screen.
    pub(crate) fn bounds(&self, center: Vec3, radius: f32) -> Option<Bounds> {
        let full = Some(Bounds {
            rows: (0, self.height),
            cols: Span {
                start: 0,
                end: self.width,
            },
        });
        let oc = center - self.eye;
        let (cx, cy, cz) = (oc.dot(self.right), oc.dot(self.up), oc.dot(self.forward));
        if !(cz > NEAR * radius) {
            return full;
        }
        let k = cz * cz - radius * radius;
        let extent = |c: f32| {
            let s = radius * libm::sqrtf(c * c + k);
            let mid = c * cz;
            ((mid - s) / k, (mid + s) / k)
        };
        let (x_lo, x_hi) = extent(cx);
        let (y_lo, y_hi) = extent(cy);
        // Plane x = (2i + 1 − w)·q  ⇒  i = (x/q + w − 1)/2; plane y = (h − 2j − 1)·q.
        let q = self.half_pixel;
        let (w, h) = (self.width as f32, self.height as f32);
        let col = |x: f32| (x / q + w - 1.0) * 0.5;
        let row = |y: f32| (h - 1.0 - y / q) * 0.5;
        let (Some(cols), Some(rows)) = (
            pixel_range(col(x_lo), col(x_hi), self.width),
            pixel_range(row(y_hi), row(y_lo), self.height),
        ) else {
            return full;
        };
        Some(Bounds {
            rows: rows?,
            cols: cols.map(|(start, end)| Span { start, end })?,
        })
    }
}

/// The widened, clamped, half-open pixel range over fractional indices `[lo, hi]`:
/// `Some(None)` if it is empty, `None` if it is not finite.
#[allow(clippy::neg_cmp_op_on_partial_ord)]
fn pixel_range(lo: f32, hi: f32, size: u32) -> Option<Option<(u32, u32)>> {
    let lo = lo - MARGIN_PIXELS - MARGIN_RELATIVE * lo.abs();
    let hi = hi + MARGIN_PIXELS + MARGIN_RELATIVE * hi.abs();
    if !(lo.is_finite() && hi.is_finite()) {
        return None;
    }
    let n = size as f32;
    if hi < 0.0 || lo >= n {
        return Some(None);
    }
    // Clamped into [0, n], so the casts are exact and in range.
    let start = libm::floorf(lo.max(0.0)) as u32;
    let end = (libm::ceilf(hi.min(n)) as u32).saturating_add(1).min(size);
    Some((start < end).then_some((start, end)))
}
