//! The STM32F411 "Black Pill": 25 MHz crystal, 100 MHz system clock, SPI1 at 50 MHz (half
//! APB2) to the panel: SCK PA5, MOSI PA7, CS PA4, DC PB0, RST PB1, backlight PB10.

use cortex_m_rt::entry;
use embedded_hal::spi::MODE_0;
use embedded_hal_bus::spi::ExclusiveDevice;
use mipidsi::interface::SpiInterface;
use mipidsi::models::ST7789;
use mipidsi::options::{ColorInversion, Orientation, Rotation};
use mipidsi::Builder;
use stm32f4xx_hal::pac::{self, SPI1};
use stm32f4xx_hal::prelude::*;
use stm32f4xx_hal::rcc::Config;

#[entry]
fn main() -> ! {
    let dp = pac::Peripherals::take().unwrap();
    let mut rcc = dp.RCC.freeze(Config::hse(25.MHz()).sysclk(100.MHz()));
    let mut delay = dp.TIM1.delay_us(&mut rcc);
    let gpioa = dp.GPIOA.split(&mut rcc);
    let gpiob = dp.GPIOB.split(&mut rcc);

    let spi = dp.SPI1.spi(
        (Some(gpioa.pa5), SPI1::NoMiso, Some(gpioa.pa7)),
        MODE_0,
        50.MHz(),
        &mut rcc,
    );
    let cs = gpioa.pa4.into_push_pull_output();
    let dc = gpiob.pb0.into_push_pull_output();
    let rst = gpiob.pb1.into_push_pull_output();
    let mut backlight = gpiob.pb10.into_push_pull_output();
    let spi = ExclusiveDevice::new_no_delay(spi, cs).unwrap();
    let mut bytes = [0; 512];
    let mut display = Builder::new(ST7789, SpiInterface::new(spi, dc, &mut bytes))
        .orientation(Orientation::new().rotate(Rotation::Deg90))
        .invert_colors(ColorInversion::Inverted)
        .reset_pin(rst)
        .init(&mut delay)
        .unwrap();
    backlight.set_high();
    super::animate(&mut display)
}
