//! A Linux framebuffer device (`/dev/fb0`: a panel, an fbtft SPI display): opened, its
//! screen information read and its memory mapped through the `framebuffer` crate, and its
//! pixel format checked; [`crate::fb_pixels`] writes into the memory.
//!
//! Every refusal names the device ([`DeviceError`]): a path that does not exist or cannot be
//! opened, a file that is not a character device, a device whose screen information cannot
//! be read (not a framebuffer), and a format shadeline does not write: not packed pixels, a
//! palette or greyscale visual, a non-standard or FOURCC format, channels stored
//! most-significant bit on the right, or a layout [`FbFormat::depth`] refuses.

use crate::fb_pixels::{Channel, FbFormat, FormatError};
use framebuffer::{Bitfield, FixScreeninfo, Framebuffer, FramebufferErrorKind, VarScreeninfo};
use std::fmt;
use std::os::unix::fs::FileTypeExt;
use std::path::{Path, PathBuf};

/// `FB_TYPE_PACKED_PIXELS` of `linux/fb.h`.
const FB_TYPE_PACKED_PIXELS: u32 = 0;
/// `FB_VISUAL_TRUECOLOR` of `linux/fb.h`.
const FB_VISUAL_TRUECOLOR: u32 = 2;
/// `FB_VISUAL_DIRECTCOLOR` of `linux/fb.h` (true colour through a per-channel ramp).
const FB_VISUAL_DIRECTCOLOR: u32 = 4;

/// What a framebuffer shows: its pixel format, its visible size, and where the visible area
/// starts in its memory.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Screen {
    /// The pixel format and the line length.
    pub format: FbFormat,
    /// The visible width and height in pixels (`xres`, `yres`).
    pub size: (u32, u32),
    /// The visible area's top-left pixel in the virtual screen (`xoffset`, `yoffset`).
    pub origin: (u32, u32),
}

/// Why a screen's format is not written.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ScreenError {
    /// A format the kernel describes in a way other than packed true-colour channels: what
    /// it is.
    Kind(&'static str),
    /// Packed true colour in a layout shadeline does not write.
    Format(FormatError),
}

impl fmt::Display for ScreenError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ScreenError::Kind(what) => write!(
                f,
                "shadeline does not write this pixel format: {what} (it writes packed true \
                 colour: RGB565, BGR565, RGB888, XRGB8888 and their BGR orders)"
            ),
            ScreenError::Format(e) => e.fmt(f),
        }
    }
}

impl std::error::Error for ScreenError {}

fn channel(b: &Bitfield) -> Channel {
    Channel::new(b.offset, b.length)
}

/// The screen a device's var and fixed screen information describe, if shadeline writes its
/// format.
pub fn screen_of(var: &VarScreeninfo, fix: &FixScreeninfo) -> Result<Screen, ScreenError> {
    if fix.fb_type != FB_TYPE_PACKED_PIXELS {
        return Err(ScreenError::Kind("not packed pixels (planes or text)"));
    }
    if var.grayscale == 1 {
        return Err(ScreenError::Kind("greyscale"));
    }
    if var.grayscale > 1 {
        return Err(ScreenError::Kind("a FOURCC format"));
    }
    if var.nonstd != 0 {
        return Err(ScreenError::Kind("a non-standard format"));
    }
    if !matches!(fix.visual, FB_VISUAL_TRUECOLOR | FB_VISUAL_DIRECTCOLOR) {
        return Err(ScreenError::Kind(
            "a palette or monochrome visual, not true colour",
        ));
    }
    let fields = [&var.red, &var.green, &var.blue, &var.transp];
    if fields.iter().any(|b| b.msb_right != 0) {
        return Err(ScreenError::Kind(
            "channels stored most-significant bit on the right",
        ));
    }
    let format = FbFormat {
        bits_per_pixel: var.bits_per_pixel,
        red: channel(&var.red),
        green: channel(&var.green),
        blue: channel(&var.blue),
        transp: channel(&var.transp),
        line_length: fix.line_length as usize,
    };
    format.depth().map_err(ScreenError::Format)?;
    Ok(Screen {
        format,
        size: (var.xres, var.yres),
        origin: (var.xoffset, var.yoffset),
    })
}

