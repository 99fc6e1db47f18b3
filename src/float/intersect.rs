//! The ray–sphere tests of the float kernels, in closest-approach form: the nearest hit
//! ([`nearest_hit`], the general kernel's `hit`), the shadow test ([`meets`], the general
//! kernel's `shadow` and the narrow kernel's caster tests) and the nearest hit under a
//! [`Filter`] (the second and third shadings of an anti-aliased edge).
//!
//! Each test starts from the ray's closest approach to the centre, `f = oc − (oc·dir)·dir`
//! and `disc = r² − f·f`, not from the quadratic's coefficients: the hit point's offset from
//! the centre then comes out at the sphere's radius to within a rounding (see
//! [`nearest_hit`]), and the shadow test decides from signs and squares with no square root
//! (see [`meets`]). They are a file of their own because three parts of the float paths call
//! them (the general kernel's stages, the narrow kernel's caster tests, the `edges` stage)
//! and none of those needs anything else of another.

use super::lane::Lane;
use crate::vec3::Vec3;

/// Which spheres an edge's extra shading may hit, per lane: the edge's sphere alone
/// (`only` lanes, where the centre ray misses it), or every candidate but the edge's sphere
/// and `also` (an edge in front of it, already accounted for).
// Built only by the `edges` stage.
#[cfg_attr(not(feature = "antialias"), allow(dead_code))]
#[derive(Clone, Copy)]
pub(crate) struct Filter<T: Lane> {
    /// The edge's sphere, as `f32`; `-1` on lanes with no edge.
    pub sphere: T,
    /// A sphere the lanes that are not `only` leave out as well; `-1`: none.
    pub also: T,
    /// Lanes that shade the edge's sphere alone.
    pub only: T::Mask,
}

#[cfg_attr(not(feature = "antialias"), allow(dead_code))]
impl<T: Lane> Filter<T> {
    /// [`nearest_hit`] for candidate sphere `k` under the filter: lanes that may not hit `k`
    /// miss it, and `only` lanes hit it even where rounding puts their ray just outside it,
    /// at the closest approach (the outline itself).
    #[inline(always)]
    pub(crate) fn nearest_hit(
        &self,
        k: u16,
        oc: Vec3<T>,
        dir: Vec3<T>,
        radius_sq: T,
        eps: T,
    ) -> (T, T::Mask, Vec3<T>) {
        let (zero, one) = (T::splat(0.0), T::splat(1.0));
        let kf = T::splat(k as f32);
        let is = |v: T| T::and(v.le(kf), kf.le(v));
        let is_k = is(self.sphere);
        let forced = T::and(self.only, is_k);
        // The closest-approach form of `nearest_hit`, with no early exit.
        let b = oc.dot(dir);
        let f = oc - dir * b;
        let disc = radius_sq - f.dot(f);
        let touches = zero.le(disc);
        let (t, offset) = nearer_root(b, f, disc, dir, eps);
        let left_out = T::or(is_k, is(self.also));
        let allowed = T::select(
            self.only,
            T::select(is_k, one, zero),
            T::select(left_out, zero, one),
        );
        let meets = T::and(T::or(touches, forced), eps.lt(t));
        (t, T::and(meets, zero.lt(allowed)), offset)
    }
}

/// Nearest intersection with `t > ε` of the ray `origin + t·dir` (`dir` unit) with the sphere
/// at offset `oc = origin − center`: `(t, hit, offset)`, where `offset` is the hit point
/// relative to the centre.
///
/// The offset is not computed as `origin + t·dir − center`: with the eye ten or more radii
/// away, `t` carries an absolute error of a few `ulp(|oc|)`, and the resulting normal would
/// be off unit length by about `|oc|·2⁻²³/r`, which `max(0, R·V)^n` amplifies `n` times
/// (a 1 % error at `n = 1250`). Instead it is `f ∓ √disc·dir`, from the closest-approach
/// vector `f = oc − (oc·dir)·dir` and `disc = r² − f·f`: its squared length is `f·f + disc
/// = r²` up to one rounding, so the normal is unit length to within a few `f32` ulps.
#[inline(always)]
pub(crate) fn nearest_hit<T: Lane>(
    oc: Vec3<T>,
    dir: Vec3<T>,
    radius_sq: T,
    eps: T,
) -> (T, T::Mask, Vec3<T>) {
    let zero = T::splat(0.0);
    let Some((b, f, disc, touches)) = closest_approach(oc, dir, radius_sq) else {
        // No lane meets the sphere: skip the square root (the mask is all false, so the
        // caller reads neither `t` nor `offset`).
        return (zero, T::lt(zero, zero), oc);
    };
    let (t, offset) = nearer_root(b, f, disc, dir, eps);
    (t, T::and(touches, eps.lt(t)), offset)
}

