//! The BRDF laws, for every model, on the brdf module's own formulas evaluated in `f64`
//! ([`brdf::value`] over `f64`: the same code the float kernel runs on its lanes).
//!
//! - positivity: `f ≥ 0` on random pairs of directions above the surface;
//! - reciprocity: `f(ω_i, ω_o) = f(ω_o, ω_i)` within `1e-6` relative, for the models that
//!   are reciprocal (Lambert and every normalized model, with Fresnel, metals and several
//!   lobes). The classic models are not: the lesson adds `ks·I·(R·V)^n` to the pixel with no
//!   `cos θ_i`, so their BRDF carries `1/cos θ_i`; a test shows the asymmetry;
//! - energy conservation: the directional albedo `∫ f cos θ_i dω_i` is at most 1 (within
//!   four standard errors of its Monte Carlo estimate) for every outgoing direction on a
//!   grid of polar angles, for the normalized models with `kd + Σ w = 1` (albedo 1, the
//!   worst case) and `n` from 1 to 10 000;
//! - classic Phong breaks energy conservation: the largest albedo found is reported.
//!
//! Monte Carlo: fixed seeds (SplitMix64), one-sample multiple importance sampling with the
//! balance heuristic over a cosine-weighted strategy and one strategy per specular lobe
//! (`cos^n` around the mirror direction for Phong lobes, around the normal for the half
//! vector of Blinn-Phong lobes), so the estimator stays bounded even at `n = 10⁴`. The
//! models are isotropic, so outgoing directions differ only in their polar angle.
//! Run with `-- --nocapture` for the figures.

use shadeline::brdf::{self, Params};
use shadeline::*;

type D = Vec3<f64>;

const EXPONENTS: [f32; 10] = [
    1.0, 2.0, 5.0, 10.0, 50.0, 100.0, 500.0, 1000.0, 5000.0, 10000.0,
];
/// Outgoing polar angles, in degrees.
const VIEW_ANGLES: [f64; 8] = [0.0, 15.0, 30.0, 45.0, 60.0, 75.0, 85.0, 89.0];
const SAMPLES: usize = 40_000;

struct Rng(u64);

impl Rng {
    fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    }
}

fn v(x: f64, y: f64, z: f64) -> D {
    Vec3::new(x, y, z)
}
fn dot(a: D, b: D) -> f64 {
    a.x * b.x + a.y * b.y + a.z * b.z
}
fn unit(a: D) -> D {
    let l = dot(a, a).sqrt();
    v(a.x / l, a.y / l, a.z / l)
}
const N: D = Vec3::new(0.0, 0.0, 1.0);

/// A direction around `axis` with `cos θ = u1^(1/(n+1))`: pdf `(n+1)/(2π)·cos^n θ`.
fn sample_power(axis: D, n: f64, u1: f64, u2: f64) -> D {
    let c = u1.powf(1.0 / (n + 1.0));
    let s = (1.0 - c * c).max(0.0).sqrt();
    let phi = 2.0 * std::f64::consts::PI * u2;
    let t = if axis.x.abs() < 0.9 {
        unit(v(0.0, -axis.z, axis.y))
    } else {
        unit(v(axis.z, 0.0, -axis.x))
    };
    let b = v(
        axis.y * t.z - axis.z * t.y,
        axis.z * t.x - axis.x * t.z,
        axis.x * t.y - axis.y * t.x,
    );
    let (a, bb) = (s * phi.cos(), s * phi.sin());
    v(
        a * t.x + bb * b.x + c * axis.x,
        a * t.y + bb * b.y + c * axis.y,
        a * t.z + bb * b.z + c * axis.z,
    )
}

fn power_pdf(cos: f64, n: f64) -> f64 {
    if cos > 0.0 {
        (n + 1.0) / (2.0 * std::f64::consts::PI) * cos.powf(n)
    } else {
        0.0
    }
}

fn reflect(d: D, about: D) -> D {
    let k = 2.0 * dot(d, about);
    v(k * about.x - d.x, k * about.y - d.y, k * about.z - d.z)
}

