//! The CRCs the firmware checks on target (`firmware/expected.rs`) are the host's: this test
//! renders the same frames on the host and compares, so a change to the renderer that moves a
//! pixel fails here, next to the constant to update, rather than only under QEMU. The fixed
//! value is also `tests/fixed_golden.rs`'s golden; both tests failing together is the sign of
//! a deliberate change to the fixed kernel.

use shadeline::{
    exponent_series, microfacets, HitRecord, Prepared, PreparedFixed, Render, Rgb565, Scalar,
};

mod expected {
    include!("../firmware/expected.rs");
}

/// CRC32/IEEE over the pixels as little-endian `u16` bytes, row-major: the firmware's rule.
/// Bit by bit, straight from the definition (reflected, polynomial `0xEDB88320`), so it is an
/// independent check of the firmware's table-driven one.
fn rgb565_crc32(pixels: &[Rgb565]) -> u32 {
    let mut crc = !0u32;
    for byte in pixels.iter().flat_map(|px| px.0.to_le_bytes()) {
        crc ^= u32::from(byte);
        for _ in 0..8 {
            crc = if crc & 1 != 0 {
                (crc >> 1) ^ 0xedb8_8320
            } else {
                crc >> 1
            };
        }
    }
    !crc
}

fn frame<R: Render>(path: &R) -> Vec<Rgb565> {
    let mut pixels = vec![Rgb565::default(); (path.width() * path.height()) as usize];
    path.render_frame(&mut pixels).expect("frame renders");
    pixels
}

#[test]
fn scalar_crc_matches_the_firmware_constant() {
    let scene = exponent_series().expect("built-in scene is valid");
    let path = Prepared::<Scalar>::new(&scene, expected::WIDTH, expected::HEIGHT).unwrap();
    let crc = rgb565_crc32(&frame(&path));
    assert_eq!(
        crc,
        expected::SCALAR_RGB565_CRC32,
        "host scalar CRC is {crc:#010x}: update firmware/expected.rs"
    );
}

#[test]
fn antialiased_scalar_crc_matches_the_firmware_constant() {
    let scene = exponent_series().expect("built-in scene is valid");
    let path = Prepared::<Scalar>::new(&scene, expected::WIDTH, expected::HEIGHT)
        .unwrap()
        .with_antialiasing(true);
    let crc = rgb565_crc32(&frame(&path));
    assert_eq!(
        crc,
        expected::SCALAR_AA_RGB565_CRC32,
        "host anti-aliased scalar CRC is {crc:#010x}: update firmware/expected.rs"
    );
}

#[test]
fn fixed_crc_matches_the_firmware_constant() {
    let scene = exponent_series().expect("built-in scene is valid");
    let path = PreparedFixed::new(&scene, expected::WIDTH, expected::HEIGHT).unwrap();
    let crc = rgb565_crc32(&frame(&path));
    assert_eq!(
        crc,
        expected::FIXED_RGB565_CRC32,
        "host fixed CRC is {crc:#010x}: update firmware/expected.rs (and tests/fixed_golden.rs)"
    );
}

#[cfg(all(feature = "antialias", feature = "full-width"))]
#[test]
fn antialiased_fixed_crc_matches_the_firmware_constant() {
    let scene = exponent_series().expect("built-in scene is valid");
    let path = PreparedFixed::new(&scene, expected::WIDTH, expected::HEIGHT)
        .unwrap()
        .with_antialiasing(true);
    let crc = rgb565_crc32(&frame(&path));
    assert_eq!(
        crc,
        expected::FIXED_AA_RGB565_CRC32,
        "host anti-aliased fixed CRC is {crc:#010x}: update firmware/expected.rs"
    );
}

/// Pixels whose primary ray hits a sphere, from the path's own hit records.
fn covered<R: Render>(path: &R) -> u64 {
    let mut hits = vec![HitRecord::default(); (path.width() * path.height()) as usize];
    path.render_frame(&mut hits).expect("frame renders");
    hits.iter().filter(|h| h.sphere.is_some()).count() as u64
}

