//! The prepare step of the fixed path: the scene converted to fixed point, once per frame.
//!
//! This is the only place the fixed path touches floating point: `f32` arithmetic (IEEE `+ − × ÷`,
//! exact power-of-two scaling), `libm`'s `sqrtf`/`floorf`/`ceilf` and the camera's tangent
//! (`Camera::tan_half_fov`), the same operations on every target, followed by exact conversions to
//! fixed bits ([`super::convert`]). So the prepared numbers, and with them every pixel, are the
//! same bits on a host, a Cortex-M0 and a RISC-V core.
//!
//! What it does, in order: check the size and the camera's plane scale; pick the scene's
//! power-of-two scale; convert and check every sphere, material and light (each refusal is
//! [`RenderError::OutOfFixedRange`] naming the item and field); compute each sphere's screen
//! rectangle (`spans`, with the full-width kernel); then, for a frame the narrow kernel
//! takes, its constants: the exact quadrics (`quadric`), the caster filters and, without the
//! full-width kernel, each sphere's rows and columns (`outline`).

use super::convert::{fixed_bits, fixed_bits_i32, fixed_bits_u32, to_f32};
use super::exact::Exact;
use super::mul::{dot_ii, mul_128, mul_ii, mul_iu, mul_uu};
#[cfg(not(feature = "full-width"))]
use super::outline::{outline_columns, outline_rows};
use super::quadric::Quadric;
use super::roots::{inv_sqrt, sqrt};
#[cfg(feature = "full-width")]
use super::spans::{Bounds, View};
use super::vector::{each3, Len, Unit, V3};
#[cfg(feature = "full-width")]
use crate::brdf::LOBES;
use crate::brdf::{Params, BLINN_PHONG};
use crate::render::{Kernel, RenderError};
use crate::scene::Model;
#[cfg(feature = "full-width")]
use crate::scene::MORE_LOBES;
use crate::scene::{Item, Light, Scene};
use crate::vec3::Vec3;
use crate::MAX_DIMENSION;
use fixed::types::{I16F48, I32F32, U16F16};

/// The scene is scaled by a power of two so that its extent is below `2^EXTENT_LOG2` units.
pub(crate) const EXTENT_LOG2: i32 = 13;
/// The largest scale, `2¹⁹`: keeps the ray epsilon (`10⁻⁴` for scenes smaller than one unit)
/// below 64 units.
pub(crate) const MAX_SCALE_LOG2: i32 = 19;

/// Smallest sphere radius after scaling, in units (`2¹⁶` raw I16F16 steps): normals then
/// carry at least 16 bits. In scene terms: a radius at least `2⁻¹³` of the scene's extent.
pub const MIN_SCALED_RADIUS: f32 = 1.0;
/// Largest `tan(vfov/2)·max(1, width/height)`: keeps primary-ray directions within ±256.
pub const MAX_PLANE_SCALE: f32 = 127.0;
/// Largest `kd·albedo`, `ks` and distant-light `colour·intensity` per channel: they are
/// U16F16 and two of them multiply and add without wrapping.
pub const MAX_LEVEL: f32 = 32_767.0;

/// The largest error of the narrow kernel's fast `h = 1 − cos` (Phong's `1 − R·V`,
/// Blinn-Phong's `1 − N·H` where `|L + V| ≥ ¾`), `6·2⁻¹⁵`: checked by the narrow module's
/// `fast_h_within_its_bound` on the exponent series and on random frames. The prepare's lobe
/// cutoff and the test of whether a sphere's lobe needs the precise `h` use it.
pub(crate) const H_ERROR: f32 = 6.0 / 32768.0;

/// The primary directions of a frame in narrow form: `D = forward + dy·step_y + dx·step_x`
/// with `dx = 2x + 1 − w` and `dy = h − 2y − 1`, integer vectors with `|D| < 2³⁰`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct NarrowView {
    pub forward: V3<i32>,
    pub step_x: V3<i32>,
    pub step_y: V3<i32>,
}

impl NarrowView {
    /// The quadrics' three directions `[forward, step_x, step_y]` (see [`quadric`]).
    fn dirs(&self) -> [V3<i32>; 3] {
        [self.forward, self.step_x, self.step_y]
    }
}

/// `v` (I16F48 bits, each component below 2 in magnitude) rounded to Q29, the narrow
/// kernel's directions. Out of line on ARMv6-M: three vectors a frame.
#[cfg_attr(shadeline_short_mul, inline(never))]
fn to_q29(v: V3<I16F48>) -> [i32; 3] {
    // ((c >> 18) + 1) >> 1 is (c + 2¹⁸) >> 19, with no overflow near `i64::MAX`.
    v.map(|c| (((c.to_bits() >> 18) + 1) >> 1) as i32)
}

/// An `h` (Q31) from which a lobe of exponent `n` times `ks_intensity` (`ks` times the sum
/// of the lights' brightest channels) is below `τ = 2⁻¹⁷`, half a U16F16 step, allowing for
/// the fast `h`'s error ([`H_ERROR`]).
///
/// `(1 − h)ⁿ < τ/k` from `h = 1 − e^(−x)` on, `x = ln(k/τ)/n`; that is below
/// `x − x²/2 + x³/6` (the series alternates with falling terms for `x < 3`), and
/// `ln(k/τ) = ln 2·log₂(k/τ)` is at most `ln 2·e + (m − 1)` for `k/τ = m·2^e`, `m` in
/// `[1, 2)` (as `ln m ≤ m − 1`, within 0.06). So this bound, a few `f32` operations on the
/// number's bits, is never below the true cutoff: it only shades a few more pixels' lobes
/// (to 0) than needed, and needs no `powf`.
fn lobe_cutoff(ks_intensity: f32, n: f32) -> u32 {
    let ratio = ks_intensity * 131_072.0; // k/τ
    if ratio.is_nan() || ratio <= 1.0 || n.is_nan() || n <= 0.0 {
        return 0;
    }
    let bits = ratio.to_bits();
    let e = ((bits >> 23) & 0xff) as i32 - 127;
    let m = f32::from_bits((bits & 0x7f_ffff) | (127 << 23)); // in [1, 2)
    let x = (e as f32 * core::f32::consts::LN_2 + (m - 1.0)) / n;
    // From x = 1.5 on, 1: the whole lit lobe (the true cutoff is above 0.77 there).
    let h = if x < 1.5 {
        x - x * x * (0.5 - x / 6.0)
    } else {
        1.0
    } + 2.0 * H_ERROR;
    (h * (1u64 << 31) as f32) as u32
}

/// The index pairs `(a, b)` of a quadric's coefficients in the order of [`Quadric::c`]:
/// `c₀₀` from the directions `(0, 0)`, `c₁₀` from `(0, 1)` …, `c₀₂` from `(2, 2)`.
const PAIRS: [(usize, usize); 6] = [(0, 0), (0, 1), (0, 2), (1, 1), (1, 2), (2, 2)];

/// Which of a sphere's two quadrics [`quadric`] makes (see [`Quadric`]). By the identities
/// of Lagrange and Binet–Cauchy, `|oc × D|² = |oc|²·|D|² − (oc·D)²` and
/// `(oc × D)·(L × D) = (oc·L)·|D|² − (oc·D)(L·D)`, so both come from dot products alone:
enum Form<'a> {
    /// `E′·r²·2⁵⁸ = r²·|D|² − |oc × D|² = (r² − |oc|²)·|D|² + (oc·D)²`.
    E,
    /// `G·r·2⁸⁸ = (oc × D)·(L × D) = (oc·L)·|D|² − (oc·D)(L·D)`, with `L·Dₐ` for each of
    /// the three directions.
    G(&'a [i64; 3]),
}

/// A sphere's quadric `form` over `den`, for `D = dc + x·sx + y·sy`: from `s` (`r² − |oc|²`
/// for `E′`, `oc·L` for `G`), the Gram matrix `gram` of the three directions (`Dₐ·D_b` in
/// the order of [`PAIRS`]) and `b`, their dot products with `oc`. Each raw coefficient is
/// exact in `i128`: `s·(Dₐ·D_b) ± sym(bₐ·v_b)`, doubled off the diagonal, with `v = b` for
/// `E′` and `v = L·D` for `G` (below `2¹²⁷`: `|s| < 2⁶²`; `|Dₐ·D_b|`, `|bₐ|` and `|L·Dₐ|`
/// below `3·2⁶⁰`). Each is divided as soon as it is made (one `i128` at a time on the
/// stack), into `c`. One loop over [`PAIRS`] for both, for the flash: once per sphere and
/// per sphere and light. `None` if a coefficient does not fit.
#[inline(never)]
fn quadric(
    (s, gram, b): (i64, &[i64; 6], &[i64; 3]),
    form: Form,
    den: &Divisor,
    c: &mut Quadric,
) -> Option<()> {
    let v = match form {
        Form::E => b,
        Form::G(l) => l,
    };
    for ((slot, &(i, k)), &dot) in c.c.iter_mut().zip(&PAIRS).zip(gram) {
        let (i, k) = (i % 3, k % 3);
        // The symmetric product; for `E′`, `v` is `b` and its two halves are equal.
        let mut raw = mul_128(b[i], v[k]);
        if i != k {
            raw += match form {
                Form::E => raw,
                Form::G(_) => mul_128(b[k], v[i]),
            };
        }
        // |Dₐ·D_b| < 3·2⁶⁰: doubled, it fits `i64`.
        let scaled = mul_128(s, if i == k { dot } else { 2 * dot });
        raw = match form {
            Form::E => scaled + raw,
            Form::G(_) => scaled - raw,
        };
        *slot = den.divide(raw)?;
    }
    Some(())
}

/// A positive divisor `dᵏ·2^z` (`d` below `2³²`, `k` one or two, `z` below 64): the
/// prepare divides each of a sphere's quadric coefficients by `r²` or `r` times a power of
/// two. The quotient is exact, rounded toward zero: the dividend's magnitude is divided as
/// four 32-bit limbs, each one 64/32-bit division (the runtime's `u64` division, which a
/// 32-bit core links anyway), `k` times over, then shifted. No 128-bit division routine
/// (a long one on a 32-bit core) and no reciprocal to make.
struct Divisor {
    d: u32,
    passes: u32,
    z: u32,
}

