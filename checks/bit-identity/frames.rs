//! The frames of the bit-identity check, and one hash line per frame.
//!
//! Bit identity across instruction sets needs the same frames on every ISA, not the whole
//! test suite on each: this module renders a fixed list of frames (the presets, every
//! reflection model, every encoding, anti-aliased edges, sphere lights, seeded random scenes
//! and odd widths) on every path and prints one line per frame:
//!
//! ```text
//! materials 97x55 float 3f0c…  aa 91d2…  fixed 0a77…  fixed-aa 51c8…
//! ```
//!
//! Within one run, every float variant (scalar with and without spans, `f32x4` and `f32x8`
//! with and without spans) must give the scalar frame's hash, row for row, or [`lines`]
//! returns an error naming the frame, the variant and the first row that differs; the fixed
//! path's frame must not depend on its spans either. Across runs, the lines must equal the
//! committed `expected.txt`: the host test run compares them (`tests/frame_hashes.rs`, at the
//! workspace's x86-64-v3), and `.ci/bit-identity` builds this crate's program for the SSE2
//! baseline, the native CPU, aarch64 (NEON, under QEMU) and wasm32 (simd128, under Node) and
//! compares its output with the same file. So a lane operation whose rounding depends on the
//! ISA fails the run on the ISA where it differs, and a change of the scalar frame (a new
//! rounding anywhere) fails every run until `expected.txt` is written anew.
//!
//! The random scenes come from a SplitMix64 stream through exact operations only (integer
//! to `f32`, `+ − × ÷` and `sqrt`), so they are the same scenes on every ISA: no `sin`,
//! `powf` or other routine of the platform's maths library touches them.

use shadeline::{
    area_lights, covered_sphere, exponent_series, full_moon, materials, microfacets, model_samples,
    BytePixel, Camera, Encoding, Gray8, HitRecord, Light, LinearRgb, Lobe, Material, Metal,
    Microfacet, Model, Prepared, PreparedFixed, Render, Rgb565, Rgb888, Scalar, Scene, Simd4,
    Simd8, Specular, Sphere, Surface, Vec3, AREA_LIGHT_RADIUS, MORE_LOBES,
};

/// The four encodings every variant is hashed with.
const ENCODINGS: [Encoding; 4] = [
    Encoding::LINEAR,
    Encoding::LINEAR.dithered(),
    Encoding::SRGB,
    Encoding::SRGB.dithered(),
];

/// FNV-1a, 64 bits: small, and the same on every target.
#[derive(Clone, Copy)]
struct Fnv(u64);

impl Fnv {
    const fn new() -> Self {
        Fnv(0xcbf2_9ce4_8422_2325)
    }
    fn bytes(&mut self, bytes: &[u8]) {
        for b in bytes {
            self.0 = (self.0 ^ u64::from(*b)).wrapping_mul(0x0000_0100_0000_01b3);
        }
    }
    fn u32(&mut self, v: u32) {
        self.bytes(&v.to_le_bytes());
    }
    fn u64(&mut self, v: u64) {
        self.bytes(&v.to_le_bytes());
    }
}

/// One row of a frame in every output the hash covers: linear colour to the bit, hit
/// records, Rgb565 and Gray8 with every encoding, and the display bytes of `bytes` (the same
/// frame wrapped with an encoding).
fn row_hash<R: Render, B: Render>(frame: &R, bytes: &B, y: u32) -> Result<u64, String> {
    let w = frame.width() as usize;
    let mut h = Fnv::new();
    let err = |e: shadeline::RenderError| format!("row {y}: {e}");
    let mut linear = vec![LinearRgb::default(); w];
    frame.render_line(y, &mut linear).map_err(err)?;
    for c in &linear {
        for v in [c.r, c.g, c.b] {
            h.u32(v.to_bits());
        }
    }
    let mut hits = vec![HitRecord::default(); w];
    frame.render_line(y, &mut hits).map_err(err)?;
    for hit in &hits {
        h.u32(hit.sphere.map_or(u32::MAX, u32::from));
        h.u32(hit.shadowed);
    }
    for e in ENCODINGS {
        levels::<Rgb565, _>(frame, y, e, &mut h).map_err(err)?;
        levels::<Gray8, _>(frame, y, e, &mut h).map_err(err)?;
    }
    let mut row = vec![0u8; w * <Rgb888 as BytePixel>::BYTES];
    bytes
        .render_line_bytes::<Rgb888>(y, &mut row)
        .map_err(err)?;
    h.bytes(&row);
    Ok(h.0)
}

