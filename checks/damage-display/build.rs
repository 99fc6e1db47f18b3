//! Puts the board's memory map where cortex-m-rt's `link.x` looks for `memory.x` (the
//! linker's search path): the Pico's for thumbv6m, the STM32F411's for thumbv7em.

use std::{env, fs, path::PathBuf};

fn main() {
    let out = PathBuf::from(env::var_os("OUT_DIR").expect("cargo sets OUT_DIR"));
    let target = env::var("TARGET").unwrap_or_default();
    let map = if target.starts_with("thumbv7em") {
        "memory-stm32f411.x"
    } else {
        "memory-rp2040.x"
    };
    fs::copy(map, out.join("memory.x")).expect("the memory maps are next to build.rs");
    println!("cargo:rustc-link-search={}", out.display());
    println!("cargo:rerun-if-changed=memory-rp2040.x");
    println!("cargo:rerun-if-changed=memory-stm32f411.x");
    println!("cargo:rerun-if-changed=build.rs");
}
