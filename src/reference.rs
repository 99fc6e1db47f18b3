//! The `f64` reference renderer: the truth every path is measured against.
//!
//! Written straight from the formulas of the model ([`crate::brdf`], [`crate::Camera`],
//! [`crate::Light`]), one pixel at a time, in `f64`, sharing no code with the kernels: its own
//! vector type, its own camera basis, the textbook quadratic, `libm`'s correctly rounded `pow`.
//! It reads the scene's numbers and the one model constant every path shares,
//! [`Scene::ray_epsilon`](crate::Scene::ray_epsilon). It is slow on purpose (no spans, no
//! prepare step), and it is not meant for firmware, though it is `no_std` like the rest.
//!
//! It is also the one renderer of sphere lights (point lights with a `radius`): it
//! integrates each over the cone of directions toward the light's sphere, with a shadow ray
//! per direction, which gives wider highlights, exact diffuse light above the horizon (the
//! same as the point at the centre) and penumbrae, to measure the paths against when they
//! render sphere lights too.

use crate::pixel::{HitRecord, LinearRgb};
use crate::render::RenderError;
use crate::scene::{Light, Material, Model, Scene, Surface};

/// One pixel as the reference sees it.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct RefPixel {
    /// Linear colour, unclamped.
    pub color: [f64; 3],
    /// Which sphere the primary ray hit and which lights were blocked there.
    pub hit: HitRecord,
}

/// The arriving-light cap of the model (see `MAX_ARRIVING` in the prepare step): a point
/// light at zero distance delivers this much, not infinity.
const ARRIVING_CAP: f64 = 1.0e30;

#[derive(Clone, Copy, Debug, Default)]
struct D3 {
    x: f64,
    y: f64,
    z: f64,
}

impl D3 {
    fn of(v: crate::Vec3) -> D3 {
        D3 {
            x: v.x as f64,
            y: v.y as f64,
            z: v.z as f64,
        }
    }
    fn add(self, o: D3) -> D3 {
        D3 {
            x: self.x + o.x,
            y: self.y + o.y,
            z: self.z + o.z,
        }
    }
    fn sub(self, o: D3) -> D3 {
        D3 {
            x: self.x - o.x,
            y: self.y - o.y,
            z: self.z - o.z,
        }
    }
    fn mul(self, s: f64) -> D3 {
        D3 {
            x: self.x * s,
            y: self.y * s,
            z: self.z * s,
        }
    }
    fn dot(self, o: D3) -> f64 {
        self.x * o.x + self.y * o.y + self.z * o.z
    }
    fn cross(self, o: D3) -> D3 {
        D3 {
            x: self.y * o.z - self.z * o.y,
            y: self.z * o.x - self.x * o.z,
            z: self.x * o.y - self.y * o.x,
        }
    }
    fn len(self) -> f64 {
        libm::sqrt(self.dot(self))
    }
    fn unit(self) -> D3 {
        let l = self.len();
        if l > 0.0 {
            self.mul(1.0 / l)
        } else {
            D3::default()
        }
    }
}

/// Nearest `t > eps` where `origin + t·dir` (`dir` unit) meets the sphere, textbook quadratic.
fn intersect(origin: D3, dir: D3, center: D3, radius: f64, eps: f64) -> Option<f64> {
    let oc = origin.sub(center);
    let b = oc.dot(dir);
    let c = oc.dot(oc) - radius * radius;
    let disc = b * b - c;
    if disc < 0.0 {
        return None;
    }
    let root = libm::sqrt(disc);
    let (t0, t1) = (-b - root, -b + root);
    if t0 > eps {
        Some(t0)
    } else if t1 > eps {
        Some(t1)
    } else {
        None
    }
}

