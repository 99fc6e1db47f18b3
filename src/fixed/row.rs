//! The row driver of the fixed path: [`Render`] for [`PreparedFixed`].
//!
//! Like the float driver: spans (each sphere's outline on the row: within its prepared
//! screen rectangle where the full-width kernel is built, see `spans`; otherwise exactly its
//! hit pixels, see `outline`), covered runs walked with the float path's own `walk_runs`
//! (background outside the runs, the kernel inside). With the full-width kernel the runs are
//! the spans merged (`merge_runs`): its pixels are dear, so none outside a span is shaded.
//! Without it every frame is a narrow one, and the row is one run, the spans' hull: the
//! narrow kernel tracks each span itself and passes the columns between spans as the
//! background at the cost of a few additions each, so the sort and merge are not linked.
//! Within a run the unnormalized primary direction advances by one integer addition per
//! pixel (`2·step_x`), which is exactly the value `(2x + 1 − w)·step_x` would give: no
//! rounding accumulates. Rows, pixels and slices are only reached through `get_mut` and
//! iterators, and every index is checked, so nothing here can panic.
//!
//! The parts that differ by feature are one function per variant, each variant's in an
//! `impl` block of its own (the full-width kernel's or not, the edge stage's or not), so
//! that the row functions read the same in every build.

#[cfg(all(feature = "antialias", feature = "full-width"))]
use super::edges::EdgeRow;
#[cfg(feature = "full-width")]
use super::kernel::ray;
#[cfg(feature = "full-width")]
use super::mul::{mul_ii, mul_iu};
use super::narrow::{Narrow, Shaded};
use super::narrow_run::{NarrowRun, NO_TRACK};
#[cfg(not(feature = "full-width"))]
use super::outline::outline_on_row;
use super::prepare::{FixedSphere, PreparedFixed};
#[cfg(feature = "full-width")]
use super::vector::{each3, V3};
use crate::encoding::{linear_code_fixed, Encoding};
use crate::pixel::{pixel_from_codes, FixedShade, HitRecord, Pixel};
use crate::render::{check_segment, Kernel, Render, RenderError};
#[cfg(feature = "full-width")]
use crate::runs::merge_runs_into;
use crate::runs::{coverage_of, walk_runs, Background, Span};
#[cfg(feature = "full-width")]
use fixed::types::I16F48;

impl<const S: usize, const L: usize> PreparedFixed<S, L> {
    /// Each sphere's span on row `y`, in scene order (`None`: not on this row): the columns
    /// its outline can reach on the row (within its screen rectangle where the full-width
    /// kernel is built; without it, exactly the columns where the narrow kernel's hit test
    /// passes). With spans off ([`PreparedFixed::with_spans`]) every sphere
    /// spans the whole row.
    pub fn row_spans(&self, y: u32) -> heapless::Vec<Option<Span>, S> {
        let mut out = heapless::Vec::new();
        self.row_spans_into(y, &mut out);
        out
    }

    /// [`Self::row_spans`] into `out` (cleared first), in place: the row driver keeps the
    /// spans in its own frame instead of receiving a copy.
    #[inline(never)]
    fn row_spans_into(&self, y: u32, out: &mut heapless::Vec<Option<Span>, S>) {
        let full = Span {
            start: 0,
            end: self.width,
        };
        out.clear();
        for s in &self.spheres {
            let span = if self.use_spans {
                self.sphere_span(s, y)
            } else {
                Some(full)
            };
            // Same capacity as the sphere list: cannot fail. (Not `collect`: heapless's
            // `FromIterator` panics on overflow, and a panic path would stay in the binary.)
            let pushed = out.push(span);
            debug_assert!(pushed.is_ok(), "more spans than spheres");
        }
    }

