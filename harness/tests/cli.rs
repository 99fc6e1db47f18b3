//! The `shadeline` binary, run as a user would: exit codes, messages, and the PNGs it writes.

mod common;

use common::{shadeline, stderr};
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// A fresh, empty directory for one test.
fn temp_dir(test: &str) -> PathBuf {
    common::temp_dir("cli", test)
}

fn exponent_series_text() -> String {
    std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../scenes/exponent-series.toml"
    ))
    .unwrap()
}

/// Decodes a PNG: (width, height, colour type, bit depth, pixel bytes).
fn read_png(path: &Path) -> (u32, u32, png::ColorType, png::BitDepth, Vec<u8>) {
    let file = std::io::BufReader::new(std::fs::File::open(path).unwrap());
    let mut reader = png::Decoder::new(file).read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut buf).unwrap();
    buf.truncate(info.buffer_size());
    (
        info.width,
        info.height,
        info.color_type,
        info.bit_depth,
        buf,
    )
}

/// Asserts a refusal: exit code 2, one line on stderr saying `words`, no panic.
fn assert_refused(out: &Output, words: &[&str]) {
    let err = stderr(out);
    assert_eq!(out.status.code(), Some(2), "stderr: {err}");
    assert!(!err.contains("panicked"), "{err}");
    assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    for w in words {
        assert!(err.contains(w), "{err:?} does not contain {w:?}");
    }
}

#[test]
fn a_bad_scene_file_is_one_located_message_and_exit_code_2() {
    let dir = temp_dir("bad-scene");
    let text = exponent_series_text().replacen("radius = 0.9", "radius = 0.0", 1);
    let line = text[..text.find("radius = 0.0").unwrap()]
        .matches('\n')
        .count()
        + 1;
    std::fs::write(dir.join("bad.toml"), text).unwrap();
    for command in ["render", "compare"] {
        let out = shadeline(
            &[command, "bad.toml", "--width", "8", "--height", "6"],
            &dir,
        );
        let at = format!("bad.toml:{line}:10: error:");
        assert_refused(
            &out,
            &[&at, "(key `sphere[0].radius`)", "greater than zero"],
        );
    }
    assert!(!dir.join("spheres.png").exists());
    assert!(!dir.join("compare.png").exists());
}

#[test]
fn unreadable_non_utf8_and_directory_inputs_are_refused_without_panic() {
    let dir = temp_dir("unreadable");
    assert_refused(
        &shadeline(&["render", "missing.toml"], &dir),
        &["missing.toml: error: cannot read"],
    );
    std::fs::create_dir(dir.join("scene.toml")).unwrap();
    assert_refused(
        &shadeline(&["render", "scene.toml"], &dir),
        &["scene.toml: error: cannot read"],
    );
    std::fs::write(dir.join("latin1.toml"), b"[image]\nwidth = 4 # caf\xe9\n").unwrap();
    assert_refused(
        &shadeline(&["render", "latin1.toml"], &dir),
        &["latin1.toml:2:", "not UTF-8", "0xe9"],
    );
}

#[test]
fn a_bad_size_on_the_command_line_is_refused() {
    let dir = temp_dir("bad-size");
    assert_refused(
        &shadeline(&["render", "--width", "0"], &dir),
        &["error:", "not supported"],
    );
    assert_refused(
        &shadeline(&["compare", "--height", "70000"], &dir),
        &["error:", "not supported"],
    );
}

/// Runs the binary with its address space limited to 1 GiB (`ulimit -v`), so that a frame
/// larger than that cannot be allocated on any machine, however much memory it has.
#[cfg(unix)]
fn shadeline_in_1_gib(args: &[&str], dir: &Path) -> Output {
    Command::new("sh")
        .arg("-c")
        .arg("ulimit -v 1048576 && exec \"$0\" \"$@\"")
        .arg(env!("CARGO_BIN_EXE_shadeline"))
        .args(args)
        .current_dir(dir)
        .output()
        .expect("sh runs")
}

