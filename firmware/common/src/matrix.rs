//! The scene matrix (`shadeline::floor`, `shadeline::lamp`, `shadeline::three_lights` at
//! `shadeline::MATRIX_SIZE`): what a user draws first, measured per path. Each firmware renders
//! it with its feature `matrix`, which turns on the shadeline features the scenes need
//! (`blinn-phong`, and the fixed path's `full-width` kernel); every run is one
//! [`Session::run`] line named after its path and scene (`fixed-floor`, `scalar-lamp`, …),
//! checked against the host's CRC and covered count (`expected.rs`).
//!
//! Each path renders the three scenes in turn from one scene slot and one prepared-frame slot
//! of the caller's (statics on the small boards), like [`Session::fixed_area_lights`].

use crate::expected::{MATRIX_FIXED_COVERED, MATRIX_RGB565_CRC32, MATRIX_SCALAR_COVERED};
use crate::meter::InstructionCounter;
use crate::run::{Board, Expected, Session, Sink};
use shadeline::{FloatPath, MatrixScene, Prepared, PreparedFixed, Rgb565, SceneError};

/// The capacities of the matrix's scenes (`shadeline::MatrixScene`) and prepared frames:
/// spheres.
pub const MATRIX_SPHERES: usize = 6;
/// Lights.
pub const MATRIX_LIGHTS: usize = 3;

/// A prepared frame of the matrix on the fixed path.
pub type MatrixFixed = PreparedFixed<MATRIX_SPHERES, MATRIX_LIGHTS>;

/// A prepared frame of the matrix on the float path `W`.
pub type MatrixPrepared<W> = Prepared<W, MATRIX_SPHERES, MATRIX_LIGHTS>;

/// One scene of the matrix: its name (in error reports), the names of its scalar and fixed
/// runs, and its constructor.
type MatrixEntry = (
    &'static str,
    [&'static str; 2],
    fn() -> Result<MatrixScene, SceneError>,
);

/// The matrix's scenes, in the order of `MATRIX_RGB565_CRC32`: two distant lights, one point
/// light, a point light and two distant lights.
const SCENES: [MatrixEntry; 3] = [
    ("floor", ["scalar-floor", "fixed-floor"], shadeline::floor),
    ("lamp", ["scalar-lamp", "fixed-lamp"], shadeline::lamp),
    (
        "three-lights",
        ["scalar-three-lights", "fixed-three-lights"],
        shadeline::three_lights,
    ),
];

impl<B: Board, C: InstructionCounter> Session<B, C> {
    /// The matrix on the fixed path: each scene built into `scene`, prepared in place into
    /// `fixed`, rendered into `buffer` (a line buffer if `line`, else a framebuffer) and
    /// checked against the host's figures (`fixed-floor`, `fixed-lamp`,
    /// `fixed-three-lights`). A shadeline without its `full-width` feature refuses these
    /// scenes on the fixed path, and one without `blinn-phong` refuses `lamp` and
    /// `three-lights`: each refusal is reported and fails the session.
    pub fn fixed_matrix(
        &mut self,
        scene: &mut Option<MatrixScene>,
        fixed: &mut MatrixFixed,
        buffer: &mut [Rgb565],
        line: bool,
    ) {
        let (w, h) = shadeline::MATRIX_SIZE;
        for ((scene_name, [_, name], make), [_, crc]) in SCENES.into_iter().zip(MATRIX_RGB565_CRC32)
        {
            let Some(built) = self.matrix_scene(&mut *scene, scene_name, make) else {
                continue;
            };
            let (Some(path), prepare) = self.build_in(&mut *fixed, |f| f.prepare(built, w, h))
            else {
                self.prepare_failed(name);
                continue;
            };
            let expected = Expected {
                crc,
                covered: MATRIX_FIXED_COVERED,
            };
            if !self.run_in(name, path, (buffer, line), prepare, expected) {
                return;
            }
        }
    }

    /// The matrix on the float path `W` (the scalar path, whose frames are the host's
    /// `Prepared::<Scalar>`'s bit for bit): each scene built into `scene`, prepared into
    /// `prepared`, rendered into the framebuffer `frame` and checked against the host's
    /// figures (`scalar-floor`, `scalar-lamp`, `scalar-three-lights`). A shadeline without
    /// `blinn-phong` refuses `lamp` and `three-lights`, which fails the session.
    pub fn scalar_matrix<W: FloatPath>(
        &mut self,
        scene: &mut Option<MatrixScene>,
        prepared: &mut Option<MatrixPrepared<W>>,
        frame: &mut [Rgb565],
    ) {
        let (w, h) = shadeline::MATRIX_SIZE;
        let Some(out) = frame.get_mut(..(w * h) as usize) else {
            self.note("shadeline-fw error=buffer-matrix\n");
            self.fail();
            return;
        };
        for ((scene_name, [name, _], make), [crc, _]) in SCENES.into_iter().zip(MATRIX_RGB565_CRC32)
        {
            let Some(built) = self.matrix_scene(&mut *scene, scene_name, make) else {
                continue;
            };
            let expected = Expected {
                crc,
                covered: MATRIX_SCALAR_COVERED,
            };
            self.build_and_run(
                name,
                &mut *prepared,
                || MatrixPrepared::<W>::new(built, w, h),
                Sink::Frame(&mut *out),
                expected,
            );
        }
    }

    /// Builds a scene of the matrix into `slot`; reports `error=scene-<name>` and fails the
    /// session if it is refused.
    fn matrix_scene<'s>(
        &mut self,
        slot: &'s mut Option<MatrixScene>,
        name: &str,
        make: fn() -> Result<MatrixScene, SceneError>,
    ) -> Option<&'s MatrixScene> {
        let (built, _) = self.build(slot, make);
        if built.is_none() {
            self.note("shadeline-fw error=scene-");
            self.note(name);
            self.note("\n");
            self.fail();
        }
        built
    }
}
