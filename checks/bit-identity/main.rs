//! `frame-hashes`: prints one hash line per frame of the bit-identity check (see
//! `frames.rs`), or, when two paths of this build disagree, names the frame, the variant and
//! the row, and exits with status 1. `.ci/bit-identity` builds it for each instruction set
//! and compares its output with `expected.txt`.
//!
//! ```text
//! cargo run --release --manifest-path checks/bit-identity/Cargo.toml > checks/bit-identity/expected.txt
//! ```
//!
//! writes the expected lines anew, after a change that is meant to change frames.

mod frames;

fn main() {
    match frames::lines() {
        Ok(lines) => {
            for line in lines {
                println!("{line}");
            }
        }
        Err(e) => {
            eprintln!("frame-hashes: the paths of this build disagree: {e}");
            std::process::exit(1);
        }
    }
}
