//! The fixed constants of a GGX sphere (feature `models`), converted once per frame from
//! the float paths' own ([`crate::brdf::Params`]): the full-width kernel's GGX term
//! (`kernel_models`) reads them.
//!
//! Only a build with the microfacet models holds them, so they live in a module that exists
//! only with the feature, not field by field under its gate.

use super::exact::Exact;
use crate::brdf::Params;

/// A GGX sphere's constants (`α = roughness²`).
#[derive(Clone, Copy, Debug)]
#[cfg_attr(not(feature = "full-width"), allow(dead_code))]
pub(crate) struct FixedGgx {
    /// `α²`, U1F31.
    pub alpha2: u32,
    /// `1 − α²`, U1F31.
    pub one_minus_alpha2: u32,
    /// `ks·α²/(2π)`, the `f32` value exactly.
    pub scale: Exact,
    /// `α`, U1F31, for the widening under a sphere light.
    #[cfg(all(feature = "area-lights", feature = "full-width"))]
    pub alpha: u32,
}

impl FixedGgx {
    /// GGX's constants from the float paths' `params` of its material.
    #[inline(always)]
    pub(super) fn of(params: &Params<f32>) -> FixedGgx {
        let u1f31 = |v: f32| (v.clamp(0.0, 1.0) * (1u64 << 31) as f32) as u32;
        FixedGgx {
            alpha2: u1f31(params.alpha2),
            one_minus_alpha2: u1f31(1.0 - params.alpha2),
            scale: Exact::from_f32(
                params.weight[0] * params.alpha2 / (2.0 * core::f32::consts::PI),
            ),
            #[cfg(all(feature = "area-lights", feature = "full-width"))]
            alpha: u1f31(libm::sqrtf(params.alpha2)),
        }
    }
}
