//! The `edges` stage of the fixed path: analytic anti-aliasing of the spheres' silhouettes
//! in integers (features `antialias` and `full-width`), the float paths' rule
//! (`src/float/edges.rs`) on the fixed formats.
//!
//! # The outline's distance
//!
//! Along the unit ray `d` of a pixel, a sphere with `oc = eye − C` has `b = oc·d`, the
//! closest approach `f = oc − b·d` and the discriminant `disc = r² − |f|²`, which the hit
//! test computes anyway: the outline is `disc = 0`, positive inside. With `u` the
//! unnormalized direction (`d = u/|u|`) and `S` its step for one pixel (`2·step_x` to the
//! right, `2·step_y` up), `∂b/∂S = (f·S)/|u|`, so the gradient of `disc` in pixels is
//!
//! ```text
//! ∇disc = (2b/|u|)·(f·S_x, f·S_y)        1/|u| = d·forward
//! ```
//!
//! (`forward` is the camera's unit axis and `u`'s forward part is 1). The signed distance
//! from the pixel centre to the outline, positive outside, is `−disc/|∇disc|` to first
//! order, and the outline's outward normal is `(f·S_x, f·S_y)/|…|` for a sphere in front
//! of the eye (`b < 0`). This is not the float paths' implicit function (`src/float/edges.rs`
//! takes `F = k·|u|² − (oc·u)²`), but both vanish on the same outline, so their first-order
//! distances agree to second order in the distance.
//!
//! # Formats
//!
//! `disc` is I32F32 and `f·S` an exact sum of 32×32→64 products (`S` held as 30-bit
//! mantissas with one shared power of two per frame). The distance is one 64-bit division
//! of `disc` by `2|b|·(d·forward)·|f·S|` taken to 40 bits, in Q16 pixels; the normal comes
//! from [`inv_sqrt`], in Q16. Coverage (the exact area of the square pixel inside a straight
//! edge, as on the float paths), the second edge's overlap on an 8×8 grid, and the blends
//! are Q16 too. Every step is integer arithmetic on exactly specified operations: the same
//! bits on every target.
//!
//! # Where it runs
//!
//! After a covered run is shaded as usual (by the narrow kernel or the full-width one), the
//! pixels of the run near an outline are tested (a band per sphere and row, two pixels up and
//! down and two columns each side of the outline, from the spans' row conic: `spans`'
//! `near_outline`; the others are left as they are): the centre ray's nearest hit and, for
//! every sphere whose span covers the pixel, the distance to that sphere's outline. A pixel
//! with no outline within `1/√2` of its centre keeps the run's pixel bit for bit; one with an
//! outline is shaded again by the full-width kernel and blended: the centre ray, the ray
//! behind the edge's sphere or the
//! ray pulled inside its outline, and where a second outline crosses the pixel, one more
//! (the table in `src/float/edges.rs`). The spans of an anti-aliased frame are the spheres'
//! screen rectangles, two pixels wider than the spheres on each side, not the outlines' row
//! spans: those are exact to a few columns, and a pixel outside every span is background
//! whatever its distance to an outline.

use super::kernel::ray;
use super::mul::{leading_zeros, mul_ii, mul_iu, mul_uu};
use super::narrow::Shaded;
use super::prepare::{FixedSphere, PreparedFixed};
use super::roots::{inv_sqrt, sqrt};
use super::vector::{dot_len_unit, dot_unit, each3, len_times_unit, length_sq, Unit, V3};
use crate::runs::Span;
use fixed::types::I16F48;

/// `1/√2` in Q16, rounded up: no straight edge farther from the centre crosses the pixel.
const REACH: u64 = 46_341;
/// One in Q16: a full pixel, full coverage, a colour channel at 1.
const ONE: i64 = 1 << 16;
/// Points per side of the grid [`Edge::coverage_left`] counts overlaps on.
const GRID: i64 = 8;

