//! The fixed-point path against the f64 reference: the acceptance budget, per scene and, on
//! the exponent series, per shininess `n`.
//!
//! Budget (pixels whose hit record — sphere hit, lights blocked — agrees with the
//! reference's): at most 2 levels per 8-bit channel, at least 99% within 1 level; pixels whose
//! hit record differs: at most 0.1% of a frame, and on the exponent series and the point-light
//! scene at most 0.1% of
//! each sphere's own pixels (those the reference sees on it), so a small sphere cannot hide
//! its errors in a large frame. Run with `-- --nocapture` to see the tables.

use crate::common;
use common::*;
use shadeline::reference::{self, RefPixel};
use shadeline::*;

const MAX_LEVELS: u16 = 2;
const MIN_WITHIN_ONE: f64 = 0.99;
const MAX_DIFFER: f64 = 0.001;

/// Colour error statistics of one group of pixels.
#[derive(Default, Clone, Copy)]
struct Stats {
    pixels: usize,
    differ: usize,
    max_levels: u16,
    within_one: usize,
    exact: usize,
}

impl Stats {
    fn add(&mut self, got: Rgb888, hit: HitRecord, want: &RefPixel) {
        self.pixels += 1;
        if hit != want.hit {
            self.differ += 1;
            return;
        }
        let levels = [got.r, got.g, got.b]
            .iter()
            .zip(want.color)
            .map(|(&g, w)| (g as i32 - reference::quantize(w, 255.0) as i32).unsigned_abs() as u16)
            .max()
            .unwrap_or(0);
        self.max_levels = self.max_levels.max(levels);
        self.within_one += (levels <= 1) as usize;
        self.exact += (levels == 0) as usize;
    }
    fn within_one_share(&self) -> f64 {
        self.within_one as f64 / (self.pixels - self.differ).max(1) as f64
    }
    fn differ_share(&self) -> f64 {
        self.differ as f64 / self.pixels.max(1) as f64
    }
    fn row(&self, label: &str) -> String {
        format!(
            "| {label} | {} | {} | {:.3}% | {:.2}% | {} ({:.4}%) |",
            self.pixels,
            self.max_levels,
            100.0 * self.within_one_share(),
            100.0 * self.exact as f64 / (self.pixels - self.differ).max(1) as f64,
            self.differ,
            100.0 * self.differ_share()
        )
    }
    /// The budget, for a whole frame or for one sphere's pixels: differing decisions are a
    /// share of this group's pixels.
    fn check(&self, label: &str) {
        assert!(
            self.max_levels <= MAX_LEVELS,
            "{label}: {} levels",
            self.max_levels
        );
        assert!(
            self.within_one_share() >= MIN_WITHIN_ONE,
            "{label}: {:.4} within one level",
            self.within_one_share()
        );
        assert!(
            self.differ as f64 <= MAX_DIFFER * self.pixels as f64,
            "{label}: {} of {} decisions differ",
            self.differ,
            self.pixels
        );
    }
}

/// Whole-frame statistics, and the same split by the sphere the reference hit.
fn measure<const S: usize, const L: usize>(
    scene: &Scene<S, L>,
    w: u32,
    h: u32,
) -> (Stats, Vec<Stats>) {
    let fixed = PreparedFixed::<S, L>::new(scene, w, h).expect("fits the fixed formats");
    let reference = reference_frame(scene, w, h);
    let colors: Vec<Rgb888> = frame(&fixed);
    let hits: Vec<HitRecord> = frame(&fixed);
    let mut all = Stats::default();
    let mut per_sphere = vec![Stats::default(); scene.spheres().len()];
    for ((c, hit), want) in colors.iter().zip(&hits).zip(&reference) {
        all.add(*c, *hit, want);
        if let Some(s) = want.hit.sphere.and_then(|k| per_sphere.get_mut(k as usize)) {
            s.add(*c, *hit, want);
        }
    }
    (all, per_sphere)
}

const HEADER: &str = "| scene | pixels | max levels | within 1 level | exact | hit/shadow decisions differ |\n|---|---|---|---|---|---|";

#[test]
fn exponent_series_within_budget_per_size_and_per_n() {
    let scene = exponent_series().unwrap();
    let (w, h) = EXPONENT_SERIES_SIZE;
    for (w, h) in [(w, h), (320, 240)] {
        let (all, per_sphere) = measure(&scene, w, h);
        println!("\nexponent series {w}x{h}\n{HEADER}");
        println!("{}", all.row("whole frame"));
        for (s, sphere) in per_sphere.iter().zip(scene.spheres()) {
            let label = format!("n = {}", sphere.material.shininess);
            println!("{}", s.row(&label));
            s.check(&format!("{w}x{h} {label}"));
        }
        all.check(&format!("exponent series {w}x{h}"));
    }
}

#[test]
fn point_lights_and_blinn_phong_within_budget() {
    let scene = point_lights_blinn_phong().unwrap();
    let (all, per_sphere) = measure(&scene, 400, 300);
    println!("\npoint lights, Blinn-Phong 400x300\n{HEADER}");
    println!("{}", all.row("whole frame"));
    for (s, sphere) in per_sphere.iter().zip(scene.spheres()) {
        let label = format!(
            "{:?} n = {}",
            sphere.material.model, sphere.material.shininess
        );
        println!("{}", s.row(&label));
        s.check(&label);
    }
    all.check("point lights, Blinn-Phong");
}

#[test]
fn random_scenes_within_budget() {
    let (w, h) = (240, 180);
    println!("\n64 random scenes at {w}x{h}\n{HEADER}");
    let mut total = Stats::default();
    for (i, scene) in random_scenes(64, 0x5eed_f1ed).iter().enumerate() {
        let (all, _) = measure(scene, w, h);
        println!("{}", all.row(&format!("random {i}")));
        all.check(&format!("random scene {i}"));
        total.pixels += all.pixels;
        total.differ += all.differ;
        total.within_one += all.within_one;
        total.exact += all.exact;
        total.max_levels = total.max_levels.max(all.max_levels);
    }
    println!("{}", total.row("all 64"));
}
