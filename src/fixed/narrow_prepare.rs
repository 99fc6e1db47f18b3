//! The fixed path's prepare for its narrow kernel ([`super::narrow`]): whether a frame
//! takes it, and its constants: each sphere's exact quadrics `E′` and, per light, `G`
//! ([`quadric`], in `i128` from the frame's integer geometry), the caster filters and the
//! quick caster test's constants, and the lobe's cutoffs. The rest of the prepare (the
//! scene in fixed point, the spans) is in [`super::prepare`]; this part runs after it, on
//! its scaled integers.

use super::convert::to_f32;
use super::exact::{arriving, Exact};
use super::mul::{dot_ii, mul_128, mul_ii};
use super::narrow_depth::DEPTH_ORDER;
#[cfg(not(feature = "full-width"))]
use super::outline::{outline_columns, outline_rows};
use super::prepare::{
    FixedLight, FixedSphere, NarrowLight, NarrowPoint, NarrowSphere, NarrowView, PreparedFixed,
};
use super::quadric::Quadric;
use super::roots::{inv_sqrt, sqrt};
use super::vector::{each3, Unit, V3};
use crate::scene::{Item, Model, Scene};
use fixed::types::I16F48;

/// The largest error of the narrow kernel's fast `h = 1 − cos` (Phong's `1 − R·V`,
/// Blinn-Phong's `1 − N·H` where `|L + V| ≥ ¾`), `6·2⁻¹⁵`: checked by the narrow module's
/// `fast_h_within_its_bound` on the exponent series and on random frames. The prepare's lobe
/// cutoff and the test of whether a sphere's lobe needs the precise `h` use it.
pub(crate) const H_ERROR: f32 = 6.0 / 32768.0;

/// `v` (I16F48 bits, each component below 2 in magnitude) rounded to Q29, the narrow
/// kernel's directions. Out of line on ARMv6-M: three vectors a frame.
#[cfg_attr(shadeline_short_mul, inline(never))]
fn to_q29(v: V3<I16F48>) -> [i32; 3] {
    // ((c >> 18) + 1) >> 1 is (c + 2¹⁸) >> 19, with no overflow near `i64::MAX`.
    v.map(|c| (((c.to_bits() >> 18) + 1) >> 1) as i32)
}

/// An `h` (Q31) from which a lobe of exponent `n` times `ks_intensity` (`ks` times the sum
/// of the lights' brightest channels) is below `τ = 2⁻¹⁷`, half a U16F16 step, allowing for
/// the fast `h`'s error ([`H_ERROR`]).
///
/// `(1 − h)ⁿ < τ/k` from `h = 1 − e^(−x)` on, `x = ln(k/τ)/n`; that is below
/// `x − x²/2 + x³/6` (the series alternates with falling terms for `x < 3`), and
/// `ln(k/τ) = ln 2·log₂(k/τ)` is at most `ln 2·e + (m − 1)` for `k/τ = m·2^e`, `m` in
/// `[1, 2)` (as `ln m ≤ m − 1`, within 0.06). So this bound, a few `f32` operations on the
/// number's bits, is never below the true cutoff: it only shades a few more pixels' lobes
/// (to 0) than needed, and needs no `powf`.
fn lobe_cutoff(ks_intensity: f32, n: f32) -> u32 {
    let ratio = ks_intensity * 131_072.0; // k/τ
    if ratio.is_nan() || ratio <= 1.0 || n.is_nan() || n <= 0.0 {
        return 0;
    }
    let bits = ratio.to_bits();
    let e = ((bits >> 23) & 0xff) as i32 - 127;
    let m = f32::from_bits((bits & 0x7f_ffff) | (127 << 23)); // in [1, 2)
    let x = (e as f32 * core::f32::consts::LN_2 + (m - 1.0)) / n;
    // From x = 1.5 on, 1: the whole lit lobe (the true cutoff is above 0.77 there).
    let h = if x < 1.5 {
        x - x * x * (0.5 - x / 6.0)
    } else {
        1.0
    } + 2.0 * H_ERROR;
    (h * (1u64 << 31) as f32) as u32
}

/// The largest fast lobe (U1F16) within half a level where `h ≤ ½`, for a lobe of exponent
/// `n` times `ks_intensity` whose `h` is within `h_error`: `2¹⁶` or more if it is wherever
/// the lobe is not 0, 0 if nowhere. The lobe's error is its slope `n·(1 − h)^(n − 1)`
/// times `h`'s error, and the narrow `pow`'s own (module `narrow`); the slope is at most `n`
/// (at `h = 0`), and at most `2n` times the lobe where `h ≤ ½`. Above `n = 256`, the range
/// the `pow`'s bound of `1.4·10⁻⁴` is held on, 0.
pub(super) fn fast_lobe_max(ks_intensity: f32, n: f32, h_error: f32) -> u32 {
    let budget = 0.5 / (ks_intensity * 255.0) - 1.4e-4;
    if n > 256.0 || budget.is_nan() || budget <= 0.0 {
        0
    } else if n * h_error <= budget {
        u32::MAX
    } else {
        ((budget / (2.0 * n * h_error)) * 65536.0) as u32
    }
}

