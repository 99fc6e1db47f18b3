//! The cargo-fuzz target `damage`: libFuzzer's input through
//! [`shadeline_fuzz::targets::damage::check`], where the target's checks are (and where
//! `tests/replay.rs` runs the committed corpus through them in the test command).
#![no_main]

use libfuzzer_sys::fuzz_target;

use shadeline_fuzz::targets::damage::DamageInput;

fuzz_target!(|input: DamageInput| shadeline_fuzz::targets::damage::check(&input));
