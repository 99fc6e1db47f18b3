//! shadeline's integration tests, one module per file of this directory, built as one test
//! binary: each file on its own would be a binary of its own that instantiates the kernels
//! again, and compiling those optimized copies was most of the test command's time. The
//! shared helpers are in `common`. `checks/bit-identity` builds four of these files for other
//! targets in the same way (`checks/bit-identity/tests/main.rs`).

mod common;

mod antialias;
mod bad_input;
mod brdf_laws;
mod capacities;
mod eg_drawable;
mod encodings;
mod firmware_crcs;
mod fixed_agreement;
mod fixed_golden;
mod fixed_no_panic;
mod fixed_render;
mod models_agree;
mod paths_agree;
mod readme;
mod reference_agreement;
mod scene_validation;
mod sphere_lights;
