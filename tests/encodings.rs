//! Encodings (sRGB, ordered dithering) and the new formats (`Bgr565`, `Gray8`, byte rows):
//!
//! - the scalar and SIMD paths give the same bits with every encoding, in every format;
//! - each path's packet-wide encode stage stores what the per-pixel rule of
//!   `shadeline::encoding` gives for its own linear colour;
//! - a row rendered in segments equals the row rendered at once (encoding is a function of
//!   position only), and `row_coverage` never leaves out a covered pixel;
//! - golden CRCs of dithered frames; the fixed path's closeness to scalar with each encoding;
//! - byte order of the display-ready byte rows.
//!
//! On the default target CPU; `checks/bit-identity` hashes every encoding of its frames on
//! the SSE2 baseline, the native CPU, aarch64 (NEON) and wasm32 (simd128).

use crate::common;
use common::*;
use shadeline::encoding::{encode_levels, linear_code, linear_code_fixed};
use shadeline::*;

const ENCODINGS: [Encoding; 4] = [
    Encoding::LINEAR,
    Encoding::LINEAR.dithered(),
    Encoding::SRGB,
    Encoding::SRGB.dithered(),
];

fn frame_with<P: Pixel + Default, R: Render>(r: &R, e: Encoding) -> Vec<P> {
    let w = r.width() as usize;
    let mut out = vec![P::default(); w * r.height() as usize];
    for (y, row) in out.chunks_exact_mut(w).enumerate() {
        r.render_segment_with(y as u32, 0, row, e).unwrap();
    }
    out
}

/// Every level format, every encoding: the frame of `r` equals the per-pixel rule applied to
/// `codes(e)` (the path's own linear codes under that encoding), and `r` wrapped with the
/// encoding equals `r` rendered with it explicitly.
fn check_against_rule<R: Render + Clone>(
    r: &R,
    codes: impl Fn(Encoding) -> Vec<[u32; 3]>,
    label: &str,
) {
    let w = r.width();
    for e in ENCODINGS {
        let codes = &codes(e);
        fn one<P: Pixel + Default + PartialEq + core::fmt::Debug, R: Render + Clone>(
            r: &R,
            codes: &[[u32; 3]],
            e: Encoding,
            w: u32,
            label: &str,
        ) {
            let got: Vec<P> = frame_with(r, e);
            let levels = P::LEVELS.unwrap();
            for (i, (px, c)) in got.iter().zip(codes).enumerate() {
                let (x, y) = (i as u32 % w, i as u32 / w);
                let want = P::from_levels(encode_levels(*c, levels, P::GRAY, e, x, y));
                if e != Encoding::LINEAR {
                    assert_eq!(*px, want, "{label}, {e:?}: pixel ({x},{y})");
                }
            }
            let wrapped: Vec<P> = frame(&r.clone().with_encoding(e));
            assert!(wrapped == got, "{label}, {e:?}: with_encoding differs");
        }
        one::<Rgb565, R>(r, codes, e, w, label);
        one::<Bgr565, R>(r, codes, e, w, label);
        one::<Rgb888, R>(r, codes, e, w, label);
        one::<Gray8, R>(r, codes, e, w, label);
    }
}

fn float_codes<R: Render>(r: &R) -> Vec<[u32; 3]> {
    frame::<LinearRgb, _>(r)
        .iter()
        .map(|c| [linear_code(c.r), linear_code(c.g), linear_code(c.b)])
        .collect()
}

