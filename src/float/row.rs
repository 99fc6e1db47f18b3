//! The row driver of the float paths: [`Render`] for [`Prepared`].
//!
//! For row `y` it computes every sphere's span ([`Prepared::row_spans`]), merges them into
//! covered runs and walks them with the shared [`walk_runs`]: the background outside the runs,
//! encoded once per row, and inside each run packets of the path's lane count, each handed
//! to the kernel ([`Prepared::shade`]) with only the spheres whose spans touch the packet. The
//! last packet of a run computes full lanes and stores only the pixels that belong to the
//! run: no per-lane branch in the math, no read or write outside the caller's slice. Then
//! `encode` ([`store_packet`]) quantizes the packet into the caller's pixel format. The
//! general kernel's packet loop ([`Prepared::shade_packets`]) is compiled once per pair of
//! the format's flags (hit records, saturation) and hands its packets to the format's store
//! through one indirect call each, so that a build rendering several formats holds a few
//! copies of the kernel rather than one per format and encoding. On the scalar paths, rows
//! of a frame without a normalized material go to the kernel without the normalized models'
//! code (see [`super::kernel`]).
//!
//! A row is a pure function of the prepared frame and `y`: rows can be rendered in any order,
//! on any number of threads, or streamed to a display one line buffer at a time.

use super::kernel::Packet;
use super::lane::Lane;
use super::narrow::NarrowRow;
use super::prepare::{FloatPath, Prepared, Row};
use crate::encoding::{linear_code, luma, Encoding};
use crate::pixel::{pixel_from_codes, HitRecord, LinearRgb, Pixel, Shade};
use crate::render::{check_segment, Kernel, Render, RenderError};
use crate::runs::{coverage_of, merge_runs, walk_runs, Background, Span};

impl<W: FloatPath, const S: usize, const L: usize> Prepared<W, S, L> {
    /// The background at `(x, y)`; `PLAIN` as in [`store_packet`].
    fn background_pixel<P: Pixel, const PLAIN: bool>(
        &self,
        encoding: Encoding,
        x: u32,
        y: u32,
    ) -> P {
        if !PLAIN && !encoding.is_default() {
            let c = self.background;
            let codes = [linear_code(c.r), linear_code(c.g), linear_code(c.b)];
            if let Some(px) = pixel_from_codes(codes, encoding, x, y) {
                return px;
            }
        }
        P::encode(&Shade {
            color: self.background,
            hit: HitRecord::default(),
        })
    }
}

