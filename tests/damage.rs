//! The damage between two frames never misses a changed pixel: both frames are rendered in
//! full on every path (scalar, f32x4, f32x8, fixed; the float paths with and without
//! anti-aliasing), and every pixel whose linear colour differs by a bit must lie inside the
//! damage. On the presets with animations (a light orbiting, a sphere moved, a sphere
//! bounced, a material recoloured, the camera moved) and on random scenes with random
//! changes. Each animation must change pixels (or the check would prove nothing), and an
//! empty damage must be caught missing them. The tightness (damaged ÷ changed pixels) is
//! printed per animation (`cargo test --release --test integration damage_tightness --
//! --nocapture`), the table of `docs/performance.md`.

use crate::common;
use shadeline::damage::Damage;
use shadeline::*;

const W: u32 = 64;
const H: u32 = 48;

/// What one comparison found, summed over paths and frames.
#[derive(Clone, Copy, Debug, Default)]
struct Tally {
    /// Frame pairs compared (one per path).
    pairs: u64,
    /// Pixels compared.
    pixels: u64,
    /// Pixels that differ between the two frames.
    changed: u64,
    /// Pixels inside the damage.
    damaged: u64,
    /// Changed pixels outside the damage: must be 0.
    missed: u64,
}

impl Tally {
    fn add(&mut self, o: Tally) {
        self.pairs += o.pairs;
        self.pixels += o.pixels;
        self.changed += o.changed;
        self.damaged += o.damaged;
        self.missed += o.missed;
    }
}

fn bits(frame: &[LinearRgb]) -> Vec<[u32; 3]> {
    frame
        .iter()
        .map(|c| [c.r.to_bits(), c.g.to_bits(), c.b.to_bits()])
        .collect()
}

/// Compares two frames of one path against `damage`.
fn compare<R: Render>(a: &R, b: &R, damage: &Damage, label: &str) -> Tally {
    let old = bits(&common::frame::<LinearRgb, _>(a));
    let new = bits(&common::frame::<LinearRgb, _>(b));
    let mut t = Tally {
        pairs: 1,
        pixels: old.len() as u64,
        damaged: damage.pixels(),
        ..Tally::default()
    };
    for y in 0..H {
        let row = damage.row(y);
        for x in 0..W {
            let i = (y * W + x) as usize;
            if old[i] != new[i] {
                t.changed += 1;
                if !row.contains(x) {
                    if t.missed == 0 {
                        eprintln!("{label}: pixel ({x}, {y}) changed outside the damage");
                    }
                    t.missed += 1;
                }
            }
        }
    }
    t
}

/// One path's frames of both scenes, with their damage.
fn path<R: Render, const S: usize, const L: usize>(
    shown: &Scene<S, L>,
    next: &Scene<S, L>,
    make: impl Fn(&Scene<S, L>) -> Option<R>,
    label: &str,
    damage_of: &impl Fn(&Scene<S, L>, &R, &Scene<S, L>, &R) -> Damage,
) -> Tally {
    let (Some(a), Some(b)) = (make(shown), make(next)) else {
        return Tally::default();
    };
    let damage = damage_of(shown, &a, next, &b);
    compare(&a, &b, &damage, label)
}

/// Every path's comparison of `shown` and `next` with `damage_of`'s damage.
fn check_with<const S: usize, const L: usize>(
    shown: &Scene<S, L>,
    next: &Scene<S, L>,
    label: &str,
    damage_of: DamageOf,
) -> Tally {
    let mut t = Tally::default();
    macro_rules! float {
        ($lanes:ty, $aa:expr) => {
            t.add(path(
                shown,
                next,
                |s| {
                    Prepared::<$lanes, S, L>::new(s, W, H)
                        .ok()
                        .map(|f| f.with_antialiasing($aa))
                },
                &format!("{label} {} aa={}", stringify!($lanes), $aa),
                &|a: &Scene<S, L>, fa: &_, b: &Scene<S, L>, fb: &_| damage_of.of(a, fa, b, fb),
            ))
        };
    }
    float!(Scalar, false);
    float!(Simd4, false);
    float!(Simd8, false);
    float!(Scalar, true);
    float!(Simd8, true);
    t.add(path(
        shown,
        next,
        |s| PreparedFixed::<S, L>::new(s, W, H).ok(),
        &format!("{label} fixed"),
        &|a: &Scene<S, L>, fa: &_, b: &Scene<S, L>, fb: &_| damage_of.of(a, fa, b, fb),
    ));
    t.add(path(
        shown,
        next,
        |s| {
            PreparedFixed::<S, L>::new(s, W, H)
                .ok()
                .map(|f| f.with_antialiasing(true))
        },
        &format!("{label} fixed aa"),
        &|a: &Scene<S, L>, fa: &_, b: &Scene<S, L>, fb: &_| damage_of.of(a, fa, b, fb),
    ));
    t
}