/// Why a framebuffer device cannot be drawn into. Its message names the device.
#[derive(Debug)]
pub enum DeviceError {
    /// The path does not exist, or cannot be opened (permissions).
    Open(PathBuf, std::io::Error),
    /// The path is not a character device: what it is.
    NotCharDevice(PathBuf, &'static str),
    /// A character device whose screen information cannot be read: not a framebuffer.
    NotFramebuffer(PathBuf, String),
    /// The memory could not be mapped.
    Map(PathBuf, String),
    /// A framebuffer (its id) in a format shadeline does not write.
    Format(PathBuf, String, ScreenError),
}

impl fmt::Display for DeviceError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            DeviceError::Open(path, e) => {
                write!(
                    f,
                    "{}: error: cannot open the framebuffer device: {e}",
                    path.display()
                )?;
                if e.kind() == std::io::ErrorKind::PermissionDenied {
                    f.write_str(" (is the user in the `video` group?)")?;
                }
                Ok(())
            }
            DeviceError::NotCharDevice(path, what) => write!(
                f,
                "{}: error: not a framebuffer device: it is {what}, and a framebuffer is a \
                 character device (/dev/fb0, say)",
                path.display()
            ),
            DeviceError::NotFramebuffer(path, why) => write!(
                f,
                "{}: error: not a framebuffer device: its screen information cannot be read \
                 ({why})",
                path.display()
            ),
            DeviceError::Map(path, why) => write!(
                f,
                "{}: error: cannot map the framebuffer's memory: {why}",
                path.display()
            ),
            DeviceError::Format(path, id, e) => {
                write!(f, "{} ({id}): error: {e}", path.display())
            }
        }
    }
}

impl std::error::Error for DeviceError {}

/// An open framebuffer device with its memory mapped.
pub struct Device {
    fb: Framebuffer,
    path: PathBuf,
    /// The screen: format, visible size, origin.
    pub screen: Screen,
}

impl fmt::Debug for Device {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Device")
            .field("path", &self.path)
            .field("screen", &self.screen)
            .finish_non_exhaustive()
    }
}

impl Device {
    /// Opens the framebuffer at `path`, reads its screen information, checks its format and
    /// maps its memory.
    pub fn open(path: &Path) -> Result<Device, DeviceError> {
        let owned = || path.to_path_buf();
        let meta = std::fs::metadata(path).map_err(|e| DeviceError::Open(owned(), e))?;
        let kind = meta.file_type();
        if !kind.is_char_device() {
            let what = if kind.is_file() {
                "a regular file"
            } else if kind.is_dir() {
                "a directory"
            } else if kind.is_block_device() {
                "a block device"
            } else {
                "not a device"
            };
            return Err(DeviceError::NotCharDevice(owned(), what));
        }
        // The crate opens the device, reads both screen infos, then maps the memory; which
        // step failed is in the error's kind and message.
        let fb = Framebuffer::new(path).map_err(|e| match e.kind {
            FramebufferErrorKind::IoctlFailed => DeviceError::NotFramebuffer(owned(), e.details),
            FramebufferErrorKind::IoError if e.details.starts_with("Failed to map") => {
                DeviceError::Map(owned(), e.details)
            }
            FramebufferErrorKind::IoError => {
                DeviceError::Open(owned(), std::io::Error::other(e.details))
            }
        })?;
        let screen = screen_of(&fb.var_screen_info, &fb.fix_screen_info)
            .map_err(|e| DeviceError::Format(owned(), id(&fb.fix_screen_info), e))?;
        Ok(Device {
            fb,
            path: owned(),
            screen,
        })
    }

    /// The driver's name for the device (`fb_ili9341`, `simple`, …).
    pub fn id(&self) -> String {
        id(&self.fb.fix_screen_info)
    }

    /// The device's path.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// The mapped memory: `line_length × yres_virtual` bytes.
    pub fn memory(&mut self) -> &mut [u8] {
        &mut self.fb.frame[..]
    }
}

