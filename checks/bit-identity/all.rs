//! The bit-identity test files of shadeline as the modules of one test binary, for
//! `.ci/bit-identity`: one crate instantiates the generic renderers once for all four files
//! (each path, capacity and pixel format they use), where four binaries would each compile
//! and link their own copies. The workspace's `cargo test` builds them the same way, with
//! the other test files (`tests/all.rs`); their helpers, `tests/common`, are a module of the
//! binary.

#[path = "../../tests/common/mod.rs"]
mod common;

#[path = "../../tests/paths_agree.rs"]
mod paths_agree;

#[path = "../../tests/models_agree.rs"]
mod models_agree;

#[path = "../../tests/encodings.rs"]
mod encodings;

#[path = "../../tests/antialias.rs"]
mod antialias;
