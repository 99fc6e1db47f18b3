//! Sending a moving picture to a mipidsi panel, damage only: [`send_damage`] renders the
//! pixels of the next frame that can differ from the frame shown
//! ([`shadeline::damage::Damage`]) and writes each damaged range of a row to the panel with
//! `set_pixels`, an address window one row high. Nothing else goes over the bus, and no
//! framebuffer is kept: one row's buffer of [`Rgb565`](shadeline::Rgb565) holds what is in
//! flight. [`bounce`] makes the frames of a small animation for the example's `main`.
#![no_std]
#![deny(unsafe_code)]

use embedded_graphics_core::pixelcolor::Rgb565;
use embedded_hal::digital::OutputPin;
use mipidsi::interface::{Interface, InterfacePixelFormat};
use mipidsi::models::Model;
use mipidsi::Display;
use shadeline::damage::Damage;
use shadeline::{Render, RenderError, Scene, SceneError, Vec3};

/// Why a frame's damage could not be sent.
#[derive(Debug)]
pub enum SendError<E> {
    /// shadeline refused to render a range (a buffer of no pixels).
    Render(RenderError),
    /// The panel's interface failed.
    Display(E),
}

impl<E> From<RenderError> for SendError<E> {
    fn from(e: RenderError) -> Self {
        SendError::Render(e)
    }
}

/// Sends `display` the pixels of `frame` that `damage` holds, and returns how many: each
/// damaged range of a row is one `set_pixels` call (`CASET`, `RASET`, `RAMWR`, then the
/// range's pixels), rendered into `buffer` with `render_segment`. A `buffer` as wide as the
/// frame sends each range whole; a shorter one sends it in pieces of `buffer.len()`.
///
/// `damage` is [`Damage::between`] the frame on the panel and `frame`, or [`Damage::full`]
/// for the first frame. The panel's coordinates are the frame's (shadeline's frames are at
/// most 65,535 pixels a side, so they fit mipidsi's `u16`).
pub fn send<DI, M, RST, R, const N: usize>(
    display: &mut Display<DI, M, RST>,
    damage: &Damage<N>,
    frame: &R,
    buffer: &mut [shadeline::Rgb565],
) -> Result<u64, SendError<DI::Error>>
where
    DI: Interface,
    M: Model<ColorFormat = Rgb565>,
    Rgb565: InterfacePixelFormat<DI::Word>,
    RST: OutputPin,
    R: Render,
{
    let mut sent = 0;
    damage.render(frame, buffer, |x, y, pixels| {
        let (x0, y0) = (x as u16, y as u16);
        let x1 = x0 + (pixels.len() as u16 - 1);
        let colors = pixels.iter().map(|&p| Rgb565::from(p));
        display
            .set_pixels(x0, y0, x1, y0, colors)
            .map_err(SendError::Display)?;
        sent += pixels.len() as u64;
        Ok::<(), SendError<DI::Error>>(())
    })?;
    Ok(sent)
}

/// Sends `display` the damage between `shown` (the scene of `shown_frame`, the frame on the
/// panel) and `next` as `next_frame` renders it ([`send`]), and returns the pixels sent.
pub fn send_damage<DI, M, RST, R, const S: usize, const L: usize>(
    display: &mut Display<DI, M, RST>,
    (shown, shown_frame): (&Scene<S, L>, &R),
    (next, next_frame): (&Scene<S, L>, &R),
    buffer: &mut [shadeline::Rgb565],
) -> Result<u64, SendError<DI::Error>>
where
    DI: Interface,
    M: Model<ColorFormat = Rgb565>,
    Rgb565: InterfacePixelFormat<DI::Word>,
    RST: OutputPin,
    R: Render,
{
    let damage: Damage = Damage::between(shown, shown_frame, next, next_frame);
    send(display, &damage, next_frame, buffer)
}

/// Frames in one bounce of [`bounce`].
pub const BOUNCE_FRAMES: u32 = 30;

/// Frame `k` of a bounce: `scene` with sphere `sphere` lifted by `height` scene units at
/// the middle of every [`BOUNCE_FRAMES`] frames and resting at their ends (a parabola in
/// time, as a ball thrown up falls back; no trigonometry, so no maths library).
pub fn bounce<const S: usize, const L: usize>(
    scene: &Scene<S, L>,
    sphere: usize,
    height: f32,
    k: u32,
) -> Result<Scene<S, L>, SceneError> {
    let t = (k % BOUNCE_FRAMES) as f32 / BOUNCE_FRAMES as f32;
    let lift = height * 4.0 * t * (1.0 - t);
    let mut out = Scene::new(*scene.camera(), scene.background())?;
    for (i, s) in scene.spheres().iter().enumerate() {
        let mut s = *s;
        if i == sphere {
            s.center = s.center + Vec3::new(0.0, lift, 0.0);
        }
        out.add_sphere(s)?;
    }
    for light in scene.lights() {
        out.add_light(*light)?;
    }
    Ok(out)
}
