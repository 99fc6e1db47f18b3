//! shadeline built without the feature `full-width`: the fixed path's spans are the spheres'
//! outlines alone, row by row (no screen rectangle around them), and they change no pixel.
//! Each frame is rendered twice, with spans and with every sphere tested at every pixel
//! (`with_spans(false)`), and compared pixel by pixel: a span that left out a pixel a sphere
//! covers would show as a difference. The frames: the exponent series at several sizes, and
//! random scenes of spheres near the frame's edges, partly off screen and close to the camera.

use shadeline::{
    exponent_series_with_capacity, Camera, Light, LinearRgb, Material, PreparedFixed, Render,
    Rgb888, Scene, Sphere, Vec3,
};

fn frame<const S: usize, const L: usize>(frame: &PreparedFixed<S, L>) -> Vec<Rgb888> {
    let (w, h) = (frame.width(), frame.height());
    let mut out = vec![Rgb888::default(); (w * h) as usize];
    for (y, row) in out.chunks_mut(w as usize).enumerate() {
        frame
            .render_line(y as u32, row)
            .expect("a row of the frame");
    }
    out
}

/// Renders `scene` at `w × h` with and without spans and compares; `false` if the narrow
/// kernel refuses the frame (a random scene may put the camera too close to a sphere), or
/// the frame is of one colour.
fn spans_change_nothing<const S: usize, const L: usize>(
    scene: &Scene<S, L>,
    (w, h): (u32, u32),
    what: &str,
) -> bool {
    let Ok(with) = PreparedFixed::<S, L>::new(scene, w, h) else {
        return false;
    };
    let without = with.clone().with_spans(false);
    let (a, b) = (frame(&with), frame(&without));
    for (i, (p, q)) in a.iter().zip(&b).enumerate() {
        assert_eq!(
            p,
            q,
            "{what} at {w}x{h}: pixel ({}, {}) differs with spans",
            i as u32 % w,
            i as u32 / w
        );
    }
    // A frame of one colour (the background alone, or a sphere in shadow filling it) tests
    // nothing: it is not counted.
    a.iter().any(|p| *p != a[0])
}

#[test]
fn the_exponent_series_at_several_sizes() {
    let scene: Scene<5, 1> = exponent_series_with_capacity().expect("the preset");
    for size in [(320, 240), (64, 48), (97, 73), (31, 97), (200, 200)] {
        assert!(
            spans_change_nothing(&scene, size, "the exponent series"),
            "refused at {size:?}"
        );
    }
}

/// A small xorshift generator: the same scenes on every run.
struct Random(u64);

impl Random {
    fn unit(&mut self) -> f32 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 40) as f32 / (1u64 << 24) as f32
    }

    fn range(&mut self, lo: f32, hi: f32) -> f32 {
        lo + (hi - lo) * self.unit()
    }

    /// An empty scene seen from 8 units up the z axis, looking near the origin, with a
    /// field of view of 20° to `max_vfov`.
    fn scene<const S: usize, const L: usize>(&mut self, max_vfov: f32) -> Scene<S, L> {
        let camera = Camera {
            position: Vec3::new(0.0, 0.0, 8.0),
            look_at: Vec3::new(self.range(-0.5, 0.5), self.range(-0.5, 0.5), 0.0),
            up: Vec3::new(self.range(-0.3, 0.3), 1.0, 0.0),
            vfov_degrees: self.range(20.0, max_vfov),
        };
        Scene::new(camera, LinearRgb::new(0.1, 0.1, 0.2)).expect("valid camera")
    }
}

/// `scene` with one white-lit, default-material sphere of `center` and `radius` under a
/// distant light along `direction`.
fn one_sphere(
    mut scene: Scene<1, 1>,
    (center, radius): (Vec3, f32),
    direction: Vec3,
) -> Scene<1, 1> {
    let material = Material::default();
    scene
        .add_sphere(Sphere {
            center,
            radius,
            material,
        })
        .expect("a valid sphere");
    scene
        .add_light(Light::Distant {
            direction,
            color: LinearRgb::new(1.0, 1.0, 1.0),
            intensity: 1.0,
        })
        .expect("a valid light");
    scene
}

