//! shadeline on an RP2040: a Raspberry Pi Pico drives a 320×240 ST7789 SPI panel, both
//! Cortex-M0+ cores shade rows with the fixed path, and every finished line goes to the panel
//! by DMA. No framebuffer: four line buffers of 640 bytes hold everything in flight.
//!
//! The M0+ has no FPU, so the frame is prepared once with [`PreparedFixed`] (integers only per
//! row and pixel) and shared by reference: a prepared frame is plain data, `Sync`, and
//! `render_line_bytes::<Rgb565>` writes the big-endian bytes the panel reads, so a shaded
//! line goes to the SPI peripheral as it is. Core 0 shades the even rows, core 1 the odd rows.
//!
//! One panel means one SPI bus, and core 0 owns it. It lends it to `mipidsi` for the panel's
//! initialisation and, once per frame, for the address window (`CASET`, `RASET`, `RAMWR`),
//! then takes it back and hands it to the DMA engine line by line: row 0, 1, 2, … in order,
//! the whole frame as one memory write.
//!
//! Each core has two line buffers, so that neither core waits for the wire:
//!
//! - core 0 stays one of its rows ahead: when row `y` goes out, row `y + 2` is already
//!   shaded in its other buffer, and while core 1's row `y + 1` goes out, core 0 shades row
//!   `y + 4` into the buffer that row `y` has just left;
//! - core 1 shades a row into one buffer while the other waits in a mailbox for core 0, goes
//!   out, and comes back through a second mailbox.
//!
//! The hand-over is two one-place mailboxes ([`Mailbox`]): `SHADED` carries `(row, line)` from
//! core 1 to core 0, `SENT` carries the sent line back. A line buffer is a
//! `&'static mut [u8; 640]` that moves between the cores, so only one core can reach it at a
//! time and the compiler checks it: the renderer cannot write a line that the DMA engine is
//! still reading, because the transfer owns it until `wait` gives it back. A mailbox holds the
//! HAL's critical section (a hardware spinlock) only to move the value in or out, and a core
//! that waits sleeps in `WFE` until the other core's `SEV`. The rows of both cores meet in
//! order because each core shades its rows in order and core 0 sends them alternately.
//!
//! The line buffers and the prepared frame live in statics (`cortex_m::singleton!`), since
//! DMA and the second core both need `'static` data. The example has no `unsafe` code
//! (`#![deny(unsafe_code)]`); the lint is allowed on one item, boot2's `#[link_section]`.
//!
//! Wiring is the Waveshare Pico-LCD-2 layout (SPI1): DC GP8, CS GP9, SCK GP10, MOSI GP11,
//! RST GP12, backlight GP13. The panel is the bus's only device, so CS stays low. The clocks
//! are the HAL's defaults (125 MHz system clock), which give the SPI its 62.5 MHz maximum.
//!
//! Compile-checked for thumbv6m-none-eabi by `.ci/rp2040-check` (built, not run);
//! `docs/firmware.md`, section "RP2040", gives the frame time the M0 instruction count implies.
#![no_std]
#![no_main]
#![deny(unsafe_code)]

use core::cell::Cell;

use critical_section::Mutex;
use embedded_hal::digital::{OutputPin, PinState};
use embedded_hal::spi::{SpiBus, MODE_0};
use mipidsi::interface::Interface;
use mipidsi::models::ST7789;
use mipidsi::options::{ColorInversion, Orientation, Rotation};
use mipidsi::Builder;
use panic_halt as _;
use rp2040_hal::dma::{single_buffer, DMAExt, SingleChannel, WriteTarget};
use rp2040_hal::fugit::RateExtU32;
use rp2040_hal::multicore::{Multicore, Stack};
use rp2040_hal::{self as hal, entry, gpio, pac, Clock};
use shadeline::{exponent_series_with_capacity, PreparedFixed, Render, Rgb565, Scene};

/// The second-stage boot loader for the Pico's W25Q080 flash, in the first 256 bytes of flash.
#[allow(unsafe_code)] // the lint counts `link_section`: the linker, not Rust, places the data
#[link_section = ".boot2"]
#[used]
pub static BOOT2_FIRMWARE: [u8; 256] = rp2040_boot2::BOOT_LOADER_W25Q080;

