//! Shared pieces of the shadeline fuzz targets: the arbitrary input (a scene description made
//! of numbers that include NaN, ±inf, subnormals, huge and tiny values), the scene builder
//! with an independent model of what validation must accept, the list of rendering paths, and
//! the checks every rendered row must pass.
//!
//! | target | proves |
//! |---|---|
//! | `scene` | validation accepts exactly the documented ranges, for every model and option (lobes, `ior`, metals), and never panics; every scene it accepts renders, in every path and pixel format, without a panic, to finite non-negative linear colour, hit records that name existing spheres and lights, 8-bit / 5-6-5 pixels that are the quantized linear colour, and, with one of the four encodings, Rgb888 / Rgb565 / Bgr565 / Gray8 pixels that are the encoding rule and byte rows that are their bytes; bad sizes, rows and slices are refused with the exact error |
//! | `paths_agree` | scalar, 4-lane and 8-lane output are bit-identical, with and without scanline spans, in every format and encoding; the fixed-point path, on well-conditioned scenes it accepts, is within 2 levels (8-bit) of the scalar path wherever their hit records agree, and at most 0.1 % of the pixels compared over a run have differing hit records; refusals are counted |
//! | `scene_file` | any bytes through the harness's TOML parser give an error or a scene, never a panic; parsed scenes render on the scalar, 8-lane and fixed paths, the float paths bit-identical with an encoding |
//!
//! # Adding a path
//!
//! Every check is generic over [`Render`]; the paths are listed once, in [`for_each_path`],
//! so a new path is one more line there. The fixed-point path is the one path allowed to
//! refuse a valid scene (with `RenderError::OutOfFixedRange`), and its linear output is
//! 16.16 fixed point, so a miss is the background quantized, not the background's bits.

pub mod targets;

use arbitrary::Arbitrary;
use shadeline::encoding::{encode_levels, linear_code, linear_code_fixed};
use shadeline::scene::{
    MAX_COORDINATE, MAX_INTENSITY, MAX_OREN_NAYAR_ROUGHNESS, MAX_SHININESS, MAX_VALUE,
    MIN_GGX_ROUGHNESS, MIN_RADIUS,
};
use shadeline::{
    Bgr565, BytePixel, Camera, Encoding, FixedShade, Gray8, HitRecord, Item, ItemKind, Light,
    LinearRgb, Lobe, Material, Metal, Microfacet, Model, Pixel, Prepared, PreparedFixed, Problem,
    Render, RenderError, Rgb565, Rgb888, Scalar, Scene, SceneError, Shade, Simd4, Simd8, Specular,
    Sphere, Surface, Vec3, MORE_LOBES,
};

/// Sphere capacity of the fuzzed scenes: small, so that the capacity error is reached.
pub const SPHERES: usize = 4;
/// Light capacity of the fuzzed scenes.
pub const LIGHTS: usize = 3;
/// The scene type every target builds.
pub type FuzzScene = Scene<SPHERES, LIGHTS>;
/// Widest image the targets render (1..=67 covers 0, 1 and 2 full 8-lane packets plus tails,
/// and every tail length of both SIMD widths).
pub const MAX_WIDTH: u32 = 67;

/// Values that sit on an edge of some range, or are otherwise interesting to a float kernel.
const SPECIALS: [f32; 32] = [
    f32::NAN,
    f32::INFINITY,
    f32::NEG_INFINITY,
    0.0,
    -0.0,
    f32::MIN_POSITIVE,
    1.0e-45, // the smallest subnormal
    -1.0e-45,
    f32::MAX,
    f32::MIN,
    f32::EPSILON,
    1.0,
    -1.0,
    MAX_COORDINATE,
    -MAX_COORDINATE,
    1_000_000.06, // the f32 above MAX_COORDINATE (and MAX_VALUE, MAX_SHININESS)
    MAX_INTENSITY,
    1.000_000_1e12, // above MAX_INTENSITY
    180.0,
    179.999_98, // the f32 below 180
    179.999,
    1.0e-6,
    90.0,
    0.5,
    1.0e30,
    -1.0e30,
    1.0e-30,
    1.0e-39, // subnormal: its reciprocal overflows
    1.0e-20, // its square underflows
    2.0,
    1.0e6,
    1.0e-3,
];