/// The fixed screen info's `id`, up to its first NUL.
fn id(fix: &FixScreeninfo) -> String {
    let end = fix.id.iter().position(|&b| b == 0).unwrap_or(fix.id.len());
    String::from_utf8_lossy(&fix.id[..end]).into_owned()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn field(offset: u32, length: u32) -> Bitfield {
        Bitfield {
            offset,
            length,
            msb_right: 0,
        }
    }

    /// A 320×240 RGB565 panel with 8 bytes of padding per line, panned to its second page.
    fn panel() -> (VarScreeninfo, FixScreeninfo) {
        let var = VarScreeninfo {
            xres: 320,
            yres: 240,
            xres_virtual: 320,
            yres_virtual: 480,
            yoffset: 240,
            bits_per_pixel: 16,
            red: field(11, 5),
            green: field(5, 6),
            blue: field(0, 5),
            ..Default::default()
        };
        let fix = FixScreeninfo {
            line_length: 648,
            visual: FB_VISUAL_TRUECOLOR,
            ..Default::default()
        };
        (var, fix)
    }

    #[test]
    fn the_screen_takes_the_line_length_size_and_offset_of_the_infos() {
        let (var, fix) = panel();
        let screen = screen_of(&var, &fix).unwrap();
        assert_eq!(screen.format.line_length, 648);
        assert_eq!(screen.format.name(), "RGB565");
        assert_eq!(screen.size, (320, 240));
        assert_eq!(screen.origin, (0, 240));
    }

    #[test]
    fn formats_the_kernel_marks_as_other_than_true_colour_are_refused() {
        let (var, fix) = panel();
        type Change = fn(&mut VarScreeninfo, &mut FixScreeninfo);
        let cases: [(Change, &str); 6] = [
            (|_, f| f.fb_type = 1, "not packed pixels"),
            (|v, _| v.grayscale = 1, "greyscale"),
            (|v, _| v.grayscale = 0x3231_5659, "FOURCC"),
            (|v, _| v.nonstd = 1, "non-standard"),
            (|_, f| f.visual = 3, "palette"),
            (
                |v, _| v.green.msb_right = 1,
                "most-significant bit on the right",
            ),
        ];
        for (change, words) in cases {
            let (mut v, mut f) = (var.clone(), fix.clone());
            change(&mut v, &mut f);
            let e = screen_of(&v, &f).unwrap_err();
            assert!(matches!(e, ScreenError::Kind(_)), "{e}");
            assert!(e.to_string().contains(words), "{e}");
        }
        let mut v = var.clone();
        v.red = field(10, 5);
        v.green = field(5, 5);
        assert!(matches!(
            screen_of(&v, &fix),
            Err(ScreenError::Format(FormatError::ChannelLengths(_)))
        ));
    }

    #[test]
    fn a_missing_path_a_regular_file_and_a_device_that_is_no_framebuffer_are_named() {
        let dir = std::env::temp_dir().join(format!("shadeline-fb-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let missing = dir.join("fb9");
        let e = Device::open(&missing).unwrap_err();
        assert!(matches!(e, DeviceError::Open(..)), "{e}");
        let message = e.to_string();
        assert!(message.starts_with(&format!("{}: error: cannot open", missing.display())));
        let file = dir.join("fb.raw");
        std::fs::write(&file, [0u8; 64]).unwrap();
        let e = Device::open(&file).unwrap_err();
        assert!(e
            .to_string()
            .contains("not a framebuffer device: it is a regular file"));
        assert!(e.to_string().starts_with(&file.display().to_string()));
        // Its contents are untouched.
        assert_eq!(std::fs::read(&file).unwrap(), [0u8; 64]);
        let e = Device::open(&dir).unwrap_err();
        assert!(e.to_string().contains("it is a directory"), "{e}");
        // A character device that is not a framebuffer: its ioctl fails.
        let null = Path::new("/dev/null");
        if null.exists() {
            let e = Device::open(null).unwrap_err();
            assert!(matches!(e, DeviceError::NotFramebuffer(..)), "{e}");
            assert!(e
                .to_string()
                .starts_with("/dev/null: error: not a framebuffer"));
        }
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