/// A normalized sphere's lobes: the sum of their weights (each `wₖ` times its normalization,
/// as `FixedSphere::weight` holds it), and the least and largest exponent of a lobe of
/// nonzero weight (`n` is lobe 0's).
#[inline(never)]
fn lobe_range(sphere: &FixedSphere, n: f32) -> (f32, f32, f32) {
    let value = |e: Exact| libm::ldexpf(e.mantissa as f32, e.exponent);
    let (mut sum, mut low, mut high) = (value(sphere.weight[0]), n, n);
    for (w, e) in sphere.weight[1..].iter().zip(sphere.more_shininess) {
        if w.mantissa != 0 {
            sum += value(*w);
            low = low.min(value(e));
            high = high.max(value(e));
        }
    }
    (sum, low, high)
}

/// The lobe stage's limits of sphere `s`, of shininess `n`, under lights whose brightest
/// channels sum to `intensity` (`terms`: the normalized models' fast terms): the lobes'
/// cutoff ([`lobe_cutoff`]) and the fast lobe's largest value ([`fast_lobe_max`]), with the
/// lobes' largest exponent and their scale, which the fast point light's limits take.
#[inline(always)]
fn lobe_limits(s: &FixedSphere, (n, intensity, terms): (f32, f32, bool)) -> (u32, u32, (f32, f32)) {
    // The lobes' scale and exponents: `ks` and `n` for the classic models; for the
    // normalized ones the sum of the lobes' weights (F ≤ 1), the least exponent for the
    // cutoff (the widest lobe) and the largest for the error (the steepest).
    let (scale, n_low, n_high) = if terms {
        lobe_range(s, n)
    } else {
        (to_f32(s.ks.to_bits() as i64, 16), n, n)
    };
    let ks_intensity = scale * intensity;
    let cutoff = lobe_cutoff(ks_intensity, n_low);
    // The fast lobe's error (see `fast_lobe_max`). For the normalized models a limit of
    // at least one step: where lobe 0 is below it, so is every lobe of a larger exponent,
    // and whatever the exponent its error is far below a level.
    let fast_lobe_max = match fast_lobe_max(ks_intensity, n_high, H_ERROR) {
        0 if terms => 1,
        max => max,
    };
    (cutoff, fast_lobe_max, (n_high, scale))
}

/// The index pairs `(a, b)` of a quadric's coefficients in the order of [`Quadric::c`]:
/// `c₀₀` from the directions `(0, 0)`, `c₁₀` from `(0, 1)` …, `c₀₂` from `(2, 2)`.
const PAIRS: [(usize, usize); 6] = [(0, 0), (0, 1), (0, 2), (1, 1), (1, 2), (2, 2)];

/// Which of a sphere's two quadrics [`quadric`] makes (see [`Quadric`]). By the identities
/// of Lagrange and Binet–Cauchy, `|oc × D|² = |oc|²·|D|² − (oc·D)²` and
/// `(oc × D)·(L × D) = (oc·L)·|D|² − (oc·D)(L·D)`, so both come from dot products alone:
enum Form<'a> {
    /// `E′·r²·2⁵⁸ = r²·|D|² − |oc × D|² = (r² − |oc|²)·|D|² + (oc·D)²`.
    E,
    /// `G·r·2⁸⁸ = (oc × D)·(L × D) = (oc·L)·|D|² − (oc·D)(L·D)`, with `L·Dₐ` for each of
    /// the three directions.
    G(&'a [i64; 3]),
}

