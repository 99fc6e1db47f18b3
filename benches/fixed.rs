//! Criterion benchmarks of the fixed-point path against the float paths, single thread,
//! reported as Mpix/s: the exponent series at 320×240 and 1024×747, on `fixed`, `scalar`
//! (f32, one pixel at a time) and `simd8` (f32x8), each with its scanline spans on.
//!
//! On a host the fixed path pays for 64-bit products and has no SIMD; what it buys is
//! integer-only rows for cores without an FPU, and frames that are the same bits everywhere.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use shadeline::*;
use std::hint::black_box;
use std::time::Duration;

fn render<R: Render>(r: &R, buf: &mut [Rgb565]) {
    r.render_frame(buf).unwrap();
    black_box(&buf[0]);
}

fn benches(c: &mut Criterion) {
    let series = exponent_series().unwrap();
    for (w, h) in [(320, 240), (1024, 747)] {
        let id = format!("{w}x{h}");
        let mut g = c.benchmark_group("fixed-vs-float/exponent-series");
        g.throughput(Throughput::Elements(w as u64 * h as u64));
        let mut buf = vec![Rgb565::default(); w as usize * h as usize];
        let fixed = PreparedFixed::new(&series, w, h).unwrap();
        g.bench_function(BenchmarkId::new("fixed", &id), |b| {
            b.iter(|| render(&fixed, &mut buf))
        });
        let scalar = Prepared::<Scalar>::new(&series, w, h).unwrap();
        g.bench_function(BenchmarkId::new("scalar", &id), |b| {
            b.iter(|| render(&scalar, &mut buf))
        });
        let simd8 = Prepared::<Simd8>::new(&series, w, h).unwrap();
        g.bench_function(BenchmarkId::new("simd8", &id), |b| {
            b.iter(|| render(&simd8, &mut buf))
        });
        g.finish();
    }
}

criterion_group! {
    name = fixed_benches;
    config = Criterion::default()
        .sample_size(20)
        .warm_up_time(Duration::from_millis(300))
        .measurement_time(Duration::from_secs(2));
    targets = benches
}
criterion_main!(fixed_benches);