/// What the edge stage needs of a frame and a row, made once per row (not per run or per
/// pixel): the camera's pixel steps and axis, each sphere's columns near its outline, and
/// which spheres have an outline at all.
pub(super) struct EdgeRow<const S: usize> {
    /// `2·step_x` and `2·step_y` (one pixel right, one pixel up) as 30-bit mantissas…
    steps: [V3<i32>; 2],
    /// …times `2^shift` in I16F48.
    shift: u32,
    /// The camera's forward axis, unit.
    forward: V3<Unit>,
    /// Per sphere, the row's columns near its outline (see `spans`' `near_outline`).
    near: heapless::Vec<[Option<Span>; 2], S>,
    /// Per sphere, whether the eye is outside it (inside, it has no outline).
    outside: heapless::Vec<bool, S>,
}

/// The spheres a shading behind an edge leaves out: the edge's, and the first edge's when
/// this is the second.
#[derive(Clone, Copy)]
struct Without(usize, Option<usize>);

impl Without {
    #[inline(always)]
    fn keeps(self, k: usize) -> bool {
        k != self.0 && Some(k) != self.1
    }
}

/// The nearest outline within reach found so far by [`PreparedFixed::edge`].
#[derive(Clone, Copy)]
struct Candidate {
    sphere: usize,
    /// Whether it is the centre ray's hit.
    inside: bool,
    /// The distance along the ray: the hit's, or the closest approach's.
    depth: i64,
    /// Q16 pixels, as [`Edge::dist`].
    dist: i64,
    /// `f·S` for the steps right and up.
    h: (i64, i64),
}

/// An outline within reach of a pixel's centre.
struct Edge {
    /// The edge's sphere.
    sphere: usize,
    /// Whether the centre ray hits that sphere (its nearest hit).
    inside: bool,
    /// The sphere's coverage of the pixel, Q16 in `[0, 1]`.
    coverage: i64,
    /// Signed distance from the centre to the outline, Q16 pixels, positive outside.
    dist: i64,
    /// The outline's outward unit normal in pixel axes (`x` right, `y` up), Q16.
    normal: (i64, i64),
    /// The unnormalized direction of the edge's own shading where the centre ray misses
    /// its sphere: through the point `c/2` inside the outline.
    pulled: V3<I16F48>,
}

impl Edge {
    /// `c·front + (1 − c)·behind` per channel of U16F16 colours, each clamped to 1 first
    /// (a box filter of the displayed image averages clamped values).
    fn mix(&self, front: [u32; 3], behind: [u32; 3]) -> [u32; 3] {
        let c = self.coverage;
        let clamp = |v: u32| (v as i64).min(ONE);
        let mut out = [0u32; 3];
        for ((o, f), b) in out.iter_mut().zip(front).zip(behind) {
            *o = ((clamp(f) * c + clamp(b) * (ONE - c) + (ONE >> 1)) >> 16) as u32;
        }
        out
    }

    /// The edge's blend of `base`, the colour without its shading, and `shaded`, that
    /// shading's colour: `base` is in front where the centre ray hits the edge's sphere.
    fn blend(&self, base: [u32; 3], shaded: [u32; 3]) -> [u32; 3] {
        if self.inside {
            self.mix(base, shaded)
        } else {
            self.mix(shaded, base)
        }
    }

    /// The share of the part of the pixel this (front) edge leaves uncovered that `behind`
    /// covers, Q16: `(c_b − area(A ∩ B))/(1 − c_a)`, the overlap counted on an 8×8 grid of
    /// points, as on the float paths.
    fn coverage_left(&self, behind: &Edge) -> i64 {
        let (mut both, mut all) = (0i64, 0i64);
        let offset = |i: i64| ((2 * i + 1) << 16) / (2 * GRID) - (ONE >> 1);
        for i in 0..GRID {
            let oy = offset(i);
            let a_row = self.dist + ((self.normal.1 * oy) >> 16);
            let b_row = behind.dist + ((behind.normal.1 * oy) >> 16);
            for j in 0..GRID {
                let ox = offset(j);
                let in_b = b_row + ((behind.normal.0 * ox) >> 16) < 0;
                let in_a = a_row + ((self.normal.0 * ox) >> 16) < 0;
                all += in_b as i64;
                both += (in_a && in_b) as i64;
            }
        }
        // Unsigned divisions by divisors of at least 1: no division can fail.
        let shared = ((both as u64) << 16) / (all as u64).max(1);
        let left = (ONE - self.coverage).max(1) as u64;
        let rest = (ONE as u64).saturating_sub(shared);
        ((behind.coverage.max(0) as u64 * rest) / left).min(ONE as u64) as i64
    }
}

