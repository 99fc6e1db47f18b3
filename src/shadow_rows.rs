//! The geometry of the shadow rows both narrow kernels use (`src/fixed/narrow_shadow_rows.rs`,
//! `src/float/shadow_rows.rs`): for a receiver sphere, the rows of the frame on which a
//! caster's shadow can fall on it at all, so that the receiver's pixels on every other row
//! skip the casters' filters and rays. The geometry is here once, in `f32`, over points,
//! lengths and directions in whatever unit a path has (the fixed path's raw scaled integers,
//! the float path's scene units); each path brings its own margins for its own rounding,
//! which is why they are parameters, as [`crate::caster_plane`] leaves its margin to each
//! path too.
//!
//! A ray from a point `X` toward a light meets a caster of radius `r` only if `X` lies in the
//! caster's shadow volume ([`Volume`]): for a distant light the half-cylinder of radius `r`
//! along the light behind the caster, for a point light the cone from the light through the
//! caster, beyond its near side. With `A(s)` the volume's axis at `s` along it and `ρ(s)` its
//! radius there (constant, or growing linearly from a point light), such an `X` on the
//! receiver (centre `C`, radius `R`) has `A(s)` within `ρ(s)` of the receiver's surface,
//! which bounds `s` to at most two intervals (the axis entering and leaving the receiver's
//! shell), each from one quadratic; and `X` is on the part of the receiver the eye sees
//! (`(X − C)·(E − C) ≥ R²`), which bounds `s` once more. Each interval is cut in [`PIECES`];
//! the volume over a piece lies in a ball around its middle, and the shadow on the receiver
//! in that ball's cap of the receiver's surface, a disc seen at a slant ([`Screen::cap`]),
//! whose rows follow from each camera coordinate's interval. The rows are the union of those
//! over the receiver's casters and lights, widened by two ([`Screen::rows`]).
//!
//! Besides the margins a path passes in (the casters' radii widened, the receiver's surface
//! widened by `δ`, an absolute part of each interval's margin), each interval is widened by
//! `2⁻¹¹` of the lengths it is made from. A cap that reaches the eye's plane, a light within
//! or close to a caster, or a NaN keeps every row (`None`): the rows only ever skip pixels no
//! caster can block.

/// The pieces an interval of a shadow volume is bounded in (see [`Screen::cap`]).
const PIECES: usize = 8;

/// A point or vector in a path's unit (`f32`).
pub(crate) type P3 = [f32; 3];

/// `a > b`, false where either is NaN (which then keeps every row).
fn greater(a: f32, b: f32) -> bool {
    a.partial_cmp(&b) == Some(core::cmp::Ordering::Greater)
}

#[inline(never)]
fn dot(a: P3, b: P3) -> f32 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn minus(a: P3, b: P3) -> P3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn length(a: P3) -> f32 {
    root(dot(a, a))
}

/// `|a − b|`, in `f32` as the rows' geometry computes it.
pub(crate) fn distance(a: P3, b: P3) -> f32 {
    length(minus(a, b))
}

/// `√x` (`libm`'s, correctly rounded), out of line: on a core without an FPU every copy is
/// a few hundred bytes of flash, and the prepare takes it a few dozen times a sphere.
#[inline(never)]
fn root(x: f32) -> f32 {
    libm::sqrtf(x)
}

/// A light as the shadow volumes see it.
#[derive(Clone, Copy)]
pub(crate) enum Light {
    /// A distant light whose rays travel along the unit vector (away from the light).
    Distant(P3),
    /// A point light at the position.
    Point(P3),
}

/// A shadow volume: its axis `origin + s·dir` for `s ≥ s_min`, of radius `base + slope·s`.
struct Volume {
    origin: P3,
    dir: P3,
    base: f32,
    slope: f32,
    s_min: f32,
}

impl Volume {
    /// The volume of a caster at `center` of radius `r` (already widened by the path's
    /// margin) for `light`; `None` where it cannot be bounded so (a point light within or
    /// close to the caster, which then subtends a cone wider than about 26° from it).
    fn new(light: Light, center: P3, r: f32) -> Option<Self> {
        match light {
            Light::Distant(dir) => Some(Volume {
                origin: center,
                dir,
                base: r,
                slope: 0.0,
                s_min: -r,
            }),
            Light::Point(p) => {
                let v = [center[0] - p[0], center[1] - p[1], center[2] - p[2]];
                let d0 = length(v);
                if !greater(d0, 2.5 * r) {
                    return None;
                }
                let slope = r / root(d0 * d0 - r * r) * (1.0 + 1.0 / 1024.0);
                Some(Volume {
                    origin: p,
                    dir: v.map(|c| c / d0),
                    base: 0.0,
                    slope,
                    s_min: d0 - r,
                })
            }
        }
    }

    fn at(&self, s: f32) -> (P3, f32) {
        let [o, d] = [self.origin, self.dir];
        let c = [o[0] + s * d[0], o[1] + s * d[1], o[2] + s * d[2]];
        (c, self.base + self.slope * s)
    }
}