impl Divisor {
    /// `c` over the divisor, rounded toward zero; `None` if it does not fit `i64`. Inlined
    /// into `quadric`, its one caller (smaller on the M0).
    #[inline(always)]
    fn divide(&self, c: i128) -> Option<i64> {
        let m = c.unsigned_abs();
        let mut limbs = [
            (m >> 96) as u32,
            (m >> 64) as u32,
            (m >> 32) as u32,
            m as u32,
        ];
        // The prepare's radii are at least one unit (2¹⁶ raw): the `max` only shows the
        // compiler that the division cannot be by 0.
        let d = self.d.max(1) as u64;
        for _ in 0..self.passes {
            // Each step's dividend is below d·2³², so its quotient fits a limb.
            let mut rest = 0u64;
            for limb in &mut limbs {
                let part = (rest << 32) | *limb as u64;
                *limb = (part / d) as u32;
                rest = part % d;
            }
        }
        let [a, b, c2, c3] = limbs;
        let (high, low) = (
            ((a as u64) << 32) | b as u64,
            ((c2 as u64) << 32) | c3 as u64,
        );
        // (high·2⁶⁴ + low) >> z is below 2⁶³ iff high is below 2^(z − 1) (for z = 0:
        // high is 0 and low below 2⁶³).
        let z = self.z.min(63);
        let q = match z {
            0 => (high == 0).then_some(low),
            _ => (high >> (z - 1) == 0).then_some((high << (64 - z)) | (low >> z)),
        }?;
        let q = i64::try_from(q).ok()?;
        Some(if c < 0 { -q } else { q })
    }
}

/// A sphere's narrow constants, the per-pixel ones first (see [`FixedSphere`]).
///
/// Its two quadrics (`e` here, `g` per light in [`NarrowLight`]) hold, for the direction `d`
/// of a pixel (`D/2²⁹`, length in `[1, √2]`) and `ô = (eye − centre)/r`:
///
/// - `E′ = |d|² − |ô × d|²`, the ray's discriminant times `|d|²/r²`: the ray hits iff
///   `E′ ≥ 0`, and then `N·V = √(E′/|d|²)`;
/// - `G = (ô × d)·(L × d)`, from which `N·L = (G − √E′·(d·L))/|d|²`.
///
/// `e` is held times `2^(29 + e_shift)` and `g` times `2^(29 + g_shift)`, the largest powers
/// that keep every value in the frame 16 times below `2⁶³` (`|E′| ≤ 2·max(1, |ô|²)`,
/// `|G| ≤ 2|ô|`), so a value shifted right by its shift is `E′` or `G` in Q29.
#[derive(Clone, Copy, Debug)]
#[repr(C)]
pub(crate) struct NarrowSphere {
    /// The largest fast lobe (U1F16) that is within half a level where `h ≤ ½`: 2¹⁶ or more
    /// if it is wherever the lobe is not 0, 0 if nowhere (see the narrow module).
    pub fast_lobe_max: u32,
    /// `1 − r²/(r + ε)²` in Q30: `(N·L)²` above it, with `N·L < 0`, is in the own shadow.
    pub shadow_limit: u32,
    /// `h` (Q31) from which the lobe is 0.
    pub cutoff: u32,
    /// See the type's docs.
    pub e_shift: u32,
    pub g_shift: u32,
    /// `N` from `oc × D` (on demand, for caster tests): that product's bits from this one
    /// on, `(oc × D) >> cross_shift`, are below `2¹⁶` on a hit; with `gain = 2^(L + 15)/r`
    /// (`L` the raw radius's bit length, `cross_shift = L + 14`).
    pub cross_shift: u32,
    pub gain: u32,
    /// Whether `b = oc·D` grows along a row (`oc·step_x > 0`).
    pub b_rises: bool,
    /// `E′`, see above.
    pub e: Quadric,
    /// The rows and the columns on which `E′` can be at least 0, each `[start, end)` (see
    /// `outline`): the spans without the full-width kernel.
    #[cfg(not(feature = "full-width"))]
    pub rows: (u32, u32),
    #[cfg(not(feature = "full-width"))]
    pub columns: (u32, u32),
    /// The spheres within `4ε` of this one (bit `k` for sphere `k`; a sphere resting on a
    /// floor sphere, and the floor under it): only from these can a lifted point start
    /// inside a caster, which the caster test then checks for (`narrow_blocked`).
    pub touching: u32,
    /// The margin of the quick caster test (`narrow_blocked`) where this sphere receives a
    /// shadow, in that test's units ([`PreparedFixed::quick_shift`]): a bound on its
    /// rounding and on how far the exact test's `|oc|² − b² ≤ r²` reaches beyond the
    /// caster's cylinder, from the largest `|O − C_k|` the sphere's lifted points can have.
    /// `−1`: no quick test.
    pub quick_margin: i32,
}

/// A sphere's narrow constants for one light: `G` (see [`NarrowSphere`]) and a filter in
/// front of the caster tests.
///
/// The filter holds for the lifted origin `O = C + (r + ε)·N` of any caster `k` of the
/// sphere: the shadow ray can meet the caster only if `O` is behind it along `L`
/// (`N·L < −(C − C_k)·L/(r + ε)`) and if `O` can come within `r_k` of the caster's axis,
/// `C_k + s·L`: at a given `N·L`, `N`'s part across `L` has length `√(1 − (N·L)²)`, so that
/// needs `(N·L)² ≤ 1 − ((|Δ⊥| − r_k)/(r + ε))²` with `Δ⊥` the part of `C − C_k` across `L`.
/// `ahead` and `reach` are the loosest of these over the casters, widened by the fast
/// `N·L`'s error; a pixel outside them skips every caster test for the light.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct NarrowLight {
    pub g: Quadric,
    /// The light's arriving colour (U16F16 bits).
    pub arriving: [u32; 3],
    /// The spheres that can shadow the sphere from this light (bit `k` for sphere `k`, see
    /// `PreparedFixed::narrow_casters`).
    pub casters: u32,
    /// `N·L` (Q15) at or above this: no caster is ahead.
    pub ahead: i32,
    /// `(N·L)²` (Q30) above this: no caster is within reach.
    pub reach: u32,
    /// The sphere's centre across the light, `C·u` and `C·v` in the quick caster test's
    /// units ([`PreparedFixed::quick_shift`]), `u` and `v` the light's
    /// [`PreparedFixed::across`]: the quick caster test's constants.
    pub across: [i32; 2],
}

/// A sphere's per-frame constants, in scaled units.
///
/// `repr(C)` with the narrow kernel's per-pixel fields first: ARMv6-M's loads reach only
/// 124 bytes past a base register (62 for halfwords, 31 for bytes), and fields beyond that
/// cost the row loop an address computation each, which it keeps in stack slots.
#[derive(Clone, Copy, Debug)]
#[repr(C)]
pub(crate) struct FixedSphere {
    /// The narrow kernel's constants, if the frame uses it.
    pub narrow: Option<NarrowSphere>,
    pub kd_albedo: V3<U16F16>,
    pub ks: U16F16,
    pub shininess: Exact,
    pub blinn: bool,
    /// A normalized model (or Lambert): the kernel's `normalized` terms, not the classic ones.
    pub normalized: bool,
    #[cfg(feature = "full-width")]
    /// Schlick's factor applies.
    pub schlick: bool,
    #[cfg(feature = "full-width")]
    /// The diffuse lobe is multiplied by `1 − F`.
    pub diffuse_loss: bool,
    pub center: V3<Len>,
    /// `eye − centre`: the primary rays' origin offset.
    pub eye_offset: V3<Len>,
    pub radius_sq: I32F32,
    /// `1/r` of the raw radius bits, as [`inv_sqrt`] returns it: `y·2^-shift`. Only the
    /// full-width kernel reads it.
    #[cfg(feature = "full-width")]
    pub inv_radius: (u32, u32),
    #[cfg(feature = "full-width")]
    /// Normalized models: each lobe's weight times its normalization factor, exact.
    pub weight: [Exact; LOBES],
    #[cfg(feature = "full-width")]
    /// Exponents of lobes 1 and 2.
    pub more_shininess: [Exact; MORE_LOBES],
    #[cfg(feature = "full-width")]
    /// `F₀` per channel, U2F30 (`1 << 30` is 1).
    pub f0: [u32; 3],
    /// The sphere's spans: its screen rectangle and its outline's row conic; `None` if the
    /// sphere is off screen. (Without the full-width kernel, the spans are the narrow
    /// quadric's, see `outline`.)
    #[cfg(feature = "full-width")]
    pub bounds: Option<Bounds>,
    /// Oren–Nayar's `A` and `B` (U2F30), if the diffuse lobe is Oren–Nayar's.
    #[cfg(feature = "models")]
    pub oren_nayar: Option<[u32; 2]>,
    /// GGX's constants, if the specular lobe is GGX.
    #[cfg(feature = "models")]
    pub ggx: Option<FixedGgx>,
    /// The scaled radius: for the narrow kernel's prepare (its square is `radius_sq`) and
    /// the soft shadows of sphere lights.
    pub radius: Len,
    /// Per lobe (`shininess`, then `more_shininess`), the constants of its energy factor
    /// under a sphere light (`area::lobe_widening`): `√(πn′/2)` in U16F16 and `n′/2` in
    /// U20F12, saturating.
    #[cfg(all(feature = "area-lights", feature = "full-width"))]
    pub widening: [[u32; 2]; LOBES],
}

impl FixedSphere {
    /// Whether the lobe is Blinn-Phong's: always `false` in a build without the feature
    /// `blinn-phong` ([`BLINN_PHONG`]), whose scenes hold no such sphere, so that the kernels'
    /// half-vector code is left out.
    #[inline(always)]
    pub(crate) fn blinn(&self) -> bool {
        BLINN_PHONG && self.blinn
    }
}

/// A GGX sphere's constants (`α = roughness²`).
#[cfg(feature = "models")]
#[derive(Clone, Copy, Debug)]
#[cfg_attr(not(feature = "full-width"), allow(dead_code))]
pub(crate) struct FixedGgx {
    /// `α²`, U1F31.
    pub alpha2: u32,
    /// `1 − α²`, U1F31.
    pub one_minus_alpha2: u32,
    /// `ks·α²/(2π)`, the `f32` value exactly.
    pub scale: Exact,
    /// `α`, U1F31, for the widening under a sphere light.
    #[cfg(all(feature = "area-lights", feature = "full-width"))]
    pub alpha: u32,
}

/// A light's per-frame constants.
#[derive(Clone, Copy, Debug)]
pub(crate) enum FixedLight {
    /// `to_light`: unit vector toward the light; `arriving`: `colour·intensity`.
    Distant {
        to_light: V3<Unit>,
        arriving: V3<U16F16>,
    },
    /// `power`: `colour·intensity/4π` times the scale squared, per channel, exact; arriving
    /// is `power/d²` in scaled units. Only the full-width kernel reads them.
    #[cfg_attr(not(feature = "full-width"), allow(dead_code))]
    Point { position: V3<Len>, power: V3<Exact> },
    /// A sphere light (a point light with a radius, see `area`): `position` and `power` as
    /// for `Point`, and its scaled radius.
    #[cfg(all(feature = "area-lights", feature = "full-width"))]
    Sphere {
        position: V3<Len>,
        power: V3<Exact>,
        radius: Len,
    },
}

