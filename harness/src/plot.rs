//! Lobe plots: pictures of what a material does to light, drawn from the same formulas the
//! renderer shades with.
//!
//! A rendered sphere shows a highlight; it does not show the function behind it. This module
//! draws that function, as one SVG of two panels (what `shadeline plot` writes):
//!
//! 1. a polar plot of one sphere's BRDF in the plane of incidence: light arrives at
//!    `incidence` degrees from the normal (from the left), the outgoing direction sweeps the
//!    upper half plane, and the radius is the reflected radiance per unit irradiance,
//!    `f(ω_i, ω_o)·cos θ_o`, per colour channel. The normal, the light and the mirror
//!    direction are marked;
//! 2. the lesson's curves `max(0, cos α)^n` against `α` for every distinct shininess the
//!    scene's spheres use, one line per `n`.
//!
//! The BRDF is [`shadeline::brdf::value`] evaluated on `f64`, with the constants of
//! [`Params::of`]: the code the float kernel runs on its lanes, not a copy of it, so the
//! plot cannot drift from the renderer. The sampling is separate from the drawing
//! ([`sample_lobe`], [`sample_curve`], [`shininesses`]) so that the numbers can be tested
//! without reading a picture back; [`figure`] only draws them, with `plotters`' SVG backend
//! (text is written as SVG `<text>`, so no font files are needed).
//!
//! Angles: `θ` is measured in degrees from the normal in the plane of incidence, positive
//! to the right. The light is at `θ = −incidence`, so the mirror direction is at
//! `θ = +incidence` ([`mirror_angle`]).

use plotters::coord::types::RangedCoordf64;
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use shadeline::brdf::{self, Params};
use shadeline::{Material, Model, Sphere, Surface, Vec3};
use std::fmt;

/// The incidence `shadeline plot` uses unless told otherwise, in degrees from the normal.
pub const DEFAULT_INCIDENCE: f64 = 45.0;

/// Samples of the polar lobe, over `θ_o` from −90° to 90° inclusive: a step of 0.25°.
pub const LOBE_SAMPLES: usize = 721;

/// Samples of each `cos^n` curve, over `α` from 0° to 90° inclusive: a step of 0.25°.
pub const CURVE_SAMPLES: usize = 361;

/// The step between two lobe samples, in degrees.
pub const LOBE_STEP: f64 = 180.0 / (LOBE_SAMPLES - 1) as f64;

/// The step between two curve samples, in degrees.
pub const CURVE_STEP: f64 = 90.0 / (CURVE_SAMPLES - 1) as f64;

/// The SVG's size in pixels: the polar panel on the left, the curves on the right.
pub const FIGURE_SIZE: (u32, u32) = (1400, 620);

/// Why a figure could not be made.
#[derive(Clone, Debug, PartialEq)]
pub enum PlotError {
    /// The sphere asked for is not in the scene.
    NoSuchSphere {
        /// The index asked for.
        index: usize,
        /// How many spheres the scene has.
        count: usize,
    },
    /// The incidence is not a finite angle in `[0, 90)` degrees.
    Incidence(f64),
    /// The drawing failed (`plotters`' message).
    Draw(String),
}

impl fmt::Display for PlotError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            PlotError::NoSuchSphere { index, count: 0 } => {
                write!(f, "there is no sphere {index}: the scene has no spheres")
            }
            PlotError::NoSuchSphere { index, count } => write!(
                f,
                "there is no sphere {index}: the scene has {count} sphere{}, numbered 0 to {}",
                if count == 1 { "" } else { "s" },
                count - 1
            ),
            PlotError::Incidence(deg) => write!(
                f,
                "the incidence is {deg}°: it is an angle from the normal, at least 0° and below 90°"
            ),
            PlotError::Draw(ref message) => write!(f, "the plot could not be drawn: {message}"),
        }
    }
}

impl std::error::Error for PlotError {}

/// Checks an incidence: a finite angle in `[0, 90)` degrees (at 90° the light grazes the
/// surface and the BRDF's `1/cos θ_i` is not defined).
pub fn check_incidence(degrees: f64) -> Result<f64, PlotError> {
    if (0.0..90.0).contains(&degrees) {
        Ok(degrees)
    } else {
        Err(PlotError::Incidence(degrees))
    }
}

/// The mirror direction of light arriving at `incidence` degrees: `θ = +incidence` (the
/// light is at `θ = −incidence`).
pub fn mirror_angle(incidence: f64) -> f64 {
    incidence
}

