//! The reflection models, in one place: every model as a function of the directions, written
//! once over [`Real`] and [`Vec3`] so that the float kernel evaluates it on its lanes (`f32`,
//! `f32x4`, `f32x8`) and the law tests (`tests/brdf_laws.rs`) on `f64`. The kernel's helpers
//! (`terms` and its flags) are public only for those tests and hidden from the docs.
//!
//! Notation: `N` the unit normal, `L` the unit vector toward the light (`ω_i`), `V` the unit
//! vector toward the eye (`ω_o`), `R = 2(N·L)N − L` the light mirrored about the normal,
//! `H = normalize(L + V)` the half vector, `cos θ_i = N·L`. A model is its BRDF `f(ω_i, ω_o)`;
//! a light of arriving colour `I` adds `I·f·max(0, N·L)` to the pixel.
//!
//! | model | `f(ω_i, ω_o)` | reciprocal |
//! |---|---|---|
//! | classic Phong (the lesson's) | `kd·albedo + ks·max(0, R·V)^n / cos θ_i` | no |
//! | classic Blinn-Phong | `kd·albedo + ks·max(0, N·H)^n / cos θ_i` | no |
//! | Lambert | `kd·albedo/π` | yes |
//! | normalized Phong (Lafortune–Willems) | `kd·albedo/π + Σₖ wₖ·(nₖ + 2)/(2π)·max(0, R·V)^nₖ` | yes |
//! | normalized Blinn-Phong | `kd·albedo/π + Σₖ wₖ·c(nₖ)·max(0, N·H)^nₖ`, `c(n) = (n + 2)(n + 4) / (8π(2^(−n/2) + n))` | yes |
//! | Oren–Nayar (qualitative, 1994) | `kd·albedo/π·(A + B·max(0, s)/max(N·L, N·V))`, `s = L·V − (N·L)(N·V)` | yes |
//! | GGX (Cook–Torrance) | `kd·albedo/π + ks·D(H)·V₂(L, V)·F`, `D = α²/(π((N·H)²(α² − 1) + 1)²)`, `V₂ = ½ / (N·L·√((N·V)²(1 − α²) + α²) + N·V·√((N·L)²(1 − α²) + α²))` | yes |
//!
//! The classic models are the lesson's code read as a BRDF: the lesson adds
//! `ks·I·max(0, R·V)^n` to the pixel with no `cos θ_i`, so its BRDF carries `1/cos θ_i`, which
//! is not symmetric in `ω_i` and `ω_o`; and it has no `1/π` and no normalization, so it can
//! reflect up to about π times (diffuse) or `2π/(n + 1)` times (specular) the light it gets.
//! `R·V = 2(N·L)(N·V) − L·V` and `N·H` are themselves symmetric, which is what makes the
//! normalized lobes reciprocal.
//!
//! Normalizations. Phong's `(n + 2)/(2π)` makes the directional albedo of the lobe exactly 1
//! when `V = N` and less elsewhere (part of the lobe falls below the horizon). For Blinn-Phong
//! we use the exact factor for the same condition (F. Giesen, *Derivation of Phong and
//! Blinn-Phong BRDF normalization factors*, 2009), not the well-known approximation
//! `(n + 8)/(8π)`: measured with `n` from 1 to 10 000, the approximation overshoots the exact
//! factor by up to 7.5 % (at `n ≈ 10`), so its albedo exceeds 1 at normal view; with the
//! exact one the largest albedo over every view direction is 1 (at `V = N`).
//!
//! Oren–Nayar. The qualitative model of M. Oren and S. K. Nayar (*Generalization of
//! Lambert's reflectance model*, SIGGRAPH 1994, eq. 30 without the interreflection term):
//! `f = ρ/π·(A + B·max(0, cos(φᵢ − φₒ))·sin α·tan β)`, `α = max(θᵢ, θₒ)`,
//! `β = min(θᵢ, θₒ)`, `A = 1 − σ²/(2(σ² + 0.33))`, `B = 0.45σ²/(σ² + 0.09)`, `σ` the
//! roughness in radians ([`oren_nayar_ab`]). No angle is needed:
//! `cos(φᵢ − φₒ)·sin θᵢ·sin θₒ = L·V − (N·L)(N·V) = s`, and `sin α·tan β` is
//! `sin θᵢ·sin θₒ / cos β`, so the azimuth term is `max(0, s)/max(N·L, N·V)` — rational, with
//! IEEE operations only. At `σ = 0`, `A = 1` and `B = 0`: Lambert. The kernel evaluates the
//! term times `N·L` as `A·(N·L) + B·max(0, s)·(N·L/max(N·L, N·V))`, whose ratio is at most 1,
//! so nothing overflows at grazing angles. The model is reciprocal (`s` and the `max` are
//! symmetric) but not exactly energy conserving: its directional albedo grows toward grazing
//! light up to `ρ(A + B/2)`, which exceeds `ρ` by up to 1.5 % (at `σ ≈ 0.2`, measured in
//! `tests/brdf_laws.rs`) and is below `ρ` from `σ ≈ 0.33` on. Lit from behind the viewer
//! (`L = V`), `s = sin²θ` and the reflected light is `ρ/π·(A·cos θ + B·sin²θ)`: where
//! Lambert's `cos θ` falls to 0 at the rim, this falls only to `B` (from `A` at the centre),
//! which is why the full moon looks flat ([`full_moon`](crate::full_moon)).
//!
//! GGX. The Cook–Torrance microfacet BRDF `D·G₂·F/(4(N·L)(N·V))` with the GGX
//! (Trowbridge–Reitz) distribution `D` of width `α = roughness²` (the perceptual
//! remapping of Burley 2012, glTF, three.js) and Smith's height-correlated
//! masking-shadowing `G₂ = 1/(1 + Λ(L) + Λ(V))`, `Λ(ω) = (√(1 + α²tan²θ) − 1)/2` (Heitz,
//! *Understanding the masking-shadowing function*, JCGT 2014), folded with the `4(N·L)(N·V)`
//! into `V₂` of the table. `D` is evaluated as `α²/(π(cos²θ_h·α² + sin²θ_h)²)` with
//! `sin²θ_h = |N × H|²/|H|²` from a cross product, so that no `1 − cos²` cancels at the
//! peak. The accepted roughness starts at [`MIN_GGX_ROUGHNESS`](crate::MIN_GGX_ROUGHNESS),
//! so `α² ≥ 6.25·10⁻⁶` and every quotient is finite. Fresnel, metals and the diffuse lobe
//! are the normalized models' (below); the single-scattering lobe loses energy at high
//! roughness (light scattered more than once among the facets is not counted): its albedo at
//! `F = 1` is measured against Kulla and Conty's table in `tests/brdf_laws.rs`.
//!
//! Fresnel and metals (the lesson: "never tint a dielectric's highlight; metals tint their
//! reflection with their colour"). Schlick: `F = F₀ + (1 − F₀)(1 − L·H)⁵`, with `L·H = V·H`
//! (symmetric, so reciprocity is kept, for Phong lobes too). A dielectric's `F₀` is grey,
//! `((ior − 1)/(ior + 1))²` (0.04 at `ior` 1.5): with an `ior`, each specular weight is
//! multiplied by `F` and the diffuse lobe by `1 − F`; without one, neither is (`F₀ = 1`, no
//! Schlick). A metal has no diffuse lobe and `F₀` is its colour per channel
//! ([`Metal::f0`](crate::Metal::f0)), always with Schlick. Since `F ≤ 1` and `1 − F ≤ 1`,
//! `kd·max(albedo) + Σ wₖ ≤ 1` is enough for energy conservation in every case
//! ([`Material::is_energy_conserving`](crate::Material::is_energy_conserving)).
//!
//! How the kernel uses this: the per-material constants are a [`Params`], computed once per
//! frame by [`Params::of`] (in prepare, in `f32`; normalization factors and `F₀` folded in).
//! Per light, `terms` returns the diffuse factor and the specular colour, times `cos θ_i`
//! for the normalized models; the kernel accumulates `I·terms` and multiplies by
//! `kd·albedo` and `ks` once per pixel. For the classic models `terms` computes only
//! `max(0, N·L)` and the one lobe, nothing else. [`value`] is `f` itself, from the same
//! `terms`, for the law tests. The fixed-point path mirrors
//! these formulas in integers (see `src/fixed/mod.rs`); the `f64` [`reference`](crate::reference) implements every model again,
//! independently (Oren–Nayar from the angles themselves, GGX in its `tan θ` form). A packet
//! computes the Oren–Nayar and GGX terms only when one of its lanes shows such a material
//! ([`Present`]), so frames without them run the same arithmetic as before they existed.
//!
//! The kernels hold Oren–Nayar and GGX only with the crate feature `models` (on by default).
//! Without it, [`Params`], `Masks` and `Present` have no fields for them, [`Params::of`]
//! computes no constants of them and `terms` no term, so neither the kernels nor the
//! prepares carry any of their code; a [`Scene`](crate::Scene) refuses such a sphere instead
//! ([`Problem::ModelNotBuilt`](crate::Problem::ModelNotBuilt)). The formulas themselves
//! ([`oren_nayar_ab`], [`oren_nayar`], [`ggx`]) stay public either way: they cost nothing
//! where they are not called.

