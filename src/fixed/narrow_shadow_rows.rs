//! The rows of a floor's shadows (`NarrowSphere::shadows`): the rows of the frame on which a
//! caster can block a light on a sphere at all, made once per frame, so that the sphere's
//! pixels on every other row skip the casters' filters and rays ([`super::narrow`]'s shadow
//! stages).
//!
//! # Why
//!
//! The narrow kernel's filters settle a caster per pixel in a few dozen instructions, but
//! on a floor they run on nearly every pixel of the floor, for every light: `N·L` is about
//! the same over a floor, so the `N·L` filter (`NarrowLight::ahead`, `reach`) passes it
//! everywhere, although the spheres' shadows cover a band of it. The rows skip them outside
//! that band for one flag a pixel, set per run. Only a receiver four times the radius of each
//! of its casters (a floor) gets rows of its own; on spheres of like sizes the shadows cover
//! most of the sphere and every row is kept, which costs the prepare nothing.
//!
//! # How
//!
//! A ray from a point `X` toward a light meets a caster of radius `r` only if `X` lies in the
//! caster's shadow volume: for a distant light the half-cylinder of radius `r` along the
//! light behind the caster, for a point light the cone from the light through the caster,
//! beyond its near side. With `A(s)` the volume's axis at `s` along it and `ρ(s)` its radius
//! there (constant, or growing linearly from a point light), such an `X` on the receiver
//! (centre `C`, radius `R`) has `A(s)` within `ρ(s)` of the receiver's surface, which bounds
//! `s` to at most two intervals (the axis entering and leaving the receiver's shell), each
//! from one quadratic; and `X` is on the part of the receiver the eye sees
//! (`(X − C)·(E − C) ≥ R²`), which bounds `s` once more. Each interval is cut in
//! [`PIECES`]; the volume over a piece lies in a ball around its middle, and the shadow on
//! the receiver in that ball's cap of the receiver's surface, a disc seen at a slant
//! ([`Screen::cap`]), whose rows follow from each camera coordinate's interval. The rows
//! are the union of those over the sphere's casters and lights, widened by two.
//!
//! In `f32` from the scaled integer geometry, with margins that cover its rounding many
//! times over: the casters widened by `2⁻¹⁰` of their radius and `4ε` (which also covers
//! the shadow ray's lift), the receiver's surface by `2⁻²⁰` of its distance from the eye,
//! each interval by `2⁻¹¹` of the lengths it is made from. A cap that reaches the eye's
//! plane, a light within a caster, or a caster that subtends too wide a cone from a point
//! light keeps every row: the rows only ever skip pixels no caster can block, which the
//! crate's tests hold against the exact rays (`the_shadow_rows_change_no_pixel`, and the
//! shadow stages' assertions under `cfg(test)`).

use super::prepare::{FixedLight, FixedSphere, NarrowView, PreparedFixed};
use super::vector::{Len, V3};

/// The pieces an interval of a shadow volume is bounded in (see [`Screen::cap`]).
const PIECES: usize = 8;

/// A point or vector in raw units (`f32`).
type P3 = [f32; 3];

/// `a > b`, false where either is NaN (which then keeps every row).
fn greater(a: f32, b: f32) -> bool {
    a.partial_cmp(&b) == Some(core::cmp::Ordering::Greater)
}

#[inline(never)]
fn dot(a: P3, b: P3) -> f32 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn minus(a: P3, b: P3) -> P3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn length(a: P3) -> f32 {
    root(dot(a, a))
}

/// `√x` (`libm`'s, correctly rounded), out of line: on a core without an FPU every copy is
/// a few hundred bytes of flash, and the prepare takes it a few dozen times a sphere.
#[inline(never)]
fn root(x: f32) -> f32 {
    libm::sqrtf(x)
}

fn raw(v: &V3<Len>) -> P3 {
    v.map(|c| c.to_bits() as f32)
}

