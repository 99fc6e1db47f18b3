//! Damage between two frames: the rows, and in each row the column ranges, whose pixels can
//! differ between the frame just shown and the next one, so a display is sent only those.
//!
//! [`Damage::between`] reads the two scenes and their prepared frames (the same path, the
//! same size); it never renders. It is built from the geometry because a display driver has
//! no framebuffer to diff, and it must never miss a changed pixel, so every bound is
//! conservative and tightness comes second:
//!
//! | what changed | what is damaged |
//! |---|---|
//! | the size, the encoding, the camera, the background, the number of spheres or lights | the whole frame |
//! | a light (any field), the kernel the path chose ([`Render::kernel`]), or the scene's extent (the fixed path's scale and every path's ray epsilon follow it) | every sphere's outline, in both frames |
//! | a sphere's material | its outline |
//! | a sphere's centre or radius | its outline in both frames, and in both frames, for every light and every other sphere, the part of that sphere its shadow can reach |
//!
//! An outline is a ball's projection, grown by three pixel pitches (the anti-aliased edge
//! pixels and the paths' rounding; see `outline`). A shadow's reach is a chain of balls along
//! the entry patch of the caster's shadow volume on the receiver (see `shadow`). The balls are
//! held in a fixed number of slots (`N`, [`DEFAULT_REGIONS`] by default): when they are all
//! taken, a new ball joins the one it grows least. A row's ranges are found when the row is
//! asked for, in at most [`RANGES_PER_ROW`] ranges (more are joined). Joining only ever adds
//! pixels. No allocation, no panic: the damage lives on the stack or in a `static`.
//!
//! The kernels shade each pixel from the frame's constants and its own `(x, y)` alone: the
//! fixed narrow kernel steps its quadrics along a run by exact integer differences, so a
//! pixel's bits do not depend on where its run starts, and the damage need not widen to
//! whole runs (the no-miss tests render both frames on every path to hold this).
//!
//! Rendering only the damage is [`Damage::render`]: [`Render::render_segment`] over the
//! damaged ranges, each handed to a display window.
//!
//! The files: `outline` (a ball's columns on a row), `shadow` (a shadow's reach), `ranges`
//! (a row's bounded ranges, [`DamageRow`]), and this one, [`Damage`] and its rows.

mod outline;
mod ranges;
mod shadow;

pub use ranges::{DamageRow, RANGES_PER_ROW};

use crate::pixel::Pixel;
use crate::render::{Kernel, Render, RenderError};
use crate::scene::{Scene, Sphere};
use outline::{Outline, View};
use shadow::shadow_ball;

/// The default number of ball slots of a [`Damage`].
pub const DEFAULT_REGIONS: usize = 32;

/// The pixels that can differ between two frames: see the [module docs](self).
///
/// ```
/// use shadeline::{damage::Damage, floor, MatrixScene, Prepared, Render, Rgb565, Simd8};
///
/// // The floor scene, and the same with its first small sphere rolled 0.3 forward.
/// let shown = floor()?;
/// let mut next = MatrixScene::new(*shown.camera(), shown.background())?;
/// for (i, sphere) in shown.spheres().iter().enumerate() {
///     let mut sphere = *sphere;
///     if i == 1 {
///         sphere.center.z += 0.3;
///     }
///     next.add_sphere(sphere)?;
/// }
/// for light in shown.lights() {
///     next.add_light(*light)?;
/// }
/// let (a, b) = (
///     Prepared::<Simd8, _, _>::new(&shown, 96, 64)?,
///     Prepared::<Simd8, _, _>::new(&next, 96, 64)?,
/// );
/// let damage: Damage = Damage::between(&shown, &a, &next, &b);
/// assert!(damage.pixels() < 96 * 64 / 2);
/// // Send only the damage: each piece goes to the display's window at (x, y).
/// let mut buffer = [Rgb565::default(); 32];
/// let mut sent = 0;
/// damage.render(&b, &mut buffer, |_x, _y, pixels: &[Rgb565]| {
///     sent += pixels.len();
///     Ok::<(), shadeline::RenderError>(())
/// })?;
/// assert_eq!(sent as u64, damage.pixels());
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug)]
pub struct Damage<const N: usize = DEFAULT_REGIONS> {
    view: View,
    whole: bool,
    balls: heapless::Vec<Outline, N>,
}

