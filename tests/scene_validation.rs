//! One test per validation rule of the scene model: each bad value is refused with the error
//! that names its item, its field and the problem, and the scene is left unchanged.

use shadeline::*;

fn camera() -> Camera {
    Camera {
        position: Vec3::new(0.0, 0.0, 5.0),
        look_at: Vec3::new(0.0, 0.0, 0.0),
        up: Vec3::new(0.0, 1.0, 0.0),
        vfov_degrees: 40.0,
    }
}

fn scene() -> Scene<2, 2> {
    Scene::new(camera(), LinearRgb::new(0.1, 0.2, 0.3)).unwrap()
}

fn sphere() -> Sphere {
    Sphere {
        center: Vec3::new(0.0, 0.0, 0.0),
        radius: 1.0,
        material: Material::default(),
    }
}

fn distant() -> Light {
    Light::Distant {
        direction: Vec3::new(0.0, -1.0, 0.0),
        color: LinearRgb::new(1.0, 1.0, 1.0),
        intensity: 1.0,
    }
}

fn invalid(item: Item, field: &'static str, problem: Problem) -> SceneError {
    SceneError::Invalid {
        item,
        field,
        problem,
    }
}

fn camera_error(c: Camera) -> SceneError {
    Scene::<2, 2>::new(c, LinearRgb::default()).unwrap_err()
}

fn sphere_error(s: Sphere) -> SceneError {
    let mut sc = scene();
    let err = sc.add_sphere(s).unwrap_err();
    assert!(
        sc.spheres().is_empty(),
        "a refused sphere must not be added"
    );
    err
}

fn light_error(l: Light) -> SceneError {
    let mut sc = scene();
    let err = sc.add_light(l).unwrap_err();
    assert!(sc.lights().is_empty(), "a refused light must not be added");
    err
}

#[test]
fn non_finite_numbers_are_refused_in_every_field() {
    for bad in [f32::NAN, f32::INFINITY, f32::NEG_INFINITY] {
        let c = Camera {
            position: Vec3::new(bad, 0.0, 5.0),
            ..camera()
        };
        assert_eq!(
            camera_error(c),
            invalid(Item::Camera, "position", Problem::NotFinite)
        );
        let c = Camera {
            look_at: Vec3::new(0.0, bad, 0.0),
            ..camera()
        };
        assert_eq!(
            camera_error(c),
            invalid(Item::Camera, "look_at", Problem::NotFinite)
        );
        let c = Camera {
            up: Vec3::new(0.0, 1.0, bad),
            ..camera()
        };
        assert_eq!(
            camera_error(c),
            invalid(Item::Camera, "up", Problem::NotFinite)
        );
        let c = Camera {
            vfov_degrees: bad,
            ..camera()
        };
        assert_eq!(
            camera_error(c),
            invalid(Item::Camera, "vfov", Problem::NotFinite)
        );
        assert_eq!(
            Scene::<2, 2>::new(camera(), LinearRgb::new(0.0, bad, 0.0)).unwrap_err(),
            invalid(Item::Background, "background", Problem::NotFinite)
        );
        let s0 = Item::Sphere(0);
        assert_eq!(
            sphere_error(Sphere {
                center: Vec3::new(0.0, 0.0, bad),
                ..sphere()
            }),
            invalid(s0, "center", Problem::NotFinite)
        );
        assert_eq!(
            sphere_error(Sphere {
                radius: bad,
                ..sphere()
            }),
            invalid(s0, "radius", Problem::NotFinite)
        );
        let m = Material::default();
        let with = |material| Sphere {
            material,
            ..sphere()
        };
        assert_eq!(
            sphere_error(with(Material {
                albedo: LinearRgb::new(bad, 0.0, 0.0),
                ..m
            })),
            invalid(s0, "albedo", Problem::NotFinite)
        );
        assert_eq!(
            sphere_error(with(Material { kd: bad, ..m })),
            invalid(s0, "kd", Problem::NotFinite)
        );
        assert_eq!(
            sphere_error(with(Material { ks: bad, ..m })),
            invalid(s0, "ks", Problem::NotFinite)
        );
        assert_eq!(
            sphere_error(with(Material {
                shininess: bad,
                ..m
            })),
            invalid(s0, "shininess", Problem::NotFinite)
        );
        let l0 = Item::Light(0);
        let c1 = LinearRgb::new(1.0, 1.0, 1.0);
        assert_eq!(
            light_error(Light::Distant {
                direction: Vec3::new(bad, -1.0, 0.0),
                color: c1,
                intensity: 1.0
            }),
            invalid(l0, "direction", Problem::NotFinite)
        );
        assert_eq!(
            light_error(Light::Distant {
                direction: Vec3::new(0.0, -1.0, 0.0),
                color: LinearRgb::new(1.0, bad, 1.0),
                intensity: 1.0
            }),
            invalid(l0, "color", Problem::NotFinite)
        );
        assert_eq!(
            light_error(Light::Point {
                position: Vec3::new(0.0, bad, 0.0),
                color: c1,
                intensity: 1.0,
                radius: 0.0,
            }),
            invalid(l0, "position", Problem::NotFinite)
        );
        assert_eq!(
            light_error(Light::Point {
                position: Vec3::new(0.0, 3.0, 0.0),
                color: c1,
                intensity: bad,
                radius: 0.0,
            }),
            invalid(l0, "intensity", Problem::NotFinite)
        );
        assert_eq!(
            light_error(Light::Point {
                position: Vec3::new(0.0, 3.0, 0.0),
                color: c1,
                intensity: 1.0,
                radius: bad,
            }),
            invalid(l0, "radius", Problem::NotFinite)
        );
    }
}

