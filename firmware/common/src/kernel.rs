//! The kernel a prepared frame's rows take, on the report: every path says it
//! (`Render::kernel`), and [`report`] writes it without `core::fmt`.

use crate::text::Line;
use shadeline::{Item, Kernel};

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
