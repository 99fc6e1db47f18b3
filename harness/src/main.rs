//! The `shadeline` command: render a scene to PNG on one path, or compare every path with the
//! `f64` reference.
//!
//! ```text
//! shadeline render  [SCENE.toml | --preset NAME] [--path scalar|simd4|simd8|simd|fixed]
//!                   [-o spheres.png] [--threads N] [--width W] [--height H] [--repeat N] [--antialias]
//! shadeline compare [SCENE.toml | --preset NAME] [-o compare.png] [--threads N] [--width W] [--height H] [--antialias]
//! shadeline plot    [SCENE.toml | --preset NAME] [--sphere N] [--incidence DEG] [-o lobes.svg]
//! shadeline show    [SCENE.toml | --preset NAME] [--fb /dev/fb0] [--path scalar|simd4|simd8|simd|fixed]
//!                   [--threads N] [--width W] [--height H] [--antialias]
//! shadeline animate [SCENE.toml | --preset NAME] (--orbit-light I | --move-sphere I --to X,Y,Z)
//!                   [--frames N] [--fps F] [--path scalar|simd4|simd8|simd|fixed] [-o animation.png]
//!                   [--threads N] [--width W] [--height H] [--antialias]
//! ```
//!
//! `render` uses the widest SIMD path unless `--path` names another (its frames are
//! bit-identical to `scalar`'s); `compare` runs every path; `plot` draws sphere `N`'s BRDF
//! and the scene's `cos^n` curves to an SVG ([`shadeline_harness::plot`]).
//!
//! `--preset materials` is the gallery of reflection models (`scenes/materials.toml`,
//! 768×432), `--preset microfacets` sets GGX and Oren–Nayar next to their normalized
//! counterparts (`scenes/microfacets.toml`, 960×480), and `--preset full-moon` is a Lambert
//! and an Oren–Nayar sphere lit from behind the viewer (`scenes/full-moon.toml`, 640×320);
//! `--preset area-lights` is four spheres of growing shininess under one sphere light
//! (`scenes/area-lights.toml`, 640×320); `--preset floor`, `lamp` and `three-lights` are the
//! scene matrix (spheres resting on a floor under distant lights, a point light, or both;
//! 320×240). Without a scene file or preset all three use the built-in exponent series (the numbers of
//! `scenes/exponent-series.toml`, 1024×747). A bad scene file is reported as one line
//! `FILE:LINE:COL: error: …` on stderr, with exit code 2; so is a bad size or a frame too
//! large for the memory, as one `error: …` line (the message names the size; buffers are
//! allocated fallibly), and an unknown `--path` is an `error:` naming it, exit code 2. The
//! output file is opened before rendering: an output that cannot be written is exit code 1,
//! before the render rather than after it. `plot` draws first (it takes milliseconds) and
//! writes after, so that a `--sphere` the scene does not have (exit code 2, naming
//! `--sphere` and the number of spheres) leaves an existing SVG alone; an `--incidence`
//! outside `[0, 90)` is refused with the other bad arguments, exit code 2.
//!
//! `show` draws the frame into a Linux framebuffer device at the screen's visible resolution
//! (`--width`/`--height`: a frame of that size, centred and cropped); a device that is
//! missing, is not a framebuffer or has a format shadeline does not write is an error naming
//! it, exit code 2 (see `shadeline_harness::fb_device`). `animate` writes an animated PNG of
//! a light orbiting the vertical axis or a sphere moving to a point
//! (`shadeline_harness::animation`), and prints per frame what a display would be sent.

use clap::builder::PossibleValuesParser;
use clap::{ArgGroup, Args, Parser, Subcommand};
use shadeline::{Rgb565, Rgb888, Vec3, MAX_DIMENSION};
use shadeline_harness::animation::{self, Motion};
use shadeline_harness::apng::AnimatedPng;
use shadeline_harness::bus::{tightness, Changed, Sent};
use shadeline_harness::compare::{self, Row};
use shadeline_harness::edges::{self, EdgeRow};
use shadeline_harness::image::PngFile;
use shadeline_harness::paths::{self, Frame, Options, Path, PrepareError, PATHS};
use shadeline_harness::plot::{self, PlotError};
use shadeline_harness::progress::Progress;
use shadeline_harness::rows::{check_memory, default_threads, new_frame, FrameError};
use shadeline_harness::scene_file::{
    builtin_scene, check_size, parse_scene, preset, FileScene, SceneFile, PRESETS,
};
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