/// The BRDF `f(L, V)` of a normalized model or Lambert, per channel, straight from the
/// formulas of [`crate::brdf`]'s table: `kd·albedo/π` (times `1 − F` for a dielectric with an
/// `ior`, nothing for a metal) plus `F·Σ wₖ·cₖ·max(0, c)^nₖ`, `c = R·V` with
/// `cₖ = (nₖ + 2)/(2π)` or `c = N·H` with `cₖ = (nₖ + 2)(nₖ + 4)/(8π(2^(−nₖ/2) + nₖ))`, and
/// Schlick's `F = F₀ + (1 − F₀)(1 − L·H)⁵`.
fn normalized_brdf(m: &Material, n: D3, l: D3, v: D3) -> [f64; 3] {
    use core::f64::consts::PI;
    let albedo = [m.albedo.r as f64, m.albedo.g as f64, m.albedo.b as f64];
    let diffuse = albedo.map(|a| m.kd as f64 * a / PI);
    let h = l.add(v);
    let h = if h.len() > 0.0 {
        h.unit()
    } else {
        D3::default()
    };
    let (spec, blinn) = match m.model {
        Model::NormalizedPhong(spec) => (spec, false),
        Model::NormalizedBlinnPhong(spec) => (spec, true),
        Model::OrenNayar { roughness } => {
            let on = oren_nayar_factor(roughness as f64, n, l, v);
            return diffuse.map(|d| d * on);
        }
        Model::Ggx(micro) => {
            let lobe = m.ks as f64 * ggx_lobe(micro.roughness as f64, n, l, v, h);
            return surface_mix(micro.surface, diffuse, lobe, l, h);
        }
        _ => return diffuse,
    };
    let cosine = if blinn {
        n.dot(h)
    } else {
        // R = 2(N·L)N − L
        n.mul(2.0 * n.dot(l)).sub(l).dot(v)
    };
    let mut lobes = 0.0;
    let first = (m.ks, m.shininess);
    let more = spec.more_lobes.map(|lobe| (lobe.weight, lobe.shininess));
    for (w, e) in core::iter::once(first).chain(more) {
        let (w, e) = (w as f64, e as f64);
        let c = if blinn {
            (e + 2.0) * (e + 4.0) / (8.0 * PI * (libm::exp2(-e / 2.0) + e))
        } else {
            (e + 2.0) / (2.0 * PI)
        };
        if cosine > 0.0 {
            lobes += w * c * libm::pow(cosine.min(1.0), e);
        }
    }
    surface_mix(spec.surface, diffuse, lobes, l, h)
}

/// The diffuse lobe and the specular `lobes` combined as the surface combines them:
/// unchanged (dielectric without `ior`), with Schlick's `F` on the lobes and `1 − F` on the
/// diffuse lobe (with `ior`), or tinted by the metal's `F` with no diffuse lobe.
fn surface_mix(surface: Surface, diffuse: [f64; 3], lobes: f64, l: D3, h: D3) -> [f64; 3] {
    let schlick = libm::pow(1.0 - l.dot(h).clamp(0.0, 1.0), 5.0);
    let fresnel = |f0: f64| f0 + (1.0 - f0) * schlick;
    match surface {
        Surface::Dielectric { ior: None } => diffuse.map(|d| d + lobes),
        Surface::Dielectric { ior: Some(ior) } => {
            let r = (ior as f64 - 1.0) / (ior as f64 + 1.0);
            let f0 = r * r;
            let f = fresnel(f0);
            diffuse.map(|d| d * (1.0 - f) + f * lobes)
        }
        Surface::Metal(metal) => {
            let c = metal.f0();
            [c.r, c.g, c.b].map(|f0| fresnel(f0 as f64) * lobes)
        }
    }
}

/// Oren–Nayar's factor on `ρ/π` (the qualitative model of 1994) from the angles themselves:
/// `A + B·max(0, cos(φᵢ − φₒ))·sin(max(θᵢ, θₒ))·tan(min(θᵢ, θₒ))`, the azimuths measured in
/// the tangent plane.
fn oren_nayar_factor(sigma: f64, n: D3, l: D3, v: D3) -> f64 {
    let s2 = sigma * sigma;
    let a = 1.0 - 0.5 * s2 / (s2 + 0.33);
    let b = 0.45 * s2 / (s2 + 0.09);
    let theta_i = libm::acos(n.dot(l).clamp(-1.0, 1.0));
    let theta_o = libm::acos(n.dot(v).clamp(-1.0, 1.0));
    let lt = l.sub(n.mul(n.dot(l)));
    let vt = v.sub(n.mul(n.dot(v)));
    let cos_phi = if lt.len() > 0.0 && vt.len() > 0.0 {
        lt.unit().dot(vt.unit())
    } else {
        0.0
    };
    let (alpha, beta) = (theta_i.max(theta_o), theta_i.min(theta_o));
    a + b * cos_phi.max(0.0) * libm::sin(alpha) * libm::tan(beta)
}