fn sphere_light(position: Vec3, radius: f32) -> Light {
    Light::Point {
        position,
        color: LinearRgb::new(1.0, 1.0, 1.0),
        intensity: 1.0,
        radius,
    }
}

#[test]
fn a_light_radius_must_not_be_negative_or_beyond_the_coordinates() {
    let l0 = Item::Light(0);
    let at = Vec3::new(0.0, 3.0, 0.0);
    assert_eq!(
        light_error(sphere_light(at, -0.5)),
        invalid(l0, "radius", Problem::Negative)
    );
    assert_eq!(
        light_error(sphere_light(at, 2.0e6)),
        invalid(l0, "radius", Problem::TooLarge)
    );
    // The radius is checked after the position, before the colour.
    let mut both = sphere_light(Vec3::new(f32::NAN, 0.0, 0.0), -1.0);
    assert_eq!(
        light_error(both),
        invalid(l0, "position", Problem::NotFinite)
    );
    if let Light::Point {
        position, color, ..
    } = &mut both
    {
        *position = at;
        *color = LinearRgb::new(-1.0, 0.0, 0.0);
    }
    assert_eq!(light_error(both), invalid(l0, "radius", Problem::Negative));
}

#[test]
fn a_sphere_light_may_not_overlap_a_sphere_whichever_comes_first() {
    let overlap = invalid(Item::Light(0), "radius", Problem::LightOverlapsSphere);
    // The sphere first, then a light reaching into it: refused, the scene unchanged.
    let mut sc = scene();
    sc.add_sphere(sphere()).unwrap();
    assert_eq!(
        sc.add_light(sphere_light(Vec3::new(0.0, 3.0, 0.0), 2.5)),
        Err(overlap)
    );
    assert!(sc.lights().is_empty());
    // Touching is allowed, and so is a point light inside nothing.
    sc.add_light(sphere_light(Vec3::new(0.0, 3.0, 0.0), 2.0))
        .unwrap();
    // The light first, then a sphere reaching into it: refused, naming the light.
    let mut sc = scene();
    sc.add_light(sphere_light(Vec3::new(0.0, 3.0, 0.0), 2.5))
        .unwrap();
    assert_eq!(sc.add_sphere(sphere()), Err(overlap));
    assert!(sc.spheres().is_empty());
    // A point light (radius 0) may even sit inside a sphere, as before.
    let mut sc = scene();
    sc.add_sphere(sphere()).unwrap();
    sc.add_light(sphere_light(Vec3::new(0.0, 0.5, 0.0), 0.0))
        .unwrap();
    let message = overlap.to_string();
    assert!(
        message.contains("light 0") && message.contains("radius"),
        "{message}"
    );
}