#[test]
fn float_paths_store_the_encoding_rule_and_agree_bit_for_bit() {
    let mut scenes: Vec<(String, TestScene, u32, u32)> = random_scenes(16, 0x5eed_e1c0)
        .into_iter()
        .enumerate()
        .map(|(i, s)| (format!("random scene {i}"), s, 61 + i as u32 % 9, 37))
        .collect();
    let series = exponent_series().unwrap();
    let (w, h) = (160, 120);
    let scalar = Prepared::<Scalar>::new(&series, w, h).unwrap();
    let codes = float_codes(&scalar);
    let codes = |_| codes.clone();
    check_against_rule(&scalar, codes, "series scalar");
    check_against_rule(
        &Prepared::<Simd4>::new(&series, w, h).unwrap(),
        codes,
        "series simd4",
    );
    check_against_rule(
        &Prepared::<Simd8>::new(&series, w, h).unwrap(),
        codes,
        "series simd8",
    );
    for (label, scene, w, h) in scenes.drain(..) {
        let scalar = Prepared::<Scalar>::new(&scene, w, h).unwrap();
        let codes = float_codes(&scalar);
        let codes = |_| codes.clone();
        check_against_rule(&scalar, codes, &label);
        check_against_rule(
            &Prepared::<Simd4>::new(&scene, w, h).unwrap(),
            codes,
            &label,
        );
        check_against_rule(
            &Prepared::<Simd8>::new(&scene, w, h)
                .unwrap()
                .with_spans(false),
            codes,
            &label,
        );
    }
}

/// The fixed path's linear codes under encoding `e`: its LinearRgb output is its 16.16 colour
/// divided by 65536, exactly. The encoding's transfer sets which pixels the narrow kernel
/// hands to the full-width one (the dark silhouette pixels under sRGB), so the codes are
/// taken under the same encoding.
fn fixed_codes<R: Render>(r: &R, e: Encoding) -> Vec<[u32; 3]> {
    frame_with::<LinearRgb, _>(r, e)
        .iter()
        .map(|c| [c.r, c.g, c.b].map(|v| linear_code_fixed((v * 65536.0) as u32)))
        .collect()
}

#[test]
fn fixed_path_stores_the_encoding_rule() {
    let series = exponent_series().unwrap();
    let fixed = PreparedFixed::new(&series, 160, 120).unwrap();
    check_against_rule(&fixed, |e| fixed_codes(&fixed, e), "series fixed");
    for (i, scene) in random_scenes(8, 0x5eed_f1c0).iter().enumerate() {
        let f = PreparedFixed::new(scene, 67, 41).unwrap();
        check_against_rule(
            &f,
            |e| fixed_codes(&f, e),
            &format!("random scene {i} fixed"),
        );
    }
}

#[test]
fn default_encoding_is_the_historical_output() {
    let series = exponent_series().unwrap();
    let scalar = Prepared::<Scalar>::new(&series, 96, 64).unwrap();
    let linear: Vec<LinearRgb> = frame(&scalar);
    let shade = |c: &LinearRgb| Shade {
        color: *c,
        hit: HitRecord::default(),
    };
    let want: Vec<Rgb565> = linear.iter().map(|c| Rgb565::encode(&shade(c))).collect();
    assert!(frame::<Rgb565, _>(&scalar) == want);
    assert!(frame::<Rgb565, _>(&scalar.clone().with_encoding(Encoding::LINEAR)) == want);
    assert_eq!(Encoding::default(), Encoding::LINEAR);
    // Gray8 by default: the f32 luma rounded like `quantize`, per pixel and per packet.
    let want: Vec<Gray8> = linear.iter().map(|c| Gray8::encode(&shade(c))).collect();
    assert!(frame::<Gray8, _>(&scalar) == want);
    assert!(frame::<Gray8, _>(&Prepared::<Simd8>::new(&series, 96, 64).unwrap()) == want);
    let want: Vec<Bgr565> = linear.iter().map(|c| Bgr565::encode(&shade(c))).collect();
    assert!(frame::<Bgr565, _>(&Prepared::<Simd4>::new(&series, 96, 64).unwrap()) == want);
}

