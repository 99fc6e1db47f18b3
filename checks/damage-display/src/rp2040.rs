//! The Raspberry Pi Pico: SPI1 at 62.5 MHz to the panel, wired as the Waveshare Pico-LCD-2
//! (DC GP8, CS GP9, SCK GP10, MOSI GP11, RST GP12, backlight GP13).

use embedded_hal::digital::OutputPin;
use embedded_hal::spi::MODE_0;
use embedded_hal_bus::spi::ExclusiveDevice;
use mipidsi::interface::SpiInterface;
use mipidsi::models::ST7789;
use mipidsi::options::{ColorInversion, Orientation, Rotation};
use mipidsi::Builder;
use rp2040_hal::fugit::RateExtU32;
use rp2040_hal::{self as hal, entry, gpio, pac, Clock};

/// The second-stage boot loader for the Pico's W25Q080 flash, in the first 256 bytes of flash.
#[allow(unsafe_code)] // the lint counts `link_section`: the linker, not Rust, places the data
#[link_section = ".boot2"]
#[used]
pub static BOOT2_FIRMWARE: [u8; 256] = rp2040_boot2::BOOT_LOADER_W25Q080;

/// The Pico's crystal.
const XTAL_FREQ_HZ: u32 = 12_000_000;

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
    let sio = hal::Sio::new(pac.SIO);
    let pins = gpio::Pins::new(
        pac.IO_BANK0,
        pac.PADS_BANK0,
        sio.gpio_bank0,
        &mut pac.RESETS,
    );
    let mut delay = hal::Timer::new(pac.TIMER, &mut pac.RESETS, &clocks);

    let dc = pins.gpio8.into_push_pull_output();
    let cs = pins.gpio9.into_push_pull_output();
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
    let spi = ExclusiveDevice::new_no_delay(spi, cs).unwrap();
    let mut bytes = [0; 512];
    let mut display = Builder::new(ST7789, SpiInterface::new(spi, dc, &mut bytes))
        .orientation(Orientation::new().rotate(Rotation::Deg90))
        .invert_colors(ColorInversion::Inverted)
        .reset_pin(rst)
        .init(&mut delay)
        .unwrap();
    backlight.set_high().unwrap();
    super::animate(&mut display)
}
