//! Fuzz target `paths_agree` (differential): for every scene that validates, with every
//! reflection model and one of the four encodings, the scalar, 4-lane and 8-lane paths give
//! bit-identical rows — linear colour to the last bit, hit records, 8-bit and 5-6-5 pixels,
//! and with the encoding Rgb888, Rgb565, Bgr565, Gray8 and their display bytes — and turning
//! the scanline spans off (every packet tests every sphere) changes no bit either, so the
//! spans are conservative. The same holds with anti-aliased edges on (`with_antialiasing`):
//! every width gives the scalar bits, and so do the spans off, so the anti-aliased frame's
//! widened spans hold every pixel an outline reaches.
//!
//! The fixed-point path, for scenes it accepts (it refuses the others with
//! `OutOfFixedRange`, counted), renders without a panic; on *well-conditioned*
//! scenes its 8-bit output is within [`FIXED_LEVELS`] levels of the scalar output on every
//! pixel whose hit record agrees with the scalar one. Most pixels whose hit records differ
//! lie on a *boundary*, where one of the pixel's eight neighbours has another hit record in
//! the scalar or the fixed frame (a silhouette, a shadow's edge, a row tangent to a sphere):
//! there a decision is a rounding. Differences are counted over the whole run, on
//! boundaries and off them; the share off boundaries (a decision that rounds differently
//! with no visible edge next to it, such as a shadow ray grazing a sphere at one pixel) may
//! not exceed [`MAX_DIFFER`] (the fixed contract's 0.1 %) once [`MIN_PIXELS`] pixels have
//! been compared. The share on boundaries has no cap here: the fuzzer steers toward scenes
//! made of them (tiny frames, tangent rows), where it reached the contract's 0.1 % after
//! some 50,000 inputs; the contract itself is held on natural scenes by
//! `tests/fixed_agreement.rs`. Well-conditioned
//! ([`conditioned`]) bounds how much a rounding of a cosine or of the hit point can move a
//! pixel: exponents in `[1, 1e4]` (below 1 the lobe `cos^n` has an infinite slope at 0,
//! above 1e4 an `f32` cosine is too coarse for the lobe), weights and arriving light of
//! order 1, no point light inside or near a sphere, no sphere light (the edge of a penumbra
//! moves by a fraction of a pixel between the paths, and a pixel on it by many levels: the
//! fixed path's budget under sphere lights is held by `tests/sphere_lights.rs`; the float
//! paths' bit identity holds for sphere lights here too), and frames at most [`MAX_CONDITIONED`]
//! pixels across: the narrow kernel rounds a direction to about 2⁻¹⁵ of the field of view,
//! which on a frame tens of thousands of rows high is a band of rows where a decision
//! rounds the other way, every pixel of it with neighbours that agree (a 20-minute run
//! crossed the cap on such inputs; its last was 63 × 26,214), and at least
//! [`MIN_CONDITIONED`] pixels across: in a 1 × 1 frame a primary ray tangent to a sphere
//! (which the fuzzer finds easily: a camera looking at a point of the surface, at right
//! angles to its radius) decides its pixel by a rounding, and with no neighbour to show the
//! silhouette it counts as off a boundary (two 3-minute runs found 86 such frames, 258
//! pixels off a boundary), and with a pixel pitch (the field of view over the frame's
//! height) of at least [`MIN_PITCH`] radians: below it neighbouring pixels are one ray to
//! `f32` or nearly, so a tangent decision covers the whole frame with no neighbour to show
//! it (a 20-minute run found one such scene, a 1.4·10⁻¹⁹° field of view with every ray
//! tangent to a sphere: 2,655 pixels off a boundary). Outside that domain two correct paths disagree by
//! many levels or decisions — so would two float builds — and no budget is claimed. The
//! counts are printed to stderr every 2¹⁴ inputs.

use crate::{
    build_scene, for_each_path, render_row, FuzzScene, PathVisitor, Row, SceneInput, LIGHTS,
    SPHERES,
};
use shadeline::{Encoding, Light, Prepared, Render, RenderError, Scalar, Simd4, Simd8};
use std::sync::atomic::{AtomicU64, Ordering};