/// One number of the fuzzed scene, drawn from a mix that reaches every kind of `f32`.
#[derive(Arbitrary, Clone, Copy, Debug)]
pub enum Num {
    /// `v / 4`: everyday values in `[-32, 32)`.
    Small(i8),
    /// `v / 65535`: a value in `[0, 1]`.
    Fraction(u16),
    /// `(m / 16)·10^e`, `e` in `-45..=45`: huge, tiny and subnormal values, zero and inf.
    Power(i8, i8),
    /// An entry of the table of edge values (NaN, ±inf, range limits, …).
    Special(u8),
    /// Any bit pattern, NaN payloads included.
    Bits(u32),
}

impl Num {
    /// The `f32` this stands for.
    pub fn value(self) -> f32 {
        match self {
            Num::Small(v) => f32::from(v) / 4.0,
            Num::Fraction(v) => f32::from(v) / 65535.0,
            Num::Power(m, e) => (f32::from(m) / 16.0) * 10f32.powi(i32::from(e) % 46),
            Num::Special(i) => SPECIALS[usize::from(i) % SPECIALS.len()],
            Num::Bits(b) => f32::from_bits(b),
        }
    }
}

/// Three numbers.
#[derive(Arbitrary, Clone, Copy, Debug)]
pub struct V3(pub Num, pub Num, pub Num);

impl V3 {
    fn vec(self) -> Vec3 {
        Vec3::new(self.0.value(), self.1.value(), self.2.value())
    }
    fn rgb(self) -> LinearRgb {
        LinearRgb::new(self.0.value(), self.1.value(), self.2.value())
    }
}

/// The camera's numbers.
#[derive(Arbitrary, Clone, Copy, Debug)]
pub struct CameraIn {
    /// `position`.
    pub position: V3,
    /// `look_at`.
    pub look_at: V3,
    /// `up`.
    pub up: V3,
    /// `vfov_degrees`.
    pub vfov: Num,
}

/// A sphere's numbers.
#[derive(Arbitrary, Clone, Copy, Debug)]
pub struct SphereIn {
    /// `center`.
    pub center: V3,
    /// `radius`.
    pub radius: Num,
    /// `albedo`.
    pub albedo: V3,
    /// `kd`.
    pub kd: Num,
    /// `ks`.
    pub ks: Num,
    /// `shininess`.
    pub shininess: Num,
    /// The reflection model and its options.
    pub model: ModelIn,
}

/// A reflection model: every [`Model`], with arbitrary specular options.
#[derive(Arbitrary, Clone, Copy, Debug)]
pub enum ModelIn {
    /// [`Model::Phong`].
    Phong,
    /// [`Model::BlinnPhong`].
    BlinnPhong,
    /// [`Model::Lambert`].
    Lambert,
    /// [`Model::NormalizedPhong`].
    NormalizedPhong(SpecularIn),
    /// [`Model::NormalizedBlinnPhong`].
    NormalizedBlinnPhong(SpecularIn),
    /// [`Model::OrenNayar`] with this roughness.
    OrenNayar(Num),
    /// [`Model::Ggx`] with this roughness and surface.
    Ggx(Num, SurfaceIn),
}

/// The normalized models' options: the surface and lobes 1 and 2.
#[derive(Arbitrary, Clone, Copy, Debug)]
pub struct SpecularIn {
    /// What the surface is.
    pub surface: SurfaceIn,
    /// Lobes 1 and 2 (weight 0: absent).
    pub lobes: [LobeIn; MORE_LOBES],
}

/// A [`Surface`].
#[derive(Arbitrary, Clone, Copy, Debug)]
pub enum SurfaceIn {
    /// A dielectric without `ior`.
    Dielectric,
    /// A dielectric with this `ior`.
    Fresnel(Num),
    /// A metal, [`Metal::ALL`] modulo its length.
    Metal(u8),
}

/// A [`Lobe`]'s numbers.
#[derive(Arbitrary, Clone, Copy, Debug)]
pub struct LobeIn {
    /// `weight`.
    pub weight: Num,
    /// `shininess`.
    pub shininess: Num,
}