/// The GGX microfacet lobe `D·G₂/(4 cos θᵢ cos θₒ)` (no Fresnel) in its angular form:
/// `D = α²/(π cos⁴θ_h (α² + tan²θ_h)²)`, `G₂ = 1/(1 + Λ(θᵢ) + Λ(θₒ))`,
/// `Λ(θ) = (√(1 + α²tan²θ) − 1)/2`, `α = roughness²`. A view at or below the horizon takes
/// the lobe's limit there (`cos θₒ` clamped to `10⁻¹²`).
fn ggx_lobe(roughness: f64, n: D3, l: D3, v: D3, h: D3) -> f64 {
    use core::f64::consts::PI;
    let alpha = roughness * roughness;
    let a2 = alpha * alpha;
    let cos_i = n.dot(l);
    let cos_o = n.dot(v).max(1e-12);
    let cos_h = n.dot(h);
    if cos_i <= 0.0 || cos_h <= 0.0 {
        return 0.0;
    }
    let tan2 = |c: f64| (1.0 - c * c).max(0.0) / (c * c);
    let t = a2 + tan2(cos_h);
    let c2 = cos_h * cos_h;
    let d = a2 / (PI * c2 * c2 * t * t);
    let lambda = |c: f64| (libm::sqrt(1.0 + a2 * tan2(c)) - 1.0) / 2.0;
    let g2 = 1.0 / (1.0 + lambda(cos_i) + lambda(cos_o));
    d * g2 / (4.0 * cos_i * cos_o)
}

/// Strata per axis of a sphere light's cone: the reference integrates a sphere light over
/// `SPHERE_LIGHT_STRATA²` directions of equal solid angle per pixel (`cos θ` evenly from 1 to
/// the cone's rim, the azimuth evenly around it, one direction through each cell's middle).
/// Against twice as many per axis, the frames of `tests/sphere_lights.rs` differ by at most
/// 0.34 of an 8-bit level.
pub const SPHERE_LIGHT_STRATA: usize = 64;

/// A point light with a radius, as the reference integrates it.
struct SphereLight {
    center: D3,
    radius: f64,
    /// `colour·intensity`, the light's power per channel.
    power: [f64; 3],
}

