//! Rendering a frame on threads allocates a fixed number of times, whatever its height: the
//! harness's row threading (`shadeline_harness::rows`) allocates per thread (its list of
//! blocks, the thread itself), never per row or per block, and the rows it renders (the
//! core, which has no allocator at all: `.ci/no-alloc-check`) allocate nothing.
//!
//! A counting global allocator sees every thread, so this file runs without the libtest
//! harness (`harness = false` in `Cargo.toml`): libtest's own thread allocates while it waits
//! for a test, at a moment that depends on the machine's load, and its allocations would be
//! counted with the frame's. Here `main` is the only other thread, and it waits in the
//! scoped-thread join, which allocates nothing.

use shadeline::{exponent_series, Prepared, Render, Rgb888, Simd8};
use shadeline_harness::rows::{render_rows_into, BLOCK_ROWS};
use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering};

struct Counting;

static ALLOCATIONS: AtomicUsize = AtomicUsize::new(0);

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        ALLOCATIONS.fetch_add(1, Ordering::SeqCst);
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        ALLOCATIONS.fetch_add(1, Ordering::SeqCst);
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

fn count<F: FnOnce()>(f: F) -> usize {
    let before = ALLOCATIONS.load(Ordering::SeqCst);
    f();
    ALLOCATIONS.load(Ordering::SeqCst) - before
}

/// Allocations of rendering an exponent-series frame `320 × height` into a buffer made
/// before counting, on `threads` threads.
fn frame_allocations(height: u32, threads: usize) -> usize {
    let scene = exponent_series().unwrap();
    let frame = Prepared::<Simd8>::new(&scene, 320, height).unwrap();
    let mut pixels = vec![Rgb888::default(); 320 * height as usize];
    let n = count(|| {
        render_rows_into(&mut pixels, 320, threads, |y, row| {
            frame.render_line(y, row)
        })
        .unwrap();
    });
    // The frame was really rendered: not all background.
    assert!(pixels.iter().any(|p| *p != pixels[0]), "{height} rows");
    n
}

fn main() {
    println!("threaded rendering allocates per thread, not per row");
    // The counter works: a Vec allocates once, and growing it reallocates.
    assert_eq!(count(|| drop(std::hint::black_box(vec![1u8; 16]))), 1);
    for threads in [1, 2, 3, 8] {
        // Enough rows that every thread gets at least one block.
        let short = (threads * BLOCK_ROWS) as u32;
        let (a, b) = (
            frame_allocations(short, threads),
            frame_allocations(2400, threads),
        );
        println!("{threads} thread(s): {a} allocations for {short} rows, {b} for 2400 rows");
        assert_eq!(a, b, "{threads} threads: allocations grow with the height");
        assert!(b <= 4 + 16 * threads, "{threads} threads: {b} allocations");
    }
}