#[cfg(unix)]
#[test]
fn a_frame_too_large_for_the_memory_is_refused_with_its_size_not_an_abort() {
    let dir = temp_dir("huge");
    let huge = ["--width", "65535", "--height", "65535"];
    for command in ["render", "compare"] {
        let args: Vec<&str> = [command].iter().chain(&huge).copied().collect();
        let out = shadeline_in_1_gib(&args, &dir);
        assert_refused(
            &out,
            &["error:", "65535x65535 frame", "cannot allocate", "GB"],
        );
    }
    // Nothing is left behind, and an existing output keeps its contents.
    assert!(!dir.join("spheres.png").exists());
    assert!(!dir.join("compare.png").exists());
    std::fs::write(dir.join("old.png"), "old").unwrap();
    let args = [
        "render", "--width", "65535", "--height", "65535", "-o", "old.png",
    ];
    assert_refused(&shadeline_in_1_gib(&args, &dir), &["65535x65535 frame"]);
    assert_eq!(std::fs::read_to_string(dir.join("old.png")).unwrap(), "old");
}

#[cfg(unix)]
#[test]
fn an_unwritable_output_is_refused_before_rendering() {
    let dir = temp_dir("unwritable");
    // With a frame that cannot be allocated: the output is checked first, so the message
    // is about the output.
    for command in ["render", "compare"] {
        let out = shadeline_in_1_gib(
            &[
                command,
                "--width",
                "65535",
                "--height",
                "65535",
                "-o",
                "no-dir/out.png",
            ],
            &dir,
        );
        let err = stderr(&out);
        assert_eq!(out.status.code(), Some(1), "{err}");
        assert!(
            err.starts_with("no-dir/out.png: error: cannot write:"),
            "{err}"
        );
    }
    // A directory is not a file to write.
    let out = shadeline(
        &["render", "--width", "8", "--height", "6", "-o", "."],
        &dir,
    );
    assert_eq!(out.status.code(), Some(1), "{}", stderr(&out));
    assert!(
        stderr(&out).contains(".: error: cannot write:"),
        "{}",
        stderr(&out)
    );
}

#[test]
fn a_negative_number_is_refused_as_a_value_not_taken_for_an_option() {
    let dir = temp_dir("negative");
    for (option, words) in [
        (
            "--width",
            "a size is a whole number of pixels, from 1 to 65535",
        ),
        (
            "--height",
            "a size is a whole number of pixels, from 1 to 65535",
        ),
        ("--threads", "-5 is not in 1..=65535"),
        ("--repeat", "-5 is not in 1..=65535"),
    ] {
        let out = shadeline(&["render", option, "-5"], &dir);
        let err = stderr(&out);
        assert_eq!(out.status.code(), Some(2), "{err}");
        assert!(
            err.contains(&format!("invalid value '-5' for '{option}")),
            "{err}"
        );
        assert!(err.contains(words), "{err}");
        assert!(!err.contains("-- -5"), "{err}");
    }
    assert!(!dir.join("spheres.png").exists());
}

#[test]
fn a_scene_file_and_a_preset_together_are_one_accurate_message() {
    let dir = temp_dir("file-and-preset");
    std::fs::write(dir.join("scene.toml"), exponent_series_text()).unwrap();
    for args in [
        ["render", "scene.toml", "--preset", "materials"],
        ["compare", "--preset", "materials", "scene.toml"],
    ] {
        let out = shadeline(&args, &dir);
        assert_refused(
            &out,
            &["error: both a scene file (scene.toml) and --preset materials were given"],
        );
        assert!(!stderr(&out).contains("Usage"), "{}", stderr(&out));
    }
}

#[test]
fn an_empty_scene_file_names_the_missing_table_once() {
    let dir = temp_dir("empty");
    std::fs::write(dir.join("empty.toml"), "").unwrap();
    let out = shadeline(&["render", "empty.toml"], &dir);
    assert_refused(&out, &["empty.toml:1:1: error: missing key `image`"]);
    assert_eq!(stderr(&out).matches("image").count(), 1, "{}", stderr(&out));
}

