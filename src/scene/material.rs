//! How a sphere's surface reflects light: the [`Material`], its reflection [`Model`], and the
//! model's options (the specular [`Lobe`]s, the [`Surface`], the [`Metal`] presets, the GGX
//! [`Microfacet`]).
//!
//! A material is `Copy` and of fixed size whatever its model, so a scene holds it inline in a
//! `heapless::Vec`. Its check refuses a model that this build's kernels leave out before it
//! reads the model's own numbers, so a scene never holds a material no kernel can shade.

use super::check::Check;
use super::error::{Item, Problem, SceneError};
#[cfg(feature = "models")]
use super::limits::{MAX_OREN_NAYAR_ROUGHNESS, MIN_GGX_ROUGHNESS};
use super::limits::{MAX_SHININESS, MAX_VALUE};
use crate::pixel::LinearRgb;

/// Which reflection model a material uses. The formulas are in [`crate::brdf`].
///
/// The two classic models are the lesson's: empirical, not normalized, not energy
/// conserving (their highlight does not dim as it widens). The others are normalized BRDFs:
/// positive, reciprocal, and energy conserving when [`Material::is_energy_conserving`].
///
/// For every model `kd`, `albedo`, `ks` and `shininess` keep their meaning: the diffuse
/// weight and colour, and the weight and exponent of the first specular lobe.
///
/// [`Model::OrenNayar`] and [`Model::Ggx`] exist in every build, but render only with the
/// crate feature `models`, and [`Model::BlinnPhong`] and [`Model::NormalizedBlinnPhong`] only
/// with `blinn-phong` (both on by default): without it, [`Scene::add_sphere`](crate::Scene::add_sphere) refuses them
/// with [`Problem::ModelNotBuilt`].
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum Model {
    /// Classic Phong: `ks·I·max(0, R·V)^n`, `R` the light's travel direction mirrored about `N`.
    Phong,
    /// Classic Blinn-Phong: `ks·I·max(0, N·H)^n` with `H = normalize(L + V)`. Feature
    /// `blinn-phong`.
    BlinnPhong,
    /// Lambert: the diffuse lobe `kd·albedo/π` alone; `ks` and `shininess` are not used.
    Lambert,
    /// Normalized (Lafortune–Willems modified) Phong:
    /// `kd·albedo/π + Σ wₖ·(nₖ + 2)/(2π)·max(0, R·V)^nₖ`.
    NormalizedPhong(Specular),
    /// Normalized Blinn-Phong: `kd·albedo/π + Σ wₖ·c(nₖ)·max(0, N·H)^nₖ` with the exact
    /// normalization `c(n) = (n + 2)(n + 4) / (8π(2^(−n/2) + n))`, which makes the lobe's
    /// directional albedo 1 at normal view (see [`crate::brdf`]). Feature `blinn-phong`.
    NormalizedBlinnPhong(Specular),
    /// Oren–Nayar rough diffuse (the qualitative model of Oren and Nayar, 1994):
    /// `kd·albedo/π·(A + B·max(0, cos(φᵢ − φₒ))·sin α·tan β)`, with `roughness` the standard
    /// deviation `σ` of the facet slopes in radians, `0 ≤ σ ≤` [`MAX_OREN_NAYAR_ROUGHNESS`](super::MAX_OREN_NAYAR_ROUGHNESS).
    /// At `σ = 0` it is Lambert. `ks` and `shininess` are not used. Feature `models`.
    OrenNayar {
        /// `σ`, radians.
        roughness: f32,
    },
    /// Cook–Torrance microfacet specular with the GGX (Trowbridge–Reitz) distribution, Smith
    /// height-correlated masking-shadowing and Schlick Fresnel, weighted by `ks`, plus a
    /// Lambert lobe `kd·albedo/π` for dielectrics (see [`Microfacet`] and [`crate::brdf`]).
    /// `shininess` is not used. Feature `models`.
    Ggx(Microfacet),
}

/// The options of the GGX model: the perceptual roughness and the surface.
///
/// ```
/// use shadeline::{Material, Metal, Microfacet, Model, Surface};
/// let brushed_gold = Material {
///     kd: 0.0,
///     ks: 1.0,
///     model: Model::Ggx(Microfacet { roughness: 0.4, surface: Surface::Metal(Metal::Gold) }),
///     ..Material::default()
/// };
/// assert!(brushed_gold.is_energy_conserving());
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Microfacet {
    /// Perceptual roughness `r`, [`MIN_GGX_ROUGHNESS`](super::MIN_GGX_ROUGHNESS) `≤ r ≤ 1`; the distribution's width
    /// is `α = r²`.
    pub roughness: f32,
    /// Dielectric (a Lambert lobe under an untinted highlight; with `ior`, Schlick Fresnel
    /// and `1 − F` on the diffuse lobe; without, `F = 1`) or metal (tinted, no diffuse lobe).
    pub surface: Surface,
}

