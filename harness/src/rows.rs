//! Rendering a frame's rows on several threads.
//!
//! The frame is cut into blocks of [`BLOCK_ROWS`] whole rows, and the blocks are dealt
//! round-robin to the threads (thread `t` gets blocks `t`, `t + N`, `t + 2N`, …). Each thread
//! writes only into the blocks it was dealt, which are disjoint `&mut` slices of the one
//! framebuffer, so no locking and no copying is needed. Interleaving small blocks balances
//! the load: the spheres usually sit in the middle rows, which contiguous bands would hand
//! to one or two threads. Since every row is a pure function of its index, the output does not
//! depend on the number of threads.

use shadeline::RenderError;
use std::thread;

/// Rows per block dealt to a thread.
pub const BLOCK_ROWS: usize = 8;

/// The number of threads to use when none is asked for: what the OS says is available.
pub fn default_threads() -> usize {
    thread::available_parallelism().map_or(1, |n| n.get())
}

/// Renders a `width × height` frame, row-major, on `threads` scoped threads (at least one),
/// into a new buffer.
///
/// `shade_row(y, row)` fills row `y`; its first error, if any, is returned.
pub fn render_rows<T, F>(
    width: u32,
    height: u32,
    threads: usize,
    shade_row: F,
) -> Result<Vec<T>, RenderError>
where
    T: Copy + Default + Send,
    F: Fn(u32, &mut [T]) -> Result<(), RenderError> + Sync,
{
    let w = width as usize;
    let h = height as usize;
    if w == 0 || h == 0 {
        return Err(RenderError::BadSize { width, height });
    }
    let mut frame = vec![T::default(); w * h];
    render_rows_into(&mut frame, width, threads, shade_row)?;
    Ok(frame)
}

/// Renders every row of `frame` (row-major, `width` pixels per row) on `threads` scoped
/// threads (at least one), into the caller's buffer.
///
/// `shade_row(y, row)` fills row `y`; its first error, if any, is returned.
pub fn render_rows_into<T, F>(
    frame: &mut [T],
    width: u32,
    threads: usize,
    shade_row: F,
) -> Result<(), RenderError>
where
    T: Send,
    F: Fn(u32, &mut [T]) -> Result<(), RenderError> + Sync,
{
    let w = width as usize;
    if w == 0 || !frame.len().is_multiple_of(w) {
        return Err(RenderError::FrameLength {
            expected: frame.len().div_ceil(w.max(1)) * w,
            got: frame.len(),
        });
    }
    let threads = threads.max(1);
    // Each thread's list of blocks has its final size from the start: the allocations here
    // are one list per thread whatever the height (tests/rows_alloc.rs counts them).
    let blocks = frame.len().div_ceil(w * BLOCK_ROWS);
    let mut dealt: Vec<Vec<(usize, &mut [T])>> = (0..threads)
        .map(|_| Vec::with_capacity(blocks.div_ceil(threads)))
        .collect();
    for (block, rows) in frame.chunks_mut(w * BLOCK_ROWS).enumerate() {
        dealt[block % threads].push((block * BLOCK_ROWS, rows));
    }
    let shade_row = &shade_row;
    thread::scope(|scope| {
        let workers: Vec<_> = dealt
            .into_iter()
            .filter(|blocks| !blocks.is_empty())
            .map(|blocks| {
                scope.spawn(move || {
                    for (first_row, rows) in blocks {
                        for (i, row) in rows.chunks_exact_mut(w).enumerate() {
                            shade_row((first_row + i) as u32, row)?;
                        }
                    }
                    Ok(())
                })
            })
            .collect();
        workers.into_iter().try_for_each(|worker| {
            worker
                .join()
                .unwrap_or_else(|panic| std::panic::resume_unwind(panic))
        })
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_row_is_rendered_once_at_its_index_on_any_thread_count() {
        for threads in [1, 2, 3, 7, 50] {
            let frame = render_rows(5, 21, threads, |y, row: &mut [u32]| {
                for (x, px) in row.iter_mut().enumerate() {
                    *px += y * 100 + x as u32 + 1;
                }
                Ok(())
            })
            .unwrap();
            for (i, px) in frame.iter().enumerate() {
                assert_eq!(*px as usize, (i / 5) * 100 + i % 5 + 1, "{threads} threads");
            }
        }
    }

    #[test]
    fn a_row_error_is_returned() {
        let result = render_rows(4, 40, 3, |y, _row: &mut [u8]| {
            if y == 33 {
                Err(RenderError::RowOutOfRange { y, height: 0 })
            } else {
                Ok(())
            }
        });
        assert_eq!(result, Err(RenderError::RowOutOfRange { y: 33, height: 0 }));
    }
}