/// A sphere's quadric `form` over `den`, for `D = dc + x·sx + y·sy`: from `s` (`r² − |oc|²`
/// for `E′`, `oc·L` for `G`), the Gram matrix `gram` of the three directions (`Dₐ·D_b` in
/// the order of [`PAIRS`]) and `b`, their dot products with `oc`. Each raw coefficient is
/// exact in `i128`: `s·(Dₐ·D_b) ± sym(bₐ·v_b)`, doubled off the diagonal, with `v = b` for
/// `E′` and `v = L·D` for `G` (below `2¹²⁷`: `|s| < 2⁶²`; `|Dₐ·D_b|`, `|bₐ|` and `|L·Dₐ|`
/// below `3·2⁶⁰`). Each is divided as soon as it is made (one `i128` at a time on the
/// stack), into `c`. One loop over [`PAIRS`] for both, for the flash: once per sphere and
/// per sphere and light. `None` if a coefficient does not fit.
#[inline(never)]
fn quadric(
    (s, gram, b): (i64, &[i64; 6], &[i64; 3]),
    form: Form,
    den: &Divisor,
    c: &mut Quadric,
) -> Option<()> {
    let v = match form {
        Form::E => b,
        Form::G(l) => l,
    };
    for ((slot, &(i, k)), &dot) in c.c.iter_mut().zip(&PAIRS).zip(gram) {
        let (i, k) = (i % 3, k % 3);
        // The symmetric product; for `E′`, `v` is `b` and its two halves are equal.
        let mut raw = mul_128(b[i], v[k]);
        if i != k {
            raw += match form {
                Form::E => raw,
                Form::G(_) => mul_128(b[k], v[i]),
            };
        }
        // |Dₐ·D_b| < 3·2⁶⁰: doubled, it fits `i64`.
        let scaled = mul_128(s, if i == k { dot } else { 2 * dot });
        raw = match form {
            Form::E => scaled + raw,
            Form::G(_) => scaled - raw,
        };
        *slot = den.divide(raw)?;
    }
    Some(())
}

/// A positive divisor `dᵏ·2^z` (`d` below `2³²`, `k` one or two, `z` below 64): the
/// prepare divides each of a sphere's quadric coefficients by `r²` or `r` times a power of
/// two. The quotient is exact, rounded toward zero: the dividend's magnitude is divided as
/// four 32-bit limbs, each one 64/32-bit division (the runtime's `u64` division, which a
/// 32-bit core links anyway), `k` times over, then shifted. No 128-bit division routine
/// (a long one on a 32-bit core) and no reciprocal to make.
struct Divisor {
    d: u32,
    passes: u32,
    z: u32,
}

impl Divisor {
    /// `c` over the divisor, rounded toward zero; `None` if it does not fit `i64`. Inlined
    /// into `quadric`, its one caller (smaller on the M0).
    #[inline(always)]
    fn divide(&self, c: i128) -> Option<i64> {
        let m = c.unsigned_abs();
        let mut limbs = [
            (m >> 96) as u32,
            (m >> 64) as u32,
            (m >> 32) as u32,
            m as u32,
        ];
        // The prepare's radii are at least one unit (2¹⁶ raw): the `max` only shows the
        // compiler that the division cannot be by 0.
        let d = self.d.max(1) as u64;
        for _ in 0..self.passes {
            // Each step's dividend is below d·2³², so its quotient fits a limb.
            let mut rest = 0u64;
            for limb in &mut limbs {
                let part = (rest << 32) | *limb as u64;
                *limb = (part / d) as u32;
                rest = part % d;
            }
        }
        let [a, b, c2, c3] = limbs;
        let (high, low) = (
            ((a as u64) << 32) | b as u64,
            ((c2 as u64) << 32) | c3 as u64,
        );
        // (high·2⁶⁴ + low) >> z is below 2⁶³ iff high is below 2^(z − 1) (for z = 0:
        // high is 0 and low below 2⁶³).
        let z = self.z.min(63);
        let q = match z {
            0 => (high == 0).then_some(low),
            _ => (high >> (z - 1) == 0).then_some((high << (64 - z)) | (low >> z)),
        }?;
        let q = i64::try_from(q).ok()?;
        Some(if c < 0 { -q } else { q })
    }
}

