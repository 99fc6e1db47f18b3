//! The fixed-point path: integers only per row and per pixel, for cores without an FPU
//! (Cortex-M0/M0+/M3, RP2040, rv32imac), and the same bits on every target.
//!
//! [`PreparedFixed::new`] converts the scene once per frame (the only floating point of the
//! path, see `prepare`); [`Render::render_line`](crate::Render::render_line) then shades rows
//! with integer arithmetic only, through the same stages as the float kernel, under the same
//! names, in the same order (`spans`, then the kernel's `ray`, `hit`, `normal`, `lights` with
//! `incoming`, `shadow`, `diffuse`, `specular` per light, and `combine`; then `encode`). Its contract is agreement with the `f64`
//! [`reference`](crate::reference) within a stated budget (`tests/fixed_agreement.rs`: at
//! most 2 levels per 8-bit channel, ≥ 99% within 1 level, ≤ 0.1% of ray decisions differ;
//! the measured agreement is in `docs/accuracy.md`), and bit-identical frames on every target
//! (`tests/fixed_golden.rs`; `.ci/no-float-check` proves the row function calls no
//! soft-float routine on `thumbv6m-none-eabi`).
//!
//! ```
//! use shadeline::{exponent_series, PreparedFixed, Render, Rgb565};
//! let frame = PreparedFixed::<16, 8>::new(&exponent_series()?, 32, 24)?;
//! let mut pixels = [Rgb565::default(); 32 * 24];
//! frame.render_frame(&mut pixels)?;
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! # Scaling
//!
//! Prepare multiplies every coordinate by a power of two `2^k` (exact in `f32`) so that the
//! scene's extent (camera, sphere centres plus radii, point lights, largest coordinate
//! magnitude) lies in `[2¹², 2¹³)` units, with `k ≤ 19`. The model is scale-free apart from
//! point-light falloff, whose power is multiplied by `2^2k`, and the ray epsilon, which is
//! scaled with the scene. So any scene the model accepts fits, and the fixed formats get
//! the same relative precision whatever the units; what can be refused is a *ratio* that
//! does not fit (a sphere below `2⁻¹³` of the extent).
//!
//! # Formats
//!
//! | quantity | format | range | why |
//! |---|---|---|---|
//! | positions, offsets, `t`, distances, ε | I16F16 | `±2¹⁵` units; the scene is within `±2¹³`, so any difference of two points, and any distance, is below `2¹⁵` | 16 fraction bits against radii of at least `2¹⁶` raw steps: normals carry ≥ 16 bits, hit points are within `2⁻¹⁶` units |
//! | squared lengths, `r²`, the discriminant | I32F32 (`i64`) | `< 2³⁰` units² | exact products of two I16F16 (`wide_mul`), so the hit test's only rounding is in `oc·d` |
//! | unit vectors (ray, normal, `L`, `H`), cosines | I2F30 | `[−2, 2)` | 30 bits: a direction error of `10⁻⁹`, far below what the specular lobe can see at `n = 10⁴` |
//! | camera-plane steps, primary direction before normalizing | I16F48 (`i64`) | `±2¹⁵`; with `tan(vfov/2)·max(1, w/h) ≤ 127`, components stay within ±255 | integer steps per pixel are exact: `(2x + 1 − w)·step` by additions |
//! | `1 − cos` (`h`) | U3F61 (`u64`) | `[0, 4)` | `½|R − V|²` from 30-bit components is exact in 61 bits: full relative precision at the highlight |
//! | specular lobe | U1F31 | `[0, 1]` | absolute error `≤ 1.1·10⁻⁸` (see `pow`) |
//! | `n·(−log2 cos)` | U6F26 | `[0, 64)`; ≥ 32 is a lobe of 0 | relative lobe error `y·2⁻²⁶ ≤ 5·10⁻⁷` |
//! | shininess `n`, point-light power | `f32` mantissa and exponent (integers) | any `f32` | both span many decades; held exactly |
//! | `kd·albedo`, `ks`, arriving light, sums, output colour | U16F16 | `[0, 65536)`; inputs ≤ [`MAX_LEVEL`] (32767) | matches [`FixedShade`](crate::FixedShade); products of two are `u64` and saturate, so a point light very close to a surface saturates instead of wrapping (the fixed path's arriving-light cap: 65536) |
//!
//! # Reflection models
//!
//! The fixed kernel mirrors [`crate::brdf`]'s formulas in integers; the per-material
//! constants are the float paths' own ([`crate::brdf::Params::of`], `f32`, once per frame),
//! converted at the fixed prepare:
//!
//! | brdf | fixed |
//! |---|---|
//! | `kd·albedo` (classic) or `kd·albedo/π` (normalized, Lambert; 0 for metals) | `kd_albedo`, U16F16 |
//! | `ks` (classic) or 1 (normalized: the weights carry it) | `ks`, U16F16 |
//! | lobe cosine `R·V` or `N·H` | `h = 1 − cos = ½|R − V|²` or `½|N − H|²`, U3F61, the same for every lobe |
//! | `max(0, c)^nₖ` for each lobe | `pow::lobe(h, nₖ)`, U1F31, per lobe (the classic models' lobe) |
//! | `wₖ·cₖ` (weight times normalization) | `f32` held exactly (mantissa, exponent): no range limit, the product with the lobe is shifted into U16F16 and saturates |
//! | `max(0, N·L)` | U2F30 |
//! | Schlick `(1 − L·H)⁵`, `F = F₀ + (1 − F₀)·w` per channel | U2F30, four multiplications; `F₀` U2F30 |
//! | diffuse `I·max(0, N·L)·(1 − F)`, specular `I·max(0, N·L)·F·Σ wₖcₖ·lobeₖ` | U16F16, saturating (`normalized` in `kernel`) |
//!
//! The classic models have their own `diffuse` and `specular`, which do none of the
//! normalized models' work (`N·L` scaling, Fresnel, more lobes). The models' budget against
//! the reference is tested in `tests/models_agree.rs`.
//!
//! Oren–Nayar (feature `models`) is the normalized terms with the diffuse factor
//! `A·(N·L) + B·max(0, s)·(N·L/max(N·L, N·V))` in U2F30, `A` and `B` converted from the float
//! paths' constants; its ratio is one 64-bit division where `N·V > N·L`, the only division
//! in the kernel. GGX (feature `models`) replaces the lobes' sum with `ks·D(H)·V₂(L, V)·(N·L)`:
//! `D` and `V₂` from F60 sums of squares (`|N × H|²` from the cross product, which keeps
//! its relative precision at the peak), two reciprocals from `inv_sqrt` squared, and their
//! product as a 32-bit mantissa and a power of two, since the term spans seven decades;
//! saturated into U16F16 like the other lobes. Fresnel and the diffuse lobe are the
//! normalized models' own.
//!
//! # Refused scenes
//!
//! [`PreparedFixed::new`] returns [`RenderError::OutOfFixedRange`](crate::RenderError) naming
//! the item and field, never a frame of wrapped values: `radius` (below `2⁻¹³` of the scene's
//! extent, [`MIN_SCALED_RADIUS`] after scaling), `vfov` (`tan(vfov/2)·max(1, w/h)` above
//! [`MAX_PLANE_SCALE`]), `kd`/`ks`/`intensity` (a channel of `kd·albedo`, `ks` or a
//! distant light's `colour·intensity` above [`MAX_LEVEL`]: the levels the kernels use; an
//! albedo or a colour above it alone, times a `kd` or an intensity that brings it within,
//! is taken).
//!
//! # Costs
//!
//! Frames whose lights are distant or point lights of radius 0 and whose spheres use the
//! classic, Lambert or normalized models (the conditions are in its module, `narrow`) are
//! shaded by the narrow kernel: no vectors per pixel, but the ray's discriminant and each
//! light's `N·L` numerator as exact quadrics in the column, forward-differenced (two 64-bit
//! additions each), 16×16→32-bit products, two table lookups with linear interpolation for
//! `1/|D|` and `N·V`, and 64-bit arithmetic only where a pixel's error bound asks for it
//! (the bright part of a narrow highlight, a point light's shadow edge). Its cost per frame
//! on each core is in `docs/performance.md`. Without `full-width` each sphere is tested only
//! at the pixels its hit test passes (`outline`; on ARMv6-M within its rows and columns, see
//! there); with it, within each row's outline span (`spans`).
//!
//! The full-width kernel, per tested sphere nine 32×32→64-bit products and, on a hit, a square root (seven more, see
//! `roots`); per lit pixel and light, a normalization (point lights), a shadow test against
//! the sphere itself (three products when the ray leaves its lit side) and each sphere the
//! prepare found can cast a shadow on it ([`Scene::shadow_casters`](crate::Scene)), and
//! about twelve products for the lobe. No division per pixel except Oren–Nayar's ratio and
//! a sphere light's closed forms (below). On ARMv6-M (Cortex-M0,
//! RP2040), whose multiplier is 32×32→32 and which has no `CLZ`, `mul` builds each product
//! from four 16×16 `MULS` inline and counts leading zeros by a binary search, instead of
//! calls to `__aeabi_lmul` and `__clzsi2`.
//!
//! # Sphere lights
//!
//! With the features `area-lights` and `full-width`, the full-width kernel shades a point
//! light with a `radius` by the float paths' closed forms (`src/float/area.rs`) in integers
//! (`area`): the representative point's direction from the reflected ray, the sphere's
//! irradiance for the diffuse term, each lobe's energy factor from two per-lobe constants the
//! prepare computes, and the soft shadow as the product of every nearer sphere's uncovered
//! share of the light's cap. Cosines, sines, chords and shares are 30-bit fractions, each
//! ratio is one integer division (about a dozen per lit pixel and light, more where an
//! occluder overlaps the light), and the results are the same bits on every target. Against
//! the scalar path, the budgets `tests/sphere_lights.rs` holds (the measured figures are
//! in `docs/accuracy.md`). A frame with a sphere light never takes the narrow kernel.
//!
//! # Modules
//!
//! `prepare` (scene → formats, the refusals; its stages' parts in `prepare_plane`, the
//! camera's plane and size checks, `prepare_convert`, the checked conversions and the
//! range limits, and `prepare_ggx`, GGX's constants) · `spans` (each row's outline spans
//! within screen rectangles, feature `full-width`) · `outline` (exact spans from the narrow kernel's quadric,
//! without `full-width`) · `row` (the row driver) · `narrow` (the 16-bit kernel and when it
//! applies) · `kernel` (the full-width kernel's stages, feature `full-width`; its `incoming`
//! in `kernel_light`, its sphere lights' stages in `kernel_sphere` and the Oren–Nayar and GGX
//! terms in `kernel_models`) · `edges`
//! (anti-aliased silhouettes, features `antialias` and `full-width`) · `area` (sphere lights'
//! closed forms, features `area-lights` and `full-width`) · `pow` (the lobe) · `roots` (`√x`,
//! `1/√x`) · `quadric` (the narrow kernel's exact quadrics and their steps) · `vector` (dot
//! products and normalization) · `mul` (exact 32×32→64 products, leading zeros) · `exact` (`f32` as
//! mantissa and exponent).

