//! The float paths' narrow kernel: classic Phong and Blinn-Phong, and Lambert, under
//! distant lights, shaded from a few scalars per pixel instead of vectors, at every lane
//! width.
//!
//! # Why it exists
//!
//! The general kernel ([`super::kernel`]) normalizes the ray, finds the hit from the
//! closest-approach vector, builds the normal, the reflected ray and each light's vectors:
//! about a hundred `f32` operations per pixel and several vectors live at once, which on a
//! Cortex-M4F's register file means as many loads and stores again. For the frames most
//! firmware draws, every number the shading needs is a low-degree polynomial of the pixel's
//! column on its row, so this kernel evaluates those instead, the way the fixed path's
//! narrow kernel does (`src/fixed/narrow.rs`, which holds them as exact integer quadrics).
//!
//! # When it applies
//!
//! A frame takes it ([`Prepared`]'s `narrow`) when every light is distant and every sphere
//! uses a classic model or Lambert (shaded as a classic sphere with no lobe), the camera is outside every sphere, no sphere's highlight is too
//! sharp for it (`ks·ΣI·n` within [`SHARPEST`](super::prepare::SHARPEST)). Other frames take the general kernel.
//! The conditions are frame-wide, and each lane's result depends only on its own pixel
//! (never on which candidates its packet has), so the scalar and SIMD paths stay
//! bit-identical. With anti-aliasing on, the lanes an outline crosses are blended as the
//! general kernel's are (`narrow_antialiased`), and every other pixel keeps its bits.
//!
//! # How a pixel is computed
//!
//! With `D = F + X·Sx + Y·Sy` the pixel's unnormalized direction (`X = 2x + 1 − w`,
//! `Y = h − 2y − 1` its offsets from the image centre in half pixels, `F` the unit
//! forward vector), `ô = (eye − centre)/r` and `L` a light's unit direction:
//!
//! ```text
//! A  = |D|²                        σ = 1/√A
//! E′ = |D|² − |ô × D|²             the hit: E′ ≥ 0 and b = ô·D < 0; N·V = √E′·σ
//! G  = (ô × D)·(L × D)             N·L = G·σ² − (N·V)·(L·D̂),  L·D̂ = (D·L)·σ
//! Phong:       cos = R·V = 2·(N·L)(N·V) + L·D̂
//! Blinn-Phong: cos = N·H = (N·L + N·V)/√(2 − 2·L·D̂)
//! ```
//!
//! `A`, `E′` and `G` are quadratics in the column and `b`, `D·L` lines, whose coefficients
//! the row driver makes once per row from the sphere's vectors (`NarrowRow`); a pixel
//! evaluates them by Horner's rule at its column's offset from the sphere's middle column,
//! where each term is of the order of the result. The nearest of several spheres is the
//! smallest `r·(−b − √E′)` (the distance times `|D|`). Distances and the normal are not
//! formed, except where a shadow ray must be tested against another sphere, which takes the
//! general kernel's [`super::intersect::meets`] from `P + ε·N` with
//! `N = ô − (b·σ + N·V)·σ·D`; a lane's own sphere shadows it iff `N·L < 0` and
//! `(N·L)² > 1 − r²/(r + ε)²`, and a caster is tested only where the caster filter (from
//! `N·L` alone, see the fixed path's `NarrowLight`) lets it; a caster a plane keeps off
//! every such ray (the floor under a sphere resting on it) is not among the sphere's. On a
//! floor, a run of packets whose only candidate is the floor tests no caster on the rows
//! outside its shadow rows (`NarrowSphere::shadows`, feature `shadow-rows`, see
//! `shadow_rows`), where none can block a light; packets with several candidates test them
//! as before, which changes no pixel either.
//!
//! # Precision
//!
//! The cosines (`N·V`, `N·L`, the lobe's) are within `|ô|·`[`COS_ERROR`] of the exact ones
//! (test `narrow_cosines_within_their_bound`): the error of an `f32` ray's hit, which the
//! general kernel has too. Frames up to [`SHARPEST`](super::prepare::SHARPEST) stay within
//! a level of the general kernel's in 8-bit colour and within a tenth of a level of the `f64` reference in linear colour
//! (`narrow_frames_agree_with_the_general_kernel`; `tests/reference_agreement.rs` and
//! `tests/paths_agree.rs` check the public paths).
//!
//! # Cost
//!
//! It takes about two thirds of the general kernel's instructions on a Cortex-M4F
//! (`docs/performance.md, "Choices measured"`): the row's quadrics are made once per row (`narrow_row`, into a buffer the row driver owns), and
//! while a packet's only candidate stays the same sphere its constants are looked up once
//! (`single`, `shade_single`).

use super::intersect::meets;
use super::kernel::{combine_with, Packet};
use super::lane::Lane;
use super::prepare::{FloatPath, NarrowLight, Prepared, PreparedLight};
use crate::brdf::{Pow, BLINN_PHONG};
use crate::real::Real;
use crate::runs::Span;
use crate::vec3::Vec3;

/// The error of the narrow kernel's cosines (`N·V`, `N·L`, the lobe's) against the exact
/// ones, per unit of `|ô|` (the eye's distance from the sphere in radii): `2⁻¹⁸`. A pixel's
/// direction carries a rounding error of `2⁻²⁴` relative, which moves the hit on a sphere
/// `|ô|` radii away by `|ô|` times as much; the general kernel's hit point has the same
/// error. Measured by `narrow_cosines_within_their_bound`: at most `0.57·|ô|·2⁻¹⁸`, the
/// largest next to outlines, where `N·V` is small.
#[cfg_attr(not(test), allow(dead_code))]
pub(crate) const COS_ERROR: f32 = 1.0 / 262_144.0;

