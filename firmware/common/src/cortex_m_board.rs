//! The Cortex-M side shared by the m4f and m0 firmwares: SysTick as an instruction counter
//! under QEMU `-icount`, the semihosting console and exit, and the stack limits from
//! cortex-m-rt's linker script.
//!
//! # Counting instructions with SysTick
//!
//! QEMU has no cycle counter, but with `-icount shift=N` its virtual clock advances exactly
//! `2^N` ns per executed instruction, and SysTick (on the processor clock, `f` Hz) ticks from
//! that clock. So a region of `I` instructions spans `I·2^N·f/10⁹` ticks, give or take the
//! phase of the first tick: `I = round(ticks·10⁹ / (f·2^N))` exactly as long as one tick is
//! under a quarter of an instruction (two reads, each off by under a tick, must stay under
//! half an instruction): `f·2^N ≥ 4·10⁹`. Both boards run at `2^9` ns per instruction:
//! 25 MHz (mps2-an386) gives 12.8 ticks per instruction, 16 MHz (microbit) 8.192.
//!
//! SysTick is 24 bits. Rather than count reloads in an interrupt (whose handler would run
//! inside the measured region), each region restarts the counter (writing `CVR` clears it
//! and `COUNTFLAG`) and reads it once at the end; `COUNTFLAG` set means the region ran past
//! one full period (`2^24` ticks: 1.3 M instructions on mps2, 2 M on microbit) and the
//! count is reported as unknown instead of wrong. The demos measure one row per region.
//! No SysTick interrupt is enabled.

use crate::meter::InstructionCounter;
use crate::run::Board;
use core::num::NonZeroU64;
use cortex_m::peripheral::syst::SystClkSource;
use cortex_m::peripheral::SYST;
use cortex_m_semihosting::{debug, hio};

/// The `-icount shift` both Cortex-M runners use (`.cargo/config.toml`).
pub const ICOUNT_SHIFT: u32 = 9;

const RELOAD: u32 = 0x00ff_ffff;

/// SysTick counting instructions under QEMU `-icount shift=`[`ICOUNT_SHIFT`].
pub struct SysTickCounter {
    syst: SYST,
    /// SysTick clock times `2^shift`: ticks per 10⁹ instructions. Non-zero by type, so the
    /// division in `stop` has no divide-by-zero panic path.
    ticks_per_giga_instructions: NonZeroU64,
}

impl SysTickCounter {
    /// Takes over SysTick, clocked from the processor clock of `clock_hz` Hz.
    pub fn new(mut syst: SYST, clock_hz: u32) -> Self {
        syst.disable_interrupt();
        syst.set_clock_source(SystClkSource::Core);
        syst.set_reload(RELOAD);
        syst.clear_current();
        syst.enable_counter();
        SysTickCounter {
            syst,
            ticks_per_giga_instructions: NonZeroU64::new(u64::from(clock_hz) << ICOUNT_SHIFT)
                .unwrap_or(NonZeroU64::MIN),
        }
    }
}

impl InstructionCounter for SysTickCounter {
    #[inline(always)]
    fn start(&mut self) -> u64 {
        self.syst.clear_current();
        u64::from(SYST::get_current())
    }

    #[inline(always)]
    fn stop(&mut self, start: u64) -> Option<u64> {
        let now = u64::from(SYST::get_current());
        if self.syst.has_wrapped() {
            return None;
        }
        // Down-counter; right after the restart it may still read 0 before reloading.
        let ticks = start.wrapping_sub(now) & u64::from(RELOAD);
        let scale = self.ticks_per_giga_instructions;
        Some((ticks * 1_000_000_000 + scale.get() / 2) / scale)
    }

    #[inline(always)]
    fn known_loop(iterations: u32) {
        // SAFETY: a register-only countdown loop; touches no memory, keeps the stack.
        unsafe {
            core::arch::asm!(
                "2:",
                "subs {n}, #1",
                "bne 2b",
                n = inout(reg) iterations => _,
                options(nomem, nostack),
            );
        }
    }

    fn name(&self) -> &'static str {
        "systick"
    }
}

/// A Cortex-M board under QEMU: semihosting console, cortex-m-rt stack limits.
pub struct CortexMBoard {
    name: &'static str,
    stdout: Option<hio::HostStream>,
}

impl CortexMBoard {
    /// Opens the semihosting console; a board that cannot print still runs and exits.
    pub fn new(name: &'static str) -> Self {
        CortexMBoard {
            name,
            stdout: hio::hstdout().ok(),
        }
    }
}

extern "C" {
    /// Top of the stack (cortex-m-rt `link.x`).
    static _stack_start: u32;
    /// Lowest address the stack may reach: the end of `.bss` (cortex-m-rt `link.x`).
    static _stack_end: u32;
}

impl Board for CortexMBoard {
    fn name(&self) -> &'static str {
        self.name
    }

    fn write(&mut self, text: &[u8]) {
        if let Some(out) = self.stdout.as_mut() {
            let _ = out.write_all(text);
        }
    }

    fn stack_pointer(&self) -> usize {
        cortex_m::register::msp::read() as usize
    }

    fn stack_limits(&self) -> (usize, usize) {
        // Only the symbols' addresses are taken, never their (nonexistent) contents.
        let lowest = core::ptr::addr_of!(_stack_end) as usize;
        let top = core::ptr::addr_of!(_stack_start) as usize;
        (lowest, top)
    }
}

/// Ends the QEMU run through semihosting: exit status 0 on success, 1 on failure.
pub fn exit(success: bool) -> ! {
    debug::exit(if success {
        debug::EXIT_SUCCESS
    } else {
        debug::EXIT_FAILURE
    });
    loop {
        cortex_m::asm::wfi();
    }
}