impl Default for Model {
    /// [`Model::Phong`], the lesson's classic model.
    fn default() -> Self {
        Model::Phong
    }
}

impl Model {
    /// The specular options of a normalized Phong or Blinn-Phong model (`None` for the
    /// others).
    pub fn specular(&self) -> Option<&Specular> {
        match self {
            Model::NormalizedPhong(s) | Model::NormalizedBlinnPhong(s) => Some(s),
            _ => None,
        }
    }

    /// Whether this is one of the lesson's two classic, unnormalized models.
    pub fn is_classic(&self) -> bool {
        matches!(self, Model::Phong | Model::BlinnPhong)
    }

    /// The surface of a model that has one (normalized Phong and Blinn-Phong, GGX).
    pub fn surface(&self) -> Option<Surface> {
        match self {
            Model::NormalizedPhong(s) | Model::NormalizedBlinnPhong(s) => Some(s.surface),
            Model::Ggx(m) => Some(m.surface),
            _ => None,
        }
    }
}

/// Specular options of the normalized models: what the surface is made of, and the lobes
/// after the first.
///
/// ```
/// use shadeline::{Material, Metal, Model, Specular, Surface, Lobe};
/// let gold = Material {
///     kd: 0.0,
///     ks: 0.6,
///     shininess: 400.0,
///     model: Model::NormalizedBlinnPhong(Specular {
///         surface: Surface::Metal(Metal::Gold),
///         more_lobes: [Lobe { weight: 0.3, shininess: 40.0 }, Lobe::NONE],
///     }),
///     ..Material::default()
/// };
/// assert!(gold.is_energy_conserving());
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Specular {
    /// Dielectric (untinted highlight, optionally with Schlick Fresnel) or metal (tinted).
    pub surface: Surface,
    /// Specular lobes 1 and 2 (lobe 0 is the material's `ks` and `shininess`). A lobe of
    /// weight 0 is absent: [`Lobe::NONE`]. In a scene file all lobes are written as
    /// `lobes = [{ weight = …, shininess = … }, …]`, lobe 0 first.
    pub more_lobes: [Lobe; MORE_LOBES],
}

/// Specular lobes a material may have besides lobe 0 (`ks`, `shininess`): three in all.
pub const MORE_LOBES: usize = 2;

/// One specular lobe: its weight and its exponent.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Lobe {
    /// Weight, `≥ 0`; 0 means the lobe is absent.
    pub weight: f32,
    /// Exponent `n > 0`.
    pub shininess: f32,
}

impl Lobe {
    /// No lobe: weight 0 (exponent 1, so it is still a valid lobe).
    pub const NONE: Lobe = Lobe {
        weight: 0.0,
        shininess: 1.0,
    };
}

impl Default for Lobe {
    /// [`Lobe::NONE`]: weight 0, exponent 1 (no lobe).
    fn default() -> Self {
        Lobe::NONE
    }
}

impl Default for Specular {
    /// A dielectric without Fresnel (`Surface::Dielectric { ior: None }`: an untinted
    /// highlight of constant weight) and no lobes besides lobe 0 (both `more_lobes` are
    /// [`Lobe::NONE`]).
    ///
    /// ```
    /// use shadeline::{Lobe, Specular, Surface};
    /// let s = Specular::default();
    /// assert_eq!(s.surface, Surface::Dielectric { ior: None });
    /// assert_eq!(s.more_lobes, [Lobe::NONE; 2]);
    /// assert_eq!(Surface::default(), s.surface);
    /// ```
    fn default() -> Self {
        Specular {
            surface: Surface::default(),
            more_lobes: [Lobe::NONE; MORE_LOBES],
        }
    }
}

