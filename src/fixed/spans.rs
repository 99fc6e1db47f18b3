//! Scanline spans of the fixed path: a conservative screen rectangle per sphere, computed
//! once per frame at prepare, narrowed on each row to the sphere's outline.
//!
//! The rectangle alone costs about `4/π` more tested pixels than the ellipse inside it (1.56
//! sphere-pixels tested per covered pixel on the exponent series, with its margins), and
//! every tested pixel costs the kernel its hit test and its forward differences. So each
//! sphere also gets its outline's row coefficients ([`RowConic`]), computed in `f32` at
//! prepare like the rectangle, and evaluated per row in integers: a few exact products and
//! an integer square root per row and sphere, no division, widened by bounds on the `f32`
//! coefficients' errors so that it stays conservative. Spheres whose coefficients do not
//! fit (frames over 4096 pixels, spheres far off screen) keep the rectangle.
//!
//! This module exists with the feature `full-width` (the full-width kernel and the
//! anti-aliased edges need the rectangles); without it the spans are `outline`'s, exact
//! from the narrow kernel's own quadric.
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

use super::mul::{mul_ii, mul_uu};
use crate::runs::Span;
use crate::vec3::Vec3;

/// Pixels of widening on each side.
const MARGIN_PIXELS: f32 = 2.0;
/// The same widening of the outline's spans, in columns.
const MARGIN_COLUMNS: i64 = 2;
/// Relative widening on each side.
const MARGIN_RELATIVE: f32 = 1.0e-4;
/// Spheres with `cz ≤ NEAR·r` span the whole frame.
const NEAR: f32 = 1.05;

/// The rows and columns a sphere can cover, both half-open, and its outline row by row.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Bounds {
    /// First row and one past the last.
    pub rows: (u32, u32),
    /// The columns, as a row span.
    pub cols: Span,
    /// The outline, where its coefficients fit the row arithmetic.
    pub conic: Option<RowConic>,
}

impl Bounds {
    /// The span on row `y` of a frame `height` rows high: the rectangle's columns, narrowed
    /// to the outline's on that row unless `rectangle`.
    #[inline(always)]
    pub(crate) fn on_row(&self, y: u32, height: u32, rectangle: bool) -> Option<Span> {
        if !(self.rows.0 <= y && y < self.rows.1) {
            return None;
        }
        match &self.conic {
            Some(conic) if !rectangle => conic.on_row(y, height, self.cols),
            _ => Some(self.cols),
        }
    }
}

/// How far from a row the edges stage looks for an outline, in half pixels (`dy`): two
/// pixels up and down, beyond the `1/√2` pixel of its reach, for the first-order distance
/// it takes can underrate the true one near a small sphere.
#[cfg(all(feature = "antialias", feature = "full-width"))]
const NEAR_DY: i32 = 3;
/// The same in columns, on each side.
#[cfg(all(feature = "antialias", feature = "full-width"))]
const NEAR_COLUMNS: i64 = 2;

#[cfg(all(feature = "antialias", feature = "full-width"))]
impl Bounds {
    /// The columns of row `y` (frame `height` rows high) near the sphere's outline, as two
    /// spans that may overlap, for the edges stage: a pixel outside both has no point of the
    /// outline within two pixels. The rectangle's columns on its rows where the sphere has
    /// no row conic.
    pub(crate) fn near_outline(&self, y: u32, height: u32) -> [Option<Span>; 2] {
        if !(self.rows.0 <= y && y < self.rows.1) {
            return [None, None];
        }
        match &self.conic {
            Some(conic) => conic.near_outline(y, height, self.cols),
            None => [Some(self.cols), None],
        }
    }
}

