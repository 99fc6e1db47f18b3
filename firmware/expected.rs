// The frame every firmware renders and the CRCs it must produce: the one source of truth,
// included (with `include!`) by the firmware's common crate and by the host test
// `tests/firmware_crcs.rs`, which renders the same frames on the host and checks these
// numbers, so firmware and host can never drift apart silently.
//
// CRC32/IEEE (the zlib/PNG one) over the RGB565 pixels, row-major, each pixel as its
// little-endian u16 bytes.

/// Width of the frame every firmware renders, in pixels.
pub const WIDTH: u32 = 320;
/// Height of the frame every firmware renders, in pixels.
pub const HEIGHT: u32 = 240;

/// CRC32 of the exponent series at 320×240 rendered by `Prepared::<Scalar>` into `Rgb565`.
/// IEEE single precision with the same operations in the same order gives the same bits on
/// every target, hard float (Cortex-M4F) or soft float (RV32IMAC).
pub const SCALAR_RGB565_CRC32: u32 = 0xaea2_bfb6;

/// CRC32 of the same frame with analytic anti-aliasing
/// (`Prepared::<Scalar>::with_antialiasing(true)`): the M4F firmware's `scalar-aa` run.
pub const SCALAR_AA_RGB565_CRC32: u32 = 0x44cb_9b4f;

/// CRC32 of the exponent series at 320×240 rendered by `PreparedFixed` into `Rgb565`: the
/// golden value of `tests/fixed_golden.rs` (`GOLDEN_EXPONENT_SERIES_320X240`). Integer
/// arithmetic only, so the same bits on every target.
pub const FIXED_RGB565_CRC32: u32 = 0x0d0e_0408;

/// CRC32 of the same frame with analytic anti-aliasing on the fixed path
/// (`PreparedFixed::with_antialiasing(true)`, features `antialias` and `full-width`): the M0
/// and M4F firmware's `fixed-aa` runs (feature `antialias`; reported, not budgeted).
pub const FIXED_AA_RGB565_CRC32: u32 = 0xc45c_06e5;

/// Pixels of that frame whose primary ray hits a sphere on the scalar path: the `covered=`
/// figure, and its per-covered-pixel ratio, of the firmware that do not count on target.
pub const SCALAR_COVERED: u64 = 11_840;

/// Pixels of that frame whose primary ray hits a sphere on the fixed path (the same as the
/// scalar path's: the narrow kernel's hit test is the sign of an exact quadric).
pub const FIXED_COVERED: u64 = 11_840;

/// CRC32 of the microfacet gallery (`shadeline::microfacets`, GGX, Oren–Nayar and their
/// normalized matches) at 320×240 rendered by `Prepared::<Scalar>` into `Rgb565`: the M4F
/// firmware's `scalar-microfacets` run (feature `microfacets`; reported, not budgeted).
pub const MICROFACETS_SCALAR_RGB565_CRC32: u32 = 0x9be3_dc87;
/// Pixels of that frame whose primary ray hits a sphere.
pub const MICROFACETS_SCALAR_COVERED: u64 = 38_796;

/// CRC32 of the microfacet gallery at 320×240 rendered by `PreparedFixed` into `Rgb565`: the
/// M4F firmware's `fixed-microfacets` run (feature `microfacets`; reported, not budgeted).
pub const MICROFACETS_FIXED_RGB565_CRC32: u32 = 0x0227_dcea;
/// Pixels of that frame whose primary ray hits a sphere on the fixed path.
pub const MICROFACETS_FIXED_COVERED: u64 = 38_796;

/// CRC32s (scalar, fixed) of the per-model frames at 320×240 in `Rgb565`:
/// `shadeline::covered_sphere` of each of `shadeline::model_samples()`, in that order,
/// rendered by `Prepared::<Scalar, 1, 2>` and by `PreparedFixed::<1, 2>`: the M4F
/// firmware's `scalar-<model>` and `fixed-<model>` runs (feature `microfacets`; reported,
/// not budgeted).
pub const MODEL_RGB565_CRC32: [[u32; 2]; 5] = [
    [0xa2d2_70f0, 0x2f91_9c90],
    [0xf4f0_01a9, 0x79aa_8a97],
    [0x1a73_07b5, 0x4b0d_59b8],
    [0xb3cc_f6fb, 0x678c_25f4],
    [0xf42f_798e, 0x810b_fdb9],
];
/// Pixels of each per-model frame whose primary ray hits the sphere: all of them.
pub const MODEL_COVERED: u64 = 76_800;

/// Size of the area-lights frames (`shadeline::area_lights`, whose own size is 640×320):
/// half of it in each direction, which the M4F's framebuffer holds.
pub const AREA_LIGHTS_WIDTH: u32 = 320;
/// Height of the area-lights frames.
pub const AREA_LIGHTS_HEIGHT: u32 = 160;