/// A shadow volume: its axis `origin + s·dir` for `s ≥ s_min`, of radius `base + slope·s`.
struct Volume {
    origin: P3,
    dir: P3,
    base: f32,
    slope: f32,
    s_min: f32,
}

impl Volume {
    /// The volume of a caster at `center` of radius `r` (raw, already widened) for `light`;
    /// `None` where it cannot be bounded so (a light within or close to the caster).
    fn new(light: &FixedLight, center: P3, r: f32) -> Option<Self> {
        match light {
            FixedLight::Distant { to_light, .. } => Some(Volume {
                origin: center,
                dir: to_light.map(|c| -(c.to_bits() as f32) / (1u64 << 30) as f32),
                base: r,
                slope: 0.0,
                s_min: -r,
            }),
            FixedLight::Point { position, .. } => {
                let p = raw(position);
                let v = [center[0] - p[0], center[1] - p[1], center[2] - p[2]];
                let d0 = length(v);
                // A cone wider than about 26° from the light: left unbounded.
                if !greater(d0, 2.5 * r) {
                    return None;
                }
                let slope = r / root(d0 * d0 - r * r) * (1.0 + 1.0 / 1024.0);
                Some(Volume {
                    origin: p,
                    dir: v.map(|c| c / d0),
                    base: 0.0,
                    slope,
                    s_min: d0 - r,
                })
            }
            #[allow(unreachable_patterns)]
            _ => None,
        }
    }

    fn at(&self, s: f32) -> (P3, f32) {
        let [o, d] = [self.origin, self.dir];
        let c = [o[0] + s * d[0], o[1] + s * d[1], o[2] + s * d[2]];
        (c, self.base + self.slope * s)
    }
}

/// The screen's rows: each pixel's direction is `F + dx·Sx + dy·Sy` with
/// `dy = height − 2y − 1` (the narrow view); here the unit vectors along `F` and `Sy`, and
/// the scale from a tangent above the view's axis to `dy`.
struct Screen {
    eye: P3,
    /// The unit vectors along `F` (the depth) and along `Sy` (up).
    axes: [P3; 2],
    /// `|F|/|Sy|`: `dy` per unit of the tangent.
    scale: f32,
    height: f32,
}

impl Screen {
    fn new(view: &NarrowView, eye: P3, height: u32) -> Self {
        let f = view.forward.map(|c| c as f32);
        let sy = view.step_y.map(|c| c as f32);
        let (lf, ly) = (length(f), length(sy));
        Screen {
            eye,
            axes: [f.map(|c| c / lf), sy.map(|c| c / ly)],
            scale: lf / ly,
            height: height as f32,
        }
    }

    /// The rows (fractional, `(first, last)`) of the part of a receiver's surface
    /// (`(centre, radius, δ)`) within `rho` of `center`, or `None` if it reaches the eye's
    /// plane; `first > last` if there is none.
    ///
    /// That part is a cap of the receiver: the points `X` with `(X − C)·n̂ ≥ τ`, `n̂` toward
    /// `center` and `τ` from the triangle of the two radii and the centres' distance. It lies
    /// in a disc of the cap's radius `a` across `n̂`, thick from `τ` to `R` along it (each
    /// widened by `δ`), so each camera coordinate of its points lies in an interval, and the
    /// screen coordinates (their ratios to the depth) between those of the intervals' ends.
    /// On a floor, whose caps are flat and seen at a slant, this is several times tighter
    /// than the ball around `center`.
    #[inline(never)]
    fn cap(&self, center: P3, rho: f32, (c, r, delta): (P3, f32, f32)) -> Option<(f32, f32)> {
        let v = minus(center, c);
        let dl = length(v);
        let (outer, tau) = if dl > rho {
            let tau = (r * r + dl * dl - rho * rho) / (2.0 * dl);
            // A point up to δ off the surface moves τ by up to δ·R/|A − C|.
            let tau = tau - delta * (1.0 + r / dl);
            if tau > r + delta {
                return Some((1.0, 0.0));
            }
            (r + delta, tau.max(-r - delta))
        } else {
            // The ball holds the receiver's centre: the whole receiver.
            (r + delta, -r - delta)
        };
        let n = if dl > 0.0 {
            v.map(|k| k / dl)
        } else {
            [0.0; 3]
        };
        let across = if tau > 0.0 {
            root(outer * outer - tau * tau)
        } else {
            outer
        };
        let q = minus(c, self.eye);
        // Each camera coordinate's interval: the centre's, the thickness along n̂, the disc.
        let range = |axis: P3| {
            let (base, along) = (dot(q, axis), dot(n, axis));
            let (a, b) = (tau * along, outer * along);
            let wide = across * root((1.0 - along * along).max(0.0));
            (base + a.min(b) - wide, base + a.max(b) + wide)
        };
        let [z, y] = self.axes.map(range);
        if !greater(z.0, 1.0) {
            return None;
        }
        // The tangents above the axis at the interval's ends, over the nearest and the
        // farthest depth; y = (h − 1 − dy)/2 with dy = tangent·|F|/|Sy|.
        let (low, high) = ((y.0 / z.0).min(y.0 / z.1), (y.1 / z.0).max(y.1 / z.1));
        let row = |t: f32| (self.height - 1.0 - t * self.scale) / 2.0;
        Some((row(high), row(low)))
    }
}

