//! `shadeline plot`, run as a user would: the SVG it writes (one curve per shininess of the
//! scene, counted from the scene; the legend; the lobe's peak), and its refusals.

use shadeline::{Model, Sphere};
use shadeline_harness::parse_scene;
use shadeline_harness::plot::{self, CURVE_SAMPLES, LOBE_SAMPLES, LOBE_STEP};
use shadeline_harness::scene_file::builtin_scene;
mod common;

use common::{shadeline, stderr};
use std::path::PathBuf;

/// The exponents of the specular lobes the spheres have, distinct: lobe 0 unless the model
/// is Lambert, and the further lobes of positive weight. Written here apart from
/// `plot::shininesses`, which it checks.
fn lobe_exponents(spheres: &[Sphere]) -> Vec<f32> {
    let mut all = Vec::new();
    for s in spheres {
        let m = s.material;
        if m.model != Model::Lambert && m.ks > 0.0 {
            all.push(m.shininess);
        }
        if let Some(spec) = m.model.specular() {
            all.extend(
                spec.more_lobes
                    .iter()
                    .filter(|l| l.weight > 0.0)
                    .map(|l| l.shininess),
            );
        }
    }
    all.sort_by(f32::total_cmp);
    all.dedup();
    all
}

/// A fresh, empty directory for one test.
fn temp_dir(test: &str) -> PathBuf {
    common::temp_dir("plot", test)
}

fn materials_path() -> String {
    concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes/materials.toml").to_string()
}

/// Runs `plot ARGS` and returns the SVG it wrote to `out.svg`.
fn plot_svg(args: &[&str], test: &str) -> String {
    let dir = temp_dir(test);
    let mut all = vec!["plot", "-o", "out.svg"];
    all.extend(args);
    let out = shadeline(&all, &dir);
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(stderr(&out).is_empty(), "{}", stderr(&out));
    std::fs::read_to_string(dir.join("out.svg")).unwrap()
}

/// Checks that `svg` is one `<svg>` element whose tags all close in order, and returns the
/// tags' names in document order (self-closing ones too).
fn well_formed(svg: &str) -> Vec<String> {
    let mut open: Vec<String> = Vec::new();
    let mut names = Vec::new();
    let mut rest = svg.trim();
    assert!(rest.starts_with("<svg"), "{}", &rest[..rest.len().min(80)]);
    assert!(rest.ends_with("</svg>"));
    while let Some(start) = rest.find('<') {
        let end = start + rest[start..].find('>').expect("every tag closes");
        let tag = &rest[start + 1..end];
        assert!(!tag.contains('<'), "an unescaped < in {tag:?}");
        if let Some(name) = tag.strip_prefix('/') {
            assert_eq!(
                open.pop().as_deref(),
                Some(name),
                "</{name}> closes nothing"
            );
        } else if !tag.starts_with('?') && !tag.starts_with('!') {
            let name = tag.split_whitespace().next().unwrap().trim_end_matches('/');
            names.push(name.to_string());
            if !tag.ends_with('/') {
                open.push(name.to_string());
            }
        }
        rest = &rest[end + 1..];
    }
    assert!(open.is_empty(), "unclosed: {open:?}");
    names
}

/// The number of `<polyline>`s of `points` points.
fn polylines_of(svg: &str, points: usize) -> usize {
    svg.lines()
        .filter(|l| l.starts_with("<polyline"))
        .filter(|l| {
            let list = l
                .split("points=\"")
                .nth(1)
                .unwrap()
                .split('"')
                .next()
                .unwrap();
            list.split_whitespace().count() == points
        })
        .count()
}

/// The texts of the `<text>` elements.
fn texts(svg: &str) -> Vec<String> {
    svg.split("<text")
        .skip(1)
        .map(|t| {
            let body = &t[t.find('>').unwrap() + 1..t.find("</text>").unwrap()];
            body.trim().to_string()
        })
        .collect()
}

