//! The few vector operations the fixed kernel needs, on `fixed` types, each with its format
//! stated in its name and its products widened with `wide_mul`.
//!
//! Lengths are [`Len`] (I16F16, scene units after prepare's power-of-two scaling), unit
//! vectors are [`Unit`] (I2F30). A product of the two is I18F46 and is brought back to a
//! length by an arithmetic shift (rounding toward −∞, like `fixed`'s own `*`). Sums of three
//! wide products stay in `i64` and saturate, so no input can wrap, even outside the ranges
//! the prepare step guarantees.

#[cfg(feature = "full-width")]
use super::mul::{leading_zeros, mul_ii, mul_iu, mul_uu};
use fixed::types::{I16F16, I2F30};

/// A length or coordinate in scaled scene units.
pub(crate) type Len = I16F16;
/// A component of a unit vector, or a cosine.
pub(crate) type Unit = I2F30;
/// Three components.
pub(crate) type V3<T> = [T; 3];

/// `[f(0), f(1), f(2)]`: per-component work with constant indices. `[0, 1, 2].map(f)` means
/// the same, but the optimiser does not always unroll it (it did not for thumbv6m), and then
/// every `a[i]` inside keeps a bounds check: a panic path that fails the firmware's
/// link-time panic proof. Here each index is a literal, so no check is ever emitted.
#[inline(always)]
pub(crate) fn each3<T>(mut f: impl FnMut(usize) -> T) -> [T; 3] {
    [f(0), f(1), f(2)]
}

/// `a·b` for a length vector and a unit vector, as raw I16F16 bits in `i64`.
#[cfg(feature = "full-width")]
#[inline(always)]
pub(crate) fn dot_len_unit(a: V3<Len>, b: V3<Unit>) -> i64 {
    let [x, y, z] = each3(|i| mul_ii(a[i].to_bits(), b[i].to_bits()));
    x.saturating_add(y).saturating_add(z) >> 30
}

/// `a·b` for two unit vectors, as raw I2F30 bits in `i64`.
#[cfg(feature = "full-width")]
#[inline(always)]
pub(crate) fn dot_unit(a: V3<Unit>, b: V3<Unit>) -> i64 {
    let [x, y, z] = each3(|i| mul_ii(a[i].to_bits(), b[i].to_bits()));
    x.saturating_add(y).saturating_add(z) >> 30
}

/// `|a|²` of a length vector held as raw I16F16 bits in `i64`, as raw I32F32 bits.
#[cfg(feature = "full-width")]
#[inline(always)]
pub(crate) fn length_sq(a: V3<i64>) -> i64 {
    let sq = |v: i64| {
        let v = to_len(v).to_bits();
        mul_ii(v, v)
    };
    sq(a[0]).saturating_add(sq(a[1])).saturating_add(sq(a[2]))
}

/// A raw I16F16 length (in `i64`) times a unit component: raw I16F16 bits in `i64`.
///
/// The length is clamped into I16F16 first; every length the kernel passes (`oc·d`, `t`,
/// ε) is already within it, because the prepared scene lies within `±2¹³` units.
#[cfg(feature = "full-width")]
#[inline(always)]
pub(crate) fn len_times_unit(len: i64, u: Unit) -> i64 {
    mul_ii(to_len(len).to_bits(), u.to_bits()) >> 30
}

/// A raw `i64` clamped into an I16F16.
#[cfg(feature = "full-width")]
#[inline(always)]
pub(crate) fn to_len(v: i64) -> Len {
    Len::from_bits(v.clamp(i32::MIN as i64, i32::MAX as i64) as i32)
}

/// The unit vector along `v` (any common fixed format, raw bits), or `None` for zero.
///
/// The components are first shifted (exactly, by a power of two: only the direction
/// matters) so the largest has 30 significant bits; then `1/|v|` comes from
/// [`inv_sqrt`](super::roots::inv_sqrt), so the result's length is 1 within about `2⁻²⁹`.
#[cfg(feature = "full-width")]
#[cfg_attr(not(shadeline_short_mul), inline(always))]
#[cfg_attr(shadeline_short_mul, inline(never))]
pub(crate) fn normalize(v: V3<i64>) -> Option<V3<Unit>> {
    let largest = v.iter().map(|c| c.unsigned_abs()).max().unwrap_or(0);
    if largest == 0 {
        return None;
    }
    let bits = 64 - leading_zeros(largest);
    let c = if bits > 30 {
        v.map(|c| c >> (bits - 30))
    } else {
        v.map(|c| c << (30 - bits))
    };
    // |c| < 2³⁰ each (so `as i32` is exact), and the sum of squares is below 3·2⁶⁰.
    let c = c.map(|x| x as i32);
    let sum = c.iter().fold(0u64, |acc, &x| {
        let m = x.unsigned_abs();
        acc + mul_uu(m, m)
    });
    let (y, shift) = super::roots::inv_sqrt(sum)?;
    // c·y·2^-shift is the unit component; shift ≥ 31, so this is a right shift by ≥ 1.
    Some(c.map(|x| {
        let u = mul_iu(x, y) >> (shift - 30).min(63);
        Unit::from_bits(u.clamp(-(1 << 30), 1 << 30) as i32)
    }))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn normalize_gives_unit_vectors() {
        for v in [
            [1i64, 0, 0],
            [-3, 4, 0],
            [1 << 50, -(1 << 49), 12345],
            [7, 7, 7],
            [-1, -1, i64::MAX / 4],
        ] {
            let u = normalize(v).unwrap();
            let len2 = dot_unit(u, u) as f64 / (1u64 << 30) as f64;
            assert!((len2 - 1.0).abs() < 4e-9, "{v:?}: |u|² = {len2}");
            let f = v.map(|c| c as f64);
            let n = (f[0] * f[0] + f[1] * f[1] + f[2] * f[2]).sqrt();
            for i in 0..3 {
                let got = u[i].to_bits() as f64 / (1u64 << 30) as f64;
                assert!((got - f[i] / n).abs() < 4e-9, "{v:?}");
            }
        }
        assert_eq!(normalize([0, 0, 0]), None);
    }
}
