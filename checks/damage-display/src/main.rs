//! A sphere bouncing on a 320×240 ST7789 panel, sent damage only: after the first frame,
//! each frame sends the panel only the pixels that can differ from the one it shows
//! ([`shadeline_damage_display::send_damage`]), range by range through mipidsi's
//! `set_pixels`. Frames are prepared on the fixed path (no FPU on the M0+; the same integers
//! on the M4F), two at a time: the one shown and the next. No framebuffer: one row's buffer.
//!
//! The board is the target's: a Raspberry Pi Pico (RP2040) for thumbv6m-none-eabi, an
//! STM32F411 "Black Pill" for thumbv7em-none-eabihf; each sets up its SPI bus, pins and
//! panel in its own module and calls [`animate`]. Compile-checked by
//! `.ci/damage-display-check` (built, not run).
#![no_std]
#![no_main]
#![deny(unsafe_code)]

use embedded_graphics_core::pixelcolor::Rgb565;
use embedded_hal::digital::OutputPin;
use mipidsi::interface::{Interface, InterfacePixelFormat};
use mipidsi::models::Model;
use mipidsi::Display;
use panic_halt as _;
use shadeline::damage::Damage;
use shadeline::{exponent_series_with_capacity, PreparedFixed, Scene};
use shadeline_damage_display::{bounce, send, send_damage};

#[cfg_attr(target_abi = "eabihf", path = "stm32f411.rs")]
#[cfg_attr(not(target_abi = "eabihf"), path = "rp2040.rs")]
mod board;

/// The panel in landscape.
const WIDTH: u32 = 320;
const HEIGHT: u32 = 240;

/// The exponent series' 5 spheres and 1 light: a prepared frame of these capacities takes
/// 1,928 bytes, and the example holds two.
type Frame = PreparedFixed<5, 1>;

/// The sphere that bounces (the middle one of the series) and how high, in scene units.
const BOUNCING: usize = 2;
const HEIGHT_UNITS: f32 = 1.5;

/// Draws the first frame whole, then bounces the sphere for ever, sending each frame's
/// damage alone. A scene, frame or panel error stops it (panic-halt).
fn animate<DI, M, RST>(display: &mut Display<DI, M, RST>) -> !
where
    DI: Interface,
    DI::Error: core::fmt::Debug,
    M: Model<ColorFormat = Rgb565>,
    Rgb565: InterfacePixelFormat<DI::Word>,
    RST: OutputPin,
{
    let scene: Scene<5, 1> = exponent_series_with_capacity().unwrap();
    let mut buffer = [shadeline::Rgb565::default(); WIDTH as usize];
    let mut shown = bounce(&scene, BOUNCING, HEIGHT_UNITS, 0).unwrap();
    let mut shown_frame = Frame::new(&shown, WIDTH, HEIGHT).unwrap();
    let first: Damage = Damage::full(&shown, WIDTH, HEIGHT);
    send(display, &first, &shown_frame, &mut buffer).unwrap();
    for k in 1.. {
        let next = bounce(&scene, BOUNCING, HEIGHT_UNITS, k).unwrap();
        let next_frame = Frame::new(&next, WIDTH, HEIGHT).unwrap();
        send_damage(
            display,
            (&shown, &shown_frame),
            (&next, &next_frame),
            &mut buffer,
        )
        .unwrap();
        (shown, shown_frame) = (next, next_frame);
    }
    unreachable!("the frames run for ever")
}