/// Hashes row `y` of `frame` in format `P` with encoding `e`, through its display bytes.
fn levels<P: BytePixel, R: Render>(
    frame: &R,
    y: u32,
    e: Encoding,
    h: &mut Fnv,
) -> Result<(), shadeline::RenderError> {
    let mut row = vec![P::default(); frame.width() as usize];
    frame.render_segment_with(y, 0, &mut row, e)?;
    for p in row {
        h.bytes(p.to_bytes().as_ref());
    }
    Ok(())
}

/// Every row's hash; the display bytes are sRGB-encoded and dithered.
fn row_hashes<R: Render + Clone>(frame: &R) -> Result<Vec<u64>, String> {
    let bytes = frame.clone().with_encoding(Encoding::SRGB.dithered());
    (0..frame.height())
        .map(|y| row_hash(frame, &bytes, y))
        .collect()
}

/// The frame's hash from its rows' hashes.
fn fold(rows: &[u64]) -> u64 {
    let mut h = Fnv::new();
    for r in rows {
        h.u64(*r);
    }
    h.0
}

/// `got` must be `want`, row for row; the error names the first row that differs.
fn same(got: &[u64], want: &[u64], what: &str) -> Result<(), String> {
    match got.iter().zip(want).position(|(a, b)| a != b) {
        None => Ok(()),
        Some(y) => Err(format!("{what}: row {y} differs from the scalar path's")),
    }
}

/// The float paths' hash of one frame, with or without anti-aliased edges: every variant
/// checked against the scalar path's rows.
fn float_hash(scene: &Frame, (w, h): (u32, u32), aa: bool, name: &str) -> Result<u64, String> {
    let what = |p: &str, spans: bool| {
        let edges = if aa { ", anti-aliased" } else { "" };
        format!("{name}: {p} (spans {spans}{edges})")
    };
    let prepare_err = |e: shadeline::RenderError| format!("{name}: {e}");
    let scalar = Prepared::<Scalar>::new(scene, w, h)
        .map_err(prepare_err)?
        .with_antialiasing(aa);
    let want = row_hashes(&scalar)?;
    same(
        &row_hashes(&scalar.clone().with_spans(false))?,
        &want,
        &what("scalar", false),
    )?;
    for spans in [true, false] {
        let simd4 = Prepared::<Simd4>::new(scene, w, h)
            .map_err(prepare_err)?
            .with_antialiasing(aa)
            .with_spans(spans);
        same(&row_hashes(&simd4)?, &want, &what("simd4", spans))?;
        let simd8 = Prepared::<Simd8>::new(scene, w, h)
            .map_err(prepare_err)?
            .with_antialiasing(aa)
            .with_spans(spans);
        same(&row_hashes(&simd8)?, &want, &what("simd8", spans))?;
    }
    Ok(fold(&want))
}

/// The fixed path's hash of one frame, or the refusal it gives; its spans must change no bit.
fn fixed_hash(scene: &Frame, (w, h): (u32, u32), aa: bool, name: &str) -> Result<String, String> {
    let frame = match PreparedFixed::new(scene, w, h) {
        Ok(frame) => frame.with_antialiasing(aa),
        // A refusal is part of the output: it too must be the same on every ISA.
        Err(e) => return Ok(format!("refused({})", refusal(&e))),
    };
    let want = row_hashes(&frame)?;
    let what = format!("{name}: fixed without spans (anti-aliased {aa})");
    same(&row_hashes(&frame.with_spans(false))?, &want, &what)?;
    Ok(format!("{:016x}", fold(&want)))
}

