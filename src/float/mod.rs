//! The float paths: `f32`, one pixel at a time ([`Scalar`]) or in SIMD lanes ([`Simd4`],
//! [`Simd8`]), from one kernel written once over a lane type.
//!
//! The files mirror the fixed path's (`src/fixed/`), one concept each, in the order a row
//! flows through them:
//!
//! | file | what it holds |
//! |---|---|
//! | `prepare` | [`Prepared`] and its per-frame constants; the width markers; per-row constants |
//! | `spans` | each sphere's analytic, conservative pixel span on a row |
//! | `row` | the row driver: [`Render`](crate::Render) for [`Prepared`], and the `encode` step |
//! | `kernel` | the general kernel's per-packet stages: `shade`, `ray`, `hit`, `normal`, `combine` |
//! | `light_loop` | the general kernel's light loop, `lights`, and its per-light stages: `incoming`, `shadow`, `diffuse`, `specular` |
//! | `sphere_light` | a sphere light's `incoming` and `shadow` in the general kernel (`area-lights`) |
//! | `intersect` | the ray–sphere tests: the nearest hit, the shadow test, an edge's filtered hit |
//! | `narrow` | the narrow kernel: classic models under distant lights, from quadrics along the row |
//! | `shadow_rows` | the narrow kernel's shadow rows on a floor (`shadow-rows`): where its casters' tests can be skipped |
//! | `area` | sphere lights: the diffuse horizon, the covered share of the light's cap, `acos` |
//! | `edges` | analytic anti-aliasing of the silhouettes: each outline's coverage of a pixel, and the blend |
//! | `lane` | the lane trait: [`Real`](crate::real::Real) plus the operations only lanes have, each exactly specified |
//! | `math` | the specular `pow`, identical at every width |
//!
//! Scalar and SIMD differ only in the lane type, and every operation the kernel uses has the
//! same IEEE-754 result at every width, so their frames are bit-identical
//! (`tests/paths_agree.rs`, `tests/models_agree.rs`, `tests/encodings.rs` on the host;
//! `checks/bit-identity`'s frames on x86-64 at the SSE2 baseline, AVX2 and the native CPU, on
//! aarch64 with NEON and on wasm32 with simd128: `.ci/bit-identity`).

#[cfg(feature = "area-lights")]
pub(crate) mod area;
#[cfg(feature = "antialias")]
mod edges;
mod intersect;
mod kernel;
mod lane;
// Its name is a measured choice (`docs/performance.md, "Choices measured"`).
mod light_loop;
mod math;
mod narrow;
mod prepare;
mod row;
#[cfg(feature = "shadow-rows")]
mod shadow_rows;
mod spans;
#[cfg(feature = "area-lights")]
mod sphere_light;

#[doc(hidden)]
pub use lane::{Lane, Rooted};
pub use lane::{Libm, SquareRoot};
pub use prepare::{FloatPath, Prepared, Scalar, ScalarWith, Simd4, Simd8};
