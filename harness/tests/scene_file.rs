//! The scene file parser: the committed exponent series matches the built-in scene, and every
//! class of error is one located message naming the key.

use shadeline_harness::{parse_scene, SceneFileError};

fn exponent_series_text() -> String {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../scenes/exponent-series.toml"
    );
    std::fs::read_to_string(path).expect("the committed scene file is readable")
}

/// The exponent series with the first occurrence of `from` replaced by `to`.
fn edited(from: &str, to: &str) -> String {
    let text = exponent_series_text();
    assert!(
        text.contains(from),
        "the scene file no longer contains {from:?}"
    );
    text.replacen(from, to, 1)
}

/// The 1-based line of the first occurrence of `needle` in `text`.
fn line_of(text: &str, needle: &str) -> usize {
    let at = text.find(needle).expect("needle is in the text");
    text[..at].matches('\n').count() + 1
}

fn error(text: &str) -> SceneFileError {
    match parse_scene(text) {
        Ok(_) => panic!("the scene was accepted"),
        Err(e) => e,
    }
}

/// Asserts the error is on the line of `needle`, names `key`, and says `words`.
fn assert_error(text: &str, needle: &str, key: Option<&str>, words: &str) {
    let e = error(text);
    assert_eq!(e.line, line_of(text, needle), "{e}");
    assert_eq!(e.key.as_deref(), key, "{e}");
    assert!(e.message.contains(words), "{e:?} does not say {words:?}");
    let shown = e.to_string();
    assert!(
        shown.starts_with(&format!("{}:{}: error: ", e.line, e.column)),
        "{shown}"
    );
    assert!(!shown.contains('\n'), "{shown}");
}

#[test]
fn the_committed_scene_file_is_the_built_in_exponent_series() {
    let file = parse_scene(&exponent_series_text()).unwrap();
    let builtin = shadeline::exponent_series().unwrap();
    assert_eq!((file.width, file.height), shadeline::EXPONENT_SERIES_SIZE);
    assert_eq!((file.width, file.height), (1024, 747));
    assert_eq!(file.scene.camera(), builtin.camera());
    assert_eq!(file.scene.background(), builtin.background());
    assert_eq!(file.scene.spheres(), builtin.spheres());
    assert_eq!(file.scene.lights(), builtin.lights());
    assert_eq!(file.scene.spheres().len(), 5);
}

#[test]
fn point_lights_and_blinn_phong_are_read() {
    let text = edited(
        "type = \"distant\"\ndirection = [-0.4347962, -0.8416416, 0.3202994]",
        "type = \"point\"\nposition = [1.0, 2.0, 3.0]",
    )
    .replacen(
        "shininess = 2.0",
        "shininess = 2.0\nmodel = \"blinn-phong\"",
        1,
    );
    let file = parse_scene(&text).unwrap();
    assert!(matches!(
        file.scene.lights()[0],
        shadeline::Light::Point { position, .. } if position == shadeline::Vec3::new(1.0, 2.0, 3.0)
    ));
    assert_eq!(
        file.scene.spheres()[0].material.model,
        shadeline::Model::BlinnPhong
    );
    assert_eq!(
        file.scene.spheres()[1].material.model,
        shadeline::Model::Phong
    );
}

#[test]
fn toml_syntax_error() {
    let text = edited("kd = 0.8\nks = 0.1", "kd = = 0.8\nks = 0.1");
    assert_error(&text, "kd = = 0.8", None, "invalid TOML");
}

#[test]
fn duplicate_key_is_named() {
    let text = edited("ks = 0.1\n", "ks = 0.1\nks = 0.2\n");
    assert_error(&text, "ks = 0.2", None, "duplicate key `ks`");
}

#[test]
fn antialias_is_read_off_by_default_and_checked() {
    assert!(!parse_scene(&exponent_series_text()).unwrap().antialias);
    let on = edited("height = 747\n", "height = 747\nantialias = true\n");
    assert!(parse_scene(&on).unwrap().antialias);
    let text = edited("height = 747\n", "height = 747\nantialias = \"yes\"\n");
    assert_error(&text, "antialias", Some("image.antialias"), "boolean");
}