/// The screen's rows: each pixel's direction is `F + dx·Sx + dy·Sy` with
/// `dy = height − 2y − 1` (both narrow kernels' view); here the unit vectors along `F` and
/// `Sy`, and the scale from a tangent above the view's axis to `dy`.
pub(crate) struct Screen {
    eye: P3,
    /// The unit vectors along `F` (the depth) and along `Sy` (up).
    axes: [P3; 2],
    /// `|F|/|Sy|`: `dy` per unit of the tangent.
    scale: f32,
    height: f32,
    /// The least depth a cap's nearest point may have: nearer, its rows are not bounded.
    near: f32,
}

impl Screen {
    /// The screen of a frame `height` rows high seen from `eye`, whose pixels' directions
    /// have the depth `forward` (`F`) and the step `step_y` (`Sy`, half a row up); a cap
    /// whose depth is not above `near` (a small length of the path's unit) keeps every row.
    pub(crate) fn new(eye: P3, (forward, step_y): (P3, P3), height: u32, near: f32) -> Self {
        let (lf, ly) = (length(forward), length(step_y));
        Screen {
            eye,
            axes: [forward.map(|c| c / lf), step_y.map(|c| c / ly)],
            scale: lf / ly,
            height: height as f32,
            near,
        }
    }

    /// The eye.
    pub(crate) fn eye(&self) -> P3 {
        self.eye
    }

    /// The whole rows `[first, end)` that hold the fractional rows `seen`
    /// (`(first, last)`), widened by two and clamped to the frame; `(0, 0)` if `seen` is
    /// empty (`first > last`).
    pub(crate) fn rows(&self, (first, last): (f32, f32)) -> (u16, u16) {
        if first > last {
            return (0, 0);
        }
        // The frame's height is at most `MAX_DIMENSION`, which fits 16 bits.
        let clamp = |v: f32| libm::floorf(v).max(0.0).min(self.height) as u16;
        (clamp(first - 2.0), clamp(last + 3.0))
    }

    /// The rows (fractional, `(first, last)`) of the part of a receiver's surface
    /// (`(centre, radius, δ)`) within `rho` of `center`, or `None` if it comes within the
    /// screen's `near` of the eye's plane; `first > last` if there is none.
    ///
    /// That part is a cap of the receiver: the points `X` with `(X − C)·n̂ ≥ τ`, `n̂` toward
    /// `center` and `τ` from the triangle of the two radii and the centres' distance. It lies
    /// in a disc of the cap's radius `a` across `n̂`, thick from `τ` to `R` along it (each
    /// widened by `δ`), so each camera coordinate of its points lies in an interval, and the
    /// screen coordinates (their ratios to the depth) between those of the intervals' ends.
    /// On a floor, whose caps are flat and seen at a slant, this is several times tighter
    /// than the ball around `center`.
    #[inline(never)]
    fn cap(&self, center: P3, rho: f32, (c, r, delta): (P3, f32, f32)) -> Option<(f32, f32)> {
        let v = minus(center, c);
        let dl = length(v);
        let (outer, tau) = if dl > rho {
            let tau = (r * r + dl * dl - rho * rho) / (2.0 * dl);
            // A point up to δ off the surface moves τ by up to δ·R/|A − C|.
            let tau = tau - delta * (1.0 + r / dl);
            if tau > r + delta {
                return Some((1.0, 0.0));
            }
            (r + delta, tau.max(-r - delta))
        } else {
            // The ball holds the receiver's centre: the whole receiver.
            (r + delta, -r - delta)
        };
        let n = if dl > 0.0 {
            v.map(|k| k / dl)
        } else {
            [0.0; 3]
        };
        let across = if tau > 0.0 {
            root(outer * outer - tau * tau)
        } else {
            outer
        };
        let q = minus(c, self.eye);
        // Each camera coordinate's interval: the centre's, the thickness along n̂, the disc.
        let range = |axis: P3| {
            let (base, along) = (dot(q, axis), dot(n, axis));
            let (a, b) = (tau * along, outer * along);
            let wide = across * root((1.0 - along * along).max(0.0));
            (base + a.min(b) - wide, base + a.max(b) + wide)
        };
        let [z, y] = self.axes.map(range);
        if !greater(z.0, self.near) {
            return None;
        }
        // The tangents above the axis at the interval's ends, over the nearest and the
        // farthest depth; y = (h − 1 − dy)/2 with dy = tangent·|F|/|Sy|.
        let (low, high) = ((y.0 / z.0).min(y.0 / z.1), (y.1 / z.0).max(y.1 / z.1));
        let row = |t: f32| (self.height - 1.0 - t * self.scale) / 2.0;
        Some((row(high), row(low)))
    }
}