fn assert_segments_match<R: Render>(r: &R, label: &str) {
    let w = r.width() as usize;
    for e in ENCODINGS {
        let whole: Vec<Rgb565> = frame_with(r, e);
        let hits: Vec<HitRecord> = frame(r);
        for y in 0..r.height() {
            let mut row = vec![Rgb565::default(); w];
            // Cut the row at irregular places, including empty segments.
            let mut x = 0usize;
            let mut step = 1 + y as usize % 7;
            while x < w {
                let end = (x + step).min(w);
                r.render_segment_with(y, x as u32, &mut row[x..end], e)
                    .unwrap();
                r.render_segment_with(y, x as u32, &mut row[x..x], e)
                    .unwrap();
                x = end;
                step = step * 3 % 23 + 1;
            }
            let want = &whole[y as usize * w..(y as usize + 1) * w];
            assert_eq!(row, want, "{label}, {e:?}: row {y} in segments");
            // Coverage is conservative: outside it, nothing is hit.
            let row_hits = &hits[y as usize * w..(y as usize + 1) * w];
            let cov = r.row_coverage(y);
            for (x, h) in row_hits.iter().enumerate() {
                let inside = cov.is_some_and(|s| s.start as usize <= x && x < s.end as usize);
                assert!(
                    inside || h.sphere.is_none(),
                    "{label}: ({x},{y}) covered outside row_coverage {cov:?}"
                );
            }
        }
    }
    let mut row = vec![Rgb565::default(); 3];
    assert_eq!(
        r.render_segment(0, r.width() - 2, &mut row),
        Err(RenderError::SegmentOutOfRange {
            x: r.width() - 2,
            len: 3,
            width: r.width()
        })
    );
    assert_eq!(
        r.render_segment(r.height(), 0, &mut row[..1]),
        Err(RenderError::RowOutOfRange {
            y: r.height(),
            height: r.height()
        })
    );
}

#[test]
fn segments_equal_whole_rows_and_coverage_is_conservative() {
    let series = exponent_series().unwrap();
    let (w, h) = (101, 50);
    assert_segments_match(&Prepared::<Scalar>::new(&series, w, h).unwrap(), "scalar");
    assert_segments_match(&Prepared::<Simd8>::new(&series, w, h).unwrap(), "simd8");
    assert_segments_match(&PreparedFixed::new(&series, w, h).unwrap(), "fixed");
    for (i, scene) in random_scenes(6, 0x5eed_5e90).iter().enumerate() {
        let label = format!("random scene {i}");
        assert_segments_match(&Prepared::<Simd4>::new(scene, 45, 30).unwrap(), &label);
        assert_segments_match(&PreparedFixed::new(scene, 45, 30).unwrap(), &label);
    }
}

/// CRC-32 (IEEE) of a frame of RGB565 pixels as little-endian `u16`s, row-major (the rule
/// of `tests/fixed_golden.rs`).
fn crc_rgb565(pixels: &[Rgb565]) -> u32 {
    let mut hasher = crc32fast::Hasher::new();
    for p in pixels {
        hasher.update(&p.0.to_le_bytes());
    }
    hasher.finalize()
}

/// CRC-32 (IEEE) of a frame of `Gray8` levels, row-major.
fn crc_gray8(pixels: &[Gray8]) -> u32 {
    crc32fast::hash(&pixels.iter().map(|p| p.0).collect::<Vec<u8>>())
}

/// Golden CRC32s of the exponent series at 320×240 with dithering, per encoding and format:
/// `[linear dithered RGB565, sRGB dithered RGB565, sRGB dithered Gray8]`. Printed by
/// `cargo test --test encodings golden -- --nocapture` on x86_64 and copied here.
const GOLDEN_SCALAR_DITHERED: [u32; 3] = [0xb13b_70b5, 0x39e7_519d, 0x2142_2168];
/// The same frames on the fixed path (integers only: the same bits on every target). The
/// sRGB RGB565 value last changed when the prepare's distant-light direction became the
/// unit vector to within a step of 2⁻³⁰ (`unit_q30`, one Newton step from the `f32` unit
/// vector, instead of the general normalization's 1.9 steps): a pixel that lies on a
/// dithering threshold can round the other way, and in this frame some do.
const GOLDEN_FIXED_DITHERED: [u32; 3] = [0x5302_95fb, 0x0bc4_1ae3, 0x87b1_9132];

