//! The full-width kernel's `incoming` stage: a light as seen from one surface point, its
//! direction, the colour that arrives there and the length of the shadow ray toward it.
//!
//! It sits below both the kernel's light loop (`kernel`) and the sphere lights' stages
//! (`kernel_sphere`), which build their own `Incoming` from the representative point, so
//! both use it without using each other.

use super::exact::arriving;
use super::mul::mul_iu;
use super::prepare::{FixedLight, PreparedFixed};
use super::roots::{inv_sqrt, sqrt};
use super::vector::{each3, length_sq, to_len, Len, Unit, V3};
use fixed::types::U16F16;

/// A light as seen from one surface point.
pub(super) struct Incoming {
    /// Unit vector toward the light; zero if the point is at the light.
    pub(super) to_light: V3<Unit>,
    /// Arriving light per channel.
    pub(super) arriving: [u32; 3],
    /// Distance to a point light (raw I16F16); `None` for a distant light.
    pub(super) reach: Option<i64>,
}

/// Component `v` (raw I16F16) of a vector over its length, `1/|v| = y·2^-shift` as
/// [`inv_sqrt`] returns it: I2F30, clamped to `[−1, 1]`.
#[inline(always)]
pub(super) fn unit_component(v: i64, (y, shift): (u32, u32)) -> Unit {
    let u = mul_iu(to_len(v).to_bits(), y) >> (shift - 30).min(63);
    Unit::from_bits(u.clamp(-(1 << 30), 1 << 30) as i32)
}

impl<const S: usize, const L: usize> PreparedFixed<S, L> {
    /// One light as seen from `p`: direction toward it, arriving colour, shadow-ray length.
    #[inline(always)]
    pub(super) fn incoming(&self, light: &FixedLight, p: V3<Len>) -> Incoming {
        match *light {
            FixedLight::Distant { to_light, arriving } => Incoming {
                to_light,
                arriving: arriving.map(U16F16::to_bits),
                reach: None,
            },
            // Shaded by `sphere_incoming`, never here; as the point at its centre otherwise.
            #[cfg(feature = "area-lights")]
            FixedLight::Sphere {
                position, power, ..
            } => self.incoming(&FixedLight::Point { position, power }, p),
            FixedLight::Point { position, power } => {
                // Both points lie within ±2¹³ units: the difference fits I16F16.
                let lv = each3(|i| position[i].to_bits() as i64 - p[i].to_bits() as i64);
                let d2 = length_sq(lv).max(0) as u64;
                let Some((y, shift)) = inv_sqrt(d2) else {
                    // At the light: arriving light is capped, the direction is undefined.
                    return Incoming {
                        to_light: [Unit::ZERO; 3],
                        arriving: [u32::MAX; 3],
                        reach: Some(0),
                    };
                };
                Incoming {
                    to_light: lv.map(|c| unit_component(c, (y, shift))),
                    arriving: arriving(power, (y, shift)),
                    reach: Some(sqrt(d2) as i64),
                }
            }
        }
    }
}