/// The sphere's outline on the screen, a conic, as the row arithmetic needs it.
///
/// With `dy = h − 2y − 1` the row's offset from the image centre in half pixels, the rays of
/// row `y` that meet the sphere are the columns `x` with `|x − x_c(dy)| ≤ √hw²(dy)`, where
/// the chord's centre moves linearly and its squared half-width is a downward parabola:
///
/// ```text
/// x_c(dy) = p + q·dy          hw²(dy) = H − G·(dy − dy₀)²
/// ```
///
/// With the centre at `(cx, cy, cz)` in camera coordinates, `K = |c|² − r²`,
/// `A = cy² + cz² − r²`, `s` half a pixel on the image plane `z = 1` and `x = (X/s + w − 1)/2`
/// the column of an image-plane coordinate `X`:
///
/// ```text
/// p = (cx·cz/(A·s) + w − 1)/2     q = cx·cy/(2A)     dy₀ = cy·cz/((cz² − r²)·s)
/// H = K·r²/(4A·s²·(cz² − r²))      G = K·(cz² − r²)/(4A²)
/// ```
///
/// (from `(c·d)² ≥ K·|d|²` for the direction `d = (X, Y, 1)`, solved for `X`). The
/// coefficients are computed in `f32` at prepare and held in fixed point; each row takes
/// three exact 32×32→64 products and an integer square root. The span is
/// widened so that no rounding can leave out a pixel the hit tests take: `hw²` by
/// `4 + 2⁻¹³·(H + G·t²)` columns² and `|dy − dy₀|` shrunk by `2⁻¹⁶·|dy₀| + 2⁻⁷` (bounds on
/// the `f32` coefficients' errors, far above them), then two columns on each side, as the
/// rectangle is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct RowConic {
    /// `dy₀`, Q8; `|dy₀| ≤ 2¹⁴`.
    dy0: i32,
    /// `H`, columns², Q8; `H ≤ 2²⁴`.
    h: u32,
    /// `G`, columns² per `dy²`, Q16; `G ≤ 2⁴`.
    g: u32,
    /// `p`, columns, Q8; `|p| ≤ 2²⁰`.
    p: i32,
    /// `q`, columns per `dy`, Q16; `|q| ≤ 2⁸`.
    q: i32,
    /// A bound on the shrunk `|dy − dy₀|` (Q8, as [`Self::on_row`] computes it) beyond
    /// which the outline has no span: a row that far is refused before its products.
    t_max: u32,
}

impl RowConic {
    /// The columns of `cols` on row `y` of a frame `height` rows high the outline can reach,
    /// or `None`.
    #[inline(always)]
    fn on_row(&self, y: u32, height: u32, cols: Span) -> Option<Span> {
        // y < height ≤ 2¹²: dy in (−2¹², 2¹²).
        let dy = height as i32 - 2 * y as i32 - 1;
        // |t| < 2²³ (Q8), shrunk toward 0 by the slack for dy₀'s error.
        let t = ((dy << 8) - self.dy0).unsigned_abs();
        let t = t.saturating_sub((self.dy0.unsigned_abs() >> 16) + 2);
        if t > self.t_max {
            return None;
        }
        let t2 = (mul_uu(t, t) >> 16) as u32; // dy², Q0: < 2³⁰
        let gt = mul_uu(self.g, t2) as i64; // Q16, < 2⁵⁰
        let h = (self.h as i64) << 8; // Q16
        let slack = (4 << 16) + ((h + gt) >> 13);
        let v = h - gt + slack;
        if v < 0 {
            return None;
        }
        // √v in Q8 columns, rounded up: v < 2⁴² (H ≤ 2²⁴ in Q16 plus its slack).
        let v = v as u64;
        let root = if v >> 32 == 0 {
            (v as u32).isqrt() + 1
        } else {
            (((v >> 16) as u32).isqrt() + 1) << 8
        };
        let half = (root >> 8) as i64 + 1 + MARGIN_COLUMNS;
        let centre = (((self.p as i64) << 8) + mul_ii(self.q, dy)) >> 16; // floor of x_c
        let start = (centre - half).max(cols.start as i64);
        // + 1: x_c may lie anywhere in [centre, centre + 1).
        let end = (centre + half + 2).min(cols.end as i64);
        (start < end).then_some(Span {
            start: start as u32,
            end: end as u32,
        })
    }
}

