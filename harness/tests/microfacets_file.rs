//! The microfacet gallery, full-moon and area-lights scene files: each is its built-in preset, and the
//! keys of the two models have located errors for nonsense.

use shadeline_harness::{parse_scene, SceneFileError};

fn text(name: &str) -> String {
    let path = format!("{}/../scenes/{name}", env!("CARGO_MANIFEST_DIR"));
    std::fs::read_to_string(path).expect("the committed scene file is readable")
}

fn error(text: &str) -> SceneFileError {
    match parse_scene(text) {
        Ok(_) => panic!("the scene was accepted"),
        Err(e) => e,
    }
}

/// Asserts the error is on the line of `needle`, names `key`, and says `words`.
fn assert_error(text: &str, needle: &str, key: &str, words: &str) {
    let e = error(text);
    let at = text.find(needle).expect("needle is in the text");
    assert_eq!(e.line, text[..at].matches('\n').count() + 1, "{e}");
    assert_eq!(e.key.as_deref(), Some(key), "{e}");
    assert!(e.message.contains(words), "{e:?} does not say {words:?}");
}

#[test]
fn the_committed_microfacets_file_is_the_built_in_gallery() {
    let file = parse_scene(&text("microfacets.toml")).unwrap();
    let builtin = shadeline::microfacets().unwrap();
    assert_eq!((file.width, file.height), shadeline::MICROFACETS_SIZE);
    assert_eq!(file.scene.camera(), builtin.camera());
    assert_eq!(file.scene.background(), builtin.background());
    assert_eq!(file.scene.spheres(), builtin.spheres());
    assert_eq!(file.scene.lights(), builtin.lights());
    for s in builtin.spheres() {
        assert!(s.material.is_energy_conserving(), "{:?}", s.material);
    }
}

#[test]
fn the_committed_area_lights_file_is_the_built_in_scene() {
    let file = parse_scene(&text("area-lights.toml")).unwrap();
    let builtin = shadeline::area_lights(shadeline::AREA_LIGHT_RADIUS).unwrap();
    assert_eq!((file.width, file.height), shadeline::AREA_LIGHTS_SIZE);
    assert_eq!(file.scene.camera(), builtin.camera());
    assert_eq!(file.scene.background(), builtin.background());
    assert_eq!(file.scene.spheres(), builtin.spheres());
    assert_eq!(file.scene.lights(), builtin.lights());
    assert_eq!(builtin.sphere_light(), Some(0));
}

#[test]
fn the_committed_full_moon_file_is_the_built_in_scene() {
    let file = parse_scene(&text("full-moon.toml")).unwrap();
    let builtin = shadeline::full_moon().unwrap();
    assert_eq!((file.width, file.height), shadeline::FULL_MOON_SIZE);
    assert_eq!(file.scene.camera(), builtin.camera());
    assert_eq!(file.scene.spheres(), builtin.spheres());
    assert_eq!(file.scene.lights(), builtin.lights());
}

#[test]
fn roughness_is_checked_and_located() {
    let moon = text("full-moon.toml");
    let bad = moon.replacen("roughness = 1.0", "roughness = 2.0", 1);
    assert_error(
        &bad,
        "roughness = 2.0",
        "sphere[1].roughness",
        "larger than the accepted range",
    );
    let bad = moon.replacen("roughness = 1.0", "roughness = -0.1", 1);
    assert_error(
        &bad,
        "roughness = -0.1",
        "sphere[1].roughness",
        "must not be negative",
    );
    let gallery = text("microfacets.toml");
    let bad = gallery.replacen("roughness = 0.25", "roughness = 0.01", 1);
    assert_error(
        &bad,
        "roughness = 0.01",
        "sphere[0].roughness",
        "smaller than the accepted range",
    );
    let bad = gallery.replacen("roughness = 0.25", "roughness = 1.5", 1);
    assert_error(
        &bad,
        "roughness = 1.5",
        "sphere[0].roughness",
        "larger than the accepted range",
    );
}

#[test]
fn roughness_belongs_to_the_two_models_and_they_need_it() {
    let moon = text("full-moon.toml");
    let bad = moon.replacen(
        "model = \"lambert\"",
        "model = \"lambert\"\nroughness = 0.5",
        1,
    );
    assert_error(
        &bad,
        "roughness = 0.5",
        "sphere[0].roughness",
        "needs model = \"oren-nayar\" or \"ggx\"",
    );
    let bad = moon.replacen("roughness = 1.0\n", "", 1);
    let e = error(&bad);
    assert_eq!(e.key.as_deref(), Some("sphere[1].model"), "{e}");
    assert!(e.message.contains("missing key `roughness`"), "{e}");
    // Lobes stay with the normalized Phong models.
    let gallery = text("microfacets.toml");
    let bad = gallery.replacen(
        "roughness = 0.25",
        "roughness = 0.25\nlobes = [{ weight = 0.3, shininess = 10.0 }]",
        1,
    );
    assert_error(&bad, "lobes = ", "sphere[0].lobes", "`lobes` needs model");
}