fn dithered_crcs<R: Render + Clone>(r: &R) -> [u32; 3] {
    let lin = r.clone().with_encoding(Encoding::LINEAR.dithered());
    let srgb = r.clone().with_encoding(Encoding::SRGB.dithered());
    [
        crc_rgb565(&frame(&lin)),
        crc_rgb565(&frame(&srgb)),
        crc_gray8(&frame(&srgb)),
    ]
}

#[test]
fn dithered_frames_match_their_golden_crcs() {
    let series = exponent_series().unwrap();
    let scalar = Prepared::<Scalar>::new(&series, 320, 240).unwrap();
    let fixed = PreparedFixed::new(&series, 320, 240).unwrap();
    let got_scalar = dithered_crcs(&scalar);
    let got_fixed = dithered_crcs(&fixed);
    println!("scalar dithered: {got_scalar:#010x?}");
    println!("fixed dithered:  {got_fixed:#010x?}");
    // The SIMD paths give the scalar bits; rows rendered bottom-up give the same frame.
    assert_eq!(
        dithered_crcs(&Prepared::<Simd8>::new(&series, 320, 240).unwrap()),
        got_scalar
    );
    assert_eq!(
        dithered_crcs(&Prepared::<Simd4>::new(&series, 320, 240).unwrap()),
        got_scalar
    );
    let srgb = fixed.clone().with_encoding(Encoding::SRGB.dithered());
    let mut rows = vec![Rgb565::default(); 320 * 240];
    for (y, row) in rows.chunks_exact_mut(320).enumerate().rev() {
        srgb.render_line(y as u32, row).unwrap();
    }
    assert_eq!(crc_rgb565(&rows), got_fixed[1]);
    assert_eq!(
        got_scalar, GOLDEN_SCALAR_DITHERED,
        "scalar golden CRCs changed"
    );
    assert_eq!(
        got_fixed, GOLDEN_FIXED_DITHERED,
        "fixed golden CRCs changed"
    );
}

/// Largest per-channel difference in levels between two frames, and the share of equal
/// channels.
fn closeness<P: Copy>(a: &[P], b: &[P], levels: impl Fn(P) -> [u8; 3]) -> (u8, f64) {
    let mut max = 0u8;
    let mut equal = 0usize;
    for (a, b) in a.iter().zip(b) {
        for (x, y) in levels(*a).iter().zip(levels(*b)) {
            max = max.max(x.abs_diff(y));
            equal += (*x == y) as usize;
        }
    }
    (max, equal as f64 / (3 * a.len()) as f64)
}

#[test]
fn fixed_stays_close_to_scalar_with_every_encoding() {
    let series = exponent_series().unwrap();
    let scalar = Prepared::<Scalar>::new(&series, 320, 240).unwrap();
    let fixed = PreparedFixed::new(&series, 320, 240).unwrap();
    // The fixed contract lets 0.1% of a frame's ray decisions differ; colours are compared
    // where both paths made the same ones.
    let hits_a = frame::<HitRecord, _>(&scalar);
    let hits_b = frame::<HitRecord, _>(&fixed);
    let same: Vec<bool> = hits_a.iter().zip(&hits_b).map(|(a, b)| a == b).collect();
    let differ = same.iter().filter(|s| !**s).count();
    println!("ray decisions differ: {differ} of {}", same.len());
    assert!(differ * 1000 <= same.len(), "{differ} ray decisions differ");
    fn kept<P>(v: Vec<P>, same: &[bool]) -> Vec<P> {
        v.into_iter()
            .zip(same)
            .filter_map(|(p, s)| s.then_some(p))
            .collect()
    }
    for e in ENCODINGS {
        let a: Vec<Rgb888> = kept(frame_with(&scalar, e), &same);
        let b: Vec<Rgb888> = kept(frame_with(&fixed, e), &same);
        let (max888, eq888) = closeness(&a, &b, |p| [p.r, p.g, p.b]);
        let a: Vec<Rgb565> = kept(frame_with(&scalar, e), &same);
        let b: Vec<Rgb565> = kept(frame_with(&fixed, e), &same);
        let (max565, eq565) = closeness(&a, &b, |p| {
            let (r, g, b) = p.levels();
            [r, g, b]
        });
        let a: Vec<Gray8> = kept(frame_with(&scalar, e), &same);
        let b: Vec<Gray8> = kept(frame_with(&fixed, e), &same);
        let (maxg, eqg) = closeness(&a, &b, |p| [p.0; 3]);
        println!(
            "{e:?}: Rgb888 max {max888} ({:.3}% equal), Rgb565 max {max565} ({:.3}% equal), \
             Gray8 max {maxg} ({:.3}% equal)",
            eq888 * 100.0,
            eq565 * 100.0,
            eqg * 100.0
        );
        assert!(max888 <= 2 && maxg <= 2 && max565 <= 1, "{e:?}");
    }
}