#[test]
fn covered_counts_match_the_firmware_constants() {
    let scene = exponent_series().expect("built-in scene is valid");
    let scalar = Prepared::<Scalar>::new(&scene, expected::WIDTH, expected::HEIGHT).unwrap();
    let fixed = PreparedFixed::new(&scene, expected::WIDTH, expected::HEIGHT).unwrap();
    assert_eq!(
        (covered(&scalar), covered(&fixed)),
        (expected::SCALAR_COVERED, expected::FIXED_COVERED),
        "host covered counts (scalar, fixed): update firmware/expected.rs"
    );
}

#[test]
fn microfacet_gallery_crc_and_covered_count_match_the_firmware_constants() {
    let scene = microfacets().expect("built-in scene is valid");
    let path = Prepared::<Scalar>::new(&scene, expected::WIDTH, expected::HEIGHT).unwrap();
    let (crc, hits) = (rgb565_crc32(&frame(&path)), covered(&path));
    assert_eq!(
        (crc, hits),
        (
            expected::MICROFACETS_SCALAR_RGB565_CRC32,
            expected::MICROFACETS_SCALAR_COVERED
        ),
        "host microfacets CRC {crc:#010x}, covered {hits}: update firmware/expected.rs"
    );
    let fixed = PreparedFixed::new(&scene, expected::WIDTH, expected::HEIGHT).unwrap();
    let (crc, hits) = (rgb565_crc32(&frame(&fixed)), covered(&fixed));
    assert_eq!(
        (crc, hits),
        (
            expected::MICROFACETS_FIXED_RGB565_CRC32,
            expected::MICROFACETS_FIXED_COVERED
        ),
        "host fixed microfacets CRC {crc:#010x}, covered {hits}: update firmware/expected.rs"
    );
}

#[cfg(feature = "area-lights")]
#[test]
fn area_lights_crcs_and_covered_count_match_the_firmware_constants() {
    let (w, h) = (expected::AREA_LIGHTS_WIDTH, expected::AREA_LIGHTS_HEIGHT);
    let mut found = Vec::new();
    for radius in [shadeline::AREA_LIGHT_RADIUS, 0.0] {
        let scene = shadeline::area_lights(radius).expect("built-in scene is valid");
        let path = Prepared::<Scalar, 5, 1>::new(&scene, w, h).unwrap();
        found.push((rgb565_crc32(&frame(&path)), covered(&path)));
    }
    let [(sphere, covered_sphere), (point, covered_point)] = found[..] else {
        unreachable!("two radii")
    };
    assert_eq!(
        (sphere, point, covered_sphere, covered_point),
        (
            expected::AREA_LIGHTS_SPHERE_RGB565_CRC32,
            expected::AREA_LIGHTS_POINT_RGB565_CRC32,
            expected::AREA_LIGHTS_COVERED,
            expected::AREA_LIGHTS_COVERED
        ),
        "host area-lights CRCs (sphere light {sphere:#010x}, point light {point:#010x}), \
         covered ({covered_sphere}, {covered_point}): update firmware/expected.rs"
    );
    assert_ne!(sphere, point, "the sphere light changes the frame");
}

#[cfg(all(feature = "area-lights", feature = "full-width"))]
#[test]
fn fixed_area_lights_crcs_match_the_firmware_constants() {
    let (w, h) = (expected::AREA_LIGHTS_WIDTH, expected::AREA_LIGHTS_HEIGHT);
    let [sphere, point] = [shadeline::AREA_LIGHT_RADIUS, 0.0].map(|radius| {
        let scene = shadeline::area_lights(radius).expect("built-in scene is valid");
        let path = PreparedFixed::<5, 1>::new(&scene, w, h).unwrap();
        (rgb565_crc32(&frame(&path)), covered(&path))
    });
    assert_eq!(
        (sphere, point),
        (
            (
                expected::AREA_LIGHTS_FIXED_SPHERE_RGB565_CRC32,
                expected::AREA_LIGHTS_COVERED
            ),
            (
                expected::AREA_LIGHTS_FIXED_POINT_RGB565_CRC32,
                expected::AREA_LIGHTS_COVERED
            ),
        ),
        "host fixed area-lights CRCs (sphere light {:#010x}, point light {:#010x}) and covered \
         counts ({}, {}): update firmware/expected.rs",
        sphere.0,
        point.0,
        sphere.1,
        point.1
    );
    assert_ne!(sphere.0, point.0, "the sphere light changes the frame");
}