/// CRC32 of the area-lights preset under its sphere light (`shadeline::AREA_LIGHT_RADIUS`)
/// at 320×160 rendered by `Prepared::<Scalar, 5, 1>` into `Rgb565`: the M4F firmware's
/// `scalar-sphere-light` run (feature `area-lights`; reported, not budgeted).
pub const AREA_LIGHTS_SPHERE_RGB565_CRC32: u32 = 0xdddc_f1b9;
/// CRC32 of the same frame under a point light at the light sphere's centre (radius 0):
/// `scalar-point-light`.
pub const AREA_LIGHTS_POINT_RGB565_CRC32: u32 = 0xbf38_9e03;
/// CRC32 of the area-lights frame under its sphere light rendered by `PreparedFixed::<5, 1>`
/// into `Rgb565`: the M4F firmware's `fixed-sphere-light` run (feature `area-lights`, which
/// turns on the fixed path's `full-width` kernel; reported, not budgeted).
pub const AREA_LIGHTS_FIXED_SPHERE_RGB565_CRC32: u32 = 0x739b_e030;
/// The same under the point light: `fixed-point-light`.
pub const AREA_LIGHTS_FIXED_POINT_RGB565_CRC32: u32 = 0x6ddb_6ffe;
/// Pixels of either frame whose primary ray hits a sphere (the light's size changes no
/// primary ray).
pub const AREA_LIGHTS_COVERED: u64 = 36_588;

/// CRC32s (scalar, fixed) of the scene matrix at `shadeline::MATRIX_SIZE` (320×240) in
/// `Rgb565`: `shadeline::floor`, `shadeline::lamp` and `shadeline::three_lights`, in that
/// order, rendered by `Prepared::<Scalar, 6, 3>` and by `PreparedFixed::<6, 3>`: the
/// firmware's `scalar-<scene>` runs (the M4F's, with `VSQRT.F32`) and `fixed-<scene>` runs
/// (feature `matrix`).
pub const MATRIX_RGB565_CRC32: [[u32; 2]; 3] = [
    [0xe45b_8b57, 0xb6e6_70bd],
    [0x1500_ec46, 0xca43_a581],
    [0x7c40_2ce9, 0xb2f5_108d],
];
/// Pixels of each matrix frame whose primary ray hits a sphere on the scalar path (the three
/// scenes share their spheres and camera).
pub const MATRIX_SCALAR_COVERED: u64 = 50_132;
/// Pixels of each matrix frame whose primary ray hits a sphere on the fixed path.
pub const MATRIX_FIXED_COVERED: u64 = 50_132;

/// CRC32s of all the frames (1 to `ANIMATION_FRAMES`, one after the other) of each animation of
/// `firmware/animation.rs` (orbit, bounce) at `ANIMATION_WIDTH × ANIMATION_HEIGHT`, rendered in
/// full by `PreparedFixed::<5, 2>` into `Rgb565`: with micromath's sine and cosine (feature
/// `animation-micromath`), then with libm's (what the firmware keeps). The firmware's
/// `anim-orbit` and `anim-bounce` runs (feature `animation`).
pub const ANIMATION_FRAMES_RGB565_CRC32: [[u32; 2]; 2] = [
    [0x06cb_cb8f, 0x2ced_3c49],
    [0xd8c2_27db, 0xd598_09f5],
];
/// CRC32s of the last frame (frame `ANIMATION_FRAMES`) of each animation, in the same order:
/// what the M4F's framebuffer must hold after the damage run. Both animations end where they
/// began, so each is the floor scene's own frame (`MATRIX_RGB565_CRC32`'s fixed `floor`).
pub const ANIMATION_LAST_RGB565_CRC32: [[u32; 2]; 2] = [
    [0xb6e6_70bd, 0xb6e6_70bd],
    [0xb6e6_70bd, 0xb6e6_70bd],
];
/// CRC32s of everything damage-only rendering sends a display over each animation (frames 1
/// to `ANIMATION_FRAMES`, each the damage against the frame before): per piece, its `x`, `y`
/// and length as little-endian `u16`s, then its pixels. Same order as above.
pub const ANIMATION_DAMAGE_STREAM_CRC32: [[u32; 2]; 2] = [
    [0xde99_1abc, 0x498f_cbb7],
    [0xdb01_968f, 0x3296_ef13],
];
/// Damaged pixels over frames 1 to `ANIMATION_FRAMES` of each animation. Same order as above.
pub const ANIMATION_DAMAGE_PIXELS: [[u64; 2]; 2] = [[1_559_040, 1_153_780], [1_559_040, 1_153_756]];