    /// Shades the pixels of the run from column `start` of `row` (`y`, the row's spans, the
    /// encoding and the background) with the narrow kernel (and the full-width one should
    /// it hand a pixel over, on that pixel's direction: exact whether stepped or computed
    /// directly); `false` (nothing written) if the frame does not use the narrow kernel. Not
    /// inlined, so the pixel loop is compiled apart from the row's set-up.
    #[inline(never)]
    fn narrow_pixels<P: Pixel, const PLAIN: bool>(
        &self,
        row: RunRow<'_, P>,
        start: u32,
        run_pixels: &mut [P],
    ) -> bool {
        let (y, spans, encoding, background) = row;
        let mut narrow = NarrowRun::new();
        let end = start + run_pixels.len() as u32;
        if !self.narrow_run(&mut narrow, start, end, y, spans) {
            return false;
        }
        let narrow = &mut narrow;
        let finish = |px: &mut P, shaded: Narrow, column: u32| {
            let shaded = match shaded {
                Narrow::Done(shaded) => shaded,
                Narrow::Precise => self.handed_over(column, y, spans, P::NEEDS_HITS),
            };
            *px = match shaded {
                Some(s) => encode::<P, PLAIN>(s.color, s.hit, encoding, column, y),
                None => background.at(column as usize),
            };
        };
        // One light (always, at a capacity of one): the loops over lights have a fixed
        // length. Not on ARMv6-M, where the fixed-length loop made the exponent series
        // dearer: its eight registers were allocated worse.
        // A frame with a point light or a normalized sphere (`precise_pixels`) takes a loop
        // of its own, so that the others' loops carry none of the precise cosines' code.
        // Without `narrow-precise` the prepare refuses such frames: no such loop.
        let one = cfg!(not(shadeline_short_mul)) && (L == 1 || self.lights.len() == 1);
        #[cfg(feature = "narrow-precise")]
        if self.precise_pixels {
            if one {
                self.narrow_loop::<1, P, true>(narrow, start, run_pixels, &finish);
            } else {
                self.narrow_loop::<0, P, true>(narrow, start, run_pixels, &finish);
            }
            return true;
        }
        if one {
            self.narrow_loop::<1, P, false>(narrow, start, run_pixels, &finish);
        } else {
            self.narrow_loop::<0, P, false>(narrow, start, run_pixels, &finish);
        }
        true
    }

    /// The pixel loop of [`Self::narrow_pixels`] over `run_pixels` from column `start`,
    /// `finish` encoding and storing each; `N` and `PRECISE` as [`Self::narrow_shade`] takes
    /// them. Inlined on
    /// ARMv6-M, out of line elsewhere: measured, each is the cheaper there (QEMU counts).
    #[cfg_attr(shadeline_short_mul, inline(always))]
    #[cfg_attr(not(shadeline_short_mul), inline(never))]
    fn narrow_loop<const N: usize, P: Pixel, const PRECISE: bool>(
        &self,
        narrow: &mut NarrowRun<S, L>,
        start: u32,
        run_pixels: &mut [P],
        finish: &impl Fn(&mut P, Narrow, u32),
    ) {
        let mut column = start;
        let mut rest = run_pixels;
        while !rest.is_empty() {
            // One sphere alone up to column `until`: no search for the nearest hit there.
            let (single, count) = match narrow.single() {
                Some((track, until)) => (
                    Some(track),
                    (until.saturating_sub(column) as usize).clamp(1, rest.len().max(1)),
                ),
                None => (None, 1),
            };
            let Some((now, later)) = rest.split_at_mut_checked(count) else {
                break;
            };
            // No active track (between the spans of a run that is the row's hull): the
            // background, and the run moved on. On ARMv6-M the single-track path below does
            // the same per pixel (`NO_TRACK` finds no surface), for less flash and a few more
            // instructions; elsewhere this is the faster (`docs/performance.md, "Choices measured"`).
            if cfg!(not(shadeline_short_mul)) && single == Some(NO_TRACK) {
                for (px, c) in now.iter_mut().zip(column..) {
                    finish(px, Narrow::Done(None), c);
                }
                narrow.skip(count as u32, self.light_count::<N>());
            } else {
                for (px, c) in now.iter_mut().zip(column..) {
                    finish(
                        px,
                        self.narrow_shade::<N, PRECISE>(narrow, single, P::NEEDS_HITS),
                        c,
                    );
                }
            }
            if single.is_some() {
                narrow.refresh();
            }
            column += count as u32;
            rest = later;
        }
    }
}

