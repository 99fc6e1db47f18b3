//! The scene file: TOML text → a validated [`FileScene`] and an image size, or one error that
//! names the line, the column and the key.
//!
//! The format is the one of `scenes/exponent-series.toml`:
//!
//! | table | keys |
//! |---|---|
//! | `[image]` | `width`, `height` (pixels), `background` = `[r, g, b]` linear, optional `antialias = true` (analytic edges, every path) |
//! | `[camera]` | `position`, `look_at`, `up` = `[x, y, z]`, `vfov` (degrees) |
//! | `[[light]]` | `type = "distant"` with `direction`, or `type = "point"` with `position` and optionally `radius` (0: a point; more: a sphere light); both with `color`, `intensity` |
//! | `[[sphere]]` | `center`, `radius`, `albedo`, `kd`, `ks`, `shininess`, optional `model` (below) |
//!
//! Materials (`scenes/materials.toml` shows each):
//!
//! | key | values | notes |
//! |---|---|---|
//! | `model` | `"phong"` (default), `"blinn-phong"`, `"lambert"`, `"normalized-phong"`, `"normalized-blinn-phong"`, `"oren-nayar"`, `"ggx"` | `lambert` and `oren-nayar` need no `ks`/`shininess`, `ggx` no `shininess` |
//! | `roughness` | `oren-nayar`: `σ` in radians, `0` (Lambert) to `π/2`; `ggx`: perceptual roughness `0.05` to `1` (`α = roughness²`) | required by those two models, refused by the others |
//! | `metal` | `"gold"`, `"copper"`, `"bronze"` | normalized Phong and Blinn-Phong, and `ggx`; a metal has no diffuse lobe, so no `albedo`/`kd`, and no `ior` |
//! | `ior` | a number `> 1` | dielectrics of those models: Schlick Fresnel |
//! | `lobes` | `[{ weight = 0.5, shininess = 20.0 }, …]`, 1 to 3 | normalized models only; replaces `ks` and `shininess` (`lobes[0]`) |
//!
//! Parsing has three stages, each of which reports through [`SceneFileError`]: the TOML syntax
//! and a key index ([`KeyIndex`]); the typed structs (serde, unknown keys refused); and the
//! core's own validation ([`Scene::new`], `add_sphere`, `add_light`, [`Prepared::new`] for the
//! size), whose errors are placed at the key they name.

use crate::toml_keys::KeyIndex;
use serde::Deserialize;
use shadeline::{
    Camera, Item, ItemKind, Light, LinearRgb, Lobe, Material, Metal, Microfacet, Model, Prepared,
    RenderError, Scalar, Scene, SceneError, Specular, Sphere, Surface, Vec3, MAX_DIMENSION,
    MORE_LOBES,
};
use std::fmt;
use std::ops::Range;

/// Most spheres a scene file may hold.
pub const MAX_SPHERES: usize = 64;
/// Most lights a scene file may hold.
pub const MAX_LIGHTS: usize = 16;

/// The scene type the harness reads files into and renders.
pub type FileScene = Scene<MAX_SPHERES, MAX_LIGHTS>;

/// A parsed, validated scene file.
#[derive(Clone, Debug)]
pub struct SceneFile {
    /// The scene.
    pub scene: FileScene,
    /// `image.width`, in pixels.
    pub width: u32,
    /// `image.height`, in pixels.
    pub height: u32,
    /// `image.antialias`: whether silhouettes are anti-aliased (false when absent).
    pub antialias: bool,
}

/// Why a scene file was refused: where (1-based line and column, in characters), which key,
/// and what is wrong.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SceneFileError {
    /// 1-based line.
    pub line: usize,
    /// 1-based column, counted in characters.
    pub column: usize,
    /// The dotted key path the error is about (`sphere[2].radius`), if it is about one.
    pub key: Option<String>,
    /// What is wrong, as one sentence without a trailing period.
    pub message: String,
}

