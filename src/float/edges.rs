//! The `edges` stage of the float paths: analytic anti-aliasing of the spheres' silhouettes.
//!
//! A sphere's silhouette on the image plane is the conic `F(x, y) = k·|u|² − (oc·u)² = 0`
//! (`u = x·right + y·up + forward`, `oc = C − eye`, `k = |oc|² − r²`; `F < 0` inside), whose
//! gradient is `∇F = 2(k·x − (oc·u)(oc·right), k·y − (oc·u)(oc·up))`. The signed distance
//! from a pixel centre to the outline is `F/|∇F|` to first order, and the sphere covers
//! `c = clamp(½ − F/(|∇F|·pixel), 0, 1)` of the pixel: a one-pixel ramp across the outline,
//! exact for a straight edge through the pixel.
//!
//! Per lane, the *edge* is the front sphere whose outline lies within `1/√2` pixel of the
//! centre (no straight edge farther away crosses the pixel): the sphere the centre ray hits,
//! or one it misses that lies nearer than what it hits (by the distance to the ray's closest
//! approach). A sphere the centre ray meets behind the one it hits is hidden there, so its
//! outline is no edge. The pixel is then `c·front + (1 − c)·behind`, of the colours as a
//! display shows them (each clamped to 1 first), with one colour from the shading of the
//! centre ray and the other from one more shading:
//!
//! | the centre ray | front | behind |
//! |---|---|---|
//! | hits the edge's sphere | the centre ray's colour | the centre ray with that sphere left out |
//! | misses it | that sphere alone, along the ray through the point `c/2` inside the outline (the middle of the covered strip), taken at its closest approach if rounding makes it miss | the centre ray's colour |
//!
//! Where two outlines cross a pixel (a sphere's edge over another's, the common case where
//! spheres overlap on the screen), `behind` is itself anti-aliased the same way, once: the
//! second edge is looked for with the first edge's sphere left out, against what lies behind
//! it. So a pixel costs one to three shadings: one away from every outline, two on one
//! outline, three where two meet. Measured against a 16×16 supersampled truth
//! (`harness/tests/edges.rs`), this beats 4×4 supersampling on every scene tested.
//!
//! The coverage of a straight edge is the exact area of the square pixel on its inside
//! ([`square_coverage`]), not a linear ramp: for an edge at 45° the two differ by up to 6%
//! of the pixel, which on a bright sphere over a dark background is a visible 10 levels.
//!
//! Everything is lane arithmetic on exactly specified operations, so the scalar and SIMD
//! paths stay bit-identical; pixels with no outline within reach pay only the test
//! `F² < 2·pixel²·|∇F/2|²` per candidate sphere and keep their colour bit for bit; packets
//! with no such pixel skip the rest. What this does not smooth: where two spheres intersect
//! (that curve is not an outline), and a third outline in the same pixel.

use super::intersect::Filter;
use super::kernel::Packet;
use super::lane::Lane;
use super::prepare::{FloatPath, Prepared, Row};
use crate::real::Real;
use crate::vec3::Vec3;

/// What `edges` found on a packet's lanes.
pub(crate) struct Edge<T: Lane> {
    /// Lanes an outline crosses.
    lanes: T::Mask,
    /// Lanes whose centre ray hits the edge's sphere.
    inside: T::Mask,
    /// The edge sphere's coverage of the pixel, in `(0, 1)` on `lanes`.
    coverage: T,
    /// The signed distance from the pixel centre to the outline, in pixels (positive
    /// outside), and the outline's unit normal in pixel axes (`x` right, `y` up).
    dist: T,
    normal: (T, T),
    /// The unit directions of the edge's shading (front or behind, see the module docs).
    pub direction: Vec3<T>,
    /// The spheres the edge's shading may hit.
    pub filter: Filter<T>,
}

impl<T: Lane> Edge<T> {
    /// `c·front + (1 − c)·behind` per channel, of the colours as a display shows them: each
    /// clamped to 1 first. (The colours are never negative or NaN.) A box filter of the
    /// displayed image averages clamped values, and a highlight far above 1 on a sphere's rim
    /// would otherwise spill over the whole pixel.
    #[inline(always)]
    fn mix(&self, front: Vec3<T>, behind: Vec3<T>) -> Vec3<T> {
        let c = self.coverage;
        let one = T::splat(1.0);
        let rest = one - c;
        let mix = |a: T, b: T| a.min(one) * c + b.min(one) * rest;
        Vec3::new(
            mix(front.x, behind.x),
            mix(front.y, behind.y),
            mix(front.z, behind.z),
        )
    }