impl SphereLight {
    /// Integrates the light over its solid angle as seen from the surface point `p`: the cone
    /// of directions toward the sphere, of half-angle `α` with `sin α = R/d`, split into
    /// `strata × strata` cells of equal solid angle (`cos θ` evenly from 1 to `cos α`, `φ`
    /// evenly around the axis) and one direction through the middle of each. Each direction
    /// carries the sphere's radiance `power/(4π²R²)` times its cell's solid angle and goes
    /// to `arrive` with the shadow ray from `origin` to the sphere's near surface. Returns
    /// whether every direction was blocked.
    ///
    /// As `R → 0` the sum is the point light's `power/(4πd²)`; with the whole cone above the
    /// horizon and unblocked, a Lambertian surface gets exactly that too, whatever `R` (the
    /// tests check both).
    fn integrate(
        &self,
        p: D3,
        origin: D3,
        strata: usize,
        arrive: &mut impl FnMut(D3, [f64; 3], f64) -> bool,
    ) -> bool {
        let to_center = self.center.sub(p);
        let d = to_center.len();
        let axis = to_center.unit();
        let sin_a = (self.radius / d).min(1.0);
        let cos_a = libm::sqrt((1.0 - sin_a * sin_a).max(0.0));
        // An orthonormal basis around the axis.
        let helper = if axis.x.abs() < 0.9 {
            D3 {
                x: 1.0,
                y: 0.0,
                z: 0.0,
            }
        } else {
            D3 {
                x: 0.0,
                y: 1.0,
                z: 0.0,
            }
        };
        let b1 = axis.cross(helper).unit();
        let b2 = axis.cross(b1);
        let cells = (strata * strata) as f64;
        let solid_angle = 2.0 * core::f64::consts::PI * (1.0 - cos_a);
        let radiance =
            1.0 / (4.0 * core::f64::consts::PI * core::f64::consts::PI * self.radius * self.radius);
        let carried = self.power.map(|c| c * radiance * solid_angle / cells);
        let mut all_blocked = true;
        for i in 0..strata {
            let cos_t = 1.0 - (i as f64 + 0.5) / strata as f64 * (1.0 - cos_a);
            let sin_t = libm::sqrt((1.0 - cos_t * cos_t).max(0.0));
            for j in 0..strata {
                let phi = 2.0 * core::f64::consts::PI * (j as f64 + 0.5) / strata as f64;
                let l = axis
                    .mul(cos_t)
                    .add(b1.mul(sin_t * libm::cos(phi)))
                    .add(b2.mul(sin_t * libm::sin(phi)))
                    .unit();
                // The near surface of the light along `l` from `origin`; at the cone's rim the
                // lifted origin may just miss it: then the closest approach.
                let oc = origin.sub(self.center);
                let b = oc.dot(l);
                let disc = b * b - (oc.dot(oc) - self.radius * self.radius);
                let t_max = -b - libm::sqrt(disc.max(0.0));
                if !arrive(l, carried, t_max) {
                    all_blocked = false;
                }
            }
        }
        all_blocked
    }
}

/// The reference colour and hit record of pixel `(x, y)` of a `width × height` image.
///
/// A sphere light (a point light with a radius) is integrated over its solid angle with
/// [`SPHERE_LIGHT_STRATA`]² directions; its bit in the hit record is set where every one of
/// them is blocked (the umbra).
pub fn shade_pixel<const S: usize, const L: usize>(
    scene: &Scene<S, L>,
    width: u32,
    height: u32,
    x: u32,
    y: u32,
) -> RefPixel {
    shade_pixel_with_strata(scene, width, height, x, y, SPHERE_LIGHT_STRATA)
}

/// [`shade_pixel`] with `strata × strata` directions per sphere light (at least 1): the
/// tests use it to show that [`SPHERE_LIGHT_STRATA`] is enough.
pub fn shade_pixel_with_strata<const S: usize, const L: usize>(
    scene: &Scene<S, L>,
    width: u32,
    height: u32,
    x: u32,
    y: u32,
    strata: usize,
) -> RefPixel {
    let strata = strata.max(1);
    let (eye, dir) = primary_ray(scene, width, height, x, y);
    let eps = scene.ray_epsilon() as f64;
    let Some((k, t)) = nearest_hit(scene, eye, dir, eps) else {
        let bg = scene.background();
        return RefPixel {
            color: [bg.r as f64, bg.g as f64, bg.b as f64],
            hit: HitRecord::default(),
        };
    };
    let sphere = &scene.spheres()[k];
    let m = &sphere.material;
    let p = eye.add(dir.mul(t));
    let n = p.sub(D3::of(sphere.center)).mul(1.0 / sphere.radius as f64);
    let at = Surface3 {
        n,
        v: dir.mul(-1.0),
        shadow_origin: p.add(n.mul(eps)),
        eps,
    };
    let mut sums = Sums::default();
    let mut shadowed = 0u32;
    // One arriving direction `l` (unit, toward the light) carrying `arriving`, with a shadow
    // ray of length `t_max`: added to the sums unless a sphere blocks it (then `true`).
    let mut arrive = |l: D3, arriving: [f64; 3], t_max: f64| -> bool {
        at.arrive(scene, m, &mut sums, (l, arriving, t_max))
    };
    for (li, light) in scene.lights().iter().enumerate() {
        let blocked = light_arrivals(light, (p, at.shadow_origin), strata, &mut arrive);
        if blocked && li < 32 {
            shadowed |= 1 << li;
        }
    }
    RefPixel {
        color: sums.combine(m),
        hit: HitRecord {
            sphere: Some(k as u16),
            shadowed,
        },
    }
}

