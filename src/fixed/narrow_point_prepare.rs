//! The fast point light's per-frame constants ([`super::narrow_point`]), made by the narrow
//! prepare ([`super::narrow_prepare`]) for each sphere and point light: where the fast point
//! light serves on the sphere and its lobe's limit (`PointConstants::fast`), and the sphere's cone as a
//! caster seen from the light (`point_cone`), for the shadow filters
//! ([`super::narrow_point_shadow`]).

use super::convert::to_f32;
use super::exact::arriving;
use super::narrow_point::{point_error, CONE_MARGIN};
use super::narrow_prepare::{fast_lobe_max, H_ERROR};
use super::prepare::{FixedLight, FixedSphere, PreparedFixed};
use super::roots::{inv_sqrt, sqrt};
use super::vector::{each3, Len, V3};

impl<const S: usize, const L: usize> PreparedFixed<S, L> {
    /// [`PointConstants::cone`](super::prepare::PointConstants::cone) of sphere `own` for the point light at `position`: the unit
    /// vector from the light toward the centre and the cosine of the cone's half-angle,
    /// `√(1 − (ρ/|C − P|)²)` with `ρ` the radius widened by `2ε`, a raw unit and `2⁻¹²`,
    /// lowered by [`CONE_MARGIN`]; every point passes where the light is within `ρ` of the
    /// centre (inside or at the sphere). In `f32`: the margin covers its rounding many times.
    #[inline(never)]
    pub(super) fn point_cone(&self, own: &FixedSphere, position: &V3<Len>) -> [i16; 4] {
        let v = each3(|k| (own.center[k].to_bits() as i64 - position[k].to_bits() as i64) as f32);
        let len = libm::sqrtf(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
        let rho = own.radius.to_bits() as f32 * (1.0 + 1.0 / 4096.0)
            + 2.0 * self.epsilon.to_bits() as f32
            + 1.0;
        if len.is_nan() || len <= rho {
            return [0, 0, 0, i16::MIN];
        }
        let ratio = rho / len;
        let cos = libm::sqrtf(1.0 - ratio * ratio) - CONE_MARGIN;
        let q15 = |x: f32| libm::roundf(x * 32768.0).clamp(-32768.0, 32767.0) as i16;
        [
            q15(v[0] / len),
            q15(v[1] / len),
            q15(v[2] / len),
            libm::floorf(cos * 32768.0).clamp(-32768.0, 32767.0) as i16,
        ]
    }

    /// [`PointConstants::fast`](super::prepare::PointConstants::fast), [`PointConstants::ratio`](super::prepare::PointConstants::ratio) and `slack` of sphere `i` for light
    /// `light` (0 unless it is a point light), from the sphere's largest exponent `n` and
    /// its lobes' `scale` (`ks`, or the normalized models' sum of weights). With `F` the
    /// factor of [`point_error`] (`(1 + |Q|/g)²`), the cosines are within `4F` steps of
    /// `2⁻¹⁵` and the arriving light within `16F` relative (`1/d²` from `1/d`): at the
    /// brightest light arriving on the sphere (its power over the square of its distance
    /// from the surface) the diffuse term's error is at most one level (its bound; the errors measured are far below) where
    /// `F ≤ F_d`, and the cosines are within `2⁻⁹` (which the cones' `CONE_MARGIN` allows
    /// for) where `F ≤ 16`. The ratio is `(√F − 1)²` for the least of these (every pixel if
    /// the sphere's own factor, at its nearest point to the light, is below it; none if it
    /// is below 1), the lobe's limit that of `fast_lobe_max` with `h`'s error three times
    /// the cosines' at that `F` and the fast `h`'s own ([`H_ERROR`]), and the slack of the
    /// shadow filters twice the cosines' bound.
    #[inline(never)]
    pub(super) fn point_fast(
        &self,
        i: usize,
        light: usize,
        (n, scale): (f32, f32),
    ) -> (u16, u8, u8) {
        let (Some(own), Some(FixedLight::Point { position, power }), Some(point)) = (
            self.spheres.get(i),
            self.lights.get(light),
            self.points.get(light),
        ) else {
            return (0, 0, 0);
        };
        let w = each3(|k| position[k].to_bits() as i64 - own.center[k].to_bits() as i64);
        let len2 = w.iter().map(|&v| (v * v) as u64).sum::<u64>();
        let gap = (sqrt(len2) as i64 - own.radius.to_bits() as i64 - 2).max(1) as u64;
        let brightest = inv_sqrt(gap * gap).map_or(u32::MAX, |inv| {
            arriving(*power, inv).into_iter().max().unwrap_or(0)
        });
        let brightest = to_f32(brightest as i64, 16);
        let kd = own
            .kd_albedo
            .iter()
            .map(|k| k.to_num::<f32>())
            .fold(0.0, f32::max);
        let unit = point_error(0.0, 1.0); // the error at F = 1
        let diffuse = 1.0 / (255.0 * brightest * kd * 5.0 * unit);
        let limit = if diffuse.is_nan() {
            0.0
        } else {
            diffuse.min(16.0)
        };
        let own_factor = point_error(point.distance as f32, gap as f32) / unit;
        if limit.is_nan() || limit < 1.0 {
            return (0, 0, 0);
        }
        let (factor, ratio) = if own_factor <= limit {
            // |Q|/g ≤ 3 here: a ratio of 9 (144 in Q4) passes every pixel.
            (own_factor, 255)
        } else {
            let root = libm::sqrtf(limit) - 1.0;
            (limit, (root * root * 16.0) as u8)
        };
        let h_error = 3.0 * unit * factor + H_ERROR;
        // The direction's error, for the shadow filters: twice the cosines' bound, and 4 steps.
        let slack = (2.0 * unit * factor * 32768.0) as u8 + 4;
        let lobe = fast_lobe_max(scale * brightest, n, h_error).clamp(1, u16::MAX as u32);
        (lobe as u16, ratio, slack)
    }
}
