//! shadeline on a Cortex-M4F (QEMU `mps2-an386`): the exponent series at 320×240 into a full
//! RGB565 framebuffer in RAM (150 KiB of the board's 4 MiB), on the scalar `f32` path (hard
//! float) and the fixed-point path, each reported with its CRC, instruction count and stack
//! high-water mark over semihosting. Exits 0 only if every CRC matches.
//!
//! The scalar path takes its square roots from the FPU's `VSQRT.F32` ([`Vsqrt`], as an M4F
//! firmware would: `scalar`); the same frame with `libm`'s integer square root, the crate's
//! default [`Scalar`], is reported too (`scalar-libm`). With the feature
//! `antialias`, the scalar and the fixed path also render the frame with analytic
//! anti-aliasing (`scalar-aa`, `fixed-aa`); with the feature `microfacets`, it also renders the microfacet gallery
//! (GGX and Oren–Nayar spheres next to normalized Blinn-Phong and Lambert ones) on the
//! scalar and the fixed path (`scalar-microfacets`, `fixed-microfacets`), and a frame of
//! each reflection model alone (`shadeline::covered_sphere` of each of
//! `shadeline::model_samples`: `scalar-phong`, `fixed-phong`, `scalar-nbp` (normalized
//! Blinn-Phong), … `fixed-ggx-gold`); with the feature `area-lights`, it also renders the
//! area-lights preset on the scalar and the fixed path under its sphere light and under a
//! point light at the same place (`scalar-sphere-light`, `scalar-point-light`,
//! `fixed-sphere-light`, `fixed-point-light`); with the feature `matrix`, it also renders the
//! scene matrix (`shadeline::floor`, `lamp`, `three_lights`) on the scalar path with
//! `VSQRT.F32` and on the fixed path (`scalar-floor`, …, `fixed-three-lights`).
//!
//! Run with `cargo m4f` from `firmware/` (the alias and the QEMU runner are in
//! `.cargo/config.toml`).

#![no_std]
#![no_main]

use common::cortex_m_board::{exit, CortexMBoard, SysTickCounter};
use common::expected::{
    FIXED_COVERED, FIXED_RGB565_CRC32, HEIGHT, SCALAR_COVERED, SCALAR_RGB565_CRC32, WIDTH,
};
use common::{Expected, Outcome, Session, Sink};
use cortex_m_rt::entry;
use shadeline::{
    exponent_series, Prepared, PreparedFixed, Rgb565, Scalar, ScalarWith, Scene, SquareRoot,
};

/// The Cortex-M4F's square-root instruction, `VSQRT.F32`: IEEE 754's correctly rounded
/// square root, one instruction (14 cycles), where `libm::sqrtf` is an integer routine of
/// about fifty. The FPU runs with the reset FPSCR (round to nearest, no flush to zero).
struct Vsqrt;

impl SquareRoot for Vsqrt {
    #[inline(always)]
    fn sqrt(x: f32) -> f32 {
        let root: u32;
        // Rust's `asm!` offers the FPU's registers only with the double-precision `vfp2`
        // feature, which this single-precision FPU lacks: the value goes through `s0`, saved
        // and restored in a core register, so no register the compiler uses changes.
        // SAFETY: reads and writes only the registers named or restored; no memory, no
        // stack, no flags. cortex-m-rt enables the FPU before `main` on this hard-float
        // target.
        unsafe {
            core::arch::asm!(
                ".fpu fpv4-sp-d16",
                "vmov {saved}, s0",
                "vmov s0, {x}",
                "vsqrt.f32 s0, s0",
                "vmov {root}, s0",
                "vmov s0, {saved}",
                x = in(reg) x.to_bits(),
                root = lateout(reg) root,
                saved = out(reg) _,
                options(pure, nomem, nostack, preserves_flags),
            )
        };
        f32::from_bits(root)
    }
}