/// The intervals of `s` (at most two) where `volume` can reach the surface of a receiver at
/// `center` of radius `r`, seen from `eye`, its surface widened by `delta`; empty ones have
/// `lo > hi`.
/// The two `s` where `|A(s) − C| = r₀ + k·s`, with `p = (A(0) − C)·dir` and `|A(0) − C|`
/// (`s² + 2ps + |A(0) − C|² = (r₀ + k·s)²`, `k² < 1`): `None` where there are none, a
/// discriminant within rounding below 0 taken as 0 (the axis touching the sphere).
fn crossings((p, wl): (f32, f32), k: f32, r0: f32) -> Option<(f32, f32)> {
    let a = 1.0 - k * k;
    let b = p - r0 * k;
    let c = (wl - r0) * (wl + r0);
    let disc = b * b - a * c;
    if disc < -(b * b + (a * c).abs()) / 4096.0 {
        return None;
    }
    let root = root(disc.max(0.0));
    Some(((-b - root) / a, (-b + root) / a))
}

#[inline(never)]
fn intervals(volume: &Volume, (center, r, delta): (P3, f32, f32), eye: P3) -> [(f32, f32); 2] {
    const EMPTY: [(f32, f32); 2] = [(1.0, 0.0); 2];
    let w = minus(volume.origin, center);
    let (p, wl, k) = (dot(w, volume.dir), length(w), volume.slope);
    let margin = (p.abs() + wl + r) / 2048.0 + 64.0;
    let outer = r + delta + volume.base;
    let Some((o0, o1)) = crossings((p, wl), k, outer) else {
        return EMPTY;
    };
    let (lo, hi) = ((o0 - margin).max(volume.s_min - margin), o1 + margin);
    // Where the whole cross-section is inside the receiver's shell: no surface there.
    let inner = r - delta - volume.base;
    // Where `inner − k·s ≤ 0` nothing is excluded: the roots of (inner − k·s)² = |A − C|².
    let hole = if inner > 0.0 {
        crossings((p, wl), -k, inner).map(|(i0, i1)| {
            let i1 = if k > 0.0 { i1.min(inner / k) } else { i1 };
            (i0 + margin, i1 - margin)
        })
    } else {
        None
    };
    let mut pieces = match hole {
        Some((i0, i1)) if i0 < i1 => [(lo, hi.min(i0)), (lo.max(i1), hi)],
        _ => [(lo, hi), (1.0, 0.0)],
    };
    // The part of the receiver the eye sees: (X − C)·ê ≥ R²/|e| − δ with X within the
    // volume's radius of the axis: s·(dir·ê + k) ≥ R²/|e| − δ − base − w·ê.
    let e = minus(eye, center);
    let el = length(e);
    if el > r {
        let unit = e.map(|c| c / el);
        let slope = dot(volume.dir, unit) + k;
        let bound = r * r / el - delta - volume.base - dot(w, unit);
        // A shallower slope would take `s` far out, where `f32` rounding outgrows the margin:
        // no bound from it.
        if slope.abs() > 1.0 / 64.0 {
            let s = bound / slope;
            for piece in &mut pieces {
                if slope > 0.0 {
                    piece.0 = piece.0.max(s - margin);
                } else {
                    piece.1 = piece.1.min(s + margin);
                }
            }
        }
    }
    pieces
}

