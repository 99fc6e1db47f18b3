//! shadeline on a Cortex-M4F (QEMU `mps2-an386`): the exponent series at 320×240 into a full
//! RGB565 framebuffer in RAM (150 KiB of the board's 4 MiB), on the scalar `f32` path (hard
//! float) and the fixed-point path, each reported with its CRC, instruction count and stack
//! high-water mark over semihosting. Exits 0 only if every CRC matches.
//!
//! Run with `cargo m4f` from `firmware/` (the alias and the QEMU runner are in
//! `.cargo/config.toml`).

#![no_std]
#![no_main]

use common::cortex_m_board::{exit, CortexMBoard, SysTickCounter};
use common::expected::{FIXED_RGB565_CRC32, HEIGHT, SCALAR_RGB565_CRC32, WIDTH};
use common::{Outcome, Session, Sink};
use cortex_m_rt::entry;
use shadeline::{exponent_series, HitRecord, Prepared, PreparedFixed, Rgb565, Scalar};

/// mps2-an386's processor clock, which clocks SysTick: 25 MHz.
const SYSCLK_HZ: u32 = 25_000_000;

const PIXELS: usize = (WIDTH * HEIGHT) as usize;

#[entry]
fn main() -> ! {
    // cortex-m-rt turns this into a `&'static mut` owned by `main`: one framebuffer, no
    // unsafe, zeroed with .bss.
    static mut FRAME: [Rgb565; PIXELS] = [Rgb565(0); PIXELS];

    let board = CortexMBoard::new("m4f");
    let Some(peripherals) = cortex_m::Peripherals::take() else {
        exit(false)
    };
    let counter = SysTickCounter::new(peripherals.SYST, SYSCLK_HZ);
    let Some(mut session) = Session::new(board, counter) else {
        exit(false)
    };
    let mut hits = [HitRecord::default(); WIDTH as usize];

    let Ok(scene) = exponent_series() else {
        session.note("shadeline-fw error=scene\n");
        exit(false)
    };
    match Prepared::<Scalar>::new(&scene, WIDTH, HEIGHT) {
        Ok(path) => session.run(
            "scalar",
            &path,
            Sink::Frame(FRAME),
            &mut hits,
            SCALAR_RGB565_CRC32,
        ),
        Err(_) => {
            session.note("shadeline-fw error=prepare-scalar\n");
            session.fail();
        }
    }
    match PreparedFixed::new(&scene, WIDTH, HEIGHT) {
        Ok(path) => session.run(
            "fixed",
            &path,
            Sink::Frame(FRAME),
            &mut hits,
            FIXED_RGB565_CRC32,
        ),
        Err(_) => {
            session.note("shadeline-fw error=prepare-fixed\n");
            session.fail();
        }
    }
    exit(session.finish() == Outcome::Pass)
}
