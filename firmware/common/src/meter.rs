//! Counting the instructions a region of code executes, with the counter's own cost removed.
//!
//! A board supplies an [`InstructionCounter`] (SysTick under QEMU `-icount` on Cortex-M,
//! `minstret` on RISC-V). [`Meter::new`] calibrates it by measuring an empty region — what
//! remains is the cost of the two reads themselves — and [`Meter::measure`] subtracts that from
//! every region. [`Meter::self_test`] then checks exactness on code of known length:
//! hand-written loops of `2·n` instructions each must measure exactly `2·(n₂ − n₁)` apart
//! (the loops are one function, with `n` passed through `black_box`, so the code around them
//! is the same and the difference is exactly the extra iterations).
//!
//! Compiler fences keep the region's memory effects between the reads; the region is a call
//! into the renderer, which the optimiser cannot hoist past a volatile counter read.

use core::sync::atomic::{compiler_fence, Ordering};

/// A source of exact instruction counts for short regions.
pub trait InstructionCounter {
    /// Prepares the counter for a region and returns its reading at the start.
    fn start(&mut self) -> u64;
    /// Instructions executed since `start` (the reads included), or `None` if the counter
    /// cannot tell (on Cortex-M: SysTick reloaded during the region).
    fn stop(&mut self, start: u64) -> Option<u64>;
    /// Executes exactly `2·iterations` instructions (one decrement, one branch per pass) once
    /// `iterations` is in a register.
    fn known_loop(iterations: u32);
    /// How this counter counts, for the report (`"systick"`, `"minstret"`).
    fn name(&self) -> &'static str;
}

/// Loop counts for [`Meter::self_test`]. The long one runs 6 M instructions, several SysTick
/// periods on both Cortex-M boards, so reload counting is checked too.
const SELF_TEST_SHORT: u32 = 5_000;
const SELF_TEST_MEDIUM: u32 = 65_000;
const SELF_TEST_LONG: u32 = 3_005_000;

/// An [`InstructionCounter`] with its read overhead calibrated out.
pub struct Meter<C> {
    counter: C,
    overhead: u64,
}

impl<C: InstructionCounter> Meter<C> {
    /// Calibrates `counter`: the instructions of an empty region become the overhead that
    /// every measurement subtracts. `None` if the counter cannot measure even that.
    pub fn new(mut counter: C) -> Option<Self> {
        let ((), overhead) = region(&mut counter, || ());
        Some(Meter {
            counter,
            overhead: overhead?,
        })
    }

    /// The calibrated cost of the counter reads around a region, in instructions.
    pub fn overhead(&self) -> u64 {
        self.overhead
    }

    /// The counter's name.
    pub fn counter_name(&self) -> &'static str {
        self.counter.name()
    }

    /// Runs `work` and returns its result with the instructions it executed, or `None` for
    /// the count if the counter could not tell.
    #[inline(always)]
    pub fn measure<R>(&mut self, work: impl FnOnce() -> R) -> (R, Option<u64>) {
        let (result, count) = region(&mut self.counter, work);
        (result, count.and_then(|n| n.checked_sub(self.overhead)))
    }

    /// Measures three loops of known length; `Ok` with the longest difference if both
    /// differences are exact, `Err` with the first wrong one otherwise.
    pub fn self_test(&mut self) -> Result<u64, u64> {
        let [short, medium, long] =
            core::hint::black_box([SELF_TEST_SHORT, SELF_TEST_MEDIUM, SELF_TEST_LONG]);
        let (a, b, c) = (
            self.known_loop(short),
            self.known_loop(medium),
            self.known_loop(long),
        );
        let (Some(a), Some(b), Some(c)) = (a, b, c) else {
            return Err(0);
        };
        let expect = |n: u32| 2 * u64::from(n - SELF_TEST_SHORT);
        if b.wrapping_sub(a) != expect(SELF_TEST_MEDIUM) {
            return Err(b.wrapping_sub(a));
        }
        if c.wrapping_sub(a) != expect(SELF_TEST_LONG) {
            return Err(c.wrapping_sub(a));
        }
        Ok(c - a)
    }

    /// One instantiation for every loop length, so both self-test regions are the same code.
    fn known_loop(&mut self, iterations: u32) -> Option<u64> {
        self.measure(move || C::known_loop(iterations)).1
    }
}

/// One measured region, in a function of its own: the optimiser cannot schedule the caller's
/// unrelated work (report formatting, loop bookkeeping) between the two counter reads, as it
/// can when they are inlined into a larger body. What lies between them is the start read's
/// tail, `work` (inlined here) with its argument set-up, and the stop read.
#[inline(never)]
fn region<C: InstructionCounter, R>(counter: &mut C, work: impl FnOnce() -> R) -> (R, Option<u64>) {
    let start = counter.start();
    compiler_fence(Ordering::SeqCst);
    let result = work();
    compiler_fence(Ordering::SeqCst);
    (result, counter.stop(start))
}
