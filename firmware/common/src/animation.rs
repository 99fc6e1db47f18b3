//! The animations of `firmware/animation.rs` (the floor scene's key light orbiting, one of its
//! spheres bouncing) on the fixed path, each drawn twice: every frame in full, and every frame
//! as its damage against the frame before (`shadeline::damage::Damage::between`, then
//! `render_segment` over the damaged ranges). The firmware's feature `animation`.
//!
//! Measured per frame, each in regions of its own: the scene (the motion's sine and cosine
//! and building the scene), the prepare, the full render (one region per `render_line`), the
//! damage's computation (`Damage::between` and finding each damaged row's ranges) and the
//! damage's render (one region per `render_segment`). The sine and cosine alone are measured
//! once more on their own (`sincos=`), for the micromath/libm comparison.
//!
//! Checked against the host (`expected.rs`, `tests/firmware_crcs.rs`):
//!
//! - the CRC of every frame as the full run rendered it, frames 1 to N one after the other
//!   (`crc=`; the last frame alone is checked too: both animations end where they began,
//!   on the floor scene, so the last frame is `fixed-floor`'s);
//! - the CRC of everything the damage run sends a display (each piece's `x`, `y`, length,
//!   then its pixels), and its damaged pixels: the host renders the same pieces and checks
//!   that laying them over the frame before gives every frame exactly;
//! - with a framebuffer (the M4F), the damage run also lays its pieces over frame 0 in the
//!   framebuffer, and the CRC of what is left there must be the last frame's
//!   (`display_match=`).
//!
//! The report is two lines per animation:
//!
//! ```text
//! shadeline-fw firmware=m0 path=anim-orbit trig=libm frames=30 crc=… expected=…
//!   match=yes stream_crc=… stream_expected=… stream_match=yes pixels=… display=none
//! shadeline-fw firmware=m0 anim=orbit exact=yes full=… damage=… damage_calc=…
//!   damage_render=… prepare=… scene=… sincos=… bytes_full=… bytes_damage=…
//! ```
//!
//! The second line's figures are per frame (one decimal): `damage` = `damage_calc` +
//! `damage_render`; `prepare` and `scene` are the same work in both runs and not in `full`
//! or `damage`; `sincos` is the motion's sine and cosine alone (part of `scene`);
//! `bytes_full` and `bytes_damage` are the RGB565 bytes a display is sent. The frames are
//! `ANIMATION_WIDTH × ANIMATION_HEIGHT` (320×240).

use crate::crc32::Crc32;
use crate::expected::{
    ANIMATION_DAMAGE_PIXELS, ANIMATION_DAMAGE_STREAM_CRC32, ANIMATION_FRAMES_RGB565_CRC32,
    ANIMATION_LAST_RGB565_CRC32,
};
use crate::meter::InstructionCounter;
use crate::run::{Board, Session};
use crate::text::Line;
use shadeline::damage::Damage;
use shadeline::{PreparedFixed, Render, Rgb565};

mod frames {
    include!("../../animation.rs");
}
pub use frames::*;

/// The prepared frame of an animation's frame on the fixed path.
pub type AnimationFixed = PreparedFixed<5, 2>;

/// Where an animation's frames live: two scenes and two prepared frames, the one shown and
/// the next, in turn (statics on the small boards).
pub struct AnimationSlots {
    /// The scenes of frames `k` with `k % 2 == i` in slot `i`.
    pub scenes: [Option<AnimationScene>; 2],
    /// Their prepared frames.
    pub frames: [AnimationFixed; 2],
}

impl AnimationSlots {
    /// Empty slots.
    pub const EMPTY: Self = AnimationSlots {
        scenes: [None, None],
        frames: [PreparedFixed::EMPTY, PreparedFixed::EMPTY],
    };
}

/// Sums of measured regions, `None` once any count was inexact.
#[derive(Clone, Copy)]
struct Sum(Option<u64>);

impl Sum {
    const ZERO: Sum = Sum(Some(0));
    fn add(&mut self, n: Option<u64>) {
        self.0 = self.0.zip(n).map(|(a, b)| a + b);
    }
}

/// The host's figures of one animation (`expected.rs`).
struct Expected {
    /// CRC of frames 1 to N, one after the other.
    frames: u32,
    /// CRC of frame N.
    last: u32,
    /// CRC of what the damage run sends.
    stream: u32,
    /// Damaged pixels of frames 1 to N.
    pixels: u64,
}

/// The figures of one animation.
struct Figures {
    frames_crc: u32,
    last_crc: u32,
    stream_crc: u32,
    display_crc: Option<u32>,
    pixels: u64,
    full: Sum,
    damage_calc: Sum,
    damage_render: Sum,
    prepare: Sum,
    scene: Sum,
    trig: Sum,
    ok: bool,
}