/// One sphere's quadrics along a row: `E′ = e₀ + e₁·x + e₂·x²`, `b = b₀ + b₁·x`, and per
/// light `G = g₀ + g₁·x + g₂·x²`, for `x = X − X₀`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct RowSphere<const L: usize> {
    pub e: [f32; 3],
    pub b: [f32; 2],
    pub g: [[f32; 3]; L],
}

impl<const L: usize> RowSphere<L> {
    const ZERO: Self = RowSphere {
        e: [0.0; 3],
        b: [0.0; 2],
        g: [[0.0; 3]; L],
    };
}

/// Whether the frame's shadow rows (`NarrowSphere::shadows`, feature `shadow-rows`) can skip
/// the casters' tests: without the feature every row tests them.
const SHADOW_ROWS: bool = cfg!(feature = "shadow-rows");

/// A row's narrow constants: `|D|² = a₀ + a₁·X + a₂·X²`, per light `D·L = l₀ + l₁·X`, and
/// the [`RowSphere`] of each sphere with a span on the row, with its index (in scene order,
/// only those: a row touches a few of a frame's spheres).
pub(crate) struct NarrowRow<const S: usize, const L: usize> {
    a: [f32; 3],
    dl: [[f32; 2]; L],
    spheres: heapless::Vec<RowSphere<L>, S>,
    /// Per sphere, its place in `spheres` plus one (0: no span on the row).
    slot: [u16; S],
}

impl<const S: usize, const L: usize> NarrowRow<S, L> {
    /// No sphere on the row yet: [`Prepared::narrow_row`] fills it. A function, not a
    /// constant: a constant's unused capacity is stored as zeros on every row.
    #[inline(always)]
    pub(crate) fn empty() -> Self {
        NarrowRow {
            a: [0.0; 3],
            dl: [[0.0; 2]; L],
            spheres: heapless::Vec::new(),
            slot: [0; S],
        }
    }

    /// Sphere `k`'s quadrics on the row.
    #[inline(always)]
    fn sphere(&self, k: usize) -> Option<&RowSphere<L>> {
        let slot = *self.slot.get(k)? as usize;
        self.spheres.get(slot.checked_sub(1)?)
    }
}

/// The hit of each lane of a packet: its `X`, `√E′`, the sphere (`−1`: none) and the
/// lanes that hit.
struct Geometry<T: Lane> {
    x: T,
    root: T,
    id: T,
    any_hit: T::Mask,
}

/// One sphere's constants on a row, for packets that test it alone.
pub(crate) struct Single<'a, T: Lane, const L: usize> {
    /// The sphere's index, as the lanes' `id`.
    id: f32,
    origin: f32,
    radius: f32,
    row: &'a RowSphere<L>,
    filters: &'a [NarrowLight; L],
    hitting: Hitting<T>,
}

/// What the light stage reads of each lane's sphere.
struct Hitting<T: Lane> {
    kd_albedo: Vec3<T>,
    ks: T,
    shininess: T,
    blinn: T::Mask,
    own_limit: T,
}

/// `N·L = G·σ² − (N·V)·(L·D̂)` from `G`, `σ²`, `N·V` and `L·D̂`.
#[inline(always)]
fn normal_dot_light<T: Lane>(g: T, sigma2: T, nv: T, ld: T) -> T {
    g * sigma2 - nv * ld
}

/// The lobe's cosine: `R·V = 2·(N·L)(N·V) + L·D̂` (Phong), or on the `blinn` lanes
/// `N·H = (N·L + N·V)/√(2 − 2·L·D̂)`.
#[inline(always)]
fn lobe_cosine<T: Lane>(nl: T, nv: T, ld: T, blinn: T::Mask) -> T {
    let two = T::splat(2.0);
    let phong = two * nl * nv + ld;
    if BLINN_PHONG && T::any(blinn) {
        let half2 = two - two * ld;
        let h = (nl + nv) / half2.max(T::splat(f32::MIN_POSITIVE)).sqrt();
        T::select(blinn, h, phong)
    } else {
        phong
    }
}

/// The caster filters of a sphere off its shadow rows: no caster, for every light.
struct NoCasters<const L: usize>;

impl<const L: usize> NoCasters<L> {
    const FILTERS: &'static [NarrowLight; L] = &[NarrowLight::NONE; L];
}

/// `c₀ + x·(c₁ + x·c₂)`.
#[inline(always)]
fn horner<T: Lane>(c: [f32; 3], x: T) -> T {
    T::splat(c[0]) + x * (T::splat(c[1]) + x * T::splat(c[2]))
}

/// `v` of the lane's own sphere: `value(k)` of each candidate `k` where the lane's `id` is
/// `k`. One candidate: its value as it is.
#[inline(always)]
fn own<T: Lane>(candidates: &[u16], id: T, mut value: impl FnMut(usize) -> T) -> T {
    match candidates {
        [only] => value(*only as usize),
        _ => {
            let mut out = T::splat(0.0);
            for &k in candidates {
                let kf = T::splat(k as f32);
                let here = T::and(id.le(kf), kf.le(id));
                if T::any(here) {
                    out = T::select(here, value(k as usize), out);
                }
            }
            out
        }
    }
}

