//! Random classic scenes for the crate's unit tests: the frames the narrow kernels take
//! (Phong and Blinn-Phong spheres under distant lights, seen from a camera on a circle
//! around them), drawn from one seeded generator so that every test that needs such
//! frames draws them the same way.

#![cfg(test)]

use crate::scene::{Camera, Light, Material, Model, Scene, Sphere};
use crate::vec3::Vec3;
use crate::LinearRgb;

/// One xorshift step of `state`, returned.
fn xorshift(state: &mut u64) -> u64 {
    *state ^= *state << 13;
    *state ^= *state >> 7;
    *state ^= *state << 17;
    *state
}

/// A xorshift generator of uniform `f32`s in `[lo, hi)`, from `seed`.
pub(crate) fn uniform(seed: u64) -> impl FnMut(f32, f32) -> f32 {
    let mut state = seed;
    move |lo: f32, hi: f32| {
        lo + (hi - lo) * ((xorshift(&mut state) >> 40) as f32 / (1u64 << 24) as f32)
    }
}

/// How [`random_classic_scene`] draws a scene.
pub(crate) struct Draw {
    /// Each centre coordinate within `±` this.
    pub half_extent: Vec3,
    /// The radii's range.
    pub radius: (f32, f32),
    /// Random materials, light colours and intensities and background; otherwise grey
    /// spheres (`kd` 0.8, `ks` 0.3) under white lights of intensity 1.
    pub varied: bool,
}

/// The draw of the narrow kernels' random frames: grey spheres of radius 0.3 to 1.5 within a
/// box of 6 × 4 × 6 around the origin.
pub(crate) const NARROW_DRAW: Draw = Draw {
    half_extent: Vec3::new(3.0, 2.0, 3.0),
    radius: (0.3, 1.5),
    varied: false,
};

/// Of the pixels of `hits` (rows of `width`) that hit a sphere, how many there are and how
/// many lie outside their sphere's shadow rows, `[first, end)` from `rows_of(sphere)`.
pub(crate) fn outside_rows(
    hits: &[crate::HitRecord],
    width: u32,
    rows_of: impl Fn(usize) -> (u16, u16),
) -> (usize, usize) {
    let (mut covered, mut outside) = (0, 0);
    for (k, hit) in hits.iter().enumerate() {
        let Some(sphere) = hit.sphere.map(usize::from) else {
            continue;
        };
        covered += 1;
        let y = (k as u32 / width) as u16;
        let (first, end) = rows_of(sphere);
        if !(first <= y && y < end) {
            outside += 1;
        }
    }
    (covered, outside)
}

/// One to six spheres with exponents `2⁰…2¹¹` under one to three distant lights, the
/// camera 9 units from the origin, looking at it with a field of view of 25° to 60°.
pub(crate) fn random_classic_scene<const S: usize, const L: usize>(
    next: &mut impl FnMut(f32, f32) -> f32,
    draw: &Draw,
) -> Scene<S, L> {
    let angle = next(-3.1, 3.1);
    let camera = Camera {
        position: Vec3::new(
            9.0 * libm::sinf(angle),
            next(-3.0, 3.0),
            9.0 * libm::cosf(angle),
        ),
        look_at: Vec3::new(0.0, 0.0, 0.0),
        up: Vec3::new(0.0, 1.0, 0.0),
        vfov_degrees: next(25.0, 60.0),
    };
    let red = if draw.varied { next(0.0, 0.3) } else { 0.1 };
    let mut scene = Scene::new(camera, LinearRgb::new(red, 0.1, 0.2)).unwrap();
    let e = draw.half_extent;
    for _ in 0..(next(1.0, 6.99) as usize) {
        let model = if next(0.0, 1.0) < 0.5 {
            Model::Phong
        } else {
            Model::BlinnPhong
        };
        let center = Vec3::new(next(-e.x, e.x), next(-e.y, e.y), next(-e.z, e.z));
        let radius = next(draw.radius.0, draw.radius.1);
        let (albedo, kd, ks) = if draw.varied {
            let albedo = LinearRgb::new(next(0.0, 1.0), next(0.0, 1.0), next(0.0, 1.0));
            (albedo, next(0.2, 0.9), next(0.0, 0.6))
        } else {
            (LinearRgb::new(0.5, 0.5, 0.5), 0.8, 0.3)
        };
        let material = Material {
            albedo,
            kd,
            ks,
            shininess: libm::powf(2.0, next(0.0, 11.0)),
            model,
        };
        scene
            .add_sphere(Sphere {
                center,
                radius,
                material,
            })
            .unwrap();
    }
    for _ in 0..(next(1.0, 3.99) as usize) {
        let direction = Vec3::new(next(-1.0, 1.0), next(-1.0, 0.2), next(-1.0, 1.0));
        let (color, intensity) = if draw.varied {
            (
                LinearRgb::new(1.0, next(0.7, 1.0), next(0.7, 1.0)),
                next(0.5, 2.0),
            )
        } else {
            (LinearRgb::new(1.0, 1.0, 1.0), 1.0)
        };
        scene
            .add_light(Light::Distant {
                direction,
                color,
                intensity,
            })
            .unwrap();
    }
    scene
}

