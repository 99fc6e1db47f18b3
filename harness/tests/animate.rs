//! `shadeline animate`, run as a user would: the animated PNG's frames, the per-frame report,
//! and the refusals.

mod common;

use common::{shadeline, stderr};
use shadeline_harness::apng::{decode, Decoded};
use std::path::Path;

fn read_apng(path: &Path) -> Decoded {
    decode(&std::fs::read(path).unwrap()).unwrap()
}

/// The pixels of a still PNG `render` wrote.
fn read_png(path: &Path) -> Vec<u8> {
    let file = std::io::BufReader::new(std::fs::File::open(path).unwrap());
    let mut reader = png::Decoder::new(file).read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut buf).unwrap();
    buf.truncate(info.buffer_size());
    buf
}

const TINY: [&str; 4] = ["--width", "32", "--height", "24"];

#[test]
fn an_orbiting_light_gives_n_frames_of_the_size_each_unlike_the_last() {
    let dir = common::temp_dir("animate", "orbit");
    let mut args = vec!["animate", "--preset", "floor", "--orbit-light", "0"];
    args.extend(["--frames", "5", "--path", "scalar", "-o", "orbit.png"]);
    args.extend(TINY);
    let out = shadeline(&args, &dir);
    assert!(out.status.success(), "{}", stderr(&out));
    let report = String::from_utf8(out.stdout).unwrap();
    let apng = read_apng(&dir.join("orbit.png"));
    assert_eq!((apng.width, apng.height, apng.announced), (32, 24, 5));
    assert_eq!(apng.frames.len(), 5);
    for (k, frame) in apng.frames.iter().enumerate() {
        assert_eq!(frame.len(), 32 * 24 * 3);
        if k > 0 {
            assert_ne!(frame, &apng.frames[k - 1], "frame {k} is frame {}", k - 1);
        }
        // One line per frame, with the bytes of a full RGB565 frame: 32 × 24 × 2 and one
        // address window's 11 command bytes.
        let line = format!("frame {}/5: ", k + 1);
        let line = report.lines().find(|l| l.starts_with(&line)).expect(&line);
        assert!(line.contains(" ms, full frame 1547 bytes; "), "{line}");
    }
    assert!(report.contains("a display is sent 7735 bytes for the 5 full RGB565 frames"));
    // Frame 0 is the scene as it is: what `render` draws on the same path.
    let out = shadeline(
        &[
            &["render", "--preset", "floor", "--path", "scalar"][..],
            &TINY,
            &["-o", "still.png"],
        ]
        .concat(),
        &dir,
    );
    assert!(out.status.success(), "{}", stderr(&out));
    assert_eq!(apng.frames[0], read_png(&dir.join("still.png")));
}

#[test]
fn a_moving_sphere_ends_where_it_was_sent() {
    let dir = common::temp_dir("animate", "move");
    // The floor scene's sphere 1 (the leftmost resting on the floor) rolls toward the middle and
    // the camera.
    let mut args = vec!["animate", "--preset", "floor", "--move-sphere", "1"];
    args.extend(["--to=-1.8,0.7638,0.5", "--frames", "3", "-o", "move.png"]);
    args.extend(TINY);
    let out = shadeline(&args, &dir);
    assert!(out.status.success(), "{}", stderr(&out));
    let apng = read_apng(&dir.join("move.png"));
    assert_eq!((apng.announced, apng.frames.len()), (3, 3));
    assert_ne!(apng.frames[0], apng.frames[2]);
    assert_eq!(apng.rects[0], (0, 0, 32, 24));
}

/// The integer that ends `text` just before `suffix`'s first occurrence.
fn number_before(text: &str, suffix: &str) -> u64 {
    let end = text
        .find(suffix)
        .unwrap_or_else(|| panic!("`{suffix}` in {text}"));
    let head = &text[..end];
    let start = head
        .rfind(|c: char| !c.is_ascii_digit())
        .map_or(0, |i| i + 1);
    head[start..]
        .parse()
        .unwrap_or_else(|_| panic!("a number before `{suffix}` in {text}"))
}

/// A frame's or the summary's damage figures, as printed.
#[derive(Debug, Default, PartialEq)]
struct Figures {
    damage: u64,
    windows: u64,
    bytes: u64,
    changed: u64,
}