impl<const S: usize, const L: usize> PreparedFixed<S, L> {
    /// Sets up the narrow kernel ([`super::narrow`]) if the frame meets its conditions, or
    /// says which item and field keep it from them (the first found). `corners`: whether
    /// every primary direction is within `√2` of the central one in length (then
    /// `|D| < 2³⁰` and every narrow format holds) and the steps below ½, from
    /// [`Self::prepare_fields`]. Inlined into its one caller on ARMv6-M (smaller there),
    /// out of line elsewhere, like `prepare_fields` and for the same reason.
    #[cfg_attr(shadeline_short_mul, inline(always))]
    #[cfg_attr(not(shadeline_short_mul), inline(never))]
    pub(super) fn prepare_narrow(
        &mut self,
        scene: &Scene<S, L>,
        corners: bool,
    ) -> Result<(), (Item, &'static str)> {
        self.narrow_refusal(scene, corners)?;
        // D = forward + dy·step_y + dx·step_x at 2²⁹ for the unit forward vector: each
        // component of `forward` at most 2²⁹ and of a step below 2²⁸ (`corners`).
        let view = NarrowView {
            forward: to_q29(self.forward),
            step_x: to_q29(self.step_x),
            step_y: to_q29(self.step_y),
        };
        let intensity = self.distant_intensity();
        self.prepare_points();
        // The Gram matrix of the quadrics' three directions, in the order of `PAIRS`: the
        // same for every sphere.
        let dirs = view.dirs();
        let gram = PAIRS.map(|(a, b)| dot_ii(dirs[a % 3], dirs[b % 3]));
        self.prepare_across();
        self.narrow_lights.clear();
        for i in 0..self.spheres.len() {
            let m = scene.spheres().get(i).map(|s| s.material);
            let n = m.map_or(1.0, |m| m.shininess);
            // A Lambert sphere has no lobe: no light's `h` is below a cutoff of 0. The
            // normalized models shade every light with their terms (`terms`), which have no
            // cutoff.
            let model = m.map(|m| m.model);
            let terms = !matches!(
                model,
                None | Some(Model::Phong | Model::BlinnPhong | Model::Lambert)
            );
            let intensity = match model {
                Some(Model::Lambert) => 0.0,
                _ => intensity + self.point_intensity(i),
            };
            self.prepare_narrow_sphere(scene, i, (&view, &gram), (n, intensity, terms))
                .map_err(|field| (Item::Sphere(i), field))?;
        }
        self.precise_pixels = self
            .lights
            .iter()
            .any(|l| matches!(l, FixedLight::Point { .. }))
            || self
                .spheres
                .iter()
                .any(|s| s.narrow.is_some_and(|n| n.terms));
        if DEPTH_ORDER {
            self.prepare_depth_order();
        }
        self.narrow = Some(view);
        Ok(())
    }

    /// The first item and field that keep the frame from the narrow kernel before its
    /// spheres are looked at: a sphere light, an Oren–Nayar or GGX sphere, more spheres than
    /// a run's tracks index, or a view too wide (`corners`, see [`Self::prepare_narrow`]).
    #[inline(always)]
    fn narrow_refusal(
        &self,
        #[cfg_attr(not(feature = "full-width"), allow(unused_variables))] scene: &Scene<S, L>,
        corners: bool,
    ) -> Result<(), (Item, &'static str)> {
        // Sphere lights (a point light of radius above 0) need the full-width kernel.
        if let Some(light) = self
            .lights
            .iter()
            .position(|l| !matches!(l, FixedLight::Distant { .. } | FixedLight::Point { .. }))
        {
            return Err((Item::Light(light), "radius"));
        }
        // Oren–Nayar and GGX need the full-width kernel (without it, `prepare_fields` has
        // refused them already).
        #[cfg(feature = "full-width")]
        if let Some(sphere) = scene
            .spheres()
            .iter()
            .position(|s| matches!(s.material.model, Model::OrenNayar { .. } | Model::Ggx(_)))
        {
            return Err((Item::Sphere(sphere), "model"));
        }
        // The narrow run indexes its tracks by `u8`.
        if self.spheres.len() > 256 {
            return Err((Item::Sphere(256), "center"));
        }
        if !corners {
            return Err((Item::Camera, "vfov"));
        }
        Ok(())
    }

    /// The sum over the distant lights of each one's brightest channel (levels), which
    /// bounds the lobes with the point lights' (`lobe_cutoff`).
    #[inline(always)]
    fn distant_intensity(&self) -> f32 {
        // Each distant light's brightest channel, the largest level converted (the
        // conversion is monotonic, so it is the largest of the converted levels).
        self.lights
            .iter()
            .map(|l| match l {
                FixedLight::Distant { arriving, .. } => {
                    let brightest = arriving.iter().map(|c| c.to_bits()).max().unwrap_or(0);
                    to_f32(brightest as i64, 16)
                }
                _ => 0.0,
            })
            .sum()
    }

