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
//! SysTick is 24 bits, and one row of the fixed path on a Cortex-M0 runs longer than one
//! period (`2^24` ticks: 2 M instructions on microbit, 1.3 M on mps2). So each region runs
//! with the SysTick exception counting reloads, and:
//!
//! * the counter is stopped between regions (no exception ever fires outside one, so none
//!   can scribble below the painted stack or disturb the report);
//! * the end read masks interrupts and looks at `PENDSTSET`, so a reload that lands between
//!   reading the count and reading the reload counter is attributed exactly;
//! * the handler's own instructions, `H` per reload, run inside the region: `H` is measured
//!   once at start-up by pending the exception by software inside a region (and comparing
//!   with the same region writing the pend register without the pend bit) and subtracted.
//!
//! [`crate::meter::Meter::self_test`] checks all of it on loops of known length, one of which
//! spans several reloads.

use crate::meter::InstructionCounter;
use crate::run::Board;
use core::num::NonZeroU64;
use core::sync::atomic::{AtomicU32, Ordering};
use cortex_m::peripheral::{SCB, SYST};
use cortex_m_rt::exception;
use cortex_m_semihosting::{debug, hio};

/// The `-icount shift` both Cortex-M runners use (`.cargo/config.toml`).
pub const ICOUNT_SHIFT: u32 = 9;

/// Reload value: the full 24-bit period, `2^24` ticks.
const RELOAD: u32 = 0x00ff_ffff;
const PERIOD: u64 = 1 << 24;
/// SysTick control: counter on, exception on, processor clock.
const CSR_RUN: u32 = 0b111;
/// ICSR bits: SysTick pending (set, clear).
const PENDSTSET: u32 = 1 << 26;
const PENDSTCLR: u32 = 1 << 25;

/// SysTick reloads since the current region started.
static RELOADS: AtomicU32 = AtomicU32::new(0);

#[exception]
fn SysTick() {
    // Load and store, not `fetch_add`: ARMv6-M has no atomic read-modify-write, and this
    // handler is the only writer while a region runs.
    RELOADS.store(
        RELOADS.load(Ordering::Relaxed).wrapping_add(1),
        Ordering::Relaxed,
    );
}

/// SysTick counting instructions under QEMU `-icount shift=`[`ICOUNT_SHIFT`].
pub struct SysTickCounter {
    /// Owned so nothing else can reprogram it; driven through its registers below.
    _syst: SYST,
    /// SysTick clock times `2^shift`: ticks per 10⁹ instructions. Non-zero by type, so the
    /// division in `stop` has no divide-by-zero panic path.
    ticks_per_giga_instructions: NonZeroU64,
    /// Instructions the SysTick handler executes per reload (calibrated in `new`).
    handler: u64,
}

/// A raw reading: reloads and ticks into the current period since the region started.
#[derive(Clone, Copy)]
struct Reading {
    reloads: u64,
    ticks: u64,
}

impl SysTickCounter {
    /// Takes over SysTick (clocked from the processor clock of `clock_hz` Hz) and measures
    /// the cost of its exception handler.
    pub fn new(mut syst: SYST, clock_hz: u32) -> Self {
        syst.disable_counter();
        syst.set_reload(RELOAD);
        let mut counter = SysTickCounter {
            _syst: syst,
            ticks_per_giga_instructions: NonZeroU64::new(u64::from(clock_hz) << ICOUNT_SHIFT)
                .unwrap_or(NonZeroU64::MIN),
            handler: 0,
        };
        let with_handler = counter.pend_region(PENDSTSET);
        let without = counter.pend_region(0);
        counter.handler = with_handler.saturating_sub(without);
        counter
    }

    /// Instructions the SysTick handler costs per reload, as calibrated.
    pub fn handler_instructions(&self) -> u64 {
        self.handler
    }

    /// A region that writes `bits` to ICSR: with `PENDSTSET` the handler runs once.
    /// Returns the instructions of the region without the reload the handler counted.
    #[inline(never)]
    fn pend_region(&mut self, bits: u32) -> u64 {
        let bits = core::hint::black_box(bits);
        let start = self.start();
        // SAFETY: writing ICSR's set-pending bit for SysTick (or nothing) has no other effect.
        unsafe { (*SCB::PTR).icsr.write(bits) };
        let reading = Self::read(start);
        self.instructions(reading.ticks)
    }

    #[inline(always)]
    fn instructions(&self, ticks: u64) -> u64 {
        let scale = self.ticks_per_giga_instructions;
        (ticks * 1_000_000_000 + scale.get() / 2) / scale
    }

    /// Ends a region: reads the count, the reloads, and a pending reload not yet handled,
    /// with interrupts masked; then stops the counter.
    #[inline(always)]
    fn read(_start: u64) -> Reading {
        cortex_m::interrupt::disable();
        let current = SYST::get_current();
        // SAFETY: reads of SysTick and SCB registers; the writes stop the counter and drop a
        // pending SysTick, which only this module uses.
        let (pending, reloads) = unsafe {
            let pending = (*SCB::PTR).icsr.read() & PENDSTSET != 0;
            let reloads = RELOADS.load(Ordering::Relaxed);
            (*SYST::PTR).csr.write(0);
            (*SCB::PTR).icsr.write(PENDSTCLR);
            (pending, reloads)
        };
        // SAFETY: no critical section is open; the demos use no other interrupt.
        unsafe { cortex_m::interrupt::enable() };
        // A reload that happened before `current` was read but is not handled yet is
        // pending, and `current` is then near the top of the period.
        let unhandled = pending && current > RELOAD / 2;
        Reading {
            reloads: u64::from(reloads) + u64::from(unhandled),
            // Restarted at 0, the counter reloads on the first tick: elapsed = (0 − current).
            ticks: u64::from(0u32.wrapping_sub(current) & RELOAD),
        }
    }
}

impl InstructionCounter for SysTickCounter {
    #[inline(always)]
    fn start(&mut self) -> u64 {
        // SAFETY: SysTick and SCB register writes; this module owns SysTick.
        unsafe {
            (*SYST::PTR).csr.write(0);
            (*SYST::PTR).cvr.write(0);
            (*SCB::PTR).icsr.write(PENDSTCLR);
        }
        RELOADS.store(0, Ordering::Relaxed);
        // SAFETY: as above; the region starts when the counter does.
        unsafe { (*SYST::PTR).csr.write(CSR_RUN) };
        0
    }

    #[inline(always)]
    fn stop(&mut self, start: u64) -> Option<u64> {
        let r = Self::read(start);
        let ticks = r.reloads * PERIOD + r.ticks;
        self.instructions(ticks)
            .checked_sub(r.reloads * self.handler)
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