#[test]
fn random_scenes_near_the_edges_and_the_camera() {
    let mut random = Random(0x2545_f491_4f6c_dd1d);
    let mut rendered = 0;
    for i in 0..60 {
        let mut scene: Scene<6, 2> = random.scene(50.0);
        for _ in 0..5 {
            // Up to the frame's edges and beyond, and up to 2 units from the camera.
            let z = random.range(-4.0, 5.5);
            let reach = (8.0 - z) * 0.45;
            let sphere = Sphere {
                center: Vec3::new(random.range(-reach, reach), random.range(-reach, reach), z),
                radius: random.range(0.2, 1.2),
                material: Material {
                    shininess: random.range(2.0, 300.0),
                    ..Material::default()
                },
            };
            scene.add_sphere(sphere).expect("a valid sphere");
        }
        scene
            .add_light(Light::Distant {
                direction: Vec3::new(
                    random.range(-1.0, 1.0),
                    random.range(-1.0, 1.0),
                    -random.range(0.2, 1.0),
                ),
                color: LinearRgb::new(1.0, 0.9, 0.8),
                intensity: 1.5,
            })
            .expect("a valid light");
        let size = [(64, 48), (80, 80), (53, 29)][i % 3];
        if spans_change_nothing(&scene, size, &format!("random scene {i}")) {
            rendered += 1;
        }
    }
    // Most random scenes are narrow frames; the test must have compared many.
    assert!(
        rendered >= 30,
        "only {rendered} of 60 random scenes rendered"
    );
}

/// Frames two and three rows high, where the rows of a sphere's outline come from its first
/// rows alone (the walk down the rows reads no row below the frame): one sphere, its
/// silhouette crossing the frame, at several places and sizes.
#[test]
fn frames_of_two_and_three_rows() {
    let mut random = Random(0x9e37_79b9_7f4a_7c15);
    let camera = Camera {
        position: Vec3::new(0.0, 0.0, 8.0),
        look_at: Vec3::new(0.0, 0.0, 0.0),
        up: Vec3::new(0.0, 1.0, 0.0),
        vfov_degrees: 20.0,
    };
    let mut rendered = 0;
    for i in 0..60 {
        // The frame's half-height at z = 0 is 8·tan 10° ≈ 1.4 units.
        let center = Vec3::new(random.range(-0.5, 0.5), random.range(-0.5, 0.5), 0.0);
        let scene = one_sphere(
            Scene::new(camera, LinearRgb::new(0.1, 0.1, 0.2)).expect("valid camera"),
            (center, random.range(0.8, 1.6)),
            Vec3::new(0.3, -0.4, -1.0),
        );
        let size = [(3, 2), (2, 2), (4, 3), (3, 3)][i % 4];
        if spans_change_nothing(&scene, size, &format!("sphere {i}")) {
            rendered += 1;
        }
    }
    assert!(rendered >= 40, "only {rendered} of 60 frames rendered");
}

/// The spans are exact, not merely conservative: with one sphere in front of the camera
/// (its outline an ellipse on the screen), each row's span holds exactly the pixels whose
/// hit record is the sphere's, and a row the sphere does not reach has no span. Spheres of
/// every size from a few pixels to more than the frame, anywhere on screen or partly off it.
#[test]
fn spans_are_the_hit_pixels_exactly() {
    let mut random = Random(0x9e37_79b9_7f4a_7c15);
    let mut compared = 0usize;
    for i in 0..40 {
        let empty: Scene<1, 1> = random.scene(60.0);
        let z = random.range(-6.0, 4.0);
        let reach = (8.0 - z) * 0.5;
        let center = Vec3::new(random.range(-reach, reach), random.range(-reach, reach), z);
        let scene = one_sphere(
            empty,
            (center, random.range(0.05, 2.5)),
            Vec3::new(0.3, -1.0, -0.5),
        );
        let (w, h) = [(64, 48), (97, 31), (40, 90)][i % 3];
        // A wide frame at a wide field of view is the full-width kernel's.
        let Ok(frame) = PreparedFixed::<1, 1>::new(&scene, w, h) else {
            continue;
        };
        for y in 0..h {
            let mut hits = vec![shadeline::HitRecord::default(); w as usize];
            frame.render_line(y, &mut hits).expect("a row");
            let hit: Vec<u32> = (0..w)
                .filter(|&x| hits[x as usize].sphere == Some(0))
                .collect();
            let span = frame.row_spans(y)[0];
            let want = hit.first().map(|&start| (start, hit.len() as u32));
            let got = span.map(|s| (s.start, s.end - s.start));
            assert_eq!(got, want, "scene {i} ({w}x{h}), row {y}: span {span:?}");
            // The hit pixels are one run, as the span is.
            if let Some(&last) = hit.last() {
                assert_eq!(last + 1 - hit[0], hit.len() as u32, "scene {i}, row {y}");
            }
            compared += hit.len();
        }
    }
    assert!(compared > 10_000, "only {compared} hit pixels compared");
}