/// What a normalized material's surface is: it decides the highlight's colour.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Surface {
    /// An insulator (plastic, paint, wood, glass): the highlight is never tinted by the
    /// surface colour. Without `ior` the specular weights are constant; with it, they are
    /// multiplied by Schlick's Fresnel factor `F = F₀ + (1 − F₀)(1 − L·H)⁵`,
    /// `F₀ = ((ior − 1)/(ior + 1))²`, which rises toward grazing angles, and the diffuse lobe
    /// by `1 − F` (light reflected at the surface does not enter it).
    Dielectric {
        /// Index of refraction, finite and `> 1` (`1.5` for most plastics and glass).
        ior: Option<f32>,
    },
    /// A conductor: no diffuse lobe (`kd` and `albedo` are not used), and the specular lobes
    /// are tinted per channel by Schlick's factor with the metal's coloured `F₀`.
    Metal(Metal),
}

impl Default for Surface {
    /// `Surface::Dielectric { ior: None }`: an insulator without Fresnel, whose highlight is
    /// untinted and of constant weight.
    fn default() -> Self {
        Surface::Dielectric { ior: None }
    }
}

/// The metal presets, by their reflectance at normal incidence `F₀` (linear RGB).
///
/// | metal | `F₀` (linear RGB) | source |
/// |---|---|---|
/// | gold | (1.00, 0.71, 0.29) | the commonly used value (Hoffman, *Physics and Math of Shading*, SIGGRAPH 2015 course; Unreal's and Disney's tables agree within 0.01) |
/// | copper | (0.95, 0.64, 0.54) | the same tables |
/// | bronze | (0.80, 0.55, 0.32) | no standard table lists it; a ~88 % copper, ~12 % tin alloy is less red and less reflective than copper and browner than gold: we take copper's red lowered by the tin's grey (~0.6) share and a hue between copper's and gold's. An artistic value, not a measurement |
///
/// Metals use Schlick's approximation with this coloured `F₀`: the reflection is the
/// metal's colour head-on and whitens toward grazing angles.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum Metal {
    /// Gold.
    Gold,
    /// Copper.
    Copper,
    /// Bronze.
    Bronze,
}

impl Metal {
    /// Every preset, in the order of the table above.
    pub const ALL: [Metal; 3] = [Metal::Gold, Metal::Copper, Metal::Bronze];

    /// Reflectance at normal incidence, linear RGB, each channel in `[0, 1]`.
    pub fn f0(self) -> LinearRgb {
        match self {
            Metal::Gold => LinearRgb::new(1.00, 0.71, 0.29),
            Metal::Copper => LinearRgb::new(0.95, 0.64, 0.54),
            Metal::Bronze => LinearRgb::new(0.80, 0.55, 0.32),
        }
    }

    /// The name used in scene files: `"gold"`, `"copper"`, `"bronze"`.
    pub fn name(self) -> &'static str {
        match self {
            Metal::Gold => "gold",
            Metal::Copper => "copper",
            Metal::Bronze => "bronze",
        }
    }

    /// The preset called `name` (as in [`Metal::name`]), if there is one.
    pub fn from_name(name: &str) -> Option<Metal> {
        Metal::ALL.into_iter().find(|m| m.name() == name)
    }
}

/// How a sphere's surface reflects light.
///
/// `Material` is `Copy` and fixed-size whatever the model: up to three specular lobes (lobe
/// 0 here, lobes 1 and 2 in [`Specular::more_lobes`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Material {
    /// Diffuse colour, linear RGB, each component `≥ 0`.
    pub albedo: LinearRgb,
    /// Weight of the diffuse term, `≥ 0`.
    pub kd: f32,
    /// Weight of the (first) specular lobe, `≥ 0`. A dielectric's highlight is never tinted
    /// by `albedo`.
    pub ks: f32,
    /// Specular exponent `n > 0` of the first lobe: larger is a smaller, tighter highlight.
    pub shininess: f32,
    /// The reflection model.
    pub model: Model,
}

/// The field names of lobes 1 and 2, as a scene file spells them.
const LOBE_FIELDS: [(&str, &str); MORE_LOBES] = [
    ("lobes[1].weight", "lobes[1].shininess"),
    ("lobes[2].weight", "lobes[2].shininess"),
];

