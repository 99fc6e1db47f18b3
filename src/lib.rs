//! # shadeline
//!
//! A `#![no_std]`, allocation-free scanline shader for spheres lit by the Phong reflection
//! model, one row at a time, into the caller's buffer.
//!
//! ```
//! use shadeline::{Camera, LinearRgb, Light, Material, Prepared, Render, Rgb888, Scalar,
//!                 Scene, Sphere, Vec3};
//!
//! // Describe the scene: every number is checked here, with errors naming the field.
//! let camera = Camera {
//!     position: Vec3::new(0.0, 0.0, 6.0),
//!     look_at: Vec3::new(0.0, 0.0, 0.0),
//!     up: Vec3::new(0.0, 1.0, 0.0),
//!     vfov_degrees: 40.0,
//! };
//! let mut scene: Scene<4, 2> = Scene::new(camera, LinearRgb::new(0.05, 0.05, 0.1))?;
//! scene.add_sphere(Sphere { center: Vec3::new(0.0, 0.0, 0.0), radius: 1.5, material: Material::default() })?;
//! scene.add_light(Light::Distant {
//!     direction: Vec3::new(-1.0, -1.0, -1.0),
//!     color: LinearRgb::new(1.0, 1.0, 1.0),
//!     intensity: 2.0,
//! })?;
//!
//! // Prepare once per frame, then shade rows into any buffer you own. The capacities are
//! // inferred from the scene (`_`); `Prepared::<Scalar>` alone would mean the defaults.
//! let frame = Prepared::<Scalar, _, _>::new(&scene, 48, 32)?;
//! let mut line = [Rgb888::default(); 48];
//! frame.render_line(16, &mut line)?;
//! assert_ne!(line[24], line[0]); // the sphere is in the middle, the background at the edge
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! ## Paths
//!
//! | path | type | numbers | contract |
//! |---|---|---|---|
//! | scalar | [`Prepared<Scalar>`] | `f32`, one pixel per kernel call | the float reference of the crate |
//! | SIMD | [`Prepared<Simd4>`], [`Prepared<Simd8>`] | `wide::f32x4` / `f32x8` lanes | bit-identical to scalar |
//! | fixed | [`PreparedFixed`] | integers only per pixel ([`fixed`] formats) | within 2 levels of the reference, the same bits on every target |
//!
//! An independent `f64` renderer, [`reference`](mod@reference), written straight from the formulas and
//! sharing no code with the kernels, is what the paths are measured against.
//!
//! ## Output: formats, encodings, sinks
//!
//! Rows go into any [`Pixel`] format: [`Rgb888`], [`Rgb565`], [`Bgr565`], [`Gray8`] (Rec. 709
//! luma), or [`LinearRgb`] and [`HitRecord`] for tests and tools. How linear colour becomes
//! levels is the frame's [`Encoding`]: linear without dithering by default (the lesson's
//! rule), or sRGB and/or 4×4 ordered dithering, chosen with [`Render::with_encoding`]; see
//! [`encoding`] for the exact integer rule every path shares. Sinks:
//!
//! - [`Render::render_line`] / [`Render::render_frame`]: into `&mut [P]`;
//! - [`Render::render_segment`]: any run of pixels of a row (tiles, partial updates);
//! - [`Render::render_line_bytes`]: a row as the display's bytes (RGB565 big-endian for SPI
//!   panels), ready for a DMA transfer;
//! - `eg::Drawing` (feature `embedded-graphics`): a `Drawable` for any embedded-graphics
//!   `DrawTarget`, one `fill_contiguous` or `fill_solid` per row.
//!
//! A display loop with two line buffers, one shading while the other is sent:
//!
//! ```
//! use shadeline::{exponent_series, Encoding, PreparedFixed, Render, Rgb565};
//!
//! let frame = PreparedFixed::new(&exponent_series()?, 320, 240)?
//!     .with_encoding(Encoding::SRGB.dithered());
//! let mut lines = [[0u8; 2 * 320]; 2];
//! for y in 0..240 {
//!     let line = &mut lines[y as usize % 2];
//!     frame.render_line_bytes::<Rgb565>(y, line)?; // big-endian RGB565
//!     // start_dma(line); the other buffer is free for row y + 1
//! }
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! ## Feature flags
//!
//! | feature | default | what it adds |
//! |---|---|---|
//! | `antialias` | on | `Prepared::with_antialiasing` and, with `full-width` too, `PreparedFixed::with_antialiasing`: analytic anti-aliasing of the silhouettes (see `src/float/edges.rs`, `src/fixed/edges.rs`); without it the kernels hold no edge code |
//! | `area-lights` | on | sphere lights (point lights with a `radius`) on every path (see `src/float/area.rs`, and `src/fixed/area.rs` for their integer forms, which the fixed path's full-width kernel shades): representative-point highlights, the sphere's irradiance, analytic soft shadows; without it the kernels hold none of that code and a scene refuses such a light as it is added ([`Problem::SphereLightNotBuilt`] on its `radius`); with it, the fixed path without `full-width` refuses one with [`RenderError::SphereLight`] |
//! | `models` | on | the Oren–Nayar and GGX models ([`Model::OrenNayar`], [`Model::Ggx`]) on every path; without it the kernels and prepares hold none of their code, and [`Scene::add_sphere`] refuses such a sphere with [`Problem::ModelNotBuilt`] (the variants exist either way) |
//! | `blinn-phong` | on | the Blinn-Phong models ([`Model::BlinnPhong`], [`Model::NormalizedBlinnPhong`]: the half-vector lobe) on every path; without it the kernels hold none of the half-vector lobe's code, and [`Scene::add_sphere`] refuses such a sphere with [`Problem::ModelNotBuilt`] |
//! | `full-width` | on | the fixed path's full-width kernel (32×32→64-bit products throughout), for the frames its narrow kernel does not take: sphere lights, Oren–Nayar and GGX, fields of view over about 90° on the diagonal, a camera close to a sphere; without it the fixed path is the narrow kernel alone and [`PreparedFixed::new`] refuses such a frame with [`RenderError::NeedsFullWidth`] naming the item and field (see [`fixed`]) |
//! | `narrow-precise` | on | the fixed path's narrow-kernel stages for point lights (of radius 0) and the normalized models (see `src/fixed/narrow_point.rs`, `narrow_terms.rs`, `narrow_precise.rs`); without it the narrow kernel takes distant lights and the classic models and Lambert only, and a frame with a point light or a normalized sphere takes the full-width kernel, or without that is refused with [`RenderError::NeedsNarrowPrecise`] naming the light or sphere |
//! | `shadow-rows` | on | the narrow kernels' shadow rows (see `src/shadow_rows.rs`, `src/fixed/narrow_shadow_rows.rs`, `src/float/shadow_rows.rs`): per frame, the rows of a floor on which a caster can block a light, outside which its pixels skip the casters' tests, and on the fixed path each sphere's casters less those a plane keeps off its rays (a floor under a sphere resting on it); without it every row tests every caster (no pixel differs) and the prepare holds none of this `f32` geometry |
//! | `depth-order` | on | the fixed narrow kernel's depth order (see `src/fixed/narrow_depth.rs`): where no two spheres overlap, a pixel over several takes the first its ray meets in an order made once per frame, with no distances compared (the pixels of spheres over a floor); without it such pixels compare distances (no pixel differs) and the kernel holds none of that code |
//! | `embedded-graphics` | off | `eg::Drawing`, a `Drawable` over `embedded-graphics-core` 0.4 (`Rgb565`, `Bgr565`, `Rgb888`, `Gray8`), and `From` conversions both ways between those colours and shadeline's formats of the same names |
//!
//! ## Targets and MSRV
//!
//! `#![no_std]`, no allocation, `#![forbid(unsafe_code)]`; Rust 1.93 or later (the `fixed`
//! crate's MSRV). Built in CI for `thumbv6m-none-eabi` (Cortex-M0), `thumbv7em-none-eabihf`
//! (Cortex-M4F/M7) and `riscv32imac-unknown-none-elf`; the float paths' bit-identity is
//! tested on x86-64 (SSE2, AVX2, the native CPU), aarch64 (NEON) and wasm32 (simd128).
//!
//! ## The lesson
//!
//! Some docs cite *the lesson*: the tutorial on the Phong reflection model whose formulas and
//! scene this crate implements. From it come the classic Phong and Blinn-Phong models (not
//! normalized), the exponent series scene ([`exponent_series`]), the shadow-ray offset (its
//! `bias`, here [`Scene::ray_epsilon`]) and the default encoding (clamp, round to nearest,
//! no gamma: [`Encoding::LINEAR`]). The normalized models, sRGB, dithering and the fixed path
//! extend it; they leave those frames as they are.
//!
//! ## Layout
//!
//! The modules form layers; each uses only its own layer and the ones before it (checked in
//! CI by `checks/module-graph.py`):
//!
//! 1. numbers and pixels: [`real`] (the numeric trait), [`Vec3`], [`encoding`] (every
//!    rounding rule), [`pixel`] (formats and packing);
//! 2. [`scene`]: what the caller describes, validated;
//! 3. [`brdf`]: the reflection formulas, written once over [`real::Real`];
//! 4. the contract of a row: [`render`] (the [`Render`] trait, errors) and the shared row
//!    helpers (covered runs, the background fill);
//! 5. the two paths, each `prepare` → `spans` → `row` → `kernel`: [`float`] (scalar and
//!    SIMD, one kernel over a lane type) and [`fixed`] (integers only);
//! 6. sinks built on [`Render`]: `eg` (feature `embedded-graphics`) and [`damage`] (the
//!    pixels that can differ between two frames, and rendering only those);
//! 7. built on everything: [`presets`] and the independent [`reference`](mod@reference).

