//! The float narrow kernel's shadow rows (`NarrowSphere::shadows`, feature `shadow-rows`):
//! for a floor, the rows of the frame on which a caster can block a light on it at all, made
//! once per frame, so that its pixels on every other row skip the casters' filters and rays
//! (`narrow`'s light stage, in the packets whose only candidate is the floor; their own
//! shadow stays).
//!
//! # Why
//!
//! On a floor the caster filter (`NarrowLight::ahead`, `reach`, from `N·L` alone) passes
//! nearly every pixel, for every light: `N·L` is about the same over a floor, although the
//! spheres' shadows on it cover a band of rows. Outside that band the rows skip the filter and
//! the shadow rays for one test per run of the floor alone (`Prepared::single`, which gives
//! such a run no caster filters there). Packets with several candidates, a few next to the
//! spheres on the floor, test the casters on every row: a test per packet there costs the
//! kernel more than it saves. As on the fixed
//! path (`src/fixed/narrow_shadow_rows.rs`), only a receiver four times the radius of each of
//! its casters gets rows of its own: on spheres of like sizes the shadows cover most of the
//! sphere, and every row is kept for nothing.
//!
//! # How
//!
//! The geometry is [`crate::shadow_rows`]', which the fixed path shares: each caster's shadow
//! volume for each light, bounded on the receiver and projected onto the screen's rows. This
//! file gives it the float path's geometry (the scene's centres and radii, the eye and the
//! narrow view's `F` and `Sy`, the lights' directions) and margins for the rounding of its
//! `f32` rays. The absolute ones scale, as that rounding does, with the scene's extent,
//! through the ray's lift `ε` (`10⁻⁴` of the largest coordinate, a thousand times an `f32`
//! rounding of it): the casters are widened by `2⁻¹⁰` of their radius and `5ε` (the lift,
//! the lifted point's and the shadow test's rounding), each interval of a volume's axis by
//! `ε` besides the shared margin, and a cap within `ε` of the eye's plane keeps every row.
//! The receiver's surface is widened by `ε/64` (the rounding of the hit's coordinates, 16
//! times over) and `2⁻¹⁶` of its farthest distance from the eye: the narrow hit lies off the
//! surface by at most the error of its `N·V` times the radius, `|ô|·r·2⁻¹⁸` (see
//! `narrow::COS_ERROR`, measured at under 0.6 of it), which that is four times over. The
//! surface's margin is the one that costs rows: a cap's disc on a floor of radius `R`
//! widens by about `√(2Rδ)` for a margin `δ`. Where the geometry cannot bound the rows every
//! row is kept: the rows only ever skip pixels no caster can block, which
//! `the_shadow_rows_change_no_pixel` holds on random floors.

use super::prepare::{FloatPath, Prepared};
use crate::scene::Scene;
use crate::shadow_rows::{caster_rows, distance, Light, Screen, P3};
use crate::vec3::Vec3;

fn p3(v: Vec3) -> P3 {
    [v.x, v.y, v.z]
}

