//! The scene matrix's files (`scenes/floor.toml`, `lamp.toml`, `three-lights.toml`) are its
//! built-in presets, number for number, and their spheres rest on the floor.

use shadeline::{MatrixScene, MATRIX_SIZE};
use shadeline_harness::parse_scene;

fn assert_file_is(name: &str, builtin: MatrixScene) {
    let path = format!("{}/../scenes/{name}", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(path).expect("the committed scene file is readable");
    let file = parse_scene(&text).unwrap_or_else(|e| panic!("{name}: {e}"));
    assert_eq!((file.width, file.height), MATRIX_SIZE, "{name}");
    assert_eq!(file.scene.camera(), builtin.camera(), "{name}");
    assert_eq!(file.scene.background(), builtin.background(), "{name}");
    assert_eq!(file.scene.spheres(), builtin.spheres(), "{name}");
    assert_eq!(file.scene.lights(), builtin.lights(), "{name}");
}

#[test]
fn the_committed_matrix_files_are_the_built_in_scenes() {
    assert_file_is("floor.toml", shadeline::floor().unwrap());
    assert_file_is("lamp.toml", shadeline::lamp().unwrap());
    assert_file_is("three-lights.toml", shadeline::three_lights().unwrap());
}

#[test]
fn the_matrix_spheres_rest_on_the_floor() {
    for scene in [
        shadeline::floor().unwrap(),
        shadeline::lamp().unwrap(),
        shadeline::three_lights().unwrap(),
    ] {
        let (floor, spheres) = scene.spheres().split_first().unwrap();
        assert_eq!(spheres.len(), 4);
        for s in spheres {
            let d = s.center - floor.center;
            let gap = f64::from(d.dot(d)).sqrt() - f64::from(floor.radius + s.radius);
            assert!(gap.abs() < 1.0e-3, "{s:?} is {gap} from the floor");
        }
    }
}
