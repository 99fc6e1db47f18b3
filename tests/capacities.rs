//! One default capacity everywhere: the built-in scenes are `Scene` (16 spheres, 8 lights),
//! which is also what `Prepared<W>` and `PreparedFixed` mean without capacities, so a preset
//! goes into any path's default type; other capacities are inferred from the scene.
//!
//! The type annotations are half of these tests: they compile only while the presets and the
//! prepared types agree on [`DEFAULT_SPHERES`] and [`DEFAULT_LIGHTS`].

use shadeline::{
    exponent_series, exponent_series_with_capacity, materials, materials_with_capacity, ItemKind,
    Prepared, PreparedFixed, Render, Rgb888, Scalar, Scene, SceneError, Simd4, Simd8,
    DEFAULT_LIGHTS, DEFAULT_SPHERES,
};

/// Every row of a frame, as 8-bit RGB.
fn frame<R: Render>(r: &R) -> Vec<Rgb888> {
    let mut out = vec![Rgb888::default(); (r.width() * r.height()) as usize];
    r.render_frame(&mut out).unwrap();
    out
}

#[test]
fn every_preset_has_the_default_capacities_and_goes_into_every_default_type() {
    assert_eq!((DEFAULT_SPHERES, DEFAULT_LIGHTS), (16, 8));
    let series: Scene<DEFAULT_SPHERES, DEFAULT_LIGHTS> = exponent_series().unwrap();
    let gallery: Scene<DEFAULT_SPHERES, DEFAULT_LIGHTS> = materials().unwrap();
    for (scene, spheres, lights) in [(&series, 5, 1), (&gallery, 10, 2)] {
        assert_eq!(
            (scene.spheres().len(), scene.lights().len()),
            (spheres, lights)
        );
        let scalar: Prepared<Scalar, DEFAULT_SPHERES, DEFAULT_LIGHTS> =
            Prepared::<Scalar>::new(scene, 48, 30).unwrap();
        let simd4 = Prepared::<Simd4>::new(scene, 48, 30).unwrap();
        let simd8 = Prepared::<Simd8>::new(scene, 48, 30).unwrap();
        let fixed: PreparedFixed<DEFAULT_SPHERES, DEFAULT_LIGHTS> =
            PreparedFixed::new(scene, 48, 30).unwrap();
        let want = frame(&scalar);
        assert_eq!(frame(&simd4), want);
        assert_eq!(frame(&simd8), want);
        // Not a blank frame: the spheres are there.
        assert!(want.iter().any(|p| *p != want[0]));
        assert_eq!(frame(&fixed).len(), want.len());
    }
}

#[test]
fn other_capacities_are_inferred_from_the_scene() {
    let small: Scene<5, 1> = exponent_series_with_capacity().unwrap();
    let default = exponent_series().unwrap();
    let want = frame(&Prepared::<Scalar>::new(&default, 40, 24).unwrap());
    assert_eq!(
        frame(&Prepared::<Scalar, _, _>::new(&small, 40, 24).unwrap()),
        want
    );
    assert_eq!(
        frame(&Prepared::<Simd8, _, _>::new(&small, 40, 24).unwrap()),
        want
    );
    assert_eq!(
        frame(&PreparedFixed::new(&small, 40, 24).unwrap()),
        frame(&PreparedFixed::new(&default, 40, 24).unwrap())
    );
}

#[test]
fn materials_at_any_capacity_is_the_same_gallery_or_a_capacity_error() {
    let exact: Scene<10, 2> = materials_with_capacity().unwrap();
    let default = materials().unwrap();
    assert_eq!(exact.spheres(), default.spheres());
    assert_eq!(exact.lights(), default.lights());
    assert_eq!(exact.camera(), default.camera());
    let too_few_spheres = materials_with_capacity::<9, 2>().unwrap_err();
    assert_eq!(
        too_few_spheres,
        SceneError::CapacityExceeded {
            kind: ItemKind::Sphere,
            capacity: 9
        }
    );
    let too_few_lights = materials_with_capacity::<10, 1>().unwrap_err();
    assert_eq!(
        too_few_lights,
        SceneError::CapacityExceeded {
            kind: ItemKind::Light,
            capacity: 1
        }
    );
}
