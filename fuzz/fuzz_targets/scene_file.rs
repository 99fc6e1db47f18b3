//! The cargo-fuzz target `scene_file`: libFuzzer's input through
//! [`shadeline_fuzz::targets::scene_file::check`], where the target's checks are (and where
//! `tests/replay.rs` runs the committed corpus through them in the test command).
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| shadeline_fuzz::targets::scene_file::check(data));
