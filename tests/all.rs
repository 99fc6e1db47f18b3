//! Every integration test of shadeline, as the modules of one test binary: the renderers are
//! generic over path, lane width, capacities and pixel format, and one crate instantiates
//! them once for all the files, where a binary per file compiles and links its own copies
//! of each. For the same reason the files render at few capacities: the default one (the
//! presets' and `common::TestScene`'s), the capacities of the library's own scene types
//! (`MatrixScene`, `area_lights`, `covered_sphere`, the firmware's animation) and the ones a
//! test is about; each more compiles every kernel again. `common` holds the helpers the
//! files share. (`frame_hashes` holds the frames that `checks/bit-identity` renders on other
//! instruction sets.)

mod common;

mod antialias;
mod bad_input;
mod brdf_laws;
mod capacities;
mod damage;
mod eg_drawable;
mod encodings;
mod firmware_crcs;
mod fixed_agreement;
mod fixed_golden;
mod fixed_no_panic;
mod fixed_render;
mod frame_hashes;
mod kernel_choice;
mod models_agree;
mod paths_agree;
mod readme;
mod reference_agreement;
mod scene_validation;
mod sphere_lights;