impl<W: FloatPath, const S: usize, const L: usize> Prepared<W, S, L> {
    /// The packet's pixels `x0, x0 + 1, …` as offsets `X = 2x + 1 − w` from the image
    /// centre in half pixels: exact in `f32`.
    #[inline(always)]
    fn narrow_columns(&self, x0: u32) -> W::Lane {
        W::Lane::ramp(x0 as f32) * W::Lane::splat(2.0) + W::Lane::splat(1.0 - self.width_f)
    }

    /// Row `j` as its offset `Y = h − 2j − 1` from the image centre in half pixels.
    #[inline(always)]
    fn narrow_row_offset(&self, j: u32) -> f32 {
        (self.height as f32 - 2.0 * j as f32) - 1.0
    }

    /// The narrow constants of row `j` for the spheres with a span on it.
    #[inline(never)]
    pub(crate) fn narrow_row(&self, row: &mut NarrowRow<S, L>, j: u32, spans: &[Option<Span>]) {
        row.spheres.clear();
        row.slot = [0; S];
        let Some(view) = self.narrow.as_ref() else {
            return;
        };
        let y = self.narrow_row_offset(j);
        // D at X = 0 on this row.
        let base = self.forward + view.sy.scale(y);
        row.a = [
            base.dot(base),
            2.0 * base.dot(view.sx),
            view.sx.dot(view.sx),
        ];
        for (dl, l) in row.dl.iter_mut().zip(&view.to_light) {
            *dl = [base.dot(*l), view.sx.dot(*l)];
        }
        let sx2 = view.sx.dot(view.sx);
        let lights = self.lights.len().min(L);
        for (k, (s, span)) in self.spheres.iter().zip(spans).enumerate() {
            let (Some(n), Some(_)) = (s.narrow.as_ref(), span) else {
                continue;
            };
            let mut sphere = RowSphere::ZERO;
            let out = &mut sphere;
            // D at the sphere's middle column: `x = X − X₀` from there.
            let d0 = base + view.sx.scale(n.origin);
            let w0 = n.o.cross(d0);
            out.e = [
                d0.dot(d0) - w0.dot(w0),
                2.0 * (d0.dot(view.sx) - w0.dot(n.o_sx)),
                sx2 - n.o_sx.dot(n.o_sx),
            ];
            out.b = [n.o.dot(d0), n.o.dot(view.sx)];
            for l in 0..lights {
                let v0 = view.to_light[l].cross(d0);
                let vx = view.l_sx[l];
                out.g[l] = [w0.dot(v0), w0.dot(vx) + n.o_sx.dot(v0), n.o_sx.dot(vx)];
            }
            // At most one entry per sphere: cannot fail.
            let pushed = row.spheres.push(sphere);
            debug_assert!(pushed.is_ok());
            if let Some(slot) = row.slot.get_mut(k) {
                *slot = row.spheres.len() as u16;
            }
        }
    }