/// The area of the unit pixel inside a straight edge at signed distance `dist` (Q16 pixels,
/// positive outside) from its centre, with unit normal `(nx, ny)` (Q16, any signs): the
/// float paths' `square_coverage` (the trapezoid density of the pixel projected on the
/// normal) in Q16.
fn square_coverage(dist: i64, nx: i64, ny: i64) -> i64 {
    let (nx, ny) = (nx.abs(), ny.abs());
    let (a, b) = (nx.max(ny).max(1), nx.min(ny));
    let u = dist.abs();
    // Unsigned divisions by divisors of at least 1: no division can fail.
    let beyond = if 2 * u <= a - b {
        (ONE >> 1) - ((u as u64) << 16).div_ceil(a as u64).min(1 << 15) as i64
    } else {
        let corner = ((a + b) / 2 - u).max(0) as u64;
        // With b = 0 the corner is 0 wherever this branch is taken.
        (((corner * corner) << 15) / (a as u64 * b as u64).max(1)) as i64
    };
    if dist > 0 {
        beyond
    } else {
        ONE - beyond
    }
}

/// `v >> s` for a signed shift (left for negative `s`), saturating.
fn shift_signed(v: i64, s: i32) -> i64 {
    if s >= 0 {
        v >> s.min(63)
    } else {
        let l = (-s).min(63) as u32;
        let shifted = v.checked_shl(l).unwrap_or(0);
        if shifted >> l == v {
            shifted
        } else if v < 0 {
            i64::MIN
        } else {
            i64::MAX
        }
    }
}

/// The bit length of `v` (0 for 0).
fn bits(v: u64) -> u32 {
    64 - leading_zeros(v)
}

impl<const S: usize, const L: usize> PreparedFixed<S, L> {
    /// [`EdgeRow`] of row `y`, for [`Self::antialias_run`] on each of the row's runs.
    pub(super) fn edge_row(&self, y: u32) -> EdgeRow<S> {
        let sx = self.step_x.map(|c| c.to_bits().saturating_mul(2));
        let sy = self.step_y.map(|c| c.to_bits().saturating_mul(2));
        let largest = sx
            .iter()
            .chain(&sy)
            .map(|c| c.unsigned_abs())
            .max()
            .unwrap_or(0);
        let shift = bits(largest).saturating_sub(30);
        let mantissa = |v: V3<i64>| each3(|i| (v[i] >> shift) as i32);
        let full = Span {
            start: 0,
            end: self.width,
        };
        let (mut near, mut outside) = (heapless::Vec::new(), heapless::Vec::new());
        for s in &self.spheres {
            let bands = match s.bounds {
                Some(b) if self.use_spans => b.near_outline(y, self.height),
                Some(_) => [Some(full), None],
                None => [None, None],
            };
            let eye_out =
                length_sq(s.eye_offset.map(|v| v.to_bits() as i64)) > s.radius_sq.to_bits();
            // Same capacity as the sphere list: cannot fail.
            let pushed = near.push(bands).is_ok() && outside.push(eye_out).is_ok();
            debug_assert!(pushed, "more bands than spheres");
        }
        EdgeRow {
            steps: [mantissa(sx), mantissa(sy)],
            shift,
            // I16F48 to I2F30: the axis is unit, so it fits.
            forward: each3(|i| Unit::from_bits((self.forward[i].to_bits() >> 18) as i32)),
            near,
            outside,
        }
    }