/// Shades Phong-lit spheres one row at a time, with the shadeline core crate.
#[derive(Parser, Debug)]
#[command(name = "shadeline", version)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Render a scene to an 8-bit RGB PNG on one path and report the time.
    Render {
        #[command(flatten)]
        input: Input,
        /// The path: `simd` for the widest SIMD path (the default: it gives the same bits as
        /// `scalar`, faster), `simd4`, `simd8`, `scalar` (the float reference of the crate),
        /// or `fixed` (integers only per pixel).
        #[arg(long, default_value = paths::SIMD_ALIAS.0, value_parser = PossibleValuesParser::new(paths::names()))]
        path: String,
        /// Where to write the PNG.
        #[arg(short, long, default_value = "spheres.png")]
        output: PathBuf,
        /// Anti-alias the silhouettes analytically, as `antialias = true` under `[image]` does
        /// (every path).
        #[arg(long)]
        antialias: bool,
        /// Timed frames after one untimed warm-up frame; the median and best are reported.
        /// Without it: five where a frame takes under a quarter of a second, otherwise the
        /// first frame alone, timed.
        #[arg(long, allow_negative_numbers = true, value_parser = clap::value_parser!(u16).range(1..))]
        repeat: Option<u16>,
    },
    /// Compare every path with the f64 reference: a table, and a picture of the differences.
    Compare {
        #[command(flatten)]
        input: Input,
        /// Where to write the comparison PNG.
        #[arg(short, long, default_value = "compare.png")]
        output: PathBuf,
        /// Anti-alias the silhouettes analytically, as `antialias = true` under `[image]`
        /// does, and measure the edges against a 16×16 supersampled truth, next to 4×4
        /// supersampling.
        #[arg(long)]
        antialias: bool,
    },
    /// Plot a sphere's BRDF in the plane of incidence (polar, f·cos θ_o) and the lesson's
    /// max(0, cos α)^n curves for every shininess in the scene, to one SVG.
    Plot {
        #[command(flatten)]
        scene: SceneChoice,
        /// The sphere whose material is plotted, counted from 0 in the scene's order.
        #[arg(long, value_name = "N", default_value_t = 0, allow_negative_numbers = true, value_parser = sphere_index)]
        sphere: usize,
        /// The light's angle from the normal, in degrees: at least 0 and below 90.
        #[arg(long, value_name = "DEG", default_value_t = plot::DEFAULT_INCIDENCE, allow_negative_numbers = true, value_parser = incidence)]
        incidence: f64,
        /// Where to write the SVG.
        #[arg(short, long, default_value = "lobes.svg")]
        output: PathBuf,
    },
    /// Draw a scene into a Linux framebuffer (a panel, an fbtft SPI display) at the screen's
    /// resolution; with --width/--height, a frame of that size, centred and cropped.
    Show {
        #[command(flatten)]
        input: Input,
        /// The framebuffer device. Written formats: RGB565, BGR565, RGB888, BGR888,
        /// XRGB8888, XBGR8888 and the like (16, 24 or 32 bits, 5-6-5 or 8-8-8 channels).
        #[arg(long, value_name = "DEVICE", default_value = "/dev/fb0")]
        fb: PathBuf,
        /// The path, as for `render`.
        #[arg(long, default_value = paths::SIMD_ALIAS.0, value_parser = PossibleValuesParser::new(paths::names()))]
        path: String,
        /// Anti-alias the silhouettes analytically, as `antialias = true` under `[image]` does.
        #[arg(long)]
        antialias: bool,
    },
    /// Render an animation to an animated PNG: a light orbiting the vertical axis through the
    /// look-at point, or a sphere moving in a straight line; prints per frame what a display
    /// would be sent.
    #[command(group(ArgGroup::new("motion").required(true).args(["orbit_light", "move_sphere"])))]
    Animate {
        #[command(flatten)]
        input: Input,
        /// Orbit light I (from 0) once around the camera's up axis through its look-at point:
        /// a distant light's direction turns, a point light's position.
        #[arg(long, value_name = "I", allow_negative_numbers = true, value_parser = light_index)]
        orbit_light: Option<usize>,
        /// Move sphere I (from 0) at constant speed from its place to --to, reached at the
        /// last frame.
        #[arg(long, value_name = "I", requires = "to", allow_negative_numbers = true, value_parser = sphere_index)]
        move_sphere: Option<usize>,
        /// Where --move-sphere's sphere ends: x,y,z in scene units.
        #[arg(long, value_name = "X,Y,Z", requires = "move_sphere", allow_negative_numbers = true, value_parser = point)]
        to: Option<Vec3>,
        /// Frames in the animation.
        #[arg(long, default_value_t = 30, allow_negative_numbers = true, value_parser = clap::value_parser!(u16).range(1..))]
        frames: u16,
        /// Frames per second the animated PNG plays at.
        #[arg(long, default_value_t = 25, allow_negative_numbers = true, value_parser = clap::value_parser!(u16).range(1..))]
        fps: u16,
        /// The path, as for `render`.
        #[arg(long, default_value = paths::SIMD_ALIAS.0, value_parser = PossibleValuesParser::new(paths::names()))]
        path: String,
        /// Where to write the animated PNG.
        #[arg(short, long, default_value = "animation.png")]
        output: PathBuf,
        /// Anti-alias the silhouettes analytically, as `antialias = true` under `[image]` does.
        #[arg(long)]
        antialias: bool,
    },
}

