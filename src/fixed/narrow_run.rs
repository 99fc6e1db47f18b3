//! The narrow kernel's state along a run of a row: the spheres whose spans the run crosses
//! (their tracks, each with its quadrics at the run's current column), which of them cover
//! the current column, and the direction, `|D|²` and the lights' `D·L`, all moved one pixel
//! right by forward differences.
//!
//! A run is set up once (`PreparedFixed::narrow_run`, in `narrow`) and then stepped pixel
//! by pixel; the set of active tracks changes only where a span begins or ends, so the
//! pixel loop pays nothing for the spheres of the run that are elsewhere on the row.

use super::narrow_depth::DEPTH_ORDER;
use super::quadric::Step;
use super::vector::V3;
use crate::runs::Span;

/// One sphere along a run: its quadrics at the run's current column, once its span has
/// begun there.
///
/// `span` is the part of the sphere's span on the row where `b = oc·D` is negative (the
/// sphere is in front along the ray): `b` is linear along the row, so that part is one
/// interval, found once per run, and the hot loop never tests its sign.
#[derive(Clone, Copy)]
pub(super) struct Track<const L: usize> {
    pub(super) index: usize,
    /// The sphere's place in the frame's depth order (`PreparedFixed::depth_rank`). Only
    /// with the feature `depth-order`: a field more costs the pixel loop of RV32 elsewhere.
    #[cfg(feature = "depth-order")]
    pub(super) rank: u8,
    pub(super) span: Span,
    /// `E′` (see the module docs), and the shift that takes it to Q29.
    pub(super) e: Step,
    pub(super) e_shift: u16,
    /// Whether the row lies in the sphere's shadow rows (`NarrowSphere::shadows`): outside
    /// them no caster is tested.
    pub(super) shadows: bool,
    /// `G` per light.
    pub(super) g: [Step; L],
}

impl<const L: usize> Track<L> {
    /// The sphere's place in the frame's depth order; 0 without the feature `depth-order`.
    #[inline(always)]
    pub(super) fn rank(&self) -> u8 {
        #[cfg(feature = "depth-order")]
        return self.rank;
        #[cfg(not(feature = "depth-order"))]
        0
    }
}

/// The track index of no track (see [`NarrowRun::single`]).
pub(crate) const NO_TRACK: usize = usize::MAX;

/// The state of the narrow kernel along one run of a row.
///
/// A run merges the spans of every sphere it crosses, but at one column only the tracks
/// whose span covers it take part: `active` lists them (indices into `tracks`), and is
/// rebuilt only at `changes_at`, the next column where a span begins or ends, so a pixel
/// pays nothing for the spheres of the run that are elsewhere on the row.
pub(crate) struct NarrowRun<const S: usize, const L: usize> {
    /// The current column and its direction.
    pub(super) x: u32,
    pub(super) d: V3<i32>,
    pub(super) step: V3<i32>,
    /// `|D|²` and, per light, `D·L` (`L` in I2F30): exact, a quadratic and a line along the
    /// row, so two and one 64-bit additions per pixel.
    pub(super) a: Step,
    pub(super) dl: [Step; L],
    pub(super) tracks: heapless::Vec<Track<L>, S>,
    pub(super) active: heapless::Vec<u8, S>,
    pub(super) changes_at: u32,
}

impl<const S: usize, const L: usize> NarrowRun<S, L> {
    /// The active track, if at most one is active at the current column, and the column
    /// up to which that holds. With none active (between spheres, where a run spans
    /// several), the track is [`NO_TRACK`], which no track has: the row driver then
    /// passes those columns as the background ([`NarrowRun::skip`]), or on ARMv6-M
    /// [`PreparedFixed::narrow_shade`] finds no surface there, moves no track's quadrics
    /// and gives the background, with no search.
    #[inline(always)]
    pub(crate) fn single(&self) -> Option<(usize, u32)> {
        match self.active.as_slice() {
            [only] => Some((*only as usize, self.changes_at)),
            [] => Some((NO_TRACK, self.changes_at)),
            _ => None,
        }
    }

    /// Moves the direction, `|D|²` and the first `lights` of `D·L` one pixel right. The
    /// direction's three components are written out: at `opt-level = "s"` a loop over
    /// them stays a loop (as do the colour sums of `narrow_lights`, written with `each3`).
    #[inline(always)]
    pub(super) fn advance(&mut self, lights: usize) {
        let [x, y, z] = self.step;
        self.d[0] += x;
        self.d[1] += y;
        self.d[2] += z;
        self.a.v = self.a.v.wrapping_add(self.a.d);
        self.a.d = self.a.d.wrapping_add(self.a.dd);
        for dl in first(&mut self.dl, lights) {
            dl.v = dl.v.wrapping_add(dl.d);
        }
    }

