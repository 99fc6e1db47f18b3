//! The BRDF laws, for every model: on the brdf module's own formulas evaluated in `f64`
//! ([`brdf::value`] over `f64`: the same code the float kernel runs on its lanes), and on
//! what the f32 kernel and the fixed kernel actually put in a pixel.
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
//! - classic Phong breaks energy conservation: the largest albedo found is reported;
//! - the lower side of energy conservation: at normal view (`V = N`) a normalized lobe
//!   reflects exactly its weight, so Lambert and the normalized models without Fresnel
//!   reflect `kd·albedo + Σ w` (checked by quadrature to `1e-6`, and by Monte Carlo within
//!   four standard errors); a normalization half what it should be fails here, while it
//!   passes every law above;
//! - the kernels: a 1×1 frame whose one ray meets a sphere at a chosen normal and view,
//!   lit by one distant light, holds `f(L, V)·cos θ_i` in its pixel. On the scalar f32 path
//!   (the SIMD paths give its bits) and the fixed path: positivity, reciprocity (within
//!   0.2 % plus three 16.16 steps), albedo at most 1 from every view, and at normal view
//!   the albedo above.
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
/// mean and standard error), from the brdf module's `f64` formulas.
fn albedo(m: &Material, view: D, seed: u64) -> (f64, f64) {
    let p = Params::<f64>::of(m);
    let reflected = |l: D| {
        let f = brdf::value(&p, N, l, view);
        let c = dot(N, l);
        [f.x * c, f.y * c, f.z * c]
    };
    albedo_of(m, view, SAMPLES, seed, reflected)
}

