//! shadeline on a Cortex-M0 (QEMU `microbit`, nRF51: 16 KiB RAM, no FPU): the exponent series
//! at 320×240 on the fixed-point path, streamed row by row through one 320-pixel line buffer
//! (a 150 KiB framebuffer could never fit), with the CRC fed from each finished row. Reported
//! over semihosting with the instruction count and stack high-water mark; exits 0 only if
//! the CRC matches.
//!
//! What has to fit in the 16 KiB: the scene, the prepared frame and the 640-byte line buffer
//! (all three `static`: each is built in place and never moved), and the stack of the
//! deepest stage — building the scene, preparing the frame or rendering a row. It does not
//! count covered pixels itself (that would link a second row loop, into hit records, that no
//! user's firmware has): its `covered=` is the host's count from `expected.rs`. The report's `peak_stack` plus `llvm-size`'s
//! `.data + .bss` is the RAM it needs. With the feature `antialias` it also renders the
//! frame with the fixed path's analytic anti-aliasing (`fixed-aa`), in the same buffers;
//! with `microfacets`, the microfacet gallery (`fixed-microfacets`) and a frame of each
//! reflection model alone (`shadeline::covered_sphere` of each of `shadeline::model_samples`:
//! `fixed-phong`, `fixed-nbp`, … `fixed-ggx-gold`), the M4F's fixed-path runs of that
//! feature, through the same line buffer: the gallery in the same scene and prepared frame,
//! which then take its capacities, each model's frame in its own;
//! with `area-lights`, the area-lights preset at 320×160 under its sphere light and under a
//! point light at the same place (`fixed-sphere-light`, `fixed-point-light`), in the same
//! buffers too (the preset's capacities are the exponent series'); with `matrix`, the scene
//! matrix at 320×240 (`fixed-floor`, `fixed-lamp`, `fixed-three-lights`), in the same
//! buffers, which then take the matrix's capacities; with `animation`, an orbiting light and
//! a bouncing sphere over the floor scene, in full and as damage (`anim-orbit`,
//! `anim-bounce`), through the same line buffer.
//!
//! Run with `cargo m0` from `firmware/` (the alias and the QEMU runner are in
//! `.cargo/config.toml`).

#![no_std]
#![no_main]

use common::cortex_m_board::{exit, CortexMBoard, SysTickCounter};
use common::expected::HEIGHT;
use common::expected::{FIXED_COVERED, FIXED_RGB565_CRC32, WIDTH};
use common::{Expected, Outcome, Session, Sink};
use cortex_m_rt::entry;
use shadeline::{exponent_series_with_capacity, PreparedFixed, Rgb565, Scene};

/// The nRF51's processor clock as QEMU models it, which clocks SysTick: 16 MHz.
const HCLK_HZ: u32 = 16_000_000;

/// The scene's capacities: the exponent series' 5 spheres and 1 light, rather than the
/// default 16 and 8, so the scene and its prepared frame take a third of the RAM.
#[cfg(not(any(feature = "matrix", feature = "microfacets")))]
const SPHERES: usize = 5;
#[cfg(not(any(feature = "matrix", feature = "microfacets")))]
const LIGHTS: usize = 1;
/// With the feature `matrix`, the scene matrix's 6 spheres and 3 lights: the exponent series
/// and the matrix share the scene, the prepared frame and one copy of the renderer, as a
/// user's firmware drawing the matrix's scenes would.
#[cfg(feature = "matrix")]
const SPHERES: usize = common::MATRIX_SPHERES;
#[cfg(feature = "matrix")]
const LIGHTS: usize = common::MATRIX_LIGHTS;
/// With the feature `microfacets` (and not `matrix`), the microfacet gallery's 16 spheres and
/// 2 lights: the exponent series and the gallery share the scene and the prepared frame,
/// which the 16 KiB of RAM holds only once next to the stack of the full-width kernel.
#[cfg(all(feature = "microfacets", not(feature = "matrix")))]
const SPHERES: usize = 16;
#[cfg(all(feature = "microfacets", not(feature = "matrix")))]
const LIGHTS: usize = 2;

/// The per-model runs of the feature `microfacets`, in the order of
/// `shadeline::model_samples`: their names (the M4F's fixed-path names) and expected CRCs.
#[cfg(feature = "microfacets")]
const MODEL_RUNS: [(&str, u32); 5] = {
    let crc = common::expected::MODEL_RGB565_CRC32;
    [
        ("fixed-phong", crc[0][1]),
        ("fixed-nbp", crc[1][1]),
        ("fixed-oren-nayar", crc[2][1]),
        ("fixed-ggx", crc[3][1]),
        ("fixed-ggx-gold", crc[4][1]),
    ]
};