    /// Anti-aliases the shaded run `run_pixels` from column `start` of row `y`, whose spans
    /// are `spans` and whose [`EdgeRow`] is `view` (see the module docs): pixels with an
    /// outline within reach are shaded again and blended, and `encode` turns their colour
    /// (and the centre ray's hit record) into the pixel.
    pub(super) fn antialias_run<P>(
        &self,
        (y, spans): (u32, &[Option<Span>]),
        view: &EdgeRow<S>,
        start: u32,
        run_pixels: &mut [P],
        encode: impl Fn([u32; 3], crate::pixel::HitRecord, u32) -> P,
    ) {
        // The centre rays step by one addition per pixel, exactly (as in the row driver).
        let advance = self.step_x.map(|c| c.to_bits().saturating_mul(2));
        let mut next = self.direction(start, y);
        for (px, column) in run_pixels.iter_mut().zip(start..) {
            let u = next;
            for (c, a) in next.iter_mut().zip(advance) {
                *c = I16F48::from_bits(c.to_bits().saturating_add(a));
            }
            let within = |s: &Option<Span>| s.is_some_and(|s| s.start <= column && column < s.end);
            if !view.near.iter().flatten().any(within) {
                continue;
            }
            let Some(d) = ray(u) else {
                continue;
            };
            let hit = self.hit(d, column, spans, |_| true);
            let centre = hit.map(|(k, _, t)| (k, t));
            let Some(first) = self.edge(view, (u, d), centre, None, column, spans) else {
                continue;
            };

            let (base, record) = match hit {
                Some((k, sphere, t)) => {
                    let s = self.shade_edge(k, sphere, d, t);
                    (s.color, s.hit)
                }
                None => (self.background, Default::default()),
            };
            // The second shading: behind the edge's sphere, or that sphere alone.
            let (second, second_hit) = if first.inside {
                self.shade_filtered(d, Without(first.sphere, None), column, spans)
            } else {
                self.shade_alone(first.sphere, first.pulled, column, spans)
            };
            let (front, behind, behind_hit) = if first.inside {
                (base, second, second_hit)
            } else {
                (second, base, centre)
            };
            let behind =
                match self.edge(view, (u, d), behind_hit, Some(first.sphere), column, spans) {
                    Some(mut edge) => {
                        edge.coverage = first.coverage_left(&edge);
                        let (third, _) = if edge.inside {
                            let without = Without(edge.sphere, Some(first.sphere));
                            self.shade_filtered(d, without, column, spans)
                        } else {
                            self.shade_alone(edge.sphere, edge.pulled, column, spans)
                        };
                        edge.blend(behind, third)
                    }
                    None => behind,
                };
            *px = encode(first.mix(front, behind), record, column);
        }
    }

    /// The full-width kernel's stages after the hit (no hit record's shadow bits): one copy
    /// out of line for the three shadings of an edge pixel, which would otherwise each hold
    /// the whole lighting code in the firmware's flash.
    #[inline(never)]
    fn shade_edge(&self, k: usize, sphere: &FixedSphere, d: V3<Unit>, t: i64) -> Shaded {
        self.shade_hit(k, sphere, d, t, false)
    }

    /// The full-width shading along `d` of the spheres `filter` keeps, and the hit (sphere,
    /// distance); the background colour on a miss.
    #[inline(never)]
    fn shade_filtered(
        &self,
        d: V3<Unit>,
        filter: Without,
        x: u32,
        spans: &[Option<Span>],
    ) -> ([u32; 3], Option<(usize, i64)>) {
        match self.hit(d, x, spans, |k| filter.keeps(k)) {
            Some((k, sphere, t)) => (self.shade_edge(k, sphere, d, t).color, Some((k, t))),
            None => (self.background, None),
        }
    }

    /// Sphere `k` alone (its span covers `x`), shaded along the unnormalized direction `u`
    /// (inside its outline); where rounding makes that ray miss, at the ray's closest
    /// approach to the centre.
    #[inline(never)]
    fn shade_alone(
        &self,
        k: usize,
        u: V3<I16F48>,
        x: u32,
        spans: &[Option<Span>],
    ) -> ([u32; 3], Option<(usize, i64)>) {
        let (Some(sphere), Some(d)) = (self.spheres.get(k), ray(u)) else {
            return (self.background, None);
        };
        let t = match self.hit(d, x, spans, |j| j == k) {
            Some((_, _, t)) => t,
            None => (-dot_len_unit(sphere.eye_offset, d)).max(0),
        };
        (self.shade_edge(k, sphere, d, t).color, Some((k, t)))
    }

