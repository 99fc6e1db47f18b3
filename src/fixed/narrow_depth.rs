//! The narrow kernel's depth order: the order of the frame's spheres in which, wherever a
//! ray from the eye meets two of them, it meets the first one first. Made once per frame, it
//! lets a pixel over several spheres take the first one its ray hits in that order, with no
//! distance along the ray compared.
//!
//! # Why
//!
//! Where spheres rest on a floor, most of their pixels have the floor behind them: two of the
//! run's tracks hit there. Choosing the nearer by distance takes each hit's `t` (a 64-bit dot
//! product, calls of library routines on ARMv6-M) and `N·V` for both hits (a square root
//! each), where the order needs neither for the hidden one.
//!
//! # How
//!
//! The power of the eye `E` with respect to a sphere of centre `C` and radius `r` is
//! `|E − C|² − r²`. For two spheres `A` and `B`, `powerA(X) − powerB(X)` is affine in `X`,
//! so the points where it is 0 form a plane. On `A`'s surface `powerA = 0 < powerB` at every
//! point outside `B`: if the spheres do not overlap (they may touch), the plane separates
//! them, with `A` on the side where `powerA < powerB`. A ray from an eye on that side crosses
//! the plane at most once, so wherever it meets both spheres it meets `A` first; an eye on
//! the plane sees no point of both. So the spheres sorted by the eye's power are in depth
//! order, pair by pair, for every ray of the frame.
//!
//! Spheres that overlap have no such order: a frame with two spheres that overlap by more
//! than the rounding of touching spheres' coordinates ([`touching`]: a sphere resting on a
//! floor, placed in `f32`) keeps comparing the hits' distances (`narrow_t`). Up to that,
//! the order can only err where the two surfaces are within the overlap of each other along
//! the ray, a closer call than the distances' own rounding makes.
//!
//! The powers and distances are exact integers from the scaled geometry, and ties keep the
//! spheres' order, so every target finds the same order. Only with the feature
//! `depth-order` ([`DEPTH_ORDER`]); without it every frame compares distances.

use super::mul::dot_ii;
use super::prepare::{FixedSphere, PreparedFixed};
use super::vector::each3;

/// Whether frames are put in depth order (feature `depth-order`): without it no frame is,
/// and the code that would take the order folds away.
pub(super) const DEPTH_ORDER: bool = cfg!(feature = "depth-order");

/// The overlap of two spheres, in raw I16F16 units of the scaled scene, up to which they
/// count as touching: [`TOUCHING`] plus `2⁻¹⁴` of the smaller radius. The first covers the
/// rounding of the scaled centres and radii (each within a raw unit of the scene's, so the
/// distance between two centres less the two radii moves by at most `√3 + 2` of them); the
/// second, a resting sphere placed in `f32`, whose coordinates are as far from touching as
/// a few `f32` roundings of the scene's extent (a floor of radius 100 is one). Over such an
/// overlap the two surfaces are within it of each other along every ray through it, and it
/// is at most about 1% of the smaller radius across.
fn touching(a: &FixedSphere, b: &FixedSphere) -> i32 {
    let r = a.radius.to_bits().min(b.radius.to_bits());
    TOUCHING + (r >> 14)
}

/// The overlap of two spheres in raw units that always counts as touching (see [`touching`]).
pub(super) const TOUCHING: i32 = 8;

/// The eye's power with respect to `s` in raw units squared: `|E − C|² − r²`, exact (the
/// scaled scene lies within `±2²⁹` raw, so each square is below `2⁶⁰`).
fn power(s: &FixedSphere) -> i64 {
    let oc = s.eye_offset.map(|c| c.to_bits());
    dot_ii(oc, oc) - s.radius_sq.to_bits()
}

/// Whether `a` and `b` overlap by more than [`touching`] allows: the distance between their
/// centres below the sum of their radii less it (exact: the scaled scene lies within `±2²⁹`
/// raw, so each difference of coordinates fits `i32` and its square `i64`).
fn overlap(a: &FixedSphere, b: &FixedSphere) -> bool {
    let d = each3(|i| a.center[i].to_bits().wrapping_sub(b.center[i].to_bits()));
    let reach = a.radius.to_bits() + b.radius.to_bits() - touching(a, b);
    reach > 0 && dot_ii(d, d) < dot_ii([reach, 0, 0], [reach, 0, 0])
}

impl<const S: usize, const L: usize> PreparedFixed<S, L> {
    /// Sets `depth_rank` and `depth_ordered` (see the module docs): each sphere's place among
    /// them by the eye's power (ties in the spheres' order) if no two of them overlap;
    /// otherwise unordered, every rank 0. Out of line: once per frame.
    #[inline(never)]
    pub(super) fn prepare_depth_order(&mut self) {
        self.depth_rank = [0; S];
        let spheres = &self.spheres;
        let overlapping = spheres
            .iter()
            .enumerate()
            .any(|(i, a)| spheres.iter().skip(i + 1).any(|b| overlap(a, b)));
        self.depth_ordered = !overlapping;
        if overlapping {
            return;
        }
        for ((i, a), rank) in spheres.iter().enumerate().zip(&mut self.depth_rank) {
            let key = (power(a), i);
            let ahead = spheres
                .iter()
                .enumerate()
                .filter(|&(j, b)| (power(b), j) < key)
                .count();
            // The narrow kernel takes at most 256 spheres (a run's tracks are `u8`): fits.
            *rank = ahead as u8;
        }
    }
}