/// The lobe's peak as the figure labels it: `peak at θ_o = X°`.
fn labelled_peak(svg: &str) -> f64 {
    let text = texts(svg)
        .into_iter()
        .find(|t| t.starts_with("peak at θ_o = "))
        .expect("the peak is labelled");
    text["peak at θ_o = ".len()..]
        .split('°')
        .next()
        .unwrap()
        .parse()
        .unwrap()
}

#[test]
fn without_a_scene_it_plots_one_curve_per_exponent_of_the_series() {
    let dir = temp_dir("default");
    let out = shadeline(&["plot"], &dir);
    assert!(out.status.success(), "{}", stderr(&out));
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(stdout.contains("lobes.svg"), "{stdout}");
    let svg = std::fs::read_to_string(dir.join("lobes.svg")).expect("the default output");
    let names = well_formed(&svg);
    assert!(names.iter().any(|n| n == "text"));

    let series = builtin_scene().unwrap();
    let exponents = lobe_exponents(series.scene.spheres());
    assert_eq!(plot::shininesses(series.scene.spheres()), exponents);
    assert!(exponents.len() > 1);
    assert_eq!(polylines_of(&svg, CURVE_SAMPLES), exponents.len());
    let texts = texts(&svg);
    for n in &exponents {
        let label = format!("n = {n} (");
        assert_eq!(
            texts.iter().filter(|t| t.starts_with(&label)).count(),
            1,
            "the legend names n = {n} once"
        );
    }
    // Sphere 0 is grey: one line for the lobe. Its quantity is named.
    assert_eq!(polylines_of(&svg, LOBE_SAMPLES), 1);
    assert!(texts.iter().any(|t| t.starts_with("f(ω_i, ω_o)·cos θ_o")));
    assert!(texts.iter().any(|t| t.contains("sphere 0: classic Phong")));
}

#[test]
fn a_scene_file_and_a_preset_give_the_curves_of_their_own_spheres() {
    let file = parse_scene(&std::fs::read_to_string(materials_path()).unwrap()).unwrap();
    let exponents = lobe_exponents(file.scene.spheres());
    assert_eq!(plot::shininesses(file.scene.spheres()), exponents);
    let from_file = plot_svg(&[&materials_path(), "--sphere", "4"], "file");
    let from_preset = plot_svg(&["--preset", "materials", "--sphere", "4"], "preset");
    for svg in [&from_file, &from_preset] {
        well_formed(svg);
        assert_eq!(polylines_of(svg, CURVE_SAMPLES), exponents.len());
        // The lacquer is blue: one line per channel.
        assert_eq!(polylines_of(svg, LOBE_SAMPLES), 3);
        let texts = texts(svg);
        for n in &exponents {
            assert!(texts.iter().any(|t| t.starts_with(&format!("n = {n} ("))));
        }
    }
    assert_eq!(from_file, from_preset);
}

#[test]
fn a_phong_lobe_peaks_at_the_mirror_direction_and_a_blinn_phong_lobe_near_it() {
    // The exponent series' last sphere is classic Phong with the largest n: its peak is the
    // mirror direction, on the far side of the normal from the light.
    let series = builtin_scene().unwrap();
    let last = series.scene.spheres().len() - 1;
    let last = last.to_string();
    for incidence in ["0", "30", "60"] {
        let svg = plot_svg(&["--sphere", &last, "--incidence", incidence], "phong");
        let mirror = plot::mirror_angle(incidence.parse().unwrap());
        let peak = labelled_peak(&svg);
        assert!(
            (peak - mirror).abs() <= LOBE_STEP,
            "incidence {incidence}: peak at {peak}"
        );
    }
    // Gold (normalized Blinn-Phong, n = 40): within a few degrees, toward the normal.
    let svg = plot_svg(
        &[
            "--preset",
            "materials",
            "--sphere",
            "1",
            "--incidence",
            "45",
        ],
        "blinn",
    );
    let peak = labelled_peak(&svg);
    assert!((38.0..=45.0).contains(&peak), "peak at {peak}");
    assert!(texts(&svg).iter().any(|t| t.contains("gold")));
}