use crate::real::Real;
use crate::scene::{Material, Model, Surface, MORE_LOBES};
use crate::vec3::Vec3;

/// Specular lobes per material: lobe 0 (`ks`, `shininess`) and [`MORE_LOBES`] more.
pub const LOBES: usize = 1 + MORE_LOBES;

/// The lobe's power `max(0, x)^n`, the one transcendental function the models need beyond
/// [`Real`]: the float kernel's own, identical at every lane width, for the `f32` types, and
/// `libm`'s correctly rounded `pow` for `f64`, which is what lets the law tests check
/// reciprocity to `1e-6` even at `n = 10⁴`.
pub trait Pow: Real {
    /// `max(0, x)^n` for `n > 0`, `x` clamped to at most 1.
    fn pow_clamped(x: Self, n: Self) -> Self;
}

impl Pow for f64 {
    fn pow_clamped(x: Self, n: Self) -> Self {
        if x > 0.0 {
            libm::pow(x.min(1.0), n)
        } else {
            0.0
        }
    }
}

/// The scalar types per-material constants are computed in: `f32` (prepare) and `f64`
/// (tests); `2^x` is needed only there, once per material and frame.
#[doc(hidden)]
pub trait ScalarReal: Real<Mask = bool> {
    /// `2^x`.
    fn exp2(self) -> Self;
}