impl<const N: usize> Damage<N> {
    /// Every pixel of a `width × height` frame: the damage of a first frame, or of a frame
    /// the caller cannot compare.
    pub fn full<const S: usize, const L: usize>(
        scene: &Scene<S, L>,
        width: u32,
        height: u32,
    ) -> Self {
        Self::empty(View::of(scene, width, height), true)
    }

    /// No pixel of a `width × height` frame.
    pub fn none<const S: usize, const L: usize>(
        scene: &Scene<S, L>,
        width: u32,
        height: u32,
    ) -> Self {
        Self::empty(View::of(scene, width, height), false)
    }

    /// A damage of `view` with no ball: the whole frame if `whole`, else no pixel.
    fn empty(view: View, whole: bool) -> Self {
        Damage {
            view,
            whole,
            balls: heapless::Vec::new(),
        }
    }

    /// The pixels that can differ between `shown` as `shown_frame` rendered it and `next` as
    /// `next_frame` renders it: the frames of one path (the damage is sized by `next_frame`;
    /// a different size is the whole frame). See the [module docs](self) for what each
    /// change damages.
    pub fn between<const S: usize, const L: usize, A: Render, B: Render>(
        shown: &Scene<S, L>,
        shown_frame: &A,
        next: &Scene<S, L>,
        next_frame: &B,
    ) -> Self {
        let (width, height) = (next_frame.width(), next_frame.height());
        let mut damage = Self::none(next, width, height);
        if shown_frame.width() != width
            || shown_frame.height() != height
            || shown_frame.encoding() != next_frame.encoding()
            || shown.camera() != next.camera()
            || shown.background() != next.background()
            || shown.spheres().len() != next.spheres().len()
            || shown.lights().len() != next.lights().len()
        {
            damage.whole = true;
            return damage;
        }
        let narrow = |k: Kernel| matches!(k, Kernel::Narrow);
        let everything = shown.lights() != next.lights()
            || narrow(shown_frame.kernel()) != narrow(next_frame.kernel())
            || shown.extent().to_bits() != next.extent().to_bits();
        let view = damage.view;
        for (i, (old, new)) in shown.spheres().iter().zip(next.spheres()).enumerate() {
            if !everything && old == new {
                continue;
            }
            damage.add(view.ball(old.center, old.radius));
            damage.add(view.ball(new.center, new.radius));
            if !everything && !same_place(old, new) {
                damage.add_shadows(shown, i, &view);
                damage.add_shadows(next, i, &view);
            }
            if damage.whole {
                break;
            }
        }
        damage
    }

    /// The shadows sphere `caster` of `scene` casts on the other spheres, from every light.
    fn add_shadows<const S: usize, const L: usize>(
        &mut self,
        scene: &Scene<S, L>,
        caster: usize,
        view: &View,
    ) {
        let Some(c) = scene.spheres().get(caster) else {
            return;
        };
        let eps = scene.ray_epsilon();
        for light in scene.lights() {
            for (j, receiver) in scene.spheres().iter().enumerate() {
                if j == caster {
                    continue;
                }
                if let Some(chain) = shadow_ball(c, receiver, light, eps) {
                    for (centre, radius) in chain.balls() {
                        self.add(view.ball(centre, radius));
                    }
                }
            }
        }
    }