/// A scene prepared for the fixed-point path at one size: integers only per row and pixel.
///
/// ```
/// use shadeline::{exponent_series, PreparedFixed, Render, Rgb565};
/// let frame = PreparedFixed::new(&exponent_series()?, 64, 48)?;
/// let mut line = [Rgb565::default(); 64];
/// frame.render_line(24, &mut line)?;
/// assert_ne!(line[20], line[0]); // a sphere, then the background
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug)]
pub struct PreparedFixed<const S: usize = 16, const L: usize = 8> {
    pub(crate) width: u32,
    pub(crate) height: u32,
    pub(crate) eye: V3<Len>,
    /// Half a pixel to the right on the image plane `z = 1`: `right·tan(vfov/2)/h`.
    pub(crate) step_x: V3<I16F48>,
    /// Half a pixel up: `up·tan(vfov/2)/h`.
    pub(crate) step_y: V3<I16F48>,
    pub(crate) forward: V3<I16F48>,
    pub(crate) epsilon: Len,
    pub(crate) background: [u32; 3],
    pub(crate) spheres: heapless::Vec<FixedSphere, S>,
    pub(crate) lights: heapless::Vec<FixedLight, L>,
    /// Per sphere and light, the other spheres that can shadow it
    /// ([`Scene::shadow_casters`]), for the full-width kernel (the narrow kernel's are in
    /// `narrow_lights`).
    #[cfg(feature = "full-width")]
    pub(crate) casters: heapless::Vec<[u32; L], S>,
    /// The kernel the rows take, with the reason if not the narrow one
    /// (`prepare_narrow_or_refuse`). Without the full-width kernel every frame is a narrow
    /// one, and [`PreparedFixed::kernel`] says so without a field.
    #[cfg(feature = "full-width")]
    pub(crate) kernel: Kernel,
    /// The primary directions in the narrow kernel's form, if the frame uses it: `Some`
    /// exactly when the kernel is [`Kernel::Narrow`] (in a prepared frame).
    pub(crate) narrow: Option<NarrowView>,
    /// Per sphere and light, the narrow kernel's constants (set with `narrow`).
    pub(crate) narrow_lights: heapless::Vec<[NarrowLight; L], S>,
    /// Per distant light, two unit vectors `u`, `v` (Q15) across it, `L`, `u`, `v` an
    /// orthonormal basis up to rounding: the quick caster test measures a lifted point's
    /// distance from a caster's axis along the light in them (set with `narrow`).
    pub(crate) across: [[[i16; 3]; 2]; L],
    /// The quick caster test's unit of length, `2^quick_shift` raw: the smallest that
    /// takes every sphere's `r + ε` below `2¹⁶` units (set with `narrow`).
    pub(crate) quick_shift: u32,
    pub(crate) use_spans: bool,
    /// Whether silhouettes are anti-aliased ([`PreparedFixed::with_antialiasing`]).
    #[cfg(all(feature = "antialias", feature = "full-width"))]
    pub(crate) antialias: bool,
}

/// A lobe's constants for `area::lobe_widening`, from its exponent `n` (`n′ = n`, or `n/4`
/// for Blinn-Phong): `[√(πn′/2)` in U16F16, `n′/2` in U20F12`]`, saturating (0 for `n = 0`).
#[cfg(all(feature = "area-lights", feature = "full-width"))]
fn widening(n: f32, blinn: bool) -> [u32; 2] {
    let n = if blinn { n * 0.25 } else { n };
    let a = libm::sqrtf(core::f32::consts::FRAC_PI_2 * n);
    [fixed_bits_u32(a, 16), fixed_bits_u32(0.5 * n, 12)].map(|b| b.unwrap_or(u32::MAX))
}

fn out_of_range(item: Item, field: &'static str) -> RenderError {
    RenderError::OutOfFixedRange {
        item,
        field,
        beside: None,
    }
}

/// The refusal of sphere `sphere`, whose radius is below `2⁻¹³` of the scene's extent: it also
/// names the largest sphere (a floor sphere, say) when that is another and reaches at least
/// half as far as the camera, so that its size is what sets the extent. In integers: a
/// finite `f32`'s magnitude orders as its bits, and doubling it adds `2²³` to them. Out of
/// line: only refused scenes reach it.
#[inline(never)]
fn small_beside_extent<const S: usize, const L: usize>(
    scene: &Scene<S, L>,
    sphere: usize,
) -> RenderError {
    let magnitude = |v: f32| v.to_bits() & 0x7fff_ffff;
    let eye = scene.camera().position;
    let camera = magnitude(eye.x).max(magnitude(eye.y)).max(magnitude(eye.z));
    let (mut largest, mut beside) = (0, None);
    for (i, s) in scene.spheres().iter().enumerate() {
        if magnitude(s.radius) > largest {
            largest = magnitude(s.radius);
            beside = u16::try_from(i).ok();
        }
    }
    if beside.map(usize::from) == Some(sphere) || largest + (1 << 23) < camera {
        beside = None;
    }
    RenderError::OutOfFixedRange {
        item: Item::Sphere(sphere),
        field: "radius",
        beside,
    }
}

/// `v·scale` per component in fixed point with `frac` fraction bits ([`fixed_bits`]), if
/// each is within `lo..=hi`. Out of line: every point, colour and direction of the prepare
/// goes through it.
#[inline(never)]
fn scaled_bits(v: [f32; 3], scale: f32, frac: u32, (lo, hi): (i64, i64)) -> Option<[i64; 3]> {
    let mut out = [0i64; 3];
    for (o, c) in out.iter_mut().zip(v) {
        *o = fixed_bits(c * scale, frac).filter(|b| (lo..=hi).contains(b))?;
    }
    Some(out)
}

fn to_len(v: Vec3, scale: f32, item: Item, field: &'static str) -> Result<V3<Len>, RenderError> {
    let range = (i32::MIN as i64, i32::MAX as i64);
    scaled_bits([v.x, v.y, v.z], scale, 16, range)
        .map(|b| b.map(|c| Len::from_bits(c as i32)))
        .ok_or(out_of_range(item, field))
}

fn to_wide(v: Vec3, scale: f32) -> Result<V3<I16F48>, RenderError> {
    scaled_bits([v.x, v.y, v.z], scale, 48, (i64::MIN, i64::MAX))
        .map(|b| b.map(I16F48::from_bits))
        .ok_or(out_of_range(Item::Camera, "vfov"))
}

/// The I2F30 unit vector of `d`, a unit vector in `f32` (within `2⁻²³` of unit length):
/// its components rounded to 30 bits (each at most about 1, which I2F30 holds: no
/// saturation is needed, and a component that did not convert, which no unit vector has,
/// would read as 0), then one Newton step toward unit length, `v·(1 − ε/2)` for
/// `|v|² = 1 + ε`, which leaves it within `2⁻⁴⁰` of unit length before the components'
/// rounding. Exact integer arithmetic after the conversion, so the same bits on every
/// target; a few products instead of the general normalization, for a vector already
/// within a few ulps of unit length. Inlined on ARMv6-M, where its caller is too (see
/// `prepare_fields`): smaller there.
#[cfg_attr(shadeline_short_mul, inline(always))]
#[cfg_attr(not(shadeline_short_mul), inline(never))]
fn unit_q30(d: Vec3) -> V3<Unit> {
    let v = [d.x, d.y, d.z].map(|c| fixed_bits_i32(c, 30).unwrap_or(0));
    let len2 = dot_ii(v, v);
    // ε = |v|² − 1 in Q60 (|ε| < 2⁻²¹: the f32 vector's rounding and the 30-bit one), then
    // ε/2 in Q51, which holds |ε| < 2⁻²⁰ in an i32; c·ε/2 is then below 2⁶⁰.
    let half_eps = ((len2 - (1 << 60)) >> 10).clamp(-(1 << 30), 1 << 30) as i32;
    // |c·ε/2| < 2¹⁰ and |c| ≤ 2³⁰: the difference fits I2F30.
    v.map(|c| Unit::from_bits(c - (mul_ii(c, half_eps) >> 51) as i32))
}

/// Per-channel levels checked against [`MAX_LEVEL`]: U16F16 bits up to `MAX_LEVEL·2¹⁶`,
/// which is where the `f32` levels up to `MAX_LEVEL` round to (the next `f32` above it,
/// `MAX_LEVEL + 2⁻⁹`, rounds above). A scene's colours and factors are checked
/// non-negative, and so are their products; a negative level is refused all the same,
/// unless it rounds to zero.
fn to_levels(c: [f32; 3], item: Item, field: &'static str) -> Result<V3<U16F16>, RenderError> {
    const MAX_BITS: i64 = (MAX_LEVEL as i64) << 16;
    scaled_bits(c, 1.0, 16, (0, MAX_BITS))
        .map(|b| b.map(|c| U16F16::from_bits(c as u32)))
        .ok_or(out_of_range(item, field))
}

/// `2^k` as an `f32`, for `k` in `-126..=127`.
fn pow2(k: i32) -> f32 {
    f32::from_bits(((k + 127).clamp(1, 254) as u32) << 23)
}

/// The power of two `k` such that the scene's extent times `2^k` is below `2^EXTENT_LOG2`
/// units, as large as possible up to [`MAX_SCALE_LOG2`].
fn scale_log2<const S: usize, const L: usize>(scene: &Scene<S, L>) -> i32 {
    let extent = scene.extent();
    // extent = f·2^e with f in [½, 1): extent·2^(EXTENT_LOG2 − e) < 2^EXTENT_LOG2.
    let (_, e) = libm::frexpf(extent);
    (EXTENT_LOG2 - e).min(MAX_SCALE_LOG2)
}

impl<const S: usize, const L: usize> PreparedFixed<S, L> {
    /// Prepares `scene` for a `width × height` image on the fixed path.
    ///
    /// Fails with [`RenderError::BadSize`] like [`Prepared::new`](crate::Prepared::new), and
    /// with [`RenderError::OutOfFixedRange`] if a number does not fit the fixed formats (see
    /// the [module table](crate::fixed)): a sphere smaller than `2⁻¹³` of the scene's extent
    /// (`radius`), a field of view or aspect ratio with `tan(vfov/2)·max(1, w/h)` above
    /// [`MAX_PLANE_SCALE`] (`vfov`), and `kd·albedo`, `ks`, or a distant light's
    /// `colour·intensity` above [`MAX_LEVEL`] in a channel (`kd`, `ks`, `intensity`).
    pub fn new(scene: &Scene<S, L>, width: u32, height: u32) -> Result<Self, RenderError> {
        let mut frame = Self::EMPTY;
        frame.prepare(scene, width, height)?;
        Ok(frame)
    }

