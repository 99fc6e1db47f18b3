//! A fixed-size text line with hand-written number formatting.
//!
//! Why not `core::fmt`: its machinery is precompiled in `core` with bounds checks and panics
//! inside, so one `write!` keeps a panic path alive and the release link, whose panic
//! handler calls an undefined symbol, fails. Everything here is plain integer arithmetic on
//! a byte array, and text that does not fit is cut off rather than panicking.

/// Capacity of a [`Line`], in bytes: enough for the longest report line.
pub const CAPACITY: usize = 256;

/// One line of ASCII text being built.
pub struct Line {
    bytes: [u8; CAPACITY],
    len: usize,
}

impl Default for Line {
    fn default() -> Self {
        Self::new()
    }
}

impl Line {
    /// An empty line.
    pub const fn new() -> Self {
        Line {
            bytes: [0; CAPACITY],
            len: 0,
        }
    }

    /// The text so far.
    pub fn as_bytes(&self) -> &[u8] {
        self.bytes.get(..self.len).unwrap_or(&[])
    }

    /// Appends one byte; dropped if the line is full. (Not inlined, like [`Line::str`]: the
    /// report is not hot, and inlined into every call site it costs kilobytes of flash.)
    #[inline(never)]
    pub fn byte(&mut self, b: u8) -> &mut Self {
        if let Some(slot) = self.bytes.get_mut(self.len) {
            *slot = b;
            self.len += 1;
        }
        self
    }

    /// Appends text.
    #[inline(never)]
    pub fn str(&mut self, s: &str) -> &mut Self {
        for &b in s.as_bytes() {
            self.byte(b);
        }
        self
    }

    /// Appends an unsigned integer in decimal.
    pub fn dec(&mut self, mut v: u64) -> &mut Self {
        let mut digits = [0u8; 20];
        let mut n = 0;
        loop {
            digits[n % 20] = b'0' + (v % 10) as u8;
            n += 1;
            v /= 10;
            if v == 0 || n == 20 {
                break;
            }
        }
        for i in (0..n).rev() {
            self.byte(digits[i % 20]);
        }
        self
    }

    /// Appends `0x` and eight lowercase hex digits.
    pub fn hex32(&mut self, v: u32) -> &mut Self {
        self.str("0x");
        for shift in (0..8).rev() {
            let nibble = ((v >> (shift * 4)) & 0xf) as u8;
            self.byte(if nibble < 10 {
                b'0' + nibble
            } else {
                b'a' + nibble - 10
            });
        }
        self
    }

    /// Appends `num / den` rounded to one decimal place (`-` if `den` is 0).
    pub fn ratio(&mut self, num: u64, den: u64) -> &mut Self {
        if den == 0 {
            return self.byte(b'-');
        }
        let tenths = (num.saturating_mul(10) + den / 2) / den;
        self.dec(tenths / 10).byte(b'.').dec(tenths % 10)
    }

    /// Appends ` key=` followed by a decimal value.
    pub fn field(&mut self, key: &str, v: u64) -> &mut Self {
        self.byte(b' ').str(key).byte(b'=').dec(v)
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;

    #[test]
    fn formats() {
        let mut l = Line::new();
        l.dec(0)
            .byte(b' ')
            .dec(u64::MAX)
            .byte(b' ')
            .hex32(0xaea2_bfb6);
        l.byte(b' ').ratio(1234, 10).byte(b' ').ratio(5, 0);
        assert_eq!(
            l.as_bytes(),
            b"0 18446744073709551615 0xaea2bfb6 123.4 -".as_slice()
        );
    }
}