impl<W: FloatPath, const S: usize, const L: usize> Render for Prepared<W, S, L> {
    /// The narrow kernel, or the general one because of the first light that is not
    /// distant, sphere whose model is not classic or whose highlight is too sharp for the
    /// narrow kernel's `pow` (`shininess`), or sphere the camera is close to (`center`).
    fn kernel(&self) -> Kernel {
        self.kernel
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
    /// [`with_encoding`](Render::with_encoding)) has a row function of its own, so a
    /// firmware that never picks another encoding links none of their code, nor the 8 KiB
    /// sRGB table.
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

impl<W: FloatPath, const S: usize, const L: usize> Prepared<W, S, L> {
    /// The body of [`Render::render_segment_with`] on a checked segment. `PLAIN`: `encoding`
    /// is the default, a constant of the instantiation down to every store, so that the
    /// default's row function holds none of the other encodings' code.
    #[inline(never)]
    fn render_segment_encoded<P: Pixel, const PLAIN: bool>(
        &self,
        y: u32,
        x: u32,
        out: &mut [P],
        encoding: Encoding,
    ) {
        let row = self.row(y);
        let spans = self.row_spans(y);
        let runs = merge_runs::<S>(&spans);
        let background = Background::new(encoding, |x| {
            self.background_pixel::<P, PLAIN>(encoding, x, y)
        });
        let run = (x as usize, y, encoding, &background);
        // Frames the narrow kernel takes (see `narrow`) go there. Of the others, on the
        // scalar paths, frames without a normalized material get a general kernel that holds
        // only the classic models' code (see the kernel's module docs). The SIMD paths keep
        // one general kernel: on x86-64 (AVX2) the lean one costs them more instructions.
        match self.kernel {
            Kernel::Narrow => self.shade_narrow_runs::<P, PLAIN>(out, run, &row, &spans, &runs),
            Kernel::General { .. } if W::Lane::LANES > 1 || self.normalized => {
                self.shade_runs::<P, true, PLAIN>(out, run, &row, &spans, &runs)
            }
            Kernel::General { .. } => {
                self.shade_runs::<P, false, PLAIN>(out, run, &row, &spans, &runs)
            }
        }
    }
}

impl<W: FloatPath, const S: usize, const L: usize> Prepared<W, S, L> {
    /// Shades the covered `runs` of `out` (pixels `x…` of row `y`), packet by packet, and
    /// fills the rest with the background: the body of `render_segment_with`. `NORMALIZED`:
    /// see [`Prepared::shade`]. The packets come from [`Self::shade_packets`], which is not
    /// generic over the pixel format: only the stores are.
    #[inline(always)]
    fn shade_runs<P: Pixel, const NORMALIZED: bool, const PLAIN: bool>(
        &self,
        out: &mut [P],
        (x, y, encoding, background): (usize, u32, Encoding, &Background<P>),
        row: &Row,
        spans: &[Option<Span>],
        runs: &[Span],
    ) {
        walk_runs(out, x, runs, background, |start, run_pixels| {
            let lanes = W::Lane::LANES;
            let run = (row, spans, start, run_pixels.len());
            let mut store = |index: usize, packet: Option<&Packet<W::Lane>>| {
                let from = index * lanes;
                let to = (from + lanes).min(run_pixels.len());
                let Some(chunk) = run_pixels.get_mut(from..to) else {
                    return;
                };
                let x0 = start + from;
                match packet {
                    Some(packet) => {
                        store_packet::<P, _, PLAIN>(chunk, packet, encoding, x0 as u32, y)
                    }
                    None => background.fill(chunk, x0),
                }
            };
            // The flags are constants of the pixel format: one arm is left per format.
            // Formats with levels clamp each channel to [0, 1]: `+∞` stores what `f32::MAX` does.
            match (P::NEEDS_HITS, P::LEVELS.is_none()) {
                (false, false) => self.shade_packets::<NORMALIZED, false, false>(run, &mut store),
                (false, true) => self.shade_packets::<NORMALIZED, false, true>(run, &mut store),
                (true, false) => self.shade_packets::<NORMALIZED, true, false>(run, &mut store),
                (true, true) => self.shade_packets::<NORMALIZED, true, true>(run, &mut store),
            }
        });
    }

    /// The general kernel's packet loop over one covered run (`row`, the row's `spans`, the
    /// run's first column and length): each packet, shaded with the spheres whose spans touch
    /// it ([`Prepared::shade`], with `HITS` and `SATURATE` as its `record_hits` and
    /// `saturate`), goes to `store` with its index in the run, and a packet no span touches
    /// goes there as `None`. Out of line and generic only over what the kernel's code depends
    /// on: a frame rendered into several pixel formats holds one copy of the kernel per pair
    /// of flags, not one per format and encoding (about ten, each among the largest functions
    /// of a build). The call through `store` costs one indirect call per packet.
    #[inline(never)]
    fn shade_packets<const NORMALIZED: bool, const HITS: bool, const SATURATE: bool>(
        &self,
        (row, spans, start, len): (&Row, &[Option<Span>], usize, usize),
        store: &mut PacketStore<'_, W::Lane>,
    ) {
        let lanes = W::Lane::LANES;
        let mut candidates = Candidates::<S>::new();
        for index in 0..len.div_ceil(lanes) {
            let from = index * lanes;
            let x0 = (start + from) as u32;
            let x1 = x0 + lanes.min(len - from) as u32;
            let candidates = candidates.overlapping(spans, x0, x1);
            if candidates.is_empty() {
                store(index, None);
                continue;
            }
            let packet = self.shade::<NORMALIZED>(row, x0, candidates, HITS, SATURATE);
            store(index, Some(&packet));
        }
    }

    /// [`Self::shade_runs`] for frames the narrow kernel takes: the row's quadrics once
    /// (`narrow_row`), then each packet from them; while a packet's only candidate stays the
    /// same sphere, its constants are looked up once for all of its packets.
    #[inline(always)]
    fn shade_narrow_runs<P: Pixel, const PLAIN: bool>(
        &self,
        out: &mut [P],
        (x, y, encoding, background): (usize, u32, Encoding, &Background<P>),
        row: &Row,
        spans: &[Option<Span>],
        runs: &[Span],
    ) {
        let mut nrow = NarrowRow::empty();
        self.narrow_row(&mut nrow, y, spans);
        let nrow = &nrow;
        // Anti-aliased frames saturate every colour, as the general kernel's do.
        #[cfg(feature = "antialias")]
        let flags = (P::NEEDS_HITS, P::LEVELS.is_none() || self.antialias);
        #[cfg(not(feature = "antialias"))]
        let flags = (P::NEEDS_HITS, P::LEVELS.is_none());
        #[cfg(not(feature = "antialias"))]
        let _ = row;
        walk_runs(out, x, runs, background, |start, run_pixels| {
            let mut candidates = Candidates::<S>::new();
            let mut single = None;
            for (chunk_index, chunk) in run_pixels.chunks_mut(W::Lane::LANES).enumerate() {
                let x0 = (start + chunk_index * W::Lane::LANES) as u32;
                let x1 = x0 + chunk.len() as u32;
                let (list, fresh) = candidates.overlapping_fresh(spans, x0, x1);
                if fresh {
                    single = match list {
                        [k] => self.single(*k as usize, (y, nrow)),
                        _ => None,
                    };
                }
                if list.is_empty() {
                    background.fill(chunk, x0 as usize);
                    continue;
                }
                let shaded = match &single {
                    Some(single) => self.shade_single((y, nrow), single, x0, flags),
                    None => self.shade_narrow((y, nrow), x0, list, flags.0, flags.1),
                };
                #[cfg(feature = "antialias")]
                let packet = self.narrow_antialiased(shaded, (row, nrow), x0, list);
                #[cfg(not(feature = "antialias"))]
                let packet = shaded.0;
                store_packet::<P, _, PLAIN>(chunk, &packet, encoding, x0, y);
            }
        });
    }
}

/// Where [`Prepared::shade_packets`] hands each packet of a run: its index in the run, and
/// the packet (`None` where no span touches it).
type PacketStore<'a, T> = dyn FnMut(usize, Option<&Packet<T>>) + 'a;

/// The spheres whose spans overlap a packet's pixels, in scene order, kept from one packet
/// to the next while no span starts or ends between them: a run's packets walk left to
/// right, and the list changes only at the spans' ends, a few times a row, while the scalar
/// path's packets are single pixels. Any list holding every sphere whose span touches the
/// packet gives the same bits; this one holds exactly those.
struct Candidates<const S: usize> {
    /// The spheres of the last packet.
    list: heapless::Vec<u16, S>,
    /// The list holds for a later packet `x0..x1` while `x1 <= joins`: the nearest start of
    /// a span to the right of the last packet.
    joins: u32,
    /// … and while `x0 < leaves`: the nearest end of a listed span.
    leaves: u32,
}

impl<const S: usize> Candidates<S> {
    /// An empty list that holds for no packet.
    #[inline(always)]
    fn new() -> Self {
        Candidates {
            list: heapless::Vec::new(),
            joins: 0,
            leaves: 0,
        }
    }

    /// The spheres whose spans overlap `x0..x1`, for packets that walk left to right.
    #[inline(always)]
    fn overlapping(&mut self, spans: &[Option<Span>], x0: u32, x1: u32) -> &[u16] {
        self.overlapping_fresh(spans, x0, x1).0
    }

    /// [`Self::overlapping`], and whether the list is new for this packet (`false`: the
    /// last packet's list holds).
    #[inline(always)]
    fn overlapping_fresh(&mut self, spans: &[Option<Span>], x0: u32, x1: u32) -> (&[u16], bool) {
        let fresh = x1 > self.joins || x0 >= self.leaves;
        if fresh {
            self.list.clear();
            self.joins = u32::MAX;
            self.leaves = u32::MAX;
            for (k, span) in spans.iter().enumerate() {
                let Some(s) = span else { continue };
                if s.start < x1 && x0 < s.end {
                    // One span per sphere, so at most S: cannot fail.
                    let pushed = self.list.push(k as u16);
                    debug_assert!(pushed.is_ok(), "more candidates than spheres");
                    self.leaves = self.leaves.min(s.end);
                } else if s.start >= x1 {
                    self.joins = self.joins.min(s.start);
                }
            }
        }
        (&self.list, fresh)
    }
}

/// `encode` for the float paths: writes the first `chunk.len()` lanes of a packet whose
/// first pixel is `(x0, y)`.
///
/// With [`Encoding::LINEAR`], formats with levels are quantized a packet at a time with
/// [`Lane::quantize_lanes`], the rule of [`quantize`](crate::encoding::quantize) (clamp with NaN to
/// 0, `c·max + ½`, truncate; [`Gray8`](crate::Gray8) on the [`luma`]), so every width stores
/// the bits the scalar path stores. Other encodings compute the linear codes a packet at a
/// time ([`linear_code`]'s operations) and then apply the encoding's integer rule per pixel
/// ([`crate::encoding`]). `PLAIN`: the encoding is the default, a constant of the row
/// function's instantiation ([`Prepared::render_segment_encoded`]), so that its stores hold
/// no other encoding's code.
#[inline(always)]
fn store_packet<P: Pixel, T: Lane, const PLAIN: bool>(
    chunk: &mut [P],
    packet: &Packet<T>,
    encoding: Encoding,
    x0: u32,
    y: u32,
) {
    let c = packet.color;
    if let Some(max) = P::LEVELS {
        if PLAIN || encoding.is_default() {
            if P::GRAY {
                let l = luma([c.x, c.y, c.z]).quantize_lanes(max[0] as f32);
                for (px, l) in chunk.iter_mut().zip(&l) {
                    *px = P::from_levels([*l as u16; 3]);
                }
                return;
            }
            let r = c.x.quantize_lanes(max[0] as f32);
            let g = c.y.quantize_lanes(max[1] as f32);
            let b = c.z.quantize_lanes(max[2] as f32);
            for (px, ((r, g), b)) in chunk.iter_mut().zip(r.iter().zip(&g).zip(&b)) {
                *px = P::from_levels([*r as u16, *g as u16, *b as u16]);
            }
            return;
        }
        // Linear codes, `⌊clamp(c)·65536 + ½⌋`, then the encoding's integer rule per pixel.
        let r = c.x.quantize_lanes(65536.0);
        let g = c.y.quantize_lanes(65536.0);
        let b = c.z.quantize_lanes(65536.0);
        let codes = r.iter().zip(&g).zip(&b);
        for ((px, ((r, g), b)), x) in chunk.iter_mut().zip(codes).zip(x0..) {
            if let Some(p) = pixel_from_codes([*r as u32, *g as u32, *b as u32], encoding, x, y) {
                *px = p;
            }
        }
        return;
    }
    let (r, g, b) = (
        packet.color.x.to_lanes(),
        packet.color.y.to_lanes(),
        packet.color.z.to_lanes(),
    );
    let spheres = packet.sphere.to_lanes();
    let lanes = r.iter().zip(&g).zip(&b).zip(&spheres).zip(&packet.shadowed);
    for (px, ((((r, g), b), sphere), shadowed)) in chunk.iter_mut().zip(lanes) {
        let hit = *sphere >= 0.0;
        *px = P::encode(&Shade {
            color: LinearRgb::new(*r, *g, *b),
            hit: HitRecord {
                sphere: hit.then_some(*sphere as u16),
                shadowed: if hit { *shadowed } else { 0 },
            },
        });
    }
}