#[cfg(all(feature = "antialias", feature = "full-width"))]
impl RowConic {
    /// See [`Bounds::near_outline`]. Over the rows `dy ± NEAR_DY`, the outline's columns lie
    /// within `x_c ± [hw_min, hw_max]` with `x_c` between its values at both ends and `hw²`
    /// between its values at the nearest and farthest `|dy − dy₀|`, each bound widened by
    /// the same slack as [`Self::on_row`]'s, the inner one shrunk by it.
    fn near_outline(&self, y: u32, height: u32, cols: Span) -> [Option<Span>; 2] {
        let dy = height as i32 - 2 * y as i32 - 1;
        let (lo, hi) = ((dy - NEAR_DY) << 8, (dy + NEAR_DY) << 8); // Q8
        let err = (self.dy0.unsigned_abs() >> 16) + 2;
        let (ta, tb) = (
            (lo - self.dy0).unsigned_abs(),
            (hi - self.dy0).unsigned_abs(),
        );
        let t_near = if lo <= self.dy0 && self.dy0 <= hi {
            0
        } else {
            ta.min(tb).saturating_sub(err)
        };
        let t_far = ta.max(tb) + err;
        let h = (self.h as i64) << 8; // Q16
                                      // G·t² in Q16, t² rounded down (outer bound) or up (inner bound).
        let gt = |t: u32, up: bool| {
            let t2 = (mul_uu(t, t) + if up { 0xffff } else { 0 }) >> 16;
            mul_uu(self.g, t2.min(u32::MAX as u64) as u32) as i64
        };
        let (g_near, g_far) = (gt(t_near, false), gt(t_far, true));
        let outer = h - g_near + (4 << 16) + ((h + g_near) >> 13);
        if outer < 0 {
            return [None, None];
        }
        let inner = h - g_far - (4 << 16) - ((h + g_far) >> 13);
        // Columns: √ in Q8, rounded out (outer) or in (inner). Both below 2⁴² in Q16.
        let root = |v: i64| (v.max(0) as u64).isqrt() as i64;
        let (out_cols, in_cols) = ((root(outer) >> 8) + 1, root(inner) >> 8);
        let centre = |d: i32| ((self.p as i64) << 8) + mul_ii(self.q, d);
        let (a, b) = (centre(dy - NEAR_DY), centre(dy + NEAR_DY));
        let (c_lo, c_hi) = (a.min(b) >> 16, (a.max(b) >> 16) + 1);
        let clip = |start: i64, end: i64| {
            let (start, end) = (start.max(cols.start as i64), end.min(cols.end as i64));
            (start < end).then_some(Span {
                start: start as u32,
                end: end as u32,
            })
        };
        [
            clip(
                c_lo - out_cols - NEAR_COLUMNS,
                c_hi - in_cols + NEAR_COLUMNS + 1,
            ),
            clip(
                c_lo + in_cols - NEAR_COLUMNS,
                c_hi + out_cols + NEAR_COLUMNS + 1,
            ),
        ]
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
            conic: None,
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
            conic: self.conic(cx, cy, cz, radius),
        })
    }

    /// The outline's row coefficients (see [`RowConic`]) of the sphere at `(cx, cy, cz)` in
    /// camera coordinates, if the sphere is clearly in front and they fit their formats.
    fn conic(&self, cx: f32, cy: f32, cz: f32, r: f32) -> Option<RowConic> {
        if self.width > 1 << 12 || self.height > 1 << 12 {
            return None;
        }
        let s = self.half_pixel;
        let (r2, front) = (r * r, cz * cz - r * r);
        let k = cx * cx + cy * cy + front;
        let a = cy * cy + front;
        let w = self.width as f32;
        let p = (cx * cz / (a * s) + w - 1.0) * 0.5;
        let q = cx * cy / (2.0 * a);
        let dy0 = cy * cz / (front * s);
        let h = k * r2 / (4.0 * a * s * s * front);
        let g = k * front / (4.0 * a * a);
        let fits = |v: f32, limit: f32| v.is_finite() && v.abs() <= limit;
        if !(front > 0.0
            && a > 0.0
            && fits(p, (1 << 20) as f32)
            && fits(q, (1 << 8) as f32)
            && fits(dy0, (1 << 14) as f32)
            && fits(h, ((1 << 24) - 1) as f32)
            && fits(g, (1 << 4) as f32)
            && g > 0.0)
        {
            return None;
        }
        let q16 = (1u32 << 16) as f32;
        // Rounded toward wider spans: H up, G down.
        let (h_q8, g_q16) = (libm::ceilf(h * 256.0), libm::floorf(g * q16));
        // `on_row`'s test, `G·(t² − 1) ≤ (H·(1 + 2⁻¹³) + 4)/(1 − 2⁻¹³)` for the held `H` and
        // `G` (t² is rounded down), solved for `t` with margins far above `f32`'s rounding (a
        // tenth of a percent of `H` and `G`, a row); `as` saturates the bound of `G = 0`.
        let t_max = libm::sqrtf((h_q8 / 256.0 * 1.001 + 5.0) / (g_q16 / q16 * 0.999) + 2.0) + 1.0;
        Some(RowConic {
            t_max: (t_max * 256.0) as u32,
            dy0: (dy0 * 256.0) as i32,
            h: h_q8 as u32,
            g: g_q16 as u32,
            p: (p * 256.0) as i32,
            q: (q * q16) as i32,
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
