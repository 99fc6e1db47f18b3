//! Fuzz target `paths_agree` (differential): for every scene that validates, the scalar,
//! 4-lane and 8-lane paths give bit-identical rows — linear colour to the last bit, hit
//! records, 8-bit and 5-6-5 pixels — and turning the scanline spans off (every packet tests
//! every sphere) changes no bit either, so the spans are conservative.
//!
//! The fixed-point path, for scenes it accepts (it refuses the others with
//! `OutOfFixedRange`), renders without a panic; on *well-conditioned* scenes its 8-bit output
//! is within [`FIXED_LEVELS`] levels of the scalar output on every pixel whose hit record
//! agrees with the scalar one. Well-conditioned ([`conditioned`]) bounds how much a rounding
//! of a cosine or of the hit point can move a pixel: exponents in `[1, 1e4]` (below 1 the lobe
//! `cos^n` has an infinite slope at 0, above 1e4 an `f32` cosine is too coarse for the lobe),
//! weights and arriving light of order 1, no point light inside or near a sphere. Outside
//! that domain two correct paths disagree by many levels — so would two float builds — and no
//! budget is claimed.
#![no_main]

use libfuzzer_sys::fuzz_target;
use shadeline::{Light, Prepared, Render, RenderError, Scalar, Simd4, Simd8};
use shadeline_fuzz::{
    build_scene, for_each_path, render_row, FuzzScene, PathVisitor, Row, SceneInput, LIGHTS,
    SPHERES,
};

/// The fixed-point path's budget against the scalar path, in 8-bit levels.
const FIXED_LEVELS: i32 = 2;

/// Whether the fixed-point budget applies to `scene` (see the module docs).
fn conditioned(scene: &FuzzScene) -> bool {
    const MAX_ARRIVING: f32 = 4.0;
    let materials = scene.spheres().iter().all(|s| {
        let m = &s.material;
        (1.0..=1.0e4).contains(&m.shininess)
            && m.ks <= 1.0
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
    materials && lights
}

/// Compares every path's rows with the scalar path's rows.
struct Agree {
    rows: [u32; 3],
    scalar: Vec<Row>,
    /// Whether the fixed path's budget applies.
    conditioned: bool,
}

impl PathVisitor for Agree {
    fn visit<R: Render>(&mut self, name: &'static str, prepared: Result<R, RenderError>) {
        let frame = match prepared {
            Ok(frame) => frame,
            Err(RenderError::OutOfFixedRange { .. }) if name == "fixed" => return,
            Err(e) => panic!("{name}: a valid scene was refused: {e}"),
        };
        for (y, want) in self.rows.iter().zip(&self.scalar) {
            let got = render_row(&frame, *y);
            if name == "fixed" {
                if !self.conditioned {
                    continue;
                }
                for (x, (g, w)) in got.rgb888.iter().zip(&want.rgb888).enumerate() {
                    if got.hits[x] != want.hits[x] {
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
}

fn without_spans<R: Render>(frame: &R, rows: [u32; 3], scalar: &[Row], name: &str) {
    for (y, want) in rows.iter().zip(scalar) {
        let got = render_row(frame, *y);
        assert_bit_identical(&got, want, &format!("{name} without spans, row {y}"));
    }
}

fuzz_target!(|input: SceneInput| {
    let Some(scene): Option<FuzzScene> = build_scene(&input) else {
        return;
    };
    let (width, height) = input.size();
    let rows = input.rows(height);
    let scalar = Prepared::<Scalar, SPHERES, LIGHTS>::new(&scene, width, height)
        .expect("a valid scene prepares");
    let want: Vec<Row> = rows.iter().map(|&y| render_row(&scalar, y)).collect();
    let mut agree = Agree {
        rows,
        scalar: want,
        conditioned: conditioned(&scene),
    };
    for_each_path(&scene, width, height, &mut agree);
    let want = &agree.scalar;
    without_spans(&scalar.clone().with_spans(false), rows, want, "scalar");
    let simd4 = Prepared::<Simd4, SPHERES, LIGHTS>::new(&scene, width, height).unwrap();
    without_spans(&simd4.with_spans(false), rows, want, "simd4");
    let simd8 = Prepared::<Simd8, SPHERES, LIGHTS>::new(&scene, width, height).unwrap();
    without_spans(&simd8.with_spans(false), rows, want, "simd8");
});