/// A refusal as one word, for the hash line.
fn refusal(e: &shadeline::RenderError) -> String {
    let text = format!("{e:?}");
    text.split(|c: char| !c.is_alphanumeric())
        .next()
        .unwrap_or("error")
        .to_string()
}

/// One frame's line: the float hashes (sharp and anti-aliased) and the fixed path's.
fn line<const S: usize, const L: usize>(
    name: &str,
    scene: &Scene<S, L>,
    size: (u32, u32),
) -> Result<String, String> {
    let scene = &widen(scene)?;
    let float = float_hash(scene, size, false, name)?;
    let aa = float_hash(scene, size, true, name)?;
    let fixed = fixed_hash(scene, size, false, name)?;
    let fixed_aa = fixed_hash(scene, size, true, name)?;
    Ok(format!(
        "{name} {}x{} float {float:016x} aa {aa:016x} fixed {fixed} fixed-aa {fixed_aa}",
        size.0, size.1
    ))
}

/// SplitMix64: a seeded stream of numbers, the same on every target.
struct Stream(u64);

impl Stream {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }
    /// A number in `[lo, hi)`, from 24 random bits: exact to `f32`, then one `×` and `+`.
    fn range(&mut self, lo: f32, hi: f32) -> f32 {
        let unit = (self.next() >> 40) as f32 / 16_777_216.0;
        lo + (hi - lo) * unit
    }
    fn below(&mut self, n: u64) -> u64 {
        self.next() % n
    }
    fn pick<T: Copy>(&mut self, items: &[T]) -> T {
        items[self.below(items.len() as u64) as usize]
    }
    fn vec3(&mut self, r: f32) -> Vec3 {
        Vec3::new(self.range(-r, r), self.range(-r, r), self.range(-r, r))
    }
    fn color(&mut self, lo: f32, hi: f32) -> LinearRgb {
        LinearRgb::new(self.range(lo, hi), self.range(lo, hi), self.range(lo, hi))
    }
}

/// Specular exponents the random materials draw from: from a wide lobe to a pin-point one.
const SHININESS: [f32; 9] = [1.0, 2.0, 5.0, 10.0, 32.0, 100.0, 300.0, 1000.0, 2000.0];

fn surface(s: &mut Stream) -> Surface {
    match s.below(3) {
        0 => Surface::Dielectric { ior: None },
        1 => Surface::Dielectric {
            ior: Some(s.range(1.05, 2.5)),
        },
        _ => Surface::Metal(s.pick(&Metal::ALL)),
    }
}

fn model(s: &mut Stream) -> Model {
    let mut more_lobes = [Lobe::NONE; MORE_LOBES];
    for lobe in more_lobes.iter_mut().take(s.below(3) as usize) {
        *lobe = Lobe {
            weight: s.range(0.0, 1.0),
            shininess: s.pick(&SHININESS),
        };
    }
    let spec = Specular {
        surface: surface(s),
        more_lobes,
    };
    match s.below(7) {
        0 => Model::Phong,
        1 => Model::BlinnPhong,
        2 => Model::Lambert,
        3 => Model::NormalizedPhong(spec),
        4 => Model::NormalizedBlinnPhong(spec),
        5 => Model::OrenNayar {
            roughness: s.range(0.0, 1.5),
        },
        _ => Model::Ggx(Microfacet {
            roughness: s.range(0.05, 1.0),
            surface: surface(s),
        }),
    }
}

