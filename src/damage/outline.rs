//! A ball's outline on the screen: the columns of a row whose pixels can show any point of
//! the ball, or be anti-aliased against it.
//!
//! A ball is held in the camera's coordinates (`right`, `up`, `forward`), so the primary ray
//! of the plane point `(X, Y)` is `d = (X, Y, 1)` and it meets the ball of centre `c` and
//! radius `r` where `G(X, Y) = (d·c)² − (|c|² − r²)·|d|² ≥ 0` with `d·c > 0`. On a row `Y` is
//! fixed and `G ≥ 0` is a quadratic inequality in `X`: the forward nappe of the cone is
//! convex, so the covered part of the row is one interval, found from the two roots.
//!
//! Conservative by construction: the ball is grown, as it is made, by three pixel pitches
//! at its silhouette's distance, which moves every point of its outline at least three
//! pixels outward on the plane (the gnomonic projection never shrinks an angle, and the
//! outline's angular radius `asin(r/|c|)` grows by at least `Δr/√(|c|² − r²)`). So testing
//! a row at its centre, in `f32`, covers every pixel whose area or anti-aliased edge
//! touches the true outline, with room for the paths' own rounding.

use crate::scene::Scene;
use crate::vec3::Vec3;

/// Pixel pitches the outline of every ball is grown by: more than the half diagonal of a
/// pixel plus the one-pixel reach of an anti-aliased edge.
const GROW_PITCHES: f32 = 3.0;

/// The camera of a frame, as the outlines need it.
#[derive(Clone, Copy, Debug)]
pub(super) struct View {
    position: Vec3,
    right: Vec3,
    up: Vec3,
    forward: Vec3,
    /// `tan(vfov/2)`.
    tan: f32,
    /// `w/h`.
    aspect: f32,
    width: u32,
    height: u32,
}

impl View {
    /// The view of `scene`'s camera on a `width × height` frame.
    pub(super) fn of<const S: usize, const L: usize>(
        scene: &Scene<S, L>,
        width: u32,
        height: u32,
    ) -> Self {
        let (right, up, forward) = scene.camera_basis();
        View {
            position: scene.camera().position,
            right,
            up,
            forward,
            tan: scene.camera().tan_half_fov(),
            aspect: width as f32 / height.max(1) as f32,
            width,
            height,
        }
    }

    /// The plane distance between two pixel centres, `2·tan(vfov/2)/h` (square pixels).
    fn pitch(&self) -> f32 {
        2.0 * self.tan / self.height.max(1) as f32
    }

    /// The ball of `center` and `radius` (scene units) seen by this view, grown by
    /// [`GROW_PITCHES`] pixel pitches at its silhouette.
    pub(super) fn ball(&self, center: Vec3, radius: f32) -> Outline {
        let rel = center - self.position;
        let c = [rel.dot(self.right), rel.dot(self.up), rel.dot(self.forward)];
        let dist2 = rel.dot(rel);
        let r = radius.max(0.0);
        // The tangent length: the distance of the silhouette from the eye.
        let tangent = libm::sqrtf((dist2 - r * r).max(0.0));
        let grown = r + GROW_PITCHES * self.pitch() * tangent.max(r * 1.0e-3);
        Outline::new(c, grown)
    }

    /// The plane `Y` of row `y`'s centre.
    fn row_y(&self, y: u32) -> f32 {
        (1.0 - 2.0 * (y as f32 + 0.5) / self.height.max(1) as f32) * self.tan
    }

    /// The column (fractional, 0 at the first pixel's centre) whose centre is plane `x`.
    fn column(&self, x: f32) -> f32 {
        (x / (self.aspect * self.tan) + 1.0) * 0.5 * self.width as f32 - 0.5
    }

    /// The plane `X` of column `u`'s centre (`u` may be outside the frame).
    fn plane_x(&self, u: f32) -> f32 {
        (2.0 * (u + 0.5) / self.width.max(1) as f32 - 1.0) * self.aspect * self.tan
    }

    /// The frame's width.
    pub(super) fn width(&self) -> u32 {
        self.width
    }

    /// The frame's height.
    pub(super) fn height(&self) -> u32 {
        self.height
    }
}

/// A ball in the camera's coordinates, already grown (see the module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Outline {
    /// The eye is inside the grown ball: every pixel of the frame.
    Everywhere,
    /// The ball lies wholly behind the eye's plane: no pixel.
    Nowhere,
    /// A ball the eye is outside of.
    Ball {
        /// Centre, camera coordinates.
        c: [f32; 3],
        /// Radius, grown.
        r: f32,
    },
}

impl Outline {
    fn new(c: [f32; 3], r: f32) -> Self {
        let [x, y, z] = c;
        let dist2 = x * x + y * y + z * z;
        // A NaN (which validated scenes never give) falls to `Everywhere`.
        if z < -r {
            Outline::Nowhere
        } else if dist2 > r * r * 1.000_001 + 1.0e-12 {
            Outline::Ball { c, r }
        } else {
            Outline::Everywhere
        }
    }

