//! The `edges` stage of the float paths: analytic anti-aliasing of the spheres' silhouettes.
//!
//! A sphere's silhouette on the image plane is the conic `F(x, y) = k·|u|² − (oc·u)² = 0`
//! (`u = x·right + y·up + forward`, `oc = C − eye`, `k = |oc|² − r²`; `F < 0` inside), whose
//! gradient is `∇F = 2(k·x − (oc·u)(oc·right), k·y − (oc·u)(oc·up))`. The signed distance
//! from a pixel centre to the outline is `F/|∇F|` to first order, and the sphere covers
//! `c = clamp(½ − F/(|∇F|·pixel), 0, 1)` of the pixel: a one-pixel ramp across the outline,
//! exact for a straight edge through the pixel.
//!
//! Per lane, the *edge* is the front sphere whose outline lies within half a pixel of the
//! centre: the sphere the centre ray hits, or one it misses that lies nearer than what it
//! hits (by the distance to the ray's closest approach). A sphere the centre ray meets
//! behind the one it hits is hidden there, so its outline is no edge. The pixel is then
//! `c·front + (1 − c)·behind`, with one colour from the ordinary shading of the centre ray
//! and the other from a second shading:
//!
//! | the centre ray | front | behind |
//! |---|---|---|
//! | hits the edge's sphere | the centre ray's colour | the centre ray with that sphere left out |
//! | misses it | that sphere alone, along the ray through the point `c/2` inside the outline (the middle of the covered strip), taken at its closest approach if rounding makes it miss | the centre ray's colour |
//!
//! Everything is lane arithmetic on exactly specified operations, so the scalar and SIMD
//! paths stay bit-identical; pixels with no outline within half a pixel pay only the test
//! `F² < pixel²·|∇F/2|²` per candidate sphere and keep their colour bit for bit; packets with
//! no such pixel skip the rest. What this does not smooth: where two spheres intersect
//! (the curve is not an outline), and a pixel two outlines cross keeps the nearer one only.

use super::kernel::Packet;
use super::lane::Lane;
use super::prepare::{FloatPath, Prepared, Row};
use crate::real::Real;
use crate::vec3::Vec3;

/// Which spheres the second shading of an edge may hit, per lane: the edge's sphere alone
/// (`only`, where the centre ray misses it), or every candidate but that sphere.
#[derive(Clone, Copy)]
pub(crate) struct Filter<T: Lane> {
    /// The edge's sphere, as `f32`; `-1` on lanes with no edge.
    pub sphere: T,
    /// Lanes that shade the edge's sphere alone; the others leave it out.
    pub only: T::Mask,
}

impl<T: Lane> Filter<T> {
    /// [`nearest_hit`](super::kernel::nearest_hit) for candidate sphere `k` under the filter:
    /// lanes that may not hit `k` miss it, and `only` lanes hit it even where rounding puts
    /// their ray just outside it, at the closest approach (the outline itself).
    #[inline(always)]
    pub(crate) fn nearest_hit(
        &self,
        k: u16,
        oc: Vec3<T>,
        dir: Vec3<T>,
        radius_sq: T,
        eps: T,
    ) -> (T, T::Mask, Vec3<T>) {
        let zero = T::splat(0.0);
        let kf = T::splat(k as f32);
        let is_k = T::and(self.sphere.le(kf), kf.le(self.sphere));
        let forced = T::and(self.only, is_k);
        // The closest-approach form of the kernel's `nearest_hit`, with no early exit.
        let b = oc.dot(dir);
        let f = oc - dir * b;
        let disc = radius_sq - f.dot(f);
        let touches = zero.le(disc);
        let root = disc.max(zero).sqrt();
        let t_near = -b - root;
        let near = eps.lt(t_near);
        let t = T::select(near, t_near, -b + root);
        let offset = f + dir * T::select(near, -root, root);
        // Lanes that shade the edge's sphere alone hit nothing else; the others hit anything
        // but the edge's sphere.
        let allowed = T::select(
            self.only,
            T::select(is_k, T::splat(1.0), zero),
            T::select(is_k, zero, T::splat(1.0)),
        );
        let meets = T::and(T::or(touches, forced), eps.lt(t));
        (t, T::and(meets, zero.lt(allowed)), offset)
    }
}

/// What `edges` found on a packet's lanes.
pub(crate) struct Edge<T: Lane> {
    /// Lanes an outline crosses.
    lanes: T::Mask,
    /// Lanes whose centre ray hits the edge's sphere.
    inside: T::Mask,
    /// The edge sphere's coverage of the pixel, in `(0, 1)` on `lanes`.
    coverage: T,
    /// The unit directions of the second shading.
    pub direction: Vec3<T>,
    /// The spheres the second shading may hit.
    pub filter: Filter<T>,
}

impl<T: Lane> Edge<T> {
    /// The anti-aliased colour: `c·front + (1 − c)·behind` on edge lanes (see the table in
    /// the module docs), `centre` elsewhere; saturated at `f32::MAX` like `combine`.
    #[inline(always)]
    pub(crate) fn blend(&self, centre: Vec3<T>, second: Vec3<T>) -> Vec3<T> {
        let c = self.coverage;
        let rest = T::splat(1.0) - c;
        let cap = T::splat(f32::MAX);
        let front = Vec3::select(self.inside, centre, second);
        let behind = Vec3::select(self.inside, second, centre);
        let mix = |a: T, b: T| (a * c + b * rest).min(cap);
        let blended = Vec3::new(
            mix(front.x, behind.x),
            mix(front.y, behind.y),
            mix(front.z, behind.z),
        );
        Vec3::select(self.lanes, blended, centre)
    }
}

impl<W: FloatPath, const S: usize, const L: usize> Prepared<W, S, L> {
    /// The packet `centre` (the centre rays `u`, unit `d`, which hit at distance `t`) with
    /// its edge lanes anti-aliased, if anti-aliasing is on: `edges`, the second shading, and
    /// the blend.
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
        if self.antialias {
            if let Some(edge) = self.edges(row, u, d, centre.sphere, t, candidates) {
                let (second, _) =
                    self.shade_along(edge.direction, candidates, Some(edge.filter), false);
                centre.color = edge.blend(centre.color, second.color);
            }
        }
        centre
    }

    /// `edges`: for the packet whose centre rays are `u` (unit: `d`), which hit sphere `hit_id`
    /// (`-1`: none) at distance `hit_t`, the front outline within half a pixel of each lane's
    /// centre among the `candidates`, or `None` when no lane has one.
    // `!(k > 0)` on purpose: a NaN takes the branch that has no silhouette.
    #[allow(clippy::neg_cmp_op_on_partial_ord)]
    #[inline(always)]
    pub(crate) fn edges(
        &self,
        row: &Row,
        u: Vec3<W::Lane>,
        d: Vec3<W::Lane>,
        hit_id: W::Lane,
        hit_t: W::Lane,
        candidates: &[u16],
    ) -> Option<Edge<W::Lane>> {
        let zero = W::Lane::splat(0.0);
        let half = W::Lane::splat(0.5);
        let pixel = W::Lane::splat(self.pixel);
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
            if !W::Lane::any(near) {
                continue;
            }
            let kf = W::Lane::splat(k as f32);
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
        let lanes = zero.le(sphere);
        if !W::Lane::any(lanes) {
            return None;
        }
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
            direction: Vec3::select(only, pulled, d),
            filter: Filter { sphere, only },
        })
    }
}

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