#[test]
fn dithering_removes_banding_in_4x4_averages() {
    // On the dark side of the spheres, RGB565 without dithering holds one level over wide
    // bands; with it, each 4×4 block averages closer to the exact colour.
    let series = exponent_series().unwrap();
    let (w, h) = (320usize, 240usize);
    let scalar = Prepared::<Scalar>::new(&series, w as u32, h as u32).unwrap();
    let linear: Vec<LinearRgb> = frame(&scalar);
    for transfer in [Encoding::LINEAR, Encoding::SRGB] {
        let mut err = [0.0f64; 2];
        for (k, e) in [transfer, transfer.dithered()].into_iter().enumerate() {
            let px: Vec<Rgb565> = frame_with(&scalar, e);
            for by in (0..h).step_by(4) {
                for bx in (0..w).step_by(4) {
                    let (mut got, mut want) = (0.0f64, 0.0f64);
                    for y in by..by + 4 {
                        for x in bx..bx + 4 {
                            let i = y * w + x;
                            let g = px[i].levels().1 as f64 / 63.0;
                            let code = linear_code(linear[i].g);
                            let v = match e.transfer {
                                Transfer::Linear => code as f64 / 65536.0,
                                Transfer::Srgb => {
                                    shadeline::encoding::srgb_encode(code) as f64 / 65536.0
                                }
                            };
                            got += g;
                            want += v;
                        }
                    }
                    err[k] += ((got - want) / 16.0).abs();
                }
            }
        }
        println!("{transfer:?}: mean 4x4 block error without / with dithering: {err:?}");
        assert!(err[1] < err[0] * 0.5, "{transfer:?}: {err:?}");
    }
}