/// The unit vector at `theta` degrees from the normal `(0, 0, 1)`, in the plane `y = 0`,
/// positive `theta` toward `+x`.
fn direction(theta: f64) -> Vec3<f64> {
    let t = theta.to_radians();
    Vec3::new(t.sin(), 0.0, t.cos())
}

/// One outgoing direction of a lobe.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LobeSample {
    /// `θ_o`, degrees from the normal, positive on the mirror's side.
    pub theta: f64,
    /// `f(ω_i, ω_o)` per channel (red, green, blue), in 1/sr.
    pub brdf: [f64; 3],
    /// `f(ω_i, ω_o)·cos θ_o` per channel: the radiance reflected toward `θ_o` per unit
    /// irradiance. This is what the polar plot draws.
    pub reflected: [f64; 3],
}

impl LobeSample {
    /// The three channels of [`LobeSample::reflected`] added: what the peak is found on.
    pub fn total(&self) -> f64 {
        self.reflected.iter().sum()
    }
}

/// A material's BRDF sampled in the plane of incidence: [`LOBE_SAMPLES`] outgoing
/// directions from −90° to 90°.
#[derive(Clone, Debug, PartialEq)]
pub struct Lobe {
    /// The light's angle from the normal, degrees (it arrives from `θ = −incidence`).
    pub incidence: f64,
    /// The samples, in increasing `θ_o`.
    pub samples: Vec<LobeSample>,
}

impl Lobe {
    /// The sample with the largest [`LobeSample::total`] (the first of equal ones).
    ///
    /// # Panics
    ///
    /// If `samples` is empty, which a lobe from [`sample_lobe`] never is.
    pub fn peak(&self) -> LobeSample {
        self.samples
            .iter()
            .copied()
            .reduce(|best, s| if s.total() > best.total() { s } else { best })
            .expect("a lobe has samples")
    }

    /// The largest reflected value of any channel at any sample (0 for a black material).
    pub fn largest(&self) -> f64 {
        self.samples
            .iter()
            .flat_map(|s| s.reflected)
            .fold(0.0, f64::max)
    }

    /// Whether the three channels are equal everywhere (a grey material, or a white
    /// highlight on a grey diffuse lobe): then one line draws the lobe.
    pub fn is_grey(&self) -> bool {
        self.samples.iter().all(|s| {
            let [r, g, b] = s.reflected;
            let tolerance = 1e-12 * r.abs().max(g.abs()).max(b.abs());
            (r - g).abs() <= tolerance && (r - b).abs() <= tolerance
        })
    }
}

/// Samples `material`'s BRDF in the plane of incidence, light at `incidence` degrees from
/// the normal, with [`brdf::value`] on `f64`.
pub fn sample_lobe(material: &Material, incidence: f64) -> Result<Lobe, PlotError> {
    let incidence = check_incidence(incidence)?;
    let params = Params::<f64>::of(material);
    let normal = Vec3::new(0.0, 0.0, 1.0);
    let to_light = direction(-incidence);
    let samples = (0..LOBE_SAMPLES)
        .map(|i| {
            let theta = -90.0 + LOBE_STEP * i as f64;
            let view = direction(theta);
            let f = brdf::value(&params, normal, to_light, view);
            let brdf = [f.x, f.y, f.z];
            // At ±90° the cosine is 6e-17, not 0: the product is negligible either way.
            let cos_o = view.z.max(0.0);
            LobeSample {
                theta,
                brdf,
                reflected: brdf.map(|c| c * cos_o),
            }
        })
        .collect();
    Ok(Lobe { incidence, samples })
}

/// The lesson's curve: `max(0, cos α)^n`, `α` in degrees.
pub fn cosine_power(alpha: f64, n: f64) -> f64 {
    let c = alpha.to_radians().cos();
    if c > 0.0 {
        c.powf(n)
    } else {
        0.0
    }
}

/// The angle at which `cos α^n` falls to one half, in degrees: `acos(2^(−1/n))`.
pub fn half_angle(n: f64) -> f64 {
    (-1.0 / n).exp2().acos().to_degrees()
}

/// `(α, max(0, cos α)^n)` at [`CURVE_SAMPLES`] angles from 0° to 90°.
pub fn sample_curve(n: f64) -> Vec<(f64, f64)> {
    (0..CURVE_SAMPLES)
        .map(|i| {
            let alpha = CURVE_STEP * i as f64;
            (alpha, cosine_power(alpha, n))
        })
        .collect()
}

