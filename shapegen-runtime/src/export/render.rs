//! Shaded previews: a small software rasterizer that draws a model's instances through a
//! camera into an RGB image, for people to look at (the scorers count coverage
//! themselves).

use glam::{Mat4, Vec3, Vec4, Vec4Swizzles};
use image::{Rgb, RgbImage};

use super::error::ExportError;
use super::model::Model;
use crate::geometry::{BoundMeshes, Instance};

/// How a preview is drawn: the camera's view-projection matrix and the image size.
///
/// Clip space follows the scorers' convention: a point is in front of the camera when
/// its clip `w` is positive, and clip `(x, y) / w` in `[-1, 1]` maps to pixels as
/// `((x + 1) / 2 * width, (1 - y) / 2 * height)`, row 0 at the top. Nearer points have
/// the smaller `z / w`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Preview {
    /// World space to clip space.
    pub view_projection: Mat4,
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
}

/// Background of previews (sRGB).
const BACKGROUND: [u8; 3] = [240, 240, 236];
/// Direction towards the light, world space (normalized when used).
const LIGHT: Vec3 = Vec3::new(0.45, 0.8, 0.35);
/// Samples per pixel along each axis.
const SUPERSAMPLE: u32 = 2;
/// Clip `w` below which geometry counts as behind the camera.
const NEAR_W: f32 = 1e-4;

impl Preview {
    /// A camera that frames the whole model (all instances' bounds) from the front-right
    /// and above, with a 40 degree vertical field of view. An empty model is framed as
    /// the unit cube.
    ///
    /// ```
    /// use shapegen_runtime::export::{Model, Preview};
    /// use shapegen_runtime::{CUBE, Instance, MeshLibrary};
    /// use glam::Affine3A;
    ///
    /// let meshes = MeshLibrary::new().bind_names("Demo", &["cube"]).unwrap();
    /// let cube = [Instance { transform: Affine3A::IDENTITY, mesh: CUBE }];
    /// let preview = Preview::framing(&cube, &meshes, 64, 48);
    /// let image = preview.render(Model::new(&cube, &meshes, &Default::default())).unwrap();
    /// assert_eq!(image.dimensions(), (64, 48));
    /// // The cube is in the middle of the picture, on the background.
    /// assert_ne!(image.get_pixel(32, 24), image.get_pixel(0, 0));
    /// ```
    pub fn framing(
        instances: &[Instance],
        meshes: &BoundMeshes,
        width: u32,
        height: u32,
    ) -> Preview {
        let (mut lo, mut hi) = (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY));
        for instance in instances {
            let Some(mesh) = meshes.get(instance.mesh) else {
                continue;
            };
            for &p in &mesh.positions {
                let p = instance.transform.transform_point3(p);
                if p.is_finite() {
                    lo = lo.min(p);
                    hi = hi.max(p);
                }
            }
        }
        if !(lo.cmple(hi).all()) {
            (lo, hi) = (Vec3::splat(-0.5), Vec3::splat(0.5));
        }
        let centre = (lo + hi) / 2.0;
        let radius = ((hi - lo).length() / 2.0).max(1e-3);
        let fov = 40f32.to_radians();
        let aspect = width.max(1) as f32 / height.max(1) as f32;
        // Far enough that the bounding sphere fits the narrower field of view.
        let half = (fov / 2.0).tan().min((fov / 2.0).tan() * aspect);
        let distance = radius / half.atan().sin();
        let eye = centre + Vec3::new(1.0, 0.7, 1.3).normalize() * distance;
        Preview {
            view_projection: look_at(eye, centre, fov, aspect),
            width,
            height,
        }
    }

    /// Draws the model's instances shaded by their meshes' colours in its palette, with
    /// a depth buffer, two-sided Lambert lighting from a fixed direction and 2 x 2
    /// supersampling.
    ///
    /// # Errors
    /// [`ExportError::UnknownMesh`] when an instance names a mesh the model's meshes lack.
    pub fn render(&self, model: Model<'_>) -> Result<RgbImage, ExportError> {
        let Model {
            instances,
            meshes,
            palette,
        } = model;
        let (w, h) = (self.width * SUPERSAMPLE, self.height * SUPERSAMPLE);
        let mut target = Target {
            width: w as usize,
            height: h as usize,
            depth: vec![f32::INFINITY; w as usize * h as usize],
            color: vec![srgb_to_linear(BACKGROUND); w as usize * h as usize],
        };
        let light = LIGHT.normalize();
        for (index, instance) in instances.iter().enumerate() {
            let mesh = meshes.get(instance.mesh).ok_or(ExportError::UnknownMesh {
                instance: index,
                mesh: instance.mesh.0,
                bound: meshes.len(),
            })?;
            let name = meshes.name(instance.mesh).unwrap_or_default();
            let base = Vec3::from(palette.color(instance.mesh, name));
            for [a, b, c] in mesh.triangles() {
                let world = [a, b, c].map(|i| {
                    instance
                        .transform
                        .transform_point3(mesh.positions[i as usize])
                });
                let normal = (world[1] - world[0])
                    .cross(world[2] - world[0])
                    .normalize_or_zero();
                let shade = 0.35 + 0.65 * normal.dot(light).abs();
                let clip = world.map(|p| self.view_projection * p.extend(1.0));
                target.triangle(clip, base * shade);
            }
        }
        Ok(target.resolve(self.width, self.height))
    }
}

