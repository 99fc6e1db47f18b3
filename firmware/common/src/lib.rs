//! What every shadeline firmware demo shares, so that the three programs differ only in
//! their board: how to print, how to count instructions, where the stack is.
//!
//! | module | holds |
//! |---|---|
//! | [`crc32`] | CRC32/IEEE over RGB565 pixels, row by row or over a whole frame |
//! | [`text`] | a fixed-size line with hand-written integer formatting (no `core::fmt`) |
//! | [`stack`] | painting the free stack and finding the deepest word the render touched |
//! | [`meter`] | instruction counting with the counter's own cost calibrated out |
//! | [`run`] | one path end to end: build in place, prepare and render measured, CRC, report |
//! | `animation` | an orbiting light and a bouncing sphere, in full and as damage (feature `animation`) |
//! | [`matrix`] | the scene matrix (`floor`, `lamp`, `three-lights`) on the fixed and scalar paths |
//! | `cortex_m_board` | SysTick counter, semihosting, stack limits (Cortex-M targets only) |
//! | [`expected`] | the frame size and the CRCs to match (`firmware/expected.rs`) |
//!
//! Nothing here uses `core::fmt` or can panic: every release firmware links a panic handler
//! that calls an undefined symbol ([`panic_proof`]), so the link itself proves it.

#![no_std]

#[cfg(feature = "animation")]
pub mod animation;
#[cfg(target_arch = "arm")]
pub mod cortex_m_board;
pub mod crc32;
pub mod kernel;
pub mod matrix;
pub mod meter;
mod panic_proof;
pub mod run;
pub mod stack;
pub mod text;

/// The frame size and expected CRCs, shared with the host test `tests/firmware_crcs.rs`.
pub mod expected {
    include!("../../expected.rs");
}

pub use matrix::{MatrixFixed, MatrixPrepared, MATRIX_LIGHTS, MATRIX_SPHERES};
pub use meter::{InstructionCounter, Meter};
pub use run::{Board, Expected, Outcome, Session, Sink};
