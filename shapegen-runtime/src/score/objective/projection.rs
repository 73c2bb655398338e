//! Orthographic projections of a model compared with black-and-white target images.

use glam::{Vec2, Vec3};
use image::{GrayImage, Luma};

use super::error::ObjectiveError;
use super::surface::Surface;
use crate::score::silhouette::MAX_TARGET_PIXELS;
use crate::score::silhouette::raster::{Coverage, row_words};

/// The direction an orthographic [`ProjectionMatch`] looks in, and how its image lies
/// in the world.
///
/// Each view maps a world point to a point `(u, v)` of its view plane, and the image
/// covers the rectangle `[area_min, area_max]` of that plane, pixel `(0, 0)` at the top
/// left of the picture.
///
/// ```
/// use glam::{Vec2, Vec3};
/// use shapegen_runtime::score::objective::View;
///
/// let p = Vec3::new(1.0, 2.0, 3.0);
/// assert_eq!((View::Top.plane(p), View::Top.depth(p)), (Vec2::new(1.0, 3.0), 2.0));
/// assert_eq!((View::Front.plane(p), View::Front.depth(p)), (Vec2::new(1.0, 2.0), 3.0));
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum View {
    /// Looking down `-y`, as on a map seen from above: `(u, v) = (x, z)`. The image's
    /// `x` is world `x` (`area_min.x` at the left edge), and its rows run along world
    /// `z`, row 0 at `z = area_min.y` (the far edge seen from the [front](View::Front))
    /// and the bottom row at `z = area_max.y`.
    Top,
    /// Looking along `-z` (from the `+z` side): `(u, v) = (x, y)`. The image's `x` is
    /// world `x` (`area_min.x` at the left edge) and its up is world `y`, row 0 at
    /// `y = area_max.y` and the bottom row at `y = area_min.y`.
    Front,
}

impl View {
    /// The component of `v` along the viewing axis (`y` seen from the top, `z` from the
    /// front).
    #[inline]
    pub fn depth(self, v: Vec3) -> f32 {
        match self {
            View::Top => v.y,
            View::Front => v.z,
        }
    }

    /// A world point's coordinates in the view plane.
    #[inline]
    pub fn plane(self, p: Vec3) -> Vec2 {
        match self {
            View::Top => Vec2::new(p.x, p.z),
            View::Front => Vec2::new(p.x, p.y),
        }
    }
}

/// How well a model's orthographic projection matches a black-and-white target image:
/// the fraction of pixels whose coverage agrees with the target (1 = every pixel
/// matches, 0 = none does).
///
/// A pixel is covered when its centre lies inside the projection of any triangle of the
/// [`Surface`], with the silhouette scorer's rule for centres on an edge (the top-left
/// rule) and the same rasterizer. The target mask is `true` (black) where the model
/// should cover. With `W x H` pixels, the score is
/// `#{pixels where covered == mask} / (W * H)`.
///
/// ```
/// use glam::{Affine3A, Vec2, Vec3};
/// use shapegen_runtime::score::objective::{ProjectionMatch, Surface, View};
/// use shapegen_runtime::{CUBE, Instance, MeshLibrary};
///
/// // A 4 x 4 image of the square [-1, 1]^2 seen from above; the target is the centre
/// // 2 x 2 pixels, which is exactly what a unit cube at the origin covers.
/// let mask: Vec<bool> = (0..16).map(|i| (1..3).contains(&(i % 4)) && (1..3).contains(&(i / 4))).collect();
/// let top = ProjectionMatch::new(View::Top, Vec2::splat(-1.0), Vec2::splat(1.0), 4, 4, &mask)?;
/// let meshes = MeshLibrary::new().bind_names("Boxes", &["cube"])?;
/// let cube = Surface::from_instances(&[Instance { transform: Affine3A::IDENTITY, mesh: CUBE }], &meshes);
/// assert_eq!(top.score(&cube), 1.0);
/// let moved = Surface::from_instances(
///     &[Instance { transform: Affine3A::from_translation(Vec3::X * 0.5), mesh: CUBE }],
///     &meshes,
/// );
/// assert_eq!(top.score(&moved), 12.0 / 16.0);
/// assert_eq!(top.render(&cube).get_pixel(1, 1).0, [0]);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct ProjectionMatch {
    view: View,
    area_min: Vec2,
    area_max: Vec2,
    width: u32,
    height: u32,
    /// The mask as one bit per pixel, rows padded to whole words as [`Coverage`] lays
    /// them out.
    words: Vec<u64>,
    mask_pixels: u64,
}