#![no_std]
#![forbid(unsafe_code)]
#![deny(missing_docs)]

pub mod brdf;
mod caster_plane;
pub mod damage;
#[cfg(feature = "embedded-graphics")]
pub mod eg;
pub mod encoding;
pub mod fixed;
pub mod float;
pub mod pixel;
pub mod presets;
pub mod real;
pub mod reference;
pub mod render;
mod runs;
pub mod scene;
#[cfg(feature = "shadow-rows")]
mod shadow_rows;
mod test_scenes;
mod vec3;

pub use encoding::{Encoding, Transfer};
pub use fixed::PreparedFixed;
pub use float::{FloatPath, Libm, Prepared, Scalar, ScalarWith, Simd4, Simd8, SquareRoot};
pub use pixel::{
    Bgr565, BytePixel, FixedShade, Gray8, HitRecord, LinearRgb, Pixel, Rgb565, Rgb888, Shade,
};
pub use presets::{
    area_lights, covered_sphere, exponent_series, exponent_series_with_capacity, floor, full_moon,
    lamp, materials, materials_with_capacity, microfacets, microfacets_with_capacity,
    model_samples, three_lights, MatrixScene, AREA_LIGHTS_SIZE, AREA_LIGHT_RADIUS,
    EXPONENT_SERIES_SIZE, FULL_MOON_SIZE, MATERIALS_SIZE, MATRIX_SIZE, MATRIX_SPHERE_RADIUS,
    MICROFACETS_SIZE,
};
pub use render::{Encoded, Kernel, Render, RenderError, LINE_CHUNK, MAX_DIMENSION};
pub use runs::Span;
pub use scene::{
    Camera, Item, ItemKind, Light, Lobe, Material, Metal, Microfacet, Model, Problem, Scene,
    SceneError, Specular, Sphere, Surface, DEFAULT_LIGHTS, DEFAULT_SPHERES,
    MAX_OREN_NAYAR_ROUGHNESS, MIN_GGX_ROUGHNESS, MORE_LOBES,
};
pub use vec3::Vec3;

/// The README's Rust examples, compiled and run as doctests (`cargo test --doc`), so the
/// README cannot drift from the API. Its other blocks are marked `sh` or `text`.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
pub struct ReadmeDoctests;

/// The Rust example of `docs/animation.md` (sending only the damage), compiled as a doctest.
#[cfg(doctest)]
#[doc = include_str!("../docs/animation.md")]
pub struct AnimationDoctests;