/// Which scene: a file, a preset, or (with neither) the built-in exponent series.
#[derive(Args, Debug)]
struct SceneChoice {
    /// A scene file (TOML); without one (and without `--preset`), the built-in exponent series.
    scene: Option<PathBuf>,
    /// A built-in scene instead of a file: `exponent-series`, `materials` (the gallery of
    /// reflection models), `microfacets` (GGX and Oren–Nayar), `full-moon`, `area-lights`, or
    /// the scene matrix: `floor`, `lamp`, `three-lights`.
    #[arg(long, value_parser = PossibleValuesParser::new(PRESETS))]
    preset: Option<String>,
}

/// What to render, how large, on how many threads.
#[derive(Args, Debug)]
struct Input {
    #[command(flatten)]
    scene: SceneChoice,
    /// Image width in pixels, instead of the scene file's.
    #[arg(long, allow_negative_numbers = true, value_parser = pixels)]
    width: Option<u32>,
    /// Image height in pixels, instead of the scene file's.
    #[arg(long, allow_negative_numbers = true, value_parser = pixels)]
    height: Option<u32>,
    /// Threads to render rows on [default: the available parallelism].
    #[arg(long, allow_negative_numbers = true, value_parser = clap::value_parser!(u16).range(1..))]
    threads: Option<u16>,
}

/// `--width`/`--height`: a whole number of pixels. Negative numbers reach this parser as
/// values (rather than as unknown options), so `-5` is refused as a size; 0 and sizes above
/// the largest are refused by the size check, which names the limit.
fn pixels(value: &str) -> Result<u32, String> {
    value
        .parse()
        .map_err(|_| format!("a size is a whole number of pixels, from 1 to {MAX_DIMENSION}"))
}

/// `--sphere`: a sphere's place in the scene, from 0. Whether the scene has it is checked once
/// the scene is read.
fn sphere_index(value: &str) -> Result<usize, String> {
    value
        .parse()
        .map_err(|_| "a sphere is a whole number, from 0 for the scene's first sphere".to_string())
}

/// `--orbit-light`: a light's place in the scene, from 0. Whether the scene has it is checked
/// once the scene is read.
fn light_index(value: &str) -> Result<usize, String> {
    value
        .parse()
        .map_err(|_| "a light is a whole number, from 0 for the scene's first light".to_string())
}

/// `--to`: a point `x,y,z` in scene units.
fn point(value: &str) -> Result<Vec3, String> {
    let refused = || format!("a point is x,y,z: three numbers separated by commas, not `{value}`");
    let numbers: Vec<f32> = value
        .split(',')
        .map(|n| n.trim().parse::<f32>().map_err(|_| refused()))
        .collect::<Result<_, _>>()?;
    match numbers[..] {
        [x, y, z] if numbers.iter().all(|n| n.is_finite()) => Ok(Vec3::new(x, y, z)),
        _ => Err(refused()),
    }
}

/// `--incidence`: degrees from the normal, in `[0, 90)`.
fn incidence(value: &str) -> Result<f64, String> {
    let refused =
        || "an incidence is in degrees from the normal, at least 0 and below 90".to_string();
    let degrees: f64 = value.parse().map_err(|_| refused())?;
    plot::check_incidence(degrees).map_err(|_| refused())
}

/// A failure: the message (already naming the file or option) and the exit code.
struct Failure {
    message: String,
    code: u8,
}

impl Failure {
    /// Bad input (scene file, size): exit code 2.
    fn input(message: String) -> Self {
        Failure { message, code: 2 }
    }
    /// The output could not be written: exit code 1.
    fn output(message: String) -> Self {
        Failure { message, code: 1 }
    }

    /// A frame that could not be rendered: a refusal of the renderer, or a frame too large
    /// for the memory (exit code 2, naming the size).
    fn frame(e: FrameError) -> Self {
        Failure::input(format!("error: {e}"))
    }
}

/// Opens the output before any rendering, so an unwritable path fails at once (exit code 1).
fn open_output(output: &std::path::Path) -> Result<PngFile, Failure> {
    PngFile::open(output).map_err(write_failed(output))
}

/// The output could not be written (exit code 1).
fn write_failed(output: &std::path::Path) -> impl FnOnce(std::io::Error) -> Failure + '_ {
    move |e| Failure::output(format!("{}: error: cannot write: {e}", output.display()))
}

/// Writes a line to standard output. A reader that has gone away (`shadeline … | head`)
/// ends the command quietly with success: what it asked for it has; any other write error
/// is reported and exits with 1.
macro_rules! say {
    ($($arg:tt)*) => {
        stdout_or_exit(format_args!("{}\n", format_args!($($arg)*)))
    };
}

/// [`say!`] without the line end.
macro_rules! say_raw {
    ($($arg:tt)*) => {
        stdout_or_exit(format_args!($($arg)*))
    };
}