#[test]
fn per_model_crcs_and_covered_counts_match_the_firmware_constants() {
    let (w, h) = (expected::WIDTH, expected::HEIGHT);
    let mut found = Vec::new();
    for (name, material) in shadeline::model_samples() {
        let scene = shadeline::covered_sphere(material).expect("built-in scene is valid");
        let scalar = Prepared::<Scalar, 1, 2>::new(&scene, w, h).unwrap();
        let fixed = PreparedFixed::<1, 2>::new(&scene, w, h).unwrap();
        let crcs = [rgb565_crc32(&frame(&scalar)), rgb565_crc32(&frame(&fixed))];
        let counts = [covered(&scalar), covered(&fixed)];
        found.push((name, crcs, counts));
    }
    let crcs: Vec<[u32; 2]> = found.iter().map(|f| f.1).collect();
    assert_eq!(
        crcs,
        expected::MODEL_RGB565_CRC32,
        "host per-model CRCs (scalar, fixed) {:#010x?}: update firmware/expected.rs",
        found
    );
    for (name, _, counts) in &found {
        assert_eq!(
            *counts,
            [expected::MODEL_COVERED; 2],
            "{name}: covered pixels"
        );
    }
}

/// The scene matrix's scenes, in the order of `expected::MATRIX_RGB565_CRC32`.
#[cfg(feature = "blinn-phong")]
fn matrix_scenes() -> [shadeline::MatrixScene; 3] {
    [
        shadeline::floor(),
        shadeline::lamp(),
        shadeline::three_lights(),
    ]
    .map(|scene| scene.expect("built-in scene is valid"))
}

#[cfg(feature = "blinn-phong")]
#[test]
fn matrix_scalar_crcs_and_covered_counts_match_the_firmware_constants() {
    let (w, h) = shadeline::MATRIX_SIZE;
    let found = matrix_scenes().map(|scene| {
        let path = Prepared::<Scalar, 6, 3>::new(&scene, w, h).unwrap();
        (rgb565_crc32(&frame(&path)), covered(&path))
    });
    let crcs = found.map(|(crc, _)| crc);
    assert_eq!(
        crcs,
        expected::MATRIX_RGB565_CRC32.map(|[scalar, _]| scalar),
        "host scalar CRCs of the matrix (floor, lamp, three-lights) {crcs:#010x?}: update \
         firmware/expected.rs"
    );
    assert_eq!(
        found.map(|(_, hits)| hits),
        [expected::MATRIX_SCALAR_COVERED; 3],
        "host scalar covered counts of the matrix (floor, lamp, three-lights): update \
         firmware/expected.rs"
    );
}

#[cfg(all(feature = "blinn-phong", feature = "full-width"))]
#[test]
fn matrix_fixed_crcs_and_covered_counts_match_the_firmware_constants() {
    let (w, h) = shadeline::MATRIX_SIZE;
    let found = matrix_scenes().map(|scene| {
        let path = PreparedFixed::<6, 3>::new(&scene, w, h).unwrap();
        (rgb565_crc32(&frame(&path)), covered(&path))
    });
    let crcs = found.map(|(crc, _)| crc);
    assert_eq!(
        crcs,
        expected::MATRIX_RGB565_CRC32.map(|[_, fixed]| fixed),
        "host fixed CRCs of the matrix (floor, lamp, three-lights) {crcs:#010x?}: update \
         firmware/expected.rs"
    );
    assert_eq!(
        found.map(|(_, hits)| hits),
        [expected::MATRIX_FIXED_COVERED; 3],
        "host fixed covered counts of the matrix (floor, lamp, three-lights): update \
         firmware/expected.rs"
    );
}

/// The animations of the firmware's feature `animation`: the same scenes, from the same file
/// (whose report names and indices only the firmware reads).
#[allow(dead_code)]
mod animation {
    include!("../firmware/animation.rs");
}

