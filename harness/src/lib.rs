//! The shadeline host harness: everything the `shadeline` command does, as a library, so the
//! tests (and later a fuzzer) can call it directly.
//!
//! - [`scene_file`]: the TOML scene format → a validated scene, with located errors
//!   ([`toml_keys`] finds the keys);
//! - [`paths`]: the list of rendering paths; [`rows`]: rendering rows on threads;
//! - [`compare`]: measuring the paths against the `f64` reference; [`image`]: PNG output;
//! - [`plot`]: lobe plots, a material's BRDF and the scene's `cos^n` curves as SVG;
//! - [`progress`]: a progress bar for work that takes more than a second;
//! - [`fb_pixels`]: writing a frame into a Linux framebuffer's memory, any stride and format;
//!   [`fb_device`] (Linux): the device itself;
//! - [`animation`]: the scene of each frame of an animation; [`apng`]: animated PNG output;
//!   [`bus`]: the bytes a display is sent for a full frame or for the damage alone.

#![warn(missing_docs)]

pub mod animation;
pub mod apng;
pub mod bus;
pub mod compare;
pub mod edges;
#[cfg(target_os = "linux")]
pub mod fb_device;
pub mod fb_pixels;
pub mod image;
pub mod paths;
pub mod plot;
pub mod progress;
pub mod rows;
pub mod scene_file;
pub mod toml_keys;

pub use scene_file::{parse_scene, FileScene, SceneFile, SceneFileError};