    /// The share of the part of the pixel that this (front) edge leaves uncovered which
    /// `behind`, an edge further away, covers: `(c_b − area(A ∩ B))/(1 − c_a)`, in `[0, 1]`.
    ///
    /// Both coverages are exact for straight edges ([`square_coverage`]); the overlap of the
    /// two half-planes is taken as `c_b` times the share of `behind`'s points that this edge
    /// covers too, counted on an 8×8 grid of points in the pixel. Two edges on opposite
    /// sides of a pixel (a gap between two spheres) then share nothing, and an edge over a
    /// parallel one (a sphere in front of another's rim) hides the part it overlaps.
    #[inline(always)]
    fn coverage_left(&self, behind: &Edge<T>) -> T {
        let (zero, one) = (T::splat(0.0), T::splat(1.0));
        let (mut both, mut all) = (zero, zero);
        for i in 0..GRID {
            let oy = T::splat((i as f32 + 0.5) / GRID as f32 - 0.5);
            let (a_row, b_row) = (
                self.dist + self.normal.1 * oy,
                behind.dist + behind.normal.1 * oy,
            );
            for j in 0..GRID {
                let ox = T::splat((j as f32 + 0.5) / GRID as f32 - 0.5);
                let in_b = (b_row + behind.normal.0 * ox).lt(zero);
                let in_a = (a_row + self.normal.0 * ox).lt(zero);
                all = all + T::select(in_b, one, zero);
                both = both + T::select(T::and(in_a, in_b), one, zero);
            }
        }
        let shared = both / all.max(one);
        let left = one - self.coverage;
        let share = (behind.coverage * (one - shared)) / left.max(T::splat(1.0e-6));
        share.max(zero).min(one)
    }

    /// The edge's lanes blended from `base`, the colour without this edge's shading, and
    /// `shaded`, that shading's colour (front and behind as in the module docs); `base`
    /// elsewhere.
    #[inline(always)]
    fn blend(&self, base: Vec3<T>, shaded: Vec3<T>) -> Vec3<T> {
        let front = Vec3::select(self.inside, base, shaded);
        let behind = Vec3::select(self.inside, shaded, base);
        Vec3::select(self.lanes, self.mix(front, behind), base)
    }
}

/// What the first half of `edges` found on a packet's lanes: the front outline within
/// reach of each centre.
struct Front<T: Lane> {
    /// The outline's sphere, as `f32`; `-1` on lanes with none.
    sphere: T,
    /// Lanes whose centre ray hits that sphere.
    inside: T::Mask,
    /// The conic `F` at the centre, and half its gradient, `∇F/2`, in image-plane axes.
    f: T,
    gx: T,
    gy: T,
}

impl<W: FloatPath, const S: usize, const L: usize> Prepared<W, S, L> {
    /// The packet `centre` (the centre rays `u`, unit `d`, which hit at distance `t`) with
    /// the lanes that outlines cross anti-aliased, if anti-aliasing is on: the first edge,
    /// its shading, then the edge behind it, its shading, and the blends (see the module
    /// docs).
    #[inline(always)]
    pub(crate) fn antialiased(
        &self,
        mut centre: Packet<W::Lane>,
        row: &Row,
        u: Vec3<W::Lane>,
        d: Vec3<W::Lane>,
        t: W::Lane,
        candidates: &[u16],
    ) -> Packet<W::Lane> {
        if !self.antialias {
            return centre;
        }
        let none = W::Lane::splat(-1.0);
        let Some(first) = self.edges(row, u, d, (centre.sphere, t), none, candidates) else {
            return centre;
        };
        let (second, second_t) = self.shade_filtered(&(first.direction, first.filter), candidates);
        // What lies behind the first edge: the second shading where the centre ray hits the
        // edge's sphere (it left that sphere out), the centre ray elsewhere.
        let inside = first.inside;
        let behind = Vec3::select(inside, second.color, centre.color);
        let behind_id = W::Lane::select(inside, second.sphere, centre.sphere);
        let behind_t = W::Lane::select(inside, second_t, t);
        let front = Vec3::select(inside, centre.color, second.color);
        let sphere = first.filter.sphere;
        let behind = match self.edges(row, u, d, (behind_id, behind_t), sphere, candidates) {
            Some(mut edge) => {
                edge.filter.also = sphere;
                edge.coverage = first.coverage_left(&edge);
                let (third, _) = self.shade_filtered(&(edge.direction, edge.filter), candidates);
                edge.blend(behind, third.color)
            }
            None => behind,
        };
        centre.color = Vec3::select(first.lanes, first.mix(front, behind), centre.color);
        centre
    }