    /// The front outline within reach of the centre of pixel `x` (centre ray `u`, unit
    /// `d`), behind which the nearest sphere is `hit` (sphere, distance; `None`: none),
    /// among the spheres whose span covers `x` but `exclude`: the nearest outline
    /// (`front_outline`), its outward normal, the pixel's coverage, and the ray pulled
    /// inside it (`pulled_inside`).
    #[allow(clippy::too_many_arguments)]
    fn edge(
        &self,
        view: &EdgeRow<S>,
        (u, d): (V3<I16F48>, V3<Unit>),
        hit: Option<(usize, i64)>,
        exclude: Option<usize>,
        x: u32,
        spans: &[Option<Span>],
    ) -> Option<Edge> {
        let Candidate {
            sphere,
            inside,
            dist,
            h,
            ..
        } = self.front_outline(view, d, hit, exclude, x, spans)?;
        let normal = outline_normal(h)?;
        let coverage = square_coverage(dist, normal.0, normal.1);
        let pulled = pulled_inside(view, u, dist, coverage, normal);
        Some(Edge {
            sphere,
            inside,
            coverage,
            dist,
            normal,
            pulled,
        })
    }

    /// The nearest outline in front of `hit` within reach of pixel `x`'s centre, along the
    /// unit ray `d`, among the spheres whose span covers `x` but `exclude`: the first stage
    /// of [`Self::edge`].
    #[inline(always)]
    fn front_outline(
        &self,
        view: &EdgeRow<S>,
        d: V3<Unit>,
        hit: Option<(usize, i64)>,
        exclude: Option<usize>,
        x: u32,
        spans: &[Option<Span>],
    ) -> Option<Candidate> {
        // 1/|u| in Q30, in (0, 1].
        let c = dot_unit(d, view.forward).clamp(1, 1 << 30) as u32;
        let hit_t = hit.map_or(i64::MAX, |(_, t)| t);
        let mut best: Option<Candidate> = None;
        for (k, (s, span)) in self.spheres.iter().zip(spans).enumerate() {
            if !span.is_some_and(|span| span.start <= x && x < span.end) || Some(k) == exclude {
                continue;
            }
            let oc = s.eye_offset;
            let r2 = s.radius_sq.to_bits();
            // The eye inside or on the sphere: no outline.
            if !view.outside.get(k).copied().unwrap_or(false) {
                continue;
            }
            let b = dot_len_unit(oc, d);
            // The closest approach behind the eye: no outline in front.
            if b >= 0 {
                continue;
            }
            let f = each3(|i| (oc[i].to_bits() as i64).saturating_sub(len_times_unit(b, d[i])));
            let disc = r2.saturating_sub(length_sq(f));
            // |f| < 2¹⁵ units: each component fits 32 bits.
            let f32s = f.map(|c| c.clamp(i32::MIN as i64, i32::MAX as i64) as i32);
            let dot = |s: &V3<i32>| {
                mul_ii(f32s[0], s[0])
                    .saturating_add(mul_ii(f32s[1], s[1]))
                    .saturating_add(mul_ii(f32s[2], s[2]))
            };
            let h = [dot(&view.steps[0]), dot(&view.steps[1])];
            let Some(dist) = distance(disc, b, c, h, view.shift) else {
                continue;
            };
            let is_hit = hit.is_some_and(|(j, _)| j == k);
            let depth = if is_hit { hit_t } else { -b };
            let in_front = is_hit || (disc <= 0 && depth < hit_t);
            if in_front && best.is_none_or(|b| depth < b.depth) {
                best = Some(Candidate {
                    sphere: k,
                    inside: is_hit,
                    depth,
                    dist,
                    h: (h[0], h[1]),
                });
            }
        }
        best
    }
}