impl<const S: usize, const L: usize> PreparedFixed<S, L> {
    /// `NarrowSphere::shadows` of sphere `i` on the frame's narrow `view`: the rows,
    /// `[start, end)`, outside which no caster of the sphere (`NarrowLight::casters`, for any
    /// light) can block a light; empty if it has none. See the module docs. Out of line:
    /// once per sphere.
    #[inline(never)]
    pub(super) fn shadow_rows(&self, i: usize, view: &NarrowView) -> (u16, u16) {
        // The frame's height is at most `MAX_DIMENSION`, which fits 16 bits.
        let whole = (0, self.height as u16);
        let (Some(own), Some(lights)) = (self.spheres.get(i), self.narrow_lights.get(i)) else {
            return whole;
        };
        // Only a receiver four times the radius of each of its casters (a floor under the
        // spheres resting on it) gets rows of its own: its shadows cover a band of it, where
        // on spheres of like sizes they cover most of the sphere, and the `f32` arithmetic
        // (library calls on cores without an FPU) would cost the prepare more than it saves.
        let casters = lights.iter().fold(0, |m, l| m | l.casters);
        let small = |(k, s): (usize, &FixedSphere)| {
            k < 32 && casters & (1 << k) != 0 && s.radius.to_bits() > own.radius.to_bits() / 4
        };
        if casters == 0 {
            return (0, 0);
        }
        if self.spheres.iter().enumerate().any(small) {
            return whole;
        }
        let screen = Screen::new(view, raw(&self.eye), self.height);
        let radius = own.radius.to_bits() as f32;
        // The hit's distance from the receiver's surface: the rounding of the hit and of the
        // `f32` lengths involved, each many times over. (The shadow ray's lift off the
        // surface widens the casters instead.)
        let reach = length(minus(raw(&own.center), screen.eye)) + radius;
        let receiver = (raw(&own.center), radius, 1024.0 + reach / (1 << 20) as f32);
        let (mut first, mut last) = (f32::INFINITY, f32::NEG_INFINITY);
        for (light, constants) in self.lights.iter().zip(lights) {
            for (k, caster) in self.spheres.iter().enumerate().take(32) {
                if constants.casters & (1 << k) == 0 {
                    continue;
                }
                let Some(seen) = self.caster_rows(light, caster, receiver, &screen) else {
                    return whole;
                };
                (first, last) = (first.min(seen.0), last.max(seen.1));
            }
        }
        if first > last {
            return (0, 0);
        }
        let clamp = |v: f32| libm::floorf(v).max(0.0).min(screen.height) as u16;
        (clamp(first - 2.0), clamp(last + 3.0))
    }