impl<const S: usize, const L: usize> Render for PreparedFixed<S, L> {
    /// The narrow kernel, or the full-width one because of the first light that is not
    /// distant, sphere with a normalized model (or Oren–Nayar, GGX), sphere the
    /// camera is close to (`center`) or whose numbers do not fit the narrow
    /// formats (`radius`), or a field of view too wide for them (`vfov`). Without the
    /// feature `full-width` it is always [`Kernel::Narrow`]: such a frame is refused instead
    /// ([`RenderError::NeedsFullWidth`], with the same item and field).
    fn kernel(&self) -> Kernel {
        self.chosen_kernel()
    }

    fn width(&self) -> u32 {
        self.width
    }

    fn height(&self) -> u32 {
        self.height
    }

    fn row_coverage(&self, y: u32) -> Option<Span> {
        coverage_of(&self.row_spans(y))
    }

    /// A dispatch, inlined into the caller: the default encoding (what
    /// [`render_line`](Render::render_line) passes, unless the frame is wrapped by
    /// [`with_encoding`](Render::with_encoding)) has a row function of its own, so a firmware
    /// that never picks another encoding links none of their code, nor the 8 KiB sRGB table.
    #[inline(always)]
    fn render_segment_with<P: Pixel>(
        &self,
        y: u32,
        x: u32,
        out: &mut [P],
        encoding: Encoding,
    ) -> Result<(), RenderError> {
        check_segment(y, x, out.len(), self.width, self.height)?;
        if encoding.is_default() {
            self.render_segment_encoded::<P, true>(y, x, out, encoding);
        } else {
            self.render_segment_encoded::<P, false>(y, x, out, encoding);
        }
        Ok(())
    }
}

/// What a run of a row is shaded with: the row, its spheres' spans, the encoding and the
/// background.
type RunRow<'a, P> = (u32, &'a [Option<Span>], Encoding, &'a Background<P>);

impl<const S: usize, const L: usize> PreparedFixed<S, L> {
    /// The body of [`Render::render_segment_with`] on a checked segment; `PLAIN`: whether
    /// `encoding` is the default.
    #[inline(never)]
    fn render_segment_encoded<P: Pixel, const PLAIN: bool>(
        &self,
        y: u32,
        x: u32,
        out: &mut [P],
        encoding: Encoding,
    ) {
        let mut spans = heapless::Vec::new();
        self.row_spans_into(y, &mut spans);
        self.with_runs(&spans, |runs| {
            let background = Background::new(encoding, |x| {
                encode::<P, PLAIN>(self.background, HitRecord::default(), encoding, x, y)
            });
            // The edge stage's row state, once per row for all its runs.
            let edges = self.row_edges(y);
            walk_runs(out, x as usize, runs, &background, |start, run_pixels| {
                let row = (y, &spans[..], encoding, &background);
                match self.chosen_kernel() {
                    Kernel::Narrow => {
                        self.narrow_pixels::<P, PLAIN>(row, start as u32, run_pixels);
                    }
                    Kernel::General { .. } => {
                        self.full_width_pixels::<P, PLAIN>(row, start as u32, run_pixels);
                    }
                }
                self.antialiased::<P, PLAIN>(
                    (y, &spans[..], encoding),
                    &edges,
                    start as u32,
                    run_pixels,
                );
            });
        });
    }
}

/// The row driver's parts for the full-width kernel: its spans, runs and pixels, and the
/// pixels the narrow kernel hands it.
#[cfg(feature = "full-width")]
impl<const S: usize, const L: usize> PreparedFixed<S, L> {
    /// Sphere `s`'s span on row `y`: its rectangle's columns narrowed to its outline's.
    #[inline(always)]
    fn sphere_span(&self, s: &FixedSphere, y: u32) -> Option<Span> {
        s.bounds
            .and_then(|b| b.on_row(y, self.height, self.rectangles()))
    }

    /// `f` on the row's runs: the spans merged, so that no pixel outside a span is shaded.
    #[inline(always)]
    fn with_runs(&self, spans: &[Option<Span>], f: impl FnOnce(&[Span])) {
        let mut merged = heapless::Vec::<Span, S>::new();
        merge_runs_into(spans, &mut merged);
        f(&merged)
    }

