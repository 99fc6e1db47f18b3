//! The prepare's checked conversions: the scene's `f32` points, directions, levels and
//! scale to the fixed formats, each refusal an [`RenderError::OutOfFixedRange`] naming the
//! item and field.
//!
//! They are the prepare's only rounding of scene numbers, exact `f32` arithmetic followed by
//! [`super::convert`]'s exact conversions, so that every target gets the same bits; kept
//! apart from the prepare's order of work (`prepare`), which calls them for every item.

use super::convert::{fixed_bits, fixed_bits_i32};
use super::mul::{dot_ii, mul_ii};
use super::vector::{Len, Unit, V3};
use crate::render::RenderError;
use crate::scene::{Item, Scene};
use crate::vec3::Vec3;
use fixed::types::{I16F48, U16F16};

/// The scene is scaled by a power of two so that its extent is below `2^EXTENT_LOG2` units.
pub(crate) const EXTENT_LOG2: i32 = 13;
/// The largest scale, `2¹⁹`: keeps the ray epsilon (`10⁻⁴` for scenes smaller than one unit)
/// below 64 units.
pub(crate) const MAX_SCALE_LOG2: i32 = 19;

/// Smallest sphere radius after scaling, in units (`2¹⁶` raw I16F16 steps): normals then
/// carry at least 16 bits. In scene terms: a radius at least `2⁻¹³` of the scene's extent.
pub const MIN_SCALED_RADIUS: f32 = 1.0;
/// Largest `tan(vfov/2)·max(1, width/height)`: keeps primary-ray directions within ±256.
pub const MAX_PLANE_SCALE: f32 = 127.0;
/// Largest `kd·albedo`, `ks` and distant-light `colour·intensity` per channel: they are
/// U16F16 and two of them multiply and add without wrapping.
pub const MAX_LEVEL: f32 = 32_767.0;

pub(super) fn out_of_range(item: Item, field: &'static str) -> RenderError {
    RenderError::OutOfFixedRange {
        item,
        field,
        beside: None,
    }
}

/// The refusal of sphere `sphere`, whose radius is below `2⁻¹³` of the scene's extent: it also
/// names the largest sphere (a floor sphere, say) when that is another and reaches at least
/// half as far as the camera, so that its size is what sets the extent. In integers: a
/// finite `f32`'s magnitude orders as its bits, and doubling it adds `2²³` to them. Out of
/// line: only refused scenes reach it.
#[inline(never)]
pub(super) fn small_beside_extent<const S: usize, const L: usize>(
    scene: &Scene<S, L>,
    sphere: usize,
) -> RenderError {
    let magnitude = |v: f32| v.to_bits() & 0x7fff_ffff;
    let eye = scene.camera().position;
    let camera = magnitude(eye.x).max(magnitude(eye.y)).max(magnitude(eye.z));
    let (mut largest, mut beside) = (0, None);
    for (i, s) in scene.spheres().iter().enumerate() {
        if magnitude(s.radius) > largest {
            largest = magnitude(s.radius);
            beside = u16::try_from(i).ok();
        }
    }
    if beside.map(usize::from) == Some(sphere) || largest + (1 << 23) < camera {
        beside = None;
    }
    RenderError::OutOfFixedRange {
        item: Item::Sphere(sphere),
        field: "radius",
        beside,
    }
}

/// `v·scale` per component in fixed point with `frac` fraction bits ([`fixed_bits`]), if
/// each is within `lo..=hi`. Out of line: every point, colour and direction of the prepare
/// goes through it.
#[inline(never)]
pub(super) fn scaled_bits(
    v: [f32; 3],
    scale: f32,
    frac: u32,
    (lo, hi): (i64, i64),
) -> Option<[i64; 3]> {
    let mut out = [0i64; 3];
    for (o, c) in out.iter_mut().zip(v) {
        *o = fixed_bits(c * scale, frac).filter(|b| (lo..=hi).contains(b))?;
    }
    Some(out)
}

pub(super) fn to_len(
    v: Vec3,
    scale: f32,
    item: Item,
    field: &'static str,
) -> Result<V3<Len>, RenderError> {
    let range = (i32::MIN as i64, i32::MAX as i64);
    scaled_bits([v.x, v.y, v.z], scale, 16, range)
        .map(|b| b.map(|c| Len::from_bits(c as i32)))
        .ok_or(out_of_range(item, field))
}

pub(super) fn to_wide(v: Vec3, scale: f32) -> Result<V3<I16F48>, RenderError> {
    scaled_bits([v.x, v.y, v.z], scale, 48, (i64::MIN, i64::MAX))
        .map(|b| b.map(I16F48::from_bits))
        .ok_or(out_of_range(Item::Camera, "vfov"))
}

