//! The scalar path against the independent f64 reference: on pixels whose ray decisions
//! agree (same sphere hit, same lights blocked), every channel is within one 8-bit level;
//! pixels whose decisions differ are at most 0.05 % of a frame.

use crate::common;
use common::*;
use shadeline::*;

const MAX_DIFFER_SHARE: f64 = 0.0005;

#[test]
fn scalar_matches_reference_on_the_exponent_series() {
    let scene = exponent_series().unwrap();
    let (w, h) = EXPONENT_SERIES_SIZE;
    let reference = reference_frame(&scene, w, h);
    let frame = Prepared::<Scalar>::new(&scene, w, h).unwrap();
    let a = agreement(&frame, &reference);
    println!("exponent series {w}x{h}: {a:?}");
    assert!(a.max_levels <= 1, "{a:?}");
    assert!(a.differ_share() <= MAX_DIFFER_SHARE, "{a:?}");
    // The scene is not trivial: spheres and background both present.
    let hits: Vec<HitRecord> = common::frame(&frame);
    assert!(hits.iter().any(|h| h.sphere == Some(4)));
    assert!(hits.iter().any(|h| h.sphere.is_none()));
}

#[test]
fn scalar_matches_reference_on_64_random_scenes() {
    let (w, h) = (160, 120);
    let mut worst_levels = 0;
    let mut worst_differ = 0.0f64;
    for (i, scene) in random_scenes(64, 0x5eed_0001).iter().enumerate() {
        let reference = reference_frame(scene, w, h);
        let frame = Prepared::<Scalar>::new(scene, w, h).unwrap();
        let a = agreement(&frame, &reference);
        assert!(a.max_levels <= 1, "scene {i}: {a:?}\n{scene:?}");
        assert!(
            a.differ_share() <= MAX_DIFFER_SHARE,
            "scene {i}: {a:?}\n{scene:?}"
        );
        worst_levels = worst_levels.max(a.max_levels);
        worst_differ = worst_differ.max(a.differ_share());
    }
    println!("64 random scenes: worst max error {worst_levels} level(s), worst decisions-differ share {:.4}%", worst_differ * 100.0);
}

#[test]
fn random_scenes_exercise_hits_shadows_and_both_models() {
    // Guards the test above against a generator that only makes empty frames.
    let (w, h) = (160, 120);
    let (mut hit, mut shadowed, mut total) = (0usize, 0usize, 0usize);
    let scenes = random_scenes(64, 0x5eed_0001);
    for scene in &scenes {
        let frame = Prepared::<Scalar>::new(scene, w, h).unwrap();
        let hits: Vec<HitRecord> = common::frame(&frame);
        total += hits.len();
        hit += hits.iter().filter(|r| r.sphere.is_some()).count();
        shadowed += hits.iter().filter(|r| r.shadowed != 0).count();
    }
    println!(
        "random scenes: {:.1}% of pixels hit a sphere, {:.1}% have a blocked light",
        100.0 * hit as f64 / total as f64,
        100.0 * shadowed as f64 / total as f64
    );
    assert!(hit * 10 > total, "fewer than 10% of pixels hit a sphere");
    assert!(
        shadowed * 50 > total,
        "fewer than 2% of pixels are in a shadow"
    );
    let blinn = scenes
        .iter()
        .flat_map(|s| s.spheres())
        .filter(|s| s.material.model == Model::BlinnPhong)
        .count();
    assert!(blinn > 10);
}
