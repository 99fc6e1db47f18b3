//! The committed corpus of every fuzz target, replayed through the target's own checks
//! (`shadeline_fuzz::targets`) in the test command: every input libFuzzer was seeded with
//! or found worth keeping must still pass, so a regression on any of them fails here in
//! seconds, without nightly or libFuzzer. The long campaigns are `.ci/fuzz`'s.
//!
//! A structured input is decoded as libFuzzer's `fuzz_target!` decodes it
//! (`arbitrary_take_rest` over the whole input); an input that does not decode is skipped
//! there and counted here, and a target whose inputs all fail to decode fails the test.

use arbitrary::{Arbitrary, Unstructured};
use shadeline_fuzz::targets::{damage, paths_agree, scene, scene_file};
use shadeline_fuzz::SceneInput;
use std::fs;
use std::path::PathBuf;

/// The committed inputs of `target`, sorted by name.
fn corpus(target: &str) -> Vec<(String, Vec<u8>)> {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("corpus")
        .join(target);
    let mut inputs: Vec<(String, Vec<u8>)> = fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|entry| {
            let path = entry.expect("a corpus entry").path();
            let name = path.file_name().unwrap().to_string_lossy().into_owned();
            (name, fs::read(&path).expect("a corpus file reads"))
        })
        .collect();
    inputs.sort();
    assert!(!inputs.is_empty(), "{}: no inputs", dir.display());
    inputs
}

/// Runs every structured input of `target` through `check`; returns how many decoded.
fn replay_structured(target: &str, check: fn(&SceneInput)) -> usize {
    let mut decoded = 0;
    for (name, bytes) in corpus(target) {
        let Ok(input) = SceneInput::arbitrary_take_rest(Unstructured::new(&bytes)) else {
            continue;
        };
        decoded += 1;
        let run = std::panic::catch_unwind(|| check(&input));
        assert!(run.is_ok(), "{target}: corpus input {name} fails its check");
    }
    assert!(decoded > 0, "{target}: no corpus input decodes");
    decoded
}

#[test]
fn scene_corpus_passes() {
    let n = replay_structured("scene", scene::check);
    eprintln!("scene: {n} inputs replayed");
}

#[test]
fn paths_agree_corpus_passes() {
    let n = replay_structured("paths_agree", paths_agree::check);
    eprintln!("paths_agree: {n} inputs replayed");
}

#[test]
fn damage_corpus_passes() {
    let mut decoded = 0;
    for (name, bytes) in corpus("damage") {
        let Ok(input) = damage::DamageInput::arbitrary_take_rest(Unstructured::new(&bytes)) else {
            continue;
        };
        decoded += 1;
        let run = std::panic::catch_unwind(|| damage::check(&input));
        assert!(run.is_ok(), "damage: corpus input {name} fails its check");
    }
    assert!(decoded > 0, "damage: no corpus input decodes");
    eprintln!("damage: {decoded} inputs replayed");
}

#[test]
fn scene_file_corpus_passes() {
    let inputs = corpus("scene_file");
    for (name, bytes) in &inputs {
        let run = std::panic::catch_unwind(|| scene_file::check(bytes));
        assert!(
            run.is_ok(),
            "scene_file: corpus input {name} fails its check"
        );
    }
    eprintln!("scene_file: {} inputs replayed", inputs.len());
}