#[test]
fn byte_rows_are_big_endian_and_checked() {
    let series = exponent_series().unwrap();
    let (w, h) = (150u32, 90u32);
    let scalar = Prepared::<Simd8>::new(&series, w, h)
        .unwrap()
        .with_encoding(Encoding::SRGB.dithered());
    let fixed = PreparedFixed::new(&series, w, h).unwrap();
    fn check<R: Render>(r: &R, w: u32, h: u32) {
        for y in 0..h {
            let mut line = vec![Rgb565::default(); w as usize];
            r.render_line(y, &mut line).unwrap();
            let mut bytes = vec![0u8; 2 * w as usize];
            r.render_line_bytes::<Rgb565>(y, &mut bytes).unwrap();
            let want: Vec<u8> = line.iter().flat_map(|p| p.0.to_be_bytes()).collect();
            assert_eq!(bytes, want);

            let mut line = vec![Bgr565::default(); w as usize];
            r.render_line(y, &mut line).unwrap();
            r.render_line_bytes::<Bgr565>(y, &mut bytes).unwrap();
            let want: Vec<u8> = line.iter().flat_map(|p| p.0.to_be_bytes()).collect();
            assert_eq!(bytes, want);

            let mut line = vec![Rgb888::default(); w as usize];
            r.render_line(y, &mut line).unwrap();
            let mut bytes3 = vec![0u8; 3 * w as usize];
            r.render_line_bytes::<Rgb888>(y, &mut bytes3).unwrap();
            let want: Vec<u8> = line.iter().flat_map(|p| [p.r, p.g, p.b]).collect();
            assert_eq!(bytes3, want);

            let mut line = vec![Gray8::default(); w as usize];
            r.render_line(y, &mut line).unwrap();
            let mut bytes1 = vec![0u8; w as usize];
            r.render_line_bytes::<Gray8>(y, &mut bytes1).unwrap();
            let want: Vec<u8> = line.iter().map(|p| p.0).collect();
            assert_eq!(bytes1, want);
        }
    }
    check(&scalar, w, h);
    check(&fixed, w, h);

    // Wrong lengths and rows are typed errors and write nothing.
    let mut bytes = vec![0xaau8; 2 * w as usize + 1];
    assert_eq!(
        fixed.render_line_bytes::<Rgb565>(0, &mut bytes),
        Err(RenderError::ByteLength {
            expected: 2 * w as usize,
            got: 2 * w as usize + 1
        })
    );
    assert_eq!(
        fixed.render_line_bytes::<Rgb565>(0, &mut bytes[..w as usize]),
        Err(RenderError::ByteLength {
            expected: 2 * w as usize,
            got: w as usize
        })
    );
    assert_eq!(
        fixed.render_line_bytes::<Rgb565>(h, &mut bytes[..2 * w as usize]),
        Err(RenderError::RowOutOfRange { y: h, height: h })
    );
    assert!(bytes.iter().all(|b| *b == 0xaa));
}

#[test]
fn byte_order_of_known_colours() {
    let shade = |r, g, b| Shade {
        color: LinearRgb::new(r, g, b),
        hit: HitRecord::default(),
    };
    let red = shade(1.0, 0.0, 0.0);
    let green = shade(0.0, 1.0, 0.0);
    let blue = shade(0.0, 0.0, 1.0);
    assert_eq!(Rgb565::encode(&red).to_bytes(), [0xf8, 0x00]);
    assert_eq!(Rgb565::encode(&green).to_bytes(), [0x07, 0xe0]);
    assert_eq!(Rgb565::encode(&blue).to_bytes(), [0x00, 0x1f]);
    assert_eq!(Bgr565::encode(&red).to_bytes(), [0x00, 0x1f]);
    assert_eq!(Bgr565::encode(&green).to_bytes(), [0x07, 0xe0]);
    assert_eq!(Bgr565::encode(&blue).to_bytes(), [0xf8, 0x00]);
    assert_eq!(Bgr565::encode(&red).levels(), (31, 0, 0));
    assert_eq!(Rgb888::encode(&blue).to_bytes(), [0, 0, 255]);
    assert_eq!(Gray8::encode(&shade(1.0, 1.0, 1.0)).to_bytes(), [255]);
    assert_eq!(Gray8::encode(&green).0, 182); // 0.7152·255 = 182.4
    let fixed = |r: u32, g: u32, b: u32| FixedShade {
        color: [r, g, b],
        hit: HitRecord::default(),
    };
    assert_eq!(
        Rgb565::encode_fixed(&fixed(65536, 0, 0)).to_bytes(),
        [0xf8, 0x00]
    );
    assert_eq!(
        Bgr565::encode_fixed(&fixed(65536, 0, 0)).to_bytes(),
        [0x00, 0x1f]
    );
    assert_eq!(Gray8::encode_fixed(&fixed(0, 65536, 0)).0, 182);
    assert_eq!(
        Gray8::encode_fixed(&fixed(1 << 20, 1 << 20, 1 << 20)).0,
        255
    );
}
