//! Two exported functions for `.ci/no-float-check` to disassemble on `thumbv6m-none-eabi`:
//!
//! - `shadeline_fixed_row`: one row of a fixed-path frame into RGB565 — the function that
//!   must reach no soft-float routine;
//! - `shadeline_float_probe`: deliberately multiplies and adds `f32` through a helper, so the
//!   check can show that it does find soft-float calls, one call deep.
#![no_std]
#![no_main]

use core::panic::PanicInfo;
use shadeline::{PreparedFixed, Render, Rgb565};

/// Renders row `y` of a prepared fixed-path frame into `out`; `false` on a bad request.
#[no_mangle]
pub fn shadeline_fixed_row(frame: &PreparedFixed, y: u32, out: &mut [Rgb565]) -> bool {
    frame.render_line(y, out).is_ok()
}

/// Uses `f32` on purpose: the check must fail on this root.
#[no_mangle]
pub fn shadeline_float_probe(a: f32, b: f32) -> f32 {
    scaled(a, b) + 1.0
}

#[inline(never)]
fn scaled(a: f32, b: f32) -> f32 {
    a * b
}

#[panic_handler]
fn panic(_: &PanicInfo) -> ! {
    loop {}
}