/// The damage under test, or an empty one (to show the check catches a miss).
#[derive(Clone, Copy)]
enum DamageOf {
    Between,
    Nothing,
}

impl DamageOf {
    fn of<const S: usize, const L: usize, R: Render>(
        self,
        a: &Scene<S, L>,
        fa: &R,
        b: &Scene<S, L>,
        fb: &R,
    ) -> Damage {
        match self {
            DamageOf::Between => Damage::between(a, fa, b, fb),
            DamageOf::Nothing => Damage::none(b, W, H),
        }
    }
}

fn check<const S: usize, const L: usize>(
    shown: &Scene<S, L>,
    next: &Scene<S, L>,
    label: &str,
) -> Tally {
    check_with(shown, next, label, DamageOf::Between)
}

/// `scene` rebuilt with its camera, spheres and lights passed through the closures; `None`
/// if the result is not a valid scene (a sphere moved into a sphere light).
fn rebuild<const S: usize, const L: usize>(
    scene: &Scene<S, L>,
    camera: impl Fn(Camera) -> Camera,
    sphere: impl Fn(usize, Sphere) -> Sphere,
    light: impl Fn(usize, Light) -> Light,
) -> Option<Scene<S, L>> {
    let mut out = Scene::new(camera(*scene.camera()), scene.background()).ok()?;
    for (i, s) in scene.spheres().iter().enumerate() {
        out.add_sphere(sphere(i, *s)).ok()?;
    }
    for (i, l) in scene.lights().iter().enumerate() {
        out.add_light(light(i, *l)).ok()?;
    }
    Some(out)
}

fn rotate_y(v: Vec3, a: f32) -> Vec3 {
    let (s, c) = a.sin_cos();
    Vec3::new(c * v.x + s * v.z, v.y, -s * v.x + c * v.z)
}

/// An animation: frame `k` of a scene.
#[derive(Clone, Copy, Debug)]
enum Animation {
    /// Light `i` turned about the vertical axis by 0.15 rad a frame.
    OrbitLight(usize),
    /// Sphere `i` moved along `x` by 0.2 a frame.
    Slide(usize),
    /// Sphere `i` lifted by `0.5·|sin(0.7k)|`.
    Bounce(usize),
    /// Sphere `i`'s albedo and specular weight changed every frame.
    Recolour(usize),
    /// The camera moved sideways by 0.1 a frame.
    Camera,
}

impl Animation {
    fn frame<const S: usize, const L: usize>(self, scene: &Scene<S, L>, k: u32) -> Scene<S, L> {
        let kf = k as f32;
        let out = match self {
            Animation::OrbitLight(i) => rebuild(
                scene,
                |c| c,
                |_, s| s,
                |j, l| {
                    if j != i {
                        l
                    } else {
                        l.moved(
                            |direction| rotate_y(direction, 0.15 * kf),
                            |position| rotate_y(position, 0.15 * kf),
                        )
                    }
                },
            ),
            Animation::Slide(i) => rebuild(
                scene,
                |c| c,
                |j, mut s| {
                    if j == i {
                        s.center.x += 0.2 * kf;
                    }
                    s
                },
                |_, l| l,
            ),
            Animation::Bounce(i) => rebuild(
                scene,
                |c| c,
                |j, mut s| {
                    if j == i {
                        s.center.y += 0.5 * (0.7 * kf).sin().abs();
                    }
                    s
                },
                |_, l| l,
            ),
            Animation::Recolour(i) => rebuild(
                scene,
                |c| c,
                |j, mut s| {
                    if j == i {
                        let t = 0.5 + 0.4 * (0.9 * kf).sin();
                        s.material.albedo = LinearRgb::new(t, 1.0 - t, 0.5 * t);
                        s.material.ks *= 1.0 - 0.2 * t;
                    }
                    s
                },
                |_, l| l,
            ),
            Animation::Camera => rebuild(
                scene,
                |mut c| {
                    c.position.x += 0.1 * kf;
                    c
                },
                |_, s| s,
                |_, l| l,
            ),
        };
        out.expect("the animation keeps the scene valid")
    }
}

