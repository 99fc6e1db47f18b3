//! The plane rule both narrow kernels (`src/fixed/narrow_caster_prepare.rs`,
//! `src/float/prepare.rs`) use to leave a caster out of a sphere's shadow casters: the
//! geometry, in `f32`, once per frame and pair of spheres. Each path compares the clearance
//! with a margin for its own exact ray's rounding, which is why the margin is not here.
//!
//! With `Δ` the sphere's centre less the caster's, `n = Δ/|Δ|` and `δ` a lower bound on
//! `n·L` over the rays (`L` each ray's unit direction toward the light, `δ > 0`), the plane
//! across `n` through the caster's point nearest the sphere has the caster on one side, and
//! a ray moving along `L` from the other side only moves away from it. A pixel's lifted
//! point `O = C + (r + ε)·N` lies on that other side by `|Δ| − r_c + (r + ε)·N·n`. The pixels
//! that test casters are those not in their own shadow: `N·L ≥ −s`, with
//! `s = √(1 − r²/(r + ε)²)` the shadow limit, widened by the error of the `N·L` the test
//! reads. Over those, the angle between `N` and `−n` is at least `asin δ − asin s`, so the
//! lifted point clears the plane by at least `|Δ| − r_c − (r + ε)·cos(asin δ − asin s)`.
//! A floor sphere under a sphere resting on it, lit from above their contact, is the case
//! the rule is for: distance alone keeps a touching sphere among the casters, and every
//! lit pixel would test it.

/// The least distance by which a lifted point of a pixel that tests casters clears the
/// plane (see the module docs), for a sphere of radius `r` with lift `ε`, a caster of
/// radius `rc` at `|Δ| = len`, the bound `delta` on `n·L`, and `widen` on the own-shadow
/// limit; `None` where `δ` is not above the widened limit (or is a NaN), where the rule
/// does not apply. `s` is `√(ε·(2r + ε))/(r + ε)`, free of the cancellation in
/// `1 − r²/(r + ε)²`.
pub(crate) fn clearance(
    (r, rc, eps): (f32, f32, f32),
    len: f32,
    delta: f32,
    widen: f32,
) -> Option<f32> {
    let lift = r + eps;
    let s = libm::sqrtf(eps * (2.0 * r + eps)) / lift + widen;
    if !(delta > s && delta <= 1.0 && s < 1.0) {
        return None;
    }
    let cos = libm::sqrtf(1.0 - delta * delta) * libm::sqrtf(1.0 - s * s) + delta * s;
    Some(len - rc - lift * cos)
}