#[cfg(all(test, feature = "depth-order"))]
mod tests {
    use super::*;
    use crate::fixed::narrow::tests::surfaces;
    use crate::scene::{Camera, Light, Material, Model, Scene, Sphere};
    use crate::test_scenes::{
        random_classic_scene, random_floor_scene, random_lamp_scene, uniform,
    };
    use crate::vec3::Vec3;
    use crate::LinearRgb;

    extern crate std;
    use std::vec::Vec;

    /// Random narrow frames: spheres drawn at random (some overlapping, which leaves the frame
    /// unordered) and spheres resting on floors under distant lights and under lamps.
    fn frames(seed: u64) -> Vec<PreparedFixed<16, 8>> {
        let mut next = uniform(seed);
        let draw = crate::test_scenes::NARROW_DRAW;
        let mut out = Vec::new();
        for k in 0..120 {
            let scene: Scene<16, 8> = match k % 3 {
                0 => random_classic_scene(&mut next, &draw),
                1 => random_floor_scene(&mut next),
                _ => random_lamp_scene(&mut next),
            };
            if let Ok(frame) = PreparedFixed::new(&scene, 96, 72) {
                if frame.narrow.is_some() {
                    out.push(frame);
                }
            }
        }
        out
    }

    /// The exact distance (raw) along `d` from the eye to sphere `s`'s first hit, in `f64`
    /// from the scaled integer geometry, and the discriminant relative to `r²` (negative off
    /// the sphere).
    fn exact_hit(s: &FixedSphere, d: [i32; 3]) -> (f64, f64) {
        let d = d.map(f64::from);
        let len = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
        let oc = s.eye_offset.map(|c| f64::from(c.to_bits()));
        let r2 = s.radius_sq.to_bits() as f64;
        let b = (oc[0] * d[0] + oc[1] * d[1] + oc[2] * d[2]) / len;
        let disc = b * b - (oc[0] * oc[0] + oc[1] * oc[1] + oc[2] * oc[2]) + r2;
        (-b - disc.max(0.0).sqrt(), disc / r2)
    }

    /// At every narrow surface of random frames, the sphere the kernel takes is the nearest
    /// exact hit along the pixel's ray, or within 64 raw units of it, both where the frame is
    /// in depth order and where it compares distances; and both kinds of frame occur, with
    /// many pixels over two spheres.
    #[test]
    fn the_nearest_sphere_is_taken() {
        let (mut ordered, mut unordered, mut behind) = (0, 0, 0usize);
        for frame in frames(0x9e37_79b9_7f4a_7c15) {
            if frame.depth_ordered {
                ordered += 1;
            } else {
                unordered += 1;
            }
            for seen in surfaces(&frame) {
                let hits: Vec<(usize, f64, f64)> = frame
                    .spheres
                    .iter()
                    .enumerate()
                    .map(|(k, s)| {
                        let (t, disc) = exact_hit(s, seen.d);
                        (k, t, disc)
                    })
                    .collect();
                let taken = hits[seen.surface.index];
                // A silhouette pixel of either sphere: the hit test's call, not the order's.
                let clear =
                    |&&(k, t, disc): &&(usize, f64, f64)| k != taken.0 && t > 0.0 && disc > 1e-6;
                if taken.2 < 1e-6 {
                    continue;
                }
                let others: Vec<_> = hits.iter().filter(clear).collect();
                behind += others.iter().filter(|h| h.1 > taken.1).count();
                for &&(k, t, _) in &others {
                    assert!(
                        taken.1 <= t + 64.0,
                        "sphere {} taken at {}, sphere {k} is nearer at {t} (ordered: {})",
                        taken.0,
                        taken.1,
                        frame.depth_ordered
                    );
                }
            }
        }
        assert!(
            ordered >= 20 && unordered >= 10,
            "{ordered} ordered, {unordered} not"
        );
        assert!(behind > 5_000, "{behind} hidden hits");
    }

    /// Two spheres that overlap leave the frame unordered; resting on each other (touching,
    /// up to the coordinates' rounding), they are ordered, the one nearer the eye first.
    #[test]
    fn overlapping_spheres_are_not_ordered() {
        let frame_of = |lift: f32| {
            let camera = Camera {
                position: Vec3::new(0.0, 3.0, 8.0),
                look_at: Vec3::new(0.0, 0.5, 0.0),
                up: Vec3::new(0.0, 1.0, 0.0),
                vfov_degrees: 50.0,
            };
            let mut scene = Scene::<4, 1>::new(camera, LinearRgb::new(0.1, 0.1, 0.2)).unwrap();
            let material = Material {
                albedo: LinearRgb::new(0.5, 0.5, 0.5),
                kd: 0.8,
                ks: 0.3,
                shininess: 20.0,
                model: Model::Phong,
            };
            for (y, radius) in [(-100.0, 100.0), (1.0 + lift, 1.0)] {
                let center = Vec3::new(0.0, y, 0.0);
                let sphere = Sphere {
                    center,
                    radius,
                    material,
                };
                scene.add_sphere(sphere).unwrap();
            }
            let light = Light::Distant {
                direction: Vec3::new(-1.0, -1.0, -1.0),
                color: LinearRgb::new(1.0, 1.0, 1.0),
                intensity: 1.0,
            };
            scene.add_light(light).unwrap();
            PreparedFixed::new(&scene, 64, 48).unwrap()
        };
        let resting = frame_of(0.0);
        assert!(resting.narrow.is_some() && resting.depth_ordered);
        assert_eq!(resting.depth_rank[..2], [1, 0]);
        let sunk = frame_of(-0.01);
        assert!(sunk.narrow.is_some() && !sunk.depth_ordered);
        assert_eq!(sunk.depth_rank[..2], [0, 0]);
    }
}