/// Frames of each animation compared pairwise (frame k against frame k + 1).
const FRAMES: u32 = 4;

/// Runs `animation` on `scene` and checks every pair of consecutive frames.
fn animate<const S: usize, const L: usize>(
    name: &str,
    scene: &Scene<S, L>,
    animation: Animation,
) -> Tally {
    let mut t = Tally::default();
    let mut shown = animation.frame(scene, 0);
    for k in 1..FRAMES {
        let next = animation.frame(scene, k);
        t.add(check(
            &shown,
            &next,
            &format!("{name} {animation:?} frame {k}"),
        ));
        shown = next;
    }
    t
}

/// The presets and their animations.
fn preset_runs() -> Vec<(String, Tally)> {
    let mut out = Vec::new();
    let mut run = |name: &str, t: Tally| out.push((name.to_string(), t));
    let series = exponent_series().unwrap();
    let floor = floor().unwrap();
    let lamp = lamp().unwrap();
    let three = three_lights().unwrap();
    let materials = materials().unwrap();
    use Animation::*;
    for a in [OrbitLight(0), Slide(2), Recolour(1), Camera] {
        run(
            &format!("exponent_series {a:?}"),
            animate("series", &series, a),
        );
    }
    for a in [OrbitLight(0), Slide(2), Bounce(3), Recolour(1)] {
        run(&format!("floor {a:?}"), animate("floor", &floor, a));
    }
    for a in [OrbitLight(0), Bounce(2), Recolour(4)] {
        run(&format!("lamp {a:?}"), animate("lamp", &lamp, a));
    }
    for a in [OrbitLight(1), Bounce(1)] {
        run(
            &format!("three_lights {a:?}"),
            animate("three_lights", &three, a),
        );
    }
    for a in [Slide(0), Recolour(3)] {
        run(
            &format!("materials {a:?}"),
            animate("materials", &materials, a),
        );
    }
    out
}

/// A small deterministic generator for the random changes.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }
    fn unit(&mut self) -> f32 {
        (self.next() >> 40) as f32 / (1u64 << 24) as f32 * 2.0 - 1.0
    }
}

/// A random change of `scene`: one or two spheres moved, a light moved, a material
/// recoloured, or a sphere moved and another recoloured at once.
fn random_change(scene: &common::TestScene, rng: &mut Rng) -> Option<common::TestScene> {
    let n = scene.spheres().len();
    let moved = rng.below(n);
    let other = rng.below(n);
    let offset = Vec3::new(rng.unit(), rng.unit(), rng.unit()).scale(0.6);
    let kind = rng.below(5);
    let light = rng.below(scene.lights().len());
    let turn = rng.unit();
    let tint = LinearRgb::new(rng.unit().abs(), rng.unit().abs(), rng.unit().abs());
    rebuild(
        scene,
        |c| c,
        |j, mut s| {
            if (kind == 0 || kind == 3 || kind == 4) && j == moved {
                s.center = s.center + offset;
            }
            if kind == 3 && j == other {
                s.center = s.center - offset.scale(0.5);
            }
            if (kind == 2 || kind == 4) && j == other && j != moved {
                s.material.albedo = tint;
            }
            s
        },
        |i, l| {
            if kind != 1 || i != light {
                l
            } else {
                l.moved(
                    |direction| rotate_y(direction, turn),
                    |position| rotate_y(position, turn),
                )
            }
        },
    )
}

#[test]
fn damage_holds_every_changed_pixel_of_the_presets() {
    let mut total = Tally::default();
    for (name, t) in preset_runs() {
        assert_eq!(t.missed, 0, "{name}: {} changed pixels missed", t.missed);
        assert!(
            t.changed > 0,
            "{name}: no pixel changed, the check proves nothing"
        );
        total.add(t);
    }
    eprintln!("presets: {total:?}");
}