/// The scene's capacities: the exponent series' 5 spheres and 1 light. A prepared frame holds
/// the narrow kernel's quadrics per sphere and light, so at the default capacities (16, 8) it
/// takes 14,456 bytes of RAM; at these, 1,928.
const SPHERES: usize = 5;
const LIGHTS: usize = 1;

/// The prepared frame both cores share.
type Frame = PreparedFixed<SPHERES, LIGHTS>;

/// The Pico's crystal.
const XTAL_FREQ_HZ: u32 = 12_000_000;
/// The panel in landscape.
const WIDTH: u32 = 320;
const HEIGHT: u32 = 240;
/// Bytes per line: RGB565, 2 bytes per pixel, big-endian as the panel reads them.
const LINE_BYTES: usize = 2 * WIDTH as usize;

/// One line buffer, owned by whichever core or DMA transfer holds the reference.
type Line = &'static mut [u8; LINE_BYTES];

/// Core 1's stack, 16 KiB: room to shade a row, with margin. (Core 0 runs on cortex-m-rt's
/// stack, the rest of RAM.)
static CORE1_STACK: Stack<4096> = Stack::new();

/// Lines core 1 has shaded, with their row, on their way to core 0.
static SHADED: Mailbox<(u32, Line)> = Mailbox::new();
/// Core 1's lines coming back from core 0 once the DMA engine has sent them.
static SENT: Mailbox<Line> = Mailbox::new();

/// A one-place mailbox between the two cores: [`put`](Mailbox::put) waits while it is full,
/// [`take`](Mailbox::take) while it is empty.
///
/// The critical section (rp2040-hal's: interrupts off and hardware spinlock 31) is held only
/// to look at the slot. A core that has to wait sleeps in `WFE`; the other core's `SEV` after
/// every put and take wakes it to look again. An `SEV` that comes between the look and the
/// `WFE` is not lost: it sets the event register, and `WFE` returns at once.
pub struct Mailbox<T>(Mutex<Cell<Option<T>>>);

impl<T> Mailbox<T> {
    const fn new() -> Self {
        Self(Mutex::new(Cell::new(None)))
    }

    /// Puts `value` in the mailbox, waiting until it is empty.
    fn put(&self, value: T) {
        let mut value = Some(value);
        loop {
            critical_section::with(|cs| {
                let slot = self.0.borrow(cs);
                let held = slot.take();
                slot.set(if held.is_none() { value.take() } else { held });
            });
            if value.is_none() {
                cortex_m::asm::sev();
                return;
            }
            cortex_m::asm::wfe();
        }
    }

    /// Takes the value out of the mailbox, waiting until there is one.
    fn take(&self) -> T {
        loop {
            if let Some(value) = critical_section::with(|cs| self.0.borrow(cs).take()) {
                cortex_m::asm::sev();
                return value;
            }
            cortex_m::asm::wfe();
        }
    }
}

/// Shades row `y` into `line`. Rows in range into a line of the right length cannot fail; a
/// row that did would go out black.
fn shade(frame: &Frame, y: u32, line: &mut [u8; LINE_BYTES]) {
    if frame.render_line_bytes::<Rgb565>(y, line).is_err() {
        line.fill(0);
    }
}

/// Core 1: shades the odd rows, frame after frame, and posts each line to core 0.
fn core1_rows(frame: &Frame, first: Line, second: Line) -> ! {
    let mut spare = Some(second);
    let mut line = first;
    loop {
        for y in (1..HEIGHT).step_by(2) {
            shade(frame, y, line);
            SHADED.put((y, line));
            // The second buffer first; after that, each line as core 0 sends it back.
            line = spare.take().unwrap_or_else(|| SENT.take());
        }
    }
}