/// The scalar path as an M4F firmware builds it: hardware square roots.
type M4fScalar = ScalarWith<Vsqrt>;

/// The per-model runs of the feature `microfacets`, in the order of
/// `shadeline::model_samples`: their names (scalar, fixed; `nbp` is normalized Blinn-Phong,
/// short so that the report line fits its 256 bytes) and expected CRCs.
#[cfg(feature = "microfacets")]
const MODEL_RUNS: [([&str; 2], [u32; 2]); 5] = {
    let crc = common::expected::MODEL_RGB565_CRC32;
    [
        (["scalar-phong", "fixed-phong"], crc[0]),
        (["scalar-nbp", "fixed-nbp"], crc[1]),
        (["scalar-oren-nayar", "fixed-oren-nayar"], crc[2]),
        (["scalar-ggx", "fixed-ggx"], crc[3]),
        (["scalar-ggx-gold", "fixed-ggx-gold"], crc[4]),
    ]
};

/// mps2-an386's processor clock, which clocks SysTick: 25 MHz.
const SYSCLK_HZ: u32 = 25_000_000;

const PIXELS: usize = (WIDTH * HEIGHT) as usize;

// `#[entry]` passes each `static mut` below to the real entry function as an argument.
#[allow(clippy::too_many_arguments)]
#[entry]
fn main() -> ! {
    // cortex-m-rt turns these into `&'static mut`s owned by `main`, no unsafe: one
    // framebuffer (zeroed with .bss), the scene and both prepared frames, each built in place.
    static mut FRAME: [Rgb565; PIXELS] = [Rgb565(0); PIXELS];
    static mut SCENE: Option<Scene> = None;
    static mut SCALAR: Option<Prepared<M4fScalar>> = None;
    static mut SCALAR_LIBM: Option<Prepared<Scalar>> = None;
    static mut FIXED: PreparedFixed = PreparedFixed::EMPTY;
    #[cfg(feature = "antialias")]
    static mut SCALAR_AA: Option<Prepared<M4fScalar>> = None;
    #[cfg(feature = "microfacets")]
    static mut MICRO_SCENE: Option<Scene> = None;
    #[cfg(feature = "microfacets")]
    static mut MICRO: Option<Prepared<M4fScalar>> = None;
    #[cfg(feature = "microfacets")]
    static mut MICRO_FIXED: PreparedFixed = PreparedFixed::EMPTY;
    #[cfg(feature = "microfacets")]
    static mut MODEL_SCENE: Option<Scene<1, 2>> = None;
    #[cfg(feature = "microfacets")]
    static mut MODEL: Option<Prepared<M4fScalar, 1, 2>> = None;
    #[cfg(feature = "microfacets")]
    static mut MODEL_FIXED: PreparedFixed<1, 2> = PreparedFixed::EMPTY;
    #[cfg(feature = "area-lights")]
    static mut AREA_SCENE: Option<Scene<5, 1>> = None;
    #[cfg(feature = "area-lights")]
    static mut AREA: Option<Prepared<M4fScalar, 5, 1>> = None;
    #[cfg(feature = "area-lights")]
    static mut POINT_SCENE: Option<Scene<5, 1>> = None;
    #[cfg(feature = "area-lights")]
    static mut POINT: Option<Prepared<M4fScalar, 5, 1>> = None;
    #[cfg(feature = "area-lights")]
    static mut AREA_FIXED: PreparedFixed<5, 1> = PreparedFixed::EMPTY;
    #[cfg(feature = "matrix")]
    static mut MATRIX_SCENE: Option<shadeline::MatrixScene> = None;
    #[cfg(feature = "matrix")]
    static mut MATRIX_SCALAR: Option<common::MatrixPrepared<M4fScalar>> = None;
    #[cfg(feature = "matrix")]
    static mut MATRIX_FIXED: common::MatrixFixed = PreparedFixed::EMPTY;

    // The animations' two scenes and prepared frames, the one shown and the next.
    #[cfg(feature = "animation")]
    static mut ANIMATION: common::animation::AnimationSlots =
        common::animation::AnimationSlots::EMPTY;
    #[cfg(feature = "animation")]
    static mut ANIMATION_LINE: [Rgb565; common::animation::ANIMATION_WIDTH as usize] =
        [Rgb565(0); common::animation::ANIMATION_WIDTH as usize];

    let board = CortexMBoard::new("m4f");
    let Some(peripherals) = cortex_m::Peripherals::take() else {
        exit(false)
    };
    let counter = SysTickCounter::new(peripherals.SYST, SYSCLK_HZ);
    let Some(mut session) = Session::new(board, counter) else {
        exit(false)
    };
    let (Some(scene), _) = session.build(SCENE, exponent_series) else {
        session.note("shadeline-fw error=scene\n");
        exit(false)
    };
    let series = Expected {
        crc: SCALAR_RGB565_CRC32,
        covered: SCALAR_COVERED,
    };
    session.build_and_run(
        "scalar",
        SCALAR,
        || Prepared::<M4fScalar>::new(scene, WIDTH, HEIGHT),
        Sink::Frame(FRAME),
        series,
    );
    session.build_and_run(
        "scalar-libm",
        SCALAR_LIBM,
        || Prepared::<Scalar>::new(scene, WIDTH, HEIGHT),
        Sink::Frame(FRAME),
        series,
    );
    #[cfg(feature = "antialias")]
    session.build_and_run(
        "scalar-aa",
        SCALAR_AA,
        || Prepared::<M4fScalar>::new(scene, WIDTH, HEIGHT).map(|p| p.with_antialiasing(true)),
        Sink::Frame(FRAME),
        Expected {
            crc: common::expected::SCALAR_AA_RGB565_CRC32,
            covered: SCALAR_COVERED,
        },
    );
    #[cfg(feature = "microfacets")]
    {
        let (Some(micro), _) = session.build(MICRO_SCENE, shadeline::microfacets) else {
            session.note("shadeline-fw error=scene-microfacets\n");
            exit(false)
        };
        session.build_and_run(
            "scalar-microfacets",
            MICRO,
            || Prepared::<M4fScalar>::new(micro, WIDTH, HEIGHT),
            Sink::Frame(FRAME),
            Expected {
                crc: common::expected::MICROFACETS_SCALAR_RGB565_CRC32,
                covered: common::expected::MICROFACETS_SCALAR_COVERED,
            },
        );
        match session.build_in(MICRO_FIXED, |f| f.prepare(micro, WIDTH, HEIGHT)) {
            (Some(path), prepare) => session.run(
                "fixed-microfacets",
                path,
                Sink::Frame(FRAME),
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
        for ((_, material), ([scalar_name, fixed_name], [scalar_crc, fixed_crc])) in models {
            let slot = &mut *MODEL_SCENE;
            let (Some(scene), _) = session.build(slot, || shadeline::covered_sphere(material))
            else {
                session.note("shadeline-fw error=scene-model\n");
                exit(false)
            };
            let expected = |crc| Expected {
                crc,
                covered: common::expected::MODEL_COVERED,
            };
            session.build_and_run(
                scalar_name,
                &mut *MODEL,
                || Prepared::<M4fScalar, 1, 2>::new(scene, WIDTH, HEIGHT),
                Sink::Frame(&mut FRAME[..]),
                expected(scalar_crc),
            );
            match session.build_in(&mut *MODEL_FIXED, |f| f.prepare(scene, WIDTH, HEIGHT)) {
                (Some(path), prepare) => session.run(
                    fixed_name,
                    path,
                    Sink::Frame(&mut FRAME[..]),
                    prepare,
                    expected(fixed_crc),
                ),
                (None, _) => {
                    session.note("shadeline-fw error=prepare-");
                    session.note(fixed_name);
                    session.note("\n");
                    session.fail();
                }
            }
        }
    }
    #[cfg(feature = "area-lights")]
    {
        use common::expected::{
            AREA_LIGHTS_COVERED, AREA_LIGHTS_FIXED_POINT_RGB565_CRC32,
            AREA_LIGHTS_FIXED_SPHERE_RGB565_CRC32, AREA_LIGHTS_HEIGHT,
            AREA_LIGHTS_POINT_RGB565_CRC32, AREA_LIGHTS_SPHERE_RGB565_CRC32, AREA_LIGHTS_WIDTH,
        };
        let runs = [
            (
                ["scalar-sphere-light", "fixed-sphere-light"],
                AREA_SCENE,
                AREA,
                shadeline::AREA_LIGHT_RADIUS,
                [
                    AREA_LIGHTS_SPHERE_RGB565_CRC32,
                    AREA_LIGHTS_FIXED_SPHERE_RGB565_CRC32,
                ],
            ),
            (
                ["scalar-point-light", "fixed-point-light"],
                POINT_SCENE,
                POINT,
                0.0,
                [
                    AREA_LIGHTS_POINT_RGB565_CRC32,
                    AREA_LIGHTS_FIXED_POINT_RGB565_CRC32,
                ],
            ),
        ];
        let pixels = (AREA_LIGHTS_WIDTH * AREA_LIGHTS_HEIGHT) as usize;
        for ([name, fixed_name], scene_slot, slot, radius, [crc, fixed_crc]) in runs {
            let (Some(scene), _) = session.build(scene_slot, || shadeline::area_lights(radius))
            else {
                session.note("shadeline-fw error=scene-area-lights\n");
                exit(false)
            };
            session.build_and_run(
                name,
                slot,
                || Prepared::<M4fScalar, 5, 1>::new(scene, AREA_LIGHTS_WIDTH, AREA_LIGHTS_HEIGHT),
                Sink::Frame(&mut FRAME[..pixels]),
                Expected {
                    crc,
                    covered: AREA_LIGHTS_COVERED,
                },
            );
            let fixed = &mut *AREA_FIXED;
            match session.build_in(fixed, |f| {
                f.prepare(scene, AREA_LIGHTS_WIDTH, AREA_LIGHTS_HEIGHT)
            }) {
                (Some(path), prepare) => session.run(
                    fixed_name,
                    path,
                    Sink::Frame(&mut FRAME[..pixels]),
                    prepare,
                    Expected {
                        crc: fixed_crc,
                        covered: AREA_LIGHTS_COVERED,
                    },
                ),
                (None, _) => {
                    session.note("shadeline-fw error=prepare-");
                    session.note(fixed_name);
                    session.note("\n");
                    session.fail();
                }
            }
        }
    }
    match session.build_in(FIXED, |f| f.prepare(scene, WIDTH, HEIGHT)) {
        (Some(path), prepare) => session.run(
            "fixed",
            path,
            Sink::Frame(FRAME),
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
            Sink::Frame(FRAME),
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
    #[cfg(feature = "matrix")]
    {
        session.scalar_matrix(MATRIX_SCENE, MATRIX_SCALAR, &mut FRAME[..]);
        session.fixed_matrix(MATRIX_SCENE, MATRIX_FIXED, &mut FRAME[..], false);
    }
    // The animations: rows and damaged pieces through a line buffer, and the framebuffer as
    // the display the damage run keeps up to date.
    #[cfg(all(feature = "animation", not(feature = "animation-micromath")))]
    session.animations::<common::animation::Libm>(
        ANIMATION,
        &mut ANIMATION_LINE[..],
        Some(&mut FRAME[..]),
    );
    #[cfg(feature = "animation-micromath")]
    session.animations::<common::animation::Micromath>(
        ANIMATION,
        &mut ANIMATION_LINE[..],
        Some(&mut FRAME[..]),
    );
    exit(session.finish() == Outcome::Pass)
}
