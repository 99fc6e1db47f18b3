//! Golden frames of the fixed path: CRC32s of RGB565 frames that must not change on any
//! target. The firmware checks the same values on Cortex-M0, Cortex-M4F and RISC-V.
//!
//! How they were produced: this test renders each scene on the fixed path into `Rgb565`,
//! row-major, takes every pixel's `u16` as two little-endian bytes, and runs CRC-32 (IEEE,
//! `crc32fast`) over them; the values were printed by
//! `cargo test --test fixed_golden -- --nocapture` on x86_64 and copied here. A change is
//! only right if the fixed kernel's arithmetic was changed on purpose, and then every
//! target's value changes with it.

use crate::common;
use common::*;
use shadeline::*;

/// The exponent series at 320×240.
const GOLDEN_EXPONENT_SERIES_320X240: u32 = 0x0d0e_0408;
/// `random_scenes(8, 0x5eed_601d)[5]` at 160×120 (its numbers are printed by this test).
const GOLDEN_RANDOM_SCENE_5_160X120: u32 = 0xf81b_50ec;
/// `common::point_lights_blinn_phong()` at 200×150.
const GOLDEN_POINT_LIGHTS_BLINN_200X150: u32 = 0xb9ad_e33c;

fn crc_rgb565<R: Render>(r: &R) -> u32 {
    let pixels: Vec<Rgb565> = frame(r);
    let mut hasher = crc32fast::Hasher::new();
    for p in &pixels {
        hasher.update(&p.0.to_le_bytes());
    }
    hasher.finalize()
}

#[test]
fn fixed_rgb565_frames_match_their_golden_crcs() {
    let series = exponent_series().unwrap();
    let random = random_scenes(8, 0x5eed_601d).swap_remove(5);
    let built = point_lights_blinn_phong().unwrap();
    println!("random scene 5 of random_scenes(8, 0x5eed_601d):\n{random:#?}");
    let got = [
        crc_rgb565(&PreparedFixed::new(&series, 320, 240).unwrap()),
        crc_rgb565(&PreparedFixed::new(&random, 160, 120).unwrap()),
        crc_rgb565(&PreparedFixed::new(&built, 200, 150).unwrap()),
    ];
    let want = [
        GOLDEN_EXPONENT_SERIES_320X240,
        GOLDEN_RANDOM_SCENE_5_160X120,
        GOLDEN_POINT_LIGHTS_BLINN_200X150,
    ];
    for (name, (g, w)) in [
        "exponent series 320x240",
        "random scene 5 160x120",
        "point lights, Blinn-Phong 200x150",
    ]
    .iter()
    .zip(got.iter().zip(want))
    {
        println!("{name}: 0x{g:08x} (golden 0x{w:08x})");
    }
    assert_eq!(got, want, "golden CRCs changed: {got:08x?}");
}

#[test]
fn golden_frames_are_deterministic_and_path_independent_of_spans_and_row_order() {
    // The CRC is a function of the prepared frame only: spans off, or rows rendered
    // bottom-up one at a time, give the same bytes.
    let built = point_lights_blinn_phong().unwrap();
    let f = PreparedFixed::new(&built, 200, 150).unwrap();
    let crc = crc_rgb565(&f);
    assert_eq!(crc_rgb565(&f.clone().with_spans(false)), crc);
    let mut rows = vec![Rgb565::default(); 200 * 150];
    for (y, row) in rows.chunks_exact_mut(200).enumerate().rev() {
        f.render_line(y as u32, row).unwrap();
    }
    let mut hasher = crc32fast::Hasher::new();
    for p in &rows {
        hasher.update(&p.0.to_le_bytes());
    }
    assert_eq!(hasher.finalize(), crc);
}
