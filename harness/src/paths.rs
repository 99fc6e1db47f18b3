//! The rendering paths the harness knows, by name, behind one object-safe interface.
//!
//! [`PATHS`] lists every path of the core crate. A path is anything with a constructor
//! `new(&scene, width, height) -> Result<Self, RenderError>` that implements
//! [`shadeline::Render`]; adding one (the fixed-point path, say) is one line in [`PATHS`].

use crate::rows::{render_rows, render_rows_into, FrameError};
use crate::scene_file::{FileScene, MAX_LIGHTS, MAX_SPHERES};
use shadeline::damage::Damage;
use shadeline::{
    FloatPath, HitRecord, Kernel, Pixel, Prepared, PreparedFixed, Render, RenderError, Rgb565,
    Rgb888, Scalar, Simd4, Simd8,
};

/// A frame prepared on some path, rendered whole into a new buffer on `threads` threads.
///
/// [`Render`] has generic methods and so cannot be a trait object; this is the part of it the
/// harness needs, for the two pixel formats it uses.
pub trait Frame: Sync {
    /// The frame as 8-bit RGB, in a new buffer (allocated fallibly).
    fn render_rgb(&self, threads: usize) -> Result<Vec<Rgb888>, FrameError>;
    /// The frame as 8-bit RGB into an existing buffer of width × height pixels.
    fn render_rgb_into(&self, frame: &mut [Rgb888], threads: usize) -> Result<(), RenderError>;
    /// The frame as 5-6-5 levels ([`Rgb565`]) into an existing buffer of width × height
    /// pixels.
    fn render_rgb565_into(&self, frame: &mut [Rgb565], threads: usize) -> Result<(), RenderError>;
    /// The frame's hit records: which sphere each pixel shows and which lights are blocked.
    fn render_hits(&self, threads: usize) -> Result<Vec<HitRecord>, FrameError>;
    /// The kernel the frame's rows take, and why.
    fn kernel(&self) -> Kernel;
    /// The frame as [`Any`](std::any::Any), so that [`Frame::damage_since`] can find the
    /// shown frame's path.
    fn as_any(&self) -> &dyn std::any::Any;
    /// The pixels that can differ between `shown` (the scene of `shown_frame`, the frame
    /// just shown) and `next` (this frame's scene): [`Damage::between`] when both frames are
    /// of one path, the whole frame when they are not.
    fn damage_since(&self, shown: &FileScene, shown_frame: &dyn Frame, next: &FileScene) -> Damage;
}

impl<R: Render + Sync + 'static> Frame for R {
    fn kernel(&self) -> Kernel {
        Render::kernel(self)
    }
    fn as_any(&self) -> &dyn std::any::Any {
        self
    }
    fn damage_since(&self, shown: &FileScene, shown_frame: &dyn Frame, next: &FileScene) -> Damage {
        match shown_frame.as_any().downcast_ref::<R>() {
            Some(shown_frame) => Damage::between(shown, shown_frame, next, self),
            None => Damage::full(next, self.width(), self.height()),
        }
    }
    fn render_rgb(&self, threads: usize) -> Result<Vec<Rgb888>, FrameError> {
        render_rows(self.width(), self.height(), threads, |y, row| {
            self.render_line(y, row)
        })
    }
    fn render_rgb_into(&self, frame: &mut [Rgb888], threads: usize) -> Result<(), RenderError> {
        render_into(self, frame, threads)
    }
    fn render_rgb565_into(&self, frame: &mut [Rgb565], threads: usize) -> Result<(), RenderError> {
        render_into(self, frame, threads)
    }
    fn render_hits(&self, threads: usize) -> Result<Vec<HitRecord>, FrameError> {
        render_rows(self.width(), self.height(), threads, |y, row| {
            self.render_line(y, row)
        })
    }
}

/// Renders every row of `frame` (which must be the frame's width × height) on `threads`
/// threads.
fn render_into<R: Render + Sync, P: Pixel + Send>(
    r: &R,
    frame: &mut [P],
    threads: usize,
) -> Result<(), RenderError> {
    let expected = r.width() as usize * r.height() as usize;
    if frame.len() != expected {
        return Err(RenderError::FrameLength {
            expected,
            got: frame.len(),
        });
    }
    render_rows_into(frame, r.width(), threads, |y, row| r.render_line(y, row))
}