/// The directional albedo of `m` seen from `view` (per channel, the largest channel's
/// mean and standard error).
fn albedo(m: &Material, view: D, seed: u64) -> (f64, f64) {
    let p = Params::<f64>::of(m);
    let blinn = matches!(m.model, Model::BlinnPhong | Model::NormalizedBlinnPhong(_));
    let mut lobes = vec![m.shininess as f64];
    if let Some(spec) = m.model.specular() {
        lobes.extend(
            spec.more_lobes
                .iter()
                .filter(|l| l.weight > 0.0)
                .map(|l| l.shininess as f64),
        );
    }
    let strategies = 1 + lobes.len();
    let mirror = reflect(view, N);
    let pdf = |l: D| {
        let mut sum = power_pdf(dot(N, l), 1.0);
        for &n in &lobes {
            sum += if blinn {
                let h = unit(v(l.x + view.x, l.y + view.y, l.z + view.z));
                power_pdf(dot(N, h), n) / (4.0 * dot(view, h)).max(1e-300)
            } else {
                power_pdf(dot(mirror, l), n)
            };
        }
        sum / strategies as f64
    };
    let mut rng = Rng(seed);
    let (mut sum, mut sum2) = ([0.0f64; 3], [0.0f64; 3]);
    for i in 0..SAMPLES {
        let (u1, u2) = (rng.next(), rng.next());
        let k = i % strategies;
        let l = match k {
            0 => sample_power(N, 1.0, u1, u2),
            _ if blinn => reflect(view, sample_power(N, lobes[k - 1], u1, u2)),
            _ => sample_power(mirror, lobes[k - 1], u1, u2),
        };
        if dot(N, l) <= 1e-12 {
            continue;
        }
        let f = brdf::value(&p, N, l, view);
        let w = dot(N, l) / pdf(l);
        for (c, fc) in [f.x, f.y, f.z].into_iter().enumerate() {
            let x = fc * w;
            sum[c] += x;
            sum2[c] += x * x;
        }
    }
    let m = SAMPLES as f64;
    (0..3)
        .map(|c| {
            let mean = sum[c] / m;
            let var = (sum2[c] / m - mean * mean).max(0.0);
            (mean, (var / m).sqrt())
        })
        .fold((0.0, 0.0), |a, b| if b.0 > a.0 { b } else { a })
}

fn view_at(deg: f64) -> D {
    let t = deg.to_radians();
    v(t.sin(), 0.0, t.cos())
}

fn normalized(blinn: bool, surface: Surface, more: [Lobe; MORE_LOBES]) -> Model {
    let spec = Specular {
        surface,
        more_lobes: more,
    };
    if blinn {
        Model::NormalizedBlinnPhong(spec)
    } else {
        Model::NormalizedPhong(spec)
    }
}

fn white(kd: f32, ks: f32, n: f32, model: Model) -> Material {
    Material {
        albedo: LinearRgb::new(1.0, 1.0, 1.0),
        kd,
        ks,
        shininess: n,
        model,
    }
}

/// One material per model and surface, at exponent `n`, with `kd + Σ w = 1`.
fn every_model(n: f32) -> Vec<(String, Material)> {
    let none = [Lobe::NONE; MORE_LOBES];
    let plain = Surface::Dielectric { ior: None };
    let fresnel = Surface::Dielectric { ior: Some(1.5) };
    let lobes = [
        Lobe {
            weight: 0.2,
            shininess: (n / 8.0).max(1.0),
        },
        Lobe {
            weight: 0.1,
            shininess: 1.0,
        },
    ];
    let mut out = vec![("lambert".to_string(), white(1.0, 0.0, n, Model::Lambert))];
    for (blinn, name) in [
        (false, "normalized-phong"),
        (true, "normalized-blinn-phong"),
    ] {
        out.push((
            format!("{name} specular only"),
            white(0.0, 1.0, n, normalized(blinn, plain, none)),
        ));
        out.push((
            format!("{name} kd 0.5 ks 0.5"),
            white(0.5, 0.5, n, normalized(blinn, plain, none)),
        ));
        out.push((
            format!("{name} ior 1.5"),
            white(0.0, 1.0, n, normalized(blinn, fresnel, none)),
        ));
        out.push((
            format!("{name} ior 1.5 kd 0.5"),
            white(0.5, 0.5, n, normalized(blinn, fresnel, none)),
        ));
        out.push((
            format!("{name} gold"),
            white(
                0.0,
                1.0,
                n,
                normalized(blinn, Surface::Metal(Metal::Gold), none),
            ),
        ));
        out.push((
            format!("{name} 3 lobes"),
            white(0.3, 0.4, n, normalized(blinn, plain, lobes)),
        ));
    }
    out
}

fn classic(n: f32) -> Vec<(String, Material)> {
    vec![
        ("phong".to_string(), white(0.5, 0.5, n, Model::Phong)),
        (
            "blinn-phong".to_string(),
            white(0.5, 0.5, n, Model::BlinnPhong),
        ),
    ]
}

fn random_direction(rng: &mut Rng) -> D {
    // Uniform on the hemisphere above N, away from the horizon by 1e-6.
    let z = rng.next().max(1e-6);
    let r = (1.0 - z * z).sqrt();
    let phi = 2.0 * std::f64::consts::PI * rng.next();
    v(r * phi.cos(), r * phi.sin(), z)
}