/// Writes `text` to standard output: see [`say!`].
fn stdout_or_exit(text: std::fmt::Arguments) {
    use std::io::Write;
    let mut out = std::io::stdout().lock();
    if let Err(e) = out.write_fmt(text).and_then(|()| out.flush()) {
        if e.kind() == std::io::ErrorKind::BrokenPipe {
            std::process::exit(0);
        }
        eprintln!("standard output: {e}");
        std::process::exit(1);
    }
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Render {
            input,
            path,
            output,
            antialias,
            repeat,
        } => render(&input, &path, (&output, antialias), repeat.map(usize::from)),
        Command::Compare {
            input,
            output,
            antialias,
        } => run_compare(&input, &output, antialias),
        Command::Plot {
            scene,
            sphere,
            incidence,
            output,
        } => run_plot(&scene, sphere, incidence, &output),
        Command::Show {
            input,
            fb,
            path,
            antialias,
        } => run_show(&input, &fb, &path, antialias),
        Command::Animate {
            input,
            orbit_light,
            move_sphere,
            to,
            frames,
            fps,
            path,
            output,
            antialias,
        } => {
            // clap requires one of the two, and --to with --move-sphere.
            let motion = match (orbit_light, move_sphere, to) {
                (Some(light), _, _) => Ok(Motion::OrbitLight(light)),
                (None, Some(sphere), Some(to)) => Ok(Motion::MoveSphere { sphere, to }),
                _ => Err(Failure::input(
                    "error: give --orbit-light I, or --move-sphere I with --to X,Y,Z".into(),
                )),
            };
            let play = Playback {
                frames: u32::from(frames),
                fps,
            };
            motion.and_then(|m| run_animate(&input, m, play, &path, (&output, antialias)))
        }
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(failure) => {
            eprintln!("{}", failure.message);
            ExitCode::from(failure.code)
        }
    }
}

impl Input {
    fn threads(&self) -> usize {
        self.threads.map_or_else(default_threads, usize::from)
    }

    /// The rendering options: the scene file's, with `--antialias` turning edges on.
    fn options(file: &SceneFile, antialias: bool) -> Options {
        Options {
            antialias: antialias || file.antialias,
        }
    }

    /// Reads and checks the scene, applying `--width`/`--height`.
    fn load(&self) -> Result<SceneFile, Failure> {
        let mut file = self.scene.load()?;
        file.width = self.width.unwrap_or(file.width);
        file.height = self.height.unwrap_or(file.height);
        check_size(&file.scene, file.width, file.height)
            .map_err(|e| Failure::input(format!("error: --width/--height: {e}")))?;
        Ok(file)
    }
}

impl SceneChoice {
    /// Reads and checks the scene file, or builds the preset or the exponent series.
    fn load(&self) -> Result<SceneFile, Failure> {
        let failed = |e: shadeline::SceneError| Failure::input(format!("error: {e}"));
        Ok(match (&self.scene, &self.preset) {
            (Some(path), Some(name)) => {
                return Err(Failure::input(format!(
                    "error: both a scene file ({}) and --preset {name} were given: give one \
                     or the other",
                    path.display()
                )))
            }
            (Some(path), None) => read_scene(path)?,
            (None, Some(name)) => preset(name)
                .ok_or_else(|| Failure::input(format!("error: unknown preset `{name}`")))?
                .map_err(failed)?,
            (None, None) => builtin_scene().map_err(failed)?,
        })
    }
}

/// Reads a scene file; every problem is one `FILE:LINE:COL: error: …` (or `FILE: error: …`).
fn read_scene(path: &std::path::Path) -> Result<SceneFile, Failure> {
    let name = path.display();
    let bytes = std::fs::read(path)
        .map_err(|e| Failure::input(format!("{name}: error: cannot read the scene file: {e}")))?;
    let text = String::from_utf8(bytes).map_err(|e| {
        let valid = e.utf8_error().valid_up_to();
        let text = String::from_utf8_lossy(&e.as_bytes()[..valid]);
        let (line, column) = shadeline_harness::scene_file::line_column(&text, valid);
        let byte = e.as_bytes()[valid];
        Failure::input(format!(
            "{name}:{line}:{column}: error: the scene file is not UTF-8 text (byte 0x{byte:02x})"
        ))
    })?;
    parse_scene(&text).map_err(|e| Failure::input(format!("{name}:{e}")))
}

/// A frame that renders in less than this is timed over several repeats by default; a
/// slower one renders once (see `--repeat`).
const CHEAP_FRAME: f64 = 0.25;

/// Repeats of a cheap frame when `--repeat` is not given.
const DEFAULT_REPEAT: usize = 5;

