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
        // One line per frame, with the bytes of a full RGB565 frame: 32 × 24 × 2.
        let line = format!("frame {}/5: ", k + 1);
        let line = report.lines().find(|l| l.starts_with(&line)).expect(&line);
        assert!(line.ends_with("full frame 1536 bytes"), "{line}");
    }
    assert!(report.contains("a display is sent 7680 bytes for the 5 full RGB565 frames"));
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
