//! shadeline on RV32IMAC (QEMU `virt`, no FPU): the exponent series at 320×240 into a full
//! RGB565 framebuffer, on the scalar `f32` path (every float operation in software, which
//! must still give the host's bits: IEEE single precision with the same operations) and the
//! fixed-point path. Reported over semihosting with CRC, instruction count (`minstret`) and
//! stack high-water mark; exits 0 only if both CRCs match. With the feature `area-lights`
//! it also renders the area-lights preset at 320×160 on the fixed path, under its sphere
//! light and under a point light at the same place (`fixed-sphere-light`,
//! `fixed-point-light`); with the feature `matrix`, the scene matrix at 320×240 on the fixed
//! path (`fixed-floor`, `fixed-lamp`, `fixed-three-lights`).
//!
//! Run with `cargo rv32` from `firmware/` (the alias and the QEMU runner are in
//! `.cargo/config.toml`).

#![no_std]
#![no_main]

mod board;

use board::{exit, Minstret, Rv32Board};
use common::expected::{
    FIXED_COVERED, FIXED_RGB565_CRC32, HEIGHT, SCALAR_COVERED, SCALAR_RGB565_CRC32, WIDTH,
};
use common::{Expected, Outcome, Session, Sink};
use riscv_rt::entry;
use shadeline::{exponent_series, Prepared, PreparedFixed, Rgb565, Scalar, Scene};

const PIXELS: usize = (WIDTH * HEIGHT) as usize;

/// The framebuffer both paths render into, in `.bss`.
struct Buffers {
    frame: [Rgb565; PIXELS],
}

#[entry]
fn main() -> ! {
    let buffers = take_buffers();
    let Some(mut session) = Session::new(Rv32Board::new(), Minstret) else {
        exit(false)
    };
    let frame = &mut buffers.frame;
    // The scene and both prepared frames: slots on `main`'s stack (this board's stack has
    // 64 KiB), each built in place by `Session::build` and never moved.
    let mut scene_slot: Option<Scene> = None;
    let mut scalar_slot: Option<Prepared<Scalar>> = None;
    let mut fixed_slot = PreparedFixed::EMPTY;
    let (Some(scene), _) = session.build(&mut scene_slot, exponent_series) else {
        session.note("shadeline-fw error=scene\n");
        exit(false)
    };
    match session.build(&mut scalar_slot, || {
        Prepared::<Scalar>::new(scene, WIDTH, HEIGHT)
    }) {
        (Some(path), prepare) => session.run(
            "scalar",
            path,
            Sink::Frame(frame),
            prepare,
            Expected {
                crc: SCALAR_RGB565_CRC32,
                covered: SCALAR_COVERED,
            },
        ),
        (None, _) => {
            session.note("shadeline-fw error=prepare-scalar\n");
            session.fail();
        }
    }
    match session.build_in(&mut fixed_slot, |f| f.prepare(scene, WIDTH, HEIGHT)) {
        (Some(path), prepare) => session.run(
            "fixed",
            path,
            Sink::Frame(frame),
            prepare,
            Expected {
                crc: FIXED_RGB565_CRC32,
                covered: FIXED_COVERED,
            },
        ),
        (None, _) => {
            session.note("shadeline-fw error=prepare-fixed\n");
            session.fail();
        }
    }
    #[cfg(feature = "area-lights")]
    {
        let (mut scene, mut fixed) = (None, PreparedFixed::<5, 1>::EMPTY);
        session.fixed_area_lights(&mut scene, &mut fixed, &mut frame[..], false);
    }
    #[cfg(feature = "matrix")]
    {
        let (mut scene, mut fixed) = (None, common::MatrixFixed::EMPTY);
        session.fixed_matrix(&mut scene, &mut fixed, &mut frame[..], false);
    }
    exit(session.finish() == Outcome::Pass)
}

/// The buffers, zeroed with `.bss`. (`riscv::singleton!` would build the 150 KiB value on
/// the stack first and overflow it; riscv-rt's `entry` has no `static mut` conversion.)
static mut BUFFERS: Buffers = Buffers {
    frame: [Rgb565(0); PIXELS],
};

/// The buffers as the one `&'static mut` the program ever makes of them.
fn take_buffers() -> &'static mut Buffers {
    // SAFETY: called once, from `main`, before anything else could reference BUFFERS; single
    // hart, no interrupts.
    unsafe { &mut *core::ptr::addr_of_mut!(BUFFERS) }
}
