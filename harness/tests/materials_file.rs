//! The materials scene file: it is the built-in gallery, and every new material key has a
//! located error for nonsense.

use shadeline_harness::{parse_scene, SceneFileError};

fn materials_text() -> String {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes/materials.toml");
    std::fs::read_to_string(path).expect("the committed scene file is readable")
}

fn edited(from: &str, to: &str) -> String {
    let text = materials_text();
    assert!(
        text.contains(from),
        "the scene file no longer contains {from:?}"
    );
    text.replacen(from, to, 1)
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
fn the_committed_scene_file_is_the_built_in_gallery() {
    let file = parse_scene(&materials_text()).unwrap();
    let builtin = shadeline::materials().unwrap();
    assert_eq!((file.width, file.height), shadeline::MATERIALS_SIZE);
    assert_eq!(file.scene.camera(), builtin.camera());
    assert_eq!(file.scene.background(), builtin.background());
    assert_eq!(file.scene.spheres(), builtin.spheres());
    assert_eq!(file.scene.lights(), builtin.lights());
}

#[test]
fn unknown_metal_is_an_error_at_its_key() {
    let text = edited("metal = \"copper\"", "metal = \"brass\"");
    assert_error(
        &text,
        "\"brass\"",
        "sphere[2].metal",
        "unknown metal `brass`, expected one of `gold`, `copper`, `bronze`",
    );
}

#[test]
fn metal_ior_and_lobes_need_a_normalized_model() {
    let text = edited(
        "model = \"normalized-blinn-phong\"\nmetal = \"gold\"",
        "model = \"phong\"\nmetal = \"gold\"",
    );
    assert_error(
        &text,
        "\"gold\"",
        "sphere[1].metal",
        "needs model = \"normalized-phong\"",
    );
    let text = edited(
        "shininess = 200.0",
        "shininess = 200.0\nior = 1.5\nmodel = \"blinn-phong\"",
    )
    .replacen("model = \"normalized-phong\"\n", "", 1);
    assert!(
        error(&text).key.as_deref() == Some("sphere[0].ior"),
        "{}",
        error(&text)
    );
}

#[test]
fn a_metal_has_no_diffuse_lobe_and_no_ior() {
    let text = edited("metal = \"gold\"", "metal = \"gold\"\nkd = 0.5");
    assert_error(
        &text,
        "kd = 0.5",
        "sphere[1].kd",
        "a metal has no diffuse lobe",
    );
    let text = edited("metal = \"gold\"", "metal = \"gold\"\nior = 1.5");
    assert_error(&text, "ior = 1.5", "sphere[1].ior", "a metal has no `ior`");
}

#[test]
fn ior_must_be_above_one() {
    for bad in ["1.0", "0.5", "-2.0"] {
        let text = edited(
            "shininess = 200.0",
            &format!("shininess = 200.0\nior = {bad}"),
        );
        assert_error(
            &text,
            &format!("ior = {bad}"),
            "sphere[0].ior",
            "must be greater than 1",
        );
    }
    let text = edited("shininess = 200.0", "shininess = 200.0\nior = nan");
    assert_error(&text, "ior = nan", "sphere[0].ior", "finite");
}

#[test]
fn lobe_errors_name_the_lobe() {
    let text = edited(
        "{ weight = 0.1, shininess = 60.0 }",
        "{ weight = -0.1, shininess = 60.0 }",
    );
    assert_error(
        &text,
        "weight = -0.1",
        "sphere[4].lobes[1].weight",
        "must not be negative",
    );
    let text = edited(
        "{ weight = 0.05, shininess = 8.0 }",
        "{ weight = 0.05, shininess = 0.0 }",
    );
    assert_error(
        &text,
        "shininess = 0.0",
        "sphere[4].lobes[2].shininess",
        "greater than zero",
    );
    let text = edited(
        "{ weight = 0.25, shininess = 800.0 }",
        "{ weight = 0.25, shininess = -8.0 }",
    );
    assert_error(
        &text,
        "shininess = -8.0",
        "sphere[4].lobes[0].shininess",
        "greater than zero",
    );
    let text = edited(
        "    { weight = 0.05, shininess = 8.0 },\n",
        "    { weight = 0.05, shininess = 8.0 },\n    { weight = 0.01, shininess = 2.0 },\n",
    );
    assert_error(
        &text,
        "weight = 0.01",
        "sphere[4].lobes[3]",
        "at most 3 lobes",
    );
    let text = edited("kd = 0.6\nlobes", "kd = 0.6\nks = 0.2\nlobes");
    assert_error(
        &text,
        "ks = 0.2",
        "sphere[4].ks",
        "`ks` and `lobes` both given",
    );
    let text = edited(
        "{ weight = 0.1, shininess = 60.0 }",
        "{ weight = 0.1, shininess = 60.0, n = 2 }",
    );
    assert!(
        error(&text).message.contains("unknown key `n`"),
        "{}",
        error(&text)
    );
}

#[test]
fn lambert_needs_no_specular_keys_and_others_do() {
    let text = edited("ks = 0.3\nshininess = 200.0", "").replacen(
        "model = \"normalized-phong\"",
        "model = \"lambert\"",
        1,
    );
    let file = parse_scene(&text).unwrap();
    assert_eq!(
        file.scene.spheres()[0].material.model,
        shadeline::Model::Lambert
    );
    let e = error(&edited("ks = 0.3\n", ""));
    assert_eq!(e.key.as_deref(), Some("sphere[0].ks"), "{e}");
    assert!(e.message.contains("missing key `ks`"), "{e}");
}
