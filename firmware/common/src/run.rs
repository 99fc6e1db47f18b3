//! One rendering path end to end on a board: build its scene and prepared frame, count
//! covered pixels, render the frame with every row measured, CRC it, report one line.
//!
//! [`Session::build`] makes a value (the scene, a prepared frame) in a caller's slot — a
//! `static` on the small boards, so nothing large is moved or copied through the stack
//! afterwards — in one measured region: the instructions of `Prepared…::new` are the
//! `prepare=` figure of the path's line, measured exactly like a row. [`Session::build_in`]
//! does the same for a value prepared in place (`PreparedFixed::prepare` into a slot holding
//! `PreparedFixed::EMPTY`), which never has the value on the stack at all.
//!
//! The order keeps everything that is not the render out of the measured regions: the
//! covered-pixel count (with the `count-covered` feature) renders the frame once more into
//! [`HitRecord`]s, a short segment at a time, and is never measured; the CRC is taken after
//! each measured row (streaming) or after the frame (framebuffer); the report is formatted after everything. Each measured
//! region is exactly one `render_line` call, so "instructions per frame" means the same
//! thing whether rows go to a framebuffer or to a line buffer, on every board. The stack of
//! every stage (build, count, render) is painted and counts toward the session's
//! `peak_stack`.
//!
//! Rendering into hit records is a second monomorphization of the row loop, several KiB of
//! flash that a user's firmware, which renders pixels only, never carries. So the count is a
//! feature: the m4f and rv32 firmware count on target and fail if the count differs from the
//! host's ([`Expected::covered`], checked on the host by `tests/firmware_crcs.rs`); the m0
//! firmware, whose flash is a budgeted figure, reports the host's count
//! (`covered_by=host`) and links only what a user's firmware would.
//!
//! The report is one line of `key=value` fields after a `shadeline-fw` tag, which
//! `.ci/firmware` parses into the figures table:
//!
//! ```text
//! shadeline-fw firmware=m0 path=fixed sink=line crc=0x… expected=0x… match=yes
//!   instructions=… pixels=76800 per_pixel=… covered=… per_covered=… prepare=… stack=…
//!   render_stack=…
//! ```

use crate::crc32::Crc32;
use crate::kernel;
use crate::meter::{InstructionCounter, Meter};
use crate::stack;
use crate::text::Line;
#[cfg(feature = "count-covered")]
use shadeline::HitRecord;
use shadeline::{PreparedFixed, Render, Rgb565, Scene};

/// What a firmware supplies about its board.
pub trait Board {
    /// The firmware's name in reports (`"m4f"`, `"m0"`, `"rv32"`).
    fn name(&self) -> &'static str;
    /// Writes text to the host console (semihosting). Errors are dropped: there is nowhere
    /// else to report them, and the exit status still carries the verdict.
    fn write(&mut self, text: &[u8]);
    /// The current stack pointer.
    fn stack_pointer(&self) -> usize;
    /// The lowest address the stack may grow down to, and the stack's top (initial pointer).
    fn stack_limits(&self) -> (usize, usize);
}

/// Where a path's pixels go.
pub enum Sink<'a> {
    /// A full `width × height` framebuffer, rows in place.
    Frame(&'a mut [Rgb565]),
    /// One `width`-pixel line buffer, reused for every row (the CRC is fed row by row).
    Line(&'a mut [Rgb565]),
}

impl Sink<'_> {
    fn name(&self) -> &'static str {
        match self {
            Sink::Frame(_) => "frame",
            Sink::Line(_) => "line",
        }
    }
}

/// What a path must produce: the host's figures for the same frame (`expected.rs`).
#[derive(Clone, Copy, Debug)]
pub struct Expected {
    /// CRC32 of the frame's RGB565 pixels.
    pub crc: u32,
    /// Pixels whose primary ray hits a sphere.
    pub covered: u64,
}

/// Whether this build counts covered pixels on target (the `count-covered` feature).
const COUNT_COVERED: bool = cfg!(feature = "count-covered");

/// The verdict of a whole session.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Outcome {
    /// Every path matched its CRC and every count was exact.
    Pass,
    /// Something did not.
    Fail,
}