impl Material {
    pub(super) fn check(&self, item: Item) -> Result<(), SceneError> {
        let c = Check { item };
        c.color("albedo", self.albedo)?;
        c.non_negative("kd", &[self.kd], MAX_VALUE)?;
        c.non_negative("ks", &[self.ks], MAX_VALUE)?;
        c.positive("shininess", self.shininess, MAX_SHININESS)?;
        // A model the build leaves out, refused before its own numbers are read.
        let left_out = (!cfg!(feature = "blinn-phong")
            && matches!(
                self.model,
                Model::BlinnPhong | Model::NormalizedBlinnPhong(_)
            ))
            || (!cfg!(feature = "models")
                && matches!(self.model, Model::OrenNayar { .. } | Model::Ggx(_)));
        if left_out {
            return Err(c.err("model", Problem::ModelNotBuilt));
        }
        if let Some(spec) = self.model.specular() {
            for (lobe, (weight, shininess)) in spec.more_lobes.iter().zip(LOBE_FIELDS) {
                c.non_negative(weight, &[lobe.weight], MAX_VALUE)?;
                c.positive(shininess, lobe.shininess, MAX_SHININESS)?;
            }
        }
        match self.model {
            #[cfg(feature = "models")]
            Model::OrenNayar { roughness } => {
                c.non_negative("roughness", &[roughness], MAX_OREN_NAYAR_ROUGHNESS)?;
            }
            #[cfg(feature = "models")]
            Model::Ggx(m) => {
                c.finite("roughness", &[m.roughness])?;
                if m.roughness < MIN_GGX_ROUGHNESS {
                    return Err(c.err("roughness", Problem::TooSmall));
                }
                if m.roughness > 1.0 {
                    return Err(c.err("roughness", Problem::TooLarge));
                }
            }
            _ => {}
        }
        if let Some(Surface::Dielectric { ior: Some(ior) }) = self.model.surface() {
            c.finite("ior", &[ior])?;
            if ior <= 1.0 {
                return Err(c.err("ior", Problem::NotAboveOne));
            }
            if ior > MAX_VALUE {
                return Err(c.err("ior", Problem::TooLarge));
            }
        }
        Ok(())
    }

    /// Whether this material cannot reflect more light than it receives, by construction:
    /// a normalized model (or Lambert, or GGX) whose diffuse weight times its brightest albedo
    /// channel plus the sum of its specular weights is at most 1 (for a metal, which has no
    /// diffuse lobe, the specular weights alone). For Oren–Nayar, the diffuse weight times
    /// the brightest albedo channel times the model's largest directional albedo `A + B/2`
    /// (reached at grazing light; it exceeds 1 by up to 1.5 % near `σ = 0.2`, see
    /// [`crate::brdf`]) is at most 1. The classic models never are: they are
    /// not normalized (see `tests/brdf_laws.rs` for by how much they can exceed 1).
    ///
    /// Materials that are not energy conserving are still accepted: this is a flag, not a
    /// validation rule.
    ///
    /// ```
    /// use shadeline::{Material, Model, Specular};
    /// let m = Material { kd: 0.7, ks: 0.3, model: Model::NormalizedPhong(Specular::default()),
    ///                    ..Material::default() };
    /// assert!(m.is_energy_conserving());
    /// assert!(!Material { ks: 0.9, ..m }.is_energy_conserving());
    /// assert!(!Material::default().is_energy_conserving()); // classic Phong
    /// ```
    pub fn is_energy_conserving(&self) -> bool {
        let a = self.albedo;
        let diffuse = self.kd * a.r.max(a.g).max(a.b);
        match self.model {
            Model::Phong | Model::BlinnPhong => false,
            Model::Lambert => diffuse <= 1.0,
            Model::NormalizedPhong(spec) | Model::NormalizedBlinnPhong(spec) => {
                let specular = self.ks + spec.more_lobes.iter().map(|l| l.weight).sum::<f32>();
                match spec.surface {
                    Surface::Metal(_) => specular <= 1.0,
                    Surface::Dielectric { .. } => diffuse + specular <= 1.0,
                }
            }
            Model::OrenNayar { roughness } => {
                // Oren–Nayar's `A` and `B` (the kernels' `brdf::oren_nayar_ab`, which this
                // module, below `brdf`, does not call).
                let s2 = roughness * roughness;
                let a = 1.0 - 0.5 * s2 / (s2 + 0.33);
                let b = 0.45 * s2 / (s2 + 0.09);
                diffuse * (a + b / 2.0) <= 1.0
            }
            Model::Ggx(m) => match m.surface {
                Surface::Metal(_) => self.ks <= 1.0,
                Surface::Dielectric { .. } => diffuse + self.ks <= 1.0,
            },
        }
    }
}

impl Default for Material {
    /// A mid-grey plastic: albedo 0.18, `kd` 0.8, `ks` 0.2, `n` 50, classic Phong.
    fn default() -> Self {
        Material {
            albedo: LinearRgb::new(0.18, 0.18, 0.18),
            kd: 0.8,
            ks: 0.2,
            shininess: 50.0,
            model: Model::Phong,
        }
    }
}
