//! Where one sphere's shadow from one light can fall on another: a ball holding every
//! point of the receiver whose shading from that light can depend on the caster.
//!
//! A shadow ray leaves a point `p` of the receiver (lifted `ε` along the normal) toward the
//! light. The caster can block it only if `p` lies in the caster's shadow volume: within
//! `ρ` of the axis from the light through the caster's centre, beyond the caster's near
//! side, where `ρ` is the caster's radius for a distant light (a cylinder), grows linearly
//! from the light for a point light (a cone), and for a sphere light grows from the light's
//! own radius (the penumbra). And the shadow matters only where the light is above the
//! surface's horizon: where `N·L < 0` every path adds nothing from that light, shadowed or
//! not. On a sphere those points are where a line from the light *enters* the receiver, so
//! only the entry points of the volume's lines count. That is what keeps a small sphere's
//! shadow on a big floor sphere small: the cylinder runs through the floor, but it enters it
//! on a small patch.
//!
//! Conservative margins: the caster grows by `6ε + 2·10⁻³(r + rⱼ)` (three times the
//! paths' own caster test, `Scene::shadow_casters`), the receiver by `2ε`, and the light's
//! horizon is taken at `N·L ≥ −10⁻²` instead of 0, for the rounding of every path. A sphere
//! light's shadow is bounded by its whole volume inside the receiver (its horizon is soft).

use crate::scene::{Light, Sphere};
use crate::vec3::Vec3;

/// How far below the horizon (`N·L ≥ −HORIZON`) a point still counts as lit.
const HORIZON: f32 = 1.0e-2;

/// The balls holding every point of `receiver` whose light from `light` can depend on
/// `caster`, or `None` where there is none; `eps` is the scene's ray epsilon.
pub(super) fn shadow_ball(
    caster: &Sphere,
    receiver: &Sphere,
    light: &Light,
    eps: f32,
) -> Option<Chain> {
    let rho = caster.radius + 6.0 * eps + 2.0e-3 * (caster.radius + receiver.radius);
    let big = receiver.radius + 2.0 * eps;
    let whole = Some(Chain::One(receiver.center, big));
    let (apex, axis, dist, light_radius) = match *light {
        Light::Distant { direction, .. } => {
            let Some(v) = direction.normalized() else {
                return whole;
            };
            return distant(caster.center, rho, receiver.center, big, v);
        }
        Light::Point {
            position, radius, ..
        } => {
            let to = caster.center - position;
            let dist = libm::sqrtf(to.dot(to));
            let Some(v) = to.normalized() else {
                return whole;
            };
            (position, v, dist, radius)
        }
    };
    // The light inside (or touching) the grown caster or receiver: every point may depend.
    let to_receiver = receiver.center - apex;
    let receiver_dist = libm::sqrtf(to_receiver.dot(to_receiver));
    if dist <= rho + light_radius || receiver_dist <= big {
        return whole;
    }
    // Offsets from the axis at axial distance `s` from the light: `R·|1 − s/D| + ρ·s/D`
    // (a line through a point of the light and a point of the caster).
    let offset = |s: f32| light_radius * (1.0 - s / dist).abs() + rho * s / dist;
    // The receiver's axial extent, and the part beyond the caster's near side.
    let along = to_receiver.dot(axis);
    let mut s0 = (along - big).max(dist - rho);
    let mut s1 = along + big;
    if light_radius <= 0.0 {
        let (near, far) = point_entry(receiver_dist, along, big, rho / dist, eps)?;
        (s0, s1) = (s0.max(near), s1.min(far));
    }
    // An empty range, or a NaN from degenerate input: no patch.
    if s0.partial_cmp(&s1).is_none_or(|o| o.is_gt()) {
        return None;
    }
    let reach = offset(s0).max(offset(s1));
    Some(chain(apex, axis, s0, s1, reach, receiver.center, big))
}

