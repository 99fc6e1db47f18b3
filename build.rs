//! Tells the fixed path whether the target multiplies 32×32→64 bits in one instruction.
//!
//! ARMv6-M (Cortex-M0/M0+/M1, RP2040) and ARMv8-M Baseline (Cortex-M23) have only a
//! 32×32→32 `MULS`: there a 64-bit product is a call to `__aeabi_lmul`, which multiplies two
//! full 64-bit operands. `src/fixed/mul.rs` then builds its exact 32×32→64 products from four
//! 16×16→32 `MULS` inline. Every other target (`SMULL`/`UMULL` on ARMv7-M, `MULH` on RV32IM,
//! any 64-bit host) uses the plain widening product. Both give the same bits.
//!
//! It also tells whether the target counts leading zeros in one instruction: ARMv6-M and
//! ARMv8-M Baseline have no `CLZ`, and RISC-V has none without the `Zbb` extension, so there
//! `u32::leading_zeros` is a routine call and the fixed path's narrow kernel counts by a short
//! binary search instead (`shadeline_no_clz`, `src/fixed/mul.rs`). Both give the same count.

fn main() {
    println!("cargo::rustc-check-cfg=cfg(shadeline_short_mul)");
    println!("cargo::rustc-check-cfg=cfg(shadeline_no_clz)");
    println!("cargo::rerun-if-env-changed=TARGET");
    let target = std::env::var("TARGET").unwrap_or_default();
    let short_mul = target.starts_with("thumbv6m") || target.starts_with("thumbv8m.base");
    if short_mul {
        println!("cargo::rustc-cfg=shadeline_short_mul");
    }
    let arch = std::env::var("CARGO_CFG_TARGET_ARCH").unwrap_or_default();
    let features = std::env::var("CARGO_CFG_TARGET_FEATURE").unwrap_or_default();
    let zbb = features.split(',').any(|f| f == "zbb");
    if short_mul || (arch.starts_with("riscv") && !zbb) {
        println!("cargo::rustc-cfg=shadeline_no_clz");
    }
}