    /// Moves the run `k` pixels right where no track is active.
    #[inline(always)]
    pub(crate) fn skip(&mut self, k: u32, lights: usize) {
        for _ in 0..k {
            self.advance(lights);
        }
        self.x += k;
    }

    /// The active tracks again, once the run has reached the column where they change.
    #[inline(always)]
    pub(crate) fn refresh(&mut self) {
        if self.x >= self.changes_at {
            (self.active, self.changes_at) = activity(&self.tracks, self.x);
        }
    }

    /// A run of no tracks, for [`PreparedFixed::narrow_run`] to set.
    #[inline(always)]
    pub(crate) const fn new() -> Self {
        NarrowRun {
            x: 0,
            d: [0; 3],
            step: [0; 3],
            a: Step { v: 0, d: 0, dd: 0 },
            dl: [Step { v: 0, d: 0, dd: 0 }; L],
            tracks: heapless::Vec::new(),
            active: heapless::Vec::new(),
            changes_at: 0,
        }
    }
}

/// The tracks whose span covers column `x` (indices into `tracks`) by their rank in the
/// frame's depth order (`Track::rank`; in the tracks' order where the ranks are equal, as
/// in a frame with no depth order), and the next column where a span begins or ends. Not
/// inlined: the pixel loop only calls it where a span begins or ends.
#[inline(never)]
pub(super) fn activity<const S: usize, const L: usize>(
    tracks: &[Track<L>],
    x: u32,
) -> (heapless::Vec<u8, S>, u32) {
    let mut active = heapless::Vec::new();
    let mut changes_at = u32::MAX;
    for (i, t) in tracks.iter().enumerate() {
        if t.span.start <= x && x < t.span.end {
            // As many entries as tracks, and the prepare only sets up the narrow kernel for
            // at most 256 spheres, which `u8` indexes: cannot fail.
            let pushed = active.push(i as u8);
            debug_assert!(pushed.is_ok());
            // Moved ahead of the tracks of a later rank, by swaps (no `memmove`).
            if DEPTH_ORDER {
                let rank = |j: u8| tracks.get(usize::from(j)).map_or(0, Track::rank);
                for k in (1..active.len()).rev() {
                    match active.get_mut(k - 1..=k) {
                        Some([a, b]) if rank(*a) > rank(*b) => core::mem::swap(a, b),
                        _ => break,
                    }
                }
            }
        }
        let next = if x < t.span.start {
            t.span.start
        } else {
            t.span.end
        };
        if x < next {
            changes_at = changes_at.min(next);
        }
    }
    (active, changes_at)
}

/// The states of the first `lights` lights, to move one pixel right; for one or two lights of
/// capacity, all of them (a light beyond the frame's has zero steps, so moving it changes
/// nothing), which spares the pixel loop a loop of unknown length.
#[inline(always)]
pub(super) fn first<const L: usize>(states: &mut [Step; L], lights: usize) -> &mut [Step] {
    if L <= 2 {
        states
    } else {
        states.get_mut(..lights).unwrap_or_default()
    }
}

/// The columns of `[start, end)` where `b_at(column)` is negative, `None` if there are none.
/// `b` is linear in the column (growing if `rises`, otherwise not), so they are one
/// interval: the first column is tested, the last one too unless the first one's sign and
/// the slope's settle it, and where the sign changes between them a binary search finds
/// the column where it does.
#[inline(always)]
pub(super) fn front_part(
    start: u32,
    end: u32,
    rises: bool,
    b_at: impl Fn(u32) -> i64,
) -> Option<Span> {
    if start >= end {
        return None;
    }
    let first = b_at(start) < 0;
    if first != rises {
        // Negative and not growing, or not negative and growing: the sign stays.
        return first.then_some(Span { start, end });
    }
    let last = b_at(end - 1) < 0;
    if first == last {
        return first.then_some(Span { start, end });
    }
    // The sign at `lo` is `first`'s, the sign at `hi` is `last`'s.
    let (mut lo, mut hi) = (start, end - 1);
    while hi - lo > 1 {
        let mid = lo + (hi - lo) / 2;
        if (b_at(mid) < 0) == first {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    Some(if first {
        Span { start, end: hi }
    } else {
        Span { start: hi, end }
    })
}