/// The cosine-power lobes of `material` that it has, as `(weight, shininess)`: lobe 0 (`ks`,
/// `shininess`) and, for the normalized models, lobes 1 and 2; a lobe of weight 0 is absent.
/// Lambert and Oren–Nayar have none, and GGX's lobe is not a cosine power: none either.
pub fn lobes(material: &Material) -> Vec<(f32, f32)> {
    let mut lobes = match material.model {
        Model::Lambert | Model::OrenNayar { .. } | Model::Ggx(_) => return Vec::new(),
        _ => vec![(material.ks, material.shininess)],
    };
    if let Some(spec) = material.model.specular() {
        lobes.extend(spec.more_lobes.iter().map(|l| (l.weight, l.shininess)));
    }
    lobes.retain(|&(weight, _)| weight > 0.0);
    lobes
}

/// Every distinct shininess of every lobe of every sphere (see [`lobes`]), ascending.
pub fn shininesses(spheres: &[Sphere]) -> Vec<f32> {
    let mut all: Vec<f32> = spheres
        .iter()
        .flat_map(|s| lobes(&s.material))
        .map(|(_, n)| n)
        .collect();
    all.sort_by(f32::total_cmp);
    all.dedup();
    all
}

/// A short name for a material: its model, roughness, surface and exponents, e.g.
/// `classic Phong, n = 50`, `normalized Blinn-Phong, gold, n = 40` or
/// `GGX, roughness 0.5, gold`.
pub fn describe(material: &Material) -> String {
    let model = match material.model {
        Model::Phong => "classic Phong",
        Model::BlinnPhong => "classic Blinn-Phong",
        Model::Lambert => "Lambert",
        Model::NormalizedPhong(_) => "normalized Phong",
        Model::NormalizedBlinnPhong(_) => "normalized Blinn-Phong",
        Model::OrenNayar { .. } => "Oren-Nayar",
        Model::Ggx(_) => "GGX",
        _ => "another model",
    };
    let mut parts = vec![model.to_string()];
    match material.model {
        Model::OrenNayar { roughness } => parts.push(format!("σ = {roughness} rad")),
        Model::Ggx(m) => parts.push(format!("roughness {}", m.roughness)),
        _ => {}
    }
    if let Some(surface) = material.model.surface() {
        match surface {
            Surface::Metal(metal) => parts.push(metal.name().to_string()),
            Surface::Dielectric { ior: Some(ior) } => parts.push(format!("ior {ior}")),
            Surface::Dielectric { ior: None } => {}
        }
    }
    let exponents: Vec<String> = lobes(material).iter().map(|(_, n)| n.to_string()).collect();
    if !exponents.is_empty() {
        parts.push(format!("n = {}", exponents.join(", ")));
    }
    parts.join(", ")
}

/// The colour of curve `i` of `count`: along a dark-blue → green → yellow ramp, so that the
/// order of the exponents reads from the colours.
fn ramp(i: usize, count: usize) -> RGBColor {
    const STOPS: [(f64, f64, f64); 5] = [
        (68.0, 1.0, 84.0),
        (59.0, 82.0, 139.0),
        (33.0, 145.0, 140.0),
        (94.0, 201.0, 98.0),
        (220.0, 200.0, 30.0),
    ];
    let t = if count > 1 {
        i as f64 / (count - 1) as f64
    } else {
        0.0
    };
    let at = t * (STOPS.len() - 1) as f64;
    let k = (at.floor() as usize).min(STOPS.len() - 2);
    let u = at - k as f64;
    let (a, b) = (STOPS[k], STOPS[k + 1]);
    let mix = |x: f64, y: f64| (x + (y - x) * u).round() as u8;
    RGBColor(mix(a.0, b.0), mix(a.1, b.1), mix(a.2, b.2))
}

/// A number for a label: three significant digits, trailing zeros dropped.
fn short(value: f64) -> String {
    if value == 0.0 || !value.is_finite() {
        return format!("{value}");
    }
    let digits = (2 - value.abs().log10().floor() as i32).max(0) as usize;
    let text = format!("{value:.digits$}");
    if text.contains('.') {
        text.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        text
    }
}

fn draw_error<E: std::error::Error + Send + Sync>(e: DrawingAreaErrorKind<E>) -> PlotError {
    PlotError::Draw(e.to_string())
}