impl SceneFileError {
    /// An error at byte `offset` of `text`.
    pub fn at(text: &str, offset: usize, key: Option<String>, message: String) -> Self {
        let (line, column) = line_column(text, offset);
        SceneFileError {
            line,
            column,
            key,
            message,
        }
    }
}

impl fmt::Display for SceneFileError {
    /// `LINE:COL: error: MESSAGE (key `KEY`)`, without the key when the message already names
    /// it as `` `KEY` ``; the caller puts the file name in front.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}:{}: error: {}", self.line, self.column, self.message)?;
        if let Some(key) = &self.key {
            if !self.message.contains(&format!("`{key}`")) {
                write!(f, " (key `{key}`)")?;
            }
        }
        Ok(())
    }
}

impl std::error::Error for SceneFileError {}

/// The 1-based line and character column of byte `offset` (clamped to the text, and moved
/// back to a character boundary).
pub fn line_column(text: &str, offset: usize) -> (usize, usize) {
    let mut offset = offset.min(text.len());
    while !text.is_char_boundary(offset) {
        offset -= 1;
    }
    let before = &text[..offset];
    let line = before.matches('\n').count() + 1;
    let line_start = before.rfind('\n').map_or(0, |i| i + 1);
    (line, before[line_start..].chars().count() + 1)
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawFile {
    image: RawImage,
    camera: RawCamera,
    #[serde(default)]
    light: Vec<RawLight>,
    #[serde(default)]
    sphere: Vec<RawSphere>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawImage {
    width: u32,
    height: u32,
    background: [f64; 3],
    #[serde(default)]
    antialias: bool,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawCamera {
    position: [f64; 3],
    look_at: [f64; 3],
    up: [f64; 3],
    vfov: f64,
}

#[derive(Deserialize, Clone, Copy, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
enum LightType {
    Distant,
    Point,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawLight {
    #[serde(rename = "type")]
    kind: LightType,
    direction: Option<[f64; 3]>,
    position: Option<[f64; 3]>,
    color: [f64; 3],
    intensity: f64,
    radius: Option<f64>,
}

#[derive(Deserialize, Clone, Copy, Default, PartialEq, Eq)]
#[serde(rename_all = "kebab-case")]
enum RawModel {
    #[default]
    Phong,
    BlinnPhong,
    Lambert,
    NormalizedPhong,
    NormalizedBlinnPhong,
    OrenNayar,
    Ggx,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawSphere {
    center: [f64; 3],
    radius: f64,
    albedo: Option<[f64; 3]>,
    kd: Option<f64>,
    ks: Option<f64>,
    shininess: Option<f64>,
    #[serde(default)]
    model: RawModel,
    metal: Option<String>,
    ior: Option<f64>,
    lobes: Option<Vec<RawLobe>>,
    roughness: Option<f64>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawLobe {
    weight: f64,
    shininess: f64,
}

/// An `f64` from the file as the core's `f32`. A finite number too large for `f32` becomes
/// `±f32::MAX` rather than infinity, so the core reports it as too large, not as not finite.
fn narrow(v: f64) -> f32 {
    if v.is_finite() {
        v.clamp(-f64::from(f32::MAX), f64::from(f32::MAX)) as f32
    } else {
        v as f32
    }
}

fn vec3([x, y, z]: [f64; 3]) -> Vec3 {
    Vec3::new(narrow(x), narrow(y), narrow(z))
}

fn rgb([r, g, b]: [f64; 3]) -> LinearRgb {
    LinearRgb::new(narrow(r), narrow(g), narrow(b))
}

/// Parses and validates a scene file's text.
///
/// Every problem, from a TOML syntax error to a negative radius or an image width of 0, comes
/// back as a [`SceneFileError`]; this never panics.
pub fn parse_scene(text: &str) -> Result<SceneFile, SceneFileError> {
    let index = KeyIndex::parse(text).map_err(|e| syntax_error(text, &e))?;
    let raw: RawFile = toml::from_str(text).map_err(|e| toml_error(text, &index, &e))?;
    let place = Placer {
        text,
        index: &index,
        lobes: (raw.sphere.iter().enumerate())
            .filter(|(_, s)| s.lobes.is_some())
            .map(|(i, _)| i)
            .collect(),
    };
    build(&raw, &place)
}

/// A TOML syntax error: toml's message at toml's span. A duplicated key is named from the
/// text (its path is not known yet: the document did not parse).
fn syntax_error(text: &str, e: &toml::de::Error) -> SceneFileError {
    let span = e.span().unwrap_or(0..0);
    let mut message = format!("invalid TOML: {}", one_line(e.message()));
    if message.ends_with("duplicate key") {
        if let Some(name) = text.get(span.clone()) {
            message = format!("{message} `{}`", name.trim());
        }
    }
    SceneFileError::at(text, span.start, None, message)
}

fn one_line(message: &str) -> String {
    message.trim().replace('\n', "; ")
}

/// Maps a serde error from the typed structs to a [`SceneFileError`], finding the key from
/// its span, and rewording serde's Rust-side vocabulary into the file's.
fn toml_error(text: &str, index: &KeyIndex, e: &toml::de::Error) -> SceneFileError {
    let span = e.span().unwrap_or(0..0);
    let entry = index.innermost_at(span.start);
    let mut key = entry.map(|entry| entry.path.clone());
    let message = one_line(e.message());
    // A datetime reaches serde as a map; anything else that does is a table.
    let found = match entry.map(|e| e.kind) {
        Some("datetime") => "a datetime",
        _ => "a table",
    };
    let message = message.replace("invalid type: map", &format!("invalid type: {found}"));
    let message = message.replace("unknown variant", "unknown value");
    let message = match message.find("expected struct ") {
        Some(at) => format!("{}expected a table", &message[..at]),
        None => message,
    };
    // serde speaks of fields; the file has keys. A missing key is reported on its table,
    // so the key path is completed with the missing name.
    let message = if let Some(rest) = message.strip_prefix("missing field ") {
        let name = rest.trim_matches('`');
        key = Some(match key {
            Some(table) => format!("{table}.{name}"),
            None => name.to_string(),
        });
        format!("missing key {rest}")
    } else if let Some(rest) = message.strip_prefix("unknown field ") {
        // toml reports an unknown key at the key itself, which has no entry of its own.
        let name = rest.split('`').nth(1).unwrap_or_default();
        key = index.named_after(name, span.start).map(|e| e.path.clone());
        format!(
            "unknown key {}",
            rest.replace("expected one of", "expected one of the keys")
        )
    } else {
        message
    };
    SceneFileError::at(text, span.start, key, message)
}

/// Places validation errors at the key they are about.
struct Placer<'a> {
    text: &'a str,
    index: &'a KeyIndex,
    /// Spheres whose lobes are written as `lobes = [...]`.
    lobes: Vec<usize>,
}

impl Placer<'_> {
    /// An error about `path`, at its value (or, if the file lacks it, at the nearest
    /// enclosing key that the file has).
    fn error(&self, path: &str, message: String) -> SceneFileError {
        let mut probe = path;
        let span: Range<usize> = loop {
            if let Some(entry) = self.index.get(probe) {
                break entry.value.clone();
            }
            match probe.rfind(['.', '[']) {
                Some(cut) => probe = &probe[..cut],
                None => break 0..0,
            }
        };
        SceneFileError::at(self.text, span.start, Some(path.to_string()), message)
    }

    fn scene_error(&self, e: &SceneError) -> SceneFileError {
        let path = match *e {
            SceneError::Invalid { item, field, .. } => match item {
                Item::Camera => format!("camera.{field}"),
                Item::Background => format!("image.{field}"),
                Item::Sphere(i) => {
                    // Lobe 0 is `ks`/`shininess` in the core, `lobes[0]` in a file that
                    // lists lobes.
                    let field = match field {
                        "ks" if self.lobes.contains(&i) => "lobes[0].weight",
                        "shininess" if self.lobes.contains(&i) => "lobes[0].shininess",
                        f => f,
                    };
                    format!("sphere[{i}].{field}")
                }
                Item::Light(i) => format!("light[{i}].{field}"),
            },
            SceneError::CapacityExceeded { kind, capacity } => match kind {
                ItemKind::Sphere => format!("sphere[{capacity}]"),
                ItemKind::Light => format!("light[{capacity}]"),
            },
            // `SceneError` is non-exhaustive: a future variant is still reported, at the top.
            _ => String::new(),
        };
        self.error(&path, e.to_string())
    }
}

fn build(raw: &RawFile, place: &Placer<'_>) -> Result<SceneFile, SceneFileError> {
    let camera = Camera {
        position: vec3(raw.camera.position),
        look_at: vec3(raw.camera.look_at),
        up: vec3(raw.camera.up),
        vfov_degrees: narrow(raw.camera.vfov),
    };
    let background = rgb(raw.image.background);
    let mut scene = FileScene::new(camera, background).map_err(|e| place.scene_error(&e))?;
    for (i, l) in raw.light.iter().enumerate() {
        let light = light(l, i, place)?;
        scene.add_light(light).map_err(|e| place.scene_error(&e))?;
    }
    for (i, s) in raw.sphere.iter().enumerate() {
        let sphere = Sphere {
            center: vec3(s.center),
            radius: narrow(s.radius),
            material: material(s, i, place)?,
        };
        scene
            .add_sphere(sphere)
            .map_err(|e| place.scene_error(&e))?;
    }
    let (width, height) = (raw.image.width, raw.image.height);
    check_size(&scene, width, height).map_err(|e| {
        let key = if width == 0 || width > MAX_DIMENSION {
            "image.width"
        } else {
            "image.height"
        };
        place.error(key, e.to_string())
    })?;
    Ok(SceneFile {
        scene,
        width,
        height,
        antialias: raw.image.antialias,
    })
}

/// Asks the core whether it renders this size, so the file and the renderer agree on limits.
/// A sphere light is not a size problem: the prepare checks the size before the lights, and
/// the paths' refusal of sphere lights comes when a path is asked to render.
pub fn check_size(scene: &FileScene, width: u32, height: u32) -> Result<(), RenderError> {
    match Prepared::<Scalar, MAX_SPHERES, MAX_LIGHTS>::new(scene, width, height) {
        Ok(_) | Err(RenderError::SphereLight { .. }) => Ok(()),
        Err(e) => Err(e),
    }
}

/// A sphere's material from its keys, checking that they fit its `model` (the numbers are
/// checked by the core).
fn material(s: &RawSphere, i: usize, place: &Placer<'_>) -> Result<Material, SceneFileError> {
    let key = |name: &str| format!("sphere[{i}].{name}");
    let err = |name: &str, message: String| Err(place.error(&key(name), message));
    let normalized = matches!(
        s.model,
        RawModel::NormalizedPhong | RawModel::NormalizedBlinnPhong
    );
    let ggx = s.model == RawModel::Ggx;
    let rough = matches!(s.model, RawModel::OrenNayar | RawModel::Ggx);
    for (name, given) in [("metal", s.metal.is_some()), ("ior", s.ior.is_some())] {
        if given && !normalized && !ggx {
            return err(
                name,
                format!(
                    "`{name}` needs model = \"normalized-phong\", \"normalized-blinn-phong\" \
                     or \"ggx\""
                ),
            );
        }
    }
    if s.lobes.is_some() && !normalized {
        return err(
            "lobes",
            "`lobes` needs model = \"normalized-phong\" or \"normalized-blinn-phong\"".to_string(),
        );
    }
    let roughness = match s.roughness {
        Some(_) if !rough => {
            return err(
                "roughness",
                "`roughness` needs model = \"oren-nayar\" or \"ggx\"".to_string(),
            )
        }
        None if rough => return Err(place.error(&key("model"), "missing key `roughness`".into())),
        r => r.map(narrow).unwrap_or(0.0),
    };
    let surface = match &s.metal {
        None => Surface::Dielectric {
            ior: s.ior.map(narrow),
        },
        Some(name) => {
            let Some(metal) = Metal::from_name(name) else {
                let known: Vec<String> = Metal::ALL
                    .iter()
                    .map(|m| format!("`{}`", m.name()))
                    .collect();
                return err(
                    "metal",
                    format!(
                        "unknown metal `{name}`, expected one of {}",
                        known.join(", ")
                    ),
                );
            };
            if s.ior.is_some() {
                return err(
                    "ior",
                    "a metal has no `ior` (its F0 is its colour)".to_string(),
                );
            }
            for (name, given) in [("albedo", s.albedo.is_some()), ("kd", s.kd.is_some())] {
                if given {
                    return err(
                        name,
                        format!("a metal has no diffuse lobe: remove `{name}`"),
                    );
                }
            }
            Surface::Metal(metal)
        }
    };
    let is_metal = s.metal.is_some();
    let missing = |name: &str| Err(place.error(&key(name), format!("missing key `{name}`")));
    let (albedo, kd) = match (s.albedo, s.kd) {
        (Some(a), Some(kd)) => (rgb(a), narrow(kd)),
        _ if is_metal => (LinearRgb::new(0.0, 0.0, 0.0), 0.0),
        (None, _) => return missing("albedo"),
        (_, None) => return missing("kd"),
    };
    let mut more_lobes = [Lobe::NONE; MORE_LOBES];
    let (ks, shininess) = match &s.lobes {
        Some(lobes) => {
            for name in ["ks", "shininess"] {
                let given = if name == "ks" {
                    s.ks.is_some()
                } else {
                    s.shininess.is_some()
                };
                if given {
                    return err(
                        name,
                        format!("`{name}` and `lobes` both given: `lobes[0]` is the first lobe"),
                    );
                }
            }
            let Some(first) = lobes.first() else {
                return err("lobes", "`lobes` is empty: give 1 to 3 lobes".to_string());
            };
            if lobes.len() > 1 + MORE_LOBES {
                return err(
                    &format!("lobes[{}]", 1 + MORE_LOBES),
                    format!("at most {} lobes", 1 + MORE_LOBES),
                );
            }
            for (slot, l) in more_lobes.iter_mut().zip(&lobes[1..]) {
                *slot = Lobe {
                    weight: narrow(l.weight),
                    shininess: narrow(l.shininess),
                };
            }
            (narrow(first.weight), narrow(first.shininess))
        }
        None => match (s.ks, s.shininess) {
            (Some(ks), Some(n)) => (narrow(ks), narrow(n)),
            _ if matches!(s.model, RawModel::Lambert | RawModel::OrenNayar) => (0.0, 1.0),
            (Some(ks), None) if ggx => (narrow(ks), 1.0),
            (None, _) => return missing("ks"),
            (_, None) => return missing("shininess"),
        },
    };
    let spec = Specular {
        surface,
        more_lobes,
    };
    let model = match s.model {
        RawModel::Phong => Model::Phong,
        RawModel::BlinnPhong => Model::BlinnPhong,
        RawModel::Lambert => Model::Lambert,
        RawModel::NormalizedPhong => Model::NormalizedPhong(spec),
        RawModel::NormalizedBlinnPhong => Model::NormalizedBlinnPhong(spec),
        RawModel::OrenNayar => Model::OrenNayar { roughness },
        RawModel::Ggx => Model::Ggx(Microfacet { roughness, surface }),
    };
    Ok(Material {
        albedo,
        kd,
        ks,
        shininess,
        model,
    })
}

/// A light from its table, checking that its keys fit its `type`.
fn light(l: &RawLight, i: usize, place: &Placer<'_>) -> Result<Light, SceneFileError> {
    let (needs, refuses, kind) = match l.kind {
        LightType::Distant => ("direction", "position", "distant"),
        LightType::Point => ("position", "direction", "point"),
    };
    let (given, extra) = match l.kind {
        LightType::Distant => (l.direction, l.position),
        LightType::Point => (l.position, l.direction),
    };
    if extra.is_some() {
        return Err(place.error(
            &format!("light[{i}].{refuses}"),
            format!("a {kind} light has no `{refuses}` (it takes `{needs}`)"),
        ));
    }
    let Some(v) = given else {
        return Err(place.error(
            &format!("light[{i}].{needs}"),
            format!("missing key `{needs}` (a {kind} light needs it)"),
        ));
    };
    if let (LightType::Distant, Some(_)) = (l.kind, l.radius) {
        return Err(place.error(
            &format!("light[{i}].radius"),
            "a distant light has no `radius` (only a point light takes one)".to_string(),
        ));
    }
    let (color, intensity) = (rgb(l.color), narrow(l.intensity));
    Ok(match l.kind {
        LightType::Distant => Light::Distant {
            direction: vec3(v),
            color,
            intensity,
        },
        LightType::Point => Light::Point {
            position: vec3(v),
            color,
            intensity,
            radius: l.radius.map_or(0.0, narrow),
        },
    })
}

/// The built-in exponent series ([`shadeline::exponent_series`]) in a [`FileScene`], at its
/// scene file's size.
pub fn builtin_scene() -> Result<SceneFile, SceneError> {
    to_file_scene(
        &shadeline::exponent_series()?,
        shadeline::EXPONENT_SERIES_SIZE,
    )
}

/// The names [`preset`] knows.
pub const PRESETS: [&str; 8] = [
    "exponent-series",
    "materials",
    "microfacets",
    "full-moon",
    "area-lights",
    "floor",
    "lamp",
    "three-lights",
];

/// A built-in scene by name (see [`PRESETS`]) in a [`FileScene`], at its scene file's size:
/// `exponent-series` ([`shadeline::exponent_series`]), `materials`
/// ([`shadeline::materials`]), `microfacets` ([`shadeline::microfacets`]), `full-moon`
/// ([`shadeline::full_moon`]) or `area-lights` ([`shadeline::area_lights`] with its sphere
/// light of radius [`shadeline::AREA_LIGHT_RADIUS`]), or one of the scene matrix, `floor`,
/// `lamp` and `three-lights` ([`shadeline::floor`], [`shadeline::lamp`],
/// [`shadeline::three_lights`]).
pub fn preset(name: &str) -> Option<Result<SceneFile, SceneError>> {
    match name {
        "exponent-series" => Some(
            shadeline::exponent_series()
                .and_then(|s| to_file_scene(&s, shadeline::EXPONENT_SERIES_SIZE)),
        ),
        "materials" => {
            Some(shadeline::materials().and_then(|s| to_file_scene(&s, shadeline::MATERIALS_SIZE)))
        }
        "microfacets" => Some(
            shadeline::microfacets().and_then(|s| to_file_scene(&s, shadeline::MICROFACETS_SIZE)),
        ),
        "full-moon" => {
            Some(shadeline::full_moon().and_then(|s| to_file_scene(&s, shadeline::FULL_MOON_SIZE)))
        }
        "area-lights" => Some(
            shadeline::area_lights(shadeline::AREA_LIGHT_RADIUS)
                .and_then(|s| to_file_scene(&s, shadeline::AREA_LIGHTS_SIZE)),
        ),
        "floor" => Some(shadeline::floor().and_then(|s| to_file_scene(&s, shadeline::MATRIX_SIZE))),
        "lamp" => Some(shadeline::lamp().and_then(|s| to_file_scene(&s, shadeline::MATRIX_SIZE))),
        "three-lights" => {
            Some(shadeline::three_lights().and_then(|s| to_file_scene(&s, shadeline::MATRIX_SIZE)))
        }
        _ => None,
    }
}

fn to_file_scene<const S: usize, const L: usize>(
    small: &Scene<S, L>,
    (width, height): (u32, u32),
) -> Result<SceneFile, SceneError> {
    let mut scene = FileScene::new(*small.camera(), small.background())?;
    for light in small.lights() {
        scene.add_light(*light)?;
    }
    for sphere in small.spheres() {
        scene.add_sphere(*sphere)?;
    }
    Ok(SceneFile {
        scene,
        width,
        height,
        antialias: false,
    })
}

#[cfg(test)]
mod reference_page {
    //! `docs/scene-file.md` against the parser: every key each table accepts is in the page's
    //! section for that table, and the page's complete example parses.

    use super::*;
    use serde::de::{self, Visitor};

    const PAGE: &str = include_str!("../../docs/scene-file.md");

    /// A deserializer that only records the fields a struct asks for, then stops.
    struct Fields(&'static [&'static str]);

    impl<'de> de::Deserializer<'de> for &mut Fields {
        type Error = de::value::Error;

        fn deserialize_any<V: Visitor<'de>>(self, _: V) -> Result<V::Value, Self::Error> {
            Err(de::Error::custom("not a struct"))
        }

        fn deserialize_struct<V: Visitor<'de>>(
            self,
            _: &'static str,
            fields: &'static [&'static str],
            _: V,
        ) -> Result<V::Value, Self::Error> {
            self.0 = fields;
            Err(de::Error::custom("fields recorded"))
        }

        serde::forward_to_deserialize_any! {
            bool i8 i16 i32 i64 i128 u8 u16 u32 u64 u128 f32 f64 char str string bytes
            byte_buf option unit unit_struct newtype_struct seq tuple tuple_struct map enum
            identifier ignored_any
        }
    }

    /// The keys a raw table type accepts.
    fn keys<'de, T: Deserialize<'de>>() -> &'static [&'static str] {
        let mut fields = Fields(&[]);
        let _ = T::deserialize(&mut fields);
        fields.0
    }

    /// The page's text from heading `heading` to the next `## `.
    fn section(heading: &str) -> &'static str {
        let start = PAGE
            .find(&format!("## {heading}\n"))
            .unwrap_or_else(|| panic!("no section {heading}"));
        let rest = &PAGE[start + 3..];
        rest.find("\n## ").map_or(rest, |end| &rest[..end])
    }

    #[test]
    fn every_accepted_key_is_documented_in_its_section() {
        let tables: [(&str, &[&str]); 5] = [
            ("`[image]`", keys::<RawImage>()),
            ("`[camera]`", keys::<RawCamera>()),
            ("`[[light]]`", keys::<RawLight>()),
            ("`[[sphere]]`", keys::<RawSphere>()),
            ("`[[sphere]]`", keys::<RawLobe>()),
        ];
        let mut checked = 0;
        for (heading, fields) in tables {
            assert!(!fields.is_empty(), "{heading}: no fields recorded");
            let text = section(heading);
            for field in fields {
                assert!(
                    text.contains(&format!("`{field}`")),
                    "docs/scene-file.md: key `{field}` of {heading} is not documented there"
                );
                checked += 1;
            }
        }
        for table in keys::<RawFile>() {
            let heading = if matches!(*table, "light" | "sphere") {
                format!("## `[[{table}]]`")
            } else {
                format!("## `[{table}]`")
            };
            assert!(PAGE.contains(&heading), "no section for `{table}`");
        }
        assert!(checked >= 25, "{checked} keys");
    }

    #[test]
    fn the_complete_example_parses() {
        let start = PAGE.find("```toml\n").expect("an example") + 8;
        let end = start + PAGE[start..].find("```").expect("its end");
        let file = parse_scene(&PAGE[start..end]).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!((file.width, file.height), (320, 240));
        assert_eq!(file.scene.spheres().len(), 5);
        assert_eq!(file.scene.lights().len(), 2);
    }
}