/// One animation as the firmware draws it, with the sine and cosine of `T`: frame 0 on a
/// display, then each frame's damage against the one before, rendered in pieces of at most a
/// row (the firmware's line buffer) and laid over the display. Fails unless the display then
/// holds each frame exactly as rendered in full, and unless all but two frames differ from the
/// one before (so the check is never vacuous). Returns the CRC of frames 1 to N one after the
/// other, the CRC of the last frame, the CRC of every piece sent (its `x`, `y` and length as
/// `u16`s, then its pixels: the firmware's stream) and the damaged pixels.
fn animation_figures<T: animation::Trig>(motion: animation::Motion) -> (u32, u32, u32, u64) {
    use animation::{animation_scene, motion_at, ANIMATION_FRAMES, ANIMATION_HEIGHT};
    use shadeline::damage::Damage;
    let (w, h) = (animation::ANIMATION_WIDTH, ANIMATION_HEIGHT);
    let scene = |k| animation_scene(motion, motion_at::<T>(motion, k)).expect("scene builds");
    let prepare = |s: &animation::AnimationScene| PreparedFixed::<5, 2>::new(s, w, h).unwrap();
    let (mut shown_scene, mut shown_pixels) = (scene(0), Vec::new());
    let mut shown = prepare(&shown_scene);
    let mut display = frame(&shown);
    let (mut stream, mut damaged, mut frames, mut changed) = (Vec::new(), 0u64, Vec::new(), 0);
    let mut row = vec![Rgb565::default(); w as usize];
    for k in 1..=ANIMATION_FRAMES {
        let next_scene = scene(k);
        let next = prepare(&next_scene);
        let damage: Damage = Damage::between(&shown_scene, &shown, &next_scene, &next);
        damage
            .render(&next, &mut row, |x, y, pixels: &[Rgb565]| {
                stream.extend([x, y, pixels.len() as u32].map(|v| Rgb565(v as u16)));
                stream.extend_from_slice(pixels);
                let at = (y * w + x) as usize;
                display[at..at + pixels.len()].copy_from_slice(pixels);
                damaged += pixels.len() as u64;
                Ok::<(), shadeline::RenderError>(())
            })
            .expect("damage renders");
        let full = frame(&next);
        let wrong = display.iter().zip(&full).filter(|(a, b)| a != b).count();
        assert_eq!(wrong, 0, "{motion:?} frame {k}: pixels the damage missed");
        changed += u32::from(shown_pixels != full);
        frames.extend_from_slice(&full);
        (shown_scene, shown, shown_pixels) = (next_scene, next, full);
    }
    // The bounce's two peaks fall between frames (7.5 and 22.5 of 30): the frames either side
    // are the same scene, and their damage is empty.
    assert!(
        changed >= ANIMATION_FRAMES - 2,
        "{motion:?}: only {changed} frames differ from the one before"
    );
    let last = rgb565_crc32(&display);
    (rgb565_crc32(&frames), last, rgb565_crc32(&stream), damaged)
}

#[test]
fn animation_crcs_and_damage_match_the_firmware_constants() {
    use animation::{Libm, Micromath, MOTIONS};
    let found = [
        MOTIONS.map(animation_figures::<Micromath>),
        MOTIONS.map(animation_figures::<Libm>),
    ];
    let frames = found.map(|m| m.map(|f| f.0));
    let last = found.map(|m| m.map(|f| f.1));
    let stream = found.map(|m| m.map(|f| f.2));
    let pixels = found.map(|m| m.map(|f| f.3));
    assert_eq!(
        (frames, last, stream, pixels),
        (
            expected::ANIMATION_FRAMES_RGB565_CRC32,
            expected::ANIMATION_LAST_RGB565_CRC32,
            expected::ANIMATION_DAMAGE_STREAM_CRC32,
            expected::ANIMATION_DAMAGE_PIXELS
        ),
        "host animation figures ([micromath, libm] × [orbit, bounce]): all frames' CRCs \
         {frames:#010x?}, last frame CRCs {last:#010x?}, damage stream CRCs {stream:#010x?}, damaged pixels {pixels:?}: update \
         firmware/expected.rs"
    );
    assert_ne!(
        frames[0], frames[1],
        "micromath and libm move the scene differently"
    );
}
