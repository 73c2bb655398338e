//! The published cameras and the form the silhouette tests score with, shared by the
//! silhouette tests on the CPU and on the GPU.

use glam::vec3;
use shapegen_runtime::score::Form;
use shapegen_runtime::score::silhouette::{Camera, OrbitCamera};

pub const SMOOTH: Form = Form::Smooth {
    good: 1.0,
    bad: 1.0,
};

/// The camera of the published city scenes.
pub fn city_camera() -> Camera {
    Camera::Orbit(OrbitCamera {
        phi: -3.05161,
        theta: 0.0479887,
        radius: 12.4346,
        lookat: vec3(1.82669, 4.65407, -0.620025),
        fov_degrees: 60.0,
        near: 0.1,
        far: 100.0,
    })
}

/// The camera of the published tree scenes.
pub fn tree_camera() -> Camera {
    Camera::Orbit(OrbitCamera {
        // The published value, -1.5708 (about -pi/2).
        #[allow(clippy::approx_constant)]
        phi: -1.5708,
        theta: 0.0,
        radius: 9.4716,
        lookat: vec3(-0.680994, 3.2558, 0.0),
        fov_degrees: 60.0,
        near: 0.1,
        far: 100.0,
    })
}
