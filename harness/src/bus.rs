//! What a display is sent for a frame: the bytes on its bus for a full frame or for the
//! damage alone, and how many pixels actually changed between two rendered frames.
//!
//! The bus model is that of an MIPI DCS panel (ST7789, ILI9341, …) driven the way mipidsi's
//! `set_pixels` drives it: each write sets an address window, `CASET` (1 command byte and 4
//! parameter bytes), `RASET` (1 + 4) and `RAMWR` (1), [`WINDOW_BYTES`] = 11 bytes of
//! commands, then streams the window's pixels as RGB565, 2 bytes each. A full frame is one
//! window; a damage is one window per damaged range of a row (as
//! [`Damage::render`](shadeline::damage::Damage::render) hands them out with a buffer at
//! least a row wide), or one window when it is the whole frame. Chip select, the data/command
//! pin and any bus turnaround are not counted.

use shadeline::damage::Damage;
use shadeline::Rgb888;

/// Command bytes to set one address window and start the memory write: `CASET` and `RASET`
/// with their 4 parameter bytes each, and `RAMWR`.
pub const WINDOW_BYTES: u64 = 11;

/// Bytes per RGB565 pixel.
pub const PIXEL_BYTES: u64 = 2;

/// What a display is sent for one write: pixels, address windows and bytes on the bus.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Sent {
    /// Pixels written.
    pub pixels: u64,
    /// Address windows set.
    pub windows: u64,
}

impl Sent {
    /// A whole `width × height` frame, as one window.
    pub fn full_frame(width: u32, height: u32) -> Self {
        Sent {
            pixels: u64::from(width) * u64::from(height),
            windows: 1,
        }
    }

    /// The damage alone: one window per damaged range of a row, or one window for a damage
    /// that is the whole frame.
    pub fn damage<const N: usize>(damage: &Damage<N>) -> Self {
        if damage.is_full_frame() {
            return Sent::full_frame(damage.width(), damage.height());
        }
        damage.rows().fold(Sent::default(), |sent, row| Sent {
            pixels: sent.pixels + u64::from(row.pixels()),
            windows: sent.windows + row.ranges().len() as u64,
        })
    }

    /// The bytes on the bus: the pixels' RGB565 bytes and the windows' command bytes.
    pub fn bytes(&self) -> u64 {
        self.pixels * PIXEL_BYTES + self.windows * WINDOW_BYTES
    }

    /// The sum of two writes.
    pub fn plus(self, other: Sent) -> Sent {
        Sent {
            pixels: self.pixels + other.pixels,
            windows: self.windows + other.windows,
        }
    }
}

/// The pixels that differ between two rendered frames of the same size, and how many of
/// them lie outside `damage` (a damage that holds is 0 there).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Changed {
    /// Pixels whose colour differs.
    pub pixels: u64,
    /// Of those, the pixels the damage does not hold.
    pub outside: u64,
}

impl Changed {
    /// Compares `shown` and `next` (row-major, `damage.width()` pixels a row) pixel by
    /// pixel against `damage`. Pixels past the shorter buffer are not compared.
    pub fn between<const N: usize>(shown: &[Rgb888], next: &[Rgb888], damage: &Damage<N>) -> Self {
        let width = damage.width() as usize;
        let mut changed = Changed::default();
        if width == 0 {
            return changed;
        }
        for (y, (a, b)) in shown.chunks(width).zip(next.chunks(width)).enumerate() {
            let row = damage.row(y as u32);
            for (x, _) in a.iter().zip(b).enumerate().filter(|(_, (a, b))| a != b) {
                changed.pixels += 1;
                if !row.contains(x as u32) {
                    changed.outside += 1;
                }
            }
        }
        changed
    }

    /// The sum over two frame pairs.
    pub fn plus(self, other: Changed) -> Changed {
        Changed {
            pixels: self.pixels + other.pixels,
            outside: self.outside + other.outside,
        }
    }
}

/// Damaged pixels over changed pixels, or `None` when nothing changed.
pub fn tightness(damaged: u64, changed: u64) -> Option<f64> {
    (changed > 0).then(|| damaged as f64 / changed as f64)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::animation::{scene_at, Motion};
    use crate::scene_file::{preset, MAX_LIGHTS, MAX_SPHERES};
    use shadeline::{Prepared, Scalar};

    #[test]
    fn a_full_frame_is_its_pixels_and_one_window() {
        let sent = Sent::full_frame(320, 240);
        assert_eq!(sent.bytes(), 320 * 240 * 2 + 11);
    }

    #[test]
    fn a_damage_costs_a_window_per_range_and_the_changes_are_counted_against_it() {
        let scene = preset("floor").unwrap().unwrap().scene;
        let frame = Prepared::<Scalar, MAX_SPHERES, MAX_LIGHTS>::new(&scene, 40, 30).unwrap();
        let none: Damage = Damage::none(&scene, 40, 30);
        assert_eq!(Sent::damage(&none), Sent::default());
        let all: Damage = Damage::full(&scene, 40, 30);
        assert_eq!(Sent::damage(&all), Sent::full_frame(40, 30));
        // A light that changes damages every outline: ranges on many rows, fewer pixels
        // than the frame or as many, and a window per range.
        let next = scene_at(&scene, Motion::OrbitLight(0), 1, 4).unwrap();
        let damage: Damage = Damage::between(&scene, &frame, &next, &frame);
        let sent = Sent::damage(&damage);
        assert!(!damage.is_full_frame() && sent.windows > 1);
        let ranges: u64 = damage.rows().map(|r| r.ranges().len() as u64).sum();
        assert_eq!(sent.windows, ranges);
        assert_eq!(sent.pixels, damage.pixels());
        assert_eq!(sent.bytes(), damage.pixels() * 2 + ranges * 11);

        let black = vec![Rgb888::default(); 40 * 30];
        let mut other = black.clone();
        other[0] = Rgb888 { r: 1, g: 0, b: 0 };
        other[40 * 29 + 39] = Rgb888 { r: 0, g: 0, b: 1 };
        let changed = Changed::between(&black, &other, &none);
        assert_eq!(
            changed,
            Changed {
                pixels: 2,
                outside: 2
            }
        );
        assert_eq!(Changed::between(&black, &other, &all).outside, 0);
        assert_eq!(tightness(6, 2), Some(3.0));
        assert_eq!(tightness(6, 0), None);
    }
}
