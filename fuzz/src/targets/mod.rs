//! The fuzz targets' checks, one module per target: each `check` takes the target's input
//! and panics on a failure. The cargo-fuzz binaries in `fuzz_targets/` only hand libFuzzer's
//! input to them, so the same checks run in the test command on the committed corpus
//! (`tests/replay.rs`) and in the long campaigns of `.ci/fuzz`.

pub mod damage;
pub mod paths_agree;
pub mod scene;
pub mod scene_file;
