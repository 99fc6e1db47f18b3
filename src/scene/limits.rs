//! The accepted ranges: the bounds every number of a scene is checked against (the table of
//! the [module docs](super)).
//!
//! The bounds live apart from the checks and the errors because both read them: the checks
//! compare each field with its bound, and an error's message quotes the bound it broke
//! ([`limit_of`]).

/// Largest accepted magnitude of a coordinate component and of a radius, in scene units.
pub const MAX_COORDINATE: f32 = 1.0e6;
/// Smallest accepted radius: `r²` is then a normal `f32` and `1/r` is finite. Below it the
/// squared radius underflows to 0 and the normal `(P − C)·(1/r)` becomes `0·inf = NaN`.
pub const MIN_RADIUS: f32 = 1.0e-18;
/// Largest accepted colour component, albedo component, `kd` or `ks`.
pub const MAX_VALUE: f32 = 1.0e6;
/// Largest accepted light intensity.
pub const MAX_INTENSITY: f32 = 1.0e12;
/// Largest accepted Phong exponent.
pub const MAX_SHININESS: f32 = 1.0e6;
/// Smallest sine of the angle between the camera's up vector and its view direction.
pub const MIN_UP_SINE: f32 = 1.0e-3;

/// Smallest accepted GGX `roughness`: `α = roughness²` is then `2.5·10⁻³` and the
/// distribution's peak `1/(πα²)` is about `5·10⁴`, still a lobe some pixels wide on a sphere
/// of a few hundred pixels; a smaller one would be a mirror that pixels cannot resolve.
pub const MIN_GGX_ROUGHNESS: f32 = 0.05;

/// Largest accepted Oren–Nayar `σ`, in radians: facet slopes of 90° standard deviation
/// already make the surface as rough as the model describes.
pub const MAX_OREN_NAYAR_ROUGHNESS: f32 = core::f32::consts::FRAC_PI_2;

/// The upper bound of the field named `field` (as a scene file spells it), for the message of
/// a [`Problem::TooLarge`](super::Problem::TooLarge).
pub(super) fn limit_of(field: &str) -> f32 {
    match field {
        "intensity" => MAX_INTENSITY,
        "shininess" | "lobes[1].shininess" | "lobes[2].shininess" => MAX_SHININESS,
        "albedo" | "color" | "kd" | "ks" | "background" | "ior" => MAX_VALUE,
        "lobes[1].weight" | "lobes[2].weight" => MAX_VALUE,
        _ => MAX_COORDINATE,
    }
}
