//! The full-width kernel's terms of the microfacet and rough-diffuse models (feature
//! `models`): Oren–Nayar's diffuse factor and GGX's specular term in integers, with the
//! wide mantissa-and-exponent products GGX's range needs.
//!
//! The kernel's `normalized` calls them only for spheres of these models; kept apart, the
//! kernel reads the same with or without the feature.

use super::exact::shift_saturating;
use super::mul::{leading_zeros, mul_ii, mul_uu};
use super::prepare_ggx::FixedGgx;
use super::roots::{inv_sqrt, sqrt};
use super::vector::{dot_unit, Unit, V3};

/// Oren–Nayar's diffuse factor times `N·L`, U2F30, the integer form of
/// [`crate::brdf::oren_nayar`]: `A·(N·L) + B·max(0, s)·(N·L/max(N·L, N·V))` with
/// `s = L·V − (N·L)(N·V)` and `V = −d`, for `A`, `B` and `N·L > 0` in U2F30. The ratio is 1
/// where `N·L ≥ N·V` and otherwise one 64-bit division, exact to the last of its 30 bits:
/// the only division of the fixed kernel, and only for Oren–Nayar spheres.
#[inline(always)]
pub(super) fn oren_nayar(
    a: u32,
    b: u32,
    n_dot_l: u32,
    n: V3<Unit>,
    l: V3<Unit>,
    d: V3<Unit>,
) -> u32 {
    const ONE: u32 = 1 << 30;
    let v = d.map(|c| c.saturating_neg());
    let n_dot_v = dot_unit(n, v).clamp(0, ONE as i64) as u32;
    let l_dot_v = dot_unit(l, v);
    // s = sin θ_i·sin θ_r·cos Δφ ≤ 1.
    let s = (l_dot_v - (mul_uu(n_dot_l, n_dot_v) >> 30) as i64).clamp(0, ONE as i64) as u32;
    let ratio = if n_dot_l >= n_dot_v {
        ONE
    } else {
        // N·V > N·L ≥ 0, so the quotient is below 2³⁰ and the divisor not 0.
        (((n_dot_l as u64) << 30).checked_div(n_dot_v as u64)).unwrap_or(0) as u32
    };
    let rough = (mul_uu((mul_uu(b, s) >> 30) as u32, ratio) >> 30) as u32;
    ((mul_uu(a, n_dot_l) >> 30) as u32).saturating_add(rough)
}

/// GGX's specular term times `N·L` for the GGX constants `g`: the body of the kernel's
/// `ggx_specular`, which widens it under a sphere light.
#[inline(always)]
pub(super) fn ggx_term(
    g: &FixedGgx,
    n_dot_l: u32,
    n: V3<Unit>,
    d: V3<Unit>,
    half: Option<V3<Unit>>,
) -> u32 {
    const ONE: u32 = 1 << 30;
    let Some(h) = half else {
        return 0;
    };
    let n_dot_h = dot_unit(n, h);
    if n_dot_h <= 0 {
        return 0;
    }
    let c = n_dot_h.min(ONE as i64) as u32; // F30
    let n_dot_v = dot_unit(n, d.map(|x| x.saturating_neg())).clamp(0, ONE as i64) as u32;
    let (nb, hb) = (n.map(|x| x.to_bits()), h.map(|x| x.to_bits()));
    // N × H in F60 (each component below 2⁶¹), then |N × H|² in F60 from its F30 components.
    let cross = [
        mul_ii(nb[1], hb[2]) - mul_ii(nb[2], hb[1]),
        mul_ii(nb[2], hb[0]) - mul_ii(nb[0], hb[2]),
        mul_ii(nb[0], hb[1]) - mul_ii(nb[1], hb[0]),
    ];
    let sin2 = cross.iter().fold(0u64, |acc, &x| {
        let m = (x >> 30).unsigned_abs().min(u32::MAX as u64) as u32;
        acc.saturating_add(mul_uu(m, m))
    });
    // F60 × U1F31 (through F31 × F31 = F62).
    let times = |x60: u64, f31: u32| mul_uu((x60 >> 29).min(u32::MAX as u64) as u32, f31) >> 2;
    let q = times(mul_uu(c, c), g.alpha2).saturating_add(sin2);
    let lambda = |x: u32| {
        let l2 = times(mul_uu(x, x), g.one_minus_alpha2) + ((g.alpha2 as u64) << 29);
        sqrt(l2).min(u32::MAX as u64) as u32 // F30
    };
    let den = mul_uu(n_dot_l, lambda(n_dot_v)) + mul_uu(n_dot_v, lambda(n_dot_l)); // F60
    let (Some((yq, sq)), Some((yd, sd))) = (inv_sqrt(q), inv_sqrt(den)) else {
        return 0;
    };
    // 1/x = y²·2^(60 − 2·shift) for x in F60 with 1/√x_raw = y·2^-shift.
    let inv_q = Wide::new(mul_uu(yq, yq), 60 - 2 * sq as i32);
    let inv_den = Wide::new(mul_uu(yd, yd), 60 - 2 * sd as i32);
    let term = Wide::new(g.scale.mantissa as u64, g.scale.exponent)
        .mul(Wide::new(n_dot_l as u64, -30))
        .mul(inv_q)
        .mul(inv_q)
        .mul(inv_den);
    shift_saturating(term.m as u64, term.e + 16)
}

/// `m·2^e` with `m` normalized to its top bit (0 is `m = 0`): products of factors whose
/// range no fixed format holds, to 31 bits, rounded toward zero.
#[derive(Clone, Copy)]
struct Wide {
    m: u32,
    e: i32,
}

impl Wide {
    /// `v·2^e`, rounded toward zero to 32 significant bits.
    #[inline(always)]
    fn new(v: u64, e: i32) -> Wide {
        if v == 0 {
            return Wide { m: 0, e: 0 };
        }
        let lz = leading_zeros(v);
        Wide {
            m: ((v << lz) >> 32) as u32,
            e: e + 32 - lz as i32,
        }
    }

    /// The product, rounded toward zero.
    #[inline(always)]
    fn mul(self, o: Wide) -> Wide {
        Wide::new(mul_uu(self.m, o.m), self.e + o.e)
    }
}