    /// The second and third shadings of an edge: [`Self::shade_along`] along the edge's
    /// directions with its filter, no hit record, saturated.
    ///
    /// Out of line, with one copy per path and capacity: inlined, each of its two calls
    /// would put a copy of the whole kernel into every copy of the kernel (one per pixel
    /// format a program renders). That makes `tests/paths_agree.rs`, which renders every
    /// path into four formats, a 202 s compile (rustc `-Z time-passes`, one core); out of
    /// line, 51 s. A firmware would pay for each copy in flash.
    ///
    /// Cold, because most packets have no edge: the code around the call keeps its
    /// registers (fewer instructions with anti-aliasing off, a few more with it on, than
    /// inlined: `docs/performance.md, "Choices measured"`). The
    /// arguments come as a reference to a copy: an address passed to a call keeps the value
    /// in memory on every path.
    #[cold]
    #[inline(never)]
    fn shade_filtered(
        &self,
        &(d, filter): &(Vec3<W::Lane>, Filter<W::Lane>),
        candidates: &[u16],
    ) -> (Packet<W::Lane>, W::Lane) {
        self.shade_along::<true>(d, candidates, Some(filter), false, true)
    }

    /// `edges`: for the packet whose centre rays are `u` (unit: `d`), behind which the
    /// nearest sphere is `hit_id` (`-1`: none) at distance `hit_t` (`f32::MAX` on a miss), the
    /// front outline within reach of each lane's centre among the `candidates` but `exclude`
    /// (per lane; `-1`: none), or `None` when no lane has one.
    #[inline(always)]
    pub(crate) fn edges(
        &self,
        row: &Row,
        u: Vec3<W::Lane>,
        d: Vec3<W::Lane>,
        (hit_id, hit_t): (W::Lane, W::Lane),
        exclude: W::Lane,
        candidates: &[u16],
    ) -> Option<Edge<W::Lane>> {
        let half = W::Lane::splat(0.5);
        let pixel = W::Lane::splat(self.pixel);
        let Front {
            sphere,
            inside,
            f,
            gx,
            gy,
        } = self.front_outline(row, u, (hit_id, hit_t), exclude, candidates);
        let lanes = W::Lane::splat(0.0).le(sphere);
        if !W::Lane::any(lanes) {
            return None;
        }
        // The outline's distance, coverage and shading direction stay written out here: as an
        // `#[inline(always)]` function of their own, they take anti-aliased frames more
        // instructions on the M4F (`docs/performance.md, "Choices measured"`).
        //
        // Signed distance to the outline in pixels, F/(|∇F|·pixel), and the coverage. Lanes
        // with no edge may divide by zero here: `blend` never reads them.
        let g = (gx * gx + gy * gy).sqrt();
        let dist = f / ((W::Lane::splat(2.0) * g) * pixel);
        let coverage = square_coverage(dist, gx.max(-gx) / g, gy.max(-gy) / g);
        // Where the centre ray misses the edge's sphere: the point c/2 inside the outline,
        // a step of (dist + c/2) pixels against the gradient.
        let step = ((dist + coverage * half) * pixel) / g;
        let pulled = u - Vec3::splat(self.right) * (gx * step) - Vec3::splat(self.up) * (gy * step);
        let pulled = pulled * (W::Lane::splat(1.0) / pulled.dot(pulled).sqrt());
        let only = W::Lane::and_not(lanes, inside);
        Some(Edge {
            lanes,
            inside,
            coverage,
            dist,
            normal: (gx / g, gy / g),
            direction: Vec3::select(only, pulled, d),
            filter: Filter {
                sphere,
                also: W::Lane::splat(-1.0),
                only,
            },
        })
    }