impl ScalarReal for f32 {
    fn exp2(self) -> Self {
        libm::exp2f(self)
    }
}

impl ScalarReal for f64 {
    fn exp2(self) -> Self {
        libm::exp2(self)
    }
}

/// `R·V` with `R` the light's travel direction `−L` mirrored about `N`: `D − 2(N·D)N`,
/// `D = −L`. Unclamped. Symmetric in `L` and `V` in exact arithmetic
/// (`2(N·L)(N·V) − L·V`).
#[inline(always)]
pub fn phong_cosine<T: Real>(n: Vec3<T>, to_light: Vec3<T>, view: Vec3<T>) -> T {
    let travel = -to_light;
    let mirrored = travel - n * (T::splat(2.0) * n.dot(travel));
    mirrored.dot(view)
}

/// `1/|L + V|`, or 0 where `L + V` is zero.
#[inline(always)]
fn inverse_half_length<T: Real>(h: Vec3<T>) -> T {
    let zero = T::splat(0.0);
    let h2 = h.dot(h);
    T::select(zero.lt(h2), T::splat(1.0) / h2.sqrt(), zero)
}

/// Whether this build holds the half-vector lobe of the Blinn-Phong models (crate feature
/// `blinn-phong`). Without it no [`Scene`](crate::Scene) holds a Blinn-Phong material (it
/// refuses one with [`Problem::ModelNotBuilt`](crate::Problem::ModelNotBuilt)), and the
/// kernels test this constant before their per-sphere flag, so the compiler drops their
/// half-vector code.
pub(crate) const BLINN_PHONG: bool = cfg!(feature = "blinn-phong");

/// The cosine the specular lobe raises to the power `n`: `R·V` (Phong) or `N·H`
/// (Blinn-Phong, on lanes where `blinn` is set). Unclamped; the caller clamps at zero.
///
/// `n` is the unit normal, `to_light` the unit vector toward the light (`L`), `view` the unit
/// vector toward the eye (`V`). If `L + V` is zero, `N·H` is taken as 0.
#[inline(always)]
pub fn specular_cosine<T: Real>(n: Vec3<T>, to_light: Vec3<T>, view: Vec3<T>, blinn: T::Mask) -> T {
    let r_dot_v = phong_cosine(n, to_light, view);
    if !BLINN_PHONG || !T::any(blinn) {
        return r_dot_v;
    }
    let h = to_light + view;
    let inv_len = inverse_half_length(h);
    T::select(blinn, n.dot(h) * inv_len, r_dot_v)
}

/// `L·H = V·H`, the cosine Fresnel's factor depends on (0 where `L + V` is zero).
#[inline(always)]
pub fn half_angle_cosine<T: Real>(to_light: Vec3<T>, view: Vec3<T>) -> T {
    let h = to_light + view;
    to_light.dot(h) * inverse_half_length(h)
}

/// Schlick's weight `(1 − max(0, c))⁵`, by multiplications: `F = F₀ + (1 − F₀)·weight`.
#[inline(always)]
pub fn schlick_weight<T: Real>(cos_d: T) -> T {
    let one = T::splat(1.0);
    let zero = T::splat(0.0);
    // 1 − c, clamped to [0, 1]: c may round slightly outside [0, 1].
    let m = (one - cos_d).max(zero);
    let m = T::select(m.lt(one), m, one);
    let m2 = m * m;
    m2 * m2 * m
}

/// Schlick's `F₀` of a dielectric with index of refraction `ior` (against air):
/// `((ior − 1)/(ior + 1))²`.
#[inline(always)]
pub fn dielectric_f0<T: Real>(ior: T) -> T {
    let one = T::splat(1.0);
    let r = (ior - one) / (ior + one);
    r * r
}

/// Oren–Nayar's `A = 1 − σ²/(2(σ² + 0.33))` and `B = 0.45σ²/(σ² + 0.09)` for the roughness
/// `σ` in radians: `(1, 0)` at `σ = 0`, Lambert.
#[inline(always)]
pub fn oren_nayar_ab<T: Real>(sigma: T) -> (T, T) {
    let s2 = sigma * sigma;
    let a = T::splat(1.0) - T::splat(0.5) * s2 / (s2 + T::splat(0.33));
    let b = T::splat(0.45) * s2 / (s2 + T::splat(0.09));
    (a, b)
}

