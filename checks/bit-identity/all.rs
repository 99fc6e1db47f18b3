//! The bit-identity test files of shadeline as the modules of one test binary, for
//! `.ci/bit-identity`: one crate instantiates the generic renderers once for all four files
//! (each path, capacity and pixel format they use), where four binaries would each compile
//! and link their own copies. Each file still builds alone in the workspace's
//! `cargo test`; their helpers, `tests/common`, are a module of each.

#[path = "../../tests/paths_agree.rs"]
mod paths_agree;

#[path = "../../tests/models_agree.rs"]
mod models_agree;

#[path = "../../tests/encodings.rs"]
mod encodings;

#[path = "../../tests/antialias.rs"]
mod antialias;