    /// A frame with no size and no spheres, to [`prepare`](Self::prepare) into: a constant,
    /// so that a firmware can keep its prepared frame in a `static` and prepare it there.
    /// Rendering it fails with a typed error: it has no rows.
    pub const EMPTY: Self = Self {
        width: 0,
        height: 0,
        eye: [Len::ZERO; 3],
        step_x: [I16F48::ZERO; 3],
        step_y: [I16F48::ZERO; 3],
        forward: [I16F48::ZERO; 3],
        epsilon: Len::ZERO,
        background: [0; 3],
        spheres: heapless::Vec::new(),
        lights: heapless::Vec::new(),
        #[cfg(feature = "full-width")]
        casters: heapless::Vec::new(),
        #[cfg(feature = "full-width")]
        kernel: Kernel::Narrow,
        narrow: None,
        narrow_lights: heapless::Vec::new(),
        across: [[[0; 3]; 2]; L],
        quick_shift: 0,
        use_spans: true,
        #[cfg(all(feature = "antialias", feature = "full-width"))]
        antialias: false,
    };

    /// Prepares `scene` for a `width × height` image into `self`, in place: what [`new`](Self::new)
    /// returns, without the prepared frame ever being on the stack (the M0 firmware prepares its
    /// `static` frame this way). Fails like `new`; on an error
    /// `self` is left [`EMPTY`](Self::EMPTY), never half prepared. Spans are on, whatever
    /// [`with_spans`](Self::with_spans) set before.
    ///
    /// ```
    /// use shadeline::{exponent_series_with_capacity, PreparedFixed, Render, Rgb565, Scene};
    /// // In a firmware this is a `static`, prepared again whenever the scene moves.
    /// let mut frame = PreparedFixed::<5, 1>::EMPTY;
    /// let scene: Scene<5, 1> = exponent_series_with_capacity()?;
    /// frame.prepare(&scene, 64, 48)?;
    /// let mut line = [Rgb565::default(); 64];
    /// frame.render_line(24, &mut line)?;
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn prepare(
        &mut self,
        scene: &Scene<S, L>,
        width: u32,
        height: u32,
    ) -> Result<(), RenderError> {
        // Two calls in turn, not one inside the other: the narrow set-up's stack does not
        // add to the conversion's (the M0 firmware's peak stack is the prepare's).
        let result = self
            .prepare_fields(scene, width, height)
            .and_then(|corners| self.prepare_narrow_or_refuse(scene, corners));
        if result.is_err() {
            self.clear();
        }
        result
    }

    /// Resets `self` to [`EMPTY`](Self::EMPTY) field by field (no temporary frame).
    fn clear(&mut self) {
        self.width = 0;
        self.height = 0;
        self.spheres.clear();
        self.lights.clear();
        #[cfg(feature = "full-width")]
        self.casters.clear();
        #[cfg(feature = "full-width")]
        {
            self.kernel = Kernel::Narrow;
        }
        self.narrow = None;
        self.narrow_lights.clear();
        self.use_spans = true;
        #[cfg(all(feature = "antialias", feature = "full-width"))]
        {
            self.antialias = false;
        }
    }

    /// Converts the scene into `self`'s fields (all but the narrow kernel's), and says
    /// whether every primary direction is within `√2` of the central one in length and the
    /// steps below ½, which the narrow kernel needs (see [`Self::prepare_narrow`]).
    /// Inlined into [`Self::prepare`] on ARMv6-M, where that is smaller at the same peak
    /// stack; out of line elsewhere: inlined, it is copied to every place a firmware prepares
    /// a frame (`docs/performance.md, "Choices measured"`).
    #[cfg_attr(shadeline_short_mul, inline(always))]
    #[cfg_attr(not(shadeline_short_mul), inline(never))]
    fn prepare_fields(
        &mut self,
        scene: &Scene<S, L>,
        width: u32,
        height: u32,
    ) -> Result<bool, RenderError> {
        self.clear();
        if width == 0 || height == 0 || width > MAX_DIMENSION || height > MAX_DIMENSION {
            return Err(RenderError::BadSize { width, height });
        }
        // A scene holds a sphere light only with `area-lights`; the fixed path shades it in
        // its full-width kernel.
        #[cfg(all(feature = "area-lights", not(feature = "full-width")))]
        if let Some(light) = scene.sphere_light() {
            return Err(RenderError::SphereLight { light });
        }
        let camera = scene.camera();
        let (right, up, forward) = scene.camera_basis();
        let tan = camera.tan_half_fov();
        let (width_f, height_f) = (width as f32, height as f32);
        let x_scale = (width_f / height_f) * tan;
        if !(tan <= MAX_PLANE_SCALE && x_scale <= MAX_PLANE_SCALE) {
            return Err(out_of_range(Item::Camera, "vfov"));
        }
        let half_pixel = tan / height_f;
        // The narrow kernel's view (see `prepare_narrow`). The corners' directions are the
        // longest: `|d|² = 1 + (dx² + dy²)·half_pixel²` for the orthonormal basis, at the
        // half-pixel offsets `dx = w − 1`, `dy = h − 1`. At most 2 less `2⁻⁸`: the steps'
        // rounding to Q29 (within `2⁻³⁰`, times offsets up to `2¹⁶`) and the basis' and this
        // sum's `f32` rounding move the narrow kernel's integer `|d|²` by less than `2⁻¹⁰`,
        // so it stays below 2. And the steps below ½ (a one-pixel-wide image leaves
        // `step_x` unbounded by the corners), so that in Q29 each component of a step, at
        // most `half_pixel` (`1 + 2⁻²²` with the basis' rounding), and twice it fit `i32`.
        let (dx, dy) = (width_f - 1.0, height_f - 1.0);
        let corners = (dx * dx + dy * dy) * half_pixel * half_pixel <= 1.0 - 1.0 / 256.0
            && half_pixel < 0.499;

        let k = scale_log2(scene);
        let scale = pow2(k);
        let eye = to_len(camera.position, scale, Item::Camera, "position")?;
        let epsilon = fixed_bits_i32(scene.ray_epsilon() * scale, 16)
            .map(Len::from_bits)
            .ok_or(out_of_range(Item::Camera, "position"))?;
        #[cfg(feature = "full-width")]
        let view = View {
            eye: camera.position,
            right,
            up,
            forward,
            half_pixel,
            width,
            height,
        };

        for (i, s) in scene.spheres().iter().enumerate() {
            let item = Item::Sphere(i);
            let m = &s.material;
            let center = to_len(s.center, scale, item, "center")?;
            let radius = fixed_bits_i32(s.radius * scale, 16)
                .map(Len::from_bits)
                .ok_or(out_of_range(item, "radius"))?;
            if radius < MIN_SCALED_RADIUS {
                return Err(small_beside_extent(scene, i));
            }
            let radius_raw = radius.to_bits() as i64;
            #[cfg(feature = "full-width")]
            let inv_radius =
                inv_sqrt((radius_raw * radius_raw) as u64).ok_or(out_of_range(item, "radius"))?;
            // The float paths' constants (`kd·albedo`, or `kd·albedo/π`; `ks`, or 1 for the
            // normalized models; normalization factors; F₀), converted to fixed formats.
            // Without the full-width kernel only the classic models render: the others are
            // refused here, before their constants are computed (and their code is linked).
            #[cfg(feature = "full-width")]
            let params = Params::<f32>::of(m);
            #[cfg(not(feature = "full-width"))]
            let params = match m.model {
                Model::Phong | Model::BlinnPhong => Params::<f32>::classic(m),
                Model::Lambert => Params::<f32>::lambert(m),
                _ => {
                    return Err(RenderError::NeedsFullWidth {
                        item,
                        field: "model",
                    })
                }
            };
            let kd_albedo = params.kd_albedo;
            let kd_albedo = to_levels([kd_albedo.x, kd_albedo.y, kd_albedo.z], item, "kd")?;
            let [ks, _, _] = to_levels([params.ks, 0.0, 0.0], item, "ks")?;
            #[cfg(any(feature = "full-width", feature = "models"))]
            let unit = |v: f32| (v.clamp(0.0, 1.0) * (1u32 << 30) as f32) as u32;
            let sphere = FixedSphere {
                center,
                eye_offset: each3(|c| eye[c] - center[c]),
                radius_sq: I32F32::from_bits(radius_raw * radius_raw),
                #[cfg(feature = "full-width")]
                inv_radius,
                kd_albedo,
                ks,
                shininess: Exact::from_f32(m.shininess),
                blinn: params.blinn > 0.0,
                normalized: params.normalized > 0.0,
                #[cfg(feature = "full-width")]
                weight: params.weight.map(Exact::from_f32),
                #[cfg(feature = "full-width")]
                more_shininess: params.more_shininess.map(Exact::from_f32),
                #[cfg(feature = "full-width")]
                f0: [params.f0.x, params.f0.y, params.f0.z].map(unit),
                #[cfg(feature = "full-width")]
                schlick: params.schlick > 0.0,
                #[cfg(feature = "full-width")]
                diffuse_loss: params.diffuse_loss > 0.0,
                #[cfg(feature = "full-width")]
                bounds: view.bounds(s.center, s.radius),
                narrow: None,
                #[cfg(feature = "models")]
                oren_nayar: (params.oren_nayar > 0.0)
                    .then(|| [unit(params.on_a), unit(params.on_b)]),
                #[cfg(feature = "models")]
                ggx: (params.ggx > 0.0).then(|| {
                    let u1f31 = |v: f32| (v.clamp(0.0, 1.0) * (1u64 << 31) as f32) as u32;
                    FixedGgx {
                        alpha2: u1f31(params.alpha2),
                        one_minus_alpha2: u1f31(1.0 - params.alpha2),
                        scale: Exact::from_f32(
                            params.weight[0] * params.alpha2 / (2.0 * core::f32::consts::PI),
                        ),
                        #[cfg(all(feature = "area-lights", feature = "full-width"))]
                        alpha: u1f31(libm::sqrtf(params.alpha2)),
                    }
                }),
                radius,
                #[cfg(all(feature = "area-lights", feature = "full-width"))]
                widening: {
                    let exponents = [
                        m.shininess,
                        params.more_shininess[0],
                        params.more_shininess[1],
                    ];
                    exponents.map(|e| widening(e, params.blinn > 0.0))
                },
            };
            // Same capacity as the scene: cannot fail.
            let pushed = self.spheres.push(sphere);
            debug_assert!(pushed.is_ok(), "sphere {i} beyond the prepared capacity");
        }

        for (i, l) in scene.lights().iter().enumerate() {
            let item = Item::Light(i);
            let light = match *l {
                Light::Distant {
                    direction,
                    color,
                    intensity,
                } => {
                    let arriving = Vec3::new(color.r, color.g, color.b).scale(intensity);
                    // Validated: a scene's light direction is finite and not zero.
                    let d = (-direction)
                        .normalized()
                        .ok_or(out_of_range(item, "direction"))?;
                    FixedLight::Distant {
                        to_light: unit_q30(d),
                        arriving: to_levels(
                            [arriving.x, arriving.y, arriving.z],
                            item,
                            "intensity",
                        )?,
                    }
                }
                #[cfg(not(feature = "full-width"))]
                Light::Point { .. } => {
                    return Err(RenderError::NeedsFullWidth {
                        item,
                        field: "type",
                    })
                }
                #[cfg(feature = "full-width")]
                Light::Point {
                    position,
                    color,
                    intensity,
                    radius,
                } => {
                    let power = Vec3::new(color.r, color.g, color.b)
                        .scale(intensity / (4.0 * core::f32::consts::PI))
                        .scale(pow2(2 * k));
                    let power = [power.x, power.y, power.z];
                    if !power.iter().all(|p| p.is_finite()) {
                        return Err(out_of_range(item, "intensity"));
                    }
                    let position = to_len(position, scale, item, "position")?;
                    let power = power.map(Exact::from_f32);
                    #[cfg(feature = "area-lights")]
                    if radius > 0.0 {
                        let radius = fixed_bits_i32(radius * scale, 16)
                            .filter(|r| *r > 0)
                            .map(Len::from_bits)
                            .ok_or(out_of_range(item, "radius"))?;
                        let pushed = self.lights.push(FixedLight::Sphere {
                            position,
                            power,
                            radius,
                        });
                        debug_assert!(pushed.is_ok(), "light {i} beyond the prepared capacity");
                        continue;
                    }
                    let _ = radius;
                    FixedLight::Point { position, power }
                }
            };
            // Same capacity as the scene: cannot fail.
            let pushed = self.lights.push(light);
            debug_assert!(pushed.is_ok(), "light {i} beyond the prepared capacity");
        }

        #[cfg(feature = "full-width")]
        for i in 0..scene.spheres().len() {
            let mut per_light = [0u32; L];
            for (mask, light) in per_light.iter_mut().zip(scene.lights()) {
                *mask = scene.shadow_casters(i, light);
            }
            // Same capacity as the scene: cannot fail.
            let pushed = self.casters.push(per_light);
            debug_assert!(
                pushed.is_ok(),
                "casters of sphere {i} beyond the prepared capacity"
            );
        }

        let bg = scene.background();
        self.step_x = to_wide(right, half_pixel)?;
        self.step_y = to_wide(up, half_pixel)?;
        self.forward = to_wide(forward, 1.0)?;
        self.width = width;
        self.height = height;
        self.eye = eye;
        self.epsilon = epsilon;
        // Saturating, like `saturating_from_num`, but without its panic on NaN.
        self.background = [bg.r, bg.g, bg.b].map(|c| {
            let saturated = if c < 0.0 { U16F16::MIN } else { U16F16::MAX };
            fixed_bits_u32(c, 16)
                .map_or(saturated, U16F16::from_bits)
                .to_bits()
        });
        Ok(corners)
    }

