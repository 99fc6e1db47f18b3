//! The row helpers both paths share: spans, covered runs, the background fill.
//!
//! A path's row driver computes each sphere's [`Span`] on the row (where it may cover pixels;
//! conservative), merges them into sorted, disjoint covered runs ([`merge_runs`]), and walks
//! the caller's segment with [`walk_runs`]: outside the runs every pixel is the background,
//! encoded once per row ([`Background`]) and copied, with no per-pixel work; inside, the
//! path's kernel shades. Every slice is reached through `get`/`get_mut`, so nothing here can
//! panic, which the firmware's link-time panic proof checks.

use crate::encoding::Encoding;
use crate::pixel::Pixel;

/// The half-open pixel range `[start, end)` of a row that one sphere may cover.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Span {
    /// First pixel that may be covered.
    pub start: u32,
    /// One past the last pixel that may be covered (`start < end ≤ width`).
    pub end: u32,
}

/// The covered hull of a row's spans: from the smallest start to the largest end.
pub(crate) fn coverage_of(spans: &[Option<Span>]) -> Option<Span> {
    spans.iter().flatten().fold(None, |acc: Option<Span>, s| {
        Some(match acc {
            None => *s,
            Some(a) => Span {
                start: a.start.min(s.start),
                end: a.end.max(s.end),
            },
        })
    })
}

/// The background of one row, encoded: one pixel, or four (`x mod 4`) when dithering.
pub(crate) struct Background<P> {
    pixels: [P; 4],
    dither: bool,
}

impl<P: Pixel> Background<P> {
    /// `pixel(x)` encodes the background at column `x` (called for `x` in `0..4`, or once
    /// with 0 when not dithering).
    #[inline(always)]
    pub(crate) fn new(encoding: Encoding, pixel: impl Fn(u32) -> P) -> Self {
        let first = pixel(0);
        if encoding.dither && P::LEVELS.is_some() {
            Background {
                pixels: [first, pixel(1), pixel(2), pixel(3)],
                dither: true,
            }
        } else {
            Background {
                pixels: [first; 4],
                dither: false,
            }
        }
    }

    /// The pixel at column `x`.
    #[inline(always)]
    pub(crate) fn at(&self, x: usize) -> P {
        self.pixels[x & 3]
    }

    /// Fills `out`, whose first pixel is column `x`.
    ///
    /// The first pixels (one period of the pattern: 1, or 4 when dithering) are written one
    /// by one, the rest by doubling copies of what is already there: `[P]::fill` is a loop
    /// per element for 3-byte pixels, while a copy is a `memcpy`. The dither pattern has
    /// period 4 and every copy lands a multiple of 4 pixels further on, so it stays in phase.
    #[inline(always)]
    pub(crate) fn fill(&self, out: &mut [P], x: usize) {
        let period = if self.dither { 4 } else { 1 };
        for (px, x) in out.iter_mut().zip(x..).take(period) {
            *px = self.at(x);
        }
        let mut filled = period;
        while filled < out.len() {
            let (head, tail) = out.split_at_mut(filled);
            let n = head.len().min(tail.len());
            if let (Some(dst), Some(src)) = (tail.get_mut(..n), head.get(..n)) {
                dst.copy_from_slice(src);
            }
            filled += n;
        }
    }
}

/// The walk both row drivers share over the segment of a row that starts at column
/// `seg_start` and fills `out`: the background everywhere outside the covered `runs` (sorted,
/// disjoint), and `shade(first_column, pixels)` on each run's part inside the segment. Every
/// slice is reached through `get_mut`, so nothing here can panic.
#[inline(always)]
pub(crate) fn walk_runs<P: Pixel>(
    out: &mut [P],
    seg_start: usize,
    runs: &[Span],
    background: &Background<P>,
    mut shade: impl FnMut(usize, &mut [P]),
) {
    let seg_end = seg_start + out.len();
    let mut x = seg_start;
    for run in runs {
        let start = (run.start as usize).max(seg_start);
        let end = (run.end as usize).min(seg_end);
        if start >= end {
            continue;
        }
        if let Some(gap) = out.get_mut(x - seg_start..start - seg_start) {
            background.fill(gap, x);
        }
        x = end;
        if let Some(run_pixels) = out.get_mut(start - seg_start..end - seg_start) {
            shade(start, run_pixels);
        }
    }
    if let Some(tail) = out.get_mut(x - seg_start..) {
        background.fill(tail, x);
    }
}

/// Merged covered runs of a row: `[start, end)` pixel ranges, sorted, disjoint.
pub(crate) fn merge_runs<const S: usize>(spans: &[Option<Span>]) -> heapless::Vec<Span, S> {
    let mut runs: heapless::Vec<Span, S> = heapless::Vec::new();
    for span in spans.iter().flatten() {
        let _ = runs.push(*span);
    }
    // Insertion sort by start: S is small and this is once per row. Written with a slice
    // pattern instead of indexing so that no bounds check (and no panic path) is left for
    // the firmware's link-time panic proof to find.
    for i in 1..runs.len() {
        let mut j = i;
        while j > 0 {
            match runs.get_mut(j - 1..=j) {
                Some([a, b]) if a.start > b.start => core::mem::swap(a, b),
                _ => break,
            }
            j -= 1;
        }
    }
    let mut merged: heapless::Vec<Span, S> = heapless::Vec::new();
    for span in runs {
        match merged.last_mut() {
            Some(last) if span.start <= last.end => last.end = last.end.max(span.end),
            _ => {
                let _ = merged.push(span);
            }
        }
    }
    merged
}