    /// Sphere `i`'s narrow constants, from the frame's narrow view and its shininess `n`
    /// and the sum of the lights' brightest channels: `false` if the sphere does not meet
    /// the narrow kernel's conditions or a number does not fit. Out of line (and the
    /// quadrics' arithmetic further out) to keep the prepare's stack small.
    #[inline(never)]
    fn prepare_narrow_sphere(
        &mut self,
        scene: &Scene<S, L>,
        i: usize,
        (view, gram): (&NarrowView, &[i64; 6]),
        (n, intensity, terms): (f32, f32, bool),
    ) -> Result<(), &'static str> {
        let Some(s) = self.spheres.get(i) else {
            return Err("center");
        };
        let eye_offset = s.eye_offset;
        let eps = self.epsilon.to_bits() as i64;
        let oc = eye_offset.map(|c| c.to_bits() as i64);
        let r = s.radius.to_bits() as i64;
        // |oc|² < 3·2⁶⁰: the scene lies within 2¹³ units.
        let oc_len2 = oc.iter().map(|&c| mul_ii(c as i32, c as i32)).sum::<i64>();
        if oc_len2 <= (r + 2 * eps) * (r + 2 * eps) {
            return Err("center");
        }
        let r2 = mul_ii(r as i32, r as i32);
        let (e_shift, g_shift, e_den, g_den) = quadric_scales(oc_len2, r2, r);
        // The quadrics over D = dc + x·sx + y·sy, expanded at the centre of the screen
        // (`dx = dy = 0`), from b = oc·D in each direction (see `Form`).
        let oc32 = eye_offset.map(|c| c.to_bits());
        let b = view.dirs().map(|d| dot_ii(oc32, d));
        let mut e = Quadric::default();
        if quadric((r2 - oc_len2, gram, &b), Form::E, &e_den, &mut e).is_none() {
            return Err("radius");
        }
        #[cfg_attr(not(feature = "narrow-precise"), allow(unused_variables))]
        let (cutoff, fast_lobe_max, lobes) = lobe_limits(s, (n, intensity, terms));
        self.prepare_sphere_lights(scene, i, (view, gram, &b), &g_den)?;
        let bits = 64 - r.leading_zeros();
        let (rf, ef) = (r as f32, eps as f32);
        let (c_q30, c_shift, t_num) = hit_constants(oc_len2, r2, r);
        #[cfg(feature = "narrow-precise")]
        self.prepare_point_fast(i, lobes);
        let narrow = NarrowSphere {
            c_q30,
            c_shift,
            t_mantissa: (t_num.mantissa >> 8) as u16,
            // r·c is at least ε (1 raw unit) and below 2⁶²: an exponent in −15..=47.
            t_exponent: (t_num.exponent + 8).clamp(-128, 127) as i8,
            quick_margin: self.quick_margin(i),
            touching: self.touching(i),
            shadows: self.sphere_shadow_rows(i, view),
            fast_lobe_max,
            terms,
            shadow_limit: (ef * (2.0 * rf + ef) / ((rf + ef) * (rf + ef)) * (1u64 << 30) as f32)
                as u32,
            cutoff,
            e_shift: e_shift as u8,
            g_shift: g_shift as u8,
            cross_shift: (bits + 14) as u8,
            gain: (1u64 << (bits + 15)).checked_div(r as u64).unwrap_or(0) as u32,
            b_rises: b[1] > 0,
            #[cfg(not(feature = "full-width"))]
            rows: to_u16(outline_rows(&e, self.height)),
            #[cfg(not(feature = "full-width"))]
            columns: to_u16(outline_columns(&e, self.width)),
            e,
        };
        match self.spheres.get_mut(i) {
            Some(s) => s.narrow = Some(narrow),
            None => return Err("center"),
        }
        Ok(())
    }

    /// `NarrowSphere::shadows` of sphere `i`: its shadow rows ([`super::narrow_shadow_rows`]),
    /// or every row without the feature `shadow-rows`.
    #[inline(always)]
    fn sphere_shadow_rows(&self, i: usize, view: &NarrowView) -> (u16, u16) {
        #[cfg(feature = "shadow-rows")]
        {
            self.shadow_rows(i, view)
        }
        #[cfg(not(feature = "shadow-rows"))]
        {
            let _ = (i, view);
            (0, self.height.min(u16::MAX as u32) as u16)
        }
    }

    /// Sphere `i`'s constants for each light (`narrow_light`), pushed as its entry of
    /// `narrow_lights`.
    fn prepare_sphere_lights(
        &mut self,
        scene: &Scene<S, L>,
        i: usize,
        geometry: (&NarrowView, &[i64; 6], &[i64; 3]),
        g_den: &Divisor,
    ) -> Result<(), &'static str> {
        if self
            .narrow_lights
            .push([NarrowLight::default(); L])
            .is_err()
        {
            return Err("radius");
        }
        for light_index in 0..self.lights.len().min(L) {
            let light = self.narrow_light(scene, i, light_index, geometry, g_den)?;
            match self
                .narrow_lights
                .get_mut(i)
                .and_then(|l| l.get_mut(light_index))
            {
                Some(slot) => *slot = light,
                None => return Err("center"),
            }
        }
        Ok(())
    }

    /// Sphere `i`'s fast point light limits for each light (`point_fast`), from the lobes'
    /// largest exponent and their scale.
    #[cfg(feature = "narrow-precise")]
    fn prepare_point_fast(&mut self, i: usize, lobes: (f32, f32)) {
        for light_index in 0..self.lights.len().min(L) {
            let (fast, ratio, slack) = self.point_fast(i, light_index, lobes);
            if let Some(l) = self
                .narrow_lights
                .get_mut(i)
                .and_then(|l| l.get_mut(light_index))
            {
                (l.point.fast, l.point.ratio, l.point.slack) = (fast, ratio, slack);
            }
        }
    }

    /// Sphere `i`'s narrow constants for light `light`, from the frame's narrow view, the
    /// Gram matrix of its three directions and their dot products `b` with the sphere's eye
    /// offset (see [`quadric`]); the field that keeps the sphere from the narrow kernel if
    /// the light is not distant, `G` does not fit (`radius`) or a caster is too close
    /// (`center`, see [`Self::narrow_casters`]). Inlined into the sphere's: its one caller,
    /// and smaller on the M0 (the peak stack the same).
    #[inline(always)]
    fn narrow_light(
        &self,
        scene: &Scene<S, L>,
        i: usize,
        light: usize,
        (view, gram, b): (&NarrowView, &[i64; 6], &[i64; 3]),
        g_den: &Divisor,
    ) -> Result<NarrowLight, &'static str> {
        let Some(own) = self.spheres.get(i) else {
            return Err("center");
        };
        let l = match self.lights.get(light) {
            Some(FixedLight::Distant { to_light, .. }) => to_light.map(|c| c.to_bits()),
            Some(FixedLight::Point { .. }) => self.points.get(light).map_or([0; 3], |p| p.dir),
            _ => return Err("radius"),
        };
        let scene_light = match self.lights.get(light) {
            Some(FixedLight::Point { .. }) => scene.lights().get(light),
            _ => None,
        };
        let oc_l = dot_ii(own.eye_offset.map(|c| c.to_bits()), l);
        let mut g = Quadric::default();
        let ld = view.dirs().map(|d| dot_ii(l, d));
        quadric((oc_l, gram, b), Form::G(&ld), g_den, &mut g).ok_or("radius")?;
        let (casters, ahead, reach) = match scene_light {
            Some(_) => self.narrow_point_casters(scene, i, light).ok_or("center")?,
            None => self
                .narrow_casters(i, l.map(Unit::from_bits))
                .ok_or("center")?,
        };
        let across = self.across_from_eye(own.eye_offset.map(|c| c.to_bits()), light);
        #[cfg(feature = "narrow-precise")]
        let cone = match self.lights.get(light) {
            Some(FixedLight::Point { position, .. }) => self.point_cone(own, position),
            _ => [0, 0, 0, i16::MIN],
        };
        Ok(NarrowLight {
            g,
            casters,
            ahead,
            reach,
            across,
            #[cfg(feature = "narrow-precise")]
            point: super::prepare::PointConstants {
                cone,
                ..Default::default()
            },
            #[cfg(test)]
            separated: match scene_light {
                Some(_) => self.point_separated_casters(i, light),
                None => self.separated_casters(i, l),
            },
        })
    }

    /// [`Self::points`]: each point light's direction (I2F30) and distance (raw) from the
    /// eye, from the exact integer offset `P − eye` (`inv_sqrt` and `sqrt`, within `2⁻³⁰`
    /// relative). A light at the eye has direction 0 and distance 0, which the kernel's
    /// formulas take as they are.
    fn prepare_points(&mut self) {
        for (point, light) in self.points.iter_mut().zip(&self.lights) {
            let FixedLight::Point { position, .. } = light else {
                continue;
            };
            let q = each3(|c| position[c].to_bits() as i64 - self.eye[c].to_bits() as i64);
            // Both points lie within 2³⁰ raw of the origin: each square below 2⁶², the sum
            // below 2⁶⁴.
            let len2 = q.iter().map(|&c| (c * c) as u64).sum::<u64>();
            let dir = inv_sqrt(len2).map_or([0; 3], |(y, shift)| {
                q.map(|c| ((c * y as i64) >> (shift - 30).min(63)) as i32)
            });
            #[cfg(feature = "narrow-precise")]
            let distance = sqrt(len2).min(i32::MAX as u64) as u32;
            *point = NarrowPoint {
                dir,
                #[cfg(feature = "narrow-precise")]
                distance,
                #[cfg(feature = "narrow-precise")]
                distance_shift: super::narrow_hit::bit_length(distance).saturating_sub(15),
            };
        }
    }

    /// The sum over the point lights of the brightest channel arriving anywhere on sphere
    /// `i` (levels): each light's power over the square of its distance from the sphere,
    /// `|P − C| − r`, rounded down, so the sum is never short. It bounds the lobe with the
    /// distant lights' intensities (`lobe_cutoff`).
    fn point_intensity(&self, i: usize) -> f32 {
        let Some(own) = self.spheres.get(i) else {
            return 0.0;
        };
        let mut sum = 0.0;
        for light in &self.lights {
            let FixedLight::Point { position, power } = light else {
                continue;
            };
            let w = each3(|c| position[c].to_bits() as i64 - own.center[c].to_bits() as i64);
            let len2 = w.iter().map(|&c| (c * c) as u64).sum::<u64>();
            let gap = (sqrt(len2) as i64 - own.radius.to_bits() as i64 - 2).max(1) as u64;
            let brightest = inv_sqrt(gap * gap).map_or(u32::MAX, |inv| {
                arriving(*power, inv).into_iter().max().unwrap_or(0)
            });
            sum += to_f32(brightest as i64, 16);
        }
        sum
    }
}