    /// [`Self::prepare_narrow`], and without the full-width kernel the refusal of a frame the
    /// narrow kernel does not take.
    fn prepare_narrow_or_refuse(
        &mut self,
        scene: &Scene<S, L>,
        corners: bool,
    ) -> Result<(), RenderError> {
        let narrow = self.prepare_narrow(scene, corners);
        #[cfg(not(feature = "full-width"))]
        if let Err((item, field)) = narrow {
            return Err(RenderError::NeedsFullWidth { item, field });
        }
        #[cfg(feature = "full-width")]
        {
            self.kernel = match narrow {
                Ok(()) => Kernel::Narrow,
                Err((item, field)) => Kernel::General { item, field },
            };
        }
        Ok(())
    }

    /// [`Render::kernel`](crate::Render::kernel) of this frame: without the feature
    /// `full-width` always [`Kernel::Narrow`], every other frame being refused.
    #[inline(always)]
    pub(crate) fn chosen_kernel(&self) -> Kernel {
        #[cfg(feature = "full-width")]
        return self.kernel;
        #[cfg(not(feature = "full-width"))]
        Kernel::Narrow
    }

    /// Sets up the narrow kernel ([`super::narrow`]) if the frame meets its conditions, or
    /// says which item and field keep it from them (the first found). `corners`: whether
    /// every primary direction is within `√2` of the central one in length (then
    /// `|D| < 2³⁰` and every narrow format holds) and the steps below ½, from
    /// [`Self::prepare_fields`]. Inlined into its one caller on ARMv6-M (smaller there),
    /// out of line elsewhere, like `prepare_fields` and for the same reason.
    #[cfg_attr(shadeline_short_mul, inline(always))]
    #[cfg_attr(not(shadeline_short_mul), inline(never))]
    fn prepare_narrow(
        &mut self,
        scene: &Scene<S, L>,
        corners: bool,
    ) -> Result<(), (Item, &'static str)> {
        // Without the full-width kernel `prepare_fields` has refused these already.
        #[cfg(feature = "full-width")]
        if let Some(light) = self
            .lights
            .iter()
            .position(|l| !matches!(l, FixedLight::Distant { .. }))
        {
            return Err((Item::Light(light), "type"));
        }
        // Lambert shades as a classic sphere with no lobe (`Params::lambert`, and no cutoff
        // below); the other normalized models need the full-width kernel.
        #[cfg(feature = "full-width")]
        if let Some(sphere) = self
            .spheres
            .iter()
            .zip(scene.spheres())
            .position(|(s, m)| s.normalized && !matches!(m.material.model, Model::Lambert))
        {
            return Err((Item::Sphere(sphere), "model"));
        }
        // The narrow run indexes its tracks by `u8`.
        if self.spheres.len() > 256 {
            return Err((Item::Sphere(256), "center"));
        }
        if !corners {
            return Err((Item::Camera, "vfov"));
        }
        // D = forward + dy·step_y + dx·step_x at 2²⁹ for the unit forward vector: each
        // component of `forward` at most 2²⁹ and of a step below 2²⁸ (`corners`).
        let view = NarrowView {
            forward: to_q29(self.forward),
            step_x: to_q29(self.step_x),
            step_y: to_q29(self.step_y),
        };
        // Each light's brightest channel, the largest level converted (the conversion is
        // monotonic, so it is the largest of the converted levels).
        let intensity: f32 = self
            .lights
            .iter()
            .map(|l| match l {
                FixedLight::Distant { arriving, .. } => {
                    let brightest = arriving.iter().map(|c| c.to_bits()).max().unwrap_or(0);
                    to_f32(brightest as i64, 16)
                }
                // Never reached: the narrow kernel takes distant lights only (checked above).
                _ => 0.0,
            })
            .sum();
        // The Gram matrix of the quadrics' three directions, in the order of `PAIRS`: the
        // same for every sphere.
        let dirs = view.dirs();
        let gram = PAIRS.map(|(a, b)| dot_ii(dirs[a % 3], dirs[b % 3]));
        let eps = self.epsilon.to_bits() as i64;
        let lift = self.spheres.iter().map(|s| s.radius.to_bits() as i64 + eps);
        self.quick_shift = 64u32.saturating_sub(lift.max().unwrap_or(0).leading_zeros() + 16);
        for (across, light) in self.across.iter_mut().zip(&self.lights) {
            if let FixedLight::Distant { to_light, .. } = light {
                *across = across_light(to_light.map(|c| c.to_bits()));
            }
        }
        self.narrow_lights.clear();
        for i in 0..self.spheres.len() {
            let m = scene.spheres().get(i).map(|s| s.material);
            let n = m.map_or(1.0, |m| m.shininess);
            // A Lambert sphere has no lobe: no light's `h` is below a cutoff of 0.
            let intensity = match m {
                Some(m) if matches!(m.model, Model::Lambert) => 0.0,
                _ => intensity,
            };
            self.prepare_narrow_sphere(i, (&view, &gram), (n, intensity))
                .map_err(|field| (Item::Sphere(i), field))?;
        }
        self.narrow = Some(view);
        Ok(())
    }