impl ModelIn {
    /// The model this stands for.
    pub fn model(self) -> Model {
        let surface = |s: SurfaceIn| match s {
            SurfaceIn::Dielectric => Surface::Dielectric { ior: None },
            SurfaceIn::Fresnel(ior) => Surface::Dielectric {
                ior: Some(ior.value()),
            },
            SurfaceIn::Metal(k) => Surface::Metal(Metal::ALL[usize::from(k) % Metal::ALL.len()]),
        };
        let spec = |s: SpecularIn| Specular {
            surface: surface(s.surface),
            more_lobes: s.lobes.map(|l| Lobe {
                weight: l.weight.value(),
                shininess: l.shininess.value(),
            }),
        };
        match self {
            ModelIn::Phong => Model::Phong,
            ModelIn::BlinnPhong => Model::BlinnPhong,
            ModelIn::Lambert => Model::Lambert,
            ModelIn::NormalizedPhong(s) => Model::NormalizedPhong(spec(s)),
            ModelIn::NormalizedBlinnPhong(s) => Model::NormalizedBlinnPhong(spec(s)),
            ModelIn::OrenNayar(r) => Model::OrenNayar {
                roughness: r.value(),
            },
            ModelIn::Ggx(r, s) => Model::Ggx(Microfacet {
                roughness: r.value(),
                surface: surface(s),
            }),
        }
    }
}

/// The four encodings, by [`SceneInput::encoding`] modulo 4.
pub const ENCODINGS: [Encoding; 4] = [
    Encoding::LINEAR,
    Encoding::LINEAR.dithered(),
    Encoding::SRGB,
    Encoding::SRGB.dithered(),
];

/// A light's numbers.
#[derive(Arbitrary, Clone, Copy, Debug)]
pub enum LightIn {
    /// [`Light::Distant`].
    Distant {
        /// `direction`.
        direction: V3,
        /// `color`.
        color: V3,
        /// `intensity`.
        intensity: Num,
    },
    /// [`Light::Point`].
    Point {
        /// `position`.
        position: V3,
        /// `color`.
        color: V3,
        /// `intensity`.
        intensity: Num,
    },
}

/// A scene and a few rows to render.
#[derive(Arbitrary, Clone, Debug)]
pub struct SceneInput {
    /// The camera.
    pub camera: CameraIn,
    /// The background colour.
    pub background: V3,
    /// Spheres, in order; those past the capacity must be refused with the capacity error.
    pub spheres: Vec<SphereIn>,
    /// Lights, likewise.
    pub lights: Vec<LightIn>,
    /// The width is `1 + width % MAX_WIDTH`.
    pub width: u8,
    /// The height is `max(height, 1)`: any height the core accepts.
    pub height: u16,
    /// Rows to render, taken modulo the height; the last row is always rendered too.
    pub rows: [u16; 2],
    /// The encoding of the encoded rows: [`ENCODINGS`] modulo 4.
    pub encoding: u8,
    /// The radii of the point lights, in order (0 for a point light, more for a sphere
    /// light); a point light past the end has radius 0. Last, so that an input that ends
    /// before it (every seed written before it existed) decodes as it did.
    pub radii: Vec<Num>,
}

impl SceneInput {
    /// The image size this input asks for: width in `1..=MAX_WIDTH`, height in `1..=65535`.
    pub fn size(&self) -> (u32, u32) {
        (
            1 + u32::from(self.width) % MAX_WIDTH,
            u32::from(self.height).max(1),
        )
    }
    /// The encoding this input asks for.
    pub fn encoding(&self) -> Encoding {
        ENCODINGS[usize::from(self.encoding) % ENCODINGS.len()]
    }
    /// The rows to render, each below `height`.
    pub fn rows(&self, height: u32) -> [u32; 3] {
        [
            u32::from(self.rows[0]) % height,
            u32::from(self.rows[1]) % height,
            height - 1,
        ]
    }
}

/// What the documentation says validation does with a value: accepts it (`None`) or refuses
/// it with this problem. Written from the table in `shadeline::scene`, not from its code.
mod model {
    use super::*;

    pub fn finite(v: &[f32]) -> Option<Problem> {
        (!v.iter().all(|x| x.is_finite())).then_some(Problem::NotFinite)
    }
    pub fn point(p: Vec3) -> Option<Problem> {
        let v = [p.x, p.y, p.z];
        finite(&v).or((v.iter().any(|x| x.abs() > MAX_COORDINATE)).then_some(Problem::TooLarge))
    }
    pub fn non_negative(v: &[f32], max: f32) -> Option<Problem> {
        finite(v)
            .or(v.iter().any(|&x| x < 0.0).then_some(Problem::Negative))
            .or(v.iter().any(|&x| x > max).then_some(Problem::TooLarge))
    }
    pub fn positive(v: f32, max: f32) -> Option<Problem> {
        finite(&[v])
            .or((v <= 0.0).then_some(Problem::NotPositive))
            .or((v > max).then_some(Problem::TooLarge))
    }
    pub fn direction(d: Vec3) -> Option<Problem> {
        let v = [d.x, d.y, d.z];
        finite(&v).or(v.iter().all(|&x| x == 0.0).then_some(Problem::ZeroLength))
    }
    pub fn color(c: LinearRgb) -> Option<Problem> {
        non_negative(&[c.r, c.g, c.b], MAX_VALUE)
    }