/// Oren–Nayar's diffuse factor times `N·L`: `A·(N·L) + B·max(0, s)·(N·L/max(N·L, N·V))`,
/// `s = L·V − (N·L)(N·V)`, with `n_dot_l` and `n_dot_v` clamped at 0 (0 where both are).
#[inline(always)]
pub fn oren_nayar<T: Real>(a: T, b: T, n_dot_l: T, n_dot_v: T, l_dot_v: T) -> T {
    let zero = T::splat(0.0);
    let s = (l_dot_v - n_dot_l * n_dot_v).max(zero);
    let t = n_dot_l.max(n_dot_v);
    let ratio = T::select(zero.lt(t), n_dot_l / t, zero);
    a * n_dot_l + b * s * ratio
}

/// The GGX lobe without Fresnel and weight, `D(H)·V₂(L, V)` (see the module docs), for
/// `alpha2 = α²`: 0 where `N·H ≤ 0` or where `N·L` and `N·V` are both 0.
#[inline(always)]
pub fn ggx<T: Real>(alpha2: T, n: Vec3<T>, to_light: Vec3<T>, view: Vec3<T>) -> T {
    let zero = T::splat(0.0);
    let one = T::splat(1.0);
    let n_dot_l = n.dot(to_light).max(zero);
    let n_dot_v = n.dot(view).max(zero);
    let h = to_light + view;
    let hh = h.dot(h);
    let n_dot_h = n.dot(h);
    let side = n.cross(h);
    // cos²θ_h·|H|²·α² + sin²θ_h·|H|², over |H|²: D's denominator without cancellation.
    let q = (n_dot_h * n_dot_h * alpha2 + side.dot(side)) / hh;
    let d = alpha2 / (T::pi() * q * q);
    let k = one - alpha2;
    let lambda_v = (n_dot_v * n_dot_v * k + alpha2).sqrt();
    let lambda_l = (n_dot_l * n_dot_l * k + alpha2).sqrt();
    let den = n_dot_l * lambda_v + n_dot_v * lambda_l;
    let vis = T::select(zero.lt(den), T::splat(0.5) / den, zero);
    T::select(T::and(zero.lt(n_dot_h), zero.lt(hh)), d * vis, zero)
}

/// Normalized Phong's factor `(n + 2)/(2π)`.
#[inline(always)]
pub fn phong_normalization<T: Real>(n: T) -> T {
    (n + T::splat(2.0)) / (T::splat(2.0) * T::pi())
}

/// Normalized Blinn-Phong's exact factor `(n + 2)(n + 4) / (8π(2^(−n/2) + n))`: the
/// directional albedo of the lobe is 1 at `V = N`, its largest value.
#[inline(always)]
pub fn blinn_phong_normalization<T: ScalarReal>(n: T) -> T {
    let num = (n + T::splat(2.0)) * (n + T::splat(4.0));
    num / (T::splat(8.0) * T::pi() * ((-n / T::splat(2.0)).exp2() + n))
}

/// A material's constants, per lane: everything `terms` needs, normalizations folded in.
///
/// Flags are numbers (1 set, 0 clear) so that a packet's lanes can hold different materials;
/// [`Params::masks`] turns them into lane masks once per packet.
///
/// The Oren–Nayar and GGX fields exist only with the feature `models`: build a `Params` with
/// [`Params::of`] (and `..` from one), not from a literal of every field, to compile either
/// way.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Params<T> {
    /// `kd·albedo` (classic), `kd·albedo/π` (normalized, Lambert), 0 (metals).
    pub kd_albedo: Vec3<T>,
    /// `ks` (classic); 1 for the normalized models, whose weights are in `weight`.
    pub ks: T,
    /// Exponent of lobe 0 (and of the classic models' one lobe).
    pub shininess: T,
    /// 1: the lobe cosine is `N·H` (Blinn-Phong); 0: `R·V` (Phong).
    pub blinn: T,
    /// 1: a normalized model (or Lambert); 0: classic.
    pub normalized: T,
    /// Normalized models: `wₖ·cₖ`, each lobe's weight times its normalization factor.
    pub weight: [T; LOBES],
    /// Exponents of lobes 1 and 2.
    pub more_shininess: [T; MORE_LOBES],
    /// `F₀` per channel: 1 (dielectric without `ior`), grey (with), the metal's colour.
    pub f0: Vec3<T>,
    /// 1: Schlick's factor applies (dielectric with `ior`, metal).
    pub schlick: T,
    /// 1: the diffuse lobe is multiplied by `1 − F` (dielectric with `ior`).
    pub diffuse_loss: T,
    /// 1: the diffuse lobe is Oren–Nayar's, with `on_a` and `on_b` (feature `models`).
    #[cfg(feature = "models")]
    pub oren_nayar: T,
    /// Oren–Nayar's `A` (1 for other models; feature `models`).
    #[cfg(feature = "models")]
    pub on_a: T,
    /// Oren–Nayar's `B` (0 for other models; feature `models`).
    #[cfg(feature = "models")]
    pub on_b: T,
    /// 1: the specular lobe is GGX, weighted by `weight[0] = ks` (feature `models`).
    #[cfg(feature = "models")]
    pub ggx: T,
    /// GGX's `α² = roughness⁴` (1 for other models; feature `models`).
    #[cfg(feature = "models")]
    pub alpha2: T,
}