#[test]
fn damage_holds_every_changed_pixel_of_random_animations() {
    let scenes = common::random_scenes(120, 0xda3a6e);
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
    let mut total = Tally::default();
    let mut animated = 0;
    for (i, scene) in scenes.iter().enumerate() {
        let Some(next) = random_change(scene, &mut rng) else {
            continue;
        };
        let t = check(scene, &next, &format!("random scene {i}"));
        assert_eq!(t.missed, 0, "random scene {i}: {t:?}");
        total.add(t);
        animated += 1;
    }
    assert!(
        animated >= 100,
        "only {animated} random changes were valid scenes"
    );
    assert!(total.changed > 0);
    eprintln!("random: {animated} changes, {total:?}");
}

/// The check can fail: an empty damage misses the changes of each kind of animation.
#[test]
fn damage_check_catches_an_empty_damage() {
    let floor = floor().unwrap();
    for a in [
        Animation::OrbitLight(0),
        Animation::Bounce(2),
        Animation::Recolour(1),
    ] {
        let (shown, next) = (a.frame(&floor, 0), a.frame(&floor, 1));
        let t = check_with(&shown, &next, "empty", DamageOf::Nothing);
        assert!(t.missed > 0, "{a:?}: an empty damage was not caught");
    }
}

/// A moved sphere's damage is its outlines and its shadows, far less than the frame; a
/// recoloured one's is its outline only; a moved camera's is the whole frame.
#[test]
fn damage_is_local_where_the_change_is() {
    let floor = floor().unwrap();
    let frames = |a: Animation| {
        let (shown, next) = (a.frame(&floor, 0), a.frame(&floor, 1));
        let fa = Prepared::<Scalar, 6, 3>::new(&shown, W, H).unwrap();
        let fb = Prepared::<Scalar, 6, 3>::new(&next, W, H).unwrap();
        let d: Damage = Damage::between(&shown, &fa, &next, &fb);
        d
    };
    let all = u64::from(W * H);
    let moved = frames(Animation::Bounce(2));
    assert!(!moved.is_full_frame());
    assert!(moved.pixels() < all * 3 / 4, "{} of {all}", moved.pixels());
    let recoloured = frames(Animation::Recolour(1));
    assert!(
        recoloured.pixels() < all / 6,
        "{} of {all}",
        recoloured.pixels()
    );
    assert!(frames(Animation::Camera).is_full_frame());
    // Nothing changed: nothing damaged.
    let same = Prepared::<Scalar, 6, 3>::new(&floor, W, H).unwrap();
    let none: Damage = Damage::between(&floor, &same, &floor, &same);
    assert_eq!(none.pixels(), 0);
    assert_eq!(none.rows().count(), 0);
}

/// Rendering only the damage onto the shown frame gives the next frame, pixel for pixel.
#[test]
fn damage_render_updates_the_shown_frame_to_the_next() {
    let lamp = lamp().unwrap();
    let a = Animation::Bounce(2);
    let (shown, next) = (a.frame(&lamp, 0), a.frame(&lamp, 1));
    let fa = PreparedFixed::<6, 3>::new(&shown, W, H).unwrap();
    let fb = PreparedFixed::<6, 3>::new(&next, W, H).unwrap();
    let damage: Damage = Damage::between(&shown, &fa, &next, &fb);
    let mut display = common::frame::<Rgb565, _>(&fa);
    let mut buffer = [Rgb565::default(); 7];
    let mut sent = 0u64;
    damage
        .render(&fb, &mut buffer, |x, y, pixels: &[Rgb565]| {
            let at = (y * W + x) as usize;
            display[at..at + pixels.len()].copy_from_slice(pixels);
            sent += pixels.len() as u64;
            Ok::<(), RenderError>(())
        })
        .unwrap();
    assert_eq!(sent, damage.pixels());
    assert!(sent < u64::from(W * H));
    assert!(display == common::frame::<Rgb565, _>(&fb));
}

/// Prints the tightness table of `docs/performance.md`: per animation, the changed and the
/// damaged pixels over every path, and their ratio.
#[test]
fn damage_tightness() {
    println!("| scene and animation | frame pairs | changed px | damaged px | damaged ÷ changed |");
    println!("|---|---:|---:|---:|---:|");
    for (name, t) in preset_runs() {
        assert_eq!(t.missed, 0, "{name}");
        println!(
            "| {name} | {} | {} | {} | {:.2} |",
            t.pairs,
            t.changed,
            t.damaged,
            t.damaged as f64 / t.changed.max(1) as f64
        );
    }
}