/// The I2F30 unit vector of `d`, a unit vector in `f32` (within `2⁻²³` of unit length):
/// its components rounded to 30 bits (each at most about 1, which I2F30 holds: no
/// saturation is needed, and a component that did not convert, which no unit vector has,
/// would read as 0), then one Newton step toward unit length, `v·(1 − ε/2)` for
/// `|v|² = 1 + ε`, which leaves it within `2⁻⁴⁰` of unit length before the components'
/// rounding. Exact integer arithmetic after the conversion, so the same bits on every
/// target; a few products instead of the general normalization, for a vector already
/// within a few ulps of unit length. Inlined on ARMv6-M, where its caller is too (see
/// `prepare_fields`): smaller there.
#[cfg_attr(shadeline_short_mul, inline(always))]
#[cfg_attr(not(shadeline_short_mul), inline(never))]
pub(super) fn unit_q30(d: Vec3) -> V3<Unit> {
    let v = [d.x, d.y, d.z].map(|c| fixed_bits_i32(c, 30).unwrap_or(0));
    let len2 = dot_ii(v, v);
    // ε = |v|² − 1 in Q60 (|ε| < 2⁻²¹: the f32 vector's rounding and the 30-bit one), then
    // ε/2 in Q51, which holds |ε| < 2⁻²⁰ in an i32; c·ε/2 is then below 2⁶⁰.
    let half_eps = ((len2 - (1 << 60)) >> 10).clamp(-(1 << 30), 1 << 30) as i32;
    // |c·ε/2| < 2¹⁰ and |c| ≤ 2³⁰: the difference fits I2F30.
    v.map(|c| Unit::from_bits(c - (mul_ii(c, half_eps) >> 51) as i32))
}

/// Per-channel levels checked against [`MAX_LEVEL`]: U16F16 bits up to `MAX_LEVEL·2¹⁶`,
/// which is where the `f32` levels up to `MAX_LEVEL` round to (the next `f32` above it,
/// `MAX_LEVEL + 2⁻⁹`, rounds above). A scene's colours and factors are checked
/// non-negative, and so are their products; a negative level is refused all the same,
/// unless it rounds to zero.
pub(super) fn to_levels(
    c: [f32; 3],
    item: Item,
    field: &'static str,
) -> Result<V3<U16F16>, RenderError> {
    const MAX_BITS: i64 = (MAX_LEVEL as i64) << 16;
    scaled_bits(c, 1.0, 16, (0, MAX_BITS))
        .map(|b| b.map(|c| U16F16::from_bits(c as u32)))
        .ok_or(out_of_range(item, field))
}

/// `2^k` as an `f32`, for `k` in `-126..=127`.
pub(super) fn pow2(k: i32) -> f32 {
    f32::from_bits(((k + 127).clamp(1, 254) as u32) << 23)
}

/// The power of two `k` such that the scene's extent times `2^k` is below `2^EXTENT_LOG2`
/// units, as large as possible up to [`MAX_SCALE_LOG2`].
pub(super) fn scale_log2<const S: usize, const L: usize>(scene: &Scene<S, L>) -> i32 {
    let extent = scene.extent();
    // extent = f·2^e with f in [½, 1): extent·2^(EXTENT_LOG2 − e) < 2^EXTENT_LOG2.
    let (_, e) = libm::frexpf(extent);
    (EXTENT_LOG2 - e).min(MAX_SCALE_LOG2)
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;

    /// The light's unit vector, for directions all around the sphere (a xorshift stream)
    /// and along the axes and diagonals: each component within one step of 2⁻³⁰ of the
    /// exact (`f64`) unit vector along the same 30-bit components (the general
    /// normalization, `vector::normalize`, is within 1.94 steps on the same inputs), so of
    /// unit length within `2⁻²⁸`. Both keep the `f32` unit vector's own direction, within
    /// about `2⁻²⁴` of the scene's.
    #[test]
    fn unit_q30_is_the_unit_vector_to_a_step() {
        let mut x = 0x2545_f491_4f6c_dd1du64;
        let mut next = move || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            (x >> 40) as f32 / (1u64 << 23) as f32 - 1.0
        };
        let mut dirs: std::vec::Vec<Vec3> = (0..20_000)
            .map(|_| Vec3::new(next(), next(), next()))
            .collect();
        for (a, b, c) in [
            (1.0, 0.0, 0.0),
            (0.0, -1.0, 0.0),
            (1.0, 1.0, 1.0),
            (-1.0, 1e-6, 0.5),
        ] {
            dirs.push(Vec3::new(a, b, c));
        }
        let (mut worst_len, mut worst_step) = (0i64, 0.0f64);
        for d in dirs {
            let Some(unit) = d.normalized() else {
                continue;
            };
            let got = unit_q30(unit);
            let len2: i64 = got.iter().map(|c| mul_ii(c.to_bits(), c.to_bits())).sum();
            worst_len = worst_len.max((len2 - (1 << 60)).abs());
            let q30 = [unit.x, unit.y, unit.z].map(|c| fixed_bits_i32(c, 30).unwrap() as f64);
            let len = (q30[0] * q30[0] + q30[1] * q30[1] + q30[2] * q30[2]).sqrt();
            for (g, c) in got.iter().zip(q30) {
                let want = c / len * (1u64 << 30) as f64;
                worst_step = worst_step.max((g.to_bits() as f64 - want).abs());
            }
        }
        assert!(worst_step <= 1.0, "a component {worst_step} steps off");
        assert!(worst_len <= 1 << 32, "|v|² off by {worst_len} in Q60");
    }
}