fn render(
    input: &Input,
    path_name: &str,
    (output, antialias): (&std::path::Path, bool),
    repeat: Option<usize>,
) -> Result<(), Failure> {
    let file = input.load()?;
    let threads = input.threads();
    let path: Path = paths::find(path_name)
        .ok_or_else(|| Failure::input(format!("error: unknown path `{path_name}`")))?;
    let failed = |e: shadeline::RenderError| Failure::input(format!("error: {e}"));
    let options = Input::options(&file, antialias);
    let frame = (path.prepare)(&file.scene, file.width, file.height, options)
        .map_err(|e| Failure::input(format!("error: {e}")))?;
    let png = open_output(output)?;
    let mut rgb =
        new_frame(file.width, file.height).map_err(|e| Failure::frame(FrameError::TooLarge(e)))?;
    let rows = u64::from(file.height);
    // One frame first, timed: it faults the buffer's pages in and warms the caches, so the
    // repeats measure shading, not the operating system. A frame too slow to repeat cheaply
    // is reported from this one alone, unless `--repeat` asks for more.
    let first = {
        let _bar = Progress::start("rendering", rows);
        let start = Instant::now();
        frame.render_rgb_into(&mut rgb, threads).map_err(failed)?;
        start.elapsed().as_secs_f64()
    };
    let repeat = repeat.unwrap_or(if first < CHEAP_FRAME {
        DEFAULT_REPEAT
    } else {
        0
    });
    let mut times = Vec::with_capacity(repeat.max(1));
    {
        let _bar = Progress::start("timing", rows * repeat as u64);
        for _ in 0..repeat {
            let start = Instant::now();
            frame.render_rgb_into(&mut rgb, threads).map_err(failed)?;
            times.push(start.elapsed().as_secs_f64());
        }
    }
    let timed = if times.is_empty() {
        times.push(first);
        "one frame".to_string()
    } else {
        times.sort_by(f64::total_cmp);
        format!("median of {}, best {:.2} ms", times.len(), times[0] * 1e3)
    };
    let median = times[times.len() / 2];
    png.write_pixels(file.width, file.height, &rgb)
        .map_err(write_failed(output))?;
    let megapixels = f64::from(file.width) * f64::from(file.height) / 1e6;
    say!(
        "{}x{} {} on {} thread{}: {:.2} ms per frame ({timed}), {:.1} Mpix/s -> {}",
        file.width,
        file.height,
        path.name,
        threads,
        if threads == 1 { "" } else { "s" },
        median * 1e3,
        megapixels / median,
        output.display()
    );
    say!("{}", paths::kernel_line(path.name, frame.kernel()));
    Ok(())
}

/// Timed runs per path where a frame is cheap (see [`CHEAP_FRAME`]); the median is
/// reported. A slower frame is timed once.
const RUNS: usize = 3;

fn run_compare(input: &Input, output: &std::path::Path, antialias: bool) -> Result<(), Failure> {
    let file = input.load()?;
    let threads = input.threads();
    let (scene, w, h) = (&file.scene, file.width, file.height);
    let failed = |PrepareError::Render(e)| Failure::frame(e.into());
    let sharp = Options::default();
    let png = open_output(output)?;
    // Every buffer compare holds at once, checked before the first frame is rendered.
    check_memory(w, h, compare::bytes_per_pixel(PATHS.len()))
        .map_err(|e| Failure::frame(e.into()))?;
    let height = u64::from(h);
    let bar = Progress::start("comparing", height * (1 + 2 * PATHS.len() as u64));
    let reference = compare::render_reference(scene, w, h, threads).map_err(Failure::frame)?;
    let ref_rgb = compare::reference_rgb(&reference);
    let mut rows = Vec::new();
    let mut images = Vec::new();
    let mut notes = Vec::new();
    for path in PATHS {
        // A path that does not render something the scene holds (a shadeline built without
        // a feature the scene needs) is reported and left out, not the end of the comparison.
        match (path.prepare)(scene, w, h, sharp) {
            Err(PrepareError::Render(e)) => {
                notes.push(format!("{:<8} refused: {e}", path.name));
                images.push(vec![Rgb888::default(); w as usize * h as usize]);
                continue;
            }
            Ok(frame) => notes.push(paths::kernel_line(path.name, frame.kernel())),
        }
        let mut times = Vec::new();
        let mut rgb = Vec::new();
        for run in 0..RUNS {
            if run > 0 && times.iter().any(|&ms| ms >= CHEAP_FRAME * 1e3) {
                break;
            }
            let start = Instant::now();
            rgb = (path.prepare)(scene, w, h, sharp)
                .map_err(failed)?
                .render_rgb(threads)
                .map_err(Failure::frame)?;
            times.push(start.elapsed().as_secs_f64() * 1e3);
        }
        times.sort_by(f64::total_cmp);
        let hits = (path.prepare)(scene, w, h, sharp)
            .map_err(failed)?
            .render_hits(threads)
            .map_err(Failure::frame)?;
        rows.push(Row {
            name: path.name,
            stats: compare::stats(&reference, &ref_rgb, &rgb, &hits),
            millis: times[times.len() / 2],
        });
        images.push(rgb);
    }
    drop(bar);
    say!(
        "{w}x{h}, {threads} thread{}, against the f64 reference (8-bit levels; time is the \
         median of {RUNS}, or one frame where a frame takes {:.2} s or more)",
        if threads == 1 { "" } else { "s" },
        CHEAP_FRAME
    );
    say_raw!("{}", compare::table(&rows));
    for note in &notes {
        say!("{note}");
    }
    png.write_image(&compare::picture(w, h, &ref_rgb, &images))
        .map_err(write_failed(output))?;
    say!(
        "wrote {} (top: reference | {}; below each path: |path - reference| x {}; a path \
         that refused the scene is black)",
        output.display(),
        PATHS.iter().map(|p| p.name).collect::<Vec<_>>().join(" | "),
        compare::DIFF_GAIN
    );
    if Input::options(&file, antialias).antialias {
        // The truth, 4×4 supersampling, the sharp frame and every path's: a frame each.
        let frames = 3 + PATHS.len() as u64;
        let _bar = Progress::start("measuring the edges", height * frames);
        compare_edges(&file, threads)?;
    }
    Ok(())
}