#[doc(hidden)]
/// The flags of [`Params`] as lane masks.
#[derive(Clone, Copy, Debug)]
pub struct Masks<T: Real> {
    /// `N·H` lobes.
    pub blinn: T::Mask,
    /// Normalized models.
    pub normalized: T::Mask,
    /// Schlick's factor.
    pub schlick: T::Mask,
    /// Oren–Nayar diffuse.
    #[cfg(feature = "models")]
    pub oren_nayar: T::Mask,
    /// GGX specular.
    #[cfg(feature = "models")]
    pub ggx: T::Mask,
}

#[doc(hidden)]
/// Which optional parts of `terms` a packet needs: each is skipped as a whole when no lane
/// needs it, which changes no bit (a skipped part's contribution is exactly zero or one on
/// the lanes that do not need it).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Present {
    /// Some lane has a normalized model.
    pub normalized: bool,
    /// Some lane has Schlick's factor.
    pub schlick: bool,
    /// Some lane has lobe 1 or 2.
    pub more_lobes: bool,
    /// Some lane has Oren–Nayar diffuse.
    #[cfg(feature = "models")]
    pub oren_nayar: bool,
    /// Some lane has GGX specular.
    #[cfg(feature = "models")]
    pub ggx: bool,
}

impl Present {
    /// Everything: what [`value`] uses.
    pub const ALL: Present = Present {
        normalized: true,
        schlick: true,
        more_lobes: true,
        #[cfg(feature = "models")]
        oren_nayar: true,
        #[cfg(feature = "models")]
        ggx: true,
    };
}

impl<T: Real> Params<T> {
    /// Every lane holds `p`.
    #[inline(always)]
    pub fn splat(p: &Params<f32>) -> Self {
        let s = T::splat;
        Params {
            kd_albedo: Vec3::new(s(p.kd_albedo.x), s(p.kd_albedo.y), s(p.kd_albedo.z)),
            ks: s(p.ks),
            shininess: s(p.shininess),
            blinn: s(p.blinn),
            normalized: s(p.normalized),
            weight: p.weight.map(s),
            more_shininess: p.more_shininess.map(s),
            f0: Vec3::new(s(p.f0.x), s(p.f0.y), s(p.f0.z)),
            schlick: s(p.schlick),
            diffuse_loss: s(p.diffuse_loss),
            #[cfg(feature = "models")]
            oren_nayar: s(p.oren_nayar),
            #[cfg(feature = "models")]
            on_a: s(p.on_a),
            #[cfg(feature = "models")]
            on_b: s(p.on_b),
            #[cfg(feature = "models")]
            ggx: s(p.ggx),
            #[cfg(feature = "models")]
            alpha2: s(p.alpha2),
        }
    }

    /// `a` on lanes where `mask` is set, else `b`: only the normalized models' fields
    /// (`weight`, `more_shininess`, `f0`, `schlick`, `diffuse_loss`, `normalized`, and
    /// Oren–Nayar's and GGX's with the feature `models`).
    #[inline(always)]
    pub fn select_normalized(mask: T::Mask, a: &Params<T>, b: &mut Params<T>) {
        for (w, v) in b.weight.iter_mut().zip(a.weight) {
            *w = T::select(mask, v, *w);
        }
        for (w, v) in b.more_shininess.iter_mut().zip(a.more_shininess) {
            *w = T::select(mask, v, *w);
        }
        b.f0 = Vec3::select(mask, a.f0, b.f0);
        b.schlick = T::select(mask, a.schlick, b.schlick);
        b.diffuse_loss = T::select(mask, a.diffuse_loss, b.diffuse_loss);
        b.normalized = T::select(mask, a.normalized, b.normalized);
        #[cfg(feature = "models")]
        {
            b.oren_nayar = T::select(mask, a.oren_nayar, b.oren_nayar);
            b.on_a = T::select(mask, a.on_a, b.on_a);
            b.on_b = T::select(mask, a.on_b, b.on_b);
            b.ggx = T::select(mask, a.ggx, b.ggx);
            b.alpha2 = T::select(mask, a.alpha2, b.alpha2);
        }
    }

    /// The flags as lane masks.
    #[inline(always)]
    pub fn masks(&self) -> Masks<T> {
        let zero = T::splat(0.0);
        Masks {
            blinn: zero.lt(self.blinn),
            normalized: zero.lt(self.normalized),
            schlick: zero.lt(self.schlick),
            #[cfg(feature = "models")]
            oren_nayar: zero.lt(self.oren_nayar),
            #[cfg(feature = "models")]
            ggx: zero.lt(self.ggx),
        }
    }
}