impl<W: FloatPath, const S: usize, const L: usize> Prepared<W, S, L> {
    /// `NarrowSphere::shadows` of sphere `i` of `scene`, on the narrow view whose step up is
    /// `sy`: the rows, `[first, end)`, outside which no caster of the sphere
    /// (`NarrowLight::casters`, for any light) can block a light; empty if it has none. Needs
    /// the frame's `narrow_lights`. See the module docs. Out of line: once per sphere.
    #[inline(never)]
    pub(super) fn shadow_rows(&self, scene: &Scene<S, L>, i: usize, sy: Vec3) -> (u16, u16) {
        // The frame's height is at most `MAX_DIMENSION`, which fits 16 bits.
        let whole = (0, self.height as u16);
        let (Some(own), Some(lights)) = (scene.spheres().get(i), self.narrow_lights.get(i)) else {
            return whole;
        };
        let casters = lights.iter().fold(0, |m, l| m | l.casters);
        if casters == 0 {
            return (0, 0);
        }
        // Only a receiver four times the radius of each of its casters: a floor.
        let spheres = scene.spheres().iter().enumerate().take(32);
        if spheres
            .filter(|(k, _)| casters & (1 << k) != 0)
            .any(|(_, s)| s.radius > own.radius / 4.0)
        {
            return whole;
        }
        let eps = self.epsilon;
        // A cap within `ε` of the eye's plane keeps every row.
        let dirs = (p3(self.forward), p3(sy));
        let screen = Screen::new(p3(self.eye), dirs, self.height, eps);
        let center = p3(own.center);
        let reach = distance(center, screen.eye()) + own.radius;
        let receiver = (center, own.radius, eps / 64.0 + reach / 65536.0);
        let (mut first, mut last) = (f32::INFINITY, f32::NEG_INFINITY);
        for (light, constants) in self.lights.iter().zip(lights) {
            let super::prepare::PreparedLight::Distant { to_light, .. } = *light else {
                return whole;
            };
            let light = Light::Distant(p3(-to_light));
            for (k, caster) in scene.spheres().iter().enumerate().take(32) {
                if constants.casters & (1 << k) == 0 {
                    continue;
                }
                let r = caster.radius * (1.0 + 1.0 / 1024.0) + 5.0 * eps;
                let caster = (p3(caster.center), r);
                let Some(seen) = caster_rows(light, caster, receiver, &screen, eps) else {
                    return whole;
                };
                (first, last) = (first.min(seen.0), last.max(seen.1));
            }
        }
        screen.rows((first, last))
    }
}

#[cfg(test)]
mod tests {
    use crate::test_scenes::{random_floor_scene, uniform};
    use crate::{FloatPath, HitRecord, LinearRgb, Prepared, Render, Scalar, Scene, Simd8};
    extern crate std;
    use std::vec::Vec;

    /// The frame's colours (as bits) and hit records at its size.
    fn render<W: FloatPath>(frame: &Prepared<W, 8, 4>) -> (Vec<[u32; 3]>, Vec<HitRecord>) {
        let size = (frame.width * frame.height) as usize;
        let mut colours = std::vec![LinearRgb::default(); size];
        let mut hits = std::vec![HitRecord::default(); size];
        frame.render_frame(&mut colours).unwrap();
        frame.render_frame(&mut hits).unwrap();
        let bits = colours.iter().map(|c| [c.r, c.g, c.b].map(f32::to_bits));
        (bits.collect(), hits)
    }

    /// `frame` with every sphere's shadow rows opened to the whole frame.
    fn every_row<W: FloatPath + Clone>(frame: &Prepared<W, 8, 4>) -> Prepared<W, 8, 4> {
        let mut whole = frame.clone();
        for s in whole.spheres.iter_mut() {
            if let Some(n) = s.narrow.as_mut() {
                n.shadows = (0, frame.height as u16);
            }
        }
        whole
    }

    /// The `floor` preset and random floors under distant lights.
    fn floors() -> Vec<Scene<8, 4>> {
        let mut next = uniform(0x5eed_f10a_7c0d_e5ad);
        let scene = crate::test_scenes::with_capacity(&crate::presets::floor().unwrap());
        let mut scenes = std::vec![scene];
        scenes.extend((0..60).map(|_| random_floor_scene(&mut next)));
        scenes
    }

    /// Per pixel of `frame`'s hit records `hits`, whether a caster blocks a light there: its
    /// shadow bits differ from those of the frame without casters.
    fn caster_shadowed<W: FloatPath + Clone>(
        frame: &Prepared<W, 8, 4>,
        hits: &[HitRecord],
    ) -> Vec<bool> {
        let mut lone = frame.clone();
        for lights in lone.narrow_lights.iter_mut() {
            lights.iter_mut().for_each(|l| l.casters = 0);
        }
        let (_, alone) = render(&lone);
        hits.iter().zip(&alone).map(|(a, b)| a != b).collect()
    }

    /// `frame` with the shadow rows of its sphere 0 (a floor) set to `shadows`.
    fn with_rows<W: FloatPath + Clone>(
        frame: &Prepared<W, 8, 4>,
        shadows: (u16, u16),
    ) -> Prepared<W, 8, 4> {
        let mut f = frame.clone();
        if let Some(n) = f.spheres[0].narrow.as_mut() {
            n.shadows = shadows;
        }
        f
    }

