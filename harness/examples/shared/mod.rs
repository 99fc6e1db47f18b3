//! What the docs' image examples share: their command line.

use std::path::PathBuf;

/// The examples' arguments: the directory to write into (the first argument that is not an
/// option; `docs` without one) and whether `--full` asks for the whole frames as well.
pub fn output_dir_and_full() -> (PathBuf, bool) {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let full = args.iter().any(|a| a == "--full");
    let dir = args
        .iter()
        .find(|a| !a.starts_with("--"))
        .map_or_else(|| PathBuf::from("docs"), PathBuf::from);
    (dir, full)
}