/// A drawn figure, and the numbers it shows that a caller may want to print.
#[derive(Clone, Debug, PartialEq)]
pub struct Figure {
    /// The SVG document.
    pub svg: String,
    /// The plotted sphere's material, as [`describe`] names it.
    pub material: String,
    /// The lobe's peak ([`Lobe::peak`]).
    pub peak: LobeSample,
    /// The exponents of the curves, ascending ([`shininesses`]).
    pub exponents: Vec<f32>,
}

/// The two panels for sphere `sphere` of `spheres`, light at `incidence` degrees: the polar
/// lobe of its material on the left, the `cos^n` curves of every shininess in `spheres` on
/// the right.
pub fn figure(spheres: &[Sphere], sphere: usize, incidence: f64) -> Result<Figure, PlotError> {
    let material = spheres
        .get(sphere)
        .ok_or(PlotError::NoSuchSphere {
            index: sphere,
            count: spheres.len(),
        })?
        .material;
    let lobe = sample_lobe(&material, incidence)?;
    let exponents = shininesses(spheres);
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, FIGURE_SIZE).into_drawing_area();
        root.fill(&WHITE).map_err(draw_error)?;
        let (left, right) = root.split_horizontally(760);
        let title = format!("sphere {sphere}: {}", describe(&material));
        draw_lobe(&left, &lobe, &title)?;
        draw_curves(&right, &exponents)?;
        root.present().map_err(draw_error)?;
    }
    Ok(Figure {
        svg,
        material: describe(&material),
        peak: lobe.peak(),
        exponents,
    })
}

type Area<'a> = DrawingArea<SVGBackend<'a>, Shift>;

