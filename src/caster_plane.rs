//! The two rules both narrow kernels (`src/fixed/narrow_caster_prepare.rs`,
//! `src/float/prepare.rs`) use to leave a caster out of a sphere's shadow casters toward a
//! light: the geometry, in `f32`, once per frame and pair of spheres. Each path applies a
//! margin for its own exact ray's rounding, which is why the margins are not here.
//!
//! With `Δ` the sphere's centre less the caster's, `n = Δ/|Δ|` and `δ` a lower bound on
//! `n·L` over the rays (`L` each ray's unit direction toward the light, `δ > 0`), the plane
//! across `n` through the caster's point nearest the sphere has the caster on one side, and
//! a ray moving along `L` from the other side only moves away from it. A pixel's lifted
//! point `O = C + (r + ε)·N` lies on that other side by `|Δ| − r_c + (r + ε)·N·n`. The pixels
//! that test casters are those not in their own shadow: `N·L ≥ −s`, with
//! `s = √(1 − r²/(r + ε)²)` the shadow limit, widened by the error of the `N·L` the test
//! reads. Over those, the angle between `N` and `−n` is at least `φ = asin δ − asin s`, so
//! the lifted point clears the plane by at least `|Δ| − r_c − (r + ε)·cos φ`
//! ([`clearance`]). A floor sphere under a sphere resting on it, lit from above their
//! contact, is the case the rule is for: distance alone keeps a touching sphere among the
//! casters, and every lit pixel would test it.
//!
//! Where the light is lower, the tested pixels reach so near the contact that their lifted
//! points lie inside the floor, and no plane keeps it off. The second rule ([`recession`],
//! [`leaves_within`]) takes the exact rays' own test: a ray moving away from the caster's
//! centre (`b = (O − C_c)·L ≥ 0`) meets it only from inside, and both paths count that a
//! block only where it leaves the caster beyond `ε`, `r_c² − |O − C_c|² > ε·(2b + ε)`. Over
//! the tested pixels `b ≥ |Δ|·δ − (r + ε)·s` (as `N·L ≥ −s`), and `|O − C_c|` is least at
//! the angle `φ` from `−n`.

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

/// The receding rule's bounds over the lifted points of the pixels that test casters (see
/// the module docs), for a sphere of radius `r` with lift `ε`, a caster at `|Δ| = len`, the
/// bound `delta` on `n·L` and `widen` on the own-shadow limit: the least `b = (O − C_c)·L`,
/// `|Δ|·δ − (r + ε)·s`, and the least `|O − C_c|`, `|Δ − (r + ε)·u|` for a unit `u` at
/// `φ = asin δ − asin s` from `n` (from `cos φ` and `sin φ`, with no cancellation).
/// `None` where `δ` is not above the widened limit (or is a NaN).
pub(crate) fn recession(
    (r, eps): (f32, f32),
    len: f32,
    delta: f32,
    widen: f32,
) -> Option<(f32, f32)> {
    let lift = r + eps;
    let s = libm::sqrtf(eps * (2.0 * r + eps)) / lift + widen;
    if !(delta > s && delta <= 1.0 && s < 1.0) {
        return None;
    }
    let (cd, cs) = (libm::sqrtf(1.0 - delta * delta), libm::sqrtf(1.0 - s * s));
    let (cos, sin) = (cd * cs + delta * s, delta * cs - s * cd);
    let near = len - lift * cos;
    let far = lift * sin;
    Some((len * delta - lift * s, libm::sqrtf(near * near + far * far)))
}

/// Whether rays with `b` at least `b` (not below 0) from points at least `x` from the
/// centre of a caster of radius `rc` never leave it beyond `ε`: `(r_c − x)·(r_c + x)`, the
/// most that `r_c² − |O − C_c|²` can be, plus `slack` (the path's rounding of it) and
/// `2⁻¹⁰` of itself, below `ε·(2b + ε)`, the least the exact test compares it with. The
/// path lowers `b` and `x` by its own margins first.
pub(crate) fn leaves_within(rc: f32, eps: f32, (b, x): (f32, f32), slack: f32) -> bool {
    if b.is_nan() || b < 0.0 {
        return false;
    }
    let inside = if x >= rc { 0.0 } else { (rc - x) * (rc + x) };
    inside * (1.0 + 1.0 / 1024.0) + slack < eps * (2.0 * b + eps)
}
