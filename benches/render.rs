//! Criterion benchmarks of the float paths, single thread, reported as Mpix/s; the fixed
//! path in `frame/exponent-series` (with and without anti-aliasing), `model/*`,
//! `frame/microfacets` and `frame/area-lights` (its costs on the MCUs are QEMU counts,
//! `.ci/firmware`).
//!
//! - `frame/*`: the exponent series at 320×240 and 1024×747, every width, with and without
//!   scanline spans (without spans is the naive renderer: every sphere at every pixel), and
//!   with analytic anti-aliasing of the silhouettes (`antialiased`).
//! - `kernel/*`: the shading kernel on fully covered packets: one sphere fills the view, so
//!   every packet is shaded and the row driver's share is negligible.
//! - `lights/*`, `spheres/*`, `size/*`: how cost scales with lights, spheres and pixels.
//! - `model/*`: `shadeline::covered_sphere` (one sphere covering the frame, two lights) in
//!   each of `shadeline::model_samples` (classic Phong, normalized Blinn-Phong with Fresnel,
//!   Oren–Nayar, GGX plastic, GGX gold), the frames of the M4F firmware's per-model runs; and `frame/microfacets`, the microfacet gallery; each on the fixed path
//!   too (`fixed`).
//! - `frame/area-lights`: the area-lights preset at its size, under its sphere light
//!   (`sphere-light`) and under a point light at the same place (`point-light`): the cost of
//!   soft shadows and widened lobes, on the float paths and the fixed path (`fixed`).
//! - `frame/matrix/<scene>`: the scene matrix (`floor`, `lamp`, `three-lights`, capacities
//!   `MatrixScene`) at `MATRIX_SIZE`, 320×240, with spans, on the float paths and the fixed
//!   path (`fixed`): the frames the firmware measures per covered pixel (50,132 of each
//!   frame's pixels; the exponent series at 320×240 covers 11,840).

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use shadeline::*;
use std::hint::black_box;
use std::time::Duration;

fn render<R: Render>(r: &R, buf: &mut [Rgb888]) {
    r.render_frame(buf).unwrap();
    black_box(&buf[0]);
}

fn bench_paths<const S: usize, const L: usize>(
    c: &mut Criterion,
    group: &str,
    scene: &Scene<S, L>,
    (w, h): (u32, u32),
    id: &str,
    (spans, antialias): (bool, bool),
) {
    let mut g = c.benchmark_group(group);
    g.throughput(Throughput::Elements(w as u64 * h as u64));
    let mut buf = vec![Rgb888::default(); w as usize * h as usize];
    let scalar = Prepared::<Scalar, S, L>::new(scene, w, h)
        .unwrap()
        .with_spans(spans)
        .with_antialiasing(antialias);
    g.bench_function(BenchmarkId::new("scalar", id), |b| {
        b.iter(|| render(&scalar, &mut buf))
    });
    let simd4 = Prepared::<Simd4, S, L>::new(scene, w, h)
        .unwrap()
        .with_spans(spans)
        .with_antialiasing(antialias);
    g.bench_function(BenchmarkId::new("simd4", id), |b| {
        b.iter(|| render(&simd4, &mut buf))
    });
    let simd8 = Prepared::<Simd8, S, L>::new(scene, w, h)
        .unwrap()
        .with_spans(spans)
        .with_antialiasing(antialias);
    g.bench_function(BenchmarkId::new("simd8", id), |b| {
        b.iter(|| render(&simd8, &mut buf))
    });
    g.finish();
}

/// The fixed path's frame of `scene`, in `group` next to the float paths' figures.
fn bench_fixed<const S: usize, const L: usize>(
    c: &mut Criterion,
    group: &str,
    scene: &Scene<S, L>,
    (w, h): (u32, u32),
    id: &str,
) {
    bench_fixed_with(c, group, scene, (w, h), id, false);
}

/// [`bench_fixed`] with the anti-aliased silhouettes on or off.
fn bench_fixed_with<const S: usize, const L: usize>(
    c: &mut Criterion,
    group: &str,
    scene: &Scene<S, L>,
    (w, h): (u32, u32),
    id: &str,
    antialias: bool,
) {
    let mut g = c.benchmark_group(group);
    g.throughput(Throughput::Elements(w as u64 * h as u64));
    let mut buf = vec![Rgb888::default(); w as usize * h as usize];
    let fixed = PreparedFixed::<S, L>::new(scene, w, h)
        .unwrap()
        .with_antialiasing(antialias);
    g.bench_function(BenchmarkId::new("fixed", id), |b| {
        b.iter(|| render(&fixed, &mut buf))
    });
    g.finish();
}

fn camera(distance: f32) -> Camera {
    Camera {
        position: Vec3::new(0.0, 0.0, distance),
        look_at: Vec3::new(0.0, 0.0, 0.0),
        up: Vec3::new(0.0, 1.0, 0.0),
        vfov_degrees: 40.0,
    }
}

fn plastic(n: f32) -> Material {
    Material {
        shininess: n,
        ..Material::default()
    }
}