/// Core 0's part of a frame: shades the even rows and sends all rows in order by DMA on
/// `ch`, to the panel behind `spi` (its address window already set). Returns its two line
/// buffers, the channel and the SPI peripheral when the last line is out of memory.
fn send_frame<CH, S>(frame: &Frame, lines: [Line; 2], ch: CH, spi: S) -> ([Line; 2], CH, S)
where
    CH: SingleChannel,
    S: WriteTarget<TransmittedWord = u8>,
{
    let [first, mut ahead] = lines;
    shade(frame, 0, first);
    let mut transfer = single_buffer::Config::new(ch, first, spi).start();
    shade(frame, 2, ahead);
    // Each pass starts with row `y` on the wire and row `y + 2` (if any) shaded in `ahead`.
    let mut y = 0;
    loop {
        let (row, theirs) = SHADED.take();
        debug_assert_eq!(row, y + 1);
        let (ch, mine, spi) = transfer.wait();
        let odd = single_buffer::Config::new(ch, theirs, spi).start();
        // While core 1's row goes out, shade row `y + 4` into the line that just came back.
        if y + 4 < HEIGHT {
            shade(frame, y + 4, mine);
        }
        let (ch, theirs, spi) = odd.wait();
        SENT.put(theirs);
        if y + 2 >= HEIGHT {
            return ([mine, ahead], ch, spi);
        }
        transfer = single_buffer::Config::new(ch, ahead, spi).start();
        ahead = mine;
        y += 2;
    }
}

/// Why a command to the panel failed.
#[derive(Debug)]
pub enum PanelError<E> {
    /// The SPI peripheral failed.
    Spi(E),
    /// The data/command pin could not be set.
    Dc,
    /// The SPI peripheral is lent to the DMA engine (a frame is being sent).
    BusLent,
}

/// The panel's command interface for `mipidsi`: the SPI bus in a shared cell, so that core 0
/// can take the bus out for the DMA transfers between commands, and the data/command pin.
///
/// Every write waits until the bus is idle before `DC` changes, since a byte still shifting
/// out must not change meaning; `DC` stays high after a command, so the pixel data that
/// follows `RAMWR` (the DMA transfers) goes out as data.
pub struct PanelBus<'a, S, DC> {
    spi: &'a Cell<Option<S>>,
    dc: DC,
}

impl<S: SpiBus<u8>, DC: OutputPin> PanelBus<'_, S, DC> {
    fn with_bus(
        &mut self,
        f: impl FnOnce(&mut S, &mut DC) -> Result<(), PanelError<S::Error>>,
    ) -> Result<(), PanelError<S::Error>> {
        let mut spi = self.spi.take().ok_or(PanelError::BusLent)?;
        let result = f(&mut spi, &mut self.dc);
        self.spi.set(Some(spi));
        result
    }
}

/// Writes `bytes` and waits until the last bit is out.
fn write_all<S: SpiBus<u8>>(spi: &mut S, bytes: &[u8]) -> Result<(), PanelError<S::Error>> {
    spi.write(bytes).map_err(PanelError::Spi)?;
    spi.flush().map_err(PanelError::Spi)
}

impl<S: SpiBus<u8>, DC: OutputPin> Interface for PanelBus<'_, S, DC> {
    type Word = u8;
    type Error = PanelError<S::Error>;

    fn send_command(&mut self, command: u8, args: &[u8]) -> Result<(), Self::Error> {
        self.with_bus(|spi, dc| {
            // The last line of a frame may still be shifting out of the FIFO.
            spi.flush().map_err(PanelError::Spi)?;
            dc.set_low().map_err(|_| PanelError::Dc)?;
            write_all(spi, &[command])?;
            dc.set_high().map_err(|_| PanelError::Dc)?;
            write_all(spi, args)
        })
    }

    fn send_pixels<const N: usize>(
        &mut self,
        pixels: impl IntoIterator<Item = [u8; N]>,
    ) -> Result<(), Self::Error> {
        self.with_bus(|spi, _| {
            for pixel in pixels {
                spi.write(&pixel).map_err(PanelError::Spi)?;
            }
            spi.flush().map_err(PanelError::Spi)
        })
    }

    fn send_repeated_pixel<const N: usize>(
        &mut self,
        pixel: [u8; N],
        count: u32,
    ) -> Result<(), Self::Error> {
        self.with_bus(|spi, _| {
            for _ in 0..count {
                spi.write(&pixel).map_err(PanelError::Spi)?;
            }
            spi.flush().map_err(PanelError::Spi)
        })
    }
}