    /// A pixel the narrow kernel hands over (`Narrow::Precise`), shaded by the full-width
    /// kernel on its direction.
    #[inline(always)]
    fn handed_over(
        &self,
        column: u32,
        y: u32,
        spans: &[Option<Span>],
        record_hits: bool,
    ) -> Option<Shaded> {
        let dir = self.narrow_direction_wide(column, y);
        debug_assert_eq!(dir, self.direction(column, y));
        self.shade_ray(dir, column, spans, record_hits)
    }

    /// The full-width kernel on the unnormalized primary direction `dir` of pixel `x`: one
    /// copy in the binary, shared by both row loops.
    #[inline(never)]
    fn shade_ray(
        &self,
        dir: V3<I16F48>,
        x: u32,
        spans: &[Option<Span>],
        record_hits: bool,
    ) -> Option<Shaded> {
        ray(dir).and_then(|d| self.shade(d, x, spans, record_hits))
    }

    /// [`Self::direction`] where the narrow kernel is set up: every direction's components
    /// are then below 2 (2⁴⁹ raw) and each product fits, so `k·step` is two exact 32×32
    /// products instead of a saturating 64×64 one (a long call sequence on ARMv6-M). The
    /// same bits as [`Self::direction`]. Only the pixels the narrow kernel gives back need
    /// it; on ARMv6-M, where its six products are calls, it is not inlined into the pixel
    /// loop.
    #[cfg_attr(shadeline_short_mul, inline(never))]
    fn narrow_direction_wide(&self, x: u32, y: u32) -> V3<I16F48> {
        // |dx|, |dy| ≤ 2·MAX_DIMENSION + 1 < 2³¹.
        let dy = self.height as i32 - 2 * y as i32 - 1;
        let dx = 2 * x as i32 + 1 - self.width as i32;
        let scale =
            |k: i32, v: i64| (mul_ii(k, (v >> 32) as i32) << 32).wrapping_add(mul_iu(k, v as u32));
        each3(|i| {
            let v = self.forward[i].to_bits()
                + scale(dy, self.step_y[i].to_bits())
                + scale(dx, self.step_x[i].to_bits());
            I16F48::from_bits(v)
        })
    }

    /// Whether the spans are the spheres' rectangles alone (anti-aliased frames: the
    /// outlines' row spans leave out pixels within reach of an outline).
    #[inline(always)]
    fn rectangles(&self) -> bool {
        #[cfg(feature = "antialias")]
        return self.antialias;
        #[cfg(not(feature = "antialias"))]
        false
    }

    /// The unnormalized primary direction of pixel `(x, y)`:
    /// `forward + (h − 2y − 1)·step_y + (2x + 1 − w)·step_x`, exact in I16F48.
    pub(super) fn direction(&self, x: u32, y: u32) -> V3<I16F48> {
        let dy = self.height as i64 - 2 * y as i64 - 1;
        let dx = 2 * x as i64 + 1 - self.width as i64;
        each3(|i| {
            let v = self.forward[i].to_bits()
                + dy.saturating_mul(self.step_y[i].to_bits())
                + dx.saturating_mul(self.step_x[i].to_bits());
            I16F48::from_bits(v)
        })
    }

    /// The full-width kernel over `run_pixels` from column `start`: one ray per pixel, its
    /// direction stepped along the row.
    fn full_width_pixels<P: Pixel, const PLAIN: bool>(
        &self,
        (y, spans, encoding, background): RunRow<'_, P>,
        start: u32,
        run_pixels: &mut [P],
    ) {
        let advance = self.step_x.map(|c| c.to_bits().saturating_mul(2));
        let mut dir = self.direction(start, y);
        for (px, column) in run_pixels.iter_mut().zip(start..) {
            let shaded = self.shade_ray(dir, column, spans, P::NEEDS_HITS);
            *px = match shaded {
                Some(s) => encode::<P, PLAIN>(s.color, s.hit, encoding, column, y),
                None => background.at(column as usize),
            };
            for (c, a) in dir.iter_mut().zip(advance) {
                *c = I16F48::from_bits(c.to_bits().saturating_add(a));
            }
        }
    }
}

