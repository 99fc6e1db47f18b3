//! CRC32/IEEE (reflected, polynomial `0xEDB88320`, initial and final XOR `!0`: the zlib/PNG
//! CRC) over RGB565 pixels as little-endian `u16` bytes.
//!
//! The frame CRC is the same whether the pixels come from a framebuffer or from a line buffer
//! streamed row by row, because the CRC is fed in row-major order either way. The table is
//! built at compile time (1 KiB of flash, no RAM); a byte costs a shift, an XOR and a lookup
//! whose index is masked to 8 bits, so the optimiser drops the bounds check.

use shadeline::Rgb565;

const POLY: u32 = 0xedb8_8320;

const TABLE: [u32; 256] = {
    let mut table = [0u32; 256];
    let mut i = 0;
    while i < 256 {
        let mut c = i as u32;
        let mut k = 0;
        while k < 8 {
            c = if c & 1 != 0 { (c >> 1) ^ POLY } else { c >> 1 };
            k += 1;
        }
        table[i] = c;
        i += 1;
    }
    table
};

/// A running CRC32 over pixels.
#[derive(Clone, Copy, Debug)]
pub struct Crc32 {
    state: u32,
}

impl Default for Crc32 {
    fn default() -> Self {
        Self::new()
    }
}

impl Crc32 {
    /// An empty CRC.
    pub const fn new() -> Self {
        Crc32 { state: !0 }
    }

    #[inline(always)]
    fn byte(&mut self, b: u8) {
        let index = (self.state ^ u32::from(b)) & 0xff;
        self.state = (self.state >> 8) ^ TABLE[index as usize];
    }

    /// Feeds pixels, each as its little-endian bytes.
    pub fn update(&mut self, pixels: &[Rgb565]) {
        for px in pixels {
            let [lo, hi] = px.0.to_le_bytes();
            self.byte(lo);
            self.byte(hi);
        }
    }

    /// The CRC of everything fed so far.
    pub fn value(&self) -> u32 {
        !self.state
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;

    #[test]
    fn check_value() {
        // "123456789" is the standard check input; as pixels: 0x3231, 0x3433, ... then '9'.
        let mut crc = Crc32::new();
        for pair in b"12345678".chunks(2) {
            crc.update(&[Rgb565(u16::from_le_bytes([pair[0], pair[1]]))]);
        }
        crc.byte(b'9');
        assert_eq!(crc.value(), 0xcbf4_3926);
    }
}
