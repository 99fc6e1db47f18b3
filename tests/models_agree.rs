//! Every reflection model on every path: the agreement contracts of the classic models hold
//! for the normalized ones, Lambert, metals, Fresnel and multi-lobe materials too.
//!
//! - scalar, f32x4 and f32x8 are bit-identical (linear colour and hit records);
//! - scalar is within one 8-bit level of the f64 reference where the ray decisions agree;
//! - the fixed path is within its budget: ≤ 2 levels where decisions agree, ≥ 99 % within
//!   one level, ≤ 0.1 % of decisions differ.
//!
//! On the materials gallery and on 48 random scenes whose spheres use every model
//! (`common::random_scenes_all_models`). Oren–Nayar and GGX, on the float paths: bit
//! identity across widths and scalar within one level of the reference, on the rough-models
//! gallery and on 48 random scenes whose spheres are mostly those models
//! (`common::random_scenes_rough_models`); and the fixed path within its budget on the full
//! moon, the rough-models gallery and the same random scenes. Run with `-- --nocapture` for
//! the tables.

use crate::common;
use common::*;
use shadeline::*;

fn bits(frame: &[LinearRgb]) -> Vec<[u32; 3]> {
    frame
        .iter()
        .map(|c| [c.r.to_bits(), c.g.to_bits(), c.b.to_bits()])
        .collect()
}

/// Every width, with and without spans, against the scalar path without spans (the scalar
/// path with spans, and both SIMD widths either way).
fn assert_widths_identical<const S: usize, const L: usize>(
    scene: &Scene<S, L>,
    w: u32,
    h: u32,
    what: &str,
) {
    let naive = Prepared::<Scalar, S, L>::new(scene, w, h)
        .unwrap()
        .with_spans(false);
    let want = bits(&frame::<LinearRgb, _>(&naive));
    let want_hits: Vec<HitRecord> = frame(&naive);
    fn check<R: Render>(r: &R, want: &[[u32; 3]], want_hits: &[HitRecord], label: &str) {
        let got = bits(&frame::<LinearRgb, _>(r));
        if let Some(i) = got.iter().zip(want).position(|(a, b)| a != b) {
            panic!("{label}: pixel {i} differs: {:?} vs {:?}", got[i], want[i]);
        }
        let hits: Vec<HitRecord> = frame(r);
        assert!(hits == want_hits, "{label}: hit records differ");
    }
    let scalar = Prepared::<Scalar, S, L>::new(scene, w, h).unwrap();
    check(
        &scalar,
        &want,
        &want_hits,
        &format!("{what}: scalar, spans true"),
    );
    for spans in [false, true] {
        let label = |p: &str| format!("{what}: {p}, spans {spans}");
        let simd4 = Prepared::<Simd4, S, L>::new(scene, w, h).unwrap();
        check(&simd4.with_spans(spans), &want, &want_hits, &label("simd4"));
        let simd8 = Prepared::<Simd8, S, L>::new(scene, w, h).unwrap();
        check(&simd8.with_spans(spans), &want, &want_hits, &label("simd8"));
    }
}

#[test]
fn materials_gallery_is_bit_identical_across_widths() {
    let scene = materials().unwrap();
    let (w, h) = MATERIALS_SIZE;
    assert_widths_identical(&scene, w, h, "materials");
    for (w, h) in [(7, 5), (67, 31)] {
        assert_widths_identical(&scene, w, h, &format!("materials {w}x{h}"));
    }
}

#[test]
fn random_all_model_scenes_are_bit_identical_across_widths() {
    for (i, scene) in random_scenes_all_models(48, 0x5eed_a110).iter().enumerate() {
        let (w, h) = (93 + (i as u32 % 9), 61);
        assert_widths_identical(scene, w, h, &format!("random scene {i}"));
    }
}

/// Scalar against the reference: at most one level, at most 0.05 % decisions differ.
fn check_scalar<const S: usize, const L: usize>(scene: &Scene<S, L>, w: u32, h: u32) -> Agreement {
    let reference = reference_frame(scene, w, h);
    let a = agreement(
        &Prepared::<Scalar, S, L>::new(scene, w, h).unwrap(),
        &reference,
    );
    assert!(a.max_levels <= 1, "{a:?}\n{scene:?}");
    assert!(a.differ_share() <= 0.0005, "{a:?}\n{scene:?}");
    a
}

/// Fixed against the reference: the fixed path's budget.
fn check_fixed<const S: usize, const L: usize>(scene: &Scene<S, L>, w: u32, h: u32) -> Agreement {
    let reference = reference_frame(scene, w, h);
    let a = agreement(
        &PreparedFixed::<S, L>::new(scene, w, h).unwrap(),
        &reference,
    );
    assert!(a.max_levels <= 2, "{a:?}\n{scene:?}");
    assert!(a.within_one_share() >= 0.99, "{a:?}\n{scene:?}");
    assert!(a.differ_share() <= 0.001, "{a:?}\n{scene:?}");
    a
}

#[test]
fn materials_gallery_scalar_and_fixed_match_the_reference() {
    let scene = materials().unwrap();
    let (w, h) = MATERIALS_SIZE;
    println!("materials {w}x{h}: scalar {:?}", check_scalar(&scene, w, h));
    println!("materials {w}x{h}: fixed {:?}", check_fixed(&scene, w, h));
    for s in scene.spheres() {
        assert!(s.material.is_energy_conserving(), "{:?}", s.material);
    }
}