/// The quadrics' scales of a sphere of radius `r` (raw, `r2 = r²`) whose centre is `|oc|²`
/// (raw²) from the eye: `E′`'s shift to Q29 and `G`'s, from `⌈log₂ max(1, |ô|²)⌉` (below
/// 28, since the scene lies within 2¹³ units and `r ≥ 1` unit), and their divisors: `E′`'s
/// scale `2^(29 + e_shift)/(r²·2⁵⁸)`, `G`'s `2^(29 + g_shift)/(r·2⁸⁸)`.
fn quadric_scales(oc_len2: i64, r2: i64, r: i64) -> (u32, u32, Divisor, Divisor) {
    let ratio = (oc_len2 + r2 - 1).checked_div(r2).unwrap_or(0).max(1) as u64;
    let log_sq = 64 - (ratio - 1).leading_zeros();
    let e_shift = 29u32.saturating_sub(log_sq);
    let g_shift = 28u32.saturating_sub(log_sq.div_ceil(2));
    let divisor = |passes, z| Divisor {
        d: r as u32,
        passes,
        z,
    };
    (
        e_shift,
        g_shift,
        divisor(2, 29 - e_shift),
        divisor(1, 59 - g_shift),
    )
}

/// The fast `t`'s constants of a sphere of radius `r` (raw) whose centre is `|oc|²` (raw²)
/// from the eye, `r2` being `r²`: `c = |ô|² − 1 = (|oc|² − r²)/r²` (from the exact
/// difference) in Q30 after `c_shift` halvings of `√(1 + c)`, the shift, and `r·c`.
fn hit_constants(oc_len2: i64, r2: i64, r: i64) -> (u32, u8, Exact) {
    let c = (oc_len2 - r2) as f32 / r2 as f32;
    let mut c_shift = 0u8;
    while c_shift < 15 && 1.0 + c > (1u64 << (2 * c_shift)) as f32 {
        c_shift += 1;
    }
    let c_q30 = (c * (1u64 << (30 - 2 * c_shift)) as f32).min((1u32 << 30) as f32) as u32;
    (
        c_q30,
        c_shift,
        Exact::from_f32((oc_len2 - r2) as f32 / r as f32),
    )
}