#[test]
fn a_sphere_the_scene_does_not_have_is_refused_and_leaves_the_output_alone() {
    let dir = temp_dir("bad-sphere");
    std::fs::write(dir.join("lobes.svg"), "before").unwrap();
    let count = builtin_scene().unwrap().scene.spheres().len();
    for bad in [count.to_string(), "1000000".to_string()] {
        let out = shadeline(&["plot", "--sphere", &bad], &dir);
        let err = stderr(&out);
        assert_eq!(out.status.code(), Some(2), "{err}");
        assert!(!err.contains("panicked"), "{err}");
        assert_eq!(err.trim_end().lines().count(), 1, "{err}");
        assert!(err.starts_with("error: --sphere"), "{err}");
        assert!(err.contains(&format!("{count} spheres")), "{err}");
        assert!(err.contains(&bad), "{err}");
    }
    assert_eq!(
        std::fs::read_to_string(dir.join("lobes.svg")).unwrap(),
        "before"
    );
    let out = shadeline(&["plot", "--sphere", "-1"], &dir);
    assert_eq!(out.status.code(), Some(2));
    assert!(stderr(&out).contains("--sphere"), "{}", stderr(&out));
}

#[test]
fn an_incidence_outside_0_to_90_degrees_is_refused() {
    let dir = temp_dir("bad-incidence");
    for bad in ["90", "90.5", "-1", "nan", "inf", "forty"] {
        let out = shadeline(&["plot", "--incidence", bad], &dir);
        let err = stderr(&out);
        assert_eq!(out.status.code(), Some(2), "{bad}: {err}");
        assert!(!err.contains("panicked"), "{err}");
        assert!(err.contains("--incidence"), "{err}");
        assert!(err.contains("below 90"), "{err}");
    }
    assert!(!dir.join("lobes.svg").exists());
    let out = shadeline(&["plot", "--incidence", "89.9"], &dir);
    assert!(out.status.success(), "{}", stderr(&out));
}

#[test]
fn a_scene_file_and_a_preset_together_or_an_unwritable_output_are_refused() {
    let dir = temp_dir("refusals");
    let out = shadeline(&["plot", &materials_path(), "--preset", "materials"], &dir);
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    assert!(stderr(&out).contains("give one or the other"));
    let out = shadeline(&["plot", "-o", "missing/lobes.svg"], &dir);
    assert_eq!(out.status.code(), Some(1), "{}", stderr(&out));
    assert!(stderr(&out).starts_with("missing/lobes.svg: error: cannot write"));
}

/// The gallery's lobe plots are what the binary writes now: after a change to the plot,
/// regenerate them with the commands under their captions (`docs/gallery.md`, "Lobe plots").
#[test]
fn the_readme_lobe_plots_are_current() {
    let docs = concat!(env!("CARGO_MANIFEST_DIR"), "/../docs/");
    for (file, args) in [
        ("lobes-exponent-series.svg", &["--sphere", "2"][..]),
        (
            "lobes-materials.svg",
            &["--preset", "materials", "--sphere", "1"][..],
        ),
        (
            "lobes-microfacets.svg",
            &["--preset", "microfacets", "--sphere", "8"][..],
        ),
        (
            "lobes-full-moon.svg",
            &["--preset", "full-moon", "--sphere", "1"][..],
        ),
    ] {
        let committed = std::fs::read_to_string(format!("{docs}{file}")).unwrap();
        let gallery = include_str!("../../docs/gallery.md");
        let command = format!("shadeline plot {} -o docs/{file}", args.join(" "));
        assert!(
            gallery.contains(&command),
            "docs/gallery.md shows `{command}`"
        );
        assert!(
            plot_svg(args, file) == committed,
            "docs/{file} is out of date: regenerate it with `{command}`"
        );
    }
}