#[test]
fn render_writes_an_rgb_png_of_the_asked_size() {
    let dir = temp_dir("render-size");
    let out = shadeline(
        &[
            "render", "--width", "64", "--height", "48", "--path", "simd",
        ],
        &dir,
    );
    assert!(out.status.success(), "{}", stderr(&out));
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(stdout.contains("64x48 simd8"), "{stdout}");
    assert!(stdout.contains("Mpix/s"), "{stdout}");
    let (w, h, color, depth, pixels) = read_png(&dir.join("spheres.png"));
    assert_eq!(
        (w, h, color, depth),
        (64, 48, png::ColorType::Rgb, png::BitDepth::Eight)
    );
    // The background (top-left) and the middle sphere row differ.
    let at = |x: usize, y: usize| &pixels[(y * 64 + x) * 3..][..3];
    assert_ne!(at(0, 0), at(32, 24));
}

#[test]
fn render_uses_the_widest_simd_path_unless_told_otherwise() {
    let dir = temp_dir("default-path");
    let size = ["--width", "40", "--height", "30"];
    let run = |extra: &[&str]| {
        let args: Vec<&str> = ["render"]
            .iter()
            .chain(&size)
            .chain(extra)
            .copied()
            .collect();
        let out = shadeline(&args, &dir);
        assert!(out.status.success(), "{}", stderr(&out));
        String::from_utf8_lossy(&out.stdout).into_owned()
    };
    let default = run(&["-o", "default.png"]);
    assert!(default.starts_with("40x30 simd8 "), "{default}");
    // The kernel the path takes: the exponent series is the narrow kernel's.
    assert!(default.contains("simd8    kernel: narrow"), "{default}");
    let scalar = run(&["--path", "scalar", "-o", "scalar.png"]);
    assert!(scalar.starts_with("40x30 scalar "), "{scalar}");
    // The same bits either way.
    assert_eq!(
        read_png(&dir.join("default.png")).4,
        read_png(&dir.join("scalar.png")).4
    );
}

#[test]
fn the_thread_count_does_not_change_a_byte() {
    let dir = temp_dir("threads");
    std::fs::write(dir.join("scene.toml"), exponent_series_text()).unwrap();
    for path in ["scalar", "simd4", "simd8", "fixed"] {
        let mut files = Vec::new();
        for threads in ["1", "3"] {
            let name = format!("{path}-{threads}.png");
            let out = shadeline(
                &[
                    "render",
                    "scene.toml",
                    "--width",
                    "96",
                    "--height",
                    "70",
                    "--path",
                    path,
                    "--threads",
                    threads,
                    "-o",
                    &name,
                ],
                &dir,
            );
            assert!(out.status.success(), "{}", stderr(&out));
            files.push(std::fs::read(dir.join(&name)).unwrap());
        }
        assert!(files[0].len() > 100);
        assert_eq!(
            files[0], files[1],
            "{path}: --threads 3 differs from --threads 1"
        );
    }
}

#[test]
fn compare_prints_one_row_per_path_and_writes_the_picture() {
    let dir = temp_dir("compare");
    let out = shadeline(
        &[
            "compare",
            "--width",
            "40",
            "--height",
            "30",
            "--threads",
            "2",
        ],
        &dir,
    );
    assert!(out.status.success(), "{}", stderr(&out));
    let stdout = String::from_utf8_lossy(&out.stdout);
    let paths = ["scalar", "simd4", "simd8", "fixed"];
    for path in paths {
        assert!(
            stdout
                .lines()
                .any(|l| l.starts_with(path) && l.contains("dB")),
            "{stdout}"
        );
    }
    // The kernel each path takes, with its reason where it is not the narrow one.
    for path in paths {
        assert!(
            stdout
                .lines()
                .any(|l| l.starts_with(path) && l.contains("kernel: narrow")),
            "{stdout}"
        );
    }
    // The reference, then one panel per path.
    let (w, h, ..) = read_png(&dir.join("compare.png"));
    assert_eq!((w, h), (40 * (paths.len() as u32 + 1), 30 * 2));
}

