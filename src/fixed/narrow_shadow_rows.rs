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
//! The geometry is [`crate::shadow_rows`]', which the float path's narrow kernel shares
//! (`src/float/shadow_rows.rs`): each caster's shadow volume for each light, bounded on the
//! receiver and projected onto the screen's rows. This file gives it the fixed path's
//! geometry and margins: the scaled integer geometry in raw units, as `f32`, with margins
//! that cover its rounding many times over: the casters widened by `2⁻¹⁰` of their radius
//! and `4ε` (which also covers the shadow ray's lift) and 64 raw units, the receiver's
//! surface by 1024 raw units and `2⁻²⁰` of its distance from the eye, each interval of a
//! volume's axis by 64 raw units besides the shared margin. Where the geometry cannot bound
//! the rows every row is kept: the rows only ever skip pixels no caster can block, which the
//! crate's tests hold against the exact rays (`the_shadow_rows_change_no_pixel`, and the
//! shadow stages' assertions under `cfg(test)`).

use super::prepare::{FixedLight, FixedSphere, NarrowView, PreparedFixed};
use super::vector::{Len, V3};
use crate::shadow_rows::{caster_rows, distance, Light, Screen, P3};

/// The absolute part of the margins, in raw units: `2⁻¹⁰` of a unit.
const ABSOLUTE: f32 = 64.0;

fn raw(v: &V3<Len>) -> P3 {
    v.map(|c| c.to_bits() as f32)
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
        let [f, sy] = [view.forward, view.step_y].map(|v| v.map(|c| c as f32));
        // A cap within a raw unit of the eye's plane keeps every row.
        let screen = Screen::new(raw(&self.eye), (f, sy), self.height, 1.0);
        let radius = own.radius.to_bits() as f32;
        // The hit's distance from the receiver's surface: the rounding of the hit and of the
        // `f32` lengths involved, each many times over. (The shadow ray's lift off the
        // surface widens the casters instead.)
        let reach = distance(raw(&own.center), screen.eye()) + radius;
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
        screen.rows((first, last))
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
        let r = caster.radius.to_bits() as f32 * (1.0 + 1.0 / 1024.0) + 4.0 * eps + ABSOLUTE;
        let light = match light {
            FixedLight::Distant { to_light, .. } => {
                Light::Distant(to_light.map(|c| -(c.to_bits() as f32) / (1u64 << 30) as f32))
            }
            FixedLight::Point { position, .. } => Light::Point(raw(position)),
            #[allow(unreachable_patterns)]
            _ => return None,
        };
        caster_rows(light, (raw(&caster.center), r), receiver, screen, ABSOLUTE)
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
            scenes.push(crate::test_scenes::with_capacity(&preset().unwrap()));
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
            let rows_of = |sphere: usize| frame.spheres[sphere].narrow.unwrap().shadows;
            let (seen, off) = crate::test_scenes::outside_rows(&hits, size.0, rows_of);
            (covered, outside) = (covered + seen, outside + off);
        }
        assert!(
            outside * 8 > covered,
            "{outside} of {covered} covered pixels outside the shadow rows"
        );
    }
}