/// One to five classic spheres resting on a floor sphere of radius 20 to 150 (each touching
/// its surface; the floor Phong or Lambert), under one to three distant lights from above, seen from a camera 5 to 9
/// units away at a height of 0.5 to 4 with a field of view of 30° to 60°.
pub(crate) fn random_floor_scene<const S: usize, const L: usize>(
    next: &mut impl FnMut(f32, f32) -> f32,
) -> Scene<S, L> {
    let mut scene = random_floor(next);
    for _ in 0..(next(1.0, 3.99) as usize) {
        let direction = Vec3::new(next(-1.0, 1.0), next(-1.0, -0.2), next(-1.0, 1.0));
        scene
            .add_light(Light::Distant {
                direction,
                color: LinearRgb::new(1.0, 1.0, 1.0),
                intensity: next(0.5, 1.5),
            })
            .unwrap();
    }
    scene
}

/// The spheres and camera of [`random_floor_scene`] under one or two point lights (radius 0)
/// 0.3 to 3 units above the floor, within 4 units of its top, and half the time a distant
/// fill light: a floor under lamps. A lamp drawn inside a sphere is drawn again.
pub(crate) fn random_lamp_scene<const S: usize, const L: usize>(
    next: &mut impl FnMut(f32, f32) -> f32,
) -> Scene<S, L> {
    let mut scene = random_floor(next);
    let lamps = next(1.0, 2.99) as usize;
    let mut added = 0;
    while added < lamps {
        let position = Vec3::new(next(-4.0, 4.0), next(0.3, 3.0), next(-4.0, 4.0));
        let lamp = Light::Point {
            position,
            color: LinearRgb::new(1.0, next(0.7, 1.0), next(0.6, 1.0)),
            intensity: next(5.0, 40.0),
            radius: 0.0,
        };
        added += usize::from(scene.add_light(lamp).is_ok());
    }
    if next(0.0, 1.0) < 0.5 {
        let direction = Vec3::new(next(-1.0, 1.0), next(-1.0, -0.2), next(-1.0, 1.0));
        let fill = Light::Distant {
            direction,
            color: LinearRgb::new(0.6, 0.7, 1.0),
            intensity: next(0.2, 0.6),
        };
        scene.add_light(fill).unwrap();
    }
    scene
}

/// The floor, spheres and camera of [`random_floor_scene`], with no light.
fn random_floor<const S: usize, const L: usize>(
    next: &mut impl FnMut(f32, f32) -> f32,
) -> Scene<S, L> {
    let angle = next(-3.1, 3.1);
    let distance = next(5.0, 9.0);
    let camera = Camera {
        position: Vec3::new(
            distance * libm::sinf(angle),
            next(0.5, 4.0),
            distance * libm::cosf(angle),
        ),
        look_at: Vec3::new(0.0, 0.5, 0.0),
        up: Vec3::new(0.0, 1.0, 0.0),
        vfov_degrees: next(30.0, 60.0),
    };
    let mut scene = Scene::new(camera, LinearRgb::new(0.05, 0.06, 0.1)).unwrap();
    let floor = next(20.0, 150.0);
    let grey = |shininess: f32| Material {
        albedo: LinearRgb::new(0.5, 0.5, 0.5),
        kd: 0.8,
        ks: 0.2,
        shininess,
        model: Model::Phong,
    };
    let floor_model = if next(0.0, 1.0) < 0.5 {
        Model::Lambert
    } else {
        Model::Phong
    };
    scene
        .add_sphere(Sphere {
            center: Vec3::new(0.0, -floor, 0.0),
            radius: floor,
            material: Material {
                model: floor_model,
                ..grey(8.0)
            },
        })
        .unwrap();
    for _ in 0..(next(1.0, 5.99) as usize) {
        let radius = next(0.3, 1.2);
        let (x, z) = (next(-3.0, 3.0), next(-3.0, 3.0));
        // On the floor sphere's surface: |centre − (0, −R, 0)| = R + r.
        let reach = floor + radius;
        let y = libm::sqrtf(reach * reach - x * x - z * z) - floor;
        let model = if next(0.0, 1.0) < 0.5 {
            Model::Phong
        } else {
            Model::BlinnPhong
        };
        let material = Material {
            albedo: LinearRgb::new(next(0.0, 1.0), next(0.0, 1.0), next(0.0, 1.0)),
            model,
            ..grey(libm::powf(2.0, next(0.0, 9.0)))
        };
        // Spheres that overlap another are refused by no path, so any draw is a scene.
        scene
            .add_sphere(Sphere {
                center: Vec3::new(x, y, z),
                radius,
                material,
            })
            .unwrap();
    }
    scene
}

