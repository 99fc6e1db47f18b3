//! The bit-identity program's frames on the host: the lines of `checks/bit-identity` at the
//! workspace's target CPU (x86-64-v3: AVX2 and FMA) equal the committed
//! `checks/bit-identity/expected.txt`, which `.ci/bit-identity` also holds the SSE2
//! baseline, the native CPU, aarch64 (NEON) and wasm32 (simd128) to. Within the run every
//! float path gives the scalar path's bits, with and without spans and anti-aliased edges.

#[path = "../checks/bit-identity/frames.rs"]
mod frames;

const EXPECTED: &str = include_str!("../checks/bit-identity/expected.txt");

#[test]
fn frame_hashes_are_the_committed_ones() {
    let got = frames::lines().unwrap_or_else(|e| panic!("the paths disagree: {e}"));
    let want: Vec<&str> = EXPECTED.lines().collect();
    let differ: Vec<String> = got
        .iter()
        .zip(&want)
        .filter(|(g, w)| g != w)
        .map(|(g, w)| format!("  got  {g}\n  want {w}"))
        .collect();
    assert!(
        differ.is_empty() && got.len() == want.len(),
        "{} of {} frame lines differ from checks/bit-identity/expected.txt ({} lines there); \
         after a change meant to change frames, write it anew with `cargo run --release \
         --manifest-path checks/bit-identity/Cargo.toml > checks/bit-identity/expected.txt`:\n{}",
        differ.len(),
        got.len(),
        want.len(),
        differ.join("\n")
    );
}