impl<B: Board, C: InstructionCounter> Session<B, C> {
    /// Both animations with the sine and cosine of `T`, into `line` (a row's buffer of at
    /// least `ANIMATION_WIDTH` pixels) and, if given, a `display` framebuffer of
    /// `ANIMATION_WIDTH × ANIMATION_HEIGHT` pixels that the damage run keeps up to date.
    pub fn animations<T: Trig>(
        &mut self,
        slots: &mut AnimationSlots,
        line: &mut [Rgb565],
        mut display: Option<&mut [Rgb565]>,
    ) {
        let (w, h) = (ANIMATION_WIDTH, ANIMATION_HEIGHT);
        let (Some(line), true) = (
            line.get_mut(..w as usize),
            display.as_ref().is_none_or(|d| d.len() >= (w * h) as usize),
        ) else {
            self.note("shadeline-fw error=buffer-animation\n");
            self.fail();
            return;
        };
        for (m, motion) in MOTIONS.into_iter().enumerate() {
            let name = match motion {
                Motion::Orbit => "orbit",
                Motion::Bounce => "bounce",
            };
            let figures = self.animation::<T>(motion, slots, &mut *line, display.as_deref_mut());
            let expected = Expected {
                frames: ANIMATION_FRAMES_RGB565_CRC32[T::INDEX][m],
                last: ANIMATION_LAST_RGB565_CRC32[T::INDEX][m],
                stream: ANIMATION_DAMAGE_STREAM_CRC32[T::INDEX][m],
                pixels: ANIMATION_DAMAGE_PIXELS[T::INDEX][m],
            };
            self.report_animation::<T>(name, &figures, expected);
        }
    }

    /// One animation, in full and as damage.
    fn animation<T: Trig>(
        &mut self,
        motion: Motion,
        slots: &mut AnimationSlots,
        line: &mut [Rgb565],
        mut display: Option<&mut [Rgb565]>,
    ) -> Figures {
        let (w, h) = (ANIMATION_WIDTH, ANIMATION_HEIGHT);
        let mut f = Figures {
            frames_crc: 0,
            last_crc: 0,
            stream_crc: 0,
            display_crc: None,
            pixels: 0,
            full: Sum::ZERO,
            damage_calc: Sum::ZERO,
            damage_render: Sum::ZERO,
            prepare: Sum::ZERO,
            scene: Sum::ZERO,
            trig: Sum::ZERO,
            ok: true,
        };

        // The sine and cosine alone, as the scene regions compute them.
        for k in 1..=ANIMATION_FRAMES {
            let k = core::hint::black_box(k);
            let (params, n) = self.meter().measure(|| motion_at::<T>(motion, k));
            core::hint::black_box(params);
            f.trig.add(n);
        }

        // Every frame in full, all of them into one CRC.
        let mut frames_crc = Crc32::new();
        for k in 1..=ANIMATION_FRAMES {
            let slot = (k % 2) as usize;
            let Some(path) = self.animation_frame::<T>(motion, k, slots, slot, &mut f) else {
                f.ok = false;
                return f;
            };
            let mut crc = Crc32::new();
            let (lowest, top) = self.stack_bounds();
            let paint_top = self.paint();
            for y in 0..h {
                let (result, n) = self.meter().measure(|| path.render_line(y, &mut *line));
                f.ok &= result.is_ok();
                f.full.add(n);
                crc.update(line);
                frames_crc.update(line);
            }
            self.note_stack(lowest, paint_top, top);
            f.last_crc = crc.value();
        }
        f.frames_crc = frames_crc.value();

        // Frame 0 on the display, then every frame as its damage against the one before.
        let Some(first) = self.animation_frame::<T>(motion, 0, slots, 0, &mut Figures { ..f })
        else {
            f.ok = false;
            return f;
        };
        // Row by row: `Render::render_frame` slices by the path's width, which the optimiser
        // cannot prove non-zero here, and its panic path would fail the link.
        if let Some(display) = display.as_deref_mut() {
            for (y, row) in display
                .chunks_exact_mut(w as usize)
                .take(h as usize)
                .enumerate()
            {
                f.ok &= first.render_line(y as u32, row).is_ok();
            }
        }
        let mut stream = Crc32::new();
        for k in 1..=ANIMATION_FRAMES {
            let next = (k % 2) as usize;
            if self
                .animation_frame::<T>(motion, k, slots, next, &mut f)
                .is_none()
            {
                f.ok = false;
                return f;
            }
            let ([s0, s1], [f0, f1]) = (&slots.scenes, &slots.frames);
            let (shown, next) = if next == 1 {
                ((s0, f0), (s1, f1))
            } else {
                ((s1, f1), (s0, f0))
            };
            let ((Some(shown_scene), shown_frame), (Some(next_scene), next_frame)) = (shown, next)
            else {
                f.ok = false;
                return f;
            };
            let (lowest, top) = self.stack_bounds();
            let paint_top = self.paint();
            let (damage, n) = self.meter().measure(|| {
                Damage::<{ shadeline::damage::DEFAULT_REGIONS }>::between(
                    shown_scene,
                    shown_frame,
                    next_scene,
                    next_frame,
                )
            });
            f.damage_calc.add(n);
            let mut rows = damage.rows();
            loop {
                let (row, n) = self.meter().measure(|| rows.next());
                f.damage_calc.add(n);
                let Some(row) = row else { break };
                let y = row.y();
                for span in row.ranges() {
                    let mut x = span.start;
                    while x < span.end {
                        let len = ((span.end - x) as usize).min(line.len());
                        let piece = &mut line[..len];
                        let (result, n) = self
                            .meter()
                            .measure(|| next_frame.render_segment(y, x, &mut *piece));
                        f.ok &= result.is_ok();
                        f.damage_render.add(n);
                        stream.update(&[Rgb565(x as u16), Rgb565(y as u16), Rgb565(len as u16)]);
                        stream.update(piece);
                        f.pixels += len as u64;
                        if let Some(display) = display.as_deref_mut() {
                            let at = (y * w + x) as usize;
                            match display.get_mut(at..at + len) {
                                Some(dst) => dst.iter_mut().zip(&*piece).for_each(|(d, p)| *d = *p),
                                None => f.ok = false,
                            }
                        }
                        x += len as u32;
                    }
                }
            }
            self.note_stack(lowest, paint_top, top);
        }
        f.stream_crc = stream.value();
        f.display_crc = display.map(|d| {
            let mut crc = Crc32::new();
            crc.update(d.get(..(w * h) as usize).unwrap_or(&[]));
            crc.value()
        });
        f
    }

