//! Rendering allocates nothing: a counting global allocator watches a whole frame on every
//! path and pixel format. It counts per thread, so the test harness's own threads cannot
//! disturb the count.

use shadeline::*;
use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;

struct Counting;

thread_local! {
    // A const-initialized Cell needs no allocation and no destructor, so the allocator may
    // touch it.
    static ALLOCATIONS: Cell<usize> = const { Cell::new(0) };
}

fn record() {
    let _ = ALLOCATIONS.try_with(|n| n.set(n.get() + 1));
}

fn allocations() -> usize {
    ALLOCATIONS.with(Cell::get)
}

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        record();
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        record();
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

fn count<F: FnOnce()>(f: F) -> usize {
    let before = allocations();
    f();
    allocations() - before
}

fn frame_allocations<W: FloatPath>(
    scene: &Scene,
    rgb: &mut [Rgb888],
    rgb565: &mut [Rgb565],
    lin: &mut [LinearRgb],
) -> usize {
    count(|| {
        let frame = Prepared::<W>::new(scene, 320, 240).unwrap();
        frame.render_frame(rgb).unwrap();
        frame.render_frame(rgb565).unwrap();
        frame.render_frame(lin).unwrap();
        let mut line = [HitRecord::default(); 320];
        frame.render_line(120, &mut line).unwrap();
    })
}

#[test]
fn rendering_a_frame_allocates_nothing() {
    // Buffers and scene are made before counting starts.
    let scene = exponent_series().unwrap();
    let mut rgb = vec![Rgb888::default(); 320 * 240];
    let mut rgb565 = vec![Rgb565::default(); 320 * 240];
    let mut lin = vec![LinearRgb::default(); 320 * 240];
    // The counter works: a Vec allocates.
    assert_eq!(count(|| drop(std::hint::black_box(vec![1u8; 16]))), 1);
    assert_eq!(
        frame_allocations::<Scalar>(&scene, &mut rgb, &mut rgb565, &mut lin),
        0
    );
    assert_eq!(
        frame_allocations::<Simd4>(&scene, &mut rgb, &mut rgb565, &mut lin),
        0
    );
    assert_eq!(
        frame_allocations::<Simd8>(&scene, &mut rgb, &mut rgb565, &mut lin),
        0
    );
    // And the frame was really rendered.
    assert!(rgb.iter().any(|p| *p != rgb[0]));
}
