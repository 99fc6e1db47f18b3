//! The `shadeline` command line (in progress).
fn main() {}