/// The outline's outward normal in Q16 pixels, `h/|h|` from 30-bit mantissas of
/// `h = (f·S_x, f·S_y)`.
#[inline(always)]
fn outline_normal((hx, hy): (i64, i64)) -> Option<(i64, i64)> {
    let top = bits(hx.unsigned_abs().max(hy.unsigned_abs())).saturating_sub(30);
    let (mx, my) = ((hx >> top) as i32, (hy >> top) as i32);
    let (y, shift) = inv_sqrt(mul_ii(mx, mx) as u64 + mul_ii(my, my) as u64)?;
    let unit = |m: i32| mul_iu(m, y) >> (shift - 16);
    Some((unit(mx), unit(my)))
}

/// The centre ray `u` pulled inside the outline, for the shading of its sphere alone: moved
/// by `−(dist + coverage/2)·normal` pixels along the row's steps, to the point half the
/// pixel's coverage inside the outline.
#[inline(always)]
fn pulled_inside<const S: usize>(
    view: &EdgeRow<S>,
    u: V3<I16F48>,
    dist: i64,
    coverage: i64,
    normal: (i64, i64),
) -> V3<I16F48> {
    // The point c/2 inside the outline: a step of −(dist + c/2)·normal pixels.
    let back = dist + coverage / 2;
    let delta = (-((back * normal.0) >> 16), -((back * normal.1) >> 16));
    let [right, up] = &view.steps;
    let along = |d: i64, s: i32| {
        shift_signed(
            mul_ii(d.clamp(-4 * ONE, 4 * ONE) as i32, s),
            16 - view.shift as i32,
        )
    };
    each3(|i| {
        let v = u[i].to_bits().saturating_add(along(delta.0, right[i]));
        I16F48::from_bits(v.saturating_add(along(delta.1, up[i])))
    })
}