/// The figures of one path.
struct Figures {
    crc: u32,
    instructions: Option<u64>,
    covered: u64,
    stack: usize,
    render_stack: usize,
    render_ok: bool,
}

/// A board, its calibrated meter and the running verdict.
pub struct Session<B: Board, C: InstructionCounter> {
    board: B,
    meter: Meter<C>,
    outcome: Outcome,
    peak_stack: usize,
}

impl<B: Board, C: InstructionCounter> Session<B, C> {
    /// Calibrates the counter and runs its self-test, reporting both. `None` (after a report)
    /// if the counter cannot measure at all.
    pub fn new(mut board: B, counter: C) -> Option<Self> {
        let board_name = board.name();
        let Some(meter) = Meter::new(counter) else {
            let mut line = Line::new();
            line.str("shadeline-fw firmware=")
                .str(board_name)
                .str(" error=counter-unusable\n");
            board.write(line.as_bytes());
            return None;
        };
        let mut session = Session {
            board,
            meter,
            outcome: Outcome::Pass,
            peak_stack: 0,
        };
        let test = session.meter.self_test();
        let mut line = Line::new();
        line.str("shadeline-fw firmware=")
            .str(board_name)
            .str(" counter=")
            .str(session.meter.counter_name())
            .field("overhead", session.meter.overhead())
            .str(" selftest=");
        match test {
            Ok(n) => line.str("exact").field("measured", n),
            Err(n) => {
                session.outcome = Outcome::Fail;
                line.str("wrong").field("measured", n)
            }
        };
        line.byte(b'\n');
        session.board.write(line.as_bytes());
        Some(session)
    }