impl<T: ScalarReal> Params<T> {
    /// The classic models' constants of `m` (Phong and Blinn-Phong): `kd·albedo`, `ks`, `n`
    /// and whether the lobe is Blinn-Phong's, every other term neutral. [`Self::of`] gives
    /// these for a classic material; alone, it is what the fixed path's narrow kernel needs,
    /// without the normalization factors' code.
    pub fn classic(m: &Material) -> Self {
        let s = T::splat;
        let (zero, one) = (s(0.0), s(1.0));
        let a = m.albedo;
        let kd = s(m.kd);
        let kd_albedo = Vec3::new(s(a.r) * kd, s(a.g) * kd, s(a.b) * kd);
        Params {
            kd_albedo,
            ks: s(m.ks),
            shininess: s(m.shininess),
            blinn: if m.model == Model::BlinnPhong {
                one
            } else {
                zero
            },
            normalized: zero,
            weight: [zero; LOBES],
            more_shininess: [one; MORE_LOBES],
            f0: Vec3::new(one, one, one),
            schlick: zero,
            diffuse_loss: zero,
            #[cfg(feature = "models")]
            oren_nayar: zero,
            #[cfg(feature = "models")]
            on_a: one,
            #[cfg(feature = "models")]
            on_b: zero,
            #[cfg(feature = "models")]
            ggx: zero,
            #[cfg(feature = "models")]
            alpha2: one,
        }
    }

    /// Lambert's constants under the classic formulas: `kd·albedo/π` as the diffuse
    /// weight and no specular term (`ks` 0). What the fixed path's narrow kernel needs for a
    /// Lambert sphere, which it shades as a classic one, without the normalization code.
    pub fn lambert(m: &Material) -> Self {
        let classic = Self::classic(m);
        Params {
            kd_albedo: classic.kd_albedo.scale(T::splat(1.0) / T::pi()),
            ks: T::splat(0.0),
            ..classic
        }
    }

    /// The constants of `m`: normalization factors, `F₀`, and the diffuse scale, computed
    /// once (in prepare, or in `f64` by the tests).
    ///
    /// Without the feature `models` this computes nothing for Oren–Nayar and GGX: it gives
    /// such a material the classic constants of its `kd`, `albedo`, `ks` and `shininess`. No
    /// path ever renders them, because no [`Scene`](crate::Scene) holds such a material (it
    /// refuses it with [`Problem::ModelNotBuilt`](crate::Problem::ModelNotBuilt)).
    pub fn of(m: &Material) -> Self {
        let s = T::splat;
        let (zero, one) = (s(0.0), s(1.0));
        let classic = Self::classic(m);
        let kd_albedo = classic.kd_albedo;
        let diffuse = kd_albedo.scale(one / T::pi());
        let lambert = Params {
            kd_albedo: diffuse,
            ks: one,
            normalized: one,
            ..classic
        };
        let (spec, blinn) = match m.model {
            Model::NormalizedPhong(spec) => (spec, false),
            Model::NormalizedBlinnPhong(spec) => (spec, true),
            Model::Lambert => return lambert,
            #[cfg(feature = "models")]
            Model::OrenNayar { roughness } => {
                let (on_a, on_b) = oren_nayar_ab(s(roughness));
                return Params {
                    oren_nayar: one,
                    on_a,
                    on_b,
                    ..lambert
                };
            }
            #[cfg(feature = "models")]
            Model::Ggx(micro) => {
                let r2 = s(micro.roughness) * s(micro.roughness);
                let (kd_albedo, f0, schlick, diffuse_loss) =
                    surface_constants(micro.surface, diffuse);
                return Params {
                    kd_albedo,
                    weight: [s(m.ks), zero, zero],
                    f0,
                    schlick,
                    diffuse_loss,
                    ggx: one,
                    alpha2: r2 * r2,
                    ..lambert
                };
            }
            _ => return classic,
        };
        let norm = |n: T| {
            if blinn {
                blinn_phong_normalization(n)
            } else {
                phong_normalization(n)
            }
        };
        let mut weight = [s(m.ks) * norm(s(m.shininess)), zero, zero];
        for (w, l) in weight[1..].iter_mut().zip(spec.more_lobes) {
            *w = s(l.weight) * norm(s(l.shininess));
        }
        let (kd_albedo, f0, schlick, diffuse_loss) = surface_constants(spec.surface, diffuse);
        // `ks` and `normalized` (1) are Lambert's, and so are the Oren–Nayar and GGX fields.
        Params {
            kd_albedo,
            shininess: s(m.shininess),
            blinn: if blinn { one } else { zero },
            weight,
            more_shininess: spec.more_lobes.map(|l| s(l.shininess)),
            f0,
            schlick,
            diffuse_loss,
            ..lambert
        }
    }
}

/// A surface's constants: the diffuse lobe's `kd·albedo/π` (`diffuse`, or 0 for a metal),
/// `F₀`, and the `schlick` and `diffuse_loss` flags.
fn surface_constants<T: ScalarReal>(
    surface: Surface,
    diffuse: Vec3<T>,
) -> (Vec3<T>, Vec3<T>, T, T) {
    let s = T::splat;
    let (zero, one) = (s(0.0), s(1.0));
    match surface {
        Surface::Dielectric { ior: None } => (diffuse, Vec3::new(one, one, one), zero, zero),
        Surface::Dielectric { ior: Some(ior) } => {
            let f = dielectric_f0(s(ior));
            (diffuse, Vec3::new(f, f, f), one, one)
        }
        Surface::Metal(metal) => {
            let c = metal.f0();
            let black = Vec3::new(zero, zero, zero);
            (black, Vec3::new(s(c.r), s(c.g), s(c.b)), one, zero)
        }
    }
}