#[cfg(all(feature = "area-lights", feature = "full-width"))]
mod area;
mod convert;
#[cfg(all(feature = "antialias", feature = "full-width"))]
mod edges;
mod exact;
#[cfg(feature = "full-width")]
mod kernel;
#[cfg(feature = "full-width")]
mod kernel_light;
#[cfg(all(feature = "models", feature = "full-width"))]
mod kernel_models;
#[cfg(all(feature = "area-lights", feature = "full-width"))]
mod kernel_sphere;
mod mul;
mod narrow;
mod narrow_caster_prepare;
mod narrow_depth;
mod narrow_hit;
mod narrow_lobe;
#[cfg(feature = "narrow-precise")]
mod narrow_point;
#[cfg(feature = "narrow-precise")]
mod narrow_point_prepare;
mod narrow_point_shadow;
#[cfg(feature = "narrow-precise")]
mod narrow_precise;
mod narrow_prepare;
mod narrow_roots;
mod narrow_run;
mod narrow_scale;
mod narrow_shadow;
#[cfg(feature = "shadow-rows")]
mod narrow_shadow_rows;
#[cfg(feature = "narrow-precise")]
mod narrow_terms;
#[cfg(not(feature = "full-width"))]
mod outline;
mod pow;
mod prepare;
mod prepare_convert;
#[cfg(feature = "models")]
mod prepare_ggx;
mod prepare_plane;
mod quadric;
mod roots;
mod row;
#[cfg(feature = "full-width")]
mod spans;
mod vector;

pub use prepare::PreparedFixed;
pub use prepare_convert::{MAX_LEVEL, MAX_PLANE_SCALE, MIN_SCALED_RADIUS};