    /// Builds a value with `make` into `slot` in one measured region, and returns it with
    /// the instructions `make` took (`None` if the count is inexact). The value is `None` if
    /// `make` fails. The build's stack counts toward the session's peak.
    ///
    /// `slot` is where the value lives for the rest of the program (on the small boards a
    /// `static`): writing it in the region means the value is not moved again afterwards.
    pub fn build<'s, T, E>(
        &mut self,
        slot: &'s mut Option<T>,
        make: impl FnOnce() -> Result<T, E>,
    ) -> (Option<&'s T>, Option<u64>) {
        let (lowest, top) = self.board.stack_limits();
        let paint_top = self.paint();
        let ((), instructions) = self.meter.measure(|| *slot = make().ok());
        self.note_stack(lowest, paint_top, top);
        (slot.as_ref(), instructions)
    }

    /// Like [`Session::build`] for a value prepared in place: `prepare` fills `slot` (a
    /// `static` or a long-lived local), measured as one region, so the value is never on
    /// the stack. `None` if `prepare` fails.
    pub fn build_in<'s, T, E>(
        &mut self,
        slot: &'s mut T,
        prepare: impl FnOnce(&mut T) -> Result<(), E>,
    ) -> (Option<&'s T>, Option<u64>) {
        let (lowest, top) = self.board.stack_limits();
        let paint_top = self.paint();
        let (ok, instructions) = self.meter.measure(|| prepare(&mut *slot).is_ok());
        self.note_stack(lowest, paint_top, top);
        (ok.then_some(&*slot), instructions)
    }

    /// [`Session::build`], then [`Session::run`] on what it built: a path prepared by `make`
    /// into `slot`, rendered into `sink` and reported as `path_name`. A prepare that fails
    /// is reported as `error=prepare-<path_name>` and fails the session.
    pub fn build_and_run<R: Render, E>(
        &mut self,
        path_name: &str,
        slot: &mut Option<R>,
        make: impl FnOnce() -> Result<R, E>,
        sink: Sink<'_>,
        expected: Expected,
    ) {
        match self.build(slot, make) {
            (Some(path), prepare) => self.run(path_name, path, sink, prepare, expected),
            (None, _) => {
                self.note("shadeline-fw error=prepare-");
                self.note(path_name);
                self.note("\n");
                self.fail();
            }
        }
    }

    /// Renders `path` into `sink`, measures it and reports it against `expected`, with
    /// `prepare` (from [`Session::build`]) as the instructions of its prepare.
    pub fn run<R: Render>(
        &mut self,
        path_name: &str,
        path: &R,
        mut sink: Sink<'_>,
        prepare: Option<u64>,
        expected: Expected,
    ) {
        let sink_name = sink.name();
        let board_name = self.board.name();
        let figures = self.figures(path, &mut sink, expected.covered);
        if prepare.is_none() {
            self.outcome = Outcome::Fail;
        }
        let pixels = u64::from(path.width()) * u64::from(path.height());
        let matched = figures.render_ok && figures.crc == expected.crc;
        let covered_matched = figures.covered == expected.covered;
        if !covered_matched {
            self.outcome = Outcome::Fail;
        }
        if !matched || figures.instructions.is_none() {
            self.outcome = Outcome::Fail;
        }
        let mut line = Line::new();
        line.str("shadeline-fw firmware=")
            .str(board_name)
            .str(" path=")
            .str(path_name)
            .str(" sink=")
            .str(sink_name)
            .str(" crc=")
            .hex32(figures.crc)
            .str(" expected=")
            .hex32(expected.crc)
            .str(if matched { " match=yes" } else { " match=no" });
        match figures.instructions {
            Some(n) => {
                line.field("instructions", n)
                    .field("pixels", pixels)
                    .str(" per_pixel=")
                    .ratio(n, pixels)
                    .field("covered", figures.covered)
                    .str(" per_covered=")
                    .ratio(n, figures.covered)
                    .str(if COUNT_COVERED {
                        " covered_by=target"
                    } else {
                        " covered_by=host"
                    });
                if !covered_matched {
                    line.field("covered_expected", expected.covered);
                }
            }
            None => {
                line.str(" instructions=unknown");
            }
        }
        match prepare {
            Some(n) => line.field("prepare", n),
            None => line.str(" prepare=unknown"),
        };
        line.field("stack", figures.stack as u64)
            .field("render_stack", figures.render_stack as u64)
            .byte(b'\n');
        self.board.write(line.as_bytes());
        // The kernel on a line of its own, after the figures, in the same buffer.
        line = Line::new();
        line.str("shadeline-fw firmware=")
            .str(board_name)
            .str(" path=")
            .str(path_name);
        kernel::report(&mut line, path.kernel());
        line.byte(b'\n');
        self.board.write(line.as_bytes());
    }

    /// The area-lights preset on the fixed path at the size of `expected`'s area-lights
    /// frames, under its sphere light and under a point light at the same place
    /// (`fixed-sphere-light`, `fixed-point-light`): each scene built into `scene`, prepared
    /// in place into `fixed`, rendered into `buffer` (a line buffer if `line`, else a
    /// framebuffer) and checked against the golden CRCs. A shadeline without its
    /// `area-lights` and `full-width` features refuses the sphere light, which fails the
    /// session.
    pub fn fixed_area_lights(
        &mut self,
        scene: &mut Option<Scene<5, 1>>,
        fixed: &mut PreparedFixed<5, 1>,
        buffer: &mut [Rgb565],
        line: bool,
    ) {
        use crate::expected::{
            AREA_LIGHTS_COVERED, AREA_LIGHTS_FIXED_POINT_RGB565_CRC32,
            AREA_LIGHTS_FIXED_SPHERE_RGB565_CRC32, AREA_LIGHTS_HEIGHT, AREA_LIGHTS_WIDTH,
        };
        let runs = [
            (
                "fixed-sphere-light",
                shadeline::AREA_LIGHT_RADIUS,
                AREA_LIGHTS_FIXED_SPHERE_RGB565_CRC32,
            ),
            (
                "fixed-point-light",
                0.0,
                AREA_LIGHTS_FIXED_POINT_RGB565_CRC32,
            ),
        ];
        let (w, h) = (AREA_LIGHTS_WIDTH, AREA_LIGHTS_HEIGHT);
        for (name, radius, crc) in runs {
            let (Some(built), _) = self.build(&mut *scene, || shadeline::area_lights(radius))
            else {
                self.note("shadeline-fw error=scene-area-lights\n");
                self.fail();
                return;
            };
            let (Some(path), prepare) = self.build_in(&mut *fixed, |f| f.prepare(built, w, h))
            else {
                self.prepare_failed(name);
                continue;
            };
            let expected = Expected {
                crc,
                covered: AREA_LIGHTS_COVERED,
            };
            if !self.run_in(name, path, (buffer, line), prepare, expected) {
                return;
            }
        }
    }

    /// [`Self::run`] into the first row (`line`) or the whole frame of `buffer`; `false`
    /// (reported, and the session failed) if `buffer` is too small for it.
    pub(crate) fn run_in<R: Render>(
        &mut self,
        name: &str,
        path: &R,
        (buffer, line): (&mut [Rgb565], bool),
        prepare: Option<u64>,
        expected: Expected,
    ) -> bool {
        let (w, h) = (path.width(), path.height());
        let pixels = if line { w } else { w * h } as usize;
        let Some(out) = buffer.get_mut(..pixels) else {
            self.note("shadeline-fw error=buffer-");
            self.note(name);
            self.note("\n");
            self.fail();
            return false;
        };
        let sink = if line {
            Sink::Line(out)
        } else {
            Sink::Frame(out)
        };
        self.run(name, path, sink, prepare, expected);
        true
    }

    /// Reports `error=prepare-<name>` and fails the session.
    pub(crate) fn prepare_failed(&mut self, name: &str) {
        self.note("shadeline-fw error=prepare-");
        self.note(name);
        self.note("\n");
        self.fail();
    }

    /// Reports the verdict and the deepest stack of the session; returns the verdict.
    pub fn finish(mut self) -> Outcome {
        let board_name = self.board.name();
        let mut line = Line::new();
        line.str("shadeline-fw firmware=")
            .str(board_name)
            .str(match self.outcome {
                Outcome::Pass => " result=pass",
                Outcome::Fail => " result=fail",
            })
            .field("peak_stack", self.peak_stack as u64)
            .byte(b'\n');
        self.board.write(line.as_bytes());
        self.outcome
    }

    /// Writes a line of free text (for boards that report something extra).
    pub fn note(&mut self, text: &str) {
        self.board.write(text.as_bytes());
    }

    /// Marks the session failed (a board-side error, such as a path that did not prepare).
    pub fn fail(&mut self) {
        self.outcome = Outcome::Fail;
    }

    fn figures<R: Render>(&mut self, path: &R, sink: &mut Sink<'_>, host_covered: u64) -> Figures {
        let (lowest, top) = self.board.stack_limits();
        if self.board.stack_pointer() < lowest + stack::GUARD {
            // Already below the stack's limit: painting would hit live data, and any figure
            // would be wrong. Fail loudly instead.
            self.outcome = Outcome::Fail;
            self.note("shadeline-fw error=stack-overflow\n");
        }

        // Covered pixels: not measured, but its stack counts toward the session's peak.
        #[cfg(feature = "count-covered")]
        let covered = {
            let _ = host_covered;
            let paint_top = self.paint();
            let covered = count_covered(path);
            self.note_stack(lowest, paint_top, top);
            covered
        };
        #[cfg(not(feature = "count-covered"))]
        let covered = host_covered;

        let paint_top = self.paint();
        let (render_ok, instructions, crc) = match sink {
            Sink::Frame(frame) => {
                let (ok, n) = render_frame(&mut self.meter, path, frame);
                let mut crc = Crc32::new();
                crc.update(frame);
                (ok, n, crc.value())
            }
            Sink::Line(line) => render_streamed(&mut self.meter, path, line),
        };
        // SAFETY: the same range `paint` just painted: free stack, word-aligned, readable.
        let deepest = unsafe { stack::deepest_touched(lowest, paint_top) };
        let sp = paint_top + stack::GUARD;
        self.peak_stack = self.peak_stack.max(top - deepest);
        Figures {
            crc,
            instructions,
            covered,
            stack: top - deepest,
            render_stack: sp - deepest,
            render_ok,
        }
    }

    /// The meter, for measured regions of other modules.
    #[cfg(feature = "animation")]
    pub(crate) fn meter(&mut self) -> &mut Meter<C> {
        &mut self.meter
    }

    /// The board's name.
    #[cfg(feature = "animation")]
    pub(crate) fn board_name(&self) -> &'static str {
        self.board.name()
    }

    /// Writes a report line.
    #[cfg(feature = "animation")]
    pub(crate) fn note_bytes(&mut self, text: &[u8]) {
        self.board.write(text);
    }

    /// The lowest address the stack may grow down to, and its top.
    #[cfg(feature = "animation")]
    pub(crate) fn stack_bounds(&self) -> (usize, usize) {
        self.board.stack_limits()
    }

    /// Paints the free stack below the current frame; returns the top of the painted range.
    #[inline(never)]
    pub(crate) fn paint(&self) -> usize {
        let (lowest, _) = self.board.stack_limits();
        let paint_top = (self.board.stack_pointer().saturating_sub(stack::GUARD)) & !3;
        // SAFETY: [lowest, paint_top) is below the live stack by GUARD bytes (room for
        // `stack::paint`'s own frame), above .bss, word-aligned; no interrupt can fire here
        // (the only one, SysTick on Cortex-M, is enabled only inside measured regions).
        unsafe { stack::paint(lowest, paint_top) };
        paint_top
    }

    /// Counts the deepest word below `paint_top` that was touched since [`Self::paint`]
    /// toward the session's peak stack.
    pub(crate) fn note_stack(&mut self, lowest: usize, paint_top: usize, top: usize) {
        // SAFETY: the range `paint` just painted.
        let deepest = unsafe { stack::deepest_touched(lowest, paint_top) };
        self.peak_stack = self.peak_stack.max(top - deepest);
    }
}

