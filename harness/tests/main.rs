//! The harness's integration tests, one module per file of this directory, built as one test
//! binary (one build of the harness and its dependencies instead of one per file). The
//! shared helpers are in `common`. `rows_alloc` counts every allocation of its process, so it
//! is a test binary of its own (see `Cargo.toml`).

mod common;

mod cli;
mod edges;
mod materials_file;
mod microfacets_file;
mod plot;
mod scene_file;