/// The signed distance in Q16 pixels from a pixel's centre to a sphere's outline,
/// `−disc/(2|b|·c·|h|)` (see the module docs: `disc` I32F32, `b` I16F16, `c = 1/|u|` Q30,
/// `h = f·S` with `16 + 48 − shift` fraction bits), if it is within [`REACH`].
fn distance(disc: i64, b: i64, c: u32, h: [i64; 2], shift: u32) -> Option<i64> {
    let (hx, hy) = (h[0], h[1]);
    let top = bits(hx.unsigned_abs().max(hy.unsigned_abs()));
    if top == 0 {
        return None;
    }
    let sh = top.saturating_sub(30);
    let (mx, my) = ((hx >> sh) as i32, (hy >> sh) as i32);
    // |h| = root·2^sh, root < 2^31.
    let root = sqrt(mul_ii(mx, mx) as u64 + mul_ii(my, my) as u64);
    // |b|·c, Q46, to 32 bits.
    let bc = mul_uu(b.unsigned_abs().min(u32::MAX as u64) as u32, c);
    let bz = bits(bc).saturating_sub(32);
    let p = mul_uu((bc >> bz) as u32, root.min(u32::MAX as u64) as u32);
    let pz = bits(p).saturating_sub(40);
    let p = p >> pz;
    if p == 0 {
        return None;
    }
    // disc·2⁻³² / (2·bc·2^bz·2⁻⁴⁶ · root·2^sh·2^-(64 − shift)) in Q16, p = bc·root·2^-(bz+pz):
    // −disc·2^e/p with e = 16 − 32 + 46 + 64 − shift − 1 − sh − bz − pz.
    let e = 93 - shift as i32 - sh as i32 - bz as i32 - pz as i32;
    let magnitude = disc.unsigned_abs();
    // |dist| < REACH ⇔ |disc|·2^e < REACH·p (p < 2⁴⁰: no overflow on the right).
    let limit = REACH * p;
    let num = if e >= 0 {
        let e = e as u32;
        if magnitude == 0 {
            0
        } else if e >= 63 || magnitude > (limit >> e) {
            return None;
        } else {
            magnitude << e
        }
    } else {
        magnitude >> (-e).min(63) as u32
    };
    let q = num / p;
    if q >= REACH {
        return None;
    }
    let q = q as i64;
    Some(if disc > 0 { -q } else { q })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The area of the unit pixel with `(x, y)·n < −dist` (inside), counted on a fine grid:
    /// independent of the trapezoid formula.
    fn counted(dist: f64, nx: f64, ny: f64) -> f64 {
        const N: i32 = 400;
        let mut inside = 0;
        for i in 0..N {
            for j in 0..N {
                let x = (i as f64 + 0.5) / N as f64 - 0.5;
                let y = (j as f64 + 0.5) / N as f64 - 0.5;
                inside += (x * nx + y * ny + dist < 0.0) as i32;
            }
        }
        inside as f64 / (N * N) as f64
    }

    #[test]
    fn coverage_is_the_area_inside_a_straight_edge() {
        let q16 = |v: f64| (v * 65536.0).round() as i64;
        for degrees in [0.0f64, 10.0, 30.0, 45.0, 60.0, 80.0, 90.0, 135.0, 200.0] {
            let (ny, nx) = degrees.to_radians().sin_cos();
            for step in -8..=8 {
                let dist = step as f64 * 0.1;
                let got = square_coverage(q16(dist), q16(nx), q16(ny)) as f64 / 65536.0;
                let want = counted(dist, nx, ny);
                assert!(
                    (got - want).abs() < 3e-3,
                    "{degrees}°, dist {dist}: {got} against {want}"
                );
            }
        }
    }

    #[test]
    fn the_second_edge_keeps_only_what_the_first_leaves() {
        let edge = |dist: f64, nx: f64, ny: f64| {
            let q16 = |v: f64| (v * 65536.0).round() as i64;
            Edge {
                sphere: 0,
                inside: false,
                coverage: square_coverage(q16(dist), q16(nx), q16(ny)),
                dist: q16(dist),
                normal: (q16(nx), q16(ny)),
                pulled: [I16F48::ZERO; 3],
            }
        };
        // Two edges on opposite sides (a gap between two spheres): nothing shared.
        let (left, right) = (edge(0.25, -1.0, 0.0), edge(0.25, 1.0, 0.0));
        let share = left.coverage_left(&right) as f64 / 65536.0;
        let expected = 0.25 / (1.0 - 0.25);
        assert!(
            (share - expected).abs() < 0.01,
            "{share} against {expected}"
        );
        // An edge over a parallel one it covers entirely: nothing left.
        let (front, behind) = (edge(-0.25, 1.0, 0.0), edge(0.0, 1.0, 0.0));
        assert_eq!(front.coverage_left(&behind), 0);
        // Blends clamp each colour to 1 and weigh by the coverage.
        let half = edge(0.0, 1.0, 0.0);
        assert_eq!(half.coverage, 1 << 15);
        assert_eq!(
            half.mix([1 << 17, 0, 1 << 16], [0, 0, 1 << 16]),
            [1 << 15, 0, 1 << 16]
        );
    }

    #[test]
    fn distances_have_the_outline_sign_and_stay_within_reach() {
        // disc = 0: on the outline.
        assert_eq!(distance(0, -(1 << 20), 1 << 30, [1 << 40, 0], 10), Some(0));
        // Inside (disc > 0) is negative, outside positive, and beyond reach is none.
        let d_in = distance(1 << 20, -(1 << 20), 1 << 30, [1 << 40, 0], 10).unwrap();
        let d_out = distance(-(1 << 20), -(1 << 20), 1 << 30, [1 << 40, 0], 10).unwrap();
        assert!(d_in < 0 && d_out > 0 && d_in == -d_out, "{d_in} {d_out}");
        // disc 2⁻¹² units², b 16 units, 1/|u| = 1, |f·S| 2⁻¹⁴ units a pixel (54 fraction
        // bits): −2⁻¹²/(2·16·2⁻¹⁴) = −⅛ pixel.
        assert_eq!(d_in, -(1 << 13));
        assert_eq!(
            distance(1 << 40, -(1 << 20), 1 << 30, [1 << 40, 0], 10),
            None
        );
        // No gradient: no distance.
        assert_eq!(distance(0, -(1 << 20), 1 << 30, [0, 0], 10), None);
    }
}