/// The fixed-point path's budget against the scalar path, in 8-bit levels.
const FIXED_LEVELS: i32 = 2;
/// Largest share of compared pixels whose hit records may differ (the fixed contract).
const MAX_DIFFER: f64 = 0.001;
/// Pixels to compare before the share is checked.
const MIN_PIXELS: u64 = 100_000;
/// Widest and tallest frame the fixed path's budget is checked on (see the module docs).
const MAX_CONDITIONED: u32 = 2048;
/// Narrowest and lowest frame it is checked on: a pixel's boundary test needs neighbours,
/// and in a frame one or two pixels across a pixel has none on a side (see the module docs).
const MIN_CONDITIONED: u32 = 3;
/// Smallest pixel pitch, in radians, the budget is checked at: `2⁻¹⁶`, some 500 times the
/// `f32` resolution of a unit direction, so neighbouring pixels are distinct rays.
const MIN_PITCH: f32 = 1.0 / 65_536.0;

/// Counts over the whole run, for the fixed path on well-conditioned scenes.
struct Counts {
    inputs: AtomicU64,
    rendered: AtomicU64,
    refused: AtomicU64,
    pixels: AtomicU64,
    differ: AtomicU64,
    interior: AtomicU64,
}

static COUNTS: Counts = Counts {
    inputs: AtomicU64::new(0),
    rendered: AtomicU64::new(0),
    refused: AtomicU64::new(0),
    pixels: AtomicU64::new(0),
    differ: AtomicU64::new(0),
    interior: AtomicU64::new(0),
};

impl Counts {
    fn add(counter: &AtomicU64, n: u64) -> u64 {
        counter.fetch_add(n, Ordering::Relaxed) + n
    }

    /// Prints the counts now and then, and fails once the share of differing decisions is
    /// above the cap.
    fn check(&self) {
        let inputs = Counts::add(&self.inputs, 1);
        let (pixels, differ, interior) = (
            self.pixels.load(Ordering::Relaxed),
            self.differ.load(Ordering::Relaxed),
            self.interior.load(Ordering::Relaxed),
        );
        let share = interior as f64 / pixels.max(1) as f64;
        let line = format!(
            "paths_agree: {inputs} inputs; fixed path on well-conditioned scenes: {} rendered, \
             {} refused (OutOfFixedRange), {pixels} pixels compared, {differ} hit records \
             differ ({:.4}%), {interior} of them off boundaries ({:.4}%)",
            self.rendered.load(Ordering::Relaxed),
            self.refused.load(Ordering::Relaxed),
            100.0 * differ as f64 / pixels.max(1) as f64,
            100.0 * share
        );
        if inputs.is_power_of_two() && inputs >= 1 << 14 {
            eprintln!("{line}");
        }
        assert!(pixels < MIN_PIXELS || share <= MAX_DIFFER, "{line}");
    }
}

/// Whether the fixed-point budget applies to `scene` (see the module docs).
fn conditioned(scene: &FuzzScene) -> bool {
    const MAX_ARRIVING: f32 = 4.0;
    let materials = scene.spheres().iter().all(|s| {
        let m = &s.material;
        // The normalized models' further lobes, like lobe 0: exponents in [1, 1e4],
        // weights of order 1 (a normalized lobe's peak is then at most (n + 2)/(2π) ≈ 1600).
        let lobes = m.model.specular().is_none_or(|spec| {
            spec.more_lobes.iter().all(|l| {
                l.weight == 0.0 || ((1.0..=1.0e4).contains(&l.shininess) && l.weight <= 1.0)
            })
        });
        (1.0..=1.0e4).contains(&m.shininess)
            && m.ks <= 1.0
            && lobes
            && [m.albedo.r, m.albedo.g, m.albedo.b]
                .iter()
                .all(|a| a * m.kd <= 1.0)
    });
    let lights = scene.lights().iter().all(|l| match *l {
        Light::Distant {
            color, intensity, ..
        } => [color.r, color.g, color.b]
            .iter()
            .all(|c| c * intensity <= MAX_ARRIVING),
        Light::Point {
            position,
            color,
            intensity,
            ..
        } => scene.spheres().iter().all(|s| {
            // Arriving light at the sphere's nearest point, with the light clear of it.
            let d = position - s.center;
            let gap = d.dot(d).sqrt() - s.radius;
            let most = [color.r, color.g, color.b]
                .iter()
                .fold(0.0f32, |m, c| m.max(c * intensity));
            gap > 1.0e-2 * s.radius.max(1.0)
                && most / (4.0 * core::f32::consts::PI * gap * gap) <= MAX_ARRIVING
        }),
    });
    // A sphere light's penumbra can move by a fraction of a pixel between the paths, which
    // moves a pixel on its edge by many levels: its budget is `tests/sphere_lights.rs`'s.
    materials && lights && scene.sphere_light().is_none()
}

