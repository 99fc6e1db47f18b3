//! What the tests that run the `shadeline` binary share: a scratch directory per test, the
//! binary run in it, and its standard error as text.
#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// A fresh, empty directory for one test of one test file (`file`: its short name).
pub fn temp_dir(file: &str, test: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("shadeline-{file}-{}-{test}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Runs the binary with `args` in `dir`.
pub fn shadeline(args: &[&str], dir: &Path) -> Output {
    Command::new(env!("CARGO_BIN_EXE_shadeline"))
        .args(args)
        .current_dir(dir)
        .output()
        .expect("the binary runs")
}

/// The run's standard error.
pub fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}