    /// The first half of [`Self::edges`] (its arguments but `d`): per lane, the outline
    /// within reach of the centre, of the sphere nearest in front there, and its conic `F`
    /// and half-gradient at the centre. Lanes with none have sphere `-1`.
    // `!(k > 0)` on purpose: a NaN takes the branch that has no silhouette.
    #[allow(clippy::neg_cmp_op_on_partial_ord)]
    #[inline(always)]
    fn front_outline(
        &self,
        row: &Row,
        u: Vec3<W::Lane>,
        (hit_id, hit_t): (W::Lane, W::Lane),
        exclude: W::Lane,
        candidates: &[u16],
    ) -> Front<W::Lane> {
        let zero = W::Lane::splat(0.0);
        let band = W::Lane::splat(2.0 * self.pixel * self.pixel);
        let x = u.dot(Vec3::splat(self.right));
        let y = W::Lane::splat(row.y);
        let uu = u.dot(u);
        let mut sphere = W::Lane::splat(-1.0);
        let mut depth = W::Lane::splat(f32::MAX);
        let mut inside = zero.lt(zero);
        let (mut f, mut gx, mut gy) = (zero, zero, zero);
        for &k in candidates {
            let Some(s) = self.spheres.get(k as usize) else {
                continue;
            };
            let o = &s.outline;
            // The eye inside or on the sphere: no silhouette.
            if !(o.k > 0.0) {
                continue;
            }
            let kk = W::Lane::splat(o.k);
            let along = Vec3::splat(-s.eye_offset).dot(u);
            let fk = kk * uu - along * along;
            let gxk = kk * x - along * W::Lane::splat(o.oc_right);
            let gyk = kk * y - along * W::Lane::splat(o.oc_up);
            // |F|/|∇F| < pixel/√2 (no straight edge farther away crosses the pixel), with
            // ∇F = 2g: F² < 2·pixel²·|g|². Centre in front of the eye.
            let near = W::Lane::and((fk * fk).lt(band * (gxk * gxk + gyk * gyk)), zero.lt(along));
            // …and within the larger sphere the spans are computed for: the first-order
            // distance can underrate the true one, and a pixel outside the spans would be
            // near in a packet that lists the sphere and not in one that does not.
            let in_spans = (W::Lane::splat(o.spans_k) * uu).le(along * along);
            let near = W::Lane::and(near, in_spans);
            let kf = W::Lane::splat(k as f32);
            let excluded = W::Lane::and(exclude.le(kf), kf.le(exclude));
            let near = W::Lane::and_not(near, excluded);
            if !W::Lane::any(near) {
                continue;
            }
            let is_hit = W::Lane::and(hit_id.le(kf), kf.le(hit_id));
            let dk = W::Lane::select(is_hit, hit_t, along / uu.sqrt());
            // A sphere the centre ray misses, nearer than what it hits, is in front there.
            let in_front = W::Lane::or(is_hit, W::Lane::and(zero.le(fk), dk.lt(hit_t)));
            let take = W::Lane::and(W::Lane::and(near, in_front), dk.lt(depth));
            sphere = W::Lane::select(take, kf, sphere);
            depth = W::Lane::select(take, dk, depth);
            inside = W::Lane::or(W::Lane::and(take, is_hit), W::Lane::and_not(inside, take));
            f = W::Lane::select(take, fk, f);
            gx = W::Lane::select(take, gxk, gx);
            gy = W::Lane::select(take, gyk, gy);
        }
        Front {
            sphere,
            inside,
            f,
            gx,
            gy,
        }
    }
}

/// Points per side of the grid [`Edge::coverage_left`] counts overlaps on.
const GRID: usize = 8;

/// The area of the unit pixel on the inside of a straight edge at signed distance `dist`
/// (pixels, positive outside) from its centre, the edge's unit normal being `(nx, ny)` up to
/// sign.
///
/// Projected on the normal, a uniform point of the square is the sum of two uniform
/// variables of widths `a = max(|nx|, |ny|)` and `b = min(…)`, whose density is a trapezoid:
/// the area beyond a distance `u ≥ 0` from the centre is `½ − u/a` up to `(a − b)/2`,
/// `((a + b)/2 − u)²/(2ab)` up to `(a + b)/2`, and 0 beyond. For an edge along a pixel side
/// (`b = 0`) this is the linear ramp `½ − dist`; for a diagonal, a quadratic one across
/// `±√2/2`.
#[inline(always)]
fn square_coverage<T: Lane>(dist: T, nx: T, ny: T) -> T {
    let (zero, half, one) = (T::splat(0.0), T::splat(0.5), T::splat(1.0));
    let a = nx.max(ny);
    let b = nx.min(ny);
    let u = dist.max(-dist);
    let linear = half - u / a;
    let corner = (half * (a + b) - u).max(zero);
    // `b` is 0 only where the quadratic piece is never taken: keep the division finite.
    let quadratic = (corner * corner) / ((T::splat(2.0) * a) * b.max(T::splat(1.0e-30)));
    let beyond = T::select((half * (a - b)).lt(u), quadratic, linear);
    T::select(zero.lt(dist), beyond, one - beyond)
}
