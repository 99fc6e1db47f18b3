//! The probe of `.ci/no-alloc-check`: a `no_std` binary for `thumbv6m-none-eabi` that links
//! shadeline like its sibling and also fills a `Vec` through a global allocator. The check
//! runs its allocator-symbol search on this binary too, and fails unless it finds them here:
//! a search that cannot see an allocation proves nothing about the real binary.
//!
//! It is a binary of its own (not a feature of the real one) so that building it compiles
//! only this file: the real binary and its every-path monomorphizations are built once.
#![no_std]
#![no_main]

extern crate alloc;

use core::panic::PanicInfo;
use shadeline::{exponent_series_with_capacity, PreparedFixed};

/// Prepares the exponent series for the fixed path, so shadeline is in the link.
#[no_mangle]
pub fn shadeline_probe_prepare(w: u32, h: u32, out: &mut Option<PreparedFixed<16, 4>>) {
    *out = exponent_series_with_capacity::<16, 4>()
        .ok()
        .and_then(|s| PreparedFixed::new(&s, w, h).ok());
}

/// Allocates on purpose: the check must find the allocator in this binary.
#[no_mangle]
pub fn shadeline_alloc_probe(n: u32) -> u32 {
    let v = alloc::vec![n; n as usize];
    core::hint::black_box(&v).iter().sum()
}

/// A global allocator that never gives memory (the probe only needs to link).
struct NoMemory;

// SAFETY: `alloc` returns null, which `GlobalAlloc` allows (allocation failure), and
// `dealloc` is never given a pointer this allocator handed out, because it hands out none.
unsafe impl core::alloc::GlobalAlloc for NoMemory {
    unsafe fn alloc(&self, _: core::alloc::Layout) -> *mut u8 {
        core::ptr::null_mut()
    }
    unsafe fn dealloc(&self, _: *mut u8, _: core::alloc::Layout) {}
}

#[global_allocator]
static ALLOCATOR: NoMemory = NoMemory;

#[panic_handler]
fn panic(_: &PanicInfo) -> ! {
    loop {}
}
