//! The analytic anti-aliased silhouettes, on the scalar and on the fixed path, against a
//! 16×16 supersampled truth, next to plain 4×4 supersampling: on the exponent series, the
//! materials gallery and random scenes of spheres that overlap on the screen, the analytic
//! edges of both paths must beat 4×4 supersampling (a
//! lower mean error, and as many pixels or more within 8 levels) and keep at least 99% of the
//! silhouette pixels within 8 levels of the truth. The largest error is printed, not
//! compared: where a shadow's edge crosses a silhouette pixel, supersampling smooths the
//! shadow's edge too, and the analytic edges (which smooth outlines only) keep it hard.
//! `cargo test -p shadeline-harness --test edges -- --nocapture` prints the tables.

use shadeline::{
    Camera, Light, LinearRgb, Material, Model, Prepared, PreparedFixed, Render, Rgb888, Scalar,
    Sphere, Vec3,
};
use shadeline_harness::edges::{
    box_filtered, edge_stats, edge_table, EdgeRow, EdgeStats, SUPERSAMPLES, TRUTH_SAMPLES,
};
use shadeline_harness::scene_file::{builtin_scene, preset, FileScene, MAX_LIGHTS, MAX_SPHERES};

/// The silhouette statistics of the sharp frame, 4×4 supersampling and the analytic edges on
/// the scalar path and on the fixed path.
fn measure(scene: &FileScene, w: u32, h: u32, name: &str) -> [EdgeStats; 4] {
    let truth = box_filtered(scene, w, h, TRUTH_SAMPLES, 2).unwrap();
    let supersampled: Vec<Rgb888> = box_filtered(scene, w, h, SUPERSAMPLES, 2)
        .unwrap()
        .iter()
        .map(|p| p.color)
        .collect();
    let frame = Prepared::<Scalar, MAX_SPHERES, MAX_LIGHTS>::new(scene, w, h).unwrap();
    let mut sharp = vec![Rgb888::default(); (w * h) as usize];
    frame.render_frame(&mut sharp).unwrap();
    let mut smooth = sharp.clone();
    frame
        .with_antialiasing(true)
        .render_frame(&mut smooth)
        .unwrap();
    let mut fixed = sharp.clone();
    PreparedFixed::<MAX_SPHERES, MAX_LIGHTS>::new(scene, w, h)
        .unwrap()
        .with_antialiasing(true)
        .render_frame(&mut fixed)
        .unwrap();
    let stats = [
        edge_stats(&truth, &sharp).unwrap(),
        edge_stats(&truth, &supersampled).unwrap(),
        edge_stats(&truth, &smooth).unwrap(),
        edge_stats(&truth, &fixed).unwrap(),
    ];
    let methods = [
        "sharp",
        "4×4 supersampling",
        "analytic (scalar)",
        "analytic (fixed)",
    ];
    let rows: Vec<EdgeRow> = methods
        .iter()
        .zip(stats)
        .map(|(m, stats)| EdgeRow {
            method: format!("{name}: {m}"),
            stats,
        })
        .collect();
    print!("{}", edge_table(&rows));
    stats
}

/// Both analytic frames (scalar, fixed) against 4×4 supersampling.
fn assert_beats_supersampling([sharp, ss, scalar, fixed]: [EdgeStats; 4], name: &str) {
    assert!(
        sharp.pixels > 100,
        "{name}: {} silhouette pixels",
        sharp.pixels
    );
    for (path, analytic) in [("scalar", scalar), ("fixed", fixed)] {
        assert!(
            analytic.mean < ss.mean,
            "{name}, {path}: mean {analytic:?} vs {ss:?}"
        );
        assert!(
            analytic.within_8 >= ss.within_8,
            "{name}, {path}: within 8 {analytic:?} vs {ss:?}"
        );
        assert!(analytic.within_8 >= 99.0, "{name}, {path}: {analytic:?}");
    }
}

#[test]
fn analytic_edges_beat_supersampling_on_the_presets() {
    let series = builtin_scene().unwrap();
    let stats = measure(&series.scene, 320, 240, "exponent series");
    assert_beats_supersampling(stats, "exponent series");
    let gallery = preset("materials").unwrap().unwrap();
    let stats = measure(&gallery.scene, 320, 180, "materials");
    assert_beats_supersampling(stats, "materials");
}

/// A small xorshift generator: the same scenes on every machine.
struct Random(u64);

impl Random {
    fn next(&mut self) -> f32 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 40) as f32 / (1u64 << 24) as f32
    }
    fn range(&mut self, lo: f32, hi: f32) -> f32 {
        lo + (hi - lo) * self.next()
    }
}

/// Four to seven spheres crowded in front of the camera at different depths, so that they
/// overlap on the screen without touching in space, lit by a distant and a point light,
/// with materials of every model family.
fn overlapping_spheres(seed: u64) -> FileScene {
    let mut rng = Random(seed.wrapping_mul(0x9e37_79b9_7f4a_7c15) | 1);
    let camera = Camera {
        position: Vec3::new(0.0, 0.0, 10.0),
        look_at: Vec3::new(0.0, 0.0, 0.0),
        up: Vec3::new(0.0, 1.0, 0.0),
        vfov_degrees: 40.0,
    };
    let background = LinearRgb::new(rng.next(), rng.next(), rng.next());
    let mut scene = FileScene::new(camera, background).unwrap();
    let count = 4 + (rng.next() * 4.0) as usize;
    let mut placed: Vec<(Vec3, f32)> = Vec::new();
    while placed.len() < count {
        let center = Vec3::new(
            rng.range(-2.0, 2.0),
            rng.range(-1.5, 1.5),
            rng.range(-4.0, 3.0),
        );
        let radius = rng.range(0.4, 1.4);
        let clear = placed.iter().all(|&(c, r)| {
            let d = center - c;
            d.dot(d).sqrt() > r + radius + 0.05
        });
        if !clear {
            continue;
        }
        placed.push((center, radius));
        let model = [
            Model::Phong,
            Model::BlinnPhong,
            Model::NormalizedPhong(Default::default()),
            Model::Lambert,
        ][placed.len() % 4];
        scene
            .add_sphere(Sphere {
                center,
                radius,
                material: Material {
                    albedo: LinearRgb::new(rng.next(), rng.next(), rng.next()),
                    kd: rng.range(0.3, 0.9),
                    ks: rng.range(0.0, 0.1),
                    shininess: rng.range(5.0, 300.0),
                    model,
                },
            })
            .unwrap();
    }
    scene
        .add_light(Light::Distant {
            direction: Vec3::new(rng.range(-1.0, 1.0), -1.0, rng.range(-1.0, 0.0)),
            color: LinearRgb::new(1.0, 1.0, 1.0),
            intensity: rng.range(0.5, 1.5),
        })
        .unwrap();
    let position = Vec3::new(
        rng.range(-6.0, 6.0),
        rng.range(2.0, 6.0),
        rng.range(2.0, 8.0),
    );
    scene
        .add_light(Light::Point {
            position,
            color: LinearRgb::new(1.0, 0.9, 0.8),
            intensity: 4.0 * core::f32::consts::PI * position.dot(position) * 0.5,
            radius: 0.0,
        })
        .unwrap();
    scene
}

#[test]
fn analytic_edges_beat_supersampling_on_overlapping_spheres() {
    for seed in 1..=12 {
        let scene = overlapping_spheres(seed);
        let name = format!("overlapping spheres {seed}");
        let stats = measure(&scene, 200, 150, &name);
        assert_beats_supersampling(stats, &name);
    }
}
