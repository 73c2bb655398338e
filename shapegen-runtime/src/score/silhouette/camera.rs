//! Cameras: the original implementation's orbit camera, or explicit matrices.

use glam::{Mat4, Vec3, Vec4};

/// How a silhouette target is seen: world space to clip space.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Camera {
    /// The orbit camera of the original implementation.
    Orbit(OrbitCamera),
    /// A view and a projection matrix, used as given (OpenGL clip space: a point is in
    /// front of the near plane when `z >= -w`).
    Matrices {
        /// World space to view space.
        view: Mat4,
        /// View space to clip space.
        projection: Mat4,
    },
}

/// The original implementation's orbit camera: it looks at `lookat` from `radius` away,
/// `phi` around the vertical and `theta` above the horizon (radians).
///
/// With `w = -(cos theta cos phi, sin theta, cos theta sin phi)` (the viewing direction),
/// `v = (-sin theta cos phi, cos theta, -sin theta sin phi)` (up), `u = v x w` and
/// `eye = lookat - radius w`, the view matrix has rows `(u, -u.eye)`, `(v, -v.eye)`,
/// `(w, -w.eye)`, `(0, 0, 0, 1)`; the projection has rows `(s1, 0, 0, 0)`,
/// `(0, s2, 0, 0)`, `(0, 0, z1, z2)`, `(0, 0, 1, 0)` with `s2 = 1 / tan(fov / 2)`,
/// `s1 = s2 / aspect`, `z1 = (far + near) / (far - near)`,
/// `z2 = -2 far near / (far - near)`.
///
/// ```
/// use glam::{Vec3, Vec4};
/// use shapegen_runtime::score::silhouette::{Camera, OrbitCamera};
///
/// let camera = Camera::Orbit(OrbitCamera {
///     phi: 0.0, theta: 0.0, radius: 5.0, lookat: Vec3::ZERO,
///     fov_degrees: 90.0, near: 0.1, far: 100.0,
/// });
/// camera.validate()?;
/// // The camera sits at (5, 0, 0) looking at the origin, which lands mid-screen.
/// let clip = camera.view_projection(100, 100) * Vec4::new(0.0, 0.0, 0.0, 1.0);
/// assert!((clip.x / clip.w).abs() < 1e-6 && (clip.y / clip.w).abs() < 1e-6);
/// assert!((clip.w - 5.0).abs() < 1e-5);
/// # Ok::<(), shapegen_runtime::score::silhouette::CameraError>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OrbitCamera {
    /// Angle around the vertical axis, radians.
    pub phi: f32,
    /// Angle above the horizontal plane, radians.
    pub theta: f32,
    /// Distance from the eye to `lookat`.
    pub radius: f32,
    /// The point looked at.
    pub lookat: Vec3,
    /// Vertical field of view, degrees.
    pub fov_degrees: f32,
    /// Distance of the near clipping plane.
    pub near: f32,
    /// Distance of the far clipping plane.
    pub far: f32,
}

/// Why a camera cannot be used.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum CameraError {
    /// A number that must be finite is not.
    #[error("camera `{field}` is {value}; it must be a finite number")]
    NotFinite {
        /// The field.
        field: &'static str,
        /// Its value.
        value: f32,
    },
    /// The orbit radius is not positive.
    #[error("camera `radius` is {0}; it must be greater than 0")]
    Radius(f32),
    /// The field of view is outside `(0, 180)` degrees.
    #[error("camera `fov` is {0} degrees; it must lie strictly between 0 and 180")]
    Fov(f32),
    /// The clipping planes are not `0 < near < far`.
    #[error("camera `near` is {near} and `far` is {far}; they must satisfy 0 < near < far")]
    Planes {
        /// The near distance.
        near: f32,
        /// The far distance.
        far: f32,
    },
    /// A matrix camera's matrices do not map to a usable clip space.
    #[error("camera `{field}` matrix has a non-finite entry")]
    Matrix {
        /// `view` or `projection`.
        field: &'static str,
    },
}

impl OrbitCamera {
    /// The camera's frame: right-handed rows `u`, `v`, `w` and the eye position.
    fn frame(&self) -> (Vec3, Vec3, Vec3, Vec3) {
        let (st, ct) = self.theta.sin_cos();
        let (sp, cp) = self.phi.sin_cos();
        let w = -Vec3::new(ct * cp, st, ct * sp);
        let v = Vec3::new(-st * cp, ct, -st * sp);
        let u = v.cross(w);
        let eye = self.lookat - self.radius * w;
        (u, v, w, eye)
    }

    /// The eye position.
    pub fn eye(&self) -> Vec3 {
        self.frame().3
    }

    /// World space to view space.
    pub fn view(&self) -> Mat4 {
        let (u, v, w, eye) = self.frame();
        Mat4::from_cols(
            Vec4::new(u.x, v.x, w.x, 0.0),
            Vec4::new(u.y, v.y, w.y, 0.0),
            Vec4::new(u.z, v.z, w.z, 0.0),
            Vec4::new(-u.dot(eye), -v.dot(eye), -w.dot(eye), 1.0),
        )
    }

    /// View space to clip space for an image `aspect = width / height`.
    pub fn projection(&self, aspect: f32) -> Mat4 {
        let s2 = 1.0 / (self.fov_degrees.to_radians() / 2.0).tan();
        let s1 = s2 / aspect;
        let (n, f) = (self.near, self.far);
        let z1 = (f + n) / (f - n);
        let z2 = -2.0 * f * n / (f - n);
        Mat4::from_cols(
            Vec4::new(s1, 0.0, 0.0, 0.0),
            Vec4::new(0.0, s2, 0.0, 0.0),
            Vec4::new(0.0, 0.0, z1, 1.0),
            Vec4::new(0.0, 0.0, z2, 0.0),
        )
    }

    fn validate(&self) -> Result<(), CameraError> {
        let fields = [
            ("phi", self.phi),
            ("theta", self.theta),
            ("radius", self.radius),
            ("lookat.x", self.lookat.x),
            ("lookat.y", self.lookat.y),
            ("lookat.z", self.lookat.z),
            ("fov", self.fov_degrees),
            ("near", self.near),
            ("far", self.far),
        ];
        for (field, value) in fields {
            if !value.is_finite() {
                return Err(CameraError::NotFinite { field, value });
            }
        }
        if self.radius <= 0.0 {
            return Err(CameraError::Radius(self.radius));
        }
        if !(self.fov_degrees > 0.0 && self.fov_degrees < 180.0) {
            return Err(CameraError::Fov(self.fov_degrees));
        }
        if !(self.near > 0.0 && self.near < self.far) {
            return Err(CameraError::Planes {
                near: self.near,
                far: self.far,
            });
        }
        Ok(())
    }
}

impl Camera {
    /// Checks that the camera gives a usable projection.
    pub fn validate(&self) -> Result<(), CameraError> {
        match self {
            Camera::Orbit(orbit) => orbit.validate(),
            Camera::Matrices { view, projection } => {
                for (field, m) in [("view", view), ("projection", projection)] {
                    if !m.is_finite() {
                        return Err(CameraError::Matrix { field });
                    }
                }
                Ok(())
            }
        }
    }

    /// World space to clip space for an image of `width` x `height` pixels (the orbit
    /// camera's aspect is `width / height`; matrices are used as given).
    pub fn view_projection(&self, width: u32, height: u32) -> Mat4 {
        match self {
            Camera::Orbit(orbit) => {
                orbit.projection(width as f32 / height.max(1) as f32) * orbit.view()
            }
            Camera::Matrices { view, projection } => *projection * *view,
        }
    }
}