/// The supersampled colour and depth buffers.
struct Target {
    width: usize,
    height: usize,
    depth: Vec<f32>,
    color: Vec<Vec3>,
}

impl Target {
    /// Clips a triangle against `w > NEAR_W` and fills what is left.
    fn triangle(&mut self, clip: [Vec4; 3], color: Vec3) {
        let mut polygon = [Vec4::ZERO; 4];
        let mut count = 0;
        for i in 0..3 {
            let (p, q) = (clip[i], clip[(i + 1) % 3]);
            if p.w >= NEAR_W {
                polygon[count] = p;
                count += 1;
            }
            if (p.w >= NEAR_W) != (q.w >= NEAR_W) {
                let t = (NEAR_W - p.w) / (q.w - p.w);
                polygon[count] = p + (q - p) * t;
                count += 1;
            }
        }
        for i in 1..count.saturating_sub(1) {
            self.fill([polygon[0], polygon[i], polygon[i + 1]], color);
        }
    }

    /// Fills a triangle whose vertices are all in front of the camera.
    fn fill(&mut self, clip: [Vec4; 3], color: Vec3) {
        let (w, h) = (self.width as f32, self.height as f32);
        let screen = clip.map(|c| {
            let ndc = c.xyz() / c.w;
            Vec3::new((ndc.x + 1.0) / 2.0 * w, (1.0 - ndc.y) / 2.0 * h, ndc.z)
        });
        let [a, b, c] = screen;
        let area = edge(a, b, c);
        if area == 0.0 || !area.is_finite() {
            return;
        }
        let lo = a.min(b).min(c);
        let hi = a.max(b).max(c);
        let x0 = lo.x.floor().max(0.0) as usize;
        let y0 = lo.y.floor().max(0.0) as usize;
        let x1 = (hi.x.ceil().min(w) as usize).min(self.width);
        let y1 = (hi.y.ceil().min(h) as usize).min(self.height);
        for y in y0..y1 {
            for x in x0..x1 {
                let p = Vec3::new(x as f32 + 0.5, y as f32 + 0.5, 0.0);
                let (wa, wb, wc) = (
                    edge(b, c, p) / area,
                    edge(c, a, p) / area,
                    edge(a, b, p) / area,
                );
                if wa < 0.0 || wb < 0.0 || wc < 0.0 {
                    continue;
                }
                let z = wa * a.z + wb * b.z + wc * c.z;
                let at = y * self.width + x;
                if z < self.depth[at] {
                    self.depth[at] = z;
                    self.color[at] = color;
                }
            }
        }
    }

    /// Averages the samples of each pixel into an sRGB image.
    fn resolve(&self, width: u32, height: u32) -> RgbImage {
        let s = SUPERSAMPLE as usize;
        RgbImage::from_fn(width, height, |x, y| {
            let mut sum = Vec3::ZERO;
            for dy in 0..s {
                for dx in 0..s {
                    sum += self.color[(y as usize * s + dy) * self.width + x as usize * s + dx];
                }
            }
            Rgb(linear_to_srgb(sum / (s * s) as f32))
        })
    }
}

/// A perspective camera at `eye` looking at `target` with +y up, `fov` the vertical field
/// of view in radians: clip `w` is the distance along the view direction, and clip `z / w`
/// grows with it.
fn look_at(eye: Vec3, target: Vec3, fov: f32, aspect: f32) -> Mat4 {
    let forward = (target - eye).normalize();
    let right = forward.cross(Vec3::Y).normalize();
    let up = right.cross(forward);
    let view = Mat4::from_cols(
        right.extend(-right.dot(eye)),
        up.extend(-up.dot(eye)),
        forward.extend(-forward.dot(eye)),
        Vec4::W,
    )
    .transpose();
    let s2 = 1.0 / (fov / 2.0).tan();
    let projection = Mat4::from_cols(
        Vec4::new(s2 / aspect, 0.0, 0.0, 0.0),
        Vec4::new(0.0, s2, 0.0, 0.0),
        Vec4::new(0.0, 0.0, 1.0, 1.0),
        Vec4::new(0.0, 0.0, -1.0, 0.0),
    );
    projection * view
}

/// Twice the signed area of the triangle `(a, b, p)` in the screen plane.
fn edge(a: Vec3, b: Vec3, p: Vec3) -> f32 {
    (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x)
}

