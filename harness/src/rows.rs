//! Rendering a frame's rows on several threads.
//!
//! The frame is cut into blocks of [`BLOCK_ROWS`] whole rows, and the blocks are dealt
//! round-robin to the threads (thread `t` gets blocks `t`, `t + N`, `t + 2N`, …). Each thread
//! writes only into the blocks it was dealt, which are disjoint `&mut` slices of the one
//! framebuffer, so no locking and no copying is needed. Interleaving small blocks balances
//! the load: the spheres usually sit in the middle rows, which contiguous bands would hand
//! to one or two threads. Since every row is a pure function of its index, the output does not
//! depend on the number of threads.

use crate::progress::ROWS_SHADED;
use shadeline::RenderError;
use std::fmt;
use std::sync::atomic::Ordering;
use std::thread;

/// A frame buffer that could not be allocated: the frame's size, and the bytes it needed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TooLarge {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// The bytes asked for.
    pub bytes: u128,
}

impl fmt::Display for TooLarge {
    /// `cannot allocate the memory for a 65535x65535 frame: it needs 12.9 GB (… bytes); …`
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "cannot allocate the memory for a {}x{} frame: it needs {:.1} GB ({} bytes); \
             choose a smaller --width/--height",
            self.width,
            self.height,
            self.bytes as f64 / 1e9,
            self.bytes
        )
    }
}

impl std::error::Error for TooLarge {}

/// Why a frame could not be rendered into a new buffer.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FrameError {
    /// The renderer refused (a bad size, say).
    Render(RenderError),
    /// The buffer could not be allocated.
    TooLarge(TooLarge),
}

impl From<RenderError> for FrameError {
    fn from(e: RenderError) -> Self {
        FrameError::Render(e)
    }
}

impl From<TooLarge> for FrameError {
    fn from(e: TooLarge) -> Self {
        FrameError::TooLarge(e)
    }
}

impl fmt::Display for FrameError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            FrameError::Render(e) => e.fmt(f),
            FrameError::TooLarge(e) => e.fmt(f),
        }
    }
}

impl std::error::Error for FrameError {}

/// Reserves `bytes_per_pixel × width × height` bytes and gives them back: whether buffers of
/// that total size can be allocated now (a command that needs several checks them all at once
/// before its long part).
pub fn check_memory(width: u32, height: u32, bytes_per_pixel: usize) -> Result<(), TooLarge> {
    let pixels = u128::from(width) * u128::from(height);
    let too_large = TooLarge {
        width,
        height,
        bytes: pixels * bytes_per_pixel as u128,
    };
    let bytes = usize::try_from(too_large.bytes).map_err(|_| too_large)?;
    Vec::<u8>::new()
        .try_reserve_exact(bytes)
        .map_err(|_| too_large)
}

/// A new `width × height` frame of default pixels, row-major, allocated fallibly: a frame too
/// large for the memory is an error naming its size, not an abort.
pub fn new_frame<T: Clone + Default>(width: u32, height: u32) -> Result<Vec<T>, TooLarge> {
    let pixels = u128::from(width) * u128::from(height);
    let too_large = TooLarge {
        width,
        height,
        bytes: pixels * std::mem::size_of::<T>() as u128,
    };
    let n = usize::try_from(pixels).map_err(|_| too_large)?;
    let mut frame = Vec::new();
    frame.try_reserve_exact(n).map_err(|_| too_large)?;
    frame.resize(n, T::default());
    Ok(frame)
}

/// Rows per block dealt to a thread.
pub const BLOCK_ROWS: usize = 8;

/// The number of threads to use when none is asked for: what the OS says is available.
pub fn default_threads() -> usize {
    thread::available_parallelism().map_or(1, |n| n.get())
}

/// Renders a `width × height` frame, row-major, on `threads` scoped threads (at least one),
/// into a new buffer ([`new_frame`]: a frame too large for the memory is an error).
///
/// `shade_row(y, row)` fills row `y`; its first error, if any, is returned.
pub fn render_rows<T, F>(
    width: u32,
    height: u32,
    threads: usize,
    shade_row: F,
) -> Result<Vec<T>, FrameError>
where
    T: Copy + Default + Send,
    F: Fn(u32, &mut [T]) -> Result<(), RenderError> + Sync,
{
    if width == 0 || height == 0 {
        return Err(RenderError::BadSize { width, height }.into());
    }
    let mut frame = new_frame(width, height)?;
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
                            ROWS_SHADED.fetch_add(1, Ordering::Relaxed);
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
        assert_eq!(
            result,
            Err(FrameError::Render(RenderError::RowOutOfRange {
                y: 33,
                height: 0
            }))
        );
    }

    #[test]
    fn a_frame_too_large_for_the_address_space_is_an_error_naming_its_size() {
        // About 1.5e20 bytes: more than any address space, so this fails on every machine
        // without touching memory.
        let e = new_frame::<u64>(u32::MAX, u32::MAX).unwrap_err();
        let pixels = u128::from(u32::MAX) * u128::from(u32::MAX);
        assert_eq!(
            e,
            TooLarge {
                width: u32::MAX,
                height: u32::MAX,
                bytes: pixels * 8
            }
        );
        let message = e.to_string();
        assert!(message.contains("4294967295x4294967295 frame"), "{message}");
        assert!(check_memory(u32::MAX, u32::MAX, 1 << 20).is_err());
        assert_eq!(new_frame::<u16>(3, 2), Ok(vec![0; 6]));
        assert_eq!(check_memory(3, 2, 8), Ok(()));
    }
}