    /// Sphere `i`'s narrow constants, from the frame's narrow view and its shininess `n`
    /// and the sum of the lights' brightest channels: `false` if the sphere does not meet
    /// the narrow kernel's conditions or a number does not fit. Out of line (and the
    /// quadrics' arithmetic further out) to keep the prepare's stack small.
    #[inline(never)]
    fn prepare_narrow_sphere(
        &mut self,
        i: usize,
        (view, gram): (&NarrowView, &[i64; 6]),
        (n, intensity): (f32, f32),
    ) -> Result<(), &'static str> {
        let Some(s) = self.spheres.get(i) else {
            return Err("center");
        };
        let (eye_offset, ks) = (s.eye_offset, s.ks);
        let eps = self.epsilon.to_bits() as i64;
        let oc = eye_offset.map(|c| c.to_bits() as i64);
        let r = s.radius.to_bits() as i64;
        // |oc|² < 3·2⁶⁰: the scene lies within 2¹³ units.
        let oc_len2 = oc.iter().map(|&c| mul_ii(c as i32, c as i32)).sum::<i64>();
        if oc_len2 <= (r + 2 * eps) * (r + 2 * eps) {
            return Err("center");
        }
        // ⌈log₂ max(1, |ô|²)⌉: below 28, since the scene lies within 2¹³ units and r ≥ 1
        // unit.
        let r2 = mul_ii(r as i32, r as i32);
        let ratio = (oc_len2 + r2 - 1).checked_div(r2).unwrap_or(0).max(1) as u64;
        let log_sq = 64 - (ratio - 1).leading_zeros();
        let e_shift = 29u32.saturating_sub(log_sq);
        let g_shift = 28u32.saturating_sub(log_sq.div_ceil(2));
        // Scale 2^(29 + e_shift)/(r²·2⁵⁸); G's 2^(29 + g_shift)/(r·2⁸⁸).
        let (e_den, g_den) = (
            Divisor {
                d: r as u32,
                passes: 2,
                z: 29 - e_shift,
            },
            Divisor {
                d: r as u32,
                passes: 1,
                z: 59 - g_shift,
            },
        );
        // The quadrics over D = dc + x·sx + y·sy, expanded at the centre of the screen
        // (`dx = dy = 0`), from b = oc·D in each direction (see `Form`).
        let oc32 = eye_offset.map(|c| c.to_bits());
        let b = view.dirs().map(|d| dot_ii(oc32, d));
        let mut e = Quadric::default();
        if quadric((r2 - oc_len2, gram, &b), Form::E, &e_den, &mut e).is_none() {
            return Err("radius");
        }
        if self
            .narrow_lights
            .push([NarrowLight::default(); L])
            .is_err()
        {
            return Err("radius");
        }
        for light_index in 0..self.lights.len().min(L) {
            let light = self.narrow_light(i, light_index, (view, gram, &b), &g_den)?;
            match self
                .narrow_lights
                .get_mut(i)
                .and_then(|l| l.get_mut(light_index))
            {
                Some(slot) => *slot = light,
                None => return Err("center"),
            }
        }
        let bits = 64 - r.leading_zeros();
        let (rf, ef) = (r as f32, eps as f32);
        let ks_intensity = to_f32(ks.to_bits() as i64, 16) * intensity;
        let cutoff = lobe_cutoff(ks_intensity, n);
        // The fast lobe's error, in levels of the brightest channel: its slope
        // n·(1 − h)^(n − 1) times h's error, and the narrow `pow`'s own (module `narrow`).
        // The slope is at most n (at h = 0), and at most 2n times the lobe where h ≤ ½.
        // Above n = 256, the range the `pow`'s bound of 1.4·10⁻⁴ is held on, every pixel
        // below the cutoff takes the precise lobe.
        let budget = 0.5 / (ks_intensity * 255.0) - 1.4e-4;
        let fast_lobe_max = if n > 256.0 || budget.is_nan() || budget <= 0.0 {
            0
        } else if n * H_ERROR <= budget {
            u32::MAX
        } else {
            ((budget / (2.0 * n * H_ERROR)) * 65536.0) as u32
        };
        let narrow = NarrowSphere {
            quick_margin: self.quick_margin(i),
            touching: self.touching(i),
            fast_lobe_max,
            shadow_limit: (ef * (2.0 * rf + ef) / ((rf + ef) * (rf + ef)) * (1u64 << 30) as f32)
                as u32,
            cutoff,
            e_shift,
            g_shift,
            cross_shift: bits + 14,
            gain: (1u64 << (bits + 15)).checked_div(r as u64).unwrap_or(0) as u32,
            b_rises: b[1] > 0,
            #[cfg(not(feature = "full-width"))]
            rows: outline_rows(&e, self.height),
            #[cfg(not(feature = "full-width"))]
            columns: outline_columns(&e, self.width),
            e,
        };
        match self.spheres.get_mut(i) {
            Some(s) => s.narrow = Some(narrow),
            None => return Err("center"),
        }
        Ok(())
    }

    /// [`NarrowSphere::quick_margin`] of sphere `i`, in the quick test's units (`2^s` raw,
    /// `s` the frame's `quick_shift`): with `Ω` the largest `|O − C_k|` over its lifted
    /// points `O` and the casters `k` (at most the largest distance of centres plus
    /// `r + ε`), `17 + Ω·2⁻¹¹ + 2√(2Ω + 1)`, each in units. The quick test's own rounding
    /// is below 10 units; `u` and `v` are within `2⁻¹⁴` of an exact basis across the
    /// light, which moves a distance by `Ω·2⁻¹⁴`; and the exact test's `b`, rounded down to
    /// a raw unit, and `|L|`'s distance from 1 let it block a ray up to
    /// `√(2Ω + 1) + Ω·2⁻¹⁴` raw beyond the caster's radius. Each term is doubled or more.
    /// `−1` where the test is off or the radius too large for its units.
    fn quick_margin(&self, i: usize) -> i32 {
        let Some(own) = self.spheres.get(i) else {
            return -1;
        };
        let lift = own.radius.to_bits() as i64 + self.epsilon.to_bits() as i64;
        let shift = self.quick_shift;
        if !QUICK_CASTER_TEST || lift >> shift >= 1 << 16 {
            return -1;
        }
        // Only a receiver four times the radius of each of its casters (a floor under the
        // spheres resting on it) takes the test: most of its pixels lie far from every
        // caster's cylinder, where the test saves the exact one; on spheres of like sizes
        // it costs more than it saves.
        let casters = self
            .narrow_lights
            .get(i)
            .map_or(0, |l| l.iter().fold(0, |m, l| m | l.casters));
        let mut far = 0u64;
        for (k, s) in self.spheres.iter().enumerate() {
            if k < 32 && casters & (1 << k) != 0 && s.radius.to_bits() > own.radius.to_bits() / 4 {
                return -1;
            }
            let d = each3(|j| own.center[j].to_bits().wrapping_sub(s.center[j].to_bits()));
            far = far.max(d.iter().map(|&v| mul_ii(v, v) as u64).sum::<u64>());
        }
        // Centres within 2³⁰ raw of each other: Ω below 2³¹.
        let omega = sqrt(far) + 1 + lift as u64;
        let root = sqrt(2 * omega + 1) + 1;
        (16 + ((omega >> shift) >> 11) + ((2 * root) >> shift) + 1).min(i32::MAX as u64) as i32
    }

    /// The spheres whose surface comes within `4ε` of sphere `i`'s (bit `k` for sphere `k`,
    /// the first 32), from the exact squared distance of the centres.
    fn touching(&self, i: usize) -> u32 {
        let Some(own) = self.spheres.get(i) else {
            return 0;
        };
        let eps = self.epsilon.to_bits() as i64;
        let mut mask = 0;
        for (k, s) in self.spheres.iter().enumerate().take(32) {
            let d = each3(|j| own.center[j].to_bits().wrapping_sub(s.center[j].to_bits()));
            let len2 = d.iter().map(|&v| mul_ii(v, v)).sum::<i64>();
            // Radii below 2²⁹ raw and ε far below: the sum fits an `i32`.
            let apart = (own.radius.to_bits() as i64 + s.radius.to_bits() as i64 + 4 * eps)
                .min(i32::MAX as i64) as i32;
            if k != i && len2 <= mul_ii(apart, apart) {
                mask |= 1 << k;
            }
        }
        mask
    }

    /// Sphere `i`'s narrow constants for light `light`, from the frame's narrow view, the
    /// Gram matrix of its three directions and their dot products `b` with the sphere's eye
    /// offset (see [`quadric`]); the field that keeps the sphere from the narrow kernel if
    /// the light is not distant, `G` does not fit (`radius`) or a caster is too close
    /// (`center`, see [`Self::narrow_casters`]). Inlined into the sphere's: its one caller,
    /// and smaller on the M0 (the peak stack the same).
    #[inline(always)]
    fn narrow_light(
        &self,
        i: usize,
        light: usize,
        (view, gram, b): (&NarrowView, &[i64; 6], &[i64; 3]),
        g_den: &Divisor,
    ) -> Result<NarrowLight, &'static str> {
        let Some(FixedLight::Distant { to_light, arriving }) = self.lights.get(light) else {
            return Err("radius");
        };
        let Some(own) = self.spheres.get(i) else {
            return Err("center");
        };
        let l = to_light.map(|c| c.to_bits());
        let oc_l = dot_ii(own.eye_offset.map(|c| c.to_bits()), l);
        let mut g = Quadric::default();
        let ld = view.dirs().map(|d| dot_ii(l, d));
        quadric((oc_l, gram, b), Form::G(&ld), g_den, &mut g).ok_or("radius")?;
        let (casters, ahead, reach) = self.narrow_casters(i, *to_light).ok_or("center")?;
        let shift = 15 + self.quick_shift;
        let across = self.across.get(light).map_or([0; 2], |uv| {
            // C·u in raw units times 2¹⁵ (|C| < 2³⁰ raw), to the quick test's units.
            uv.map(|u| {
                let c = own.center.map(|c| c.to_bits());
                ((dot_ii(c, u.map(i32::from)) + (1 << (shift - 1))) >> shift) as i32
            })
        });
        Ok(NarrowLight {
            g,
            arriving: arriving.map(|c| c.to_bits()),
            casters,
            ahead,
            reach,
            across,
        })
    }

    /// The casters of sphere `i` for the distant light `to_light` and their filter, as
    /// [`NarrowLight`] holds them: `(casters, ahead, reach)`. One pass over the other
    /// spheres, on the frame's scaled integers.
    ///
    /// A shadow ray from the sphere's surface, lifted by `ε`, starts within `r + ε` of the
    /// half-line from its centre toward the light, so only a sphere whose centre comes within
    /// `r + r_k + ε` of that half-line can block it. The mask takes the spheres within
    /// `r + r_k + 5ε` and `2⁻⁹` of the radii (looser than the rule of
    /// [`Scene::shadow_casters`]), so it is never short of a caster. `ahead` and `reach` are
    /// the loosest over the casters, each rounded toward passing more pixels, then widened by
    /// the fast `N·L`'s error (`2⁻¹²`, and `2⁻¹¹` for its square); with no caster nothing
    /// passes.
    ///
    /// Integers only, from exact 32×32→64 products: the scene lies within `2¹³` units, so
    /// every centre and radius is below `2²⁹` raw and every difference below `2³⁰`. The
    /// distance of a caster's centre from the half-line is `|Δ × L|` (no cancellation, unlike
    /// `|Δ|² − (Δ·L)²`), each component taken to raw units (rounded down, within one unit)
    /// and the root ([`sqrt`], within `2⁻²⁹`) lowered by four units and that relative error,
    /// which also covers `|L|`'s distance from 1 (`2⁻²⁹`).
    ///
    /// A caster touching the sphere (a sphere resting on a floor sphere) is in the mask like
    /// any other; where the lifted point lies within `ε` of it and ahead of its centre along
    /// the light, the filter passes the pixel as unblocked, which the full-width kernel's
    /// ray, starting inside the caster, may not: a sliver of width `ε` at the contact.
    ///
    /// `None` if the frame has spheres beyond the mask's 32 bits. Out of line: once per
    /// sphere and light.
    #[inline(never)]
    fn narrow_casters(&self, i: usize, to_light: V3<Unit>) -> Option<(u32, i32, u32)> {
        let own = self.spheres.get(i)?;
        let eps = self.epsilon.to_bits() as i64;
        let radius = |s: &FixedSphere| s.radius.to_bits() as i64;
        let r = radius(own);
        let l = to_light.map(|c| c.to_bits());
        // r + ε is at least one unit (2¹⁶ raw) and below 2³¹: the `max`es only show the
        // compiler that no divisor below is 0.
        let lift = ((r + eps) as u64).max(1);
        let (mut mask, mut ahead, mut reach) = (0u32, i64::MIN, i64::MIN);
        for (k, c) in self.spheres.iter().enumerate() {
            if k == i {
                continue;
            }
            if k >= 32 {
                return None;
            }
            let rk = radius(c);
            let d = each3(|j| own.center[j].to_bits().wrapping_sub(c.center[j].to_bits()));
            let len2 = d.iter().map(|&v| mul_ii(v, v)).sum::<i64>();
            // Δ·L in raw units times 2³⁰, exact.
            let along = mul_ii(d[0], l[0]) + mul_ii(d[1], l[1]) + mul_ii(d[2], l[2]);
            // |Δ × L| in raw units, rounded down per component: below 2³¹ each.
            let cross =
                |a: usize, b: usize| ((mul_ii(d[a], l[b]) - mul_ii(d[b], l[a])) >> 30) as i32;
            let cross = [cross(1, 2), cross(2, 0), cross(0, 1)];
            let cross2 = cross.iter().map(|&v| mul_ii(v, v) as u64).sum::<u64>();
            let root = sqrt(cross2);
            let across = (root - (root >> 28)) as i64 - 4;
            let radii = r + rk;
            let near = radii + (radii >> 9) + 5 * eps;
            // The half-line's closest point to the caster's centre: its start where the
            // caster lies behind the sphere along the light (`Δ·L ≥ 0`).
            let far = if along < 0 {
                across >= near
            } else {
                len2 >= mul_ii(near as i32, near as i32)
            };
            if far {
                continue;
            }
            mask |= 1 << k;
            // −(Δ·L)/(r + ε) in Q15, rounded up (by a whole step where it is positive).
            let q = (along.unsigned_abs() / (lift << 15).max(1)) as i64;
            ahead = ahead.max(if along < 0 { q + 1 } else { -q });
            // 1 − (gap/(r + ε))² in Q30, the ratio rounded down to 30 bits (gap < 2³¹).
            let gap = across - rk;
            let g30 = if gap <= 0 {
                0
            } else {
                ((gap as u64) << 30) / lift
            };
            let g30 = g30.min(u32::MAX as u64) as u32;
            reach = reach.max((1 << 30) - (mul_uu(g30, g30) >> 30) as i64);
        }
        if mask == 0 {
            return Some((0, i32::MIN, 0));
        }
        let q15 = (ahead + 8).clamp(-2 << 15, 2 << 15);
        let q30 = (reach + (1 << 19)).clamp(0, 2 << 30);
        Some((mask, q15 as i32, q30 as u32))
    }

    /// Turns the spans on (the default) or off. Off, every pixel tests every
    /// sphere: kept for the test that spans change no pixel, and for benchmarks.
    pub fn with_spans(mut self, on: bool) -> Self {
        self.use_spans = on;
        self
    }

    /// Turns analytic anti-aliasing of the silhouettes on or off (off by default, and after
    /// every [`prepare`](Self::prepare)): a pixel an outline crosses blends the front
    /// sphere's colour with what lies behind it by the sphere's coverage of the pixel, in
    /// integers, by the float paths' rule; other pixels keep their bits. Needs the features
    /// `antialias` and `full-width` (the edge pixels are shaded by the full-width kernel);
    /// see `src/fixed/edges.rs`.
    ///
    /// ```
    /// use shadeline::{exponent_series, PreparedFixed, Render, Rgb888};
    /// let sharp = PreparedFixed::new(&exponent_series()?, 96, 64)?;
    /// let smooth = sharp.clone().with_antialiasing(true);
    /// let (mut a, mut b) = ([Rgb888::default(); 96], [Rgb888::default(); 96]);
    /// sharp.render_line(32, &mut a)?;
    /// smooth.render_line(32, &mut b)?;
    /// assert_ne!(a, b); // the row crosses the spheres' outlines
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    #[cfg(all(feature = "antialias", feature = "full-width"))]
    pub fn with_antialiasing(mut self, on: bool) -> Self {
        self.set_antialiasing(on);
        self
    }

    /// [`with_antialiasing`](Self::with_antialiasing) in place, for a frame kept in a
    /// `static` and prepared there.
    #[cfg(all(feature = "antialias", feature = "full-width"))]
    pub fn set_antialiasing(&mut self, on: bool) {
        self.antialias = on;
    }
}

