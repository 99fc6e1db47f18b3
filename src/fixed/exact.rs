//! An `f32` held exactly as an integer mantissa and a power of two, for the two per-frame
//! numbers whose range is too wide for any one fixed format: a material's shininess `n`
//! (`0 < n ≤ 10⁶`, fractions matter at the low end) and a point light's power (its arriving
//! light spans many decades with distance). Taking the `f32`'s own bits loses nothing, and
//! the kernel multiplies the mantissa by a 32-bit value and shifts the product into the
//! format it needs, saturating.

/// `mantissa · 2^exponent`, exactly the value of a finite, non-negative `f32`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub(crate) struct Exact {
    /// At most 24 bits.
    pub mantissa: u32,
    /// The power of two, in `-149..=104`.
    pub exponent: i32,
}

impl Exact {
    /// The exact value of a finite `v ≥ 0`. Anything else (which the scene model rules out)
    /// reads as 0.
    pub(crate) fn from_f32(v: f32) -> Self {
        let bits = v.to_bits();
        let biased = ((bits >> 23) & 0xff) as i32;
        let fraction = bits & 0x7f_ffff;
        if bits >> 31 != 0 || biased == 0xff {
            Exact::default()
        } else if biased == 0 {
            Exact {
                mantissa: fraction,
                exponent: -149,
            }
        } else {
            Exact {
                mantissa: fraction | (1 << 23),
                exponent: biased - 150,
            }
        }
    }
}

/// `p · 2^e` as a `u32`, saturating at `u32::MAX`; bits shifted out at the bottom are
/// dropped (rounded toward zero). Out of line on ARMv6-M, for its flash: the narrow
/// kernel's precise lobe takes it twice, and few pixels take that.
#[cfg_attr(not(shadeline_short_mul), inline(always))]
#[cfg_attr(shadeline_short_mul, inline(never))]
pub(crate) fn shift_saturating(p: u64, e: i32) -> u32 {
    if p == 0 {
        return 0;
    }
    let s = e.unsigned_abs();
    let v = if e >= 0 {
        if s >= 64 || super::mul::shift_overflows(p, s) {
            return u32::MAX;
        }
        p << s
    } else {
        p.checked_shr(s).unwrap_or(0)
    };
    u32::try_from(v).unwrap_or(u32::MAX)
}

/// `power/d²` per channel in U16F16, saturating, from `1/d = y·2^-shift` (raw I16F16 `d`) as
/// [`inv_sqrt`](super::roots::inv_sqrt) gives it: `1/d²` in units is `y²·2^(63 − 2·shift)`
/// with `y²` in U1F31. A point light's arriving colour, in both kernels.
#[inline(always)]
pub(crate) fn arriving(power: [Exact; 3], (y, shift): (u32, u32)) -> [u32; 3] {
    let y2 = (super::mul::mul_uu(y, y) >> 31) as u32;
    let e = 79 - 2 * shift as i32;
    power.map(|pw| shift_saturating(super::mul::mul_uu(pw.mantissa, y2), pw.exponent + e))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exact_round_trips() {
        for v in [0.0f32, 1.0, 3.0, 0.1, 1.0e6, 1.0e-40, 3.4e38] {
            let e = Exact::from_f32(v);
            let back = e.mantissa as f64 * (e.exponent as f64).exp2();
            assert_eq!(back, v as f64, "{v}");
        }
        assert_eq!(Exact::from_f32(-1.0), Exact::default());
        assert_eq!(Exact::from_f32(f32::NAN), Exact::default());
        assert_eq!(Exact::from_f32(f32::INFINITY), Exact::default());
    }

    #[test]
    fn shifts_saturate() {
        assert_eq!(shift_saturating(3, 1), 6);
        assert_eq!(shift_saturating(7, -1), 3);
        assert_eq!(shift_saturating(1, 31), 1 << 31);
        assert_eq!(shift_saturating(1, 32), u32::MAX);
        assert_eq!(shift_saturating(1, 200), u32::MAX);
        assert_eq!(shift_saturating(u64::MAX, -200), 0);
        assert_eq!(shift_saturating(u64::MAX, -31), u32::MAX);
        assert_eq!(shift_saturating(0, 100), 0);
    }
}