// `#[entry]` passes each `static mut` below to the real entry function as an argument.
#[allow(clippy::too_many_arguments)]
#[entry]
fn main() -> ! {
    // cortex-m-rt turns these into `&'static mut`s owned by `main`: statics, no unsafe.
    static mut LINE: [Rgb565; WIDTH as usize] = [Rgb565(0); WIDTH as usize];
    static mut SCENE: Option<Scene<SPHERES, LIGHTS>> = None;
    static mut FIXED: PreparedFixed<SPHERES, LIGHTS> = PreparedFixed::EMPTY;
    // The microfacet gallery's own capacities, when the matrix's are the scene's.
    #[cfg(all(feature = "microfacets", feature = "matrix"))]
    static mut MICRO_SCENE: Option<Scene<16, 2>> = None;
    #[cfg(all(feature = "microfacets", feature = "matrix"))]
    static mut MICRO_FIXED: PreparedFixed<16, 2> = PreparedFixed::EMPTY;
    // The per-model frames' 1 sphere and 2 lights.
    #[cfg(feature = "microfacets")]
    static mut MODEL_SCENE: Option<Scene<1, 2>> = None;
    #[cfg(feature = "microfacets")]
    static mut MODEL_FIXED: PreparedFixed<1, 2> = PreparedFixed::EMPTY;
    // The area-lights preset's own capacities, when the matrix's or the gallery's are the
    // scene's.
    #[cfg(all(
        feature = "area-lights",
        any(feature = "matrix", feature = "microfacets")
    ))]
    static mut AREA_SCENE: Option<Scene<5, 1>> = None;
    #[cfg(all(
        feature = "area-lights",
        any(feature = "matrix", feature = "microfacets")
    ))]
    static mut AREA_FIXED: PreparedFixed<5, 1> = PreparedFixed::EMPTY;

    // The animations' two scenes and prepared frames, the one shown and the next.
    #[cfg(feature = "animation")]
    static mut ANIMATION: common::animation::AnimationSlots =
        common::animation::AnimationSlots::EMPTY;

    let board = CortexMBoard::new("m0");
    let Some(peripherals) = cortex_m::Peripherals::take() else {
        exit(false)
    };
    let counter = SysTickCounter::new(peripherals.SYST, HCLK_HZ);
    let Some(mut session) = Session::new(board, counter) else {
        exit(false)
    };
    let (Some(scene), _) = session.build(SCENE, exponent_series_with_capacity) else {
        session.note("shadeline-fw error=scene\n");
        exit(false)
    };
    match session.build_in(FIXED, |f| f.prepare(scene, WIDTH, HEIGHT)) {
        (Some(path), prepare) => session.run(
            "fixed",
            path,
            Sink::Line(LINE),
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
    #[cfg(feature = "antialias")]
    match session.build_in(FIXED, |f| {
        f.prepare(scene, WIDTH, HEIGHT)
            .map(|()| f.set_antialiasing(true))
    }) {
        (Some(path), prepare) => session.run(
            "fixed-aa",
            path,
            Sink::Line(LINE),
            prepare,
            Expected {
                crc: common::expected::FIXED_AA_RGB565_CRC32,
                covered: FIXED_COVERED,
            },
        ),
        (None, _) => {
            session.note("shadeline-fw error=prepare-fixed-aa\n");
            session.fail();
        }
    }
    #[cfg(feature = "microfacets")]
    {
        #[cfg(not(feature = "matrix"))]
        let (micro_scene, micro_fixed) = (&mut *SCENE, &mut *FIXED);
        #[cfg(feature = "matrix")]
        let (micro_scene, micro_fixed) = (MICRO_SCENE, MICRO_FIXED);
        let (Some(micro), _) = session.build(micro_scene, shadeline::microfacets_with_capacity)
        else {
            session.note("shadeline-fw error=scene-microfacets\n");
            exit(false)
        };
        match session.build_in(micro_fixed, |f| f.prepare(micro, WIDTH, HEIGHT)) {
            (Some(path), prepare) => session.run(
                "fixed-microfacets",
                path,
                Sink::Line(&mut LINE[..]),
                prepare,
                Expected {
                    crc: common::expected::MICROFACETS_FIXED_RGB565_CRC32,
                    covered: common::expected::MICROFACETS_FIXED_COVERED,
                },
            ),
            (None, _) => {
                session.note("shadeline-fw error=prepare-fixed-microfacets\n");
                session.fail();
            }
        }
        // One frame per reflection model, every pixel that model's.
        let models = shadeline::model_samples().into_iter().zip(MODEL_RUNS);
        for ((_, material), (name, crc)) in models {
            let slot = &mut *MODEL_SCENE;
            let (Some(scene), _) = session.build(slot, || shadeline::covered_sphere(material))
            else {
                session.note("shadeline-fw error=scene-model\n");
                exit(false)
            };
            match session.build_in(&mut *MODEL_FIXED, |f| f.prepare(scene, WIDTH, HEIGHT)) {
                (Some(path), prepare) => session.run(
                    name,
                    path,
                    Sink::Line(&mut LINE[..]),
                    prepare,
                    Expected {
                        crc,
                        covered: common::expected::MODEL_COVERED,
                    },
                ),
                (None, _) => {
                    session.note("shadeline-fw error=prepare-");
                    session.note(name);
                    session.note("\n");
                    session.fail();
                }
            }
        }
    }
    #[cfg(all(
        feature = "area-lights",
        not(any(feature = "matrix", feature = "microfacets"))
    ))]
    session.fixed_area_lights(&mut *SCENE, &mut *FIXED, &mut LINE[..], true);
    #[cfg(all(
        feature = "area-lights",
        any(feature = "matrix", feature = "microfacets")
    ))]
    session.fixed_area_lights(AREA_SCENE, AREA_FIXED, &mut LINE[..], true);
    #[cfg(feature = "matrix")]
    session.fixed_matrix(&mut *SCENE, &mut *FIXED, &mut LINE[..], true);
    // The animations through the line buffer: the M0 has no room for a framebuffer.
    #[cfg(all(feature = "animation", not(feature = "animation-micromath")))]
    session.animations::<common::animation::Libm>(ANIMATION, &mut LINE[..], None);
    #[cfg(feature = "animation-micromath")]
    session.animations::<common::animation::Micromath>(ANIMATION, &mut LINE[..], None);
    exit(session.finish() == Outcome::Pass)
}