#[test]
fn radius_must_be_positive() {
    for r in [0.0, -0.0, -1.0] {
        assert_eq!(
            sphere_error(Sphere {
                radius: r,
                ..sphere()
            }),
            invalid(Item::Sphere(0), "radius", Problem::NotPositive)
        );
    }
}

#[test]
fn shininess_must_be_positive() {
    for n in [0.0, -2.0] {
        let material = Material {
            shininess: n,
            ..Material::default()
        };
        assert_eq!(
            sphere_error(Sphere {
                material,
                ..sphere()
            }),
            invalid(Item::Sphere(0), "shininess", Problem::NotPositive)
        );
    }
}

#[test]
fn kd_ks_and_albedo_must_not_be_negative() {
    let m = Material::default();
    let s = |material| Sphere {
        material,
        ..sphere()
    };
    assert_eq!(
        sphere_error(s(Material { kd: -0.1, ..m })),
        invalid(Item::Sphere(0), "kd", Problem::Negative)
    );
    assert_eq!(
        sphere_error(s(Material { ks: -0.1, ..m })),
        invalid(Item::Sphere(0), "ks", Problem::Negative)
    );
    assert_eq!(
        sphere_error(s(Material {
            albedo: LinearRgb::new(0.5, 0.5, -0.01),
            ..m
        })),
        invalid(Item::Sphere(0), "albedo", Problem::Negative)
    );
}

#[test]
fn light_colour_and_intensity_must_not_be_negative() {
    let err = light_error(Light::Distant {
        direction: Vec3::new(0.0, -1.0, 0.0),
        color: LinearRgb::new(1.0, 1.0, 1.0),
        intensity: -1.0,
    });
    assert_eq!(err, invalid(Item::Light(0), "intensity", Problem::Negative));
    let err = light_error(Light::Point {
        position: Vec3::new(0.0, 3.0, 0.0),
        color: LinearRgb::new(-1.0, 1.0, 1.0),
        intensity: 1.0,
        radius: 0.0,
    });
    assert_eq!(err, invalid(Item::Light(0), "color", Problem::Negative));
}

#[test]
fn light_direction_must_not_be_zero() {
    let err = light_error(Light::Distant {
        direction: Vec3::new(0.0, 0.0, 0.0),
        color: LinearRgb::new(1.0, 1.0, 1.0),
        intensity: 1.0,
    });
    assert_eq!(
        err,
        invalid(Item::Light(0), "direction", Problem::ZeroLength)
    );
}

#[test]
fn camera_up_must_not_be_zero() {
    let c = Camera {
        up: Vec3::new(0.0, 0.0, 0.0),
        ..camera()
    };
    assert_eq!(
        camera_error(c),
        invalid(Item::Camera, "up", Problem::ZeroLength)
    );
}

#[test]
fn camera_position_must_differ_from_look_at() {
    let c = Camera {
        look_at: Vec3::new(0.0, 0.0, 5.0),
        ..camera()
    };
    assert_eq!(
        camera_error(c),
        invalid(Item::Camera, "look_at", Problem::LookAtEqualsPosition)
    );
}