#[test]
fn unknown_key() {
    // (`roughness` is a key now, of the Oren–Nayar and GGX models.)
    let text = edited("ks = 0.1\n", "ks = 0.1\nglossiness = 3\n");
    assert_error(
        &text,
        "glossiness",
        Some("sphere[2].glossiness"),
        "unknown key `glossiness`",
    );
}

#[test]
fn missing_key() {
    let text = edited("ks = 0.1\n", "");
    let e = error(&text);
    assert_eq!(e.key.as_deref(), Some("sphere[2].ks"), "{e}");
    assert!(e.message.contains("missing key `ks`"), "{e}");
    // Reported at the third sphere's table, which starts after the second's last line.
    assert!(e.line > line_of(&text, "shininess = 10.0"), "{e}");
    assert!(e.line <= line_of(&text, "shininess = 50.0"), "{e}");
}

#[test]
fn missing_table() {
    let text = exponent_series_text();
    let start = text.find("[camera]").unwrap();
    let end = text.find("[[light]]").unwrap();
    let text = format!("{}{}", &text[..start], &text[end..]);
    let e = error(&text);
    assert_eq!(e.key.as_deref(), Some("camera"), "{e}");
    assert!(e.message.contains("missing key `camera`"), "{e}");
}

#[test]
fn wrong_type() {
    let text = edited("vfov = 36.87", "vfov = \"wide\"");
    assert_error(&text, "vfov =", Some("camera.vfov"), "invalid type: string");
}

#[test]
fn datetime_is_a_wrong_type_not_a_table() {
    let text = edited("vfov = 36.87", "vfov = 1979-05-27");
    assert_error(
        &text,
        "vfov =",
        Some("camera.vfov"),
        "invalid type: a datetime",
    );
}

#[test]
fn wrong_array_length() {
    let text = edited("look_at = [0.0, 1.0, 0.0]", "look_at = [0.0, 1.0]");
    assert_error(&text, "look_at", Some("camera.look_at"), "invalid length 2");
}

#[test]
fn wrong_element_type_names_the_element() {
    let text = edited(
        "albedo = [0.18, 0.18, 0.18]",
        "albedo = [0.18, \"grey\", 0.18]",
    );
    assert_error(
        &text,
        "\"grey\"",
        Some("sphere[0].albedo[1]"),
        "invalid type: string",
    );
}

#[test]
fn unknown_light_type() {
    let text = edited("type = \"distant\"", "type = \"spot\"");
    assert_error(
        &text,
        "\"spot\"",
        Some("light[0].type"),
        "unknown value `spot`",
    );
}

#[test]
fn unknown_model() {
    let text = edited("shininess = 250.0", "shininess = 250.0\nmodel = \"ward\"");
    assert_error(
        &text,
        "\"ward\"",
        Some("sphere[3].model"),
        "unknown value `ward`",
    );
}

#[test]
fn light_keys_must_fit_its_type() {
    let text = edited(
        "intensity = 5.0",
        "intensity = 5.0\nposition = [0.0, 5.0, 0.0]",
    );
    assert_error(
        &text,
        "position = [0.0, 5.0",
        Some("light[0].position"),
        "has no `position`",
    );
    let text = edited("direction = [-0.4347962, -0.8416416, 0.3202994]", "");
    let e = error(&text);
    assert_eq!(e.key.as_deref(), Some("light[0].direction"), "{e}");
    assert!(e.message.contains("missing key `direction`"), "{e}");
}

#[test]
fn invalid_sphere_radius_is_placed_at_its_key() {
    let text = edited(
        "center = [0.0, 1.0, 0.0]\nradius = 0.9",
        "center = [0.0, 1.0, 0.0]\nradius = -0.9",
    );
    assert_error(
        &text,
        "radius = -0.9",
        Some("sphere[2].radius"),
        "must be greater than zero",
    );
}

#[test]
fn invalid_camera_and_background_are_placed_at_their_keys() {
    let text = edited("vfov = 36.87", "vfov = 180.0");
    assert_error(&text, "vfov", Some("camera.vfov"), "between 0 and 180");
    let text = edited("look_at = [0.0, 1.0, 0.0]", "look_at = [0.0, 1.0, 12.0]");
    assert_error(&text, "look_at", Some("camera.look_at"), "must differ");
    let text = edited("background = [0.235294", "background = [-0.235294");
    assert_error(
        &text,
        "background",
        Some("image.background"),
        "must not be negative",
    );
}

