//! The kernel a prepared frame's rows take, for the report line: every path the firmware
//! runs says it (`Prepared::kernel`, `PreparedFixed::kernel`), and [`ChoosesKernel`] lets
//! the generic report ask for it.

use crate::text::Line;
use shadeline::{FloatPath, Item, Kernel, Prepared, PreparedFixed};

/// A prepared frame that says which kernel its rows take.
pub trait ChoosesKernel {
    /// The path's own `kernel()`.
    fn kernel(&self) -> Kernel;
}

impl<W: FloatPath, const S: usize, const L: usize> ChoosesKernel for Prepared<W, S, L> {
    fn kernel(&self) -> Kernel {
        Prepared::kernel(self)
    }
}

impl<const S: usize, const L: usize> ChoosesKernel for PreparedFixed<S, L> {
    fn kernel(&self) -> Kernel {
        PreparedFixed::kernel(self)
    }
}

/// Appends ` kernel=narrow`, or ` kernel=general why=sphere0.model` (the item and field
/// that keep the frame from the narrow kernel; on the fixed path the general kernel is the
/// full-width one).
pub fn report(line: &mut Line, kernel: Kernel) {
    match kernel {
        Kernel::Narrow => {
            line.str(" kernel=narrow");
        }
        Kernel::General { item, field } => {
            line.str(" kernel=general why=");
            match item {
                Item::Camera => line.str("camera"),
                Item::Background => line.str("background"),
                Item::Sphere(i) => line.str("sphere").dec(i as u64),
                Item::Light(i) => line.str("light").dec(i as u64),
            };
            line.str(".").str(field);
        }
    }
}
