//! The cargo-fuzz target `paths_agree`: libFuzzer's input through
//! [`shadeline_fuzz::targets::paths_agree::check`], where the target's checks are (and where
//! `tests/replay.rs` runs the committed corpus through them in the test command).
#![no_main]

use libfuzzer_sys::fuzz_target;

use shadeline_fuzz::SceneInput;

fuzz_target!(|input: SceneInput| shadeline_fuzz::targets::paths_agree::check(&input));
