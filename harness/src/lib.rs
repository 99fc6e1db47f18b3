//! The shadeline host harness (library part).
pub mod scene_file;
pub mod toml_keys;
pub use scene_file::{parse_scene, FileScene, SceneFile, SceneFileError};