    /// The first refused field of a sphere, in the documented order.
    pub fn sphere(s: &Sphere) -> Option<(&'static str, Problem)> {
        let m = &s.material;
        let checks = [
            ("center", point(s.center)),
            (
                "radius",
                positive(s.radius, MAX_COORDINATE)
                    .or((s.radius < MIN_RADIUS).then_some(Problem::TooSmall)),
            ),
            ("albedo", color(m.albedo)),
            ("kd", non_negative(&[m.kd], MAX_VALUE)),
            ("ks", non_negative(&[m.ks], MAX_VALUE)),
            ("shininess", positive(m.shininess, MAX_SHININESS)),
        ];
        let first = checks.into_iter().find_map(|(f, p)| p.map(|p| (f, p)));
        // Oren–Nayar's and GGX's roughness, after the fields every model has; then GGX's ior.
        let roughness = match m.model {
            Model::OrenNayar { roughness } => non_negative(&[roughness], MAX_OREN_NAYAR_ROUGHNESS),
            Model::Ggx(micro) => finite(&[micro.roughness])
                .or((micro.roughness < MIN_GGX_ROUGHNESS).then_some(Problem::TooSmall))
                .or((micro.roughness > 1.0).then_some(Problem::TooLarge)),
            _ => None,
        };
        let ggx_ior = match m.model {
            Model::Ggx(Microfacet {
                surface: Surface::Dielectric { ior: Some(ior) },
                ..
            }) => finite(&[ior])
                .or((ior <= 1.0).then_some(Problem::NotAboveOne))
                .or((ior > MAX_VALUE).then_some(Problem::TooLarge)),
            _ => None,
        };
        let first = first.or_else(|| {
            [("roughness", roughness), ("ior", ggx_ior)]
                .into_iter()
                .find_map(|(f, p)| p.map(|p| (f, p)))
        });
        let Some(spec) = m.model.specular() else {
            return first;
        };
        // The normalized models' options, after the fields every model has: each lobe's
        // weight and exponent, then the ior.
        const LOBES: [(&str, &str); MORE_LOBES] = [
            ("lobes[1].weight", "lobes[1].shininess"),
            ("lobes[2].weight", "lobes[2].shininess"),
        ];
        let lobes = spec.more_lobes.iter().zip(LOBES).flat_map(|(l, (w, n))| {
            [
                (w, non_negative(&[l.weight], MAX_VALUE)),
                (n, positive(l.shininess, MAX_SHININESS)),
            ]
        });
        let ior = match spec.surface {
            Surface::Dielectric { ior: Some(ior) } => finite(&[ior])
                .or((ior <= 1.0).then_some(Problem::NotAboveOne))
                .or((ior > MAX_VALUE).then_some(Problem::TooLarge)),
            _ => None,
        };
        first.or_else(|| {
            lobes
                .chain([("ior", ior)])
                .find_map(|(f, p)| p.map(|p| (f, p)))
        })
    }

    /// The first refused field of a light.
    pub fn light(l: &Light) -> Option<(&'static str, Problem)> {
        let (first, radius, color, intensity) = match *l {
            Light::Distant {
                direction: d,
                color,
                intensity,
            } => (("direction", direction(d)), None, color, intensity),
            Light::Point {
                position,
                color,
                intensity,
                radius,
            } => (
                ("position", point(position)),
                non_negative(&[radius], MAX_COORDINATE),
                color,
                intensity,
            ),
        };
        let checks = [
            first,
            ("radius", radius),
            ("color", self::color(color)),
            ("intensity", non_negative(&[intensity], MAX_INTENSITY)),
        ];
        checks.into_iter().find_map(|(f, p)| p.map(|p| (f, p)))
    }

    /// Whether a sphere light overlaps `sphere` (touching is allowed), decided by the same
    /// `f32` expression as the core's, so a tie goes the same way.
    pub fn overlaps(l: &Light, sphere: &Sphere) -> bool {
        let Light::Point {
            position, radius, ..
        } = *l
        else {
            return false;
        };
        let d = position - sphere.center;
        let reach = radius + sphere.radius;
        radius > 0.0 && d.dot(d) < reach * reach
    }