/// Whether the narrow kernel takes the quick caster test (`narrow_blocked`): on ARMv6-M,
/// where each 32×32→64-bit product of the exact test is a call, it saves most of a floor's
/// caster tests, and on RV32, whose 64-bit product is two instructions, some; with the
/// Cortex-M4's one-instruction product the exact test is about as cheap, and the quick one
/// costs the loop more than it saves (`docs/performance.md`, "Choices measured"). The
/// crate's own tests turn it on everywhere, to hold it to changing no pixel.
pub(crate) const QUICK_CASTER_TEST: bool =
    cfg!(any(shadeline_short_mul, target_arch = "riscv32", test));

/// Two unit vectors across the unit vector `l` (Q30), in Q15: `u = (l × e)/|l × e|` for the
/// axis `e` least along `l` (so `|l × e|² ≥ 2/3`), and `v = l × u`. Each is within `2⁻¹⁵`
/// of the exact basis across `l/|l|` in length (rounding down to Q15, `inv_sqrt`'s error,
/// and `|l|` within `2⁻²⁹` of 1).
fn across_light(l: [i32; 3]) -> [[i16; 3]; 2] {
    let [x, y, z] = l;
    let m = l.map(|c| c.unsigned_abs());
    // Components of a unit vector in Q30: negating one cannot overflow.
    let w = if m[0] <= m[1] && m[0] <= m[2] {
        [0, z, -y]
    } else if m[1] <= m[2] {
        [-z, 0, x]
    } else {
        [y, -x, 0]
    };
    let len2 = w.iter().map(|&c| mul_ii(c, c) as u64).sum::<u64>();
    let unit = |c: i64| c.clamp(-(1 << 15) + 1, (1 << 15) - 1) as i32;
    // w·(1/|w|) in Q15: `inv_sqrt`'s `v·y >> (shift − 15)`, `shift` at least 31.
    let (inv, shift) = inv_sqrt(len2).unwrap_or((0, 31));
    let [u0, u1, u2] = w.map(|c| unit(mul_iu(c, inv) >> (shift - 15)));
    let cross = |a: i32, b: i32, c: i32, d: i32| unit((mul_ii(a, b) - mul_ii(c, d)) >> 30);
    let v = [
        cross(y, u2, z, u1),
        cross(z, u0, x, u2),
        cross(x, u1, y, u0),
    ];
    [[u0, u1, u2].map(|c| c as i16), v.map(|c| c as i16)]
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;

    /// Values at and around every power of two of both signs, and a xorshift stream.
    fn values() -> impl Iterator<Item = i128> {
        let edges = (0..127).flat_map(|k| {
            let p = 1i128 << k;
            [p - 1, p, p.wrapping_add(1), -p - 1, -p, -p + 1]
        });
        let mut x = 0x9e37_79b9_7f4a_7c15u64;
        let mut next = move || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            x
        };
        let random = (0..2000).map(move |_| {
            let (h, l) = (next(), next());
            (((h as u128) << 64 | l as u128) as i128) >> (h % 120)
        });
        edges.chain([0, i128::MAX, i128::MIN]).chain(random)
    }

    /// The light's unit vector, for directions all around the sphere (a xorshift stream)
    /// and along the axes and diagonals: each component within one step of 2⁻³⁰ of the
    /// exact (`f64`) unit vector along the same 30-bit components (the general
    /// normalization, `vector::normalize`, is within 1.94 steps on the same inputs), so of
    /// unit length within `2⁻²⁸`. Both keep the `f32` unit vector's own direction, within
    /// about `2⁻²⁴` of the scene's.
    #[test]
    fn unit_q30_is_the_unit_vector_to_a_step() {
        let mut x = 0x2545_f491_4f6c_dd1du64;
        let mut next = move || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            (x >> 40) as f32 / (1u64 << 23) as f32 - 1.0
        };
        let mut dirs: std::vec::Vec<Vec3> = (0..20_000)
            .map(|_| Vec3::new(next(), next(), next()))
            .collect();
        for (a, b, c) in [
            (1.0, 0.0, 0.0),
            (0.0, -1.0, 0.0),
            (1.0, 1.0, 1.0),
            (-1.0, 1e-6, 0.5),
        ] {
            dirs.push(Vec3::new(a, b, c));
        }
        let (mut worst_len, mut worst_step) = (0i64, 0.0f64);
        for d in dirs {
            let Some(unit) = d.normalized() else {
                continue;
            };
            let got = unit_q30(unit);
            let len2: i64 = got.iter().map(|c| mul_ii(c.to_bits(), c.to_bits())).sum();
            worst_len = worst_len.max((len2 - (1 << 60)).abs());
            let q30 = [unit.x, unit.y, unit.z].map(|c| fixed_bits_i32(c, 30).unwrap() as f64);
            let len = (q30[0] * q30[0] + q30[1] * q30[1] + q30[2] * q30[2]).sqrt();
            for (g, c) in got.iter().zip(q30) {
                let want = c / len * (1u64 << 30) as f64;
                worst_step = worst_step.max((g.to_bits() as f64 - want).abs());
            }
        }
        assert!(worst_step <= 1.0, "a component {worst_step} steps off");
        assert!(worst_len <= 1 << 32, "|v|² off by {worst_len} in Q60");
    }

    /// The division is exact: the quotient rounded toward zero, `None` exactly where it
    /// does not fit `i64`, for divisors at the prepare's extremes (`r` from one unit, `2¹⁶`
    /// raw, to `2³¹`; `z` up to 63) and dividends at every power of two.
    #[test]
    fn divisor_is_exact() {
        for (d, passes, z) in [
            (1u32 << 16, 2u32, 0u32),
            (1 << 16, 1, 63),
            (65_537, 2, 29),
            (0x1234_5679, 1, 31),
            (0x7fff_ffff, 2, 0),
            (u32::MAX, 1, 59),
            (3 << 20, 2, 13),
        ] {
            let den = Divisor { d, passes, z };
            for c in values() {
                let mut m = c.unsigned_abs();
                for _ in 0..passes {
                    m /= d as u128;
                }
                let want = i64::try_from(m >> z)
                    .ok()
                    .map(|q| if c < 0 { -q } else { q });
                assert_eq!(den.divide(c), want, "{c}/({d}^{passes}·2^{z})");
            }
        }
    }

    /// `quadric` against the quadrics' definitions in `i128`, from cross products: `E′`'s
    /// raw coefficients `r²·(Dₐ·D_b) − (oc × Dₐ)·(oc × D_b)`, `G`'s `(oc × Dₐ)·(L × D_b)`,
    /// symmetrized and doubled off the diagonal, each through the same divisor. Random
    /// offsets, radii, lights and directions at the bounds the prepare holds them to
    /// (components below `2³⁰`, `|oc|² < 3·2⁶⁰`), and their extremes.
    #[test]
    fn quadrics_are_their_cross_product_definitions() {
        let mut x = 0x2545_f491_4f6c_dd1du64;
        let mut next = move |bits: u32| {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            // Signed, below 2^bits in magnitude, often at the extremes.
            let v = (x >> (64 - bits)) as i64;
            let v = match x % 8 {
                0 => (1 << (bits - 1)) - 1,
                1 => 1 - (1 << (bits - 1)),
                _ => v - (1 << (bits - 1)),
            };
            v as i32
        };
        let cross = |a: [i32; 3], b: [i32; 3]| {
            let m = |i: usize, j: usize| a[i] as i128 * b[j] as i128;
            [m(1, 2) - m(2, 1), m(2, 0) - m(0, 2), m(0, 1) - m(1, 0)]
        };
        let dot = |a: [i128; 3], b: [i128; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
        let wide = |a: [i32; 3]| a.map(|c| c as i128);
        let mut checked = 0;
        for _ in 0..3000 {
            let oc = [next(31), next(31), next(31)];
            let r = (next(31) as i64).unsigned_abs().max(1 << 16) as i64;
            let dirs = [
                [next(31), next(31), next(31)],
                [next(29), next(29), next(29)],
                [next(29), next(29), next(29)],
            ];
            let l = [next(31), next(31), next(31)];
            let oc_len2 = dot(wide(oc), wide(oc));
            if oc_len2 >= 3 << 60 {
                continue;
            }
            let r2 = r * r;
            let gram = PAIRS.map(|(a, b)| dot_ii(dirs[a], dirs[b]));
            let b = dirs.map(|d| dot_ii(oc, d));
            let ld = dirs.map(|d| dot_ii(l, d));
            let oc_l = dot_ii(oc, l);
            let w = dirs.map(|d| cross(oc, d));
            let v = dirs.map(|d| cross(l, d));
            // A divisor that keeps the quotients within `i64`: r²·2³⁴ is at least 2⁶⁶, and
            // 2¹²⁷ over it below 2⁶².
            let den = Divisor {
                d: r as u32,
                passes: 2,
                z: 34,
            };
            let mut e = Quadric::default();
            let mut g = Quadric::default();
            let e_ok = quadric((r2 - oc_len2 as i64, &gram, &b), Form::E, &den, &mut e);
            let g_ok = quadric((oc_l, &gram, &b), Form::G(&ld), &den, &mut g);
            assert!(
                e_ok.is_some() && g_ok.is_some(),
                "{oc:?} {r} {dirs:?} {l:?}"
            );
            for (k, &(a, c)) in PAIRS.iter().enumerate() {
                let twice = if a == c { 1 } else { 2 };
                let gram = dot(wide(dirs[a]), wide(dirs[c]));
                let e_raw = twice * (r2 as i128 * gram - dot(w[a], w[c]));
                let g_raw = if a == c {
                    dot(w[a], v[a])
                } else {
                    dot(w[a], v[c]) + dot(w[c], v[a])
                };
                assert_eq!(
                    Some(e.c[k]),
                    den.divide(e_raw),
                    "E′ c{k} of {oc:?} {r} {dirs:?}"
                );
                assert_eq!(
                    Some(g.c[k]),
                    den.divide(g_raw),
                    "G c{k} of {oc:?} {l:?} {dirs:?}"
                );
            }
            checked += 1;
        }
        assert!(checked > 1000, "{checked} cases");
    }

    /// The prepare's `f32` corner test keeps every narrow direction's integer `|D|²` within
    /// `2·2⁵⁸` (`|d|² ≤ 2`) and the steps below ½, and takes every frame whose corners are
    /// within `2 − 2⁻⁷` (computed in `f64` from the camera) and whose half pixel is below
    /// 0.49: random sizes from 1×1 up to the largest, aspect ratios, orientations and
    /// fields of view about the limit.
    #[test]
    fn the_corner_test_keeps_every_direction_within_root_two() {
        use crate::scene::Camera;
        use crate::test_scenes::uniform;
        use crate::LinearRgb;
        let mut draw = uniform(0x2545_f491_4f6c_dd1d);
        let mut next = |lo: f64, hi: f64| draw(lo as f32, hi as f32) as f64;
        let (mut taken, mut near) = (0, 0);
        for round in 0..3000 {
            let (w, h) = if round % 3 == 0 {
                (next(1.0, 65_535.0) as u32, next(1.0, 65_535.0) as u32)
            } else if round % 5 == 0 {
                (next(1.0, 4.0) as u32, next(1.0, 4.0) as u32)
            } else {
                (next(1.0, 800.0) as u32, next(1.0, 800.0) as u32)
            };
            // The field of view at which the corners reach |d|² = 2, and about it.
            let corner = ((w as f64 - 1.0).powi(2) + (h as f64 - 1.0).powi(2)).sqrt();
            let limit = 2.0 * (h as f64 / corner.max(1.0)).atan().to_degrees();
            let vfov = if w < 4 && h < 4 {
                next(1.0, 179.0)
            } else {
                (limit * next(0.97, 1.03)).min(179.0)
            };
            let camera = Camera {
                position: Vec3::new(next(-9.0, 9.0) as f32, next(-9.0, 9.0) as f32, 20.0),
                look_at: Vec3::new(next(-1.0, 1.0) as f32, next(-1.0, 1.0) as f32, 0.0),
                up: Vec3::new(next(-0.3, 0.3) as f32, 1.0, next(-0.3, 0.3) as f32),
                vfov_degrees: vfov as f32,
            };
            let Ok(scene) = Scene::<1, 1>::new(camera, LinearRgb::new(0.0, 0.0, 0.0)) else {
                continue;
            };
            let Ok(frame) = PreparedFixed::<1, 1>::new(&scene, w, h) else {
                continue;
            };
            let tan = (vfov.to_radians() / 2.0).tan();
            let want = 1.0 + corner * corner * (tan / h as f64).powi(2);
            let Some(view) = frame.narrow else {
                let steep = tan / h as f64 > 0.49;
                assert!(
                    want > 2.0 - 1.0 / 128.0 || steep,
                    "{w}x{h} at {vfov}°: |d|² {want} refused"
                );
                continue;
            };
            taken += 1;
            // Each step's components below ½ (2⁴⁷ in I16F48): twice them fit Q29 in `i32`.
            for c in frame.step_x.iter().chain(&frame.step_y) {
                assert!(c.to_bits().unsigned_abs() < 1 << 47, "{w}x{h} at {vfov}°");
            }
            near += (want > 2.0 - 1.0 / 64.0) as u32;
            let (dx, dy) = (w as i64 - 1, h as i64 - 1);
            for (sx, sy) in [(-dx, -dy), (-dx, dy), (dx, -dy), (dx, dy)] {
                let len2: i128 = (0..3)
                    .map(|i| {
                        let c = view.forward[i] as i128
                            + sy as i128 * view.step_y[i] as i128
                            + sx as i128 * view.step_x[i] as i128;
                        c * c
                    })
                    .sum();
                assert!(len2 <= 2 << 58, "{w}x{h} at {vfov}°: |D|² {len2}");
            }
        }
        assert!(
            taken > 1000 && near > 100,
            "{taken} frames taken, {near} near the limit"
        );
    }

    /// `narrow_casters` against the same geometry in `f64`, from the prepared integers, over
    /// random pairs of spheres under a random distant light: the mask never leaves out a
    /// sphere within the rule of `Scene::shadow_casters` (nor takes one well outside its own),
    /// and `ahead` and `reach` are never tighter than the exact values widened by the fast
    /// `N·L`'s error, nor looser than that by more than their rounding.
    #[test]
    fn caster_filter_is_the_exact_filter_rounded_outward() {
        use crate::scene::{Camera, Light, Material, Sphere};
        use crate::LinearRgb;
        let mut state = 0x853c_49e6_748f_ea9bu64;
        let mut next = |lo: f64, hi: f64| {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (lo + (hi - lo) * ((state >> 11) as f64 / (1u64 << 53) as f64)) as f32
        };
        let (mut masked, mut left_out) = (0, 0);
        for round in 0..4000 {
            let camera = Camera {
                position: Vec3::new(0.0, 0.0, 40.0),
                look_at: Vec3::new(0.0, 0.0, 0.0),
                up: Vec3::new(0.0, 1.0, 0.0),
                vfov_degrees: 30.0,
            };
            let mut scene: Scene<2, 1> = Scene::new(camera, LinearRgb::new(0.0, 0.0, 0.0)).unwrap();
            let direction = Vec3::new(next(-1.0, 1.0), next(-1.0, 1.0), next(-1.0, 1.0));
            let mut spheres = [0; 2].map(|_| Sphere {
                center: Vec3::new(next(-3.0, 3.0), next(-3.0, 3.0), next(-3.0, 3.0)),
                radius: next(0.2, 1.5),
                material: Material::default(),
            });
            if round % 2 == 1 {
                // The second sphere ahead of the first along the light, its centre about the
                // radii from the half-line: where the mask's margins decide (ε is 0.004 here).
                let Some(u) = (-direction).normalized() else {
                    continue;
                };
                let Some(p) = u.cross(Vec3::new(next(-1.0, 1.0), 1.0, 0.5)).normalized() else {
                    continue;
                };
                let radii = spheres[0].radius + spheres[1].radius;
                let offset = u.scale(next(1.0, 3.0)) + p.scale(radii + next(0.0, 0.04));
                spheres[1].center = spheres[0].center + offset;
            }
            if spheres.iter().any(|s| scene.add_sphere(*s).is_err()) {
                continue;
            }
            let light = Light::Distant {
                direction,
                color: LinearRgb::new(1.0, 1.0, 1.0),
                intensity: 1.0,
            };
            if scene.add_light(light).is_err() {
                continue;
            }
            let Ok(frame) = PreparedFixed::new(&scene, 64, 48) else {
                continue;
            };
            if frame.narrow.is_none() {
                continue;
            }
            let Some(FixedLight::Distant { to_light, .. }) = frame.lights.first() else {
                panic!("a distant light");
            };
            let l = to_light.map(|c| c.to_bits() as f64);
            let norm = (l[0] * l[0] + l[1] * l[1] + l[2] * l[2]).sqrt();
            let l = l.map(|c| c / norm);
            let eps = frame.epsilon.to_bits() as f64;
            for (i, k) in [(0, 1), (1, 0)] {
                let (own, other) = (&frame.spheres[i], &frame.spheres[k]);
                let d = each3(|j| (own.center[j].to_bits() - other.center[j].to_bits()) as f64);
                let (r, rk) = (own.radius.to_bits() as f64, other.radius.to_bits() as f64);
                let along = d[0] * l[0] + d[1] * l[1] + d[2] * l[2];
                let len = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
                let across = (len * len - along * along).max(0.0).sqrt();
                let dist = if along < 0.0 { across } else { len };
                let filter = frame.narrow_lights[i][0];
                let bit = filter.casters & (1 << k) != 0;
                let radii = r + rk;
                if dist < radii + 5.0 * eps + 1.0e-3 * radii {
                    assert!(bit, "sphere {k} left out of {i}'s casters at {dist} raw");
                }
                if dist > radii * (1.0 + 1.0 / 512.0) + 5.0 * eps + 16.0 {
                    assert!(!bit, "sphere {k} among {i}'s casters at {dist} raw");
                    left_out += 1;
                }
                if !bit {
                    continue;
                }
                masked += 1;
                let lift = r + eps;
                let ahead = ((-along / lift + 1.0 / 4096.0) * 32768.0).clamp(-65536.0, 65536.0);
                let got = filter.ahead as f64;
                assert!(
                    got >= ahead - 1e-3 && got <= ahead + 2.01,
                    "ahead {got} for {ahead}"
                );
                let gap = across - rk;
                let reach = if gap <= 0.0 {
                    1.0
                } else {
                    1.0 - (gap / lift).powi(2)
                };
                let reach = ((reach + 1.0 / 2048.0) * (1u64 << 30) as f64)
                    .clamp(0.0, 2.0 * (1u64 << 30) as f64);
                let got = filter.reach as f64;
                assert!(
                    got >= reach - 1.0 && got <= reach + (1 << 18) as f64,
                    "reach {got} for {reach}"
                );
            }
        }
        assert!(
            masked > 1000 && left_out > 3000,
            "{masked} masked, {left_out} left out"
        );
    }
}
