//! Shared pieces of the shadeline fuzz targets: the arbitrary input (a scene description made
//! of numbers that include NaN, ±inf, subnormals, huge and tiny values), the scene builder
//! with an independent model of what validation must accept, the list of rendering paths, and
//! the checks every rendered row must pass.
//!
//! | target | proves |
//! |---|---|
//! | `scene` | validation accepts exactly the documented ranges and never panics; every scene it accepts renders, in every path and pixel format, without a panic, to finite non-negative linear colour, hit records that name existing spheres and lights, and 8-bit / 5-6-5 pixels that are the quantized linear colour; bad sizes, rows and slices are refused with the exact error |
//! | `paths_agree` | scalar, 4-lane and 8-lane output are bit-identical, with and without scanline spans; the fixed-point path, on scenes it accepts, is within 2 levels (8-bit) of the scalar path wherever their hit records agree |
//! | `scene_file` | any bytes through the harness's TOML parser give an error or a scene, never a panic; parsed scenes render |
//!
//! # Adding a path
//!
//! Every check is generic over [`Render`]; the paths are listed once, in [`for_each_path`],
//! so a new path is one more line there. The fixed-point path is the one path allowed to
//! refuse a valid scene (with `RenderError::OutOfFixedRange`), and its linear output is
//! 16.16 fixed point, so a miss is the background quantized, not the background's bits.

use arbitrary::Arbitrary;
use shadeline::scene::{MAX_COORDINATE, MAX_INTENSITY, MAX_SHININESS, MAX_VALUE, MIN_RADIUS};
use shadeline::{
    Camera, HitRecord, Item, ItemKind, Light, LinearRgb, Material, Model, Pixel, Prepared,
    PreparedFixed, Problem, Render, RenderError, Rgb565, Rgb888, Scalar, Scene, SceneError, Shade,
    Simd4, Simd8, Sphere, Vec3,
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
    /// Blinn-Phong instead of Phong.
    pub blinn: bool,
}

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
}

impl SceneInput {
    /// The image size this input asks for: width in `1..=MAX_WIDTH`, height in `1..=65535`.
    pub fn size(&self) -> (u32, u32) {
        (
            1 + u32::from(self.width) % MAX_WIDTH,
            u32::from(self.height).max(1),
        )
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
        checks.into_iter().find_map(|(f, p)| p.map(|p| (f, p)))
    }

    /// The first refused field of a light.
    pub fn light(l: &Light) -> Option<(&'static str, Problem)> {
        let (first, color, intensity) = match *l {
            Light::Distant {
                direction: d,
                color,
                intensity,
            } => (("direction", direction(d)), color, intensity),
            Light::Point {
                position,
                color,
                intensity,
            } => (("position", point(position)), color, intensity),
        };
        let checks = [
            first,
            ("color", self::color(color)),
            ("intensity", non_negative(&[intensity], MAX_INTENSITY)),
        ];
        checks.into_iter().find_map(|(f, p)| p.map(|p| (f, p)))
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
                model: if s.blinn {
                    Model::BlinnPhong
                } else {
                    Model::Phong
                },
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
            } => Light::Point {
                position: position.vec(),
                color: color.rgb(),
                intensity: intensity.value(),
            },
        };
        let before = scene.lights().len();
        let want = match model::light(&light) {
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
    fn visit<R: Render>(&mut self, name: &'static str, prepared: Result<R, RenderError>);
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

/// A rendered row in every pixel format.
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

/// Renders row `y` in every pixel format.
pub fn render_row<R: Render>(r: &R, y: u32) -> Row {
    Row {
        linear: line(r, y),
        hits: line(r, y),
        rgb888: line(r, y),
        rgb565: line(r, y),
    }
}

/// Asserts what every row of every path must satisfy, whatever the scene: finite,
/// non-negative linear colour; hit records naming existing spheres and lights, none on
/// background; the background colour exactly where nothing is hit; 8-bit and 5-6-5 pixels
/// that are the quantized linear colour.
///
/// `float` is true for the float paths, whose misses carry the background's exact bits; the
/// fixed path's misses must be within one 8-bit level of the background's pixel.
pub fn check_row(scene: &FuzzScene, row: &Row, what: &str, float: bool) {
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
            fn visit<R: Render>(&mut self, name: &'static str, p: Result<R, RenderError>) {
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