/// A random scene: a camera 6–11 units from the origin, 1–6 spheres of every model, 1–3
/// lights (distant, point, and at most one sphere light). Items the scene refuses (a sphere
/// light when it already has one) are left out.
fn random_scene(seed: u64) -> Result<Frame, String> {
    let s = &mut Stream(seed);
    let dir = s.vec3(1.0);
    let len = (dir.dot(dir).max(1.0e-3)).sqrt();
    let dist = s.range(6.0, 11.0);
    let camera = Camera {
        position: dir * (dist / len),
        look_at: s.vec3(0.5),
        up: Vec3::new(0.0, 1.0, 0.0),
        vfov_degrees: s.range(25.0, 70.0),
    };
    let fail = |e: shadeline::SceneError| format!("random scene {seed}: {e}");
    let mut scene = Scene::new(camera, s.color(0.0, 1.0)).map_err(fail)?;
    for _ in 0..1 + s.below(6) {
        let sphere = Sphere {
            center: s.vec3(2.5),
            radius: s.range(0.3, 1.8),
            material: Material {
                albedo: s.color(0.0, 1.0),
                kd: s.range(0.0, 1.0),
                ks: s.range(0.0, 1.0),
                shininess: s.pick(&SHININESS),
                model: model(s),
            },
        };
        scene.add_sphere(sphere).map_err(fail)?;
    }
    for _ in 0..1 + s.below(3) {
        let color = s.color(0.2, 1.0);
        let light = if s.below(2) == 0 {
            Light::Distant {
                direction: s.vec3(1.0) + Vec3::new(0.0, 0.0, 0.01),
                color,
                intensity: s.range(0.5, 4.0),
            }
        } else {
            let position = s.vec3(8.0);
            let d2 = position.dot(position).max(1.0);
            let radius = if s.below(3) == 0 {
                s.range(0.1, 1.0)
            } else {
                0.0
            };
            Light::Point {
                position,
                color,
                intensity: 12.566_371 * d2 * s.range(0.5, 3.0),
                radius,
            }
        };
        // A second sphere light, or a light inside a sphere, is refused: left out.
        let _ = scene.add_light(light);
    }
    Ok(scene)
}

/// The capacities every frame is rendered at (the defaults): one instantiation of each path
/// keeps the program quick to build for every target.
type Frame = Scene;

/// `scene` with the capacities of [`Frame`].
fn widen<const S: usize, const L: usize>(scene: &Scene<S, L>) -> Result<Frame, String> {
    let fail = |e: shadeline::SceneError| format!("widening a scene: {e}");
    let mut wide = Frame::new(*scene.camera(), scene.background()).map_err(fail)?;
    for sphere in scene.spheres() {
        wide.add_sphere(*sphere).map_err(fail)?;
    }
    for light in scene.lights() {
        wide.add_light(*light).map_err(fail)?;
    }
    Ok(wide)
}

/// Every line, in order, or the first disagreement between the paths of one run.
pub fn lines() -> Result<Vec<String>, String> {
    let mut out = Vec::new();
    fn scene_err(name: &'static str) -> impl Fn(shadeline::SceneError) -> String {
        move |e| format!("{name}: {e}")
    }
    out.push(line(
        "exponent-series",
        &exponent_series().map_err(scene_err("exponent-series"))?,
        (256, 187),
    )?);
    out.push(line(
        "materials",
        &materials().map_err(scene_err("materials"))?,
        (97, 55),
    )?);
    out.push(line(
        "microfacets",
        &microfacets().map_err(scene_err("microfacets"))?,
        (121, 61),
    )?);
    out.push(line(
        "full-moon",
        &full_moon().map_err(scene_err("full-moon"))?,
        (80, 40),
    )?);
    for radius in [0.0, AREA_LIGHT_RADIUS] {
        let scene = area_lights(radius).map_err(scene_err("area-lights"))?;
        out.push(line(&format!("area-lights-r{radius}"), &scene, (96, 48))?);
    }
    for (name, material) in model_samples() {
        let scene = covered_sphere(material).map_err(scene_err(name))?;
        out.push(line(&format!("covered-{name}"), &scene, (33, 29))?);
    }
    // Odd widths: every tail length of both lane widths, and one- and three-pixel rows.
    let widths = [1, 3, 5, 7, 9, 13, 17, 31, 47, 67];
    for seed in 0..24u64 {
        let scene = random_scene(seed)?;
        let w = widths[seed as usize % widths.len()];
        let h = 9 + (seed as u32 * 7) % 31;
        out.push(line(&format!("random-{seed}"), &scene, (w, h))?);
    }
    // Larger random frames: whole packets, several spheres deep, shadows across them.
    for seed in 100..112u64 {
        let scene = random_scene(seed)?;
        out.push(line(&format!("random-{seed}"), &scene, (61, 45))?);
    }
    Ok(out)
}