#[test]
fn invalid_light_is_placed_at_its_key() {
    let text = edited("intensity = 5.0", "intensity = nan");
    assert_error(
        &text,
        "intensity = nan",
        Some("light[0].intensity"),
        "finite",
    );
    let text = edited(
        "direction = [-0.4347962, -0.8416416, 0.3202994]",
        "direction = [0, 0, 0]",
    );
    assert_error(
        &text,
        "direction",
        Some("light[0].direction"),
        "zero-length",
    );
}

#[test]
fn number_beyond_f32_is_too_large_not_infinite() {
    let text = edited("kd = 0.8", "kd = 1e300");
    assert_error(
        &text,
        "kd = 1e300",
        Some("sphere[0].kd"),
        "larger than the accepted range",
    );
}

#[test]
fn too_many_spheres_names_the_first_one_over() {
    let sphere = "[[sphere]]\ncenter = [0.0, 0.0, 0.0]\nradius = 1.0\nalbedo = [1.0, 1.0, 1.0]\nkd = 1.0\nks = 0.0\nshininess = 1.0\n";
    let text = format!("{}{}", exponent_series_text(), sphere.repeat(60));
    let e = error(&text);
    assert_eq!(e.key.as_deref(), Some("sphere[64]"), "{e}");
    assert!(e.message.contains("at most 64"), "{e}");
    let offset = text.match_indices("[[sphere]]").nth(64).unwrap().0;
    assert!(e.line > text[..offset].matches('\n').count(), "{e}");
}

#[test]
fn image_size_zero_or_huge_is_reported_against_the_dimension() {
    let text = edited("width = 1024", "width = 0");
    assert_error(&text, "width = 0", Some("image.width"), "image size 0x747");
    let text = edited("height = 747", "height = 70000");
    assert_error(
        &text,
        "height = 70000",
        Some("image.height"),
        "not supported",
    );
    let text = edited("height = 747", "height = -3");
    assert_error(&text, "height = -3", Some("image.height"), "invalid value");
}

#[test]
fn unknown_top_level_key_and_empty_text() {
    let text = format!("shadows = true\n{}", exponent_series_text());
    assert_error(&text, "shadows", Some("shadows"), "unknown key `shadows`");
    let e = error("");
    assert_eq!(
        (e.line, e.column, e.key.as_deref()),
        (1, 1, Some("image")),
        "{e}"
    );
}

#[test]
fn columns_count_characters_not_bytes() {
    let text = edited("vfov = 36.87", "vfov = \"\u{e9}\u{e9}\u{e9}\" x");
    let e = error(&text);
    // `vfov = "ééé" ` is 13 characters (16 bytes): the stray `x` is column 14.
    assert_eq!((e.line, e.column), (line_of(&text, "vfov"), 14), "{e}");
}

#[test]
fn a_point_light_takes_a_radius_and_a_distant_light_refuses_one() {
    let distant = "type = \"distant\"\ndirection = [-0.4347962, -0.8416416, 0.3202994]";
    let point = |radius: &str| {
        edited(
            distant,
            &format!("type = \"point\"\nposition = [1.0, 20.0, 3.0]\n{radius}"),
        )
    };
    let file = parse_scene(&point("radius = 0.5")).unwrap();
    assert!(matches!(
        file.scene.lights()[0],
        shadeline::Light::Point { radius, .. } if radius == 0.5
    ));
    // Without the key, a point.
    let file = parse_scene(&point("")).unwrap();
    assert!(matches!(
        file.scene.lights()[0],
        shadeline::Light::Point { radius, .. } if radius == 0.0
    ));
    let text = point("radius = -1.0");
    assert_error(&text, "radius = -1.0", Some("light[0].radius"), "negative");
    let text = point("radius = 1000.0");
    assert_error(&text, "radius = 1000.0", Some("light[0].radius"), "overlap");
    let text = edited(distant, &format!("{distant}\nradius = 0.5"));
    assert_error(
        &text,
        "radius = 0.5",
        Some("light[0].radius"),
        "a distant light has no `radius`",
    );
}