#[test]
fn camera_up_must_not_be_parallel_to_the_view() {
    for up in [
        Vec3::new(0.0, 0.0, 1.0),
        Vec3::new(0.0, 0.0, -3.0),
        Vec3::new(1e-5, 0.0, 1.0),
    ] {
        let c = Camera { up, ..camera() };
        assert_eq!(
            camera_error(c),
            invalid(Item::Camera, "up", Problem::UpParallelToView),
            "up {up:?}"
        );
    }
    // Slightly off the view direction is fine.
    assert!(Scene::<1, 1>::new(
        Camera {
            up: Vec3::new(0.01, 0.0, 1.0),
            ..camera()
        },
        LinearRgb::default()
    )
    .is_ok());
}

#[test]
fn vfov_must_be_inside_0_and_180_degrees() {
    for vfov in [0.0, -10.0, 180.0, 270.0] {
        let c = Camera {
            vfov_degrees: vfov,
            ..camera()
        };
        assert_eq!(
            camera_error(c),
            invalid(Item::Camera, "vfov", Problem::FieldOfViewOutOfRange),
            "vfov {vfov}"
        );
    }
    for vfov in [1e-6, 179.999] {
        assert!(Scene::<1, 1>::new(
            Camera {
                vfov_degrees: vfov,
                ..camera()
            },
            LinearRgb::default()
        )
        .is_ok());
    }
}

#[test]
fn values_beyond_the_documented_ranges_are_refused() {
    assert_eq!(
        sphere_error(Sphere {
            radius: 1e30,
            ..sphere()
        }),
        invalid(Item::Sphere(0), "radius", Problem::TooLarge)
    );
    assert_eq!(
        sphere_error(Sphere {
            center: Vec3::new(2e6, 0.0, 0.0),
            ..sphere()
        }),
        invalid(Item::Sphere(0), "center", Problem::TooLarge)
    );
    let material = Material {
        shininess: 1e7,
        ..Material::default()
    };
    assert_eq!(
        sphere_error(Sphere {
            material,
            ..sphere()
        }),
        invalid(Item::Sphere(0), "shininess", Problem::TooLarge)
    );
    let err = light_error(Light::Distant {
        direction: Vec3::new(0.0, -1.0, 0.0),
        color: LinearRgb::new(1.0, 1.0, 1.0),
        intensity: 1e13,
    });
    assert_eq!(err, invalid(Item::Light(0), "intensity", Problem::TooLarge));
    assert!(err.to_string().contains("at most 1e12"), "{err}");
}

#[test]
fn capacity_is_enforced_with_a_typed_error() {
    let mut sc = scene();
    sc.add_sphere(sphere()).unwrap();
    sc.add_sphere(sphere()).unwrap();
    assert_eq!(
        sc.add_sphere(sphere()),
        Err(SceneError::CapacityExceeded {
            kind: ItemKind::Sphere,
            capacity: 2
        })
    );
    sc.add_light(distant()).unwrap();
    sc.add_light(distant()).unwrap();
    assert_eq!(
        sc.add_light(distant()),
        Err(SceneError::CapacityExceeded {
            kind: ItemKind::Light,
            capacity: 2
        })
    );
    assert_eq!((sc.spheres().len(), sc.lights().len()), (2, 2));
}

#[test]
fn errors_name_the_item_and_field_in_their_message() {
    let mut sc = scene();
    sc.add_sphere(sphere()).unwrap();
    let err = sc
        .add_sphere(Sphere {
            radius: -1.0,
            ..sphere()
        })
        .unwrap_err();
    assert_eq!(
        err.to_string(),
        "sphere 1: `radius` must be greater than zero"
    );
    let as_error: &dyn core::error::Error = &err;
    assert!(as_error.source().is_none());
    let err = Scene::<1, 1>::new(
        Camera {
            vfov_degrees: 180.0,
            ..camera()
        },
        LinearRgb::default(),
    )
    .unwrap_err();
    assert_eq!(
        err.to_string(),
        "camera: `vfov` must be between 0 and 180 degrees, exclusive"
    );
}