/// For a point light (no radius): the axial range from the light (`near`, `far`) in which
/// the shadow volume's lines (within `asin(sin_alpha)` of the axis) enter a receiver of
/// radius `big` whose centre lies `receiver_dist` from the light and `along` the axis, up
/// to the points with `N·L ≥ −HORIZON`; `None` if every line misses the receiver.
fn point_entry(
    receiver_dist: f32,
    along: f32,
    big: f32,
    sin_alpha: f32,
    eps: f32,
) -> Option<(f32, f32)> {
    // A point light: the volume's lines leave the light within `α` of the axis, and
    // enter the receiver where its distance from the light is `f(γ)`, `γ` the line's
    // angle from the receiver's centre: `f` grows with `γ` up to the tangent.
    let sin_alpha = sin_alpha.min(1.0);
    let alpha = libm::asinf(sin_alpha);
    let beta = libm::acosf((along / receiver_dist).clamp(-1.0, 1.0));
    let sin_tangent = (big / receiver_dist).min(1.0);
    let tangent_angle = libm::asinf(sin_tangent);
    let entry = |gamma: f32| {
        let (s, c) = (libm::sinf(gamma), libm::cosf(gamma));
        let inside = big * big - receiver_dist * receiver_dist * s * s;
        receiver_dist * c - libm::sqrtf(inside.max(0.0))
    };
    let near = (beta - alpha).max(0.0);
    if near >= tangent_angle {
        // Every line of the volume misses the receiver.
        return None;
    }
    let tangent_len = libm::sqrtf((receiver_dist * receiver_dist - big * big).max(0.0));
    let far_gamma = beta + alpha;
    let nearest = entry(near);
    // Lines near the tangent: the points with `N·L ≥ −HORIZON` reach this far.
    let far = if far_gamma < tangent_angle
        && libm::sinf(far_gamma) < sin_tangent * libm::sqrtf(1.0 - HORIZON * HORIZON)
    {
        entry(far_gamma)
    } else {
        big * HORIZON + libm::sqrtf(big * big * HORIZON * HORIZON + tangent_len * tangent_len)
    };
    // `nearest` is a distance from the light, the axial distance at least its cosine.
    Some((nearest * libm::cosf(alpha) - 2.0 * eps, far + 2.0 * eps))
}

/// The balls along the axis from `s0` to `s1` (`CHAIN` equal pieces) holding the volume of
/// radius `reach` there, or the receiver's ball when that is smaller than their hull.
fn chain(apex: Vec3, axis: Vec3, s0: f32, s1: f32, reach: f32, receiver: Vec3, big: f32) -> Chain {
    let len = s1 - s0;
    let whole = libm::sqrtf(0.25 * len * len + reach * reach);
    if big <= whole {
        return Chain::One(receiver, big);
    }
    let piece = len / CHAIN as f32;
    let radius = libm::sqrtf(0.25 * piece * piece + reach * reach) * 1.000_1;
    Chain::Pieces {
        first: apex + axis.scale(s0 + 0.5 * piece),
        step: axis.scale(piece),
        radius,
    }
}

/// Balls a shadow's reach is cut into along its axis: a long shadow (a low light) is a
/// thin patch, which one bounding ball would hold badly.
pub(super) const CHAIN: usize = 4;

/// A shadow's reach: one ball, or [`CHAIN`] balls along the axis.
#[derive(Clone, Copy, Debug)]
pub(super) enum Chain {
    /// One ball: centre, radius.
    One(Vec3, f32),
    /// `CHAIN` balls of `radius`, the first centred at `first`, each `step` on.
    Pieces {
        /// The first ball's centre.
        first: Vec3,
        /// From one centre to the next.
        step: Vec3,
        /// Every ball's radius.
        radius: f32,
    },
}

impl Chain {
    /// Each ball: centre, radius.
    pub(super) fn balls(self) -> impl Iterator<Item = (Vec3, f32)> {
        let (first, step, radius, n) = match self {
            Chain::One(c, r) => (c, Vec3::new(0.0, 0.0, 0.0), r, 1),
            Chain::Pieces {
                first,
                step,
                radius,
            } => (first, step, radius, CHAIN),
        };
        (0..n).map(move |k| (first + step.scale(k as f32), radius))
    }
}

/// A distant light travelling along `v` (unit): the cylinder of radius `rho` from the
/// caster's centre downstream, where its lines enter the receiver.
fn distant(caster: Vec3, rho: f32, receiver: Vec3, big: f32, v: Vec3) -> Option<Chain> {
    let d = receiver - caster;
    let along = d.dot(v);
    let perp = libm::sqrtf((d.dot(d) - along * along).max(0.0));
    if perp > rho + big {
        return None;
    }
    // A line at distance `q` from the receiver's centre enters it at `along − √(R² − q²)`.
    let q_min = (perp - rho).max(0.0);
    let q_max = perp + rho;
    let mut s0 = along - libm::sqrtf((big * big - q_min * q_min).max(0.0));
    let s1 = if q_max < big * libm::sqrtf(1.0 - HORIZON * HORIZON) {
        along - libm::sqrtf(big * big - q_max * q_max)
    } else {
        // Lines near the tangent: their exit points with `N·L ≥ −HORIZON` too.
        along + big * HORIZON
    };
    // Beyond the caster's near side (the caster between the point and the light).
    s0 = s0.max(-rho);
    // An empty range, or a NaN from degenerate input: no patch.
    if s0.partial_cmp(&s1).is_none_or(|o| o.is_gt()) {
        return None;
    }
    Some(chain(caster, v, s0, s1, rho, receiver, big))
}