#[test]
fn random_all_model_scenes_scalar_and_fixed_match_the_reference() {
    let (w, h) = (160, 120);
    let (mut scalar_worst, mut fixed_worst, mut fixed_within) = (0, 0, 1.0f64);
    for scene in random_scenes_all_models(48, 0x5eed_a111) {
        scalar_worst = scalar_worst.max(check_scalar(&scene, w, h).max_levels);
        let f = check_fixed(&scene, w, h);
        fixed_worst = fixed_worst.max(f.max_levels);
        fixed_within = fixed_within.min(f.within_one_share());
    }
    println!(
        "48 all-model scenes: scalar worst {scalar_worst} level(s); fixed worst \
         {fixed_worst} level(s), lowest within-one share {:.3}%",
        100.0 * fixed_within
    );
}

#[test]
fn random_all_model_scenes_use_every_model() {
    let scenes = random_scenes_all_models(48, 0x5eed_a111);
    let models: Vec<Model> = scenes
        .iter()
        .flat_map(|s| s.spheres().iter().map(|s| s.material.model))
        .collect();
    let count = |f: &dyn Fn(&Model) -> bool| models.iter().filter(|m| f(m)).count();
    assert!(count(&|m| *m == Model::Lambert) > 5);
    assert!(count(&|m| matches!(m, Model::NormalizedPhong(_))) > 5);
    assert!(count(&|m| matches!(m, Model::NormalizedBlinnPhong(_))) > 5);
    let spec = |f: &dyn Fn(&Specular) -> bool| count(&|m| m.specular().is_some_and(f));
    assert!(spec(&|s| matches!(s.surface, Surface::Metal(_))) > 5);
    assert!(spec(&|s| matches!(s.surface, Surface::Dielectric { ior: Some(_) })) > 5);
    assert!(spec(&|s| s.more_lobes[1].weight > 0.0) > 3);
}

#[test]
fn random_rough_model_scenes_are_bit_identical_across_widths() {
    for (i, scene) in random_scenes_rough_models(48, 0x5eed_a120)
        .iter()
        .enumerate()
    {
        let (w, h) = (93 + (i as u32 % 9), 61);
        assert_widths_identical(scene, w, h, &format!("random rough scene {i}"));
    }
}

#[test]
fn random_rough_model_scenes_on_the_scalar_path_match_the_reference() {
    let (w, h) = (160, 120);
    let (mut worst, mut within, mut differ) = (0, 1.0f64, 0.0f64);
    for scene in random_scenes_rough_models(48, 0x5eed_a121) {
        let a = check_scalar(&scene, w, h);
        worst = worst.max(a.max_levels);
        within = within.min(a.within_one_share());
        differ = differ.max(a.differ_share());
    }
    println!(
        "48 rough-model scenes {w}x{h}: scalar worst {worst} level(s), lowest within-one \
         share {:.3}%, largest decisions-differ share {:.4}%",
        100.0 * within,
        100.0 * differ
    );
}

#[test]
fn random_rough_model_scenes_use_both_models_and_every_surface() {
    let scenes = random_scenes_rough_models(48, 0x5eed_a121);
    let models: Vec<Model> = scenes
        .iter()
        .flat_map(|s| s.spheres().iter().map(|s| s.material.model))
        .collect();
    let count = |f: &dyn Fn(&Model) -> bool| models.iter().filter(|m| f(m)).count();
    assert!(count(&|m| matches!(m, Model::OrenNayar { .. })) > 20);
    let ggx = |f: &dyn Fn(&Surface) -> bool| {
        count(&|m| matches!(m, Model::Ggx(micro) if f(&micro.surface)))
    };
    assert!(ggx(&|s| matches!(s, Surface::Metal(_))) > 5);
    assert!(ggx(&|s| matches!(s, Surface::Dielectric { ior: Some(_) })) > 5);
    assert!(ggx(&|s| matches!(s, Surface::Dielectric { ior: None })) > 5);
}

#[test]
fn rough_models_on_the_fixed_path_match_the_reference() {
    let moon = full_moon().unwrap();
    let (w, h) = FULL_MOON_SIZE;
    println!("full moon {w}x{h}: fixed {:?}", check_fixed(&moon, w, h));
    let gallery = microfacets().unwrap();
    let (w, h) = MICROFACETS_SIZE;
    println!(
        "microfacets {w}x{h}: fixed {:?}",
        check_fixed(&gallery, w, h)
    );
    let (w, h) = (160, 120);
    let (mut worst, mut within, mut differ) = (0, 1.0f64, 0.0f64);
    for scene in random_scenes_rough_models(48, 0x5eed_a121) {
        let a = check_fixed(&scene, w, h);
        worst = worst.max(a.max_levels);
        within = within.min(a.within_one_share());
        differ = differ.max(a.differ_share());
    }
    println!(
        "48 rough-model scenes {w}x{h}: fixed worst {worst} level(s), lowest within-one \
         share {:.3}%, largest decisions-differ share {:.4}%",
        100.0 * within,
        100.0 * differ
    );
}

#[test]
fn microfacet_gallery_and_full_moon_are_bit_identical_across_widths() {
    let gallery = microfacets().unwrap();
    let (w, h) = MICROFACETS_SIZE;
    assert_widths_identical(&gallery, w, h, "microfacets");
    assert_widths_identical(&gallery, 67, 31, "microfacets 67x31");
    let (w, h) = FULL_MOON_SIZE;
    assert_widths_identical(&full_moon().unwrap(), w, h, "full moon");
}

#[test]
fn microfacet_gallery_and_full_moon_on_the_scalar_path_match_the_reference() {
    let gallery = microfacets().unwrap();
    let (w, h) = MICROFACETS_SIZE;
    println!(
        "microfacets {w}x{h}: scalar {:?}",
        check_scalar(&gallery, w, h)
    );
    let moon = full_moon().unwrap();
    let (w, h) = FULL_MOON_SIZE;
    println!("full moon {w}x{h}: scalar {:?}", check_scalar(&moon, w, h));
}
