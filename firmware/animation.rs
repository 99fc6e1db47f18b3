// The two animations the firmware renders with its feature `animation`, and the scene of each
// of their frames: included (with `include!`) by the firmware's common crate and by the host
// test `tests/firmware_crcs.rs`, so that firmware and host build every frame's scene from the
// same code. The motion's sines and cosines are `f32` arithmetic only (micromath's parabolic
// approximation, or libm's `sinf`/`cosf`, which are IEEE operations in a fixed order too), so
// the scenes, and with them the fixed path's frames, are the same bits on every target.
//
// Both animations start from `shadeline::floor` (four spheres on a floor sphere, two distant
// lights) at `ANIMATION_WIDTH × ANIMATION_HEIGHT`:
//
// - `Motion::Orbit`: the key light (light 0) turns once about the vertical axis, by
//   `θ = 2π·k/N` at frame `k` of `N = ANIMATION_FRAMES`;
// - `Motion::Bounce`: sphere `BOUNCE_SPHERE` rises `BOUNCE_HEIGHT·|sin θ|` above where it rests:
//   two bounces.
//
// Frame 0 is what the display shows before the animation starts; frames 1 to N are the
// animation, each drawn in full or as its damage against the frame before.

/// Frames of each animation (frame 0, the picture before it, not counted).
pub const ANIMATION_FRAMES: u32 = 30;
/// Width of the animations' frames: the scene matrix's, a 320×240 SPI display's.
pub const ANIMATION_WIDTH: u32 = 320;
/// Height of the animations' frames.
pub const ANIMATION_HEIGHT: u32 = 240;

/// The scene of an animation's frame: the floor scene's five spheres and two lights.
pub type AnimationScene = shadeline::Scene<5, 2>;

/// The light that orbits: the floor scene's key light.
pub const ORBIT_LIGHT: usize = 0;
/// The sphere that bounces: the second of the four on the floor (green, exponent 40).
pub const BOUNCE_SPHERE: usize = 2;
/// How high the bouncing sphere rises above where it rests.
pub const BOUNCE_HEIGHT: f32 = 1.0;

/// What moves.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Motion {
    /// The key light orbits the vertical axis once.
    Orbit,
    /// A sphere bounces twice.
    Bounce,
}

/// The two animations, in the order of their expected figures.
pub const MOTIONS: [Motion; 2] = [Motion::Orbit, Motion::Bounce];

/// A sine and cosine for the motion.
pub trait Trig {
    /// The name in reports.
    const NAME: &'static str;
    /// The index of this trig's figures in `expected.rs`'s animation arrays.
    const INDEX: usize;
    /// `sin x`.
    fn sin(x: f32) -> f32;
    /// `cos x`.
    fn cos(x: f32) -> f32;
}

/// micromath's `sin` and `cos`: a parabolic approximation (error at most 0.002), `f32` only.
pub enum Micromath {}

impl Trig for Micromath {
    const NAME: &'static str = "micromath";
    const INDEX: usize = 0;
    fn sin(x: f32) -> f32 {
        micromath::F32Ext::sin(x)
    }
    fn cos(x: f32) -> f32 {
        micromath::F32Ext::cos(x)
    }
}

/// libm's `sinf` and `cosf`: correctly rounded in practice, through `f64` polynomials.
pub enum Libm {}

impl Trig for Libm {
    const NAME: &'static str = "libm";
    const INDEX: usize = 1;
    fn sin(x: f32) -> f32 {
        libm::sinf(x)
    }
    fn cos(x: f32) -> f32 {
        libm::cosf(x)
    }
}

/// The motion's parameters at `frame`: the orbit's `[cos θ, sin θ]`, the bounce's
/// `[height, 0]`, with `θ = 2π·frame/N`.
pub fn motion_at<T: Trig>(motion: Motion, frame: u32) -> [f32; 2] {
    let theta = core::f32::consts::TAU * frame as f32 / ANIMATION_FRAMES as f32;
    match motion {
        Motion::Orbit => [T::cos(theta), T::sin(theta)],
        Motion::Bounce => [BOUNCE_HEIGHT * T::sin(theta).abs(), 0.0],
    }
}

/// The scene of `frame` with the parameters `params` of [`motion_at`]: `shadeline::floor`
/// with the key light turned by `θ` about the vertical axis, or with the bouncing sphere
/// raised by the height.
pub fn animation_scene(
    motion: Motion,
    params: [f32; 2],
) -> Result<AnimationScene, shadeline::SceneError> {
    let floor = shadeline::floor()?;
    let mut scene = AnimationScene::new(*floor.camera(), floor.background())?;
    for (i, sphere) in floor.spheres().iter().enumerate() {
        let mut sphere = *sphere;
        if motion == Motion::Bounce && i == BOUNCE_SPHERE {
            sphere.center.y += params[0];
        }
        scene.add_sphere(sphere)?;
    }
    for (i, light) in floor.lights().iter().enumerate() {
        let mut light = *light;
        if let (Motion::Orbit, ORBIT_LIGHT, shadeline::Light::Distant { direction, .. }) =
            (motion, i, &mut light)
        {
            let [c, s] = params;
            let (x, z) = (direction.x, direction.z);
            direction.x = x * c + z * s;
            direction.z = z * c - x * s;
        }
        scene.add_light(light)?;
    }
    Ok(scene)
}
