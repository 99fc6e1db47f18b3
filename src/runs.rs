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

/// Pixels per block of [`Background::fill`]: a multiple of the dither period, 4.
const FILL_BLOCK: usize = 8;

/// The background of one row, encoded: one pixel, or four (`x mod 4`) when dithering.
pub(crate) struct Background<P> {
    pixels: [P; 4],
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
            }
        } else {
            Background { pixels: [first; 4] }
        }
    }

    /// The pixel at column `x`.
    #[inline(always)]
    pub(crate) fn at(&self, x: usize) -> P {
        self.pixels[x & 3]
    }

    /// Fills `out`, whose first pixel is column `x`.
    ///
    /// The first [`FILL_BLOCK`] pixels are written one by one, the rest as copies of that
    /// block, stored element by element: a few loads and stores per block for every pixel
    /// format at every optimisation level, with no call (`[P]::fill` is a loop per element,
    /// `memcpy` calls cost their set-up on every gap, and at `opt-level = "s"` an array
    /// assignment becomes one). The block is a multiple of the dither pattern's period, 4,
    /// so every copy stays in phase.
    #[cfg_attr(not(shadeline_short_mul), inline(always))]
    #[cfg_attr(shadeline_short_mul, inline(never))]
    pub(crate) fn fill(&self, out: &mut [P], x: usize) {
        let (head, tail) = out.split_at_mut(out.len().min(FILL_BLOCK));
        for (px, x) in head.iter_mut().zip(x..) {
            *px = self.at(x);
        }
        let Ok(block) = <&[P; FILL_BLOCK]>::try_from(&*head) else {
            // Fewer than a block: all written.
            return;
        };
        let block = *block;
        let mut chunks = tail.chunks_exact_mut(FILL_BLOCK);
        for chunk in &mut chunks {
            if let Ok(chunk) = <&mut [P; FILL_BLOCK]>::try_from(chunk) {
                let [a, b, c, d, e, f, g, h] = block;
                chunk[0] = a;
                chunk[1] = b;
                chunk[2] = c;
                chunk[3] = d;
                chunk[4] = e;
                chunk[5] = f;
                chunk[6] = g;
                chunk[7] = h;
            }
        }
        for (px, b) in chunks.into_remainder().iter_mut().zip(block) {
            *px = b;
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
        // Runs are sorted and disjoint: each starts at or after the last one's end.
        debug_assert!(x <= start, "run {run:?} starts before column {x}");
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
    let mut runs = heapless::Vec::new();
    merge_runs_into(spans, &mut runs);
    runs
}

/// [`merge_runs`] into `runs` (cleared first), in place: a row driver keeps the runs in its
/// own frame instead of receiving a copy.
#[inline(never)]
pub(crate) fn merge_runs_into<const S: usize>(
    spans: &[Option<Span>],
    runs: &mut heapless::Vec<Span, S>,
) {
    runs.clear();
    for span in spans.iter().flatten() {
        // At most one span per sphere: cannot fail.
        let pushed = runs.push(*span);
        debug_assert!(pushed.is_ok(), "more spans than spheres");
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
    // Merged in place: the first `kept` entries are the merged runs so far.
    let mut kept = 0usize;
    for i in 0..runs.len() {
        let Some(&span) = runs.get(i) else {
            break;
        };
        match kept.checked_sub(1).and_then(|k| runs.get_mut(k)) {
            Some(last) if span.start <= last.end => last.end = last.end.max(span.end),
            _ => {
                // `kept ≤ i`: a slot that exists.
                if let Some(slot) = runs.get_mut(kept) {
                    *slot = span;
                }
                kept += 1;
            }
        }
    }
    runs.truncate(kept);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::pixel::Gray8;

    const S: usize = 8;

    fn span(start: u32, end: u32) -> Option<Span> {
        Some(Span { start, end })
    }

    fn runs(spans: &[Option<Span>]) -> heapless::Vec<(u32, u32), S> {
        merge_runs::<S>(spans)
            .iter()
            .map(|s| (s.start, s.end))
            .collect()
    }

    #[test]
    fn merge_runs_of_an_empty_row() {
        assert!(runs(&[]).is_empty());
        assert!(runs(&[None, None, None]).is_empty());
        assert_eq!(coverage_of(&[None, None]), None);
    }

    #[test]
    fn merge_runs_sorts_and_joins_touching_and_overlapping_spans() {
        // Disjoint, given out of order.
        assert_eq!(runs(&[span(5, 7), None, span(0, 2)]), [(0, 2), (5, 7)]);
        // Touching: [0, 3) and [3, 5) are one run.
        assert_eq!(runs(&[span(3, 5), span(0, 3)]), [(0, 5)]);
        // Overlapping, and one inside another.
        assert_eq!(runs(&[span(1, 4), span(2, 6), span(2, 3)]), [(1, 6)]);
        // A chain that only joins once sorted.
        assert_eq!(
            runs(&[span(6, 7), span(0, 2), span(4, 6), span(2, 3)]),
            [(0, 3), (4, 7)]
        );
        assert_eq!(
            coverage_of(&[span(4, 6), None, span(1, 2)]),
            Some(Span { start: 1, end: 6 })
        );
    }

    #[test]
    fn merge_runs_at_both_ends_of_a_row() {
        assert_eq!(runs(&[span(6, 7), span(0, 1)]), [(0, 1), (6, 7)]);
        assert_eq!(runs(&[span(0, 7)]), [(0, 7)]);
        assert_eq!(runs(&[span(0, 1)]), [(0, 1)]);
    }

    /// Walks `runs` over the segment `[seg_start, seg_start + len)` with background 0 and
    /// shade writing `100 + x`; returns the pixels and the runs the shader saw.
    fn walk(
        len: usize,
        seg_start: usize,
        runs: &[Span],
        dither: bool,
    ) -> (heapless::Vec<u8, 16>, heapless::Vec<(usize, usize), 8>) {
        let encoding = Encoding {
            dither,
            ..Encoding::LINEAR
        };
        let background = Background::new(encoding, |x| Gray8(x as u8));
        let mut out = [Gray8(255); 16];
        let out = &mut out[..len];
        let mut seen = heapless::Vec::new();
        walk_runs(out, seg_start, runs, &background, |x, px| {
            seen.push((x, px.len()))
                .expect("more runs than the test's capacity");
            for (p, x) in px.iter_mut().zip(x..) {
                *p = Gray8(100 + x as u8);
            }
        });
        (out.iter().map(|p| p.0).collect(), seen)
    }

    fn s(start: u32, end: u32) -> Span {
        Span { start, end }
    }

    #[test]
    fn walk_runs_of_an_empty_row_is_all_background() {
        for len in [1, 7] {
            let (px, seen) = walk(len, 0, &[], false);
            assert!(px.iter().all(|&p| p == 0), "width {len}");
            assert!(seen.is_empty());
        }
    }

    #[test]
    fn walk_runs_at_width_1() {
        let (px, seen) = walk(1, 0, &[s(0, 1)], false);
        assert_eq!(px, [100]);
        assert_eq!(seen, [(0, 1)]);
        assert_eq!(walk(1, 0, &[], true).0, [0]);
    }

    #[test]
    fn walk_runs_at_width_7_with_runs_at_both_ends() {
        let (px, seen) = walk(7, 0, &[s(0, 2), s(5, 7)], false);
        assert_eq!(px, [100, 101, 0, 0, 0, 105, 106]);
        assert_eq!(seen, [(0, 2), (5, 2)]);
        let (px, seen) = walk(7, 0, &[s(0, 7)], false);
        assert_eq!(px, [100, 101, 102, 103, 104, 105, 106]);
        assert_eq!(seen, [(0, 7)]);
    }

    #[test]
    fn walk_runs_clips_runs_to_the_segment() {
        // The segment is columns 3..7 of a row; runs reach outside it on both sides.
        let (px, seen) = walk(4, 3, &[s(0, 4), s(6, 9)], false);
        assert_eq!(px, [103, 0, 0, 106]);
        assert_eq!(seen, [(3, 1), (6, 1)]);
        // A run entirely outside the segment is skipped.
        let (px, seen) = walk(2, 3, &[s(0, 2), s(6, 9)], false);
        assert_eq!(px, [0, 0]);
        assert!(seen.is_empty());
    }

    #[test]
    fn background_fill_keeps_the_dither_phase() {
        // Dithering: the background is `x mod 4`, whatever the first column and the length
        // (every length up to two blocks of `fill`, so every remainder after one).
        for len in 0..=16 {
            for seg_start in 0..9 {
                let (px, _) = walk(len, seg_start, &[], true);
                for (i, p) in px.iter().enumerate() {
                    assert_eq!(*p as usize, (seg_start + i) & 3, "len {len} at {seg_start}");
                }
            }
        }
        // A run in the middle: the gaps on both sides stay in phase.
        let (px, _) = walk(7, 1, &[s(3, 4)], true);
        assert_eq!(px, [1, 2, 103, 0, 1, 2, 3]);
        // Without dithering one pixel is copied everywhere.
        let (px, _) = walk(7, 2, &[], false);
        assert!(px.iter().all(|&p| p == 0));
    }
}