/// One sphere that covers every pixel, lit by `lights` distant lights.
fn covered(lights: usize) -> Scene<32, 8> {
    let mut scene = Scene::new(camera(2.2), LinearRgb::new(0.0, 0.0, 0.0)).unwrap();
    scene
        .add_sphere(Sphere {
            center: Vec3::new(0.0, 0.0, 0.0),
            radius: 1.5,
            material: plastic(60.0),
        })
        .unwrap();
    for k in 0..lights {
        let a = k as f32 * 0.7;
        scene
            .add_light(Light::Distant {
                direction: Vec3::new(a.cos(), -1.0, a.sin() - 1.0),
                color: LinearRgb::new(1.0, 1.0, 1.0),
                intensity: 1.0,
            })
            .unwrap();
    }
    scene
}

/// `n` spheres on a grid filling the view, one light.
fn grid(n: usize) -> Scene<32, 8> {
    let mut scene = Scene::new(camera(14.0), LinearRgb::new(0.1, 0.1, 0.2)).unwrap();
    let side = (n as f32).sqrt().ceil() as usize;
    let step = 9.0 / side as f32;
    for k in 0..n {
        let (i, j) = ((k % side) as f32, (k / side) as f32);
        scene
            .add_sphere(Sphere {
                center: Vec3::new((i + 0.5) * step - 4.5, (j + 0.5) * step - 4.5, 0.0),
                radius: 0.45 * step,
                material: plastic(40.0),
            })
            .unwrap();
    }
    scene
        .add_light(Light::Distant {
            direction: Vec3::new(-0.4, -0.8, -0.4),
            color: LinearRgb::new(1.0, 1.0, 1.0),
            intensity: 3.0,
        })
        .unwrap();
    scene
}

/// The scene matrix's presets and their names in the firmware's runs and the scene files.
fn matrix() -> [(&'static str, MatrixScene); 3] {
    [
        ("floor", floor().unwrap()),
        ("lamp", lamp().unwrap()),
        ("three-lights", three_lights().unwrap()),
    ]
}

fn benches(c: &mut Criterion) {
    let series = exponent_series().unwrap();
    for size in [(320, 240), (1024, 747)] {
        let id = format!("{}x{}", size.0, size.1);
        let group = "frame/exponent-series";
        bench_paths(
            c,
            &format!("{group}/spans"),
            &series,
            size,
            &id,
            (true, false),
        );
        bench_paths(
            c,
            &format!("{group}/naive"),
            &series,
            size,
            &id,
            (false, false),
        );
        bench_paths(
            c,
            &format!("{group}/antialiased"),
            &series,
            size,
            &id,
            (true, true),
        );
        for (kind, antialias) in [("spans", false), ("antialiased", true)] {
            let group = format!("{group}/{kind}");
            bench_fixed_with(c, &group, &series, size, &id, antialias);
        }
    }
    bench_paths(
        c,
        "kernel/covered",
        &covered(1),
        (320, 240),
        "1-light",
        (true, false),
    );
    for lights in [1, 2, 4, 8] {
        bench_paths(
            c,
            "lights",
            &covered(lights),
            (320, 240),
            &lights.to_string(),
            (true, false),
        );
    }
    for spheres in [1, 5, 16, 32] {
        bench_paths(
            c,
            "spheres",
            &grid(spheres),
            (320, 240),
            &spheres.to_string(),
            (true, false),
        );
    }
    for size in [(160, 120), (320, 240), (640, 480), (1280, 960)] {
        let id = format!("{}x{}", size.0, size.1);
        bench_paths(c, "size/exponent-series", &series, size, &id, (true, false));
    }
    for (name, material) in model_samples() {
        let scene = covered_sphere(material).unwrap();
        bench_paths(c, "model", &scene, (320, 240), name, (true, false));
        bench_fixed(c, "model", &scene, (320, 240), name);
    }
    bench_paths(
        c,
        "frame/microfacets",
        &microfacets().unwrap(),
        (320, 160),
        "320x160",
        (true, false),
    );
    bench_fixed(
        c,
        "frame/microfacets",
        &microfacets().unwrap(),
        (320, 160),
        "320x160",
    );
    let (w, h) = MATRIX_SIZE;
    let id = format!("{w}x{h}");
    for (name, scene) in matrix() {
        let group = format!("frame/matrix/{name}");
        bench_paths(c, &group, &scene, MATRIX_SIZE, &id, (true, false));
        bench_fixed(c, &group, &scene, MATRIX_SIZE, &id);
    }
    for (id, radius) in [("sphere-light", AREA_LIGHT_RADIUS), ("point-light", 0.0)] {
        bench_paths(
            c,
            "frame/area-lights",
            &area_lights(radius).unwrap(),
            AREA_LIGHTS_SIZE,
            id,
            (true, false),
        );
        bench_fixed(
            c,
            "frame/area-lights",
            &area_lights(radius).unwrap(),
            AREA_LIGHTS_SIZE,
            id,
        );
    }
}

criterion_group! {
    name = render_benches;
    config = Criterion::default()
        .sample_size(20)
        .warm_up_time(Duration::from_millis(300))
        .measurement_time(Duration::from_secs(1));
    targets = benches
}
criterion_main!(render_benches);