impl Figures {
    /// Reads `… N px in W windows, B bytes (…); changed C px, …` from `text`.
    fn parse(text: &str) -> Figures {
        let windows = if text.contains(" window, ") {
            " window, "
        } else {
            " windows, "
        };
        Figures {
            damage: number_before(text, " px in "),
            windows: number_before(text, windows),
            bytes: number_before(text, " bytes ("),
            changed: number_before(text, " px, tightness"),
        }
    }
}

#[test]
fn the_damage_figures_hold_every_change_cost_less_than_full_frames_and_add_up() {
    let dir = common::temp_dir("animate", "damage");
    let (w, h) = (64, 48);
    let full = w * h * 2 + 11;
    // Sphere 1 of the floor scene lifts off the floor, on the fixed path and on a float path.
    for path in ["fixed", "scalar"] {
        let mut args = vec!["animate", "--preset", "floor", "--move-sphere", "1"];
        args.extend(["--to=-1.5,1.6,0", "--frames", "4", "--path", path]);
        args.extend(["--width", "64", "--height", "48", "-o", "lift.png"]);
        let out = shadeline(&args, &dir);
        assert!(out.status.success(), "{}", stderr(&out));
        let report = String::from_utf8(out.stdout).unwrap();
        let apng = read_apng(&dir.join("lift.png"));
        let mut sum = Figures::default();
        for k in 1..=4 {
            let start = format!("frame {k}/4: ");
            let line = report
                .lines()
                .find(|l| l.starts_with(&start))
                .expect(&start);
            assert!(
                line.contains(&format!("full frame {full} bytes; ")),
                "{line}"
            );
            if k == 1 {
                assert!(line.ends_with("first frame, sent whole"), "{line}");
                continue;
            }
            let f = Figures::parse(line);
            // The changed pixels are those that differ between the animated PNG's frames.
            let (a, b) = (&apng.frames[k - 2], &apng.frames[k - 1]);
            let changed = a.chunks(3).zip(b.chunks(3)).filter(|(a, b)| a != b).count();
            assert_eq!(f.changed, changed as u64, "{path}: {line}");
            assert!(f.changed > 0, "{path}: {line}");
            assert!(f.damage >= f.changed, "{path}: {line}");
            assert_eq!(f.bytes, f.damage * 2 + f.windows * 11, "{path}: {line}");
            assert!(f.windows >= 1 && f.bytes < full, "{path}: {line}");
            assert!(!line.contains("OUTSIDE"), "{path}: {line}");
            sum = Figures {
                damage: sum.damage + f.damage,
                windows: sum.windows + f.windows,
                bytes: sum.bytes + f.bytes,
                changed: sum.changed + f.changed,
            };
        }
        let summary = (report.lines())
            .find(|l| l.starts_with("damage total over frames 2-4: "))
            .expect("the summary line");
        assert_eq!(Figures::parse(summary), sum, "{path}: {summary}");
        assert_eq!(number_before(summary, "); changed"), 3 * full, "{summary}");
        assert!(
            summary.ends_with("; 0 changed px outside the damage"),
            "{summary}"
        );
        let both = full + sum.bytes;
        assert!(
            report.contains(&format!(
                "{} bytes for the 4 full RGB565 frames, {both} for the first whole",
                4 * full
            )),
            "{report}"
        );
    }
}

#[test]
fn a_light_or_sphere_the_scene_lacks_is_refused_before_any_file_is_made() {
    let dir = common::temp_dir("animate", "refused");
    for (args, words) in [
        (
            &["--orbit-light", "2"][..],
            "error: --orbit-light 2: the scene has 2 lights (counted from 0)",
        ),
        (
            &["--move-sphere", "0", "--to", "1e9,0,0"][..],
            "error: frame 1: ",
        ),
    ] {
        let mut all = vec![
            "animate", "--preset", "floor", "--frames", "2", "-o", "x.png",
        ];
        all.extend_from_slice(args);
        let out = shadeline(&all, &dir);
        assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
        assert!(stderr(&out).starts_with(words), "{}", stderr(&out));
        assert!(!dir.join("x.png").exists());
    }
    // --to without --move-sphere, and neither motion, are usage errors.
    for args in [&["--to", "1,2,3"][..], &[][..]] {
        let mut all = vec!["animate", "--preset", "floor"];
        all.extend_from_slice(args);
        assert_eq!(shadeline(&all, &dir).status.code(), Some(2));
    }
}