fn srgb_to_linear(rgb: [u8; 3]) -> Vec3 {
    Vec3::from(rgb.map(|c| {
        let c = f32::from(c) / 255.0;
        if c <= 0.04045 {
            c / 12.92
        } else {
            ((c + 0.055) / 1.055).powf(2.4)
        }
    }))
}

fn linear_to_srgb(rgb: Vec3) -> [u8; 3] {
    rgb.to_array().map(|c| {
        let c = c.clamp(0.0, 1.0);
        let s = if c <= 0.003_130_8 {
            c * 12.92
        } else {
            1.055 * c.powf(1.0 / 2.4) - 0.055
        };
        (s * 255.0).round() as u8
    })
}

#[cfg(test)]
mod tests {
    use glam::{Affine3A, Vec3};

    use super::*;
    use crate::export::palette::Palette;
    use crate::geometry::{CUBE, MeshLibrary};

    fn meshes() -> BoundMeshes {
        MeshLibrary::new().bind_names("Test", &["cube"]).unwrap()
    }

    fn cube_at(x: f32) -> Instance {
        Instance {
            transform: Affine3A::from_translation(Vec3::new(x, 0.0, 0.0)),
            mesh: CUBE,
        }
    }

    fn covered(image: &RgbImage) -> usize {
        image.pixels().filter(|p| p.0 != BACKGROUND).count()
    }

    #[test]
    fn an_orthographic_cube_fills_its_square() {
        // Orthographic view along z, the cube spans half of a 40 x 40 image each way.
        let preview = Preview {
            view_projection: Mat4::from_scale(Vec3::new(1.0, 1.0, 0.1)),
            width: 40,
            height: 40,
        };
        let image = preview
            .render(Model::new(&[cube_at(0.0)], &meshes(), &Palette::new()))
            .unwrap();
        assert_eq!(covered(&image), 20 * 20);
        assert_ne!(image.get_pixel(20, 20).0, BACKGROUND);
        assert_eq!(image.get_pixel(9, 20).0, BACKGROUND);
        assert_ne!(image.get_pixel(10, 20).0, BACKGROUND);
    }

    #[test]
    fn framing_keeps_the_whole_model_in_view() {
        let model = [cube_at(-3.0), cube_at(3.0)];
        let preview = Preview::framing(&model, &meshes(), 80, 60);
        let image = preview
            .render(Model::new(&model, &meshes(), &Palette::new()))
            .unwrap();
        // Both cubes are drawn, and nothing touches the border.
        assert!(covered(&image) > 100);
        for x in 0..80 {
            assert_eq!(image.get_pixel(x, 0).0, BACKGROUND);
            assert_eq!(image.get_pixel(x, 59).0, BACKGROUND);
        }
        for y in 0..60 {
            assert_eq!(image.get_pixel(0, y).0, BACKGROUND);
            assert_eq!(image.get_pixel(79, y).0, BACKGROUND);
        }
        let left = (0..40).flat_map(|x| (0..60).map(move |y| (x, y)));
        assert!(
            left.clone()
                .any(|(x, y)| image.get_pixel(x, y).0 != BACKGROUND)
        );
        assert!(
            left.map(|(x, y)| (x + 40, y))
                .any(|(x, y)| image.get_pixel(x, y).0 != BACKGROUND)
        );
    }

    #[test]
    fn geometry_behind_the_camera_is_clipped() {
        let preview = Preview {
            view_projection: look_at(Vec3::ZERO, Vec3::NEG_Z, 1.0, 1.0),
            width: 20,
            height: 20,
        };
        // A cube behind the eye draws nothing; one straddling the eye is clipped, not
        // smeared, and draws without panicking.
        let behind = Instance {
            transform: Affine3A::from_translation(Vec3::new(0.0, 0.0, 5.0)),
            mesh: CUBE,
        };
        let image = preview
            .render(Model::new(&[behind], &meshes(), &Palette::new()))
            .unwrap();
        assert_eq!(covered(&image), 0);
        let around = Instance {
            transform: Affine3A::from_scale(Vec3::splat(4.0)),
            mesh: CUBE,
        };
        preview
            .render(Model::new(&[around], &meshes(), &Palette::new()))
            .unwrap();
    }

    #[test]
    fn an_unknown_mesh_is_an_error() {
        let bad = Instance {
            transform: Affine3A::IDENTITY,
            mesh: crate::geometry::MeshId(7),
        };
        let preview = Preview::framing(&[], &meshes(), 8, 8);
        let err = preview
            .render(Model::new(&[bad], &meshes(), &Palette::new()))
            .unwrap_err();
        assert!(matches!(
            err,
            ExportError::UnknownMesh {
                instance: 0,
                mesh: 7,
                ..
            }
        ));
    }
}