/// A range of rows or columns in 16 bits: each end is at most the frame's size, which is at
/// most `MAX_DIMENSION`.
#[cfg(not(feature = "full-width"))]
fn to_u16((start, end): (u32, u32)) -> (u16, u16) {
    (
        start.min(u16::MAX as u32) as u16,
        end.min(u16::MAX as u32) as u16,
    )
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;

    /// Values at and around every power of two of both signs, and a xorshift stream.
    fn values() -> impl Iterator<Item = i128> {
        let edges = (0..127).flat_map(|k| {
            let p = 1i128 << k;
            [p - 1, p, p.wrapping_add(1), -p - 1, -p, -p + 1]
        });
        let mut x = 0x9e37_79b9_7f4a_7c15u64;
        let mut next = move || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            x
        };
        let random = (0..2000).map(move |_| {
            let (h, l) = (next(), next());
            (((h as u128) << 64 | l as u128) as i128) >> (h % 120)
        });
        edges.chain([0, i128::MAX, i128::MIN]).chain(random)
    }

    /// The division is exact: the quotient rounded toward zero, `None` exactly where it
    /// does not fit `i64`, for divisors at the prepare's extremes (`r` from one unit, `2¹⁶`
    /// raw, to `2³¹`; `z` up to 63) and dividends at every power of two.
    #[test]
    fn divisor_is_exact() {
        for (d, passes, z) in [
            (1u32 << 16, 2u32, 0u32),
            (1 << 16, 1, 63),
            (65_537, 2, 29),
            (0x1234_5679, 1, 31),
            (0x7fff_ffff, 2, 0),
            (u32::MAX, 1, 59),
            (3 << 20, 2, 13),
        ] {
            let den = Divisor { d, passes, z };
            for c in values() {
                let mut m = c.unsigned_abs();
                for _ in 0..passes {
                    m /= d as u128;
                }
                let want = i64::try_from(m >> z)
                    .ok()
                    .map(|q| if c < 0 { -q } else { q });
                assert_eq!(den.divide(c), want, "{c}/({d}^{passes}·2^{z})");
            }
        }
    }

    /// `quadric` against the quadrics' definitions in `i128`, from cross products: `E′`'s
    /// raw coefficients `r²·(Dₐ·D_b) − (oc × Dₐ)·(oc × D_b)`, `G`'s `(oc × Dₐ)·(L × D_b)`,
    /// symmetrized and doubled off the diagonal, each through the same divisor. Random
    /// offsets, radii, lights and directions at the bounds the prepare holds them to
    /// (components below `2³⁰`, `|oc|² < 3·2⁶⁰`), and their extremes.
    #[test]
    fn quadrics_are_their_cross_product_definitions() {
        let mut x = 0x2545_f491_4f6c_dd1du64;
        let mut next = move |bits: u32| {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            // Signed, below 2^bits in magnitude, often at the extremes.
            let v = (x >> (64 - bits)) as i64;
            let v = match x % 8 {
                0 => (1 << (bits - 1)) - 1,
                1 => 1 - (1 << (bits - 1)),
                _ => v - (1 << (bits - 1)),
            };
            v as i32
        };
        let cross = |a: [i32; 3], b: [i32; 3]| {
            let m = |i: usize, j: usize| a[i] as i128 * b[j] as i128;
            [m(1, 2) - m(2, 1), m(2, 0) - m(0, 2), m(0, 1) - m(1, 0)]
        };
        let dot = |a: [i128; 3], b: [i128; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
        let wide = |a: [i32; 3]| a.map(|c| c as i128);
        let mut checked = 0;
        for _ in 0..3000 {
            let oc = [next(31), next(31), next(31)];
            let r = (next(31) as i64).unsigned_abs().max(1 << 16) as i64;
            let dirs = [
                [next(31), next(31), next(31)],
                [next(29), next(29), next(29)],
                [next(29), next(29), next(29)],
            ];
            let l = [next(31), next(31), next(31)];
            let oc_len2 = dot(wide(oc), wide(oc));
            if oc_len2 >= 3 << 60 {
                continue;
            }
            let r2 = r * r;
            let gram = PAIRS.map(|(a, b)| dot_ii(dirs[a], dirs[b]));
            let b = dirs.map(|d| dot_ii(oc, d));
            let ld = dirs.map(|d| dot_ii(l, d));
            let oc_l = dot_ii(oc, l);
            let w = dirs.map(|d| cross(oc, d));
            let v = dirs.map(|d| cross(l, d));
            // A divisor that keeps the quotients within `i64`: r²·2³⁴ is at least 2⁶⁶, and
            // 2¹²⁷ over it below 2⁶².
            let den = Divisor {
                d: r as u32,
                passes: 2,
                z: 34,
            };
            let mut e = Quadric::default();
            let mut g = Quadric::default();
            let e_ok = quadric((r2 - oc_len2 as i64, &gram, &b), Form::E, &den, &mut e);
            let g_ok = quadric((oc_l, &gram, &b), Form::G(&ld), &den, &mut g);
            assert!(
                e_ok.is_some() && g_ok.is_some(),
                "{oc:?} {r} {dirs:?} {l:?}"
            );
            for (k, &(a, c)) in PAIRS.iter().enumerate() {
                let twice = if a == c { 1 } else { 2 };
                let gram = dot(wide(dirs[a]), wide(dirs[c]));
                let e_raw = twice * (r2 as i128 * gram - dot(w[a], w[c]));
                let g_raw = if a == c {
                    dot(w[a], v[a])
                } else {
                    dot(w[a], v[c]) + dot(w[c], v[a])
                };
                assert_eq!(
                    Some(e.c[k]),
                    den.divide(e_raw),
                    "E′ c{k} of {oc:?} {r} {dirs:?}"
                );
                assert_eq!(
                    Some(g.c[k]),
                    den.divide(g_raw),
                    "G c{k} of {oc:?} {l:?} {dirs:?}"
                );
            }
            checked += 1;
        }
        assert!(checked > 1000, "{checked} cases");
    }
}
