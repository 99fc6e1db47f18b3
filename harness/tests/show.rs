//! `shadeline show` on a machine without a framebuffer: every device it cannot draw into is
//! refused with one line naming it, exit code 2, and nothing is written. (Writing pixels
//! into framebuffer memory of every format and stride is tested in `fb_pixels`.)

mod common;

use common::{shadeline, stderr};

/// Asserts one line on stderr, exit code 2, starting with `start` and holding `words`.
fn assert_refused(args: &[&str], dir: &std::path::Path, start: &str, words: &str) {
    let out = shadeline(args, dir);
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    assert!(
        err.starts_with(start),
        "{err:?} does not start with {start:?}"
    );
    assert!(err.contains(words), "{err:?} does not contain {words:?}");
}

#[cfg(target_os = "linux")]
#[test]
fn a_missing_device_a_file_and_a_device_that_is_no_framebuffer_are_named() {
    let dir = common::temp_dir("show", "devices");
    assert_refused(
        &["show", "--preset", "floor", "--fb", "fb7"],
        &dir,
        "fb7: error: cannot open the framebuffer device: ",
        "No such file",
    );
    std::fs::write(dir.join("fb.raw"), [7u8; 100]).unwrap();
    assert_refused(
        &["show", "--fb", "fb.raw"],
        &dir,
        "fb.raw: error: not a framebuffer device: it is a regular file",
        "character device",
    );
    assert_eq!(std::fs::read(dir.join("fb.raw")).unwrap(), [7u8; 100]);
    if std::path::Path::new("/dev/null").exists() {
        assert_refused(
            &["show", "--fb", "/dev/null"],
            &dir,
            "/dev/null: error: not a framebuffer device: its screen information cannot be read",
            "ioctl",
        );
    }
}

#[test]
fn a_bad_scene_is_refused_before_the_device_is_opened() {
    let dir = common::temp_dir("show", "scene");
    assert_refused(
        &["show", "missing.toml", "--fb", "fb7"],
        &dir,
        "missing.toml: error: cannot read",
        "scene file",
    );
}