/// The left panel: the polar plot of `lobe`.
fn draw_lobe(area: &Area<'_>, lobe: &Lobe, title: &str) -> Result<(), PlotError> {
    let incidence = lobe.incidence;
    let mirror = mirror_angle(incidence);
    let peak = lobe.peak();
    let text = |size: u32| ("sans-serif", size).into_font().color(&BLACK);
    let centred = |size: u32| text(size).pos(Pos::new(HPos::Center, VPos::Top));
    let (width, _) = area.dim_in_pixel();
    let middle = width as i32 / 2;
    area.draw(&Text::new(
        "f(ω_i, ω_o)·cos θ_o in the plane of incidence (reflected radiance per unit irradiance, 1/sr)",
        (middle, 10),
        centred(18),
    ))
    .map_err(draw_error)?;
    area.draw(&Text::new(
        format!("{title}; light at θ_i = {incidence}°"),
        (middle, 36),
        centred(17),
    ))
    .map_err(draw_error)?;
    area.draw(&Text::new(
        format!(
            "peak at θ_o = {:.2}° (mirror direction {mirror}°), {} per unit irradiance",
            peak.theta,
            short(peak.reflected.iter().copied().fold(0.0, f64::max))
        ),
        (middle, 60),
        centred(15),
    ))
    .map_err(draw_error)?;
    let plot = area.margin(90, 10, 10, 10);

    // Equal scales on both axes, so that circles are round: the plot holds x in
    // [-1.2R, 1.2R] and y in [-0.1R, 1.2R], centred in whichever direction has room left.
    let radius = match lobe.largest() {
        r if r > 0.0 => r,
        _ => 1.0,
    };
    let (w, h) = plot.dim_in_pixel();
    let (need_x, need_y) = (2.4 * radius, 1.3 * radius);
    let scale = (f64::from(w) / need_x).min(f64::from(h) / need_y);
    let (span_x, span_y) = (f64::from(w) / scale, f64::from(h) / scale);
    let bottom = -0.1 * radius - (span_y - need_y) / 2.0;
    let mut chart = ChartBuilder::on(&plot)
        .build_cartesian_2d(-span_x / 2.0..span_x / 2.0, bottom..bottom + span_y)
        .map_err(draw_error)?;
    let at = |theta: f64, r: f64| {
        let t = theta.to_radians();
        (r * t.sin(), r * t.cos())
    };

    // Rings at a quarter, half, three quarters and all of the largest value, and spokes
    // every 30°.
    let grid = RGBColor(200, 200, 200);
    for k in 1..=4 {
        let r = radius * f64::from(k) / 4.0;
        let ring: Vec<(f64, f64)> = (0..=90)
            .map(|i| at(-90.0 + 2.0 * f64::from(i), r))
            .collect();
        chart
            .draw_series(std::iter::once(PathElement::new(ring, grid)))
            .map_err(draw_error)?;
        chart
            .draw_series(std::iter::once(Text::new(
                short(r),
                (r + 0.01 * radius, -0.02 * radius),
                ("sans-serif", 12)
                    .into_font()
                    .color(&RGBColor(110, 110, 110)),
            )))
            .map_err(draw_error)?;
    }
    for k in -3..=3 {
        let theta = 30.0 * f64::from(k);
        chart
            .draw_series(std::iter::once(PathElement::new(
                vec![(0.0, 0.0), at(theta, radius)],
                grid,
            )))
            .map_err(draw_error)?;
        if k == 0 {
            continue; // the normal's label stands there
        }
        chart
            .draw_series(std::iter::once(Text::new(
                format!("{theta}°"),
                at(theta, 1.08 * radius),
                ("sans-serif", 13)
                    .into_font()
                    .color(&RGBColor(110, 110, 110))
                    .pos(Pos::new(HPos::Center, VPos::Center)),
            )))
            .map_err(draw_error)?;
    }
    chart
        .draw_series(std::iter::once(PathElement::new(
            vec![(-radius, 0.0), (radius, 0.0)],
            BLACK.stroke_width(1),
        )))
        .map_err(draw_error)?;

    // The normal, the light and the mirror direction. Near the normal the light's label
    // ends at its line and the mirror's starts at its line, so that the three do not
    // overlap even at normal incidence.
    let beside = |toward| {
        if incidence > 60.0 {
            HPos::Center
        } else {
            toward
        }
    };
    let marks = [
        (0.0, RGBColor(90, 90, 90), "N", 1.08, HPos::Center),
        (
            -incidence,
            RGBColor(230, 140, 0),
            "light",
            1.17,
            beside(HPos::Right),
        ),
        (
            mirror,
            RGBColor(160, 60, 190),
            "mirror",
            1.17,
            beside(HPos::Left),
        ),
    ];
    for (theta, colour, name, out, anchor) in marks {
        chart
            .draw_series(std::iter::once(PathElement::new(
                vec![(0.0, 0.0), at(theta, 1.02 * radius)],
                colour.stroke_width(2),
            )))
            .map_err(draw_error)?;
        let (x, y) = at(theta, out * radius);
        let gap = match anchor {
            HPos::Right => -0.02 * radius,
            HPos::Left => 0.02 * radius,
            HPos::Center => 0.0,
        };
        chart
            .draw_series(std::iter::once(Text::new(
                name,
                (x + gap, y),
                ("sans-serif", 15)
                    .into_font()
                    .color(&colour)
                    .pos(Pos::new(anchor, VPos::Center)),
            )))
            .map_err(draw_error)?;
    }

    // The lobe: one black line for a grey material, else one line per channel.
    let channels: &[(usize, RGBColor, &str)] = if lobe.is_grey() {
        &[(0, BLACK, "f·cos θ_o")]
    } else {
        &[
            (0, RGBColor(210, 30, 30), "red"),
            (1, RGBColor(30, 150, 30), "green"),
            (2, RGBColor(30, 60, 210), "blue"),
        ]
    };
    for &(channel, colour, name) in channels {
        let points: Vec<(f64, f64)> = lobe
            .samples
            .iter()
            .map(|s| at(s.theta, s.reflected[channel]))
            .collect();
        chart
            .draw_series(LineSeries::new(points, colour.stroke_width(2)))
            .map_err(draw_error)?
            .label(name)
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 20, y)], colour.stroke_width(2))
            });
    }
    chart
        .draw_series(std::iter::once(Circle::new(
            at(
                peak.theta,
                peak.reflected.iter().copied().fold(0.0, f64::max),
            ),
            4,
            BLACK.filled(),
        )))
        .map_err(draw_error)?;
    legend(&mut chart, SeriesLabelPosition::UpperLeft)
}

/// A chart of one panel: `f64` axes on the SVG backend.
type Chart<'a, 'b> = ChartContext<'a, SVGBackend<'b>, Cartesian2d<RangedCoordf64, RangedCoordf64>>;

/// Draws the legend of `chart`'s labelled series at `position`, in the figure's style.
fn legend<'a>(chart: &mut Chart<'a, 'a>, position: SeriesLabelPosition) -> Result<(), PlotError> {
    chart
        .configure_series_labels()
        .position(position)
        .background_style(WHITE.mix(0.85))
        .border_style(RGBColor(160, 160, 160))
        .label_font(("sans-serif", 14))
        .draw()
        .map_err(draw_error)
}

