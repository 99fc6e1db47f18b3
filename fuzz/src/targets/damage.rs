//! Fuzz target `damage`: the damage between a fuzzed scene and a changed copy of it never
//! misses a changed pixel. The change moves a sphere, turns or moves a light, recolours a
//! sphere or moves the camera ([`ChangeIn`]); both frames are rendered in full, at most
//! [`MAX_HEIGHT`] rows high, on the scalar, 4-lane, 8-lane and fixed paths (the float ones
//! with and without anti-aliased edges), and every pixel whose linear colour differs by a
//! bit must lie inside `Damage::between` of that path's two frames. A path that refuses
//! either scene is skipped (the fixed path's range refusals).

use crate::{build_scene, FuzzScene, SceneInput, LIGHTS, SPHERES};
use arbitrary::Arbitrary;
use shadeline::damage::Damage;
use shadeline::{LinearRgb, Prepared, PreparedFixed, Render, Scalar, Scene, Simd4, Simd8, Vec3};

/// Tallest frame the target renders: the damage is a question of geometry, not of size.
pub const MAX_HEIGHT: u32 = 40;

/// The change from the first frame to the second.
#[derive(Arbitrary, Clone, Debug)]
pub struct ChangeIn {
    /// What changes: `kind % 5` is a sphere moved, a light turned about the vertical axis
    /// (a distant one) or moved (a point one), a sphere recoloured, the camera moved, or a
    /// sphere moved and another recoloured.
    pub kind: u8,
    /// Which sphere or light (modulo their number).
    pub index: u8,
    /// How much: an offset of `amount/32` scene units, a turn of `amount[0]/32` radians, or
    /// an albedo of `|amount|/127`.
    pub amount: [i8; 3],
}

/// A damage input: the change first, then the scene (whose last field takes the rest of the
/// input, as in the other structured targets).
#[derive(Arbitrary, Clone, Debug)]
pub struct DamageInput {
    /// The change.
    pub change: ChangeIn,
    /// The first frame's scene.
    pub scene: SceneInput,
}

/// `scene` with `change` applied, or `None` if that is not a valid scene.
fn changed(scene: &FuzzScene, change: &ChangeIn) -> Option<FuzzScene> {
    let [a, b, c] = change.amount.map(|v| f32::from(v) / 32.0);
    let offset = Vec3::new(a, b, c);
    let kind = change.kind % 5;
    let n = scene.spheres().len().max(1);
    let sphere = usize::from(change.index) % n;
    let other = (sphere + 1) % n;
    let light = usize::from(change.index) % scene.lights().len().max(1);
    let mut camera = *scene.camera();
    if kind == 3 {
        camera.position = camera.position + offset;
    }
    let mut out = Scene::new(camera, scene.background()).ok()?;
    for (i, s) in scene.spheres().iter().enumerate() {
        let mut s = *s;
        if (kind == 0 || kind == 4) && i == sphere {
            s.center = s.center + offset;
        }
        if (kind == 2 && i == sphere) || (kind == 4 && i == other && other != sphere) {
            let [r, g, b] = change.amount.map(|v| f32::from(v).abs() / 127.0);
            s.material.albedo = LinearRgb::new(r, g, b);
        }
        out.add_sphere(s).ok()?;
    }
    for (i, l) in scene.lights().iter().enumerate() {
        let mut l = *l;
        if kind == 1 && i == light {
            let (sin, cos) = a.sin_cos();
            let turn = |v: Vec3| Vec3::new(cos * v.x + sin * v.z, v.y, -sin * v.x + cos * v.z);
            l = l.moved(turn, |position| position + offset);
        }
        out.add_light(l).ok()?;
    }
    Some(out)
}

/// The bits of a frame's linear colour.
fn frame<R: Render>(r: &R) -> Vec<[u32; 3]> {
    let (w, h) = (r.width() as usize, r.height() as usize);
    let mut out = vec![LinearRgb::default(); w * h];
    r.render_frame(&mut out).expect("a prepared frame renders");
    out.iter()
        .map(|c| [c.r.to_bits(), c.g.to_bits(), c.b.to_bits()])
        .collect()
}

/// Both frames of one path against their damage; panics on a miss.
fn compare<R: Render>(name: &str, shown: &FuzzScene, a: Option<R>, next: &FuzzScene, b: Option<R>) {
    let (Some(a), Some(b)) = (a, b) else {
        return;
    };
    let damage: Damage = Damage::between(shown, &a, next, &b);
    let (old, new) = (frame(&a), frame(&b));
    let w = a.width();
    for (i, (o, n)) in old.iter().zip(&new).enumerate() {
        if o != n {
            let (x, y) = (i as u32 % w, i as u32 / w);
            assert!(
                damage.contains(x, y),
                "{name}: pixel ({x}, {y}) changed outside the damage\n{shown:?}\n{next:?}"
            );
        }
    }
}

/// The target's check: panics if a changed pixel lies outside the damage.
pub fn check(input: &DamageInput) {
    let Some(shown) = build_scene(&input.scene) else {
        return;
    };
    let Some(next) = changed(&shown, &input.change) else {
        return;
    };
    let (w, h) = input.scene.size();
    let h = h.min(MAX_HEIGHT);
    macro_rules! float {
        ($lanes:ty, $aa:expr) => {{
            let make = |s: &FuzzScene| {
                Prepared::<$lanes, SPHERES, LIGHTS>::new(s, w, h)
                    .ok()
                    .map(|f| f.with_antialiasing($aa))
            };
            compare(stringify!($lanes), &shown, make(&shown), &next, make(&next));
        }};
    }
    float!(Scalar, false);
    float!(Simd4, false);
    float!(Simd8, false);
    float!(Scalar, true);
    let fixed = |s: &FuzzScene| PreparedFixed::<SPHERES, LIGHTS>::new(s, w, h).ok();
    compare("fixed", &shown, fixed(&shown), &next, fixed(&next));
    let fixed_aa = |s: &FuzzScene| {
        PreparedFixed::<SPHERES, LIGHTS>::new(s, w, h)
            .ok()
            .map(|f| f.with_antialiasing(true))
    };
    compare("fixed aa", &shown, fixed_aa(&shown), &next, fixed_aa(&next));
}