    /// Sphere `k`'s constants on row `j` (`nrow`), for packets that test it alone; `None`
    /// if it has no span there.
    #[inline(always)]
    pub(crate) fn single<'a>(
        &'a self,
        k: usize,
        (j, nrow): (u32, &'a NarrowRow<S, L>),
    ) -> Option<Single<'a, W::Lane, L>> {
        let s = self.spheres.get(k)?;
        let n = s.narrow.as_ref()?;
        let p = &s.params;
        let filters = self.narrow_lights.get(k)?;
        // Off the sphere's shadow rows no caster can block: none is tested. Chosen here,
        // once for every packet of the run.
        let (first, end) = n.shadows;
        let tested = !SHADOW_ROWS || (u32::from(first) <= j && j < u32::from(end));
        Some(Single {
            id: k as f32,
            origin: n.origin,
            radius: n.radius,
            row: nrow.sphere(k)?,
            filters: if tested {
                filters
            } else {
                NoCasters::<L>::FILTERS
            },
            hitting: Hitting {
                kd_albedo: Vec3::splat(p.kd_albedo),
                ks: W::Lane::splat(n.ks),
                shininess: W::Lane::splat(p.shininess),
                blinn: W::Lane::splat(0.0).lt(W::Lane::splat(p.blinn)),
                own_limit: W::Lane::splat(n.own_limit),
            },
        })
    }

    /// The packet of pixels `x0, x0 + 1, …` on row `j` shaded by the narrow kernel where
    /// `single` is the only candidate: [`Self::shade_narrow`] for such a packet, with the
    /// sphere's constants looked up once for every packet of a run. `flags`: record the
    /// shadow bits; saturate (as [`Prepared::shade`]'s).
    #[inline(always)]
    pub(crate) fn shade_single(
        &self,
        (j, nrow): (u32, &NarrowRow<S, L>),
        single: &Single<'_, W::Lane, L>,
        x0: u32,
        (record_hits, saturate): (bool, bool),
    ) -> (Packet<W::Lane>, W::Lane) {
        let zero = W::Lane::splat(0.0);
        let far = W::Lane::splat(f32::MAX);
        let bg = self.background;
        let mut packet = Packet {
            color: Vec3::splat(Vec3::new(bg.r, bg.g, bg.b)),
            sphere: W::Lane::splat(-1.0),
            shadowed: [0; 8],
        };
        let x = self.narrow_columns(x0);
        let xl = x - W::Lane::splat(single.origin);
        let rs = single.row;
        let e = horner(rs.e, xl);
        let b = W::Lane::splat(rs.b[0]) + xl * W::Lane::splat(rs.b[1]);
        let hit = W::Lane::and(zero.le(e), b.lt(zero));
        if !W::Lane::any(hit) {
            return (packet, far);
        }
        let id = W::Lane::select(hit, W::Lane::splat(single.id), W::Lane::splat(-1.0));
        packet.sphere = id;
        let root = W::Lane::select(hit, e.max(zero).sqrt(), zero);
        let key = W::Lane::select(hit, (-b - root) * W::Lane::splat(single.radius), far);
        let geometry = Geometry {
            x,
            root,
            id,
            any_hit: hit,
        };
        let candidates = [single.id as u16];
        self.narrow_lights_stage(
            (j, nrow, &candidates),
            &geometry,
            &single.hitting,
            |l| horner(rs.g.get(l).copied().unwrap_or([0.0; 3]), xl),
            |l| single.filters.get(l).copied().unwrap_or_default(),
            (record_hits, saturate, &mut packet),
        );
        (packet, key)
    }

    /// The packet of pixels `x0, x0 + 1, …` on row `j` (`nrow`) shaded by the narrow kernel,
    /// testing the spheres `candidates`. `saturate`: as [`Prepared::shade`]'s.
    #[inline(always)]
    pub(crate) fn shade_narrow(
        &self,
        (j, nrow): (u32, &NarrowRow<S, L>),
        x0: u32,
        candidates: &[u16],
        record_hits: bool,
        saturate: bool,
    ) -> (Packet<W::Lane>, W::Lane) {
        let bg = self.background;
        let background = Vec3::splat(Vec3::new(bg.r, bg.g, bg.b));
        let mut packet = Packet {
            color: background,
            sphere: W::Lane::splat(-1.0),
            shadowed: [0; 8],
        };
        let x = self.narrow_columns(x0);
        let (geometry, xl, key) = self.narrow_hit(nrow, x, candidates);
        let id = geometry.id;
        packet.sphere = id;
        if !W::Lane::any(geometry.any_hit) {
            return (packet, key);
        }
        let hitting = self.narrow_hitting(candidates, id);
        self.narrow_lights_stage(
            (j, nrow, candidates),
            &geometry,
            &hitting,
            |l| {
                own(candidates, id, |k| {
                    let g = nrow.sphere(k).and_then(|rs| rs.g.get(l).copied());
                    horner(g.unwrap_or([0.0; 3]), xl)
                })
            },
            |l| {
                // The union of the candidates' masks; the thresholds per lane are
                // taken in the stage.
                let mut f = NarrowLight::default();
                for &k in candidates {
                    if let Some(c) = self.narrow_lights.get(k as usize).and_then(|c| c.get(l)) {
                        f.casters |= c.casters;
                        f.ahead = f.ahead.max(c.ahead);
                        f.reach = f.reach.max(c.reach);
                    }
                }
                f
            },
            (record_hits, saturate, &mut packet),
        );
        (packet, key)
    }

    /// `hit` of the narrow kernel for the columns `x` (as `X`) on the row `nrow`: per lane
    /// the nearest of the `candidates` with `E′ ≥ 0` in front, by `r·(−b − √E′)`. Gives the
    /// lanes' [`Geometry`], each lane's `x = X − X₀` of that sphere (0 on a miss) and the
    /// distance key (`f32::MAX` on a miss).
    #[inline(always)]
    fn narrow_hit(
        &self,
        nrow: &NarrowRow<S, L>,
        x: W::Lane,
        candidates: &[u16],
    ) -> (Geometry<W::Lane>, W::Lane, W::Lane) {
        let zero = W::Lane::splat(0.0);
        let mut key = W::Lane::splat(f32::MAX);
        let (mut root, mut xl) = (zero, zero);
        let mut id = W::Lane::splat(-1.0);
        for &k in candidates {
            let (Some(n), Some(rs)) = (
                self.spheres.get(k as usize).and_then(|s| s.narrow.as_ref()),
                nrow.sphere(k as usize),
            ) else {
                continue;
            };
            let here = x - W::Lane::splat(n.origin);
            let e = horner(rs.e, here);
            let b = W::Lane::splat(rs.b[0]) + here * W::Lane::splat(rs.b[1]);
            let hit = W::Lane::and(zero.le(e), b.lt(zero));
            if !W::Lane::any(hit) {
                continue;
            }
            let r = e.max(zero).sqrt();
            let t = (-b - r) * W::Lane::splat(n.radius);
            let nearer = W::Lane::and(hit, t.lt(key));
            key = W::Lane::select(nearer, t, key);
            root = W::Lane::select(nearer, r, root);
            xl = W::Lane::select(nearer, here, xl);
            id = W::Lane::select(nearer, W::Lane::splat(k as f32), id);
        }
        let any_hit = zero.le(id);
        let geometry = Geometry {
            x,
            root,
            id,
            any_hit,
        };
        (geometry, xl, key)
    }

    /// What the light stage reads of each lane's sphere ([`Hitting`]), the sphere being the
    /// one of the `candidates` that the lane's `id` names.
    #[inline(always)]
    fn narrow_hitting(&self, candidates: &[u16], id: W::Lane) -> Hitting<W::Lane> {
        let zero = W::Lane::splat(0.0);
        let value = |f: &dyn Fn(&super::prepare::PreparedSphere) -> f32| {
            own(candidates, id, |k| {
                W::Lane::splat(self.spheres.get(k).map_or(0.0, f))
            })
        };
        Hitting {
            kd_albedo: Vec3::new(
                value(&|s| s.params.kd_albedo.x),
                value(&|s| s.params.kd_albedo.y),
                value(&|s| s.params.kd_albedo.z),
            ),
            ks: value(&|s| s.narrow.as_ref().map_or(0.0, |n| n.ks)),
            shininess: value(&|s| s.params.shininess),
            blinn: zero.lt(value(&|s| s.params.blinn)),
            own_limit: value(&|s| s.narrow.as_ref().map_or(0.0, |n| n.own_limit)),
        }
    }

    /// `packet` (shaded by [`Self::shade_single`] or [`Self::shade_narrow`], which also gave
    /// `key`, `|D|` times each lane's hit distance) with the lanes that outlines cross
    /// anti-aliased, as the general kernel's packets are ([`Prepared::antialiased`]): the
    /// centre rays and hit distances it needs are formed here, only in frames with
    /// anti-aliasing on.
    #[cfg(feature = "antialias")]
    #[inline(always)]
    pub(crate) fn narrow_antialiased(
        &self,
        (packet, key): (Packet<W::Lane>, W::Lane),
        (row, nrow): (&super::prepare::Row, &NarrowRow<S, L>),
        x0: u32,
        candidates: &[u16],
    ) -> Packet<W::Lane> {
        if !self.antialias {
            return packet;
        }
        let x = self.narrow_columns(x0);
        let hit = W::Lane::splat(0.0).le(packet.sphere);
        let t = W::Lane::select(
            hit,
            key / horner(nrow.a, x).sqrt(),
            W::Lane::splat(f32::MAX),
        );
        let (u, d) = self.ray(row, x0);
        self.antialiased(packet, row, u, d, t, candidates)
    }

    /// The `lights` and `combine` stages of the narrow kernel: for each light `N·L` from its
    /// `G` (`g(l)`, each lane's own sphere's), the shadow tests (the lane's own sphere from
    /// `N·L`; casters where `filter(l)`, the loosest over the packet's spheres, lets a ray
    /// through), the diffuse and specular sums, then the packet's colour.
    #[inline(always)]
    fn narrow_lights_stage(
        &self,
        (j, nrow, candidates): (u32, &NarrowRow<S, L>, &[u16]),
        geo: &Geometry<W::Lane>,
        hitting: &Hitting<W::Lane>,
        g: impl Fn(usize) -> W::Lane,
        filter: impl Fn(usize) -> NarrowLight,
        (record_hits, saturate, packet): (bool, bool, &mut Packet<W::Lane>),
    ) {
        let (zero, one) = (W::Lane::splat(0.0), W::Lane::splat(1.0));
        let a = horner(nrow.a, geo.x);
        let sigma = one / a.sqrt();
        let sigma2 = sigma * sigma;
        let nv = geo.root * sigma;
        let mut normal: Option<Vec3<W::Lane>> = None;
        let mut diffuse_sum = Vec3::splat(Vec3::default());
        let mut specular_sum = Vec3::splat(Vec3::default());
        let lights = self.lights.len().min(L);
        for light_index in 0..lights {
            let (Some(PreparedLight::Distant { arriving, .. }), Some(dl)) =
                (self.lights.get(light_index), nrow.dl.get(light_index))
            else {
                continue;
            };
            let ld = (W::Lane::splat(dl[0]) + geo.x * W::Lane::splat(dl[1])) * sigma;
            let nl = normal_dot_light(g(light_index), sigma2, nv, ld);
            let mut blocked = W::Lane::and(nl.lt(zero), hitting.own_limit.lt(nl * nl));
            let f = filter(light_index);
            if f.casters != 0 {
                let open = W::Lane::and_not(geo.any_hit, blocked);
                let near = W::Lane::and(
                    open,
                    W::Lane::and(
                        nl.lt(W::Lane::splat(f.ahead)),
                        (nl * nl).le(W::Lane::splat(f.reach)),
                    ),
                );
                if W::Lane::any(near) {
                    let origin = *normal.get_or_insert_with(|| {
                        self.narrow_origin((j, geo.x), candidates, geo.id, (geo.root, sigma))
                    });
                    blocked = W::Lane::or(
                        blocked,
                        self.narrow_casters(light_index, candidates, geo.id, origin, near),
                    );
                }
            }
            if record_hits && light_index < 32 {
                let bits = W::Lane::bitmask(W::Lane::and(geo.any_hit, blocked));
                for (lane, word) in packet.shadowed.iter_mut().enumerate() {
                    *word |= ((bits >> lane) & 1) << light_index;
                }
            }
            let lit = W::Lane::and_not(geo.any_hit, blocked);
            if !W::Lane::any(lit) {
                continue;
            }
            let vis = W::Lane::select(lit, one, zero);
            let arriving = Vec3::splat(*arriving);
            diffuse_sum = diffuse_sum + arriving * (nl.max(zero) * vis);
            let cosine = lobe_cosine(nl, nv, ld, hitting.blinn);
            if W::Lane::any(zero.lt(cosine)) {
                let lobe = W::Lane::pow_clamped(cosine, hitting.shininess) * vis;
                specular_sum = specular_sum + arriving * lobe;
            }
        }
        packet.color = combine_with(
            (hitting.kd_albedo, hitting.ks),
            (diffuse_sum, specular_sum),
            geo.any_hit,
            packet.color,
            saturate,
        );
    }

    /// The lanes of `near` (those the caster filter lets through) whose shadow ray from
    /// `origin` (`P + ε·N`) toward distant light `light` meets one of the casters of the
    /// lane's own sphere: the general kernel's [`meets`]. Out of line: a few pixels a frame.
    #[inline(never)]
    fn narrow_casters(
        &self,
        light: usize,
        candidates: &[u16],
        id: W::Lane,
        origin: Vec3<W::Lane>,
        near: <W::Lane as Real>::Mask,
    ) -> <W::Lane as Real>::Mask {
        let (zero, one) = (W::Lane::splat(0.0), W::Lane::splat(1.0));
        let mask = |k: usize| {
            self.narrow_lights
                .get(k)
                .and_then(|l| l.get(light))
                .map_or(0, |f| f.casters)
        };
        let Some(view) = self.narrow.as_ref() else {
            return zero.lt(zero);
        };
        let l = Vec3::splat(view.to_light.get(light).copied().unwrap_or_default());
        let eps = W::Lane::splat(self.epsilon);
        let mut casters = 0u32;
        for &k in candidates {
            casters |= mask(k as usize);
        }
        let mut blocked = zero.lt(zero);
        while casters != 0 {
            let k = casters.trailing_zeros() as usize;
            casters &= casters - 1;
            let Some(c) = self.spheres.get(k) else {
                continue;
            };
            let oc = origin - Vec3::splat(c.center);
            let hit = meets(oc, l, W::Lane::splat(c.radius_sq), eps, None);
            // Only lanes whose own sphere has `k` among its casters.
            let listed = own(candidates, id, |s| {
                if mask(s) & (1 << k) != 0 {
                    one
                } else {
                    zero
                }
            });
            blocked = W::Lane::or(
                blocked,
                W::Lane::and(W::Lane::and(hit, near), zero.lt(listed)),
            );
        }
        blocked
    }

    /// `P + ε·N` of each lane's hit, for caster tests: `P = C + r·N` with
    /// `N = ô − (b·σ + N·V)·σ·D`, `D` the pixel's direction (`x` its `X`) and `b`, `√E′` of
    /// the lane's own sphere. Out of line: only where a caster may block.
    #[inline(never)]
    fn narrow_origin(
        &self,
        (j, x): (u32, W::Lane),
        candidates: &[u16],
        id: W::Lane,
        (root, sigma): (W::Lane, W::Lane),
    ) -> Vec3<W::Lane> {
        let Some(view) = self.narrow.as_ref() else {
            return Vec3::splat(Vec3::default());
        };
        let y = self.narrow_row_offset(j);
        let base = Vec3::splat(self.forward + view.sy.scale(y));
        let d = base + Vec3::splat(view.sx) * x;
        let comp = |f: fn(&Vec3) -> f32| {
            own(candidates, id, |k| {
                W::Lane::splat(
                    self.spheres
                        .get(k)
                        .and_then(|s| s.narrow.as_ref())
                        .map_or(0.0, |n| f(&n.o)),
                )
            })
        };
        let o = Vec3::new(comp(|v| v.x), comp(|v| v.y), comp(|v| v.z));
        let b = o.dot(d);
        let n = o - d * ((b * sigma + root * sigma) * sigma);
        let center = |f: fn(&Vec3) -> f32| {
            own(candidates, id, |k| {
                W::Lane::splat(self.spheres.get(k).map_or(0.0, |s| f(&s.center)))
            })
        };
        let radius_eps = own(candidates, id, |k| {
            W::Lane::splat(
                self.spheres
                    .get(k)
                    .and_then(|s| s.narrow.as_ref())
                    .map_or(0.0, |n| n.radius),
            ) + W::Lane::splat(self.epsilon)
        });
        let c = Vec3::new(center(|v| v.x), center(|v| v.y), center(|v| v.z));
        c + n * radius_eps
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;
    use crate::scene::Scene;
    use crate::test_scenes::{random_classic_scene, uniform, Draw};
    use crate::{HitRecord, LinearRgb, Render, Rgb888, Scalar, Simd8};
    use std::vec::Vec;

    /// Random frames of classic spheres under distant lights, close enough to shadow each
    /// other, with highlights up to `n = 2¹¹`: the frames the narrow kernel takes.
    fn random_scenes(seed: u64, count: usize) -> Vec<Scene<8, 4>> {
        let mut next = uniform(seed);
        let draw = Draw {
            half_extent: Vec3::new(2.0, 1.5, 2.0),
            radius: (0.3, 1.3),
            varied: true,
        };
        (0..count)
            .map(|_| random_classic_scene(&mut next, &draw))
            .collect()
    }

    fn frame<T: crate::Pixel + Default, W: FloatPath>(p: &Prepared<W, 8, 4>) -> Vec<T> {
        let mut out = std::vec![T::default(); (p.width * p.height) as usize];
        p.render_frame(&mut out).unwrap();
        out
    }

    /// The narrow kernel's frames against the general kernel's, which computes the same
    /// model from the hit point and normal: the same sphere at every pixel, at most a level
    /// apart in 8-bit colour, and rarely that; and the narrow frames within a tenth of a
    /// level (`0.1/255`) of the `f64` reference in linear colour.
    #[test]
    fn narrow_frames_agree_with_the_general_kernel() {
        let (w, h) = (120u32, 90u32);
        let (mut narrow_frames, mut pixels, mut other_sphere, mut level_apart) = (0, 0, 0, 0);
        let (mut worst_error, mut worst_general) = (0.0f64, 0.0f64);
        for scene in random_scenes(0x6a09_e667_f3bc_c908, 40) {
            let Ok(narrow) = Prepared::<Scalar, 8, 4>::new(&scene, w, h) else {
                continue;
            };
            if narrow.narrow.is_none() {
                continue;
            }
            narrow_frames += 1;
            // The same frame through the general kernel: the row driver dispatches on
            // `kernel`, and the narrow constants go with it.
            let mut general = narrow.clone();
            general.kernel = crate::Kernel::General {
                item: crate::Item::Camera,
                field: "vfov",
            };
            general.narrow = None;
            let (ha, hb): (Vec<HitRecord>, Vec<HitRecord>) = (frame(&narrow), frame(&general));
            let (qa, qb): (Vec<Rgb888>, Vec<Rgb888>) = (frame(&narrow), frame(&general));
            let (la, lb): (Vec<LinearRgb>, Vec<LinearRgb>) = (frame(&narrow), frame(&general));
            let mut want = std::vec![crate::reference::RefPixel::default(); (w * h) as usize];
            crate::reference::render_frame(&scene, w, h, &mut want).unwrap();
            let error = |got: &[LinearRgb]| {
                let mut worst = 0.0f64;
                for (g, r) in got.iter().zip(&want) {
                    for (a, b) in [g.r, g.g, g.b].iter().zip(r.color) {
                        worst = worst.max((*a as f64 - b).abs());
                    }
                }
                worst
            };
            let (ea, eb) = (error(&la), error(&lb));
            worst_error = worst_error.max(ea);
            worst_general = worst_general.max(eb);
            for i in 0..qa.len() {
                pixels += 1;
                other_sphere += (ha[i].sphere != hb[i].sphere) as usize;
                let (ca, cb) = (qa[i], qb[i]);
                let apart = [(ca.r, cb.r), (ca.g, cb.g), (ca.b, cb.b)]
                    .iter()
                    .map(|&(x, y)| x.abs_diff(y))
                    .max()
                    .unwrap_or(0);
                assert!(apart <= 1, "8-bit colours {ca:?} and {cb:?} at pixel {i}");
                level_apart += (apart == 1) as usize;
            }
        }
        std::println!(
            "{narrow_frames} narrow frames, {pixels} pixels: {level_apart} a level apart, \
             {other_sphere} on another sphere; largest linear error to the f64 reference \
             {worst_error:.3e} (general kernel {worst_general:.3e})"
        );
        assert!(
            narrow_frames >= 20,
            "only {narrow_frames} frames took the narrow kernel"
        );
        assert!(
            worst_error <= 0.1 / 255.0,
            "linear error {worst_error} to the reference"
        );
        assert!(
            other_sphere * 1000 <= pixels,
            "{other_sphere} pixels hit another sphere"
        );
        assert!(
            level_apart * 1000 <= pixels,
            "{level_apart} of {pixels} pixels a level apart"
        );
    }

    /// The cosines the kernel shades with (`N·L`, `N·V` and the lobe's), from the row's
    /// quadrics as the kernel evaluates them, against the same cosines in `f64` from the ray
    /// and the hit point, on every lit pixel of random narrow frames: within
    /// `|ô|·`[`COS_ERROR`].
    #[test]
    fn narrow_cosines_within_their_bound() {
        let (w, h) = (120u32, 90u32);
        let (mut worst, mut measured) = ([0.0f64; 3], 0usize);
        for scene in random_scenes(0x3c6e_f372_fe94_f82b, 40) {
            let Ok(p) = Prepared::<Scalar, 8, 4>::new(&scene, w, h) else {
                continue;
            };
            let Some(view) = p.narrow else {
                continue;
            };
            let hits: Vec<HitRecord> = frame(&p);
            let f64v = |v: Vec3| [v.x as f64, v.y as f64, v.z as f64];
            let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
            let (fw, sx, sy) = (f64v(p.forward), f64v(view.sx), f64v(view.sy));
            for y in 0..h {
                let spans = p.row_spans(y);
                let mut nrow = NarrowRow::empty();
                p.narrow_row(&mut nrow, y, &spans);
                for x in 0..w {
                    let Some(k) = hits[(y * w + x) as usize].sphere else {
                        continue;
                    };
                    let (k, sphere) = (k as usize, &p.spheres[k as usize]);
                    let (Some(n), Some(rs)) = (sphere.narrow, nrow.sphere(k)) else {
                        panic!("sphere {k} hit at ({x}, {y}) without narrow constants");
                    };
                    // The kernel's values, as `shade_single` and the light stage form them.
                    let xf = (2 * x + 1) as f32 - p.width_f;
                    let xl = xf - n.origin;
                    let e = horner::<f32>(rs.e, xl);
                    let root = e.max(0.0).sqrt();
                    let sigma = 1.0 / horner::<f32>(nrow.a, xf).sqrt();
                    let nv = root * sigma;
                    // The same in f64 from the ray: D = F + X·Sx + Y·Sy, the hit on the unit
                    // sphere around the origin seen from ô.
                    let yf = (h as f64 - 2.0 * y as f64) - 1.0;
                    let d: [f64; 3] =
                        core::array::from_fn(|i| fw[i] + xf as f64 * sx[i] + yf * sy[i]);
                    let len = dot(d, d).sqrt();
                    let d = d.map(|c| c / len);
                    let o = f64v(n.o);
                    let b = dot(o, d);
                    let disc = b * b - (dot(o, o) - 1.0);
                    let t = -b - disc.max(0.0).sqrt();
                    let normal: [f64; 3] = core::array::from_fn(|i| o[i] + t * d[i]);
                    let nv_exact = -dot(normal, d);
                    // The bound scales with |ô|: see `COS_ERROR`.
                    let unit = dot(o, o).sqrt() * COS_ERROR as f64;
                    worst[0] = worst[0].max((nv as f64 - nv_exact).abs() / unit);
                    for (l, light) in view.to_light.iter().enumerate().take(p.lights.len()) {
                        let ld = (nrow.dl[l][0] + xf * nrow.dl[l][1]) * sigma;
                        let nl =
                            normal_dot_light(horner::<f32>(rs.g[l], xl), sigma * sigma, nv, ld);
                        let lv = f64v(*light);
                        let nl_exact = dot(normal, lv);
                        worst[1] = worst[1].max((nl as f64 - nl_exact).abs() / unit);
                        let blinn = sphere.params.blinn > 0.0;
                        let cos = lobe_cosine::<f32>(nl, nv, ld, blinn);
                        let cos_exact = if blinn {
                            let hv: [f64; 3] = core::array::from_fn(|i| lv[i] - d[i]);
                            dot(normal, hv) / dot(hv, hv).sqrt()
                        } else {
                            2.0 * nl_exact * nv_exact + dot(lv, d)
                        };
                        // Lit pixels, where the lobe counts.
                        if nl_exact > 0.0 {
                            worst[2] = worst[2].max((cos as f64 - cos_exact).abs() / unit);
                            measured += 1;
                        }
                    }
                }
            }
        }
        std::println!(
            "{measured} lit pixel-lights: worst errors in |ô|·COS_ERROR: N·V {:.3}, N·L {:.3}, \
             lobe cosine {:.3}",
            worst[0],
            worst[1],
            worst[2]
        );
        assert!(measured > 50_000, "only {measured} lit pixel-lights");
        for (what, e) in ["N·V", "N·L", "the lobe cosine"].iter().zip(worst) {
            assert!(e <= 1.0, "{what} off by {e} times |ô|·COS_ERROR");
        }
    }

    /// The caster filter only skips tests that fail: with it opened (every caster of
    /// [`Scene::shadow_casters`]' mask tested at every pixel, those the plane and receding
    /// rules left out too) the frames keep every bit, at every lane width. Over random
    /// frames of spheres near each other and of spheres resting on floors, and the `floor`
    /// preset.
    #[test]
    fn the_caster_filter_changes_no_pixel() {
        let (w, h) = (96u32, 72u32);
        let (mut filtered, mut planes) = (0usize, 0usize);
        let mut next = uniform(0x3c6e_f372_fe94_f82b);
        let floors = (0..30).map(|_| crate::test_scenes::random_floor_scene::<8, 4>(&mut next));
        // The floor preset: its fill light is low enough that the receding rule, not the
        // plane, leaves the floor out of the resting spheres' casters.
        let matrix_floor = crate::test_scenes::with_capacity(&crate::floor().unwrap());
        for scene in random_scenes(0xbb67_ae85_84ca_a73b, 30)
            .into_iter()
            .chain(floors)
            .chain([matrix_floor])
        {
            let Ok(frame_scalar) = Prepared::<Scalar, 8, 4>::new(&scene, w, h) else {
                continue;
            };
            if frame_scalar.narrow.is_none() {
                continue;
            }
            let simd = Prepared::<Simd8, 8, 4>::new(&scene, w, h).unwrap();
            let mut open = frame_scalar.clone();
            let mut open_simd = simd.clone();
            let opened = open.narrow_lights.iter_mut().enumerate();
            for (i, lights) in opened.chain(open_simd.narrow_lights.iter_mut().enumerate()) {
                for (k, f) in lights.iter_mut().enumerate() {
                    if f.casters != 0 {
                        filtered += (f.ahead < 1.0 || f.reach < 1.0) as usize;
                    }
                    let all = scene
                        .lights()
                        .get(k)
                        .map_or(0, |l| scene.shadow_casters(i, l));
                    planes += (all & !f.casters != 0) as usize;
                    f.casters = all;
                    f.ahead = f32::INFINITY;
                    f.reach = f32::INFINITY;
                }
            }
            let bits = |v: Vec<LinearRgb>| -> Vec<[u32; 3]> {
                v.iter()
                    .map(|c| [c.r.to_bits(), c.g.to_bits(), c.b.to_bits()])
                    .collect()
            };
            let filtered_bits = bits(frame(&frame_scalar));
            assert!(
                filtered_bits == bits(frame(&open)),
                "scalar: the filter changed a pixel"
            );
            assert!(
                filtered_bits == bits(frame(&open_simd)),
                "simd8: the filter changed a pixel"
            );
            let (ha, hb): (Vec<HitRecord>, Vec<HitRecord>) = (frame(&frame_scalar), frame(&open));
            assert_eq!(ha, hb, "the filter changed a hit record");
        }
        assert!(
            filtered > 10 && planes > 10,
            "the filter narrowed only {filtered} sphere-light pairs, the plane rule {planes}"
        );
    }

    /// The `floor` preset's floor leaves the casters of the four spheres resting on it for
    /// both its distant lights: under the key light by the plane rule, under the fill light,
    /// 24° to 27° above the floor, by the receding rule (`prepare::recedes`).
    #[test]
    fn the_floor_presets_floor_leaves_the_casters() {
        let scene = crate::floor().unwrap();
        let frame = Prepared::<Scalar, 6, 3>::new(&scene, 160, 120).unwrap();
        assert!(frame.narrow.is_some());
        let floor = (0..scene.spheres().len())
            .max_by(|&a, &b| {
                scene.spheres()[a]
                    .radius
                    .total_cmp(&scene.spheres()[b].radius)
            })
            .unwrap();
        let mut checked = 0;
        for (i, lights) in frame.narrow_lights.iter().enumerate() {
            for (k, light) in lights.iter().enumerate().take(scene.lights().len()) {
                if i != floor {
                    assert_eq!(light.casters & (1 << floor), 0, "sphere {i}, light {k}");
                    checked += 1;
                }
            }
        }
        assert_eq!(checked, 8, "four spheres, two lights");
    }
}