impl ProjectionMatch {
    /// A match of the `view` projection of the area `[area_min, area_max]` of its view
    /// plane against `mask`, a `width x height` image given row by row from the top
    /// (`true` = black = the model should cover).
    ///
    /// Fails when the image has no pixel or more than
    /// [`MAX_TARGET_PIXELS`], when `mask` does not have `width * height` entries, or when
    /// the area is not finite or has no extent in a coordinate.
    pub fn new(
        view: View,
        area_min: Vec2,
        area_max: Vec2,
        width: u32,
        height: u32,
        mask: &[bool],
    ) -> Result<ProjectionMatch, ObjectiveError> {
        if width == 0 || height == 0 {
            return Err(ObjectiveError::EmptyImage { width, height });
        }
        let pixels = u64::from(width) * u64::from(height);
        if pixels > MAX_TARGET_PIXELS {
            return Err(ObjectiveError::TooLarge {
                width,
                height,
                max: MAX_TARGET_PIXELS,
            });
        }
        if mask.len() as u64 != pixels {
            return Err(ObjectiveError::MaskSize {
                len: mask.len(),
                width,
                height,
            });
        }
        if !(area_min.is_finite() && area_max.is_finite() && area_min.cmplt(area_max).all()) {
            return Err(ObjectiveError::Area {
                min: area_min,
                max: area_max,
            });
        }
        let stride = row_words(width);
        let mut words = vec![0u64; stride * height as usize];
        let mut mask_pixels = 0;
        for (i, _) in mask.iter().enumerate().filter(|&(_, &m)| m) {
            let (x, y) = (i % width as usize, i / width as usize);
            words[y * stride + x / 64] |= 1 << (x % 64);
            mask_pixels += 1;
        }
        Ok(ProjectionMatch {
            view,
            area_min,
            area_max,
            width,
            height,
            words,
            mask_pixels,
        })
    }

    /// A match against a grey image: pixels darker than 128 are the mask (black = the
    /// model should cover), as for the silhouette scorer's masks. See [`new`](Self::new)
    /// for the rest.
    pub fn from_image(
        view: View,
        area_min: Vec2,
        area_max: Vec2,
        image: &GrayImage,
    ) -> Result<ProjectionMatch, ObjectiveError> {
        let mask: Vec<bool> = image.as_raw().iter().map(|&g| g < 128).collect();
        Self::new(
            view,
            area_min,
            area_max,
            image.width(),
            image.height(),
            &mask,
        )
    }

    /// The view.
    pub fn view(&self) -> View {
        self.view
    }

    /// The corners of the area of the view plane that the image covers.
    pub fn area(&self) -> (Vec2, Vec2) {
        (self.area_min, self.area_max)
    }

    /// Image width in pixels.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Image height in pixels.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// Number of mask (black) pixels.
    pub fn mask_pixels(&self) -> u64 {
        self.mask_pixels
    }

    /// Whether pixel `(x, y)` (row 0 at the top) is in the mask; `false` outside the
    /// image.
    pub fn mask(&self, x: u32, y: u32) -> bool {
        if x >= self.width || y >= self.height {
            return false;
        }
        let word = self.words[y as usize * row_words(self.width) + x as usize / 64];
        word >> (x % 64) & 1 == 1
    }

    /// The score of `surface`: the fraction of pixels whose coverage equals the mask.
    pub fn score(&self, surface: &Surface) -> f64 {
        self.score_with(surface, &mut Coverage::default())
    }

    /// [`score`](Self::score) with a reusable coverage buffer.
    pub(super) fn score_with(&self, surface: &Surface, coverage: &mut Coverage) -> f64 {
        self.value(self.mismatched(surface, coverage))
    }

    /// The number of pixels whose coverage by `surface` differs from the mask, with a
    /// reusable coverage buffer.
    pub(super) fn mismatched(&self, surface: &Surface, coverage: &mut Coverage) -> u64 {
        coverage.shape(self.width, self.height);
        self.rasterize(surface, coverage);
        // Untouched words are uncovered: they mismatch exactly where the mask is set.
        let mut mismatched = self.mask_pixels;
        coverage.drain(|w, bits| mismatched = self.remismatched(mismatched, w, 0, bits));
        mismatched
    }

    /// `mismatched` once the covered pixels of coverage word `w` change from `before` to
    /// `after` (both bits of pixels of that word).
    #[inline]
    pub(super) fn remismatched(&self, mismatched: u64, w: usize, before: u64, after: u64) -> u64 {
        let mask = self.words[w];
        let wrong = |bits: u64| u64::from((bits ^ mask).count_ones());
        mismatched + wrong(after) - wrong(before)
    }

    /// The score of a model whose coverage differs from the mask at `mismatched`
    /// pixels.
    pub(super) fn value(&self, mismatched: u64) -> f64 {
        let total = u64::from(self.width) * u64::from(self.height);
        (total - mismatched) as f64 / total as f64
    }

    /// The projection of `surface` as an image of this match's size: black (0) where
    /// covered, white (255) elsewhere. A target drawn this way from a model scores 1
    /// against that model.
    pub fn render(&self, surface: &Surface) -> GrayImage {
        let mut coverage = Coverage::default();
        coverage.shape(self.width, self.height);
        self.rasterize(surface, &mut coverage);
        let image = GrayImage::from_fn(self.width, self.height, |x, y| {
            Luma([if coverage.get(x, y) { 0 } else { 255 }])
        });
        coverage.drain(|_, _| {});
        image
    }

    /// Fills every triangle's projection into `coverage` (already shaped).
    pub(super) fn rasterize(&self, surface: &Surface, coverage: &mut Coverage) {
        let scale =
            Vec2::new(self.width as f32, self.height as f32) / (self.area_max - self.area_min);
        let (min, max) = (self.area_min, self.area_max);
        let to_pixels = |p: Vec3| {
            let q = self.view.plane(p);
            match self.view {
                View::Top => (q - min) * scale,
                View::Front => Vec2::new(q.x - min.x, max.y - q.y) * scale,
            }
        };
        for (tri, n) in surface.triangles().iter().zip(surface.normals()) {
            // A triangle whose plane holds the viewing direction projects to a segment.
            if self.view.depth(*n) == 0.0 {
                continue;
            }
            coverage.fill_convex(&tri.map(to_pixels));
        }
    }
}