    /// The rows of `caster`'s shadow for `light` on `receiver` (`(centre, radius, δ)`):
    /// `(first, last)` fractional, `first > last` if none; `None` where they cannot be
    /// bounded.
    fn caster_rows(
        &self,
        light: &FixedLight,
        caster: &FixedSphere,
        receiver: (P3, f32, f32),
        screen: &Screen,
    ) -> Option<(f32, f32)> {
        let eps = self.epsilon.to_bits() as f32;
        let r = caster.radius.to_bits() as f32 * (1.0 + 1.0 / 1024.0) + 4.0 * eps + 64.0;
        let volume = Volume::new(light, raw(&caster.center), r)?;
        let mut seen = (f32::INFINITY, f32::NEG_INFINITY);
        for (lo, hi) in intervals(&volume, receiver, screen.eye) {
            if lo.is_nan() || hi.is_nan() {
                return None;
            }
            if lo > hi {
                continue;
            }
            // The interval in pieces, each in a ball around its middle (the volume between
            // two cross-sections lies in the hull of the balls at its ends), each ball's cap.
            let step = (hi - lo) / PIECES as f32;
            for j in 0..PIECES {
                let (center, rho) = volume.at(lo + (j as f32 + 0.5) * step);
                let reach = rho + volume.slope * step / 2.0 + step / 2.0 + receiver.2;
                let (first, last) = screen.cap(center, reach, receiver)?;
                seen = (seen.0.min(first), seen.1.max(last));
            }
        }
        Some(seen)
    }
}
#[cfg(test)]
mod tests {
    use crate::test_scenes::{random_floor_scene, random_lamp_scene, uniform};
    use crate::{HitRecord, PreparedFixed, Render, Rgb888, Scene};
    extern crate std;
    use std::vec::Vec;

    /// The frame's colours and hit records at `w × h`.
    fn render(frame: &PreparedFixed<8, 4>, (w, h): (u32, u32)) -> (Vec<Rgb888>, Vec<HitRecord>) {
        let mut colours = std::vec![Rgb888::default(); (w * h) as usize];
        let mut hits = std::vec![HitRecord::default(); (w * h) as usize];
        frame.render_frame(&mut colours).unwrap();
        frame.render_frame(&mut hits).unwrap();
        (colours, hits)
    }

    /// The shadow rows skip only pixels no caster blocks: on the scene matrix and on random
    /// floors under distant and point lights, every pixel's colour and hit record is the
    /// same with the rows as with every row kept (and under `cfg(test)` each skipped
    /// pixel's exact rays are asserted unblocked). The rows must skip an eighth of the
    /// covered pixels, or the test proves little.
    #[test]
    fn the_shadow_rows_change_no_pixel() {
        let mut next = uniform(0x5eed_b0c5_0f5e_ad0e);
        let mut scenes: Vec<Scene<8, 4>> = Vec::new();
        for preset in [
            crate::presets::floor,
            crate::presets::lamp,
            crate::presets::three_lights,
        ] {
            let m = preset().unwrap();
            let mut scene = Scene::<8, 4>::new(*m.camera(), m.background()).unwrap();
            for s in m.spheres() {
                scene.add_sphere(*s).unwrap();
            }
            for l in m.lights() {
                scene.add_light(*l).unwrap();
            }
            scenes.push(scene);
        }
        for n in 0..48 {
            scenes.push(if n % 2 == 0 {
                random_floor_scene(&mut next)
            } else {
                random_lamp_scene(&mut next)
            });
        }
        let size = (96u32, 72u32);
        let (mut outside, mut covered) = (0usize, 0usize);
        for (n, scene) in scenes.iter().enumerate() {
            let Ok(frame) = PreparedFixed::<8, 4>::new(scene, size.0, size.1) else {
                continue;
            };
            if frame.narrow.is_none() {
                continue;
            }
            let mut whole = frame.clone();
            for s in whole.spheres.iter_mut() {
                if let Some(n) = s.narrow.as_mut() {
                    n.shadows = (0, size.1 as u16);
                }
            }
            let (colours, hits) = render(&frame, size);
            assert!((colours, hits.clone()) == render(&whole, size), "scene {n}");
            for (k, hit) in hits.iter().enumerate() {
                let Some(sphere) = hit.sphere.map(usize::from) else {
                    continue;
                };
                covered += 1;
                let y = (k as u32 / size.0) as u16;
                let (first, end) = frame.spheres[sphere].narrow.unwrap().shadows;
                if !(first <= y && y < end) {
                    outside += 1;
                }
            }
        }
        assert!(
            outside * 8 > covered,
            "{outside} of {covered} covered pixels outside the shadow rows"
        );
    }
}