    /// Adds a ball's outline: dropped if another holds it, joined into the one it grows
    /// least when every slot is taken.
    fn add(&mut self, ball: Outline) {
        match ball {
            Outline::Nowhere => return,
            Outline::Everywhere => {
                self.whole = true;
                return;
            }
            Outline::Ball { .. } => {}
        }
        if self.balls.iter().any(|b| b.holds(&ball)) {
            return;
        }
        self.balls.retain(|b| !ball.holds(b));
        if let Err(ball) = self.balls.push(ball) {
            let best = self
                .balls
                .iter()
                .map(|b| b.merged(&ball))
                .enumerate()
                .min_by(|(_, a), (_, b)| a.radius().total_cmp(&b.radius()));
            match best {
                Some((i, merged)) => {
                    if let Some(slot) = self.balls.get_mut(i) {
                        *slot = merged;
                    }
                    if merged == Outline::Everywhere {
                        self.whole = true;
                    }
                }
                // No slot at all (`N = 0`): the whole frame.
                None => self.whole = true,
            }
        }
    }

    /// The frame's width.
    pub fn width(&self) -> u32 {
        self.view.width()
    }

    /// The frame's height.
    pub fn height(&self) -> u32 {
        self.view.height()
    }

    /// Whether every pixel is damaged.
    pub fn is_full_frame(&self) -> bool {
        self.whole
    }

    /// Row `y`'s damaged ranges (none for a row out of the frame).
    pub fn row(&self, y: u32) -> DamageRow {
        let mut row = DamageRow::new(y);
        if y >= self.height() {
            return row;
        }
        if self.whole {
            row.add(0, self.width());
            return row;
        }
        for ball in &self.balls {
            if let Some((start, end)) = ball.row(&self.view, y) {
                row.add(start, end);
            }
        }
        row
    }

    /// The damaged rows, top to bottom, each with its ranges; rows with none are skipped.
    pub fn rows(&self) -> Rows<'_, N> {
        Rows { damage: self, y: 0 }
    }

    /// Whether `(x, y)` is damaged.
    pub fn contains(&self, x: u32, y: u32) -> bool {
        x < self.width() && self.row(y).contains(x)
    }

    /// The number of damaged pixels.
    pub fn pixels(&self) -> u64 {
        self.rows().map(|r| u64::from(r.pixels())).sum()
    }

    /// Renders the damaged pixels of `frame` (the next frame) with
    /// [`Render::render_segment`], `buffer.len()` pixels at most at a time, and hands each
    /// piece to `window(x, y, pixels)`: the display's address window from `(x, y)`, one row
    /// high, `pixels.len()` wide. Stops at the first error; an empty `buffer` is
    /// [`RenderError::LineLength`].
    pub fn render<R: Render, P: Pixel, E: From<RenderError>>(
        &self,
        frame: &R,
        buffer: &mut [P],
        mut window: impl FnMut(u32, u32, &[P]) -> Result<(), E>,
    ) -> Result<(), E> {
        if buffer.is_empty() {
            return Err(RenderError::LineLength {
                expected: frame.width() as usize,
                got: 0,
            }
            .into());
        }
        let chunk = buffer.len();
        for row in self.rows() {
            for span in row.ranges() {
                let mut x = span.start;
                while x < span.end {
                    let n = ((span.end - x) as usize).min(chunk);
                    let Some(pixels) = buffer.get_mut(..n) else {
                        break;
                    };
                    frame.render_segment(row.y(), x, pixels)?;
                    window(x, row.y(), pixels)?;
                    x += n as u32;
                }
            }
        }
        Ok(())
    }
}

/// The damaged rows of a [`Damage`], top to bottom ([`Damage::rows`]).
#[derive(Clone, Debug)]
pub struct Rows<'a, const N: usize> {
    damage: &'a Damage<N>,
    y: u32,
}

impl<const N: usize> Iterator for Rows<'_, N> {
    type Item = DamageRow;

    fn next(&mut self) -> Option<DamageRow> {
        while self.y < self.damage.height() {
            let row = self.damage.row(self.y);
            self.y += 1;
            if !row.ranges().is_empty() {
                return Some(row);
            }
        }
        None
    }
}

/// Whether two spheres have the same centre and radius.
fn same_place(a: &Sphere, b: &Sphere) -> bool {
    a.center == b.center && a.radius == b.radius
}