    /// The shadow rows skip only pixels no caster blocks: on the `floor` preset and on
    /// random floors under distant lights, every pixel's colour (to the bit) and hit record
    /// (with its shadow bits) is the same with the rows as with every row kept, on the
    /// scalar and the 8-lane path. The rows must skip an eighth of the covered pixels, and a
    /// fiftieth of them must lie in a caster's shadow, or the test proves little.
    #[test]
    fn the_shadow_rows_change_no_pixel() {
        let size = (240u32, 180u32);
        let (mut frames, mut outside, mut covered, mut shadowed) = (0, 0usize, 0usize, 0usize);
        for (n, scene) in floors().iter().enumerate() {
            let frame = Prepared::<Scalar, 8, 4>::new(scene, size.0, size.1).unwrap();
            if frame.narrow.is_none() {
                continue;
            }
            frames += 1;
            let want = render(&frame);
            assert!(want == render(&every_row(&frame)), "scalar, scene {n}");
            let simd = Prepared::<Simd8, 8, 4>::new(scene, size.0, size.1).unwrap();
            assert!(want == render(&simd), "simd8, scene {n}");
            let simd_whole = render(&every_row(&simd));
            assert!(want == simd_whole, "simd8 on every row, scene {n}");
            let hits = want.1;
            let blocked = caster_shadowed(&frame, &hits);
            shadowed += blocked.iter().filter(|&&b| b).count();
            let rows_of = |sphere: usize| frame.spheres[sphere].narrow.unwrap().shadows;
            let (seen, off) = crate::test_scenes::outside_rows(&hits, size.0, rows_of);
            (covered, outside) = (covered + seen, outside + off);
        }
        assert!(frames >= 40, "only {frames} narrow frames");
        assert!(
            outside * 8 > covered,
            "{outside} of {covered} covered pixels outside the shadow rows"
        );
        assert!(
            shadowed * 50 > covered,
            "{shadowed} of {covered} covered pixels in a caster's shadow"
        );
    }

    /// The kernel skips the casters' tests on the rows outside a sphere's shadow rows, and
    /// only there: with each floor's rows set to the rows where a caster blocks a light on
    /// it (from the frame with every row kept) the frame is the same at every width; with
    /// either end one row tighter, the scalar frame differs on most floors (where a pixel
    /// of the row left out, blocked, lies in a run of the floor alone, which skips its
    /// casters; packets with several candidates test them on every row). This is what makes
    /// a shadow row missed by `the_shadow_rows_change_no_pixel` show there.
    #[test]
    fn the_rows_skip_exactly_the_rows_outside_them() {
        let size = (96u32, 72u32);
        let (mut tried, mut shown) = (0, 0);
        for (n, scene) in floors().iter().enumerate() {
            let frame = Prepared::<Scalar, 8, 4>::new(scene, size.0, size.1).unwrap();
            if frame.narrow.is_none() {
                continue;
            }
            let whole = every_row(&frame);
            let want = render(&whole);
            let blocked = caster_shadowed(&whole, &want.1);
            let hits = want.1.iter().zip(&blocked).enumerate();
            let rows = hits.filter_map(|(k, (h, &b))| {
                (b && h.sphere == Some(0)).then_some((k as u32 / size.0) as u16)
            });
            let (Some(first), Some(last)) = (rows.clone().min(), rows.max()) else {
                continue;
            };
            tried += 1;
            let simd = every_row(&Prepared::<Simd8, 8, 4>::new(scene, size.0, size.1).unwrap());
            let exact = (first, last + 1);
            assert!(
                render(&with_rows(&whole, exact)) == want,
                "scalar, scene {n}"
            );
            assert!(render(&with_rows(&simd, exact)) == want, "simd8, scene {n}");
            let tighter = [(first + 1, last + 1), (first, last)];
            shown += tighter
                .iter()
                .filter(|&&rows| render(&with_rows(&whole, rows)) != want)
                .count();
        }
        assert!(tried >= 20, "only {tried} floors with caster shadows");
        assert!(
            shown * 4 > tried * 2 * 3,
            "one row tighter showed in {shown} of {} tries",
            tried * 2
        );
    }
}