/// Renders every row of `path` into `frame`, one measured region per row.
/// Returns whether every row rendered, and the total instructions if every count was exact.
#[inline(never)]
fn render_frame<C: InstructionCounter, R: Render>(
    meter: &mut Meter<C>,
    path: &R,
    frame: &mut [Rgb565],
) -> (bool, Option<u64>) {
    let width = path.width() as usize;
    let mut ok = frame.len() == width * path.height() as usize;
    let mut total = Some(0u64);
    for (y, row) in frame.chunks_exact_mut(width.max(1)).enumerate() {
        let (result, n) = meter.measure(|| path.render_line(y as u32, row));
        ok &= result.is_ok();
        total = total.zip(n).map(|(t, n)| t + n);
    }
    (ok, total)
}

/// Renders every row of `path` into the one `line` buffer, one measured region per row, and
/// feeds each finished row to the CRC outside the region.
#[inline(never)]
fn render_streamed<C: InstructionCounter, R: Render>(
    meter: &mut Meter<C>,
    path: &R,
    line: &mut [Rgb565],
) -> (bool, Option<u64>, u32) {
    let mut ok = true;
    let mut total = Some(0u64);
    let mut crc = Crc32::new();
    for y in 0..path.height() {
        let (result, n) = meter.measure(|| path.render_line(y, line));
        ok &= result.is_ok();
        total = total.zip(n).map(|(t, n)| t + n);
        crc.update(line);
    }
    (ok, total, crc.value())
}

/// Hit records per segment of [`count_covered`]: 256 bytes of stack.
#[cfg(feature = "count-covered")]
const COVER_SEGMENT: usize = 32;

/// Pixels whose primary ray hits a sphere, found by rendering each row's coverage into hit
/// records one short segment at a time (a pixel does not depend on how a row is cut), so
/// the count needs no row-long buffer.
#[cfg(feature = "count-covered")]
#[inline(never)]
fn count_covered<R: Render>(path: &R) -> u64 {
    let mut hits = [HitRecord::default(); COVER_SEGMENT];
    let mut covered = 0;
    for y in 0..path.height() {
        let Some(span) = path.row_coverage(y) else {
            continue;
        };
        let mut x = span.start;
        while x < span.end {
            let n = (span.end - x).min(COVER_SEGMENT as u32);
            let segment = hits.get_mut(..n as usize).unwrap_or(&mut []);
            if path.render_segment(y, x, segment).is_ok() {
                covered += segment.iter().filter(|h| h.sphere.is_some()).count() as u64;
            }
            x += n;
        }
    }
    covered
}