/// One light's arrival at the hit `p` (shadow rays from `shadow_origin`): each arriving
/// direction, with what it carries and the shadow ray's length, goes to `arrive` (a sphere
/// light's every sample); whether the light is blocked.
fn light_arrivals(
    light: &Light,
    (p, shadow_origin): (D3, D3),
    strata: usize,
    arrive: &mut impl FnMut(D3, [f64; 3], f64) -> bool,
) -> bool {
    match *light {
        Light::Distant {
            direction,
            color,
            intensity,
        } => {
            let i = intensity as f64;
            arrive(
                D3::of(direction).unit().mul(-1.0),
                [color.r as f64 * i, color.g as f64 * i, color.b as f64 * i],
                f64::INFINITY,
            )
        }
        Light::Point {
            position,
            color,
            intensity,
            radius,
        } if radius > 0.0 => {
            let power = [color.r, color.g, color.b].map(|c| c as f64 * intensity as f64);
            let light = SphereLight {
                center: D3::of(position),
                radius: radius as f64,
                power,
            };
            light.integrate(p, shadow_origin, strata, arrive)
        }
        Light::Point {
            position,
            color,
            intensity,
            ..
        } => {
            let (l, arriving, dist) = point_arrival(p, D3::of(position), color, intensity);
            arrive(l, arriving, dist)
        }
    }
}

/// The eye and the unit primary direction through the centre of pixel `(x, y)`.
fn primary_ray<const S: usize, const L: usize>(
    scene: &Scene<S, L>,
    width: u32,
    height: u32,
    x: u32,
    y: u32,
) -> (D3, D3) {
    let cam = scene.camera();
    let eye = D3::of(cam.position);
    let forward = D3::of(cam.look_at).sub(eye).unit();
    let right = forward.cross(D3::of(cam.up)).unit();
    let up = right.cross(forward);
    let tan = libm::tan((cam.vfov_degrees as f64).to_radians() / 2.0);
    let (w, h) = (width as f64, height as f64);
    let px = (2.0 * (x as f64 + 0.5) / w - 1.0) * (w / h) * tan;
    let py = (1.0 - 2.0 * (y as f64 + 0.5) / h) * tan;
    (eye, right.mul(px).add(up.mul(py)).add(forward).unit())
}

/// The nearest sphere along the ray and its `t`, the first one winning a tie.
fn nearest_hit<const S: usize, const L: usize>(
    scene: &Scene<S, L>,
    eye: D3,
    dir: D3,
    eps: f64,
) -> Option<(usize, f64)> {
    let mut nearest: Option<(usize, f64)> = None;
    for (k, s) in scene.spheres().iter().enumerate() {
        if let Some(t) = intersect(eye, dir, D3::of(s.center), s.radius as f64, eps) {
            if nearest.is_none_or(|(_, best)| t < best) {
                nearest = Some((k, t));
            }
        }
    }
    nearest
}

/// A point light's unit direction from `p`, the light arriving there (`I/(4πd²)` per
/// channel, capped) and its distance.
fn point_arrival(p: D3, position: D3, color: LinearRgb, intensity: f32) -> (D3, [f64; 3], f64) {
    let lv = position.sub(p);
    let dist = lv.len();
    let scale = intensity as f64 / (4.0 * core::f64::consts::PI * dist * dist);
    let a = |c: f32| {
        let v = c as f64 * scale;
        if v.is_nan() || v > ARRIVING_CAP {
            ARRIVING_CAP
        } else {
            v
        }
    };
    (lv.unit(), [a(color.r), a(color.g), a(color.b)], dist)
}