/// The two `s` where `|A(s) − C| = r₀ + k·s`, with `p = (A(0) − C)·dir` and `|A(0) − C|`
/// (`s² + 2ps + |A(0) − C|² = (r₀ + k·s)²`, `k² < 1`): `None` where there are none, a
/// discriminant within rounding below 0 taken as 0 (the axis touching the sphere).
fn crossings((p, wl): (f32, f32), k: f32, r0: f32) -> Option<(f32, f32)> {
    let a = 1.0 - k * k;
    let b = p - r0 * k;
    let c = (wl - r0) * (wl + r0);
    let disc = b * b - a * c;
    if disc < -(b * b + (a * c).abs()) / 4096.0 {
        return None;
    }
    let root = root(disc.max(0.0));
    Some(((-b - root) / a, (-b + root) / a))
}

/// The intervals of `s` (at most two) where `volume` can reach the surface of a receiver at
/// `center` of radius `r`, seen from `eye`, its surface widened by `delta`, each widened by
/// `2⁻¹¹` of the lengths it is made from and by `absolute`; empty ones have `lo > hi`.
#[inline(never)]
fn intervals(
    volume: &Volume,
    (center, r, delta): (P3, f32, f32),
    eye: P3,
    absolute: f32,
) -> [(f32, f32); 2] {
    const EMPTY: [(f32, f32); 2] = [(1.0, 0.0); 2];
    let w = minus(volume.origin, center);
    let (p, wl, k) = (dot(w, volume.dir), length(w), volume.slope);
    let margin = (p.abs() + wl + r) / 2048.0 + absolute;
    let outer = r + delta + volume.base;
    let Some((o0, o1)) = crossings((p, wl), k, outer) else {
        return EMPTY;
    };
    let (lo, hi) = ((o0 - margin).max(volume.s_min - margin), o1 + margin);
    // Where the whole cross-section is inside the receiver's shell: no surface there.
    let inner = r - delta - volume.base;
    // Where `inner − k·s ≤ 0` nothing is excluded: the roots of (inner − k·s)² = |A − C|².
    let hole = if inner > 0.0 {
        crossings((p, wl), -k, inner).map(|(i0, i1)| {
            let i1 = if k > 0.0 { i1.min(inner / k) } else { i1 };
            (i0 + margin, i1 - margin)
        })
    } else {
        None
    };
    let mut pieces = match hole {
        Some((i0, i1)) if i0 < i1 => [(lo, hi.min(i0)), (lo.max(i1), hi)],
        _ => [(lo, hi), (1.0, 0.0)],
    };
    // The part of the receiver the eye sees: (X − C)·ê ≥ R²/|e| − δ with X within the
    // volume's radius of the axis: s·(dir·ê + k) ≥ R²/|e| − δ − base − w·ê.
    let e = minus(eye, center);
    let el = length(e);
    if el > r {
        let unit = e.map(|c| c / el);
        let slope = dot(volume.dir, unit) + k;
        let bound = r * r / el - delta - volume.base - dot(w, unit);
        // A shallower slope would take `s` far out, where `f32` rounding outgrows the margin:
        // no bound from it.
        if slope.abs() > 1.0 / 64.0 {
            let s = bound / slope;
            for piece in &mut pieces {
                if slope > 0.0 {
                    piece.0 = piece.0.max(s - margin);
                } else {
                    piece.1 = piece.1.min(s + margin);
                }
            }
        }
    }
    pieces
}

/// The rows of the shadow of a caster (`(centre, radius)`, the radius already widened by
/// the path's margin) for `light` on `receiver` (`(centre, radius, δ)`, its surface widened
/// by `δ`) on `screen`: `(first, last)` fractional, `first > last` if none; `None` where they
/// cannot be bounded (see the module docs). `absolute` widens each interval of the shadow
/// volume's axis besides its relative margin.
pub(crate) fn caster_rows(
    light: Light,
    (center, r): (P3, f32),
    receiver: (P3, f32, f32),
    screen: &Screen,
    absolute: f32,
) -> Option<(f32, f32)> {
    let volume = &Volume::new(light, center, r)?;
    let mut seen = (f32::INFINITY, f32::NEG_INFINITY);
    for (lo, hi) in intervals(volume, receiver, screen.eye, absolute) {
        if lo.is_nan() || hi.is_nan() {
            return None;
        }
        if lo > hi {
            continue;
        }
        // The interval in pieces, each in a ball around its middle (the volume between
        // two cross-sections lies in the hull of the balls at its ends), each ball's cap.
        let step = (hi - lo) / PIECES as f32;
        // A count the optimiser cannot see, so that it does not unroll the loop: on a core
        // without an FPU each copy of the body is a few hundred bytes of flash.
        for j in 0..core::hint::black_box(PIECES) {
            let (center, rho) = volume.at(lo + (j as f32 + 0.5) * step);
            let reach = rho + volume.slope * step / 2.0 + step / 2.0 + receiver.2;
            let (first, last) = screen.cap(center, reach, receiver)?;
            seen = (seen.0.min(first), seen.1.max(last));
        }
    }
    Some(seen)
}
