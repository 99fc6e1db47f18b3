//! The RV32 board under QEMU `virt`: `minstret` as the instruction counter, RISC-V
//! semihosting for the console and the exit status, riscv-rt's stack limits.
//!
//! `minstret` counts retired instructions; QEMU derives it from its instruction counter only
//! under `-icount` (otherwise it returns host time), so the runner passes `-icount shift=0`.
//! No wrap to handle: it is 64 bits (read as two halves, high word re-read until stable).
//!
//! Semihosting on RISC-V is an `ebreak` between two marker instructions
//! (`slli x0, x0, 0x1f` / `srai x0, x0, 7`), uncompressed, which QEMU recognises when run
//! with `-semihosting-config enable=on`. Three calls are used: open `:tt` for writing, write,
//! and exit (on RV32 the exit reason is passed directly: ApplicationExit means status 0).

use common::meter::InstructionCounter;
use common::run::Board;

const SYS_OPEN: usize = 0x01;
const SYS_WRITE: usize = 0x05;
const SYS_EXIT: usize = 0x18;
/// Semihosting open mode "w".
const MODE_WRITE: usize = 4;
const ADP_STOPPED_APPLICATION_EXIT: usize = 0x2_0026;
const ADP_STOPPED_RUN_TIME_ERROR: usize = 0x2_0023;

/// One semihosting call: operation in `a0`, argument (a value or a pointer to a parameter
/// block) in `a1`, result in `a0`.
fn semihosting(op: usize, arg: usize) -> usize {
    let mut result = op;
    // SAFETY: the semihosting trap sequence; QEMU reads the parameter block `arg` points to
    // (callers pass live, readable blocks) and writes nothing but `a0`.
    unsafe {
        core::arch::asm!(
            ".balign 16",
            ".option push",
            ".option norvc",
            "slli x0, x0, 0x1f",
            "ebreak",
            "srai x0, x0, 7",
            ".option pop",
            inout("a0") result,
            in("a1") arg,
            options(nostack),
        );
    }
    result
}

/// The console and stack of the RV32 board.
pub struct Rv32Board {
    stdout: Option<usize>,
}

impl Rv32Board {
    /// Opens the semihosting console; a board that cannot print still runs and exits.
    pub fn new() -> Self {
        let name = b":tt\0";
        let block = [name.as_ptr() as usize, MODE_WRITE, name.len() - 1];
        let fd = semihosting(SYS_OPEN, block.as_ptr() as usize);
        Rv32Board {
            stdout: (fd != usize::MAX).then_some(fd),
        }
    }
}

extern "C" {
    /// Top of the stack (riscv-rt `link.x`).
    static _stack_start: u32;
    /// Bottom of the stack region (riscv-rt `link.x`; the `STACK` region of `memory.x`).
    static __estack: u32;
}

impl Board for Rv32Board {
    fn name(&self) -> &'static str {
        "rv32"
    }

    fn write(&mut self, text: &[u8]) {
        if let Some(fd) = self.stdout {
            let block = [fd, text.as_ptr() as usize, text.len()];
            let _ = semihosting(SYS_WRITE, block.as_ptr() as usize);
        }
    }

    fn stack_pointer(&self) -> usize {
        let sp: usize;
        // SAFETY: copies the stack pointer into a register.
        unsafe { core::arch::asm!("mv {}, sp", out(reg) sp, options(nomem, nostack)) };
        sp
    }

    fn stack_limits(&self) -> (usize, usize) {
        // Only the symbols' addresses are taken, never their (nonexistent) contents.
        let lowest = core::ptr::addr_of!(__estack) as usize;
        let top = core::ptr::addr_of!(_stack_start) as usize;
        (lowest, top)
    }
}

/// Ends the QEMU run through semihosting: exit status 0 on success, 1 on failure.
pub fn exit(success: bool) -> ! {
    let reason = if success {
        ADP_STOPPED_APPLICATION_EXIT
    } else {
        ADP_STOPPED_RUN_TIME_ERROR
    };
    semihosting(SYS_EXIT, reason);
    loop {
        riscv::asm::wfi();
    }
}

/// `minstret`, the machine-mode retired-instruction counter.
pub struct Minstret;

impl InstructionCounter for Minstret {
    #[inline(always)]
    fn start(&mut self) -> u64 {
        riscv::register::minstret::read64()
    }

    #[inline(always)]
    fn stop(&mut self, start: u64) -> Option<u64> {
        riscv::register::minstret::read64().checked_sub(start)
    }

    #[inline(always)]
    fn known_loop(iterations: u32) {
        // SAFETY: a register-only countdown loop; touches no memory, keeps the stack.
        unsafe {
            core::arch::asm!(
                "2:",
                "addi {n}, {n}, -1",
                "bnez {n}, 2b",
                n = inout(reg) iterations => _,
                options(nomem, nostack),
            );
        }
    }

    fn name(&self) -> &'static str {
        "minstret"
    }
}