#[entry]
fn main() -> ! {
    let mut pac = pac::Peripherals::take().unwrap();
    let mut watchdog = hal::Watchdog::new(pac.WATCHDOG);
    let clocks = hal::clocks::init_clocks_and_plls(
        XTAL_FREQ_HZ,
        pac.XOSC,
        pac.CLOCKS,
        pac.PLL_SYS,
        pac.PLL_USB,
        &mut pac.RESETS,
        &mut watchdog,
    )
    .ok()
    .unwrap();
    let mut sio = hal::Sio::new(pac.SIO);
    let pins = gpio::Pins::new(
        pac.IO_BANK0,
        pac.PADS_BANK0,
        sio.gpio_bank0,
        &mut pac.RESETS,
    );
    let mut delay = hal::Timer::new(pac.TIMER, &mut pac.RESETS, &clocks);

    // The frame, prepared once and shared by both cores. (Preparing uses soft-float on the M0+;
    // an animating firmware prepares a new frame whenever the scene moves.)
    let scene: Scene<SPHERES, LIGHTS> = exponent_series_with_capacity().unwrap();
    let prepared = Frame::new(&scene, WIDTH, HEIGHT).unwrap();
    let frame: &'static Frame = cortex_m::singleton!(: Frame = prepared).unwrap();
    let lines = cortex_m::singleton!(: [[u8; LINE_BYTES]; 4] = [[0; LINE_BYTES]; 4]).unwrap();
    let [mine_a, mine_b, theirs_a, theirs_b] = lines;

    // Core 1 starts shading at once; its first line waits in the mailbox for core 0.
    let mut mc = Multicore::new(&mut pac.PSM, &mut pac.PPB, &mut sio.fifo);
    let core1 = &mut mc.cores()[1];
    core1
        .spawn(CORE1_STACK.take().unwrap(), move || {
            core1_rows(frame, theirs_a, theirs_b)
        })
        .unwrap();

    // The panel: SPI1 at 62.5 MHz (half the peripheral clock, the PL022's maximum).
    let dc = pins.gpio8.into_push_pull_output();
    let _cs = pins.gpio9.into_push_pull_output_in_state(PinState::Low);
    let sclk = pins.gpio10.into_function::<gpio::FunctionSpi>();
    let mosi = pins.gpio11.into_function::<gpio::FunctionSpi>();
    let rst = pins.gpio12.into_push_pull_output();
    let mut backlight = pins.gpio13.into_push_pull_output();
    let spi = hal::spi::Spi::<_, _, _, 8>::new(pac.SPI1, (mosi, sclk)).init(
        &mut pac.RESETS,
        clocks.peripheral_clock.freq(),
        62_500_000u32.Hz(),
        MODE_0,
    );
    let bus = Cell::new(Some(spi));
    let mut display = Builder::new(ST7789, PanelBus { spi: &bus, dc })
        .orientation(Orientation::new().rotate(Rotation::Deg90))
        .invert_colors(ColorInversion::Inverted)
        .reset_pin(rst)
        .init(&mut delay)
        .unwrap();
    backlight.set_high().unwrap();

    let dma = pac.DMA.split(&mut pac.RESETS);
    let mut ch = dma.ch0;
    let mut lines = [mine_a, mine_b];
    loop {
        // mipidsi sets the address window and starts the memory write; no pixels through it.
        display
            .set_pixels(
                0,
                0,
                WIDTH as u16 - 1,
                HEIGHT as u16 - 1,
                core::iter::empty(),
            )
            .unwrap();
        let spi = bus.take().unwrap();
        let (back, ch_back, spi) = send_frame(frame, lines, ch, spi);
        bus.set(Some(spi));
        (lines, ch) = (back, ch_back);
    }
}
