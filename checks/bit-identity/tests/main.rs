//! The bit-identity tests of shadeline as one test binary: the files of the repository's
//! `tests/` (and their helpers, `tests/common`), as modules in the same way as
//! `tests/main.rs` builds them for the workspace.

#[path = "../../../tests/common/mod.rs"]
mod common;

#[path = "../../../tests/antialias.rs"]
mod antialias;
#[path = "../../../tests/encodings.rs"]
mod encodings;
#[path = "../../../tests/models_agree.rs"]
mod models_agree;
#[path = "../../../tests/paths_agree.rs"]
mod paths_agree;