/// The hit as the lights see it: the normal, the direction toward the eye, the shadow
/// rays' origin and the ray epsilon.
struct Surface3 {
    n: D3,
    v: D3,
    shadow_origin: D3,
    eps: f64,
}

/// The lights' sums at a pixel: the classic models' `Σ I·cos θ_i` and `Σ I·lobe`, and the
/// normalized models' and Lambert's `Σ I·f·cos θ_i`.
#[derive(Default)]
struct Sums {
    diffuse: [f64; 3],
    specular: [f64; 3],
    other: [f64; 3],
}

impl Sums {
    /// The pixel's colour from the sums and material `m`.
    fn combine(&self, m: &Material) -> [f64; 3] {
        let albedo = [m.albedo.r as f64, m.albedo.g as f64, m.albedo.b as f64];
        let (kd, ks) = (m.kd as f64, m.ks as f64);
        let mut color = [0.0; 3];
        for c in 0..3 {
            color[c] = kd * albedo[c] * self.diffuse[c] + ks * self.specular[c] + self.other[c];
        }
        color
    }
}

impl Surface3 {
    /// Adds light arriving along `l` (unit, toward the light) carrying `arriving` to `sums`,
    /// unless a sphere blocks the shadow ray of length `t_max` (then `true`).
    fn arrive<const S: usize, const L: usize>(
        &self,
        scene: &Scene<S, L>,
        m: &Material,
        sums: &mut Sums,
        (l, arriving, t_max): (D3, [f64; 3], f64),
    ) -> bool {
        let (n, v, eps) = (self.n, self.v, self.eps);
        let blocked = scene.spheres().iter().any(|s| {
            intersect(
                self.shadow_origin,
                l,
                D3::of(s.center),
                s.radius as f64,
                eps,
            )
            .is_some_and(|ts| ts < t_max)
        });
        if blocked {
            return true;
        }
        let n_dot_l = n.dot(l).max(0.0);
        if !matches!(m.model, Model::Phong | Model::BlinnPhong) {
            let f = normalized_brdf(m, n, l, v);
            for (c, a) in arriving.iter().enumerate() {
                sums.other[c] += a * f[c] * n_dot_l;
            }
            return false;
        }
        let cosine = match m.model {
            Model::BlinnPhong => {
                let hv = l.add(v);
                if hv.len() > 0.0 {
                    n.dot(hv.unit())
                } else {
                    0.0
                }
            }
            _ => {
                let travel = l.mul(-1.0);
                let r = travel.sub(n.mul(2.0 * n.dot(travel)));
                r.dot(v)
            }
        };
        let lobe = if cosine > 0.0 {
            libm::pow(cosine.min(1.0), m.shininess as f64)
        } else {
            0.0
        };
        for (c, a) in arriving.iter().enumerate() {
            sums.diffuse[c] += a * n_dot_l;
            sums.specular[c] += a * lobe;
        }
        false
    }
}

/// Renders a whole `width × height` frame, row-major, into `out`.
pub fn render_frame<const S: usize, const L: usize>(
    scene: &Scene<S, L>,
    width: u32,
    height: u32,
    out: &mut [RefPixel],
) -> Result<(), RenderError> {
    if width == 0 || height == 0 || width > crate::MAX_DIMENSION || height > crate::MAX_DIMENSION {
        return Err(RenderError::BadSize { width, height });
    }
    let expected = width as usize * height as usize;
    if out.len() != expected {
        return Err(RenderError::FrameLength {
            expected,
            got: out.len(),
        });
    }
    for (y, row) in out.chunks_exact_mut(width as usize).enumerate() {
        for (x, px) in row.iter_mut().enumerate() {
            *px = shade_pixel(scene, width, height, x as u32, y as u32);
        }
    }
    Ok(())
}

/// The encode rule of the paths, in `f64`: `⌊clamp(c, 0, 1)·max + ½⌋`.
pub fn quantize(c: f64, max: f64) -> u16 {
    let c = if c > 0.0 { c } else { 0.0 };
    let c = if c < 1.0 { c } else { 1.0 };
    libm::floor(c * max + 0.5) as u16
}