/// `scene`'s spheres and lights at the capacities `S`, `L`: a preset (`Scene<6, 3>`) beside
/// the random scenes of a test, which share one type.
pub(crate) fn with_capacity<const S: usize, const L: usize, const S0: usize, const L0: usize>(
    scene: &Scene<S0, L0>,
) -> Scene<S, L> {
    let mut out = Scene::new(*scene.camera(), scene.background()).unwrap();
    for s in scene.spheres() {
        out.add_sphere(*s).unwrap();
    }
    for l in scene.lights() {
        out.add_light(*l).unwrap();
    }
    out
}

/// A pair of spheres and a distant light for the tests of the plane rule that leaves a
/// caster out of a sphere's mask (`src/fixed/narrow_caster_prepare.rs`,
/// `src/float/prepare.rs`), in `f64`: the sphere's radius `r`, the caster's `rc`, the lift
/// `eps`, `d = Δ` (the sphere's centre less the caster's) and the unit `l` toward the light.
pub(crate) struct PlanePair {
    pub r: f64,
    pub rc: f64,
    pub eps: f64,
    pub d: [f64; 3],
    pub l: [f64; 3],
}

fn dot64(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn unit64(v: [f64; 3]) -> [f64; 3] {
    let n = dot64(v, v).sqrt();
    v.map(|c| c / n)
}

/// A xorshift generator of uniform `f64`s in `[lo, hi)`, from `seed`.
pub(crate) fn uniform64(seed: u64) -> impl FnMut(f64, f64) -> f64 {
    let mut state = seed;
    move |lo: f64, hi: f64| {
        lo + (hi - lo) * ((xorshift(&mut state) >> 11) as f64 / (1u64 << 53) as f64)
    }
}

impl PlanePair {
    /// A random pair in units of `unit`: `r` from 0.05 to 3, the caster that size or 50 to
    /// 200 (a floor), `ε` from 10⁻⁴ to 0.05, their surfaces from 1% of `r` into each other
    /// to half `r` apart along a random direction (`d` in whole raw units where `unit` is
    /// above 1), and a random light.
    pub(crate) fn random(next: &mut impl FnMut(f64, f64) -> f64, unit: f64) -> PlanePair {
        let (r, eps) = (next(0.05, 3.0) * unit, next(1.0e-4, 0.05) * unit);
        let rc = if next(0.0, 1.0) < 0.5 {
            next(0.05, 3.0)
        } else {
            next(50.0, 200.0)
        } * unit;
        // Whole raw units where `unit` is the fixed path's.
        let round = |x: f64| if unit > 1.0 { x.round() } else { x };
        let n = unit64([next(-1.0, 1.0), next(-1.0, 1.0), next(-1.0, 1.0)]);
        let apart = round(r + rc + next(-0.01, 0.5) * r);
        let d = n.map(|c| round(c * apart));
        let l = unit64([next(-1.0, 1.0), next(-1.0, 1.0), next(-1.0, 1.0)]);
        PlanePair { r, rc, eps, d, l }
    }

    /// The pair moved along `Δ` until the surfaces touch, as a sphere resting on another (`Δ`
    /// in whole raw units where `unit` is above 1, as [`Self::random`] makes it).
    pub(crate) fn touching(mut self, unit: f64) -> PlanePair {
        let len = dot64(self.d, self.d).sqrt();
        let apart = self.r + self.rc;
        self.d = self.d.map(|c| {
            let c = c * apart / len;
            if unit > 1.0 {
                c.round()
            } else {
                c
            }
        });
        self
    }

    /// `|Δ|` and `n·L`.
    pub(crate) fn len_and_delta(&self) -> (f64, f64) {
        let len = dot64(self.d, self.d).sqrt();
        (len, dot64(self.d, self.l) / len)
    }

    /// The least distance from the plane of a lifted point `(r + ε)·N` whose `N·L` passes
    /// the own-shadow limit `s = √(1 − r²/(r + ε)²)`: `|Δ| − r_c − (r + ε)·cos(asin δ −
    /// asin s)`; `None` where `δ ≤ s`.
    pub(crate) fn clearance(&self) -> Option<f64> {
        let (len, delta) = self.len_and_delta();
        let lift = self.r + self.eps;
        let s = (self.eps * (2.0 * self.r + self.eps)).sqrt() / lift;
        (delta > s).then(|| len - self.rc - lift * (delta.asin() - s.asin()).cos())
    }

    /// Asserts that no shadow ray along `l` from a lifted point `(r + ε)·N` of the sphere
    /// with `N·L ≥ −s` passes within `reach` of the caster's centre: at the worst such
    /// point (on the limit, turned from `L` toward `−n` as far as it goes) and at eight
    /// random ones.
    pub(crate) fn assert_no_ray_within(
        &self,
        next: &mut impl FnMut(f64, f64) -> f64,
        s: f64,
        reach: f64,
    ) {
        let (d, l) = (self.d, self.l);
        for normal in self.tested_normals(next, s) {
            // The sphere's centre at 0, the caster's at −Δ; the ray from O along L.
            let v: [f64; 3] = core::array::from_fn(|j| -d[j] - (self.r + self.eps) * normal[j]);
            let b = dot64(v, l);
            let closest2 = if b <= 0.0 {
                dot64(v, v)
            } else {
                dot64(v, v) - b * b
            };
            assert!(
                closest2 > reach * reach,
                "a ray from N = {normal:?} comes within {reach} of the caster: r {}, rc {}, \
                 ε {}, Δ {d:?}, L {l:?}",
                self.r,
                self.rc,
                self.eps
            );
        }
    }

    /// The normals of the sphere's pixels that test casters (`N·L ≥ −s`) the assertions
    /// try: the one nearest `−Δ` (on the limit, turned from `L` toward `−n` as far as it
    /// goes: the lifted point nearest the caster), then eight random ones.
    fn tested_normals(&self, next: &mut impl FnMut(f64, f64) -> f64, s: f64) -> [[f64; 3]; 9] {
        let l = self.l;
        let minus_n = unit64(self.d.map(|c| -c));
        let away = unit64(core::array::from_fn(|j| {
            minus_n[j] - dot64(minus_n, l) * l[j]
        }));
        let worst: [f64; 3] = core::array::from_fn(|j| -s * l[j] + (1.0 - s * s).sqrt() * away[j]);
        let mut normals = [worst; 9];
        for normal in normals.iter_mut().skip(1) {
            *normal = loop {
                let m = unit64([next(-1.0, 1.0), next(-1.0, 1.0), next(-1.0, 1.0)]);
                if dot64(m, l) >= -s {
                    break m;
                }
            };
        }
        normals
    }

    /// Whether every shadow ray from a lifted point whose `N·L` passes the own-shadow limit
    /// (as [`Self::clearance`]) moves away from the caster's centre and, where it starts
    /// inside the caster, leaves it within `ε`: at the least `b = (O − C_k)·L` and the
    /// least `|O − C_k|` over those points, each a bound for all of them.
    pub(crate) fn recedes(&self) -> bool {
        let (len, delta) = self.len_and_delta();
        let lift = self.r + self.eps;
        let s = (self.eps * (2.0 * self.r + self.eps)).sqrt() / lift;
        if delta <= s {
            return false;
        }
        let b = len * delta - lift * s;
        let phi = delta.asin() - s.asin();
        let x = ((len - lift * phi.cos()).powi(2) + (lift * phi.sin()).powi(2)).sqrt();
        b >= 0.0 && (self.rc - x) * (self.rc + x) <= self.eps * (2.0 * b + self.eps)
    }

    /// Asserts that every shadow ray along `l` from a lifted point `(r + ε)·N` of the
    /// sphere with `N·L ≥ −s` moves away from the caster's centre (`b = (O − C_k)·L ≥ 0`)
    /// and, where it starts inside the caster, leaves it within `ε`
    /// (`r_c² − |O − C_k|² ≤ ε·(2b + ε)`, the fixed path's exact ray's rule): at the
    /// lifted point nearest the caster and at eight random ones.
    pub(crate) fn assert_rays_recede(&self, next: &mut impl FnMut(f64, f64) -> f64, s: f64) {
        let (d, l) = (self.d, self.l);
        for normal in self.tested_normals(next, s) {
            // The sphere's centre at 0, the caster's at −Δ: o = O − C_k.
            let o: [f64; 3] = core::array::from_fn(|j| d[j] + (self.r + self.eps) * normal[j]);
            let b = dot64(o, l);
            let inside = self.rc * self.rc - dot64(o, o);
            assert!(
                b >= 0.0 && inside <= self.eps * (2.0 * b + self.eps),
                "a ray from N = {normal:?} meets the caster: b {b}, r_c² − |O − C_k|² {inside}, \
                 r {}, rc {}, ε {}, Δ {d:?}, L {l:?}",
                self.r,
                self.rc,
                self.eps
            );
        }
    }
}
