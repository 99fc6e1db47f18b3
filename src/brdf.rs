//! The reflection models, in one place: what the kernels evaluate for each light.
//!
//! Classic Phong, as in the lesson (no `1/π`, not normalized, not energy conserving):
//!
//! ```text
//! colour = kd · Σ_lights vis · albedo · I · max(0, N·L)
//!        + ks · Σ_lights vis · I · max(0, R·V)^n
//! R = D − 2(N·D)N      D = −L, the direction the light travels;   V toward the eye
//! ```
//!
//! Classic Blinn-Phong replaces `R·V` by `N·H`, `H = normalize(L + V)`.
//!
//! The specular term is never tinted by the albedo (a dielectric reflects the light's own
//! colour). The kernels accumulate `Σ vis·I·max(0, N·L)` and `Σ vis·I·lobe` and apply
//! `kd·albedo` and `ks` once per pixel; this module gives them the lobe's cosine.

use crate::lane::Lane;
use crate::vec3::Vec3;

/// The cosine the specular lobe raises to the power `n`: `R·V` (Phong) or `N·H`
/// (Blinn-Phong, on lanes where `blinn` is set). Unclamped; the caller clamps at zero.
///
/// `n` is the unit normal, `to_light` the unit vector toward the light (`L`), `view` the unit
/// vector toward the eye (`V`). If `L + V` is zero, `N·H` is taken as 0.
#[inline(always)]
pub fn specular_cosine<T: Lane>(n: Vec3<T>, to_light: Vec3<T>, view: Vec3<T>, blinn: T::Mask) -> T {
    let travel = -to_light;
    let mirrored = travel - n * (T::splat(2.0) * n.dot(travel));
    let r_dot_v = mirrored.dot(view);
    if !T::any(blinn) {
        return r_dot_v;
    }
    let zero = T::splat(0.0);
    let h = to_light + view;
    let h2 = h.dot(h);
    let inv_len = T::select(zero.lt(h2), T::splat(1.0) / h2.sqrt(), zero);
    T::select(blinn, n.dot(h) * inv_len, r_dot_v)
}