/// The reflected total of `lobe` at the sample nearest `theta`.
fn total_at(lobe: &plot::Lobe, theta: f64) -> f64 {
    lobe.samples
        .iter()
        .min_by(|a, b| (a.theta - theta).abs().total_cmp(&(b.theta - theta).abs()))
        .unwrap()
        .total()
}

#[test]
fn an_oren_nayar_lobe_leans_toward_the_light_and_a_lambert_lobe_does_not() {
    // The full moon: sphere 0 Lambert, sphere 1 Oren–Nayar σ = 1.
    let lambert = plot_svg(&["--preset", "full-moon", "--sphere", "0"], "lambert");
    let peak = labelled_peak(&lambert);
    assert!(peak.abs() <= LOBE_STEP, "Lambert peaks at {peak}");
    let svg = plot_svg(&["--preset", "full-moon", "--sphere", "1"], "oren-nayar");
    well_formed(&svg);
    // Grey: one line; no cos^n curve (neither sphere has a cosine-power lobe).
    assert_eq!(polylines_of(&svg, LOBE_SAMPLES), 1);
    assert_eq!(polylines_of(&svg, CURVE_SAMPLES), 0);
    let texts = texts(&svg);
    assert!(texts
        .iter()
        .any(|t| t.contains("sphere 1: Oren-Nayar, σ = 1 rad")));
    // Backscatter: the peak is on the light's side of the normal, and the surface sends
    // more back toward the light than toward the mirror direction.
    let peak = labelled_peak(&svg);
    assert!(peak < -LOBE_STEP, "Oren–Nayar peaks at {peak}");
    let moon = shadeline::full_moon().unwrap();
    let lobe = plot::sample_lobe(&moon.spheres()[1].material, 45.0).unwrap();
    // Back toward the light f is ρ/π·(A + B·sin 45°·tan 45°), toward the mirror ρA/π:
    // 1.47 times less at σ = 1.
    let ratio = total_at(&lobe, -45.0) / total_at(&lobe, 45.0);
    assert!((ratio - 1.468).abs() < 0.01, "{ratio}");
    let flat = plot::sample_lobe(&moon.spheres()[0].material, 45.0).unwrap();
    let (a, b) = (total_at(&flat, -45.0), total_at(&flat, 45.0));
    assert!((a - b).abs() <= 1e-12 * a, "{a} vs {b}");
}

#[test]
fn a_ggx_lobe_peaks_at_the_mirror_and_has_a_longer_tail_than_its_blinn_phong_match() {
    // The microfacet gallery: sphere 8 is GGX copper at roughness 0.5, sphere 9 its
    // normalized Blinn-Phong match (n = 30).
    let svg = plot_svg(&["--preset", "microfacets", "--sphere", "8"], "ggx");
    well_formed(&svg);
    assert_eq!(
        polylines_of(&svg, LOBE_SAMPLES),
        3,
        "copper: one line per channel"
    );
    let texts = texts(&svg);
    assert!(texts
        .iter()
        .any(|t| t.contains("sphere 8: GGX, roughness 0.5, copper")));
    let peak = labelled_peak(&svg);
    assert!((40.0..=45.0).contains(&peak), "GGX peaks at {peak}");
    let gallery = shadeline::microfacets().unwrap();
    let ggx = plot::sample_lobe(&gallery.spheres()[8].material, 45.0).unwrap();
    let blinn = plot::sample_lobe(&gallery.spheres()[9].material, 45.0).unwrap();
    // Relative to each peak, far from the mirror (θ_o = −15°, the half vector 30° from the
    // normal) GGX keeps more than Blinn-Phong: the same peak, a longer tail.
    let tail = |l: &plot::Lobe| total_at(l, -15.0) / l.peak().total();
    assert!(
        tail(&ggx) > 1.5 * tail(&blinn),
        "{} vs {}",
        tail(&ggx),
        tail(&blinn)
    );
}