/// The directional albedo `∫ f cos θ_i dω_i` of `m` seen from `view`, by Monte Carlo over
/// `samples` light directions, where `reflected(L)` is what the surface sends toward `view`
/// per unit of light arriving from `L`: `f(L, V)·cos θ_i`, per channel. Returns the largest
/// channel's mean and standard error.
fn albedo_of(
    m: &Material,
    view: D,
    samples: usize,
    seed: u64,
    mut reflected: impl FnMut(D) -> [f64; 3],
) -> (f64, f64) {
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
    for i in 0..samples {
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
        let r = reflected(l);
        let w = 1.0 / pdf(l);
        for (c, rc) in r.into_iter().enumerate() {
            let x = rc * w;
            sum[c] += x;
            sum2[c] += x * x;
        }
    }
    let m = samples as f64;
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

// ---------------------------------------------------------------------------------------------
// The lower side of energy conservation: at normal view a normalized lobe reflects exactly
// its weight, so a normalization that is too small (half of what it should be, say) fails
// here, where the upper bound above cannot see it.

/// Gauss–Legendre nodes and weights, five points on `[−1, 1]`.
const GAUSS: [(f64, f64); 5] = [
    (0.0, 0.568_888_888_888_888_9),
    (-0.538_469_310_105_683_1, 0.478_628_670_499_366_5),
    (0.538_469_310_105_683_1, 0.478_628_670_499_366_5),
    (-0.906_179_845_938_664, 0.236_926_885_056_189_1),
    (0.906_179_845_938_664, 0.236_926_885_056_189_1),
];

/// The directional albedo at normal view (`V = N`) by quadrature, per channel. At `V = N`
/// every model depends on `θ_i` alone (`R·V = cos θ_i`, `N·H = cos(θ_i/2)`, `L·H` likewise),
/// so `∫ f cos θ_i dω_i = 2π ∫₀¹ f(u)·u du` with `u = cos θ_i`. Integrated in `s = 1 − u`,
/// where the lobes concentrate, on panels `[0, 10⁻¹²]` and then 20 per decade up to 1, five
/// Gauss points each: far below `10⁻⁶` of error up to `n = 10⁴`.
fn albedo_at_normal_view(p: &Params<f64>) -> [f64; 3] {
    let mut edges = vec![0.0];
    edges.extend((0..=240).map(|k| 10f64.powf(-12.0 + k as f64 / 20.0)));
    let mut sum = [0.0f64; 3];
    for panel in edges.windows(2) {
        let (a, b) = (panel[0], panel[1]);
        for (x, w) in GAUSS {
            let u = 1.0 - (0.5 * (a + b) + 0.5 * (b - a) * x);
            let l = v((1.0 - u * u).max(0.0).sqrt(), 0.0, u);
            let f = brdf::value(p, N, l, N);
            for (s, fc) in sum.iter_mut().zip([f.x, f.y, f.z]) {
                *s += 0.5 * (b - a) * w * fc * u;
            }
        }
    }
    sum.map(|s| 2.0 * std::f64::consts::PI * s)
}

/// The albedo at normal view where it is known in closed form: `kd·max(albedo) + Σ w` for
/// Lambert and the normalized models without Fresnel (each normalized lobe reflects exactly
/// its weight at `V = N`). `None` with an `ior` or a metal, whose Schlick factor leaves only
/// the quadrature.
fn analytic_albedo_at_normal_view(m: &Material) -> Option<f64> {
    let a = m.albedo;
    let diffuse = (m.kd * a.r.max(a.g).max(a.b)) as f64;
    match m.model {
        Model::Lambert => Some(diffuse),
        Model::NormalizedPhong(spec) | Model::NormalizedBlinnPhong(spec) => match spec.surface {
            Surface::Dielectric { ior: None } => Some(
                diffuse
                    + m.ks as f64
                    + spec.more_lobes.iter().map(|l| l.weight as f64).sum::<f64>(),
            ),
            _ => None,
        },
        _ => None,
    }
}

/// What the albedo at normal view must be: the closed form where there is one, else the
/// quadrature (the largest channel).
fn expected_albedo_at_normal_view(m: &Material) -> f64 {
    analytic_albedo_at_normal_view(m).unwrap_or_else(|| {
        albedo_at_normal_view(&Params::of(m))
            .into_iter()
            .fold(0.0, f64::max)
    })
}

#[test]
fn normalized_lobes_and_lambert_reflect_their_weights_at_normal_view() {
    let none = [Lobe::NONE; MORE_LOBES];
    let plain = Surface::Dielectric { ior: None };
    let mut worst = 0.0f64;
    for n in EXPONENTS {
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
        // (material, its albedo at normal view: kd·albedo + Σ w)
        let mut cases = vec![(white(1.0, 0.0, n, Model::Lambert), 1.0)];
        for blinn in [false, true] {
            cases.extend([
                (white(0.0, 1.0, n, normalized(blinn, plain, none)), 1.0),
                (white(0.0, 0.25, n, normalized(blinn, plain, none)), 0.25),
                (white(0.5, 0.5, n, normalized(blinn, plain, none)), 1.0),
                (white(0.3, 0.4, n, normalized(blinn, plain, lobes)), 1.0),
                (white(0.2, 0.0, n, normalized(blinn, plain, lobes)), 0.5),
            ]);
        }
        for (m, want) in cases {
            let analytic = analytic_albedo_at_normal_view(&m).unwrap();
            assert!((analytic - want).abs() < 1e-6, "{m:?}: {analytic}");
            let got = albedo_at_normal_view(&Params::of(&m));
            for a in got {
                worst = worst.max((a - want).abs());
                assert!((a - want).abs() < 1e-6, "{m:?}: albedo {a}, want {want}");
            }
        }
    }
    println!("albedo at normal view: largest error {worst:.1e} (bound 1e-6)");
}

#[test]
fn blinn_phong_approximate_normalization_overshoots_at_normal_view() {
    // The module docs: the well-known (n + 8)/(8π) overshoots the exact factor by up to
    // 7.5 % near n = 10, so its albedo exceeds 1 at normal view. The quadrature sees it,
    // which is also what shows the test above would catch a wrong factor.
    let plain = Surface::Dielectric { ior: None };
    let m = white(
        0.0,
        1.0,
        10.0,
        normalized(true, plain, [Lobe::NONE; MORE_LOBES]),
    );
    let exact = Params::<f64>::of(&m);
    let approximate = Params {
        weight: [18.0 / (8.0 * std::f64::consts::PI), 0.0, 0.0],
        ..exact
    };
    let (a, e) = (
        albedo_at_normal_view(&approximate)[0],
        albedo_at_normal_view(&exact)[0],
    );
    println!("Blinn-Phong n = 10 at normal view: exact factor {e:.6}, (n + 8)/(8π) {a:.6}");
    assert!(a > 1.07 && a < 1.08, "{a}");
    let halved = Params {
        weight: exact.weight.map(|w| w / 2.0),
        ..exact
    };
    assert!((albedo_at_normal_view(&halved)[0] - 0.5).abs() < 1e-6);
}

#[test]
fn monte_carlo_albedo_at_normal_view_is_the_expected_one() {
    // The estimator of the upper-bound test, from below: each material's Monte Carlo albedo
    // at V = N is, within four standard errors, 1 for kd + Σ w = 1 without Fresnel, and
    // the quadrature's value with an ior or a metal's F₀.
    let mut seed = 0x5eed_a100u64;
    let mut worst = 0.0f64;
    for n in EXPONENTS {
        for (name, m) in every_model(n) {
            seed += 1;
            let want = expected_albedo_at_normal_view(&m);
            let (mean, se) = albedo(&m, N, seed);
            worst = worst.max((mean - want).abs() / se.max(1e-12));
            assert!(
                (mean - want).abs() <= 4.0 * se + 1e-9,
                "{name} n={n}: Monte Carlo {mean} ± {se}, want {want}"
            );
        }
    }
    println!(
        "Monte Carlo at normal view: worst {worst:.2} standard errors from the expected albedo"
    );
}

// ---------------------------------------------------------------------------------------------
// The laws on the kernels' own values: what the f32 kernel (scalar path; the SIMD paths give
// its bits) and the fixed kernel put in a pixel.
//
// A 1×1 frame's one ray goes exactly along the camera's forward axis. The camera looks at
// the origin from `4·V`; a unit sphere centred at `−N` touches the origin with normal `N`; a
// distant light of colour 1 and intensity 1 shines from `L`. The pixel's linear colour is
// then `f(L, V)·cos θ_i` per channel, for every normalized model.

/// What the kernel of path `P` reflects toward `view` from a unit light arriving from `l`.
fn kernel_reflected<P: KernelPath>(m: &Material, l: D, view: D) -> [f64; 3] {
    let f32v = |d: D| Vec3::new(d.x as f32, d.y as f32, d.z as f32);
    let camera = Camera {
        position: f32v(view).scale(4.0),
        look_at: Vec3::new(0.0, 0.0, 0.0),
        up: if view.y.abs() < 0.9 {
            Vec3::new(0.0, 1.0, 0.0)
        } else {
            Vec3::new(1.0, 0.0, 0.0)
        },
        vfov_degrees: 30.0,
    };
    let mut scene: Scene = Scene::new(camera, LinearRgb::default()).unwrap();
    scene
        .add_sphere(Sphere {
            center: f32v(N).scale(-1.0),
            radius: 1.0,
            material: *m,
        })
        .unwrap();
    scene
        .add_light(Light::Distant {
            direction: -f32v(l),
            color: LinearRgb::new(1.0, 1.0, 1.0),
            intensity: 1.0,
        })
        .unwrap();
    let c = P::pixel(&scene);
    [c.r as f64, c.g as f64, c.b as f64]
}

/// A path whose kernel the tests below read.
trait KernelPath {
    const NAME: &'static str;
    /// The one pixel of a 1×1 frame of `scene`, linear.
    fn pixel(scene: &Scene) -> LinearRgb;
}

struct FloatKernel;
impl KernelPath for FloatKernel {
    const NAME: &'static str = "f32 kernel";
    fn pixel(scene: &Scene) -> LinearRgb {
        let mut px = [LinearRgb::default()];
        let frame = Prepared::<Scalar>::new(scene, 1, 1).unwrap();
        frame.render_line(0, &mut px).unwrap();
        px[0]
    }
}

struct FixedKernel;
impl KernelPath for FixedKernel {
    const NAME: &'static str = "fixed kernel";
    fn pixel(scene: &Scene) -> LinearRgb {
        let mut px = [LinearRgb::default()];
        let frame = PreparedFixed::new(scene, 1, 1).unwrap();
        frame.render_line(0, &mut px).unwrap();
        px[0]
    }
}

/// Exponents for the kernel tests: every decade of the range.
const KERNEL_EXPONENTS: [f32; 5] = [1.0, 10.0, 100.0, 1000.0, 10000.0];
const KERNEL_SAMPLES: usize = 4_000;

fn kernel_laws<P: KernelPath>() {
    // The setup reads what it should: the kernel's pixel is f·cos θ_i from brdf::value.
    let m = white(
        0.6,
        0.4,
        20.0,
        normalized(
            false,
            Surface::Dielectric { ior: None },
            [Lobe::NONE; MORE_LOBES],
        ),
    );
    let (l, o) = (
        view_at(30.0),
        v(-(20f64.to_radians().sin()), 0.0, 20f64.to_radians().cos()),
    );
    let want = brdf::value(&Params::<f64>::of(&m), N, l, o).x * dot(N, l);
    let got = kernel_reflected::<P>(&m, l, o)[0];
    assert!(
        (got - want).abs() <= 1e-3 * want,
        "{}: {got} vs {want}",
        P::NAME
    );

    // Positivity and reciprocity on random pairs of directions.
    let mut rng = Rng(0x5eed_0b03);
    let mut worst = 0.0f64;
    for n in [1.0, 10.0, 100.0, 1000.0] {
        for (name, m) in every_model(n) {
            for _ in 0..40 {
                let (l, o) = (random_direction(&mut rng), random_direction(&mut rng));
                // Away from the horizon, where the hit point's rounding tilts N·L the most.
                if dot(N, l) < 0.05 || dot(N, o) < 0.05 {
                    continue;
                }
                let a = kernel_reflected::<P>(&m, l, o);
                let b = kernel_reflected::<P>(&m, o, l);
                for (x, y) in a.iter().zip(&b) {
                    assert!(*x >= 0.0 && *y >= 0.0, "{}: {name}: {a:?} {b:?}", P::NAME);
                    // f(L, V) = f(V, L): the pixels differ by the cosines only. Allowed:
                    // 0.2 % of f, plus three steps of the fixed path's 16.16 output in each
                    // pixel (divided by its cosine).
                    let (fx, fy) = (x / dot(N, l), y / dot(N, o));
                    let steps = 3.0 / 65536.0 * (1.0 / dot(N, l) + 1.0 / dot(N, o));
                    let diff = (fx - fy).abs() / (2e-3 * fx.max(fy) + steps);
                    worst = worst.max(diff);
                    assert!(
                        diff <= 1.0,
                        "{}: {name} n={n}: f(L,V) {fx} vs f(V,L) {fy} (L={l:?} V={o:?})",
                        P::NAME
                    );
                }
            }
        }
    }
    println!(
        "{}: reciprocity: largest difference {:.0}% of the allowance",
        P::NAME,
        100.0 * worst
    );

    // Energy conservation, both sides: at most 1 from every view; at normal view 1 when
    // kd + Σ w = 1 without Fresnel (the quadrature's value with an ior or a metal).
    let mut seed = 0x5eed_c0de;
    let mut worst = 0.0f64;
    for n in KERNEL_EXPONENTS {
        for (name, m) in every_model(n) {
            let at_normal = expected_albedo_at_normal_view(&m);
            for deg in [0.0, 60.0] {
                seed += 1;
                let view = view_at(deg);
                let reflected = |l: D| kernel_reflected::<P>(&m, l, view);
                let (mean, se) = albedo_of(&m, view, KERNEL_SAMPLES, seed, reflected);
                assert!(
                    mean <= 1.0 + 4.0 * se + 1e-3,
                    "{}: {name} n={n} view {deg}°: albedo {mean} ± {se}",
                    P::NAME
                );
                if deg == 0.0 {
                    worst = worst.max((mean - at_normal).abs() / (4.0 * se + 1e-3));
                    assert!(
                        (mean - at_normal).abs() <= 4.0 * se + 1e-3,
                        "{}: {name} n={n} at normal view: albedo {mean} ± {se}, want {at_normal}",
                        P::NAME
                    );
                }
            }
        }
    }
    println!(
        "{}: albedo at normal view: largest difference from the expected albedo {:.0}% of the \
         allowance (4 standard errors + 1e-3)",
        P::NAME,
        100.0 * worst
    );
}

#[test]
fn the_f32_kernel_obeys_the_laws() {
    kernel_laws::<FloatKernel>();
}

#[test]
fn the_fixed_kernel_obeys_the_laws() {
    kernel_laws::<FixedKernel>();
}

// Oren–Nayar and GGX.
//
// The same laws for the two microfacet models, with a Monte Carlo estimator fitted to them:
// one-sample multiple importance sampling (balance heuristic) over cosine-weighted light
// directions and, for GGX, light directions mirrored about half vectors drawn from
// `D(H)·cos θ_h` (pdf `D·cos θ_h/(4 V·H)` over light directions).

/// Oren–Nayar roughnesses σ, radians: Lambert, the largest overshoot (≈ 0.2), the point
/// where `A + B/2` falls to 1 (≈ 0.33), and rough to very rough.
const OREN_NAYAR_SIGMAS: [f32; 6] = [0.0, 0.2, 0.33, 0.5, 1.0, std::f32::consts::FRAC_PI_2];
/// GGX perceptual roughnesses, from the smallest accepted to 1.
const GGX_ROUGHNESS: [f32; 6] = [0.05, 0.1, 0.25, 0.5, 0.75, 1.0];
const ROUGH_SAMPLES: usize = 200_000;

fn oren_nayar(sigma: f32) -> Material {
    white(1.0, 0.0, 1.0, Model::OrenNayar { roughness: sigma })
}

fn ggx(roughness: f32, kd: f32, ks: f32, surface: Surface) -> Material {
    white(kd, ks, 1.0, Model::Ggx(Microfacet { roughness, surface }))
}

/// One GGX material per surface at `roughness`, with `kd + ks = 1`.
fn every_ggx(roughness: f32) -> Vec<(String, Material)> {
    let plain = Surface::Dielectric { ior: None };
    let fresnel = Surface::Dielectric { ior: Some(1.5) };
    vec![
        (
            format!("ggx r={roughness} specular only"),
            ggx(roughness, 0.0, 1.0, plain),
        ),
        (
            format!("ggx r={roughness} kd 0.5 ks 0.5"),
            ggx(roughness, 0.5, 0.5, plain),
        ),
        (
            format!("ggx r={roughness} ior 1.5 kd 0.5 ks 0.5"),
            ggx(roughness, 0.5, 0.5, fresnel),
        ),
        (
            format!("ggx r={roughness} gold"),
            ggx(roughness, 0.0, 1.0, Surface::Metal(Metal::Gold)),
        ),
    ]
}

fn every_rough_model() -> Vec<(String, Material)> {
    let mut out: Vec<(String, Material)> = OREN_NAYAR_SIGMAS
        .iter()
        .map(|&s| (format!("oren-nayar σ={s}"), oren_nayar(s)))
        .collect();
    for r in GGX_ROUGHNESS {
        out.extend(every_ggx(r));
    }
    out
}

/// The GGX distribution `D(H)` of width `α` at `cos θ_h`, written here from its textbook form
/// `α²/(π cos⁴θ_h (α² + tan²θ_h)²)` for the sampler's pdf.
fn ggx_d(alpha: f64, cos_h: f64) -> f64 {
    if cos_h <= 0.0 {
        return 0.0;
    }
    let a2 = alpha * alpha;
    let c2 = cos_h * cos_h;
    let t = a2 + (1.0 - c2) / c2;
    a2 / (std::f64::consts::PI * c2 * c2 * t * t)
}

/// The directional albedo `∫ f cos θ_i dω_i` seen from `view` of a material whose
/// `reflected(L)` is `f(L, V)·cos θ_i`, by MIS over cosine sampling and (with `alpha`) GGX
/// half-vector sampling. Returns the largest channel's mean and standard error.
fn rough_albedo(
    alpha: Option<f64>,
    view: D,
    samples: usize,
    seed: u64,
    mut reflected: impl FnMut(D) -> [f64; 3],
) -> (f64, f64) {
    use std::f64::consts::PI;
    let strategies = if alpha.is_some() { 2 } else { 1 };
    let pdf = |l: D| {
        let mut sum = power_pdf(dot(N, l), 1.0);
        if let Some(a) = alpha {
            let h = unit(v(l.x + view.x, l.y + view.y, l.z + view.z));
            sum += ggx_d(a, dot(N, h)) * dot(N, h) / (4.0 * dot(view, h).abs()).max(1e-300);
        }
        sum / strategies as f64
    };
    let mut rng = Rng(seed);
    let (mut sum, mut sum2) = ([0.0f64; 3], [0.0f64; 3]);
    for i in 0..samples {
        let (u1, u2) = (rng.next(), rng.next());
        let l = match alpha {
            Some(a) if i % 2 == 1 => {
                // tan²θ_h = α²·u/(1 − u): the half vector's pdf is D·cos θ_h.
                let t2 = a * a * u1 / (1.0 - u1).max(1e-300);
                let c = 1.0 / (1.0 + t2).sqrt();
                let s = (1.0 - c * c).max(0.0).sqrt();
                let phi = 2.0 * PI * u2;
                let h = v(s * phi.cos(), s * phi.sin(), c);
                reflect(view, h)
            }
            _ => sample_power(N, 1.0, u1, u2),
        };
        if dot(N, l) <= 1e-12 {
            continue;
        }
        let r = reflected(l);
        let w = 1.0 / pdf(l);
        for (c, rc) in r.into_iter().enumerate() {
            let x = rc * w;
            sum[c] += x;
            sum2[c] += x * x;
        }
    }
    let m = samples as f64;
    (0..3)
        .map(|c| {
            let mean = sum[c] / m;
            let var = (sum2[c] / m - mean * mean).max(0.0);
            (mean, (var / m).sqrt())
        })
        .fold((0.0, 0.0), |a, b| if b.0 > a.0 { b } else { a })
}

fn alpha_of(m: &Material) -> Option<f64> {
    match m.model {
        Model::Ggx(micro) => Some((micro.roughness as f64).powi(2)),
        _ => None,
    }
}

/// The brdf module's `f64` albedo of `m` seen from `view`.
fn rough_albedo_f64(m: &Material, view: D, samples: usize, seed: u64) -> (f64, f64) {
    let p = Params::<f64>::of(m);
    rough_albedo(alpha_of(m), view, samples, seed, |l| {
        let f = brdf::value(&p, N, l, view);
        let c = dot(N, l);
        [f.x * c, f.y * c, f.z * c]
    })
}

#[test]
fn oren_nayar_and_ggx_are_positive_and_reciprocal() {
    let mut rng = Rng(0x5eed_0b11);
    let mut worst = 0.0f64;
    for (name, m) in every_rough_model() {
        let p = Params::<f64>::of(&m);
        for _ in 0..5_000 {
            let (l, o) = (random_direction(&mut rng), random_direction(&mut rng));
            let a = brdf::value(&p, N, l, o);
            let b = brdf::value(&p, N, o, l);
            for (x, y) in [(a.x, b.x), (a.y, b.y), (a.z, b.z)] {
                assert!(
                    x >= 0.0 && x.is_finite(),
                    "{name}: f = {a:?} at L={l:?} V={o:?}"
                );
                let rel = (x - y).abs() / x.abs().max(y.abs()).max(1e-300);
                worst = worst.max(rel);
                assert!(rel <= 1e-6, "{name}: {x} vs {y} (L={l:?} V={o:?})");
            }
        }
    }
    println!("oren-nayar, ggx: f >= 0; reciprocity: largest relative difference {worst:.2e}");
}

#[test]
fn oren_nayar_at_zero_roughness_is_lambert() {
    let mut rng = Rng(0x5eed_0b12);
    let on = Params::<f64>::of(&oren_nayar(0.0));
    let lambert = Params::<f64>::of(&white(1.0, 0.0, 1.0, Model::Lambert));
    for _ in 0..2_000 {
        let (l, o) = (random_direction(&mut rng), random_direction(&mut rng));
        let (a, b) = (brdf::value(&on, N, l, o), brdf::value(&lambert, N, l, o));
        assert!((a.x - b.x).abs() <= 1e-12, "{a:?} vs {b:?}");
    }
}

#[test]
fn oren_nayar_and_ggx_conserve_energy() {
    println!("| model | largest albedo over views 0°..89° | at view | std. error | bound |");
    println!("|---|---|---|---|---|");
    let mut seed = 0x5eed_e100u64;
    for (name, m) in every_rough_model() {
        // GGX: at most 1 (single scattering only loses energy). Oren–Nayar: at most
        // A + B/2, its albedo toward grazing light (see `brdf`), which is ≤ 1 from σ ≈ 0.33.
        let bound = match m.model {
            Model::OrenNayar { roughness } => {
                let (a, b) = brdf::oren_nayar_ab(roughness as f64);
                a + b / 2.0
            }
            _ => 1.0,
        };
        let mut best = (0.0, 0.0, 0.0);
        for deg in VIEW_ANGLES {
            seed += 1;
            let (mean, se) = rough_albedo_f64(&m, view_at(deg), ROUGH_SAMPLES / 4, seed);
            assert!(
                mean <= bound + 4.0 * se,
                "{name} view {deg}°: albedo {mean} ± {se} above {bound}"
            );
            if mean > best.0 {
                best = (mean, deg, se);
            }
        }
        if bound <= 1.0 {
            assert!(m.is_energy_conserving(), "{name}");
        }
        println!(
            "| {name} | {:.4} | {}° | {:.1e} | {bound:.4} |",
            best.0, best.1, best.2
        );
    }
}

#[test]
fn oren_nayar_overshoots_near_its_bound_at_grazing_light() {
    // The qualitative model's known flaw, measured: at σ = 0.2 the albedo toward grazing
    // directions exceeds 1 (the bound A + B/2 is 1.015), so such a material with kd·albedo 1
    // is not flagged energy conserving, while one with σ = 0.5 is.
    let m = oren_nayar(0.2);
    let (mean, se) = rough_albedo_f64(&m, view_at(89.0), ROUGH_SAMPLES, 0x5eed_0b13);
    println!("oren-nayar σ=0.2 at 89°: albedo {mean:.4} ± {se:.1e}");
    assert!(mean > 1.005 + 4.0 * se, "{mean} ± {se}");
    assert!(!m.is_energy_conserving());
    assert!(oren_nayar(0.5).is_energy_conserving());
}

/// Published GGX single-scattering directional albedos `E(μ, r)` with `F = 1`, height-
/// correlated Smith, `α = r²`: Blender Cycles' `table_ggx_E` (`intern/cycles/scene/
/// shader.tables`, the 32 × 32 table of Kulla and Conty's energy compensation, *Revisiting
/// Physically Based Shading at Imageworks*, SIGGRAPH 2017 course), whose grid point `(i, j)`
/// is `r = i/31`, `μ = j/31`. `E(1, 1)` is also `1 − ln 2 = 0.306853` in closed form (at
/// `α = 1`, `D = 1/π` and `G₂ = 2 cos θᵢ/(1 + cos θᵢ)` at `V = N`).
const PUBLISHED_GGX_ALBEDO: [(f32, f64, f64); 4] = [
    // (roughness, μ = cos θ_o, E)
    (16.0 / 31.0, 1.0, 0.903873),
    (16.0 / 31.0, 16.0 / 31.0, 0.847421),
    (1.0, 1.0, 0.306853),
    (1.0, 16.0 / 31.0, 0.443841),
];

#[test]
fn ggx_albedo_matches_the_published_table() {
    println!("| roughness | μ | Monte Carlo E ± std. error | published E | difference |");
    println!("|---|---|---|---|---|");
    let mut seed = 0x5eed_a1b0u64;
    for (r, mu, published) in PUBLISHED_GGX_ALBEDO {
        seed += 1;
        let m = ggx(r, 0.0, 1.0, Surface::Dielectric { ior: None });
        let view = v((1.0 - mu * mu).max(0.0).sqrt(), 0.0, mu);
        let (mean, se) = rough_albedo_f64(&m, view, 4 * ROUGH_SAMPLES, seed);
        println!(
            "| {r:.4} | {mu:.4} | {mean:.5} ± {se:.1e} | {published} | {:+.5} |",
            mean - published
        );
        // Four standard errors, plus the table's own 6-digit rounding and its Monte Carlo
        // noise (it was estimated too): 5e-4.
        assert!(
            (mean - published).abs() <= 4.0 * se + 5e-4,
            "r={r} μ={mu}: {mean} ± {se} vs published {published}"
        );
    }
}

#[test]
fn the_f32_kernel_obeys_the_laws_for_oren_nayar_and_ggx() {
    // Positivity, reciprocity and albedo ≤ its bound, on what the f32 kernel puts in a pixel.
    let mut rng = Rng(0x5eed_0b14);
    let mut seed = 0x5eed_c1de;
    let mut worst = 0.0f64;
    for (name, m) in every_rough_model() {
        for _ in 0..40 {
            let (l, o) = (random_direction(&mut rng), random_direction(&mut rng));
            if dot(N, l) < 0.05 || dot(N, o) < 0.05 {
                continue;
            }
            let a = kernel_reflected::<FloatKernel>(&m, l, o);
            let b = kernel_reflected::<FloatKernel>(&m, o, l);
            for (x, y) in a.iter().zip(&b) {
                assert!(*x >= 0.0 && *y >= 0.0, "{name}: {a:?} {b:?}");
                let (fx, fy) = (x / dot(N, l), y / dot(N, o));
                let diff = (fx - fy).abs() / (2e-3 * fx.max(fy) + 1e-6);
                worst = worst.max(diff);
                assert!(diff <= 1.0, "{name}: f(L,V) {fx} vs f(V,L) {fy}");
            }
        }
        let bound = match m.model {
            Model::OrenNayar { roughness } => {
                let (a, b) = brdf::oren_nayar_ab(roughness as f64);
                a + b / 2.0
            }
            _ => 1.0,
        };
        for deg in [0.0, 60.0] {
            seed += 1;
            let view = view_at(deg);
            let reflected = |l: D| kernel_reflected::<FloatKernel>(&m, l, view);
            let (mean, se) = rough_albedo(alpha_of(&m), view, KERNEL_SAMPLES, seed, reflected);
            assert!(
                mean <= bound + 4.0 * se + 1e-3,
                "{name} view {deg}°: kernel albedo {mean} ± {se}"
            );
        }
    }
    println!(
        "f32 kernel, oren-nayar and ggx: reciprocity: largest difference {:.0}% of the allowance",
        100.0 * worst
    );
}

// Sphere lights: the float kernel shades a lobe at the light's representative point (the
// point of the light closest to the reflected view ray) with the energy factor
// `brdf::lobe_widening`, through `brdf::terms_with`. The reflected flux, integrated over
// every view direction, must stay below the irradiance (albedo at most 1: the energy law;
// largest found 0.978), and near the exact flux of the sphere light, the mean of the point
// light's over the light's cap: from 0.75 to 1.61 times it for `n` from 10 to 1000 and
// light cones up to 30°, furthest for Blinn-Phong lobes lit at 60° (whose lobe, in the
// light's directions, is no longer round), 0.84 to 1.07 for Phong lobes.

/// The representative point's direction for a light of angular radius `asin(s)` around the
/// unit `axis`, seen along `view` from a surface of normal [`N`]: the kernel's
/// `sphere_incoming` with the light's centre at distance 1.
fn representative(axis: D, s: f64, view: D) -> D {
    let r = v(
        2.0 * view.z * N.x - view.x,
        2.0 * view.z * N.y - view.y,
        2.0 * view.z * N.z - view.z,
    );
    let along = dot(axis, r);
    let to_ray = v(
        r.x * along - axis.x,
        r.y * along - axis.y,
        r.z * along - axis.z,
    );
    let len = dot(to_ray, to_ray).sqrt();
    let k = if len > s { s / len } else { 1.0 };
    unit(v(
        axis.x + to_ray.x * k,
        axis.y + to_ray.y * k,
        axis.z + to_ray.z * k,
    ))
}

/// The specular flux `∫ spec(V)·cos θ_o dω_V` reflected from a light of spread `s` (0: the
/// point light) toward `axis`, per unit of arriving light: quadrature around the mirror
/// direction of `axis`, in the polar angle on log-spaced panels (five Gauss points each)
/// and 64 azimuths.
fn specular_flux(p: &Params<f64>, axis: D, s: f64) -> f64 {
    let masks = p.masks();
    let mirror = v(-axis.x, -axis.y, axis.z);
    let helper = if mirror.x.abs() < 0.9 {
        v(1.0, 0.0, 0.0)
    } else {
        v(0.0, 1.0, 0.0)
    };
    let b1 = unit(mirror.cross(helper));
    let b2 = mirror.cross(b1);
    let mut edges = vec![0.0];
    edges.extend((0..=60).map(|k| std::f64::consts::PI * 10f64.powf(-6.0 + k as f64 / 10.0)));
    let azimuths = 64;
    let mut flux = 0.0;
    for panel in edges.windows(2) {
        let (a, b) = (panel[0], panel[1]);
        for (x, w) in GAUSS {
            let psi = 0.5 * (a + b) + 0.5 * (b - a) * x;
            let weight = 0.5 * (b - a) * w * psi.sin();
            for j in 0..azimuths {
                let phi = 2.0 * std::f64::consts::PI * (j as f64 + 0.5) / azimuths as f64;
                let (sp, cp) = (psi.sin(), psi.cos());
                let view = v(
                    mirror.x * cp + (b1.x * phi.cos() + b2.x * phi.sin()) * sp,
                    mirror.y * cp + (b1.y * phi.cos() + b2.y * phi.sin()) * sp,
                    mirror.z * cp + (b1.z * phi.cos() + b2.z * phi.sin()) * sp,
                );
                if view.z <= 0.0 {
                    continue;
                }
                let t = if s > 0.0 {
                    let area = brdf::Area {
                        diffuse_cos: 0.0,
                        spread: s,
                    };
                    let l = representative(axis, s, view);
                    brdf::terms_with(p, &masks, brdf::Present::ALL, N, l, view, Some(area))
                } else {
                    brdf::terms(p, &masks, brdf::Present::ALL, N, axis, view)
                };
                let spec = t.specular.x.max(t.specular.y).max(t.specular.z) * p.ks;
                flux += weight * spec * view.z * 2.0 * std::f64::consts::PI / azimuths as f64;
            }
        }
    }
    flux
}

/// The exact specular flux of a sphere light of spread `s` around `axis`: the point light's
/// flux averaged over the light's cap, `6 × 12` cells of equal solid angle.
fn exact_sphere_flux(p: &Params<f64>, axis: D, s: f64) -> f64 {
    let cos_a = (1.0 - s * s).sqrt();
    let helper = if axis.x.abs() < 0.9 {
        v(1.0, 0.0, 0.0)
    } else {
        v(0.0, 1.0, 0.0)
    };
    let b1 = unit(axis.cross(helper));
    let b2 = axis.cross(b1);
    let (rings, around) = (6, 12);
    let mut sum = 0.0;
    for i in 0..rings {
        let ct = 1.0 - (i as f64 + 0.5) / rings as f64 * (1.0 - cos_a);
        let st = (1.0 - ct * ct).max(0.0).sqrt();
        for j in 0..around {
            let phi = 2.0 * std::f64::consts::PI * (j as f64 + 0.5) / around as f64;
            let l = v(
                axis.x * ct + (b1.x * phi.cos() + b2.x * phi.sin()) * st,
                axis.y * ct + (b1.y * phi.cos() + b2.y * phi.sin()) * st,
                axis.z * ct + (b1.z * phi.cos() + b2.z * phi.sin()) * st,
            );
            sum += specular_flux(p, l, 0.0);
        }
    }
    sum / (rings * around) as f64
}

#[test]
fn sphere_lights_keep_normalized_lobes_within_the_energy_law() {
    let plain = Surface::Dielectric { ior: None };
    let (mut worst_albedo, mut lowest, mut highest) = (0.0f64, f64::MAX, 0.0f64);
    for n in [10.0f32, 100.0, 1000.0] {
        for blinn in [false, true] {
            let m = white(
                0.0,
                1.0,
                n,
                normalized(blinn, plain, [Lobe::NONE; MORE_LOBES]),
            );
            let p = Params::<f64>::of(&m);
            for theta in [0.0f64, 30.0, 60.0] {
                let t = theta.to_radians();
                let axis = v(t.sin(), 0.0, t.cos());
                for s in [0.2f64, 0.5] {
                    let shaded = specular_flux(&p, axis, s);
                    let exact = exact_sphere_flux(&p, axis, s);
                    let ratio = shaded / exact;
                    println!(
                        "n {n:6} blinn {blinn:5} θ {theta:4}° sin α {s:4}: irradiance {:.4}, exact {exact:.4}, shaded {shaded:.4}, ratio {ratio:.3}",
                        t.cos()
                    );
                    // The cap lies above the horizon: the irradiance is `cos θ`.
                    worst_albedo = worst_albedo.max(shaded / t.cos());
                    lowest = lowest.min(ratio);
                    highest = highest.max(ratio);
                }
            }
        }
    }
    println!(
        "sphere lights: largest albedo {worst_albedo:.4}; shaded over exact flux from {lowest:.3} to {highest:.3}"
    );
    assert!(worst_albedo <= 1.0 + 1e-3, "albedo {worst_albedo} above 1");
    assert!(lowest > 0.72 && highest < 1.65, "{lowest} {highest}");
}