#[doc(hidden)]
/// What one light adds, per unit of arriving light: the pixel gets
/// `kd_albedo ⊙ Σ I·diffuse + ks·Σ I ⊙ specular`.
#[derive(Clone, Copy, Debug)]
pub struct Terms<T> {
    /// Classic: `max(0, N·L)`. Normalized: `max(0, N·L)·(1 − F)` (dielectric with `ior`) or
    /// `max(0, N·L)`.
    pub diffuse: T,
    /// Classic: the lobe `max(0, c)^n` in every channel. Normalized:
    /// `max(0, N·L)·F·Σ wₖ·cₖ·max(0, c)^nₖ` per channel.
    pub specular: Vec3<T>,
}

#[doc(hidden)]
/// The diffuse and specular terms of one light for the material constants `p`, at every
/// lane: the models of the table in the module docs, times `cos θ_i` for the normalized
/// ones. `present` says which optional parts to compute (see [`Present`]).
#[inline(always)]
pub fn terms<T: Pow>(
    p: &Params<T>,
    masks: &Masks<T>,
    present: Present,
    n: Vec3<T>,
    to_light: Vec3<T>,
    view: Vec3<T>,
) -> Terms<T> {
    terms_with(p, masks, present, n, to_light, view, None)
}

#[doc(hidden)]
/// What a sphere light changes in [`terms_with`]: the diffuse cosine comes from the light's
/// whole sphere, and every specular lobe is widened by the light's angular radius.
#[derive(Clone, Copy, Debug)]
pub struct Area<T> {
    /// Replaces `max(0, N·L)` in the diffuse term: the sphere's irradiance over that of
    /// the point at its centre seen head-on (`cos θ` when the sphere is wholly above the
    /// horizon).
    pub diffuse_cos: T,
    /// `sin α`, `α` the light's angular radius as seen from the surface point.
    pub spread: T,
}

#[doc(hidden)]
/// The energy factor of a lobe `max(0, c)^n` shaded at a sphere light's representative
/// point: `1/(1 + α·√(πn′/2) + n′α²/2)`, `α` the light's angular radius (taken as
/// `spread = sin α`), `n′ = n` for Phong (`c = R·V`) and `n/4` for Blinn-Phong (`N·H` moves
/// half as fast as `L`).
///
/// Shading at the representative point spreads the lobe's peak over a disc of angular
/// radius `α`: approximating the lobe by the Gaussian `exp(−n′θ²/2)` (solid angle
/// `2π/n′`), the widened lobe covers `πα² + 2πα·√(π/(2n′)) + 2π/n′` (the disc, its rim
/// times the Gaussian's one-sided width, the lobe itself), and this factor is the ratio of
/// the two, so a bigger light reflects no more energy than a point of the same power
/// (Karis's sphere-light normalization, *Real Shading in Unreal Engine 4*, 2013, with the
/// widening computed for these lobes). At `α = 0` it is exactly 1.
#[inline(always)]
pub fn lobe_widening<T: Real>(n: T, spread: T, blinn: T::Mask) -> T {
    let one = T::splat(1.0);
    let n = T::select(blinn, n * T::splat(0.25), n);
    let half_pi = T::splat(core::f32::consts::FRAC_PI_2);
    one / (one + spread * (half_pi * n).sqrt() + T::splat(0.5) * n * spread * spread)
}

#[doc(hidden)]
/// The energy factor of the GGX lobe at a sphere light's representative point: Karis's
/// `(α/α′)²` with `α′ = min(1, α + sin α_L/2)` (the half vector moves half as fast as `L`),
/// from `alpha2 = α²`.
#[cfg(feature = "models")]
#[inline(always)]
pub fn ggx_widening<T: Real>(alpha2: T, spread: T) -> T {
    let one = T::splat(1.0);
    let wide = (alpha2.sqrt() + T::splat(0.5) * spread).min(one);
    alpha2 / (wide * wide)
}

/// Whether some lane of the packet weighs a specular lobe: lobe 0's weight (a normalized
/// lane's, or `ks`) is positive somewhere, or another lobe is present. Where none does
/// (Lambert is normalized with weight 0; classic with `ks` 0), the lobe is only ever
/// multiplied by 0, so `terms_with` takes it as 0 without changing a bit.
#[inline(always)]
fn lobe_weighs<T: Real>(p: &Params<T>, masks: &Masks<T>, present: Present) -> bool {
    let weight = if present.normalized {
        T::select(masks.normalized, p.weight[0], p.ks)
    } else {
        p.ks
    };
    #[cfg(feature = "models")]
    let other_lobes = present.more_lobes || present.ggx;
    #[cfg(not(feature = "models"))]
    let other_lobes = present.more_lobes;
    other_lobes || T::any(T::splat(0.0).lt(weight))
}