/// How a frame is rendered beyond its scene and size.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Options {
    /// Analytic anti-aliasing of the silhouettes (every path's `with_antialiasing`).
    pub antialias: bool,
}

/// Why a path cannot prepare a frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PrepareError {
    /// The core refused the scene or the size.
    Render(RenderError),
}

impl From<RenderError> for PrepareError {
    fn from(e: RenderError) -> Self {
        PrepareError::Render(e)
    }
}

impl std::fmt::Display for PrepareError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            PrepareError::Render(e) => e.fmt(f),
        }
    }
}

impl std::error::Error for PrepareError {}

/// Prepares a scene at a size on one path.
pub type Prepare = fn(&FileScene, u32, u32, Options) -> Result<Box<dyn Frame>, PrepareError>;

/// One path: its name on the command line and in reports, and how to prepare a frame on it.
#[derive(Clone, Copy)]
pub struct Path {
    /// The name (`scalar`, `simd4`, `simd8`, `fixed`).
    pub name: &'static str,
    /// Prepares a frame on this path.
    pub prepare: Prepare,
}

impl std::fmt::Debug for Path {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name)
    }
}

/// Boxes a prepared frame of any path.
fn boxed<R: Render + Sync + 'static>(
    frame: Result<R, RenderError>,
) -> Result<Box<dyn Frame>, PrepareError> {
    Ok(Box::new(frame?))
}

/// A float path's frame with the options applied.
fn float<W: FloatPath + Sync + 'static>(
    s: &FileScene,
    w: u32,
    h: u32,
    options: Options,
) -> Result<Box<dyn Frame>, PrepareError>
where
    W::Lane: Sync,
{
    boxed(Prepared::<W, S, L>::new(s, w, h).map(|f| f.with_antialiasing(options.antialias)))
}

const S: usize = MAX_SPHERES;
const L: usize = MAX_LIGHTS;

/// Every path, narrowest first. `render`'s default is [`SIMD_ALIAS`], the widest SIMD path.
pub const PATHS: &[Path] = &[
    path("scalar", float::<Scalar>),
    path("simd4", float::<Simd4>),
    path("simd8", float::<Simd8>),
    path("fixed", |s, w, h, options| {
        boxed(PreparedFixed::<S, L>::new(s, w, h).map(|f| f.with_antialiasing(options.antialias)))
    }),
];

/// What the harness prints for a path's kernel: the fixed path's general kernel is its
/// full-width one.
pub fn kernel_line(path: &str, kernel: Kernel) -> String {
    match kernel {
        Kernel::Narrow => format!("{path:<8} kernel: narrow"),
        Kernel::General { item, field } => {
            let name = if path == "fixed" {
                "full-width"
            } else {
                "general"
            };
            format!("{path:<8} kernel: {name}, because of {item}: `{field}`")
        }
    }
}

/// A [`Path`] entry of [`PATHS`].
const fn path(name: &'static str, prepare: Prepare) -> Path {
    Path { name, prepare }
}

/// The alias for the widest SIMD path, and `render`'s default path.
pub const SIMD_ALIAS: (&str, &str) = ("simd", "simd8");

/// The path called `name` (or the alias `simd`).
pub fn find(name: &str) -> Option<Path> {
    let name = if name == SIMD_ALIAS.0 {
        SIMD_ALIAS.1
    } else {
        name
    };
    PATHS.iter().copied().find(|p| p.name == name)
}

/// Every name `--path` accepts.
pub fn names() -> Vec<&'static str> {
    let mut names: Vec<_> = PATHS.iter().map(|p| p.name).collect();
    names.push(SIMD_ALIAS.0);
    names
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_name_finds_its_path_and_simd_is_the_widest() {
        for name in names() {
            assert!(find(name).is_some(), "{name}");
        }
        assert_eq!(find("simd").unwrap().name, "simd8");
        assert!(find("fast").is_none());
    }
}