/// The silhouette table: the sharp frame, 4×4 supersampling and every path with analytic
/// anti-aliasing against the 16×16 supersampled truth (see `shadeline_harness::edges`).
fn compare_edges(file: &SceneFile, threads: usize) -> Result<(), Failure> {
    let (scene, w, h) = (&file.scene, file.width, file.height);
    let truth =
        edges::box_filtered(scene, w, h, edges::TRUTH_SAMPLES, threads).map_err(Failure::frame)?;
    let supersampled: Vec<_> = edges::box_filtered(scene, w, h, edges::SUPERSAMPLES, threads)
        .map_err(Failure::frame)?
        .iter()
        .map(|p| p.color)
        .collect();
    let render = |frame: Box<dyn paths::Frame>| frame.render_rgb(threads).map_err(Failure::frame);
    let prepare_failed = |e: PrepareError| Failure::input(format!("error: {e}"));
    let mut rows = Vec::new();
    let mut push = |method: String, rgb: &[shadeline::Rgb888]| {
        if let Some(stats) = edges::edge_stats(&truth, rgb) {
            rows.push(EdgeRow { method, stats });
        }
    };
    let scalar = paths::find("scalar").expect("the scalar path is listed");
    let sharp = (scalar.prepare)(scene, w, h, Options::default()).map_err(prepare_failed)?;
    push("sharp (scalar)".into(), &render(sharp)?);
    let n = edges::SUPERSAMPLES;
    push(format!("{n}×{n} supersampling"), &supersampled);
    for path in PATHS {
        match (path.prepare)(scene, w, h, Options { antialias: true }) {
            Ok(frame) => push(format!("analytic ({})", path.name), &render(frame)?),
            Err(e) => return Err(prepare_failed(e)),
        }
    }
    let t = edges::TRUTH_SAMPLES;
    say!("\nsilhouettes against the {t}×{t} supersampled truth (8-bit levels):");
    if rows.is_empty() {
        say!("the frame has no silhouette pixels");
    } else {
        say_raw!("{}", edges::edge_table(&rows));
    }
    Ok(())
}

/// Writes the lobe plot of sphere `sphere` (see [`plot::figure`]). The figure is drawn (in
/// milliseconds) before the output is created, so a bad `--sphere` leaves an existing file as
/// it was.
fn run_plot(
    choice: &SceneChoice,
    sphere: usize,
    incidence: f64,
    output: &std::path::Path,
) -> Result<(), Failure> {
    let file = choice.load()?;
    let figure = plot::figure(file.scene.spheres(), sphere, incidence).map_err(|e| match e {
        PlotError::NoSuchSphere { .. } => Failure::input(format!("error: --sphere: {e}")),
        PlotError::Incidence(_) => Failure::input(format!("error: --incidence: {e}")),
        PlotError::Draw(_) => Failure::output(format!("{}: error: {e}", output.display())),
    })?;
    std::fs::write(output, &figure.svg).map_err(write_failed(output))?;
    let curves = figure.exponents.len();
    say!(
        "sphere {sphere} ({}), light at {incidence}° from the normal: f·cos θ_o peaks at \
         θ_o = {:.2}° (mirror direction {}°); {curves} curve{} of cos^n -> {}",
        figure.material,
        figure.peak.theta,
        plot::mirror_angle(incidence),
        if curves == 1 { "" } else { "s" },
        output.display()
    );
    Ok(())
}