/// The right panel: `max(0, cos α)^n` for each exponent, with a legend.
fn draw_curves(area: &Area<'_>, exponents: &[f32]) -> Result<(), PlotError> {
    let caption = if exponents.is_empty() {
        "max(0, cos α)ⁿ: the scene has no specular lobe".to_string()
    } else {
        "max(0, cos α)ⁿ for every shininess n in the scene".to_string()
    };
    let mut chart = ChartBuilder::on(area)
        .caption(caption, ("sans-serif", 18))
        .margin_top(10)
        .margin_right(25)
        .margin_left(5)
        .x_label_area_size(45)
        .y_label_area_size(55)
        .build_cartesian_2d(0.0..90.0, 0.0..1.05)
        .map_err(draw_error)?;
    chart
        .configure_mesh()
        .x_desc("α, degrees: the angle between R and V (Phong) or between N and H (Blinn-Phong)")
        .y_desc("max(0, cos α)ⁿ")
        .x_labels(10)
        .y_labels(11)
        .axis_desc_style(("sans-serif", 15))
        .label_style(("sans-serif", 13))
        .light_line_style(RGBColor(235, 235, 235))
        .draw()
        .map_err(draw_error)?;
    chart
        .draw_series(std::iter::once(PathElement::new(
            vec![(0.0, 0.5), (90.0, 0.5)],
            RGBColor(150, 150, 150),
        )))
        .map_err(draw_error)?;
    for (i, &n) in exponents.iter().enumerate() {
        let colour = ramp(i, exponents.len());
        let n64 = f64::from(n);
        chart
            .draw_series(LineSeries::new(sample_curve(n64), colour.stroke_width(2)))
            .map_err(draw_error)?
            .label(format!("n = {n} (½ at {:.1}°)", half_angle(n64)))
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 20, y)], colour.stroke_width(2))
            });
    }
    if !exponents.is_empty() {
        legend(&mut chart, SeriesLabelPosition::UpperRight)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use shadeline::{LinearRgb, Lobe as CoreLobe, Metal, Specular};

    fn material(model: Model, kd: f32, ks: f32, shininess: f32) -> Material {
        Material {
            albedo: LinearRgb::new(0.5, 0.5, 0.5),
            kd,
            ks,
            shininess,
            model,
        }
    }

    fn sphere(material: Material) -> Sphere {
        Sphere {
            center: shadeline::Vec3::new(0.0, 0.0, 0.0),
            radius: 1.0,
            material,
        }
    }

    /// The `θ` in `(−90°, 90°)` that maximises `g`, by golden-section search on a
    /// unimodal function: the exact peak the samples approximate.
    fn argmax(g: impl Fn(f64) -> f64, mut lo: f64, mut hi: f64) -> f64 {
        let r = (5f64.sqrt() - 1.0) / 2.0;
        for _ in 0..200 {
            let (a, b) = (hi - r * (hi - lo), lo + r * (hi - lo));
            if g(a) < g(b) {
                lo = a;
            } else {
                hi = b;
            }
        }
        (lo + hi) / 2.0
    }

    #[test]
    fn the_curve_is_one_half_at_the_half_angle() {
        for n in [1.0, 2.0, 10.0, 50.0, 250.0, 1250.0] {
            let alpha = half_angle(n);
            assert!((cosine_power(alpha, n) - 0.5).abs() < 1e-12, "n = {n}");
            // The sampled curve crosses 1/2 between the two samples around it.
            let curve = sample_curve(n);
            let i = (alpha / CURVE_STEP).floor() as usize;
            assert!(
                curve[i].1 >= 0.5 && curve[i + 1].1 <= 0.5,
                "n = {n}: {curve:?}"
            );
        }
        assert!((half_angle(1.0) - 60.0).abs() < 1e-12);
        // Tighter lobes, smaller half angles: about 9.5° at n = 50.
        assert!(
            (half_angle(50.0) - 9.5).abs() < 0.05,
            "{}",
            half_angle(50.0)
        );
    }

    #[test]
    fn a_curve_runs_from_one_at_0_to_zero_at_90_degrees_and_falls() {
        let curve = sample_curve(10.0);
        assert_eq!(curve.len(), CURVE_SAMPLES);
        assert_eq!(curve[0], (0.0, 1.0));
        let last = curve[CURVE_SAMPLES - 1];
        assert_eq!(last.0, 90.0);
        assert!(last.1 < 1e-150);
        assert!(curve
            .windows(2)
            .all(|w| w[1].1 <= w[0].1 && w[1].0 > w[0].0));
        assert_eq!(cosine_power(120.0, 3.0), 0.0);
    }

    #[test]
    fn a_phong_lobe_peaks_at_the_mirror_direction() {
        for incidence in [0.0, 20.0, 45.0, 70.0] {
            let m = material(Model::Phong, 0.5, 0.5, 1250.0);
            let lobe = sample_lobe(&m, incidence).unwrap();
            assert_eq!(lobe.samples.len(), LOBE_SAMPLES);
            let peak = lobe.peak();
            let mirror = mirror_angle(incidence);
            assert!(
                (peak.theta - mirror).abs() <= LOBE_STEP,
                "incidence {incidence}: peak at {}",
                peak.theta
            );
            // The BRDF itself (without cos θ_o) is largest exactly at the mirror sample.
            let at_mirror = lobe
                .samples
                .iter()
                .find(|s| (s.theta - mirror).abs() < 1e-9)
                .unwrap();
            assert!(lobe.samples.iter().all(|s| s.brdf[0] <= at_mirror.brdf[0]));
            // There f = kd·albedo + ks/cos θ_i, and the plotted value is f·cos θ_o.
            let cos = incidence.to_radians().cos();
            let expected = (0.5 * 0.5 + 0.5 / cos) * cos;
            assert!((at_mirror.reflected[0] - expected).abs() < 1e-6 * expected);
        }
    }

    #[test]
    fn a_broad_phong_lobe_leans_toward_the_normal_as_the_cosine_predicts() {
        // f·cos θ_o = cos(θ − θ_i)^n·cos θ: for small n its peak is nearer the normal than
        // the mirror direction; the samples find the exact maximum within a step.
        let n = 2.0;
        let m = material(Model::Phong, 0.0, 1.0, n as f32);
        let lobe = sample_lobe(&m, 45.0).unwrap();
        let exact = argmax(
            |t| cosine_power(t - 45.0, n) * t.to_radians().cos(),
            -89.0,
            89.0,
        );
        assert!(exact < 40.0, "{exact}");
        assert!((lobe.peak().theta - exact).abs() <= LOBE_STEP / 2.0 + 1e-9);
    }

    #[test]
    fn a_blinn_phong_lobe_peaks_near_the_mirror_direction_on_the_normal_side() {
        // In the plane of incidence N·H = cos((θ − θ_i)/2): the lobe of n is about Phong's of
        // n/4, and cos θ_o pulls its peak toward the normal by about 4·tan θ_i/n radians.
        for (n, within) in [(400.0, 1.0), (40.0, 7.0)] {
            let m = material(Model::BlinnPhong, 0.0, 1.0, n);
            let lobe = sample_lobe(&m, 45.0).unwrap();
            let peak = lobe.peak().theta;
            assert!(
                peak <= 45.0 && peak >= 45.0 - within,
                "n = {n}: peak at {peak}"
            );
            let exact = argmax(
                |t| cosine_power((t - 45.0) / 2.0, f64::from(n)) * t.to_radians().cos(),
                -89.0,
                89.0,
            );
            assert!(
                (peak - exact).abs() <= LOBE_STEP / 2.0 + 1e-9,
                "{peak} {exact}"
            );
        }
    }

    #[test]
    fn a_normalized_lobe_has_its_normalization() {
        // Normalized Phong at the mirror: (kd·albedo/π + ks·(n + 2)/(2π))·cos θ_o.
        let spec = Specular::default();
        let m = material(Model::NormalizedPhong(spec), 0.5, 0.5, 100.0);
        let lobe = sample_lobe(&m, 30.0).unwrap();
        let s = lobe.samples.iter().find(|s| s.theta == 30.0).unwrap();
        let pi = std::f64::consts::PI;
        let expected = (0.25 / pi + 0.5 * 102.0 / (2.0 * pi)) * 30f64.to_radians().cos();
        assert!((s.reflected[1] - expected).abs() < 1e-6 * expected, "{s:?}");
        assert!(lobe.is_grey());
    }

    #[test]
    fn a_metal_lobe_is_tinted_and_a_lambert_lobe_is_a_circle() {
        let gold = Material {
            kd: 0.0,
            ks: 1.0,
            shininess: 40.0,
            model: Model::NormalizedBlinnPhong(Specular {
                surface: Surface::Metal(Metal::Gold),
                more_lobes: [CoreLobe::NONE; 2],
            }),
            ..Material::default()
        };
        let lobe = sample_lobe(&gold, 45.0).unwrap();
        assert!(!lobe.is_grey());
        let peak = lobe.peak();
        assert!(peak.reflected[0] > peak.reflected[1] && peak.reflected[1] > peak.reflected[2]);

        // Lambert: f·cos θ_o = kd·albedo/π·cos θ_o, a circle through the origin, whatever
        // the incidence.
        let m = material(Model::Lambert, 1.0, 0.0, 1.0);
        let lobe = sample_lobe(&m, 60.0).unwrap();
        for s in &lobe.samples {
            let expected = 0.5 / std::f64::consts::PI * s.theta.to_radians().cos();
            assert!((s.reflected[2] - expected).abs() < 1e-12, "{s:?}");
        }
        assert_eq!(lobe.peak().theta, 0.0);
    }

    #[test]
    fn labels_have_three_significant_digits() {
        assert_eq!(short(0.045), "0.045");
        assert_eq!(short(0.18), "0.18");
        assert_eq!(short(1.3563), "1.36");
        assert_eq!(short(5.96), "5.96");
        assert_eq!(short(125.4), "125");
        assert_eq!(short(0.0), "0");
    }

    #[test]
    fn incidences_outside_0_to_90_are_refused() {
        let m = material(Model::Phong, 0.5, 0.5, 10.0);
        for bad in [-1.0, 90.0, 120.0, f64::NAN, f64::INFINITY] {
            assert!(matches!(sample_lobe(&m, bad), Err(PlotError::Incidence(_))));
        }
        assert!(sample_lobe(&m, 89.9).is_ok());
    }

    #[test]
    fn shininesses_are_every_distinct_lobe_exponent_ascending() {
        let series = crate::scene_file::builtin_scene().unwrap();
        assert_eq!(
            shininesses(series.scene.spheres()),
            [2.0, 10.0, 50.0, 250.0, 1250.0]
        );
        let lacquer = material(
            Model::NormalizedBlinnPhong(Specular {
                surface: Surface::Dielectric { ior: Some(1.5) },
                more_lobes: [
                    CoreLobe {
                        weight: 0.1,
                        shininess: 60.0,
                    },
                    CoreLobe::NONE,
                ],
            }),
            0.5,
            0.2,
            800.0,
        );
        let spheres = [
            sphere(lacquer),
            // Lambert's shininess and a lobe of weight 0 are not lobes.
            sphere(material(Model::Lambert, 1.0, 0.0, 7.0)),
            sphere(material(Model::Phong, 0.5, 0.0, 9.0)),
            sphere(material(Model::BlinnPhong, 0.5, 0.5, 60.0)),
        ];
        assert_eq!(shininesses(&spheres), [60.0, 800.0]);
        assert_eq!(
            describe(&lacquer),
            "normalized Blinn-Phong, ior 1.5, n = 800, 60"
        );
    }

    #[test]
    fn a_missing_sphere_is_an_error_naming_the_count() {
        let spheres = [sphere(material(Model::Phong, 0.5, 0.5, 10.0))];
        let e = figure(&spheres, 1, 45.0).unwrap_err();
        assert_eq!(e, PlotError::NoSuchSphere { index: 1, count: 1 });
        assert_eq!(
            e.to_string(),
            "there is no sphere 1: the scene has 1 sphere, numbered 0 to 0"
        );
        assert!(figure(&[], 0, 45.0)
            .unwrap_err()
            .to_string()
            .contains("no spheres"));
    }

    #[test]
    fn the_figure_has_one_line_per_exponent_and_per_lobe_channel() {
        let series = crate::scene_file::builtin_scene().unwrap();
        let spheres = series.scene.spheres();
        let figure = figure(spheres, 2, 45.0).unwrap();
        assert_eq!(figure.material, "classic Phong, n = 50");
        let lobe = sample_lobe(&spheres[2].material, 45.0).unwrap();
        assert_eq!(figure.peak, lobe.peak());
        let svg = figure.svg;
        let lines_of = |points: usize| {
            svg.lines()
                .filter(|l| l.starts_with("<polyline"))
                .filter(|l| {
                    let p = l.split("points=\"").nth(1).unwrap();
                    p.split('"').next().unwrap().split_whitespace().count() == points
                })
                .count()
        };
        assert_eq!(lines_of(CURVE_SAMPLES), shininesses(spheres).len());
        assert_eq!(lines_of(LOBE_SAMPLES), 1);
        for n in shininesses(spheres) {
            assert!(svg.contains(&format!(">\nn = {n} (")), "n = {n}");
        }
    }
}