/// From the closest-approach quantities (`b`, `f`, `disc`, see [`closest_approach`]): the
/// near root `t = −b − √disc` where it lies beyond `eps`, the far one otherwise, and the hit
/// point's offset from the centre, `f ∓ √disc·dir` (see [`nearest_hit`]). A negative `disc`
/// counts as 0: the point of closest approach.
#[inline(always)]
fn nearer_root<T: Lane>(b: T, f: Vec3<T>, disc: T, dir: Vec3<T>, eps: T) -> (T, Vec3<T>) {
    let root = disc.max(T::splat(0.0)).sqrt();
    let t_near = -b - root;
    let near = eps.lt(t_near);
    let t = T::select(near, t_near, -b + root);
    (t, f + dir * T::select(near, -root, root))
}

/// The closest-approach quantities of the ray `origin + t·dir` (`dir` unit) and the sphere at
/// `oc = origin − center`: `b = oc·dir`, `f = oc − b·dir`, `disc = r² − |f|²` and the lanes
/// with `disc ≥ 0`; `None` when no lane has.
#[inline(always)]
fn closest_approach<T: Lane>(
    oc: Vec3<T>,
    dir: Vec3<T>,
    radius_sq: T,
) -> Option<(T, Vec3<T>, T, T::Mask)> {
    let b = oc.dot(dir);
    let f = oc - dir * b;
    let disc = radius_sq - f.dot(f);
    let touches = T::splat(0.0).le(disc);
    T::any(touches).then_some((b, f, disc, touches))
}

/// Whether the ray `origin + t·dir` (`dir` unit, `oc = origin − center`) meets the sphere at
/// some `ε < t < t_max` (`t_max = None`: no end): the shadow test. It decides from the signs
/// and squares of `b = oc·dir`, `disc = r² − |oc − b·dir|²` and the bounds, with no square
/// root, by
///
/// | condition | holds exactly when |
/// |---|---|
/// | `t_near = −b − √disc > ε` | `b + ε < 0` and `disc < (b + ε)²` |
/// | `t_far = −b + √disc > ε` | `b + ε < 0` or `disc > (b + ε)²` |
/// | `t_near < t_max` | `b + t_max > 0` or `disc > (b + t_max)²` |
/// | `t_far < t_max` | `b + t_max > 0` and `disc < (b + t_max)²` |
///
/// and takes, as [`nearest_hit`] does, the near root when it lies beyond `ε` and the far
/// root otherwise. A square that overflows to infinity keeps every line of the table true
/// to its left side. Without `t_max` the last two lines hold for every ray (they do for
/// `t_max = f32::MAX` too, with `b` and `disc` bounded by the scene's coordinates), and the
/// test is `t_far > ε`: the near root's line implies the far root's.
#[inline(always)]
pub(crate) fn meets<T: Lane>(
    oc: Vec3<T>,
    dir: Vec3<T>,
    radius_sq: T,
    eps: T,
    t_max: Option<T>,
) -> T::Mask {
    let zero = T::splat(0.0);
    let Some((b, _, disc, touches)) = closest_approach(oc, dir, radius_sq) else {
        return T::lt(zero, zero);
    };
    let be = b + eps;
    let be2 = be * be;
    let far = T::or(be.lt(zero), be2.lt(disc));
    let Some(t_max) = t_max else {
        return T::and(touches, far);
    };
    let near = T::and(be.lt(zero), disc.lt(be2));
    let bm = b + t_max;
    let bm2 = bm * bm;
    let near_before = T::or(zero.lt(bm), bm2.lt(disc));
    let far_before = T::and(zero.lt(bm), disc.lt(bm2));
    let by_near = T::and(near, near_before);
    let by_far = T::and(T::and_not(far, near), far_before);
    T::and(touches, T::or(by_near, by_far))
}