/// The row driver's parts without the full-width kernel: the narrow kernel's spans, one run
/// per row, and no pixel for the full-width kernel.
#[cfg(not(feature = "full-width"))]
impl<const S: usize, const L: usize> PreparedFixed<S, L> {
    /// Sphere `s`'s span on row `y`: the columns where the narrow kernel's hit test passes,
    /// within the rows and columns the prepare found for it (see `outline`).
    #[inline(always)]
    fn sphere_span(&self, s: &FixedSphere, y: u32) -> Option<Span> {
        let n = s.narrow.as_ref()?;
        if !(u32::from(n.rows.0) <= y && y < u32::from(n.rows.1)) {
            return None;
        }
        let dy = self.height as i32 - 2 * y as i32 - 1;
        let columns = (u32::from(n.columns.0), u32::from(n.columns.1));
        outline_on_row(&n.e, dy, self.width, columns)
    }

    /// `f` on the row's runs: one run, the spans' hull (see the module docs).
    #[inline(always)]
    fn with_runs(&self, spans: &[Option<Span>], f: impl FnOnce(&[Span])) {
        let hull = coverage_of(spans);
        f(hull.as_slice())
    }

    /// A pixel the narrow kernel hands over (`Narrow::Precise`): only for data a narrow frame
    /// always has, so none without the full-width kernel.
    #[inline(always)]
    fn handed_over(&self, _: u32, _: u32, _: &[Option<Span>], _: bool) -> Option<Shaded> {
        None
    }

    /// Without the full-width kernel every prepared frame is a narrow one
    /// ([`PreparedFixed::kernel`]): never called, the background for completeness.
    fn full_width_pixels<P: Pixel, const PLAIN: bool>(
        &self,
        (_, _, _, background): RunRow<'_, P>,
        start: u32,
        run_pixels: &mut [P],
    ) {
        for (px, column) in run_pixels.iter_mut().zip(start as usize..) {
            *px = background.at(column);
        }
    }
}

/// The edge stage's parts of the row driver.
#[cfg(all(feature = "antialias", feature = "full-width"))]
impl<const S: usize, const L: usize> PreparedFixed<S, L> {
    /// The edge stage's row state, if the frame is anti-aliased.
    #[inline(always)]
    fn row_edges(&self, y: u32) -> Option<EdgeRow<S>> {
        self.antialias.then(|| self.edge_row(y))
    }

    /// The `edges` stage over a shaded run, if the frame is anti-aliased.
    #[inline(never)]
    fn antialiased<P: Pixel, const PLAIN: bool>(
        &self,
        (y, spans, encoding): (u32, &[Option<Span>], Encoding),
        view: &Option<EdgeRow<S>>,
        start: u32,
        run_pixels: &mut [P],
    ) {
        let Some(view) = view else {
            return;
        };
        self.antialias_run((y, spans), view, start, run_pixels, |color, hit, x| {
            encode::<P, PLAIN>(color, hit, encoding, x, y)
        });
    }
}

/// The row state of an edge stage that is not built.
#[cfg(not(all(feature = "antialias", feature = "full-width")))]
struct NoEdges;

/// Without the edge stage, its parts of the row driver do nothing.
#[cfg(not(all(feature = "antialias", feature = "full-width")))]
impl<const S: usize, const L: usize> PreparedFixed<S, L> {
    /// No edge stage: no row state.
    #[inline(always)]
    fn row_edges(&self, _: u32) -> NoEdges {
        NoEdges
    }

    /// No edge stage: the run as shaded.
    #[inline(always)]
    fn antialiased<P: Pixel, const PLAIN: bool>(
        &self,
        _: (u32, &[Option<Span>], Encoding),
        _: &NoEdges,
        _: u32,
        _: &mut [P],
    ) {
    }
}

/// The encode stage of the fixed path: [`Pixel::encode_fixed`] for the default encoding
/// (`PLAIN`: whether `encoding` is it, a constant of the row function's instantiation, so
/// that the default's never holds the other encodings' code), the encoding's integer rule on
/// the linear codes `min(v, 65536)` otherwise.
#[inline(always)]
fn encode<P: Pixel, const PLAIN: bool>(
    color: [u32; 3],
    hit: HitRecord,
    encoding: Encoding,
    x: u32,
    y: u32,
) -> P {
    if !PLAIN {
        if let Some(px) = pixel_from_codes(color.map(linear_code_fixed), encoding, x, y) {
            return px;
        }
    }
    P::encode_fixed(&FixedShade { color, hit })
}
