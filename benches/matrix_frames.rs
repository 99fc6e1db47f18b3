//! Renders one preset frame a given number of times on one path, single thread, and prints
//! the frame's covered pixels and kernel: a fixed workload for instruction counts on the
//! host, where criterion's times are too noisy to compare kernels by. A bench target without
//! criterion's harness, so that the test command does not build it:
//!
//! ```sh
//! exe=$(cargo bench --bench matrix_frames --no-run 2>&1 | sed -n 's/.*Executable .*(\(.*\))$/\1/p')
//! valgrind --tool=callgrind --callgrind-out-file=/tmp/cg.out "$exe" floor simd8 11
//! ```
//!
//! The scene is `floor`, `lamp` or `three-lights` (the scene matrix, at `MATRIX_SIZE`) or
//! `exponent-series` (at 320×240, the firmware's frame); the path `scalar`, `simd4`, `simd8`
//! or `fixed`. The frames are rendered into `Rgb888`, as `benches/render.rs` renders them.
//! Start-up, the prepare and the covered count are the same for any number of frames, so
//! the difference of two runs' instruction counts (say 11 frames and 1) divided by the
//! difference of their frames is one frame's. The covered pixels are counted from the path's
//! own hit records before the timed frames, as `tests/firmware_crcs.rs` counts them.

use shadeline::*;
use std::hint::black_box;
use std::process::ExitCode;

/// The exponent series' frame here: the firmware's size, 320×240.
const SERIES_SIZE: (u32, u32) = (320, 240);

/// Pixels whose primary ray hits a sphere, from the path's own hit records.
fn covered<R: Render>(frame: &R) -> usize {
    let mut hits = vec![HitRecord::default(); (frame.width() * frame.height()) as usize];
    frame.render_frame(&mut hits).unwrap();
    hits.iter().filter(|h| h.sphere.is_some()).count()
}

/// Prints the frame's size, covered pixels and kernel, then renders it `frames` times.
fn run<R: Render>(frame: R, path: &str, frames: u32) {
    let kernel = match frame.kernel() {
        Kernel::Narrow => "narrow".to_string(),
        Kernel::General { item, field } => format!("general, because of {item}: `{field}`"),
    };
    println!(
        "{}x{} {path}: covered={} kernel: {kernel}",
        frame.width(),
        frame.height(),
        covered(&frame)
    );
    let mut buf = vec![Rgb888::default(); (frame.width() * frame.height()) as usize];
    for _ in 0..frames {
        frame.render_frame(&mut buf).unwrap();
        black_box(&buf[0]);
    }
}

/// Prepares `scene` at `(w, h)` on `path` and renders it `frames` times; false for an
/// unknown path.
fn render<const S: usize, const L: usize>(
    scene: &Scene<S, L>,
    (w, h): (u32, u32),
    path: &str,
    frames: u32,
) -> bool {
    match path {
        "scalar" => run(
            Prepared::<Scalar, S, L>::new(scene, w, h).unwrap(),
            path,
            frames,
        ),
        "simd4" => run(
            Prepared::<Simd4, S, L>::new(scene, w, h).unwrap(),
            path,
            frames,
        ),
        "simd8" => run(
            Prepared::<Simd8, S, L>::new(scene, w, h).unwrap(),
            path,
            frames,
        ),
        "fixed" => run(
            PreparedFixed::<S, L>::new(scene, w, h).unwrap(),
            path,
            frames,
        ),
        _ => return false,
    }
    true
}

fn main() -> ExitCode {
    // `cargo bench` appends `--bench` to a bench target's arguments.
    let args: Vec<String> = std::env::args()
        .skip(1)
        .filter(|arg| arg != "--bench")
        .collect();
    let (scene, path, frames) = match &args[..] {
        [scene, path, frames] => (scene.as_str(), path.as_str(), frames.parse().ok()),
        _ => ("", "", None),
    };
    let done = frames.is_some_and(|frames| match scene {
        "floor" => render(&floor().unwrap(), MATRIX_SIZE, path, frames),
        "lamp" => render(&lamp().unwrap(), MATRIX_SIZE, path, frames),
        "three-lights" => render(&three_lights().unwrap(), MATRIX_SIZE, path, frames),
        "exponent-series" => render(&exponent_series().unwrap(), SERIES_SIZE, path, frames),
        _ => false,
    });
    if done {
        ExitCode::SUCCESS
    } else {
        eprintln!(
            "usage: matrix_frames floor|lamp|three-lights|exponent-series \
             scalar|simd4|simd8|fixed FRAMES"
        );
        ExitCode::FAILURE
    }
}