#[test]
fn without_a_scene_the_exponent_series_and_the_presets_render_at_their_files_sizes() {
    let dir = temp_dir("defaults");
    let scenes = concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes/");
    for (args, file, size) in [
        (
            &["render"][..],
            "exponent-series.toml",
            shadeline::EXPONENT_SERIES_SIZE,
        ),
        (
            &["render", "--preset", "materials"][..],
            "materials.toml",
            shadeline::MATERIALS_SIZE,
        ),
    ] {
        let built_in: Vec<&str> = args.iter().copied().chain(["-o", "a.png"]).collect();
        let out = shadeline(&built_in, &dir);
        assert!(out.status.success(), "{}", stderr(&out));
        let scene = format!("{scenes}{file}");
        let out = shadeline(&["render", &scene, "-o", "b.png"], &dir);
        assert!(out.status.success(), "{}", stderr(&out));
        let (a, b) = (read_png(&dir.join("a.png")), read_png(&dir.join("b.png")));
        assert_eq!((a.0, a.1), size, "{args:?}");
        assert_eq!((b.0, b.1), size, "{file}");
        assert!(a.4 == b.4, "{args:?} is not the picture of {file}");
    }
}

#[test]
fn an_unknown_path_is_refused_naming_it() {
    let dir = temp_dir("unknown-path");
    let out = shadeline(&["render", "--path", "simd16"], &dir);
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(!err.contains("panicked"), "{err}");
    assert!(err.starts_with("error:") && err.contains("simd16"), "{err}");
    assert!(!dir.join("spheres.png").exists());
}

#[test]
fn antialias_smooths_every_path() {
    let dir = temp_dir("antialias");
    let size = ["--width", "96", "--height", "72"];
    let render = |extra: &[&str], out: &str| {
        let mut args = vec!["render", "--repeat", "1", "-o", out];
        args.extend_from_slice(&size);
        args.extend_from_slice(extra);
        shadeline(&args, &dir)
    };
    for (extra, out) in [
        (&[][..], "sharp.png"),
        (&["--antialias"][..], "smooth.png"),
        (
            &["--antialias", "--path", "scalar"][..],
            "smooth-scalar.png",
        ),
    ] {
        let run = render(extra, out);
        assert!(run.status.success(), "{extra:?}: {}", stderr(&run));
    }
    let (sharp, smooth) = (
        read_png(&dir.join("sharp.png")),
        read_png(&dir.join("smooth.png")),
    );
    assert_ne!(sharp.4, smooth.4, "--antialias changed no pixel");
    // The widest SIMD path and the scalar path agree bit for bit with edges on too.
    assert_eq!(smooth.4, read_png(&dir.join("smooth-scalar.png")).4);
    // The fixed path anti-aliases too: its frame differs from its sharp one.
    for (extra, out) in [
        (&["--path", "fixed"][..], "fixed-sharp.png"),
        (&["--antialias", "--path", "fixed"][..], "fixed-smooth.png"),
    ] {
        let run = render(extra, out);
        assert!(run.status.success(), "{extra:?}: {}", stderr(&run));
    }
    assert_ne!(
        read_png(&dir.join("fixed-sharp.png")).4,
        read_png(&dir.join("fixed-smooth.png")).4,
        "--antialias changed no pixel of the fixed frame"
    );
}

#[test]
fn render_names_the_kernel_and_why() {
    let dir = temp_dir("kernel");
    let out = shadeline(
        &[
            "render",
            "--preset",
            "area-lights",
            "--width",
            "32",
            "--height",
            "24",
            "--path",
            "fixed",
            "--repeat",
            "1",
            "-o",
            "area.png",
        ],
        &dir,
    );
    assert!(out.status.success(), "{}", stderr(&out));
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        stdout.contains("fixed    kernel: full-width, because of light 0: `radius`"),
        "{stdout}"
    );
}

/// The long options of `shadeline COMMAND --help`, without `--help`.
fn help_options(command: &str) -> std::collections::BTreeSet<String> {
    let dir = temp_dir(&format!("help_{command}"));
    let out = shadeline(&[command, "--help"], &dir);
    assert!(out.status.success(), "{}", stderr(&out));
    let text = String::from_utf8(out.stdout).unwrap();
    let options = text.split("Options:").nth(1).expect("an Options section");
    long_options(options)
        .into_iter()
        .filter(|o| o != "--help")
        .collect()
}