    /// The first refused field of a camera among those that do not depend on rounding
    /// (`LookAtEqualsPosition` and `UpParallelToView` are decided in `f32` by the core and
    /// are allowed whenever these pass).
    pub fn camera(c: &Camera) -> Option<(&'static str, Problem)> {
        let vfov = finite(&[c.vfov_degrees])
            .or((!(c.vfov_degrees > 0.0 && c.vfov_degrees < 180.0))
                .then_some(Problem::FieldOfViewOutOfRange));
        let checks = [
            ("position", point(c.position)),
            ("look_at", point(c.look_at)),
            ("up", direction(c.up)),
            ("vfov", vfov),
        ];
        checks.into_iter().find_map(|(f, p)| p.map(|p| (f, p)))
    }
}

fn invalid(item: Item, (field, problem): (&'static str, Problem)) -> SceneError {
    SceneError::Invalid {
        item,
        field,
        problem,
    }
}

/// Builds the input's scene through the public API, asserting that each call accepts or
/// refuses exactly as documented (the refused item is not added; items past the capacity get
/// the capacity error). `None` if the camera or background is refused.
pub fn build_scene(input: &SceneInput) -> Option<FuzzScene> {
    let c = &input.camera;
    let camera = Camera {
        position: c.position.vec(),
        look_at: c.look_at.vec(),
        up: c.up.vec(),
        vfov_degrees: c.vfov.value(),
    };
    let background = input.background.rgb();
    let built = FuzzScene::new(camera, background);
    let geometric = |e: &SceneError| {
        matches!(e, SceneError::Invalid { item: Item::Camera, problem, .. }
            if matches!(problem, Problem::LookAtEqualsPosition | Problem::UpParallelToView))
    };
    let mut scene = match (built, model::camera(&camera)) {
        (Err(got), Some(field)) => {
            assert_eq!(got, invalid(Item::Camera, field), "camera {camera:?}");
            return None;
        }
        (Ok(_), Some(field)) => panic!("camera {camera:?} accepted, expected {field:?}"),
        // The camera's fields pass: the core may still find it degenerate (checked before
        // the background), else the background decides.
        (Err(got), None) if geometric(&got) => return None,
        (built, None) => {
            let want =
                model::color(background).map(|p| invalid(Item::Background, ("background", p)));
            match (built, want) {
                (Ok(scene), None) => scene,
                (Err(got), Some(want)) => {
                    assert_eq!(got, want, "background {background:?}");
                    return None;
                }
                (got, want) => panic!("background {background:?}: got {got:?}, expected {want:?}"),
            }
        }
    };
    // The derived basis is orthonormal and finite.
    let (r, u, f) = scene.camera_basis();
    for v in [r, u, f] {
        assert!(
            v.is_finite() && (v.dot(v) - 1.0).abs() < 1e-3,
            "basis {v:?}"
        );
    }

    for s in &input.spheres {
        let sphere = Sphere {
            center: s.center.vec(),
            radius: s.radius.value(),
            material: Material {
                albedo: s.albedo.rgb(),
                kd: s.kd.value(),
                ks: s.ks.value(),
                shininess: s.shininess.value(),
                model: s.model.model(),
            },
        };
        let before = scene.spheres().len();
        let want = match model::sphere(&sphere) {
            Some(e) => Err(invalid(Item::Sphere(before), e)),
            None if before == SPHERES => Err(SceneError::CapacityExceeded {
                kind: ItemKind::Sphere,
                capacity: SPHERES,
            }),
            None => Ok(before),
        };
        assert_eq!(scene.add_sphere(sphere), want, "{sphere:?}");
        let after = before + usize::from(want.is_ok());
        assert_eq!(scene.spheres().len(), after);
    }
    let mut points = 0;
    for l in &input.lights {
        let light = match *l {
            LightIn::Distant {
                direction,
                color,
                intensity,
            } => Light::Distant {
                direction: direction.vec(),
                color: color.rgb(),
                intensity: intensity.value(),
            },
            LightIn::Point {
                position,
                color,
                intensity,
            } => {
                let radius = input.radii.get(points).map_or(0.0, |r| r.value());
                points += 1;
                Light::Point {
                    position: position.vec(),
                    color: color.rgb(),
                    intensity: intensity.value(),
                    radius,
                }
            }
        };
        let before = scene.lights().len();
        let refused = model::light(&light).or_else(|| {
            scene
                .spheres()
                .iter()
                .any(|s| model::overlaps(&light, s))
                .then_some(("radius", Problem::LightOverlapsSphere))
        });
        let want = match refused {
            Some(e) => Err(invalid(Item::Light(before), e)),
            None if before == LIGHTS => Err(SceneError::CapacityExceeded {
                kind: ItemKind::Light,
                capacity: LIGHTS,
            }),
            None => Ok(before),
        };
        assert_eq!(scene.add_light(light), want, "{light:?}");
        assert_eq!(scene.lights().len(), before + usize::from(want.is_ok()));
    }
    let eps = scene.ray_epsilon();
    assert!(eps.is_finite() && eps > 0.0, "ray epsilon {eps}");
    Some(scene)
}

/// The rendering paths, each prepared for one scene and size.
///
/// [`for_each_path`] calls it once per path; a path that refuses the scene or size is passed
/// on as its error, so a caller can check it (a path with a narrower range refuses some
/// scenes).
pub trait PathVisitor {
    /// Called once per path with its name and its prepared frame (or why it was refused).
    fn visit<R: Render + Clone>(&mut self, name: &'static str, prepared: Result<R, RenderError>);
}

/// Prepares `scene` at `width × height` on every path and hands each to `visitor`, scalar
/// first. Adding a path is one line here.
pub fn for_each_path<V: PathVisitor>(scene: &FuzzScene, width: u32, height: u32, visitor: &mut V) {
    visitor.visit(
        "scalar",
        Prepared::<Scalar, SPHERES, LIGHTS>::new(scene, width, height),
    );
    visitor.visit(
        "simd4",
        Prepared::<Simd4, SPHERES, LIGHTS>::new(scene, width, height),
    );
    visitor.visit(
        "simd8",
        Prepared::<Simd8, SPHERES, LIGHTS>::new(scene, width, height),
    );
    visitor.visit(
        "fixed",
        PreparedFixed::<SPHERES, LIGHTS>::new(scene, width, height),
    );
}

/// A rendered row in every pixel format: with the default encoding, and with an encoding
/// (sRGB and/or dithering) in every level format and as display bytes.
#[derive(Clone, Debug, PartialEq)]
pub struct Row {
    /// Linear colour, unclamped.
    pub linear: Vec<LinearRgb>,
    /// Hit records.
    pub hits: Vec<HitRecord>,
    /// 8-bit colour.
    pub rgb888: Vec<Rgb888>,
    /// 5-6-5 colour.
    pub rgb565: Vec<Rgb565>,
    /// The encoding of the fields below.
    pub encoding: Encoding,
    /// Linear colour, rendered with the encoding: what the encoded fields below quantize.
    /// Every path gives `linear`'s bits: the encoding changes only the encode step.
    pub enc_linear: Vec<LinearRgb>,
    /// 8-bit colour, encoded.
    pub enc_rgb888: Vec<Rgb888>,
    /// 5-6-5 colour, encoded.
    pub enc_rgb565: Vec<Rgb565>,
    /// 5-6-5 colour with red and blue swapped, encoded.
    pub enc_bgr565: Vec<Bgr565>,
    /// Rec. 709 luma, encoded.
    pub enc_gray8: Vec<Gray8>,
    /// The encoded row as display bytes (`render_line_bytes`): RGB565, BGR565, RGB888, Gray8.
    pub bytes: [Vec<u8>; 4],
}

impl Row {
    /// The linear colour as bits, for bit-exact comparison (NaN-safe).
    pub fn linear_bits(&self) -> Vec<[u32; 3]> {
        self.linear
            .iter()
            .map(|c| [c.r.to_bits(), c.g.to_bits(), c.b.to_bits()])
            .collect()
    }
}

fn line<P: Pixel + Default, R: Render>(r: &R, y: u32) -> Vec<P> {
    let mut out = vec![P::default(); r.width() as usize];
    r.render_line(y, &mut out)
        .unwrap_or_else(|e| panic!("row {y} refused: {e}"));
    out
}

fn line_bytes<P: BytePixel, R: Render>(r: &R, y: u32) -> Vec<u8> {
    let mut out = vec![0u8; r.width() as usize * P::BYTES];
    r.render_line_bytes::<P>(y, &mut out)
        .unwrap_or_else(|e| panic!("byte row {y} refused: {e}"));
    out
}

/// Renders row `y` in every pixel format, and with `encoding` in every level format and as
/// display bytes.
pub fn render_row<R: Render + Clone>(r: &R, y: u32, encoding: Encoding) -> Row {
    let e = r.clone().with_encoding(encoding);
    Row {
        linear: line(r, y),
        hits: line(r, y),
        rgb888: line(r, y),
        rgb565: line(r, y),
        encoding,
        enc_linear: line(&e, y),
        enc_rgb888: line(&e, y),
        enc_rgb565: line(&e, y),
        enc_bgr565: line(&e, y),
        enc_gray8: line(&e, y),
        bytes: [
            line_bytes::<Rgb565, _>(&e, y),
            line_bytes::<Bgr565, _>(&e, y),
            line_bytes::<Rgb888, _>(&e, y),
            line_bytes::<Gray8, _>(&e, y),
        ],
    }
}

/// The pixel of format `P` at `(x, y)` that the encoding rule gives for `color`: the
/// per-pixel definition in `shadeline::encoding` (linear codes, transfer, threshold), or
/// with the default encoding the per-pixel `encode` of the path's numbers (`f32`, or the
/// fixed path's 16.16 colour, which its linear output holds exactly).
fn rule<P: Pixel>(color: LinearRgb, e: Encoding, float: bool, x: u32, y: u32) -> P {
    let raw = |v: f32| (v * 65536.0) as u32;
    if e == Encoding::LINEAR {
        return if float {
            P::encode(&Shade {
                color,
                hit: HitRecord::default(),
            })
        } else {
            P::encode_fixed(&FixedShade {
                color: [raw(color.r), raw(color.g), raw(color.b)],
                hit: HitRecord::default(),
            })
        };
    }
    let codes = [color.r, color.g, color.b].map(|v| {
        if float {
            linear_code(v)
        } else {
            linear_code_fixed(raw(v))
        }
    });
    let levels = P::LEVELS.expect("a level format");
    P::from_levels(encode_levels(codes, levels, P::GRAY, e, x, y))
}

/// Asserts that the linear colour rendered with the row's encoding is the unencoded linear
/// colour bit for bit (on every path: the encoding changes only the encode step, never
/// which kernel shades a pixel), that the encoded pixels are the encoding rule applied to
/// it, and that the byte rows are the encoded pixels' bytes. The corpus keeps the scenes
/// on which the fixed path once chose its kernel by the encoding
/// (`seed-srgb-dark-silhouette-fixed`, `seed-bright-silhouette-fixed-srgb`,
/// `seed-saturated-fixed-kernels`, `seed-fixed-kernels-disagree`).
fn check_encoded(row: &Row, y: u32, what: &str, float: bool) {
    let e = row.encoding;
    for (x, (c, plain)) in row.enc_linear.iter().zip(&row.linear).enumerate() {
        let (xi, c) = (x as u32, *c);
        let at = |f: &str| format!("{what}: pixel {x}, {f} {e:?}");
        let channels = [(c.r, plain.r), (c.g, plain.g), (c.b, plain.b)];
        let same = channels.iter().all(|(a, b)| a.to_bits() == b.to_bits());
        assert!(
            same,
            "{}: {c:?} vs {plain:?}",
            at("linear with the encoding")
        );
        assert_eq!(
            row.enc_rgb888[x],
            rule::<Rgb888>(c, e, float, xi, y),
            "{}",
            at("Rgb888")
        );
        assert_eq!(
            row.enc_rgb565[x],
            rule::<Rgb565>(c, e, float, xi, y),
            "{}",
            at("Rgb565")
        );
        assert_eq!(
            row.enc_bgr565[x],
            rule::<Bgr565>(c, e, float, xi, y),
            "{}",
            at("Bgr565")
        );
        assert_eq!(
            row.enc_gray8[x],
            rule::<Gray8>(c, e, float, xi, y),
            "{}",
            at("Gray8")
        );
    }
    fn bytes<P: BytePixel>(px: &[P]) -> Vec<u8> {
        px.iter()
            .flat_map(|p| p.to_bytes().as_ref().to_vec())
            .collect()
    }
    assert_eq!(row.bytes[0], bytes(&row.enc_rgb565), "{what}: RGB565 bytes");
    assert_eq!(row.bytes[1], bytes(&row.enc_bgr565), "{what}: BGR565 bytes");
    assert_eq!(row.bytes[2], bytes(&row.enc_rgb888), "{what}: RGB888 bytes");
    assert_eq!(row.bytes[3], bytes(&row.enc_gray8), "{what}: Gray8 bytes");
}

/// Asserts what every row `y` of every path must satisfy, whatever the scene: finite,
/// non-negative linear colour; hit records naming existing spheres and lights, none on
/// background; the background colour exactly where nothing is hit; 8-bit and 5-6-5 pixels
/// that are the quantized linear colour; with the row's encoding, every level format equal
/// to the encoding rule applied to the linear colour, and byte rows equal to those pixels'
/// bytes.
///
/// `float` is true for the float paths, whose misses carry the background's exact bits; the
/// fixed path's misses must be within one 8-bit level of the background's pixel.
pub fn check_row(scene: &FuzzScene, row: &Row, y: u32, what: &str, float: bool) {
    check_encoded(row, y, what, float);
    let spheres = scene.spheres().len();
    let light_bits = if scene.lights().len() >= 32 {
        u32::MAX
    } else {
        (1u32 << scene.lights().len()) - 1
    };
    let bg = scene.background();
    for (x, (c, h)) in row.linear.iter().zip(&row.hits).enumerate() {
        for v in [c.r, c.g, c.b] {
            assert!(
                v.is_finite() && v >= 0.0,
                "{what}: pixel {x} colour {c:?} is not finite and non-negative"
            );
        }
        match h.sphere {
            Some(k) => assert!(
                usize::from(k) < spheres,
                "{what}: pixel {x} hits sphere {k} of {spheres}"
            ),
            None => {
                assert_eq!(h.shadowed, 0, "{what}: pixel {x}: shadow bits on a miss");
                let bg_shade = Shade {
                    color: bg,
                    hit: HitRecord::default(),
                };
                if float {
                    assert_eq!(*c, bg, "{what}: pixel {x}: a miss is not the background");
                } else {
                    // The fixed path holds the background in 16.16: one level of rounding.
                    let (got, want) = (row.rgb888[x], Rgb888::encode(&bg_shade));
                    let levels = [(got.r, want.r), (got.g, want.g), (got.b, want.b)]
                        .map(|(a, b)| a.abs_diff(b));
                    assert!(
                        levels.iter().all(|&l| l <= 1),
                        "{what}: pixel {x}: a miss {got:?} is not the background {want:?}"
                    );
                }
            }
        }
        assert_eq!(
            h.shadowed & !light_bits,
            0,
            "{what}: pixel {x}: shadow bits {:#x} for {} lights",
            h.shadowed,
            scene.lights().len()
        );
        let shade = Shade {
            color: *c,
            hit: HitRecord::default(),
        };
        assert_eq!(row.rgb888[x], Rgb888::encode(&shade), "{what}: pixel {x}");
        assert_eq!(row.rgb565[x], Rgb565::encode(&shade), "{what}: pixel {x}");
    }
}

/// Asserts the row driver refuses what it must with the exact error: a row past the bottom,
/// a slice one pixel short or long (for every format the driver treats differently).
pub fn check_refusals<R: Render>(r: &R) {
    let (w, h) = (r.width(), r.height());
    let mut buf = vec![Rgb888::default(); w as usize + 1];
    let mut hits = vec![HitRecord::default(); w as usize + 1];
    assert_eq!(
        r.render_line(h, &mut buf[..w as usize]),
        Err(RenderError::RowOutOfRange { y: h, height: h })
    );
    assert_eq!(
        r.render_line(u32::MAX, &mut buf[..w as usize]),
        Err(RenderError::RowOutOfRange {
            y: u32::MAX,
            height: h
        })
    );
    for len in [w as usize - 1, w as usize + 1] {
        let want = Err(RenderError::LineLength {
            expected: w as usize,
            got: len,
        });
        assert_eq!(r.render_line(0, &mut buf[..len]), want);
        assert_eq!(r.render_line(0, &mut hits[..len]), want);
    }
    // Nothing was written by a refused call.
    assert!(buf.iter().all(|p| *p == Rgb888::default()));
    assert!(hits.iter().all(|p| *p == HitRecord::default()));
}

/// Asserts that sizes outside `1..=MAX_DIMENSION` are refused with the exact error.
pub fn check_bad_sizes(scene: &FuzzScene, width: u32, height: u32) {
    let max = shadeline::MAX_DIMENSION;
    for (w, h) in [(0, height), (width, 0), (max + 1, height), (width, max + 1)] {
        struct Refused(u32, u32);
        impl PathVisitor for Refused {
            fn visit<R: Render + Clone>(&mut self, name: &'static str, p: Result<R, RenderError>) {
                let (width, height) = (self.0, self.1);
                match p {
                    Err(e) => assert_eq!(e, RenderError::BadSize { width, height }, "{name}"),
                    Ok(_) => panic!("{name}: size {width}x{height} accepted"),
                }
            }
        }
        for_each_path(scene, w, h, &mut Refused(w, h));
    }
}