/// Draws the scene into the framebuffer at `device` (see [`shadeline_harness::fb_device`]):
/// at the screen's visible size, or at `--width`/`--height` centred on it and cropped to it.
#[cfg(target_os = "linux")]
fn run_show(
    input: &Input,
    device: &std::path::Path,
    path_name: &str,
    antialias: bool,
) -> Result<(), Failure> {
    use shadeline_harness::fb_device::Device;
    use shadeline_harness::fb_pixels::{centred, write_frame, Depth};
    let mut file = input.scene.load()?;
    let path: Path = paths::find(path_name)
        .ok_or_else(|| Failure::input(format!("error: unknown path `{path_name}`")))?;
    let mut fb = Device::open(device).map_err(|e| Failure::input(e.to_string()))?;
    let screen = fb.screen;
    file.width = input.width.unwrap_or(screen.size.0);
    file.height = input.height.unwrap_or(screen.size.1);
    let (w, h) = (file.width, file.height);
    check_size(&file.scene, w, h).map_err(|e| {
        Failure::input(format!("error: {}: a {w}x{h} frame: {e}", device.display()))
    })?;
    let options = Input::options(&file, antialias);
    let frame = (path.prepare)(&file.scene, w, h, options)
        .map_err(|e| Failure::input(format!("error: {e}")))?;
    let window = centred((w, h), screen.size, screen.origin);
    let threads = input.threads();
    let failed = |e: shadeline::RenderError| Failure::input(format!("error: {e}"));
    let start = Instant::now();
    let written = {
        let _bar = Progress::start("rendering", u64::from(h));
        match screen.format.depth() {
            Ok(Depth::Bits565) => {
                let mut pixels = new_frame::<Rgb565>(w, h)
                    .map_err(|e| Failure::frame(FrameError::TooLarge(e)))?;
                frame
                    .render_rgb565_into(&mut pixels, threads)
                    .map_err(failed)?;
                write_frame(fb.memory(), &screen.format, &pixels, w, window)
            }
            Ok(Depth::Bits888) => {
                let mut pixels = new_frame::<Rgb888>(w, h)
                    .map_err(|e| Failure::frame(FrameError::TooLarge(e)))?;
                frame
                    .render_rgb_into(&mut pixels, threads)
                    .map_err(failed)?;
                write_frame(fb.memory(), &screen.format, &pixels, w, window)
            }
            // Device::open has refused the formats it does not write.
            Err(e) => Err(e.into()),
        }
    };
    written.map_err(|e| Failure::input(format!("{}: error: {e}", device.display())))?;
    say!(
        "{w}x{h} {} in {:.2} ms -> {} ({}: {}x{} {}, line length {} bytes), {}",
        path.name,
        start.elapsed().as_secs_f64() * 1e3,
        device.display(),
        fb.id(),
        screen.size.0,
        screen.size.1,
        screen.format.name(),
        screen.format.line_length,
        placement(window, screen.origin)
    );
    Ok(())
}

/// Where a frame went on the screen: `at (x, y)` of the visible area, and `cropped to W×H`
/// when only part of it fits.
#[cfg(target_os = "linux")]
fn placement(window: shadeline_harness::fb_pixels::Window, origin: (u32, u32)) -> String {
    let (x, y) = (window.to.0 - origin.0, window.to.1 - origin.1);
    let mut text = format!("at ({x}, {y})");
    if window.from != (0, 0) {
        text += &format!(", cropped to {}x{}", window.size.0, window.size.1);
    }
    text
}

/// `show` on a system without Linux framebuffers.
#[cfg(not(target_os = "linux"))]
fn run_show(
    _input: &Input,
    device: &std::path::Path,
    _path_name: &str,
    _antialias: bool,
) -> Result<(), Failure> {
    Err(Failure::input(format!(
        "{}: error: `show` draws into a Linux framebuffer device, and this system is not Linux",
        device.display()
    )))
}

/// How an animation plays: its frames, and how many a second.
#[derive(Clone, Copy, Debug)]
struct Playback {
    frames: u32,
    fps: u16,
}

/// Renders `motion` over `play.frames` frames to an animated PNG, printing a line per frame
/// ([`frame_report`]) and the damage's totals ([`damage_summary`]).
fn run_animate(
    input: &Input,
    motion: Motion,
    play: Playback,
    path_name: &str,
    (output, antialias): (&std::path::Path, bool),
) -> Result<(), Failure> {
    let file = input.load()?;
    let path: Path = paths::find(path_name)
        .ok_or_else(|| Failure::input(format!("error: unknown path `{path_name}`")))?;
    let (w, h) = (file.width, file.height);
    let frames = play.frames;
    // Every frame's scene is made once before the first is rendered, so a motion the core
    // refuses (a sphere moved out of range) fails at once, naming the frame.
    let scene_at = |k| {
        animation::scene_at(&file.scene, motion, k, frames)
            .map_err(|e| Failure::input(format!("error: {e}")))
    };
    for k in 0..frames {
        scene_at(k)?;
    }
    let png = open_output(output)?;
    let threads = input.threads();
    let options = Input::options(&file, antialias);
    let too_large = |e| Failure::frame(FrameError::TooLarge(e));
    // This frame and the one shown before it, to count the pixels that changed.
    let mut rgb = new_frame::<Rgb888>(w, h).map_err(too_large)?;
    let mut shown_rgb = new_frame::<Rgb888>(w, h).map_err(too_large)?;
    let mut bytes = Vec::new();
    let encoding = |e: std::io::Error| Failure::output(format!("{}: error: {e}", output.display()));
    let mut apng = AnimatedPng::new(&mut bytes, w, h, frames, play.fps).map_err(encoding)?;
    say!(
        "{frames} frame{} of {w}x{h} on {}, {} fps; {}",
        if frames == 1 { "" } else { "s" },
        path.name,
        play.fps,
        DAMAGE_NOTE
    );
    let mut shown: Option<(FileScene, Box<dyn Frame>)> = None;
    let mut totals = DamageFigures::default();
    {
        let _bar = Progress::start("animating", u64::from(h) * u64::from(frames));
        for k in 0..frames {
            let scene = scene_at(k)?;
            let start = Instant::now();
            let frame = (path.prepare)(&scene, w, h, options)
                .map_err(|e| Failure::input(format!("error: frame {k}: {e}")))?;
            frame
                .render_rgb_into(&mut rgb, threads)
                .map_err(|e| Failure::input(format!("error: frame {k}: {e}")))?;
            let millis = start.elapsed().as_secs_f64() * 1e3;
            apng.push(&rgb).map_err(encoding)?;
            let figures = shown.as_ref().map(|(shown_scene, shown_frame)| {
                let damage = frame.damage_since(shown_scene, shown_frame.as_ref(), &scene);
                DamageFigures {
                    sent: Sent::damage(&damage),
                    changed: Changed::between(&shown_rgb, &rgb, &damage),
                    frames: 1,
                }
            });
            say!("{}", frame_report(k, frames, (w, h), millis, figures));
            totals = totals.plus(figures.unwrap_or_default());
            std::mem::swap(&mut rgb, &mut shown_rgb);
            shown = Some((scene, frame));
        }
    }
    apng.finish().map_err(encoding)?;
    png.write_encoded(&bytes).map_err(write_failed(output))?;
    say!("{}", damage_summary(&totals, (w, h)));
    let full = Sent::full_frame(w, h).bytes() * u64::from(frames);
    let first_then_damage = Sent::full_frame(w, h).bytes() + totals.sent.bytes();
    say!(
        "wrote {} ({} bytes, animated PNG); a display is sent {full} bytes for the {frames} \
         full RGB565 frame{}, {first_then_damage} for the first whole and then the damage alone",
        output.display(),
        bytes.len(),
        if frames == 1 { "" } else { "s" }
    );
    Ok(())
}

