//! The prepare's conversions between `f32` and fixed-point bits: one routine for every format.
//!
//! The `fixed` crate's `checked_from_num` and `to_num` are generic over both sides, and each
//! format the prepare uses (I16F16, I2F30, U16F16, I16F48, I32F32) gets its own inlined copy:
//! about 1.8 KB of the M0 firmware's flash. These give the same bits
//! (`tests::conversions_match_the_fixed_crate` checks them against `fixed` over every
//! exponent), from the `f32`'s own bits and a shift.

/// `v·2^frac` rounded to the nearest integer, ties to even: the bits of the fixed-point number
/// with `frac` fraction bits nearest `v`, as `fixed`'s `checked_from_num` rounds. `None` for
/// NaN, the infinities and a magnitude of `2⁶³` or more.
#[inline(never)]
pub(crate) fn fixed_bits(v: f32, frac: u32) -> Option<i64> {
    let bits = v.to_bits();
    let biased = ((bits >> 23) & 0xff) as i32;
    if biased == 0xff {
        return None;
    }
    let fraction = (bits & 0x7f_ffff) as u64;
    let mantissa = if biased == 0 {
        fraction
    } else {
        fraction | (1 << 23)
    };
    // |v| = mantissa · 2^(max(biased, 1) − 150).
    let shift = biased.max(1) - 150 + frac as i32;
    let magnitude = if mantissa == 0 {
        0
    } else if shift >= 0 {
        // The mantissa has at most 24 bits: a shift above 39 reaches 2⁶³.
        if shift > 39 {
            return None;
        }
        mantissa << shift
    } else {
        let s = shift.unsigned_abs();
        if s >= 64 {
            0
        } else {
            let q = mantissa >> s;
            let rest = mantissa & ((1u64 << s) - 1);
            let half = 1u64 << (s - 1);
            q + (rest > half || (rest == half && q & 1 == 1)) as u64
        }
    };
    let m = magnitude as i64;
    Some(if bits >> 31 != 0 { -m } else { m })
}

/// [`fixed_bits`] into 32 bits: `None` also outside `i32`.
pub(crate) fn fixed_bits_i32(v: f32, frac: u32) -> Option<i32> {
    fixed_bits(v, frac).and_then(|b| i32::try_from(b).ok())
}

/// [`fixed_bits`] into unsigned 32 bits: `None` also outside `u32`.
pub(crate) fn fixed_bits_u32(v: f32, frac: u32) -> Option<u32> {
    fixed_bits(v, frac).and_then(|b| u32::try_from(b).ok())
}

/// The `f32` nearest the fixed-point number with bits `bits` and `frac` fraction bits
/// (`frac ≤ 126`), ties to even, as `fixed`'s `to_num::<f32>` rounds: the integer's
/// conversion rounds once, and the power of two is exact.
#[inline(never)]
pub(crate) fn to_f32(bits: i64, frac: u32) -> f32 {
    bits as f32 * f32::from_bits((127 - frac.min(126)) << 23)
}

#[cfg(test)]
mod tests {
    use super::*;
    use fixed::types::{I16F16, I16F48, I2F30, I32F32, U16F16};

    /// `f32`s over every exponent: each biased exponent with a few mantissas, both signs,
    /// plus the halfway cases of every format below.
    fn samples() -> impl Iterator<Item = f32> {
        let mut s = 0x2545_f491_4f6c_dd1du64;
        (0..=255u32).flat_map(move |e| {
            let mut out = [0f32; 16];
            for (k, o) in out.iter_mut().enumerate() {
                s ^= s << 13;
                s ^= s >> 7;
                s ^= s << 17;
                let fraction = match k {
                    0 => 0,
                    1 => 1,
                    2 => 0x40_0000,
                    3 => 0x7f_ffff,
                    _ => (s >> 20) as u32 & 0x7f_ffff,
                };
                let sign = (k as u32 & 1) << 31;
                *o = f32::from_bits(sign | e << 23 | fraction);
            }
            out
        })
    }

    #[test]
    fn conversions_match_the_fixed_crate() {
        let halves = (0..4000).map(|k| (k as f32 - 2000.0) * 0.5 / 65536.0);
        let mut checked = 0;
        for v in samples().chain(halves) {
            let len = fixed_bits_i32(v, 16);
            assert_eq!(
                len,
                I16F16::checked_from_num(v).map(|x| x.to_bits()),
                "{v:e}"
            );
            let unit = fixed_bits_i32(v, 30);
            assert_eq!(
                unit,
                I2F30::checked_from_num(v).map(|x| x.to_bits()),
                "{v:e}"
            );
            let level = fixed_bits_u32(v, 16);
            assert_eq!(
                level,
                U16F16::checked_from_num(v).map(|x| x.to_bits()),
                "{v:e}"
            );
            if v.abs() < 32767.0 {
                let wide = fixed_bits(v, 48);
                assert_eq!(
                    wide,
                    I16F48::checked_from_num(v).map(|x| x.to_bits()),
                    "{v:e}"
                );
            }
            if let Some(b) = len {
                assert_eq!(to_f32(b as i64, 16), I16F16::from_bits(b).to_num::<f32>());
            }
            if let Some(b) = unit {
                assert_eq!(to_f32(b as i64, 30), I2F30::from_bits(b).to_num::<f32>());
            }
            if let Some(b) = fixed_bits(v, 32) {
                assert_eq!(to_f32(b, 32), I32F32::from_bits(b).to_num::<f32>(), "{v:e}");
            }
            checked += len.is_some() as u32;
        }
        assert!(checked > 1000, "only {checked} values in range");
    }
}