#[test]
fn every_model_is_positive() {
    let mut rng = Rng(0x5eed_0b01);
    let mut checked = 0;
    for n in EXPONENTS {
        for (name, m) in every_model(n).into_iter().chain(classic(n)) {
            let p = Params::<f64>::of(&m);
            for _ in 0..2_000 {
                let (l, o) = (random_direction(&mut rng), random_direction(&mut rng));
                let f = brdf::value(&p, N, l, o);
                assert!(
                    f.x >= 0.0 && f.y >= 0.0 && f.z >= 0.0,
                    "{name} n={n}: f = {f:?} at L={l:?} V={o:?}"
                );
                checked += 1;
            }
        }
    }
    println!("positivity: {checked} direction pairs, f >= 0 everywhere");
}

#[test]
fn normalized_models_and_lambert_are_reciprocal() {
    let mut rng = Rng(0x5eed_0b02);
    let mut worst = 0.0f64;
    for n in EXPONENTS {
        for (name, m) in every_model(n) {
            let p = Params::<f64>::of(&m);
            for _ in 0..2_000 {
                let (l, o) = (random_direction(&mut rng), random_direction(&mut rng));
                let a = brdf::value(&p, N, l, o);
                let b = brdf::value(&p, N, o, l);
                for (x, y) in [(a.x, b.x), (a.y, b.y), (a.z, b.z)] {
                    let rel = (x - y).abs() / x.abs().max(y.abs()).max(1e-300);
                    worst = worst.max(rel);
                    assert!(rel <= 1e-6, "{name} n={n}: {x} vs {y} (L={l:?} V={o:?})");
                }
            }
        }
    }
    println!("reciprocity: largest relative difference {worst:.2e} (bound 1e-6)");
}

#[test]
fn classic_models_are_not_reciprocal() {
    // f = kd·albedo + ks·lobe/cos θ_i: swapping the directions swaps the 1/cos θ_i.
    let l = view_at(60.0);
    let o = v(-(50f64.to_radians().sin()), 0.0, 50f64.to_radians().cos());
    for (name, m) in classic(10.0) {
        let m = Material {
            kd: 0.0,
            ks: 1.0,
            ..m
        };
        let p = Params::<f64>::of(&m);
        let (a, b) = (brdf::value(&p, N, l, o).x, brdf::value(&p, N, o, l).x);
        println!("{name}: f(L, V) = {a:.4}, f(V, L) = {b:.4}");
        assert!((a - b).abs() > 0.1 * a.max(b), "{name}: {a} vs {b}");
    }
}

#[test]
fn normalized_models_conserve_energy_for_every_view_and_n() {
    let mut table: Vec<(String, f64, f32, f64, f64)> = Vec::new();
    let mut seed = 0x5eed_e000u64;
    for n in EXPONENTS {
        for (name, m) in every_model(n) {
            assert!(m.is_energy_conserving(), "{name}");
            for deg in VIEW_ANGLES {
                seed += 1;
                let (mean, se) = albedo(&m, view_at(deg), seed);
                assert!(
                    mean <= 1.0 + 4.0 * se,
                    "{name} n={n} view {deg}°: albedo {mean} ± {se}"
                );
                match table.iter_mut().find(|r| r.0 == name) {
                    Some(r) if r.1 >= mean => {}
                    Some(r) => *r = (name.clone(), mean, n, deg, se),
                    None => table.push((name.clone(), mean, n, deg, se)),
                }
            }
        }
    }
    println!("| model | max albedo over n in 1..=10000 and views | at n | at view | std. error |");
    println!("|---|---|---|---|---|");
    for (name, a, n, deg, se) in &table {
        println!("| {name} | {a:.5} | {n} | {deg}° | {se:.1e} |");
    }
}

#[test]
fn classic_phong_breaks_energy_conservation() {
    let mut worst = (0.0f64, 0.0f32, 0.0f32, 0.0f32, 0.0f64);
    let mut seed = 0x5eed_c000u64;
    for n in [0.5f32, 1.0, 2.0, 10.0, 100.0] {
        for (kd, ks) in [(1.0f32, 0.0f32), (0.5, 0.5), (0.0, 1.0)] {
            for deg in VIEW_ANGLES {
                seed += 1;
                let m = white(kd, ks, n, Model::Phong);
                let (mean, _) = albedo(&m, view_at(deg), seed);
                if mean > worst.0 {
                    worst = (mean, n, kd, ks, deg);
                }
            }
        }
    }
    let (a, n, kd, ks, deg) = worst;
    println!(
        "classic Phong, kd + ks = 1, albedo 1: largest directional albedo {a:.4} \
         (n = {n}, kd = {kd}, ks = {ks}, view {deg}°)"
    );
    assert!(a > 3.0, "classic Phong reflected at most {a}");
}