/// What the per-frame lines report.
const DAMAGE_NOTE: &str = "bytes are what a display is sent: 2 per RGB565 pixel and 11 per \
                           address window (CASET, RASET, RAMWR); a full frame is one window, the \
                           damage one per damaged range of a row";

/// The damage's figures for one frame after the first, or summed over several.
#[derive(Clone, Copy, Debug, Default)]
struct DamageFigures {
    /// What a display is sent for the damage alone.
    sent: Sent,
    /// The pixels that changed from the frame shown, and those outside the damage.
    changed: Changed,
    /// The frames summed.
    frames: u32,
}

impl DamageFigures {
    fn plus(self, other: DamageFigures) -> DamageFigures {
        DamageFigures {
            sent: self.sent.plus(other.sent),
            changed: self.changed.plus(other.changed),
            frames: self.frames + other.frames,
        }
    }

    /// `D px in W windows, B bytes (P% of F full); changed C px, tightness T`, and
    /// the changed pixels outside the damage when there are any.
    fn describe(&self, full_bytes: u64) -> String {
        let (sent, changed) = (self.sent, self.changed);
        let tight = match tightness(sent.pixels, changed.pixels) {
            Some(t) => format!("{t:.2}"),
            None => "- (nothing changed)".to_string(),
        };
        let mut text = format!(
            "{} px in {} window{}, {} bytes ({:.1}% of {full_bytes}); changed {} px, \
             tightness {tight}",
            sent.pixels,
            sent.windows,
            if sent.windows == 1 { "" } else { "s" },
            sent.bytes(),
            100.0 * sent.bytes() as f64 / full_bytes.max(1) as f64,
            changed.pixels,
        );
        if changed.outside > 0 {
            text += &format!("; {} changed px OUTSIDE the damage", changed.outside);
        }
        text
    }
}

/// The line `animate` prints for frame `k` of `frames`: its number, its render time, the
/// bytes a display is sent for it as a full RGB565 frame, and, from the second frame on,
/// the damage since the frame before: its pixels, windows and bytes, the pixels that
/// actually changed and the tightness (damage ÷ changed). The first frame is sent whole.
fn frame_report(
    k: u32,
    frames: u32,
    (w, h): (u32, u32),
    millis: f64,
    damage: Option<DamageFigures>,
) -> String {
    let width = frames.to_string().len();
    let full = Sent::full_frame(w, h).bytes();
    let damage = match damage {
        Some(figures) => format!("damage {}", figures.describe(full)),
        None => "first frame, sent whole".to_string(),
    };
    format!(
        "frame {:>width$}/{frames}: {millis:7.2} ms, full frame {full} bytes; {damage}",
        k + 1
    )
}

/// The closing line: the damage summed over every frame after the first, against as many
/// full frames.
fn damage_summary(totals: &DamageFigures, (w, h): (u32, u32)) -> String {
    if totals.frames == 0 {
        return "damage total: none (one frame, sent whole)".to_string();
    }
    let full = Sent::full_frame(w, h).bytes() * u64::from(totals.frames);
    format!(
        "damage total over frames 2-{}: {}; {} changed px outside the damage",
        totals.frames + 1,
        totals.describe(full),
        totals.changed.outside
    )
}