    /// Builds frame `k`'s scene into `slots.scenes[slot]` and prepares it into
    /// `slots.frames[slot]`, each one measured region added to `f`.
    fn animation_frame<'s, T: Trig>(
        &mut self,
        motion: Motion,
        k: u32,
        slots: &'s mut AnimationSlots,
        slot: usize,
        f: &mut Figures,
    ) -> Option<&'s AnimationFixed> {
        let (scene_slot, frame_slot) = (slots.scenes.get_mut(slot)?, slots.frames.get_mut(slot)?);
        let (scene, n) = self.build(scene_slot, || {
            animation_scene(motion, motion_at::<T>(motion, k))
        });
        f.scene.add(n);
        let scene = scene?;
        let (path, n) = self.build_in(frame_slot, |p| {
            p.prepare(scene, ANIMATION_WIDTH, ANIMATION_HEIGHT)
        });
        f.prepare.add(n);
        path
    }

    fn report_animation<T: Trig>(&mut self, name: &str, f: &Figures, expected: Expected) {
        let Expected {
            frames: crc,
            last,
            stream,
            pixels,
        } = expected;
        let board_name = self.board_name();
        let matched = f.ok && f.frames_crc == crc && f.last_crc == last;
        let stream_matched = f.ok && f.stream_crc == stream && f.pixels == pixels;
        let display_matched = f.display_crc.is_none_or(|d| d == last);
        let figures = [
            f.full,
            f.damage_calc,
            f.damage_render,
            f.prepare,
            f.scene,
            f.trig,
        ]
        .map(|s| s.0);
        let exact = figures.iter().all(Option::is_some);
        if !(matched && stream_matched && display_matched && exact) {
            self.fail();
        }
        let mut line = Line::new();
        line.str("shadeline-fw firmware=")
            .str(board_name)
            .str(" path=anim-")
            .str(name)
            .str(" trig=")
            .str(T::NAME)
            .field("frames", u64::from(ANIMATION_FRAMES))
            .str(" crc=")
            .hex32(f.frames_crc)
            .str(" expected=")
            .hex32(crc)
            .str(if matched { " match=yes" } else { " match=no" })
            .str(" stream_crc=")
            .hex32(f.stream_crc)
            .str(" stream_expected=")
            .hex32(stream)
            .str(if stream_matched {
                " stream_match=yes"
            } else {
                " stream_match=no"
            })
            .field("pixels", f.pixels);
        if f.pixels != pixels {
            line.field("pixels_expected", pixels);
        }
        match f.display_crc {
            Some(d) => line.str(" display_crc=").hex32(d).str(if display_matched {
                " display_match=yes"
            } else {
                " display_match=no"
            }),
            None => line.str(" display=none"),
        };
        line.byte(b'\n');
        self.note_bytes(line.as_bytes());

        let [full, calc, render, prepare, scene, trig] = figures.map(|n| n.unwrap_or(0));
        let frames = u64::from(ANIMATION_FRAMES);
        let frame_bytes = 2 * u64::from(ANIMATION_WIDTH) * u64::from(ANIMATION_HEIGHT);
        let mut line = Line::new();
        line.str("shadeline-fw firmware=")
            .str(board_name)
            .str(" anim=")
            .str(name)
            .str(if exact { " exact=yes" } else { " exact=no" })
            .str(" full=")
            .ratio(full, frames)
            .str(" damage=")
            .ratio(calc + render, frames)
            .str(" damage_calc=")
            .ratio(calc, frames)
            .str(" damage_render=")
            .ratio(render, frames)
            .str(" prepare=")
            .ratio(prepare, frames)
            .str(" scene=")
            .ratio(scene, frames)
            .str(" sincos=")
            .ratio(trig, frames)
            .field("bytes_full", frame_bytes)
            .str(" bytes_damage=")
            .ratio(2 * f.pixels, frames)
            .byte(b'\n');
        self.note_bytes(line.as_bytes());
    }
}