    /// Whether `self` holds all of `other`.
    pub(super) fn holds(&self, other: &Outline) -> bool {
        match (self, other) {
            (Outline::Everywhere, _) | (_, Outline::Nowhere) => true,
            (Outline::Nowhere, _) | (_, Outline::Everywhere) => false,
            (Outline::Ball { c, r }, Outline::Ball { c: c2, r: r2 }) => {
                distance(*c, *c2) + r2 <= *r
            }
        }
    }

    /// The smallest ball holding both (the eye inside it: [`Outline::Everywhere`]), and the
    /// radius it grows to, to choose what to merge.
    pub(super) fn merged(&self, other: &Outline) -> Outline {
        match (self, other) {
            (Outline::Everywhere, _) | (_, Outline::Everywhere) => Outline::Everywhere,
            (Outline::Nowhere, o) | (o, Outline::Nowhere) => *o,
            (Outline::Ball { c, r }, Outline::Ball { c: c2, r: r2 }) => {
                let d = distance(*c, *c2);
                if d + r2 <= *r {
                    return *self;
                }
                if d + r <= *r2 {
                    return *other;
                }
                let radius = (d + r + r2) * 0.5 * 1.000_01;
                // From `c` toward `c2`, `radius − r` along.
                let t = if d > 0.0 { (radius - r) / d } else { 0.0 };
                let [x, y, z] = *c;
                let [x2, y2, z2] = *c2;
                let centre = [x + (x2 - x) * t, y + (y2 - y) * t, z + (z2 - z) * t];
                Outline::new(centre, radius)
            }
        }
    }

    /// The radius of a ball, 0 for nowhere and infinity for everywhere.
    pub(super) fn radius(&self) -> f32 {
        match self {
            Outline::Everywhere => f32::INFINITY,
            Outline::Nowhere => 0.0,
            Outline::Ball { r, .. } => *r,
        }
    }

    /// The columns `[start, end)` of row `y` the outline may touch, or `None`.
    pub(super) fn row(&self, view: &View, y: u32) -> Option<(u32, u32)> {
        let width = view.width();
        let (c, r) = match self {
            Outline::Everywhere => return Some((0, width)),
            Outline::Nowhere => return None,
            Outline::Ball { c, r } => (*c, *r),
        };
        let [cx, cy, cz] = c;
        let k = cx * cx + cy * cy + cz * cz - r * r;
        let yy = view.row_y(y);
        let q = cy * yy + cz;
        let a = cx * cx - k;
        let hb = cx * q;
        let c0 = q * q - k * (yy * yy + 1.0);
        // The frame's columns, one beyond each side, on the plane.
        let left = view.plane_x(-1.0);
        let right = view.plane_x(width as f32);
        // The forward half of the row, `cx·X + q > 0`, within the frame.
        let (mut lo, mut hi) = (left, right);
        if cx > 0.0 {
            lo = lo.max(-q / cx);
        } else if cx < 0.0 {
            hi = hi.min(-q / cx);
        } else if q <= 0.0 {
            return None;
        }
        if a < 0.0 {
            // A bounded section: between the roots.
            let disc = hb * hb - a * c0;
            if disc < 0.0 {
                return None;
            }
            let s = libm::sqrtf(disc);
            let (r1, r2) = ((-hb + s) / a, (-hb - s) / a);
            lo = lo.max(r1.min(r2));
            hi = hi.min(r1.max(r2));
        } else if a > 0.0 {
            // An unbounded section: outside the roots, if there are any; the part on the
            // forward side is one interval (convex), so the hull of the two pieces is exact
            // up to the piece on the far side, which the forward bound cuts.
            let disc = hb * hb - a * c0;
            if disc >= 0.0 {
                let s = libm::sqrtf(disc);
                let (r1, r2) = ((-hb - s) / a, (-hb + s) / a);
                let (x1, x2) = (r1.min(r2), r1.max(r2));
                let first = (lo <= x1.min(hi)).then_some((lo, x1.min(hi)));
                let second = (x2.max(lo) <= hi).then_some((x2.max(lo), hi));
                match (first, second) {
                    (Some((l, _)), Some((_, h))) => (lo, hi) = (l, h),
                    (Some(p), None) | (None, Some(p)) => (lo, hi) = p,
                    (None, None) => return None,
                }
            }
        }
        // NaN (never from a validated scene) is kept, conservatively, as the whole row.
        if lo.is_nan() || hi.is_nan() {
            return Some((0, width));
        }
        if lo > hi {
            return None;
        }
        let first = libm::floorf(view.column(lo)) - 1.0;
        let last = libm::ceilf(view.column(hi)) + 1.0;
        if last < 0.0 || first >= width as f32 {
            return None;
        }
        // Saturating conversions: both are within `[0, width]` after the clamps.
        let start = first.max(0.0) as u32;
        let end = ((last + 1.0).min(width as f32)) as u32;
        (start < end).then_some((start, end))
    }
}

fn distance(a: [f32; 3], b: [f32; 3]) -> f32 {
    let [x, y, z] = a;
    let [x2, y2, z2] = b;
    let (dx, dy, dz) = (x - x2, y - y2, z - z2);
    libm::sqrtf(dx * dx + dy * dy + dz * dz)
}
