//! The link-time proof that no panic survives in a release firmware.
//!
//! In release builds the panic handler calls a function that exists nowhere. If the
//! optimiser removes every path to a panic (every bounds check, overflow check, `unwrap`,
//! `core::fmt` call) the handler is unreachable, is dropped, and the program links. If one
//! path survives anywhere in the binary — shadeline, this crate, a board crate, a
//! dependency — the handler is kept, its call needs the symbol, and the link fails with
//! `undefined symbol: shadeline_firmware_has_a_reachable_panic` naming the proof.
//!
//! Debug builds keep overflow checks and cannot be proven panic-free, so there the handler
//! just stops (QEMU's timeout then ends the run); the demos are meant to run in release.

#[cfg(all(target_os = "none", not(debug_assertions)))]
#[panic_handler]
fn panic(_: &core::panic::PanicInfo) -> ! {
    extern "C" {
        /// Deliberately defined nowhere: see the module documentation.
        fn shadeline_firmware_has_a_reachable_panic() -> !;
    }
    // SAFETY: never runs; a reference to it only survives if a panic path does, and then
    // the link fails before any binary exists.
    unsafe { shadeline_firmware_has_a_reachable_panic() }
}

#[cfg(all(target_os = "none", debug_assertions))]
#[panic_handler]
fn panic(_: &core::panic::PanicInfo) -> ! {
    loop {
        core::hint::spin_loop();
    }
}