/// Compares every path's rows with the scalar path's rows.
struct Agree {
    rows: [u32; 3],
    encoding: Encoding,
    scalar: Vec<Row>,
    /// The scalar path, for the rows around a pixel whose hit record differs.
    scalar_path: Prepared<Scalar, SPHERES, LIGHTS>,
    height: u32,
    /// Whether the fixed path's budget applies.
    conditioned: bool,
}

/// Whether pixel `x` of row `y` lies on a boundary of `scalar`'s or `fixed`'s hit records:
/// one of its eight neighbours has another hit record in the same path.
fn on_boundary<R: Render + Clone>(
    scalar: &Prepared<Scalar, SPHERES, LIGHTS>,
    fixed: &R,
    (x, y): (usize, u32),
    height: u32,
    encoding: Encoding,
) -> bool {
    let rows = y.saturating_sub(1)..=(y + 1).min(height - 1);
    let scalar_rows: Vec<Row> = rows
        .clone()
        .map(|r| render_row(scalar, r, encoding))
        .collect();
    let fixed_rows: Vec<Row> = rows.map(|r| render_row(fixed, r, encoding)).collect();
    let centre = (y - y.saturating_sub(1)) as usize;
    [scalar_rows, fixed_rows].iter().any(|frame| {
        let own = frame[centre].hits[x];
        frame.iter().any(|row| {
            let lo = x.saturating_sub(1);
            let hi = (x + 1).min(row.hits.len() - 1);
            row.hits[lo..=hi].iter().any(|h| *h != own)
        })
    })
}

impl PathVisitor for Agree {
    fn visit<R: Render + Clone>(&mut self, name: &'static str, prepared: Result<R, RenderError>) {
        let frame = match prepared {
            Ok(frame) => frame,
            Err(RenderError::OutOfFixedRange { .. }) if name == "fixed" => {
                if self.conditioned {
                    Counts::add(&COUNTS.refused, 1);
                }
                return;
            }
            Err(e) => panic!("{name}: a valid scene was refused: {e}"),
        };
        if name == "fixed" && self.conditioned {
            Counts::add(&COUNTS.rendered, 1);
        }
        for (y, want) in self.rows.iter().zip(&self.scalar) {
            let got = render_row(&frame, *y, self.encoding);
            if name == "fixed" {
                if !self.conditioned {
                    continue;
                }
                Counts::add(&COUNTS.pixels, got.hits.len() as u64);
                for (x, (g, w)) in got.rgb888.iter().zip(&want.rgb888).enumerate() {
                    if got.hits[x] != want.hits[x] {
                        Counts::add(&COUNTS.differ, 1);
                        let at = (x, *y);
                        if !on_boundary(&self.scalar_path, &frame, at, self.height, self.encoding) {
                            Counts::add(&COUNTS.interior, 1);
                        }
                        continue;
                    }
                    let levels = [(g.r, w.r), (g.g, w.g), (g.b, w.b)]
                        .iter()
                        .map(|&(a, b)| (i32::from(a) - i32::from(b)).abs())
                        .max()
                        .unwrap_or(0);
                    assert!(
                        levels <= FIXED_LEVELS,
                        "fixed row {y} pixel {x}: {g:?} vs scalar {w:?}"
                    );
                }
                continue;
            }
            assert_bit_identical(&got, want, &format!("{name} row {y}"));
        }
    }
}

