//! A display render loop as firmware writes it: shade a row into one line buffer while the
//! previous row goes to the display by DMA from the other, then swap. No framebuffer, no
//! allocation: two `2 × WIDTH`-byte buffers on the stack hold the whole image in flight.
//!
//! The display side is the [`DmaDisplay`] trait, standing for a SPI panel (ST7789, ILI9341)
//! behind a DMA channel: `set_window` sends the column/row address commands and `RAMWR`,
//! `start_transfer` hands a line buffer to the DMA engine and returns at once, `wait` blocks
//! until the transfer is done and hands the buffer back. Passing the buffer by `&mut` in and
//! out is what makes the double buffering safe: the renderer cannot write a buffer the DMA
//! engine is still reading, and the compiler checks it.
//!
//! Built for thumbv7em-none-eabihf by `.ci/display-loop-check`; `display_loop` is exported
//! so the whole loop is compiled (monomorphized) and kept.
#![no_std]
#![no_main]

use core::panic::PanicInfo;
use shadeline::{
    exponent_series, Encoding, Prepared, PreparedFixed, Render, RenderError, Rgb565, Scalar,
};

/// Display size in pixels (a 320×240 ST7789/ILI9341 panel in landscape).
const WIDTH: usize = 320;
const HEIGHT: usize = 240;
/// Bytes per line: RGB565, 2 bytes per pixel, big-endian as the panel reads them.
const LINE_BYTES: usize = 2 * WIDTH;

/// A display controller reached through a DMA channel.
pub trait DmaDisplay<'buf> {
    /// Why a command or transfer failed.
    type Error;
    /// Selects the rectangle `x0..=x1`, `y0..=y1` (pixels) and starts a memory write into it
    /// (`CASET`, `RASET`, `RAMWR`): the bytes of the following transfers fill it row by row.
    fn set_window(&mut self, x0: u16, y0: u16, x1: u16, y1: u16) -> Result<(), Self::Error>;
    /// Starts sending `bytes` and returns at once; the display owns them until [`wait`].
    ///
    /// [`wait`]: DmaDisplay::wait
    fn start_transfer(&mut self, bytes: &'buf mut [u8]) -> Result<(), Self::Error>;
    /// Blocks until the transfer started last is complete and returns its buffer.
    fn wait(&mut self) -> Result<&'buf mut [u8], Self::Error>;
}

/// Why a frame could not be shown.
#[derive(Debug)]
pub enum ShowError<E> {
    /// The renderer refused a row (a buffer of the wrong length, say).
    Render(RenderError),
    /// The display interface failed.
    Display(E),
}

/// Shows one frame: row `y + 1` is shaded while row `y` is on its way to the display.
pub fn show_frame<'buf, R: Render, D: DmaDisplay<'buf>>(
    frame: &R,
    display: &mut D,
    lines: [&'buf mut [u8]; 2],
) -> Result<(), ShowError<D::Error>> {
    let (w, h) = (frame.width(), frame.height());
    display
        .set_window(0, 0, (w - 1) as u16, (h - 1) as u16)
        .map_err(ShowError::Display)?;
    let [mut ready, mut spare] = lines;
    frame
        .render_line_bytes::<Rgb565>(0, ready)
        .map_err(ShowError::Render)?;
    for y in 0..h {
        display.start_transfer(ready).map_err(ShowError::Display)?;
        if y + 1 < h {
            // The CPU shades the next row while the DMA engine sends this one.
            frame
                .render_line_bytes::<Rgb565>(y + 1, spare)
                .map_err(ShowError::Render)?;
        }
        let sent = display.wait().map_err(ShowError::Display)?;
        ready = spare;
        spare = sent;
    }
    Ok(())
}

/// A stand-in for the SPI + DMA peripheral: it "sends" by folding the bytes into a checksum,
/// so the loop is complete and compiles exactly as it would against a HAL.
pub struct ChecksumDisplay<'buf> {
    in_flight: Option<&'buf mut [u8]>,
    pub checksum: u32,
    pub window: (u16, u16, u16, u16),
}

impl<'buf> DmaDisplay<'buf> for ChecksumDisplay<'buf> {
    type Error = ();

    fn set_window(&mut self, x0: u16, y0: u16, x1: u16, y1: u16) -> Result<(), ()> {
        self.window = (x0, y0, x1, y1);
        Ok(())
    }

    fn start_transfer(&mut self, bytes: &'buf mut [u8]) -> Result<(), ()> {
        if self.in_flight.is_some() {
            return Err(()); // one transfer at a time, like one DMA stream
        }
        self.in_flight = Some(bytes);
        Ok(())
    }

    fn wait(&mut self) -> Result<&'buf mut [u8], ()> {
        let bytes = self.in_flight.take().ok_or(())?;
        for b in bytes.iter() {
            self.checksum = self.checksum.rotate_left(5) ^ u32::from(*b);
        }
        Ok(bytes)
    }
}

/// The firmware's main loop body: prepares the scene once, then shows it on the float path
/// (Cortex-M4F has an FPU) and on the fixed path (what a Cortex-M0 would use), sRGB with
/// ordered dithering. Returns the checksum of what was sent, or 0 on an error.
#[no_mangle]
pub fn display_loop() -> u32 {
    let Ok(scene) = exponent_series() else {
        return 0;
    };
    let mut a = [0u8; LINE_BYTES];
    let mut b = [0u8; LINE_BYTES];
    let mut display = ChecksumDisplay {
        in_flight: None,
        checksum: 0,
        window: (0, 0, 0, 0),
    };
    let encoding = Encoding::SRGB.dithered();
    if let Ok(frame) = Prepared::<Scalar>::new(&scene, WIDTH as u32, HEIGHT as u32) {
        let frame = frame.with_encoding(encoding);
        if show_frame(&frame, &mut display, [&mut a, &mut b]).is_err() {
            return 0;
        }
    }
    let mut c = [0u8; LINE_BYTES];
    let mut d = [0u8; LINE_BYTES];
    let mut display_fixed = ChecksumDisplay {
        in_flight: None,
        checksum: display.checksum,
        window: (0, 0, 0, 0),
    };
    if let Ok(frame) = PreparedFixed::<16, 8>::new(&scene, WIDTH as u32, HEIGHT as u32) {
        let frame = frame.with_encoding(encoding);
        if show_frame(&frame, &mut display_fixed, [&mut c, &mut d]).is_err() {
            return 0;
        }
    }
    display_fixed.checksum
}

#[panic_handler]
fn panic(_: &PanicInfo) -> ! {
    loop {}
}