#[doc(hidden)]
/// [`terms`], with a sphere light's changes when `area` is given (see [`Area`]): `to_light`
/// is then the representative point's direction, every lobe carries its
/// [`lobe_widening`] (or [`ggx_widening`]) and the diffuse term takes
/// [`Area::diffuse_cos`] for `max(0, N·L)`. Without `area` this is [`terms`].
#[inline(always)]
pub fn terms_with<T: Pow>(
    p: &Params<T>,
    masks: &Masks<T>,
    present: Present,
    n: Vec3<T>,
    to_light: Vec3<T>,
    view: Vec3<T>,
    area: Option<Area<T>>,
) -> Terms<T> {
    let zero = T::splat(0.0);
    let n_dot_l = n.dot(to_light).max(zero);
    let cosine = if lobe_weighs(p, masks, present) {
        specular_cosine(n, to_light, view, masks.blinn)
    } else {
        zero
    };
    // pow_clamped is exactly 0 where the cosine is not positive, so a packet with no
    // positive lane can skip it without changing a bit.
    let positive = T::any(zero.lt(cosine));
    let lobe = if positive {
        T::pow_clamped(cosine, p.shininess)
    } else {
        zero
    };
    let (lobe, diffuse_cos) = match area {
        Some(a) => (
            lobe * lobe_widening(p.shininess, a.spread, masks.blinn),
            a.diffuse_cos,
        ),
        None => (lobe, n_dot_l),
    };
    let classic = Terms {
        diffuse: diffuse_cos,
        specular: Vec3::new(lobe, lobe, lobe),
    };
    if !present.normalized {
        return classic;
    }
    let sum = lobe_sum(
        p,
        masks,
        present,
        [n, to_light, view],
        (cosine, positive, lobe),
        area,
    );
    #[cfg(feature = "models")]
    let diffuse = if present.oren_nayar {
        let n_dot_v = n.dot(view).max(zero);
        let l_dot_v = to_light.dot(view);
        let on = oren_nayar(p.on_a, p.on_b, diffuse_cos, n_dot_v, l_dot_v);
        T::select(masks.oren_nayar, on, diffuse_cos)
    } else {
        diffuse_cos
    };
    #[cfg(not(feature = "models"))]
    let diffuse = diffuse_cos;
    let one = T::splat(1.0);
    let (f, diffuse_scale) = if present.schlick {
        let w = schlick_weight(half_angle_cosine(to_light, view));
        let w = T::select(masks.schlick, w, zero);
        let f = Vec3::new(
            p.f0.x + (one - p.f0.x) * w,
            p.f0.y + (one - p.f0.y) * w,
            p.f0.z + (one - p.f0.z) * w,
        );
        (f, one - p.diffuse_loss * f.x)
    } else {
        (p.f0, one)
    };
    let sum = sum * n_dot_l;
    Terms {
        diffuse: T::select(masks.normalized, diffuse * diffuse_scale, classic.diffuse),
        specular: Vec3::select(masks.normalized, f.scale(sum), classic.specular),
    }
}

/// The normalized models' lobes in [`terms_with`], before the factor `N·L`: lobe 0's
/// weight times `lobe` (its `max(0, c)^n`, `c` being `cosine`), plus lobes 1 and 2 where a
/// lane has them and some lane's `cosine` is positive, each widened under a sphere light;
/// with `models`, GGX's lobe from `geometry` (`[N, L, V]`) in the lanes of GGX.
#[inline(always)]
#[cfg_attr(not(feature = "models"), allow(unused_variables))]
fn lobe_sum<T: Pow>(
    p: &Params<T>,
    masks: &Masks<T>,
    present: Present,
    geometry: [Vec3<T>; 3],
    (cosine, positive, lobe): (T, bool, T),
    area: Option<Area<T>>,
) -> T {
    let mut sum = p.weight[0] * lobe;
    if present.more_lobes && positive {
        for (w, e) in p.weight[1..].iter().zip(p.more_shininess) {
            let l = T::pow_clamped(cosine, e);
            let l = match area {
                Some(a) => l * lobe_widening(e, a.spread, masks.blinn),
                None => l,
            };
            sum = sum + *w * l;
        }
    }
    #[cfg(feature = "models")]
    if present.ggx {
        let [n, to_light, view] = geometry;
        let g = ggx(p.alpha2, n, to_light, view);
        let g = match area {
            Some(a) => g * ggx_widening(p.alpha2, a.spread),
            None => g,
        };
        sum = T::select(masks.ggx, p.weight[0] * g, sum);
    }
    sum
}

/// The BRDF `f(ω_i, ω_o)` itself, per channel: `terms` with everything present, combined
/// as the kernel combines it, divided by `cos θ_i`. For directions above the surface
/// (`N·L > 0`, `N·V > 0`); elsewhere it is not defined here.
pub fn value<T: Pow>(p: &Params<T>, n: Vec3<T>, to_light: Vec3<T>, view: Vec3<T>) -> Vec3<T> {
    let t = terms(p, &p.masks(), Present::ALL, n, to_light, view);
    let cos_i = n.dot(to_light);
    let c = Vec3::new(
        p.kd_albedo.x * t.diffuse,
        p.kd_albedo.y * t.diffuse,
        p.kd_albedo.z * t.diffuse,
    ) + t.specular.scale(p.ks);
    c.scale(T::splat(1.0) / cos_i)
}