fn assert_bit_identical(got: &Row, want: &Row, what: &str) {
    let (g, w) = (got.linear_bits(), want.linear_bits());
    if let Some(x) = g.iter().zip(&w).position(|(a, b)| a != b) {
        panic!(
            "{what}: pixel {x} linear {:?} vs scalar {:?}",
            got.linear[x], want.linear[x]
        );
    }
    assert_eq!(got.hits, want.hits, "{what}: hit records");
    assert_eq!(got.rgb888, want.rgb888, "{what}: Rgb888");
    assert_eq!(got.rgb565, want.rgb565, "{what}: Rgb565");
    let e = got.encoding;
    assert_eq!(got.enc_rgb888, want.enc_rgb888, "{what}: Rgb888 {e:?}");
    assert_eq!(got.enc_rgb565, want.enc_rgb565, "{what}: Rgb565 {e:?}");
    assert_eq!(got.enc_bgr565, want.enc_bgr565, "{what}: Bgr565 {e:?}");
    assert_eq!(got.enc_gray8, want.enc_gray8, "{what}: Gray8 {e:?}");
    assert_eq!(got.bytes, want.bytes, "{what}: byte rows {e:?}");
}

/// `frame`'s rows are `want`'s, bit for bit (`what` names the frame in a failure).
fn assert_same_rows<R: Render + Clone>(
    frame: &R,
    rows: [u32; 3],
    encoding: Encoding,
    want: &[Row],
    what: &str,
) {
    for (y, want) in rows.iter().zip(want) {
        let got = render_row(frame, *y, encoding);
        assert_bit_identical(&got, want, &format!("{what}, row {y}"));
    }
}

/// The target's check of one input: panics on a failure, as libFuzzer needs.
pub fn check(input: &SceneInput) {
    let Some(scene): Option<FuzzScene> = build_scene(input) else {
        return;
    };
    let (width, height) = input.size();
    let rows = input.rows(height);
    let encoding = input.encoding();
    let scalar = Prepared::<Scalar, SPHERES, LIGHTS>::new(&scene, width, height)
        .expect("a valid scene prepares");
    let want: Vec<Row> = rows
        .iter()
        .map(|&y| render_row(&scalar, y, encoding))
        .collect();
    let mut agree = Agree {
        rows,
        encoding,
        scalar: want,
        scalar_path: scalar.clone(),
        height,
        conditioned: conditioned(&scene)
            && width.max(height) <= MAX_CONDITIONED
            && width.min(height) >= MIN_CONDITIONED
            && scene.camera().vfov_degrees.to_radians() / height as f32 >= MIN_PITCH,
    };
    for_each_path(&scene, width, height, &mut agree);
    let want = &agree.scalar;
    let naive = scalar.clone().with_spans(false);
    assert_same_rows(&naive, rows, encoding, want, "scalar without spans");
    let simd4 = Prepared::<Simd4, SPHERES, LIGHTS>::new(&scene, width, height).unwrap();
    let simd8 = Prepared::<Simd8, SPHERES, LIGHTS>::new(&scene, width, height).unwrap();
    let simd4_naive = simd4.clone().with_spans(false);
    assert_same_rows(&simd4_naive, rows, encoding, want, "simd4 without spans");
    let simd8_naive = simd8.clone().with_spans(false);
    assert_same_rows(&simd8_naive, rows, encoding, want, "simd8 without spans");
    // Anti-aliased edges: the same bits at every width, and the same with the spans off
    // (the widened spans hold every pixel an outline's ramp reaches).
    let smooth = scalar.with_antialiasing(true);
    let want: Vec<Row> = rows
        .iter()
        .map(|&y| render_row(&smooth, y, encoding))
        .collect();
    let smooth_naive = smooth.with_spans(false);
    assert_same_rows(
        &smooth_naive,
        rows,
        encoding,
        &want,
        "scalar antialiased, no spans",
    );
    let simd4 = simd4.with_antialiasing(true);
    assert_same_rows(&simd4, rows, encoding, &want, "simd4 antialiased");
    let simd8 = simd8.with_antialiasing(true);
    assert_same_rows(&simd8, rows, encoding, &want, "simd8 antialiased");
    assert_same_rows(
        &simd8.with_spans(false),
        rows,
        encoding,
        &want,
        "simd8 antialiased, no spans",
    );
    COUNTS.check();
}
