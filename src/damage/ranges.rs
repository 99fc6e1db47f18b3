//! The damaged column ranges of one row, in a fixed number of slots.
//!
//! Ranges are kept sorted and disjoint; one that overlaps or touches another joins it, and
//! when every slot is taken the two ranges with the smallest gap between them become one.
//! Joining only ever adds columns, so a row's damage stays conservative however many
//! outlines cross it.

use crate::runs::Span;

/// Column ranges per damaged row, at most: more are joined (see [`DamageRow`]).
pub const RANGES_PER_ROW: usize = 4;

/// One damaged row: the row and its column ranges, sorted and disjoint.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct DamageRow {
    y: u32,
    spans: [Span; RANGES_PER_ROW],
    len: usize,
}

impl DamageRow {
    /// A row with no damaged columns yet.
    pub(super) fn new(y: u32) -> Self {
        DamageRow {
            y,
            spans: [Span { start: 0, end: 0 }; RANGES_PER_ROW],
            len: 0,
        }
    }

    /// The row, 0 at the top.
    pub fn y(&self) -> u32 {
        self.y
    }

    /// The damaged column ranges `[start, end)`, sorted, disjoint, not touching.
    pub fn ranges(&self) -> &[Span] {
        self.spans.get(..self.len).unwrap_or(&[])
    }

    /// The number of damaged pixels of the row.
    pub fn pixels(&self) -> u32 {
        self.ranges().iter().map(|s| s.end - s.start).sum()
    }

    /// Whether column `x` is damaged.
    pub fn contains(&self, x: u32) -> bool {
        self.ranges().iter().any(|s| s.start <= x && x < s.end)
    }

    /// Adds the columns `[start, end)` (nothing if empty).
    pub(super) fn add(&mut self, start: u32, end: u32) {
        if start >= end {
            return;
        }
        let mut new = Span { start, end };
        // Take out every range the new one overlaps or touches, joining them into it.
        let mut kept = 0;
        for i in 0..self.len {
            let Some(&s) = self.spans.get(i) else {
                break;
            };
            if s.start <= new.end && new.start <= s.end {
                new = Span {
                    start: new.start.min(s.start),
                    end: new.end.max(s.end),
                };
            } else {
                if let Some(slot) = self.spans.get_mut(kept) {
                    *slot = s;
                }
                kept += 1;
            }
        }
        self.len = kept;
        if self.len == RANGES_PER_ROW {
            self.join_closest();
        }
        // Insert in order.
        let at = self
            .ranges()
            .iter()
            .take_while(|s| s.end < new.start)
            .count();
        let mut carry = new;
        for i in at..=self.len {
            if let Some(slot) = self.spans.get_mut(i) {
                core::mem::swap(slot, &mut carry);
            }
        }
        self.len = (self.len + 1).min(RANGES_PER_ROW);
    }

    /// Joins the two neighbours with the smallest gap, freeing a slot.
    fn join_closest(&mut self) {
        let mut best: Option<(u32, usize)> = None;
        for (i, pair) in self.ranges().windows(2).enumerate() {
            if let [a, b] = pair {
                let gap = b.start - a.end;
                if best.is_none_or(|(g, _)| gap < g) {
                    best = Some((gap, i));
                }
            }
        }
        let Some((_, i)) = best else {
            return;
        };
        if let Some([a, b]) = self.spans.get_mut(i..i + 2) {
            a.end = b.end;
        }
        for j in i + 1..self.len.saturating_sub(1) {
            if let Some([a, b]) = self.spans.get_mut(j..j + 2) {
                *a = *b;
            }
        }
        self.len -= 1;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ranges(row: &DamageRow) -> heapless::Vec<(u32, u32), 8> {
        row.ranges().iter().map(|s| (s.start, s.end)).collect()
    }

    #[test]
    fn damage_ranges_join_overlapping_and_touching() {
        let mut row = DamageRow::new(0);
        row.add(10, 20);
        row.add(0, 5);
        row.add(30, 40);
        assert_eq!(ranges(&row), [(0, 5), (10, 20), (30, 40)]);
        row.add(5, 10);
        assert_eq!(ranges(&row), [(0, 20), (30, 40)]);
        row.add(15, 35);
        assert_eq!(ranges(&row), [(0, 40)]);
        row.add(3, 3);
        assert_eq!(ranges(&row), [(0, 40)]);
        assert_eq!(row.pixels(), 40);
    }

    #[test]
    fn damage_ranges_join_the_closest_when_full() {
        let mut row = DamageRow::new(0);
        for (s, e) in [(0, 2), (10, 12), (13, 15), (30, 32)] {
            row.add(s, e);
        }
        assert_eq!(ranges(&row), [(0, 2), (10, 12), (13, 15), (30, 32)]);
        row.add(50, 51);
        assert_eq!(ranges(&row), [(0, 2), (10, 15), (30, 32), (50, 51)]);
        // Every column ever added is still inside.
        for x in [0, 1, 10, 11, 13, 14, 30, 31, 50] {
            assert!(row.contains(x), "{x}");
        }
        row.add(40, 41);
        assert_eq!(row.ranges().len(), RANGES_PER_ROW);
        for x in [0, 1, 10, 14, 30, 31, 40, 50] {
            assert!(row.contains(x), "{x}");
        }
    }
}