/// Every `--word` in `text`.
fn long_options(text: &str) -> Vec<String> {
    text.split(|c: char| !(c.is_ascii_alphanumeric() || c == '-'))
        .filter(|w| w.starts_with("--") && w.len() > 2)
        .map(str::to_string)
        .collect()
}

/// The options a usage block (`shadeline COMMAND …` lines, continued on indented lines)
/// shows for `command`, and the preset names it lists, if it lists them.
fn usage_options(block: &str, command: &str) -> std::collections::BTreeSet<String> {
    let mut options = std::collections::BTreeSet::new();
    let mut inside = false;
    for line in block.lines() {
        let line = line.trim_start_matches("//!").trim();
        if let Some(rest) = line.strip_prefix("shadeline ") {
            inside = rest.split_whitespace().next() == Some(command);
        }
        if inside {
            options.extend(long_options(line));
            // `-o` is `--output`'s short form in the usage lines.
            if line.contains("[-o ") {
                options.insert("--output".into());
            }
        }
    }
    options
}

/// The usage lines of `docs/harness.md` and of the binary's own docs name exactly the options
/// each command's `--help` lists, and the page lists every preset.
#[test]
fn usage_lines_match_the_help() {
    let root = concat!(env!("CARGO_MANIFEST_DIR"), "/..");
    let page = std::fs::read_to_string(format!("{root}/docs/harness.md")).unwrap();
    let main = std::fs::read_to_string(format!("{root}/harness/src/main.rs")).unwrap();
    let blocks = [
        (
            "docs/harness.md",
            page.split("```sh")
                .nth(1)
                .unwrap()
                .split("```")
                .next()
                .unwrap(),
        ),
        (
            "harness/src/main.rs",
            main.split("```text")
                .nth(1)
                .unwrap()
                .split("```")
                .next()
                .unwrap(),
        ),
    ];
    for command in ["render", "compare", "plot", "show", "animate"] {
        let help = help_options(command);
        assert!(
            help.contains("--output") || help.contains("--preset"),
            "{help:?}"
        );
        for (file, block) in blocks {
            let shown = usage_options(block, command);
            assert_eq!(shown, help, "{file}: the usage of `shadeline {command}`");
        }
    }
    let presets = shadeline_harness::scene_file::PRESETS.join("|");
    assert!(
        page.contains(&format!("--preset {presets}]")),
        "docs/harness.md lists the presets"
    );
}

/// A frame renders once more per `--repeat`, and a cheap frame five times by default: the
/// report says how it was timed.
#[test]
fn repeats_are_reported_as_asked() {
    let dir = temp_dir("repeats");
    for (args, timed) in [
        (&["--repeat", "3"][..], "(median of 3, best "),
        (&[][..], "(median of 5, best "),
    ] {
        let mut all = vec!["render", "--width", "64", "--height", "48", "-o", "r.png"];
        all.extend_from_slice(args);
        let out = shadeline(&all, &dir);
        assert!(out.status.success(), "{}", stderr(&out));
        let report = String::from_utf8(out.stdout).unwrap();
        assert!(report.contains(timed), "{args:?}: {report}");
    }
}

/// A reader that closes its end of the pipe before the command prints (`shadeline … | head
/// -0`) ends the command quietly, with success, and the picture is still written.
#[test]
fn a_closed_standard_output_ends_the_command_quietly() {
    let dir = temp_dir("closed_stdout");
    let mut child = Command::new(env!("CARGO_BIN_EXE_shadeline"))
        .args([
            "render",
            "--preset",
            "floor",
            "--width",
            "320",
            "--height",
            "240",
            "--path",
            "scalar",
            "--repeat",
            "5",
            "-o",
            "floor.png",
        ])
        .current_dir(&dir)
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("the binary runs");
    // The reader goes away at once: five frames take far longer than this.
    drop(child.stdout.take());
    let out = child.wait_with_output().expect("the binary ends");
    assert!(out.status.success(), "{:?}: {}", out.status, stderr(&out));
    assert!(stderr(&out).is_empty(), "{}", stderr(&out));
    assert_eq!(read_png(&dir.join("floor.png")).0, 320);
}