#[test]
fn render_sizes_and_buffers_are_checked() {
    let sc: Scene = Scene::new(camera(), LinearRgb::new(0.1, 0.2, 0.3)).unwrap();
    assert_eq!(
        Prepared::<Scalar>::new(&sc, 0, 10).unwrap_err(),
        RenderError::BadSize {
            width: 0,
            height: 10
        }
    );
    assert_eq!(
        Prepared::<Scalar>::new(&sc, 10, 70_000).unwrap_err(),
        RenderError::BadSize {
            width: 10,
            height: 70_000
        }
    );
    let frame = Prepared::<Scalar>::new(&sc, 10, 4).unwrap();
    let mut short = [Rgb888::default(); 9];
    assert_eq!(
        frame.render_line(0, &mut short),
        Err(RenderError::LineLength {
            expected: 10,
            got: 9
        })
    );
    let mut long = [Rgb888::default(); 11];
    assert_eq!(
        frame.render_line(0, &mut long),
        Err(RenderError::LineLength {
            expected: 10,
            got: 11
        })
    );
    assert!(
        long.iter().all(|p| *p == Rgb888::default()),
        "nothing written on error"
    );
    let mut line = [Rgb888::default(); 10];
    assert_eq!(
        frame.render_line(4, &mut line),
        Err(RenderError::RowOutOfRange { y: 4, height: 4 })
    );
    let mut buf = [Rgb565::default(); 39];
    assert_eq!(
        frame.render_frame(&mut buf),
        Err(RenderError::FrameLength {
            expected: 40,
            got: 39
        })
    );
}

fn with_model(model: Model) -> Sphere {
    let mut s = sphere();
    s.material.model = model;
    s
}

#[test]
fn oren_nayar_roughness_is_checked() {
    let on = |roughness: f32| with_model(Model::OrenNayar { roughness });
    let err = |p| invalid(Item::Sphere(0), "roughness", p);
    for ok in [0.0, 0.5, MAX_OREN_NAYAR_ROUGHNESS] {
        scene().add_sphere(on(ok)).unwrap();
    }
    assert_eq!(sphere_error(on(-0.01)), err(Problem::Negative));
    assert_eq!(sphere_error(on(1.6)), err(Problem::TooLarge));
    assert_eq!(sphere_error(on(f32::NAN)), err(Problem::NotFinite));
    assert!(sphere_error(on(1.6)).to_string().contains("π/2"));
}

#[test]
fn ggx_roughness_and_ior_are_checked() {
    let ggx = |roughness: f32, surface| with_model(Model::Ggx(Microfacet { roughness, surface }));
    let plain = Surface::Dielectric { ior: None };
    let err = |f, p| invalid(Item::Sphere(0), f, p);
    for ok in [MIN_GGX_ROUGHNESS, 0.5, 1.0] {
        scene().add_sphere(ggx(ok, plain)).unwrap();
    }
    assert_eq!(
        sphere_error(ggx(0.04, plain)),
        err("roughness", Problem::TooSmall)
    );
    assert!(sphere_error(ggx(0.0, plain))
        .to_string()
        .contains("at least 5e-2"));
    assert_eq!(
        sphere_error(ggx(1.01, plain)),
        err("roughness", Problem::TooLarge)
    );
    assert_eq!(
        sphere_error(ggx(f32::INFINITY, plain)),
        err("roughness", Problem::NotFinite)
    );
    let glass = |ior| Surface::Dielectric { ior: Some(ior) };
    assert_eq!(
        sphere_error(ggx(0.5, glass(1.0))),
        err("ior", Problem::NotAboveOne)
    );
    // The roughness is reported before the ior.
    assert_eq!(
        sphere_error(ggx(2.0, glass(0.5))),
        err("roughness", Problem::TooLarge)
    );
    scene()
        .add_sphere(ggx(0.5, Surface::Metal(Metal::Copper)))
        .unwrap();
}
