//! Target images: per-pixel grey levels and the weights they stand for.

use glam::Mat4;

use super::camera::{Camera, CameraError};
use super::counts::TargetCounts;
use super::raster::row_words;
use crate::score::distance::squared_distances;

/// Most pixels one target image may have (4096 x 4096): counts of grey levels over a
/// whole image then fit in 32 bits on every backend.
pub const MAX_TARGET_PIXELS: u64 = 1 << 24;

/// Why a target image cannot be used.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum TargetError {
    /// The image has no pixels.
    #[error("target `{name}`: the image is {width} x {height}; it must have at least one pixel")]
    Empty {
        /// The target's name.
        name: String,
        /// Image width.
        width: u32,
        /// Image height.
        height: u32,
    },
    /// The image has more pixels than [`MAX_TARGET_PIXELS`].
    #[error(
        "target `{name}`: the image is {width} x {height}; at most {max} pixels are \
         supported (for example 4096 x 4096)"
    )]
    TooLarge {
        /// The target's name.
        name: String,
        /// Image width.
        width: u32,
        /// Image height.
        height: u32,
        /// [`MAX_TARGET_PIXELS`].
        max: u64,
    },
    /// A weight is infinite or NaN.
    #[error("target `{name}`: weight `{field}` is {value}; it must be a finite number")]
    Weight {
        /// The target's name.
        name: String,
        /// `on` or `off`.
        field: &'static str,
        /// Its value.
        value: f32,
    },
    /// The camera is unusable.
    #[error("target `{name}`")]
    Camera {
        /// The target's name.
        name: String,
        /// What is wrong with the camera.
        #[source]
        source: CameraError,
    },
    /// [Distance shaping](ImageTarget::shaped) asked of a target that cannot take it.
    #[error("target `{name}`: distance shaping {reason}")]
    Shaping {
        /// The target's name.
        name: String,
        /// What is wrong, and what would be valid.
        reason: String,
    },
}

/// How grey levels become weights.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TargetKind {
    /// Black and white: a target pixel (by its [`MaskRule`]) has weight `on`, any other
    /// `off`.
    Mask,
    /// Grey levels: weight `on + (off - on) * g / 255`.
    WeightMap,
}

/// Which pixels of a [mask](Weighting::mask_by) are its target pixels.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum MaskRule {
    /// Pixels whose red channel is 0: the original implementation's rule (its
    /// `compare_pixels` shader reads only the red channel). On a black-and-white image
    /// these are the black pixels; a grey, anti-aliased edge pixel is not a target
    /// pixel.
    #[default]
    RedZero,
    /// Pixels whose luminance is below this level: `DarkerThan(128)` takes a sketch's
    /// anti-aliased dark grey edges into the target.
    DarkerThan(u8),
    /// Pixels whose alpha is at least this level: a cut-out on a transparent
    /// background.
    OpaqueFrom(u8),
    /// Pixels whose colour lies more than `tolerance` from `background` (Euclidean
    /// distance of the 8-bit RGB values, 0 to 441): a photograph of an object before a
    /// plain backdrop.
    FarFrom {
        /// The backdrop's colour.
        background: [u8; 3],
        /// The largest distance from it of a backdrop pixel.
        tolerance: u16,
    },
}

impl MaskRule {
    /// Whether a pixel of this colour is a target pixel.
    fn is_target(self, pixel: image::Rgba<u8>) -> bool {
        use image::Pixel;
        match self {
            MaskRule::RedZero => pixel[0] == 0,
            MaskRule::DarkerThan(level) => pixel.to_luma()[0] < level,
            MaskRule::OpaqueFrom(level) => pixel[3] >= level,
            MaskRule::FarFrom {
                background,
                tolerance,
            } => {
                let d2: u32 = (0..3)
                    .map(|c| u32::from(pixel[c].abs_diff(background[c])).pow(2))
                    .sum();
                d2 > u32::from(tolerance).pow(2)
            }
        }
    }
}

/// One silhouette target: an image of per-pixel weights seen through a camera.
///
/// Every pixel has a grey level `g` in `0..=255` and a weight, as its [`Weighting`]
/// says: a [mask](Weighting::mask_by)'s target pixels (by its [`MaskRule`]) have level 0
/// and weight `on`, its other pixels level 255 and weight `off`; a
/// [weight map](Weighting::weight_map) keeps the image's luminance `g` as the level and
/// weighs `on + (off - on) * g / 255` (black is `on`, white `off`). Positive weights
/// attract, negative ones repel, 0 is indifferent; the *target pixels* are those of
/// positive weight. A mask keeps its levels as 0 or 255, so both kinds score with the
/// same formula.
///
/// ```
/// use glam::Vec3;
/// use image::{DynamicImage, GrayImage, Luma};
/// use shapegen_runtime::score::silhouette::{Camera, ImageTarget, MaskRule, OrbitCamera, Weighting};
///
/// let camera = Camera::Orbit(OrbitCamera {
///     phi: 0.0, theta: 0.0, radius: 5.0, lookat: Vec3::ZERO,
///     fov_degrees: 60.0, near: 0.1, far: 100.0,
/// });
/// let mut image = GrayImage::from_pixel(4, 2, Luma([255]));
/// image.put_pixel(1, 0, Luma([0]));
/// image.put_pixel(2, 1, Luma([100]));
/// let image = DynamicImage::ImageLuma8(image);
///
/// // The original's rule: only the black pixel is a target pixel.
/// let mask = ImageTarget::new("m".into(), &image, camera, Weighting::mask(1.0, -0.5))?;
/// assert_eq!(mask.target_pixels(), 1);
/// assert_eq!(mask.weight(1, 0), 1.0);
/// assert_eq!(mask.weight(2, 1), -0.5);
///
/// // A threshold takes the dark grey pixel too.
/// let dark = Weighting::mask_by(MaskRule::DarkerThan(128), 1.0, -0.5);
/// let sketch = ImageTarget::new("s".into(), &image, camera, dark)?;
/// assert_eq!(sketch.target_pixels(), 2);
/// assert_eq!(sketch.weight(2, 1), 1.0);
///
/// let map = ImageTarget::new("w".into(), &image, camera, Weighting::weight_map(1.0, 0.0))?;
/// assert_eq!(map.weight(1, 0), 1.0);
/// assert!((map.weight(2, 1) - (1.0 - 100.0 / 255.0)).abs() < 1e-12);
/// assert_eq!(map.target_pixels(), 2);
/// # Ok::<(), shapegen_runtime::score::silhouette::TargetError>(())
/// ```
#[derive(Clone, Debug)]
pub struct ImageTarget {
    name: String,
    kind: TargetKind,
    width: u32,
    height: u32,
    camera: Camera,
    view_projection: Mat4,
    on: f32,
    off: f32,
    levels: Vec<u8>,
    target_pixels: u64,
    /// The level of zero weight, when the target is [shaped](Self::shaped).
    zero_level: Option<u8>,
    /// Per 64-pixel word of a row-padded bitset: the target bits, then one word per
    /// grey-level bit plane ([`TargetKind::Mask`]: one plane, all levels 0 or 255).
    words: Vec<u64>,
}

/// How an image's pixels are read into grey levels.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Levels {
    /// 0 for the rule's target pixels, 255 for the others.
    Mask(MaskRule),
    /// The luminance.
    Luminance,
}

/// How a target's image becomes weights: which of its pixels are target pixels, or what
/// its grey levels stand for, and the weights `on` and `off` (see [`ImageTarget`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Weighting {
    levels: Levels,
    on: f32,
    off: f32,
}

impl Weighting {
    /// Black and white by the original's rule ([`MaskRule::RedZero`]): pixels whose red
    /// channel is 0 weigh `on`, the others `off`.
    pub const fn mask(on: f32, off: f32) -> Weighting {
        Weighting::mask_by(MaskRule::RedZero, on, off)
    }

    /// Black and white: the target pixels, chosen by `rule`, weigh `on` and the other
    /// pixels `off`.
    pub const fn mask_by(rule: MaskRule, on: f32, off: f32) -> Weighting {
        let levels = Levels::Mask(rule);
        Weighting { levels, on, off }
    }

    /// Grey levels: a pixel of grey level `g` weighs `on + (off - on) * g / 255`.
    pub const fn weight_map(on: f32, off: f32) -> Weighting {
        let levels = Levels::Luminance;
        Weighting { levels, on, off }
    }
}

impl ImageTarget {
    /// The target of `image`, seen through `camera`, its pixels weighed as `weighting`
    /// says.
    pub fn new(
        name: String,
        image: &image::DynamicImage,
        camera: Camera,
        weighting: Weighting,
    ) -> Result<ImageTarget, TargetError> {
        let Weighting { levels, on, off } = weighting;
        let (width, height) = (image.width(), image.height());
        if width == 0 || height == 0 {
            return Err(TargetError::Empty {
                name,
                width,
                height,
            });
        }
        if u64::from(width) * u64::from(height) > MAX_TARGET_PIXELS {
            return Err(TargetError::TooLarge {
                name,
                width,
                height,
                max: MAX_TARGET_PIXELS,
            });
        }
        for (field, value) in [("on", on), ("off", off)] {
            if !value.is_finite() {
                return Err(TargetError::Weight { name, field, value });
            }
        }
        if let Err(source) = camera.validate() {
            return Err(TargetError::Camera { name, source });
        }
        let (kind, levels): (_, Vec<u8>) = match levels {
            Levels::Mask(rule) => (
                TargetKind::Mask,
                image
                    .to_rgba8()
                    .pixels()
                    .map(|&p| if rule.is_target(p) { 0 } else { 255 })
                    .collect(),
            ),
            Levels::Luminance => (TargetKind::WeightMap, image.to_luma8().into_raw()),
        };
        let mut target = ImageTarget {
            name,
            kind,
            width,
            height,
            camera,
            view_projection: camera.view_projection(width, height),
            on,
            off,
            levels,
            target_pixels: 0,
            zero_level: None,
            words: Vec::new(),
        };
        target.build_words();
        Ok(target)
    }

    /// The mask shaped by distance: an opt-in slope for targets a generator cannot reach
    /// exactly. A target pixel keeps weight `on`; any other pixel, at Euclidean distance
    /// `d` pixels from the nearest target pixel, costs in proportion to its distance,
    /// from (nearly) nothing beside the target to the full `off` at `radius` pixels and
    /// beyond: its share of the full cost is `s = min(1, d / radius)`, quantized to the
    /// grey levels between the level of zero weight `z = ceil(255 on / (on - off))` and
    /// 255 (`level = z + ceil((255 - z) s)`), so that the weighted form reads it as a
    /// weight map. The target pixels stay those of the mask; the smoothstep form counts
    /// each covered off-target pixel as its share `s` instead of 1 (see
    /// [`off_target_cost`](Self::off_target_cost)).
    ///
    /// Fails unless the target is a mask with `on > 0 > off` (and `off` not so close to 0
    /// that no level is left between `z` and 255), and `radius` is a positive number.
    ///
    /// ```
    /// use glam::Vec3;
    /// use image::{DynamicImage, GrayImage, Luma};
    /// use shapegen_runtime::score::silhouette::{Camera, ImageTarget, OrbitCamera, Weighting};
    ///
    /// let camera = Camera::Orbit(OrbitCamera {
    ///     phi: 0.0, theta: 0.0, radius: 5.0, lookat: Vec3::ZERO,
    ///     fov_degrees: 60.0, near: 0.1, far: 100.0,
    /// });
    /// // One black pixel at the left end of a 12 x 1 row.
    /// let image = GrayImage::from_fn(12, 1, |x, _| Luma([if x == 0 { 0 } else { 255 }]));
    /// let image = DynamicImage::ImageLuma8(image);
    /// let mask = ImageTarget::new("m".into(), &image, camera, Weighting::mask(1.0, -1.0))?;
    /// let shaped = mask.shaped(10.0)?;
    /// assert_eq!(shaped.weight(0, 0), 1.0);
    /// assert!(shaped.weight(1, 0) <= 0.0 && shaped.weight(1, 0) > -0.15);
    /// assert!(shaped.weight(5, 0) < shaped.weight(1, 0));
    /// assert_eq!(shaped.weight(10, 0), -1.0);
    /// assert_eq!(shaped.weight(11, 0), -1.0);
    /// assert_eq!(shaped.target_pixels(), 1);
    /// # Ok::<(), shapegen_runtime::score::silhouette::TargetError>(())
    /// ```
    pub fn shaped(mut self, radius: f32) -> Result<ImageTarget, TargetError> {
        let refuse = |name: String, reason: String| Err(TargetError::Shaping { name, reason });
        if self.kind != TargetKind::Mask {
            return refuse(
                self.name,
                "needs a mask; a weight map has its own levels".into(),
            );
        }
        if !(radius.is_finite() && radius > 0.0) {
            return refuse(
                self.name,
                format!("radius is {radius}; it must be a positive number of pixels"),
            );
        }
        let (on, off) = (f64::from(self.on), f64::from(self.off));
        let zero = (255.0 * on / (on - off)).ceil();
        if !(on > 0.0 && off < 0.0 && zero < 255.0) {
            return refuse(
                self.name,
                format!(
                    "needs on > 0 > off with off not near 0 (it has on = {on}, off = {off}); \
                     for example on = 1, off = -1"
                ),
            );
        }
        let zero = zero as u8;
        let dims = [self.height as usize, self.width as usize];
        let distances = squared_distances(&dims, |i| self.levels[i] == 0);
        let span = f64::from(255 - zero);
        for (level, d2) in self.levels.iter_mut().zip(distances) {
            if d2 > 0.0 {
                let share = (d2.sqrt() / f64::from(radius)).min(1.0);
                *level = zero + ((span * share).ceil() as u8).max(1);
            }
        }
        self.kind = TargetKind::WeightMap;
        self.zero_level = Some(zero);
        self.build_words();
        Ok(self)
    }

    /// What the covered off-target pixels cost in the smoothstep form, from one model's
    /// counts: their number, or for a [shaped](Self::shaped) target the sum of their
    /// shares of the full cost.
    pub fn off_target_cost(&self, counts: &TargetCounts) -> f64 {
        match self.zero_level {
            None => f64::from(counts.off_target),
            Some(zero) => {
                let zero = u64::from(zero);
                let above = counts.level_sum - zero * u64::from(counts.off_target);
                above as f64 / (255 - zero) as f64
            }
        }
    }

    /// Whether the target is [shaped by distance](Self::shaped).
    pub fn is_shaped(&self) -> bool {
        self.zero_level.is_some()
    }

    /// Fills `words` and `target_pixels` from the levels.
    fn build_words(&mut self) {
        let stride = row_words(self.width);
        let planes = self.planes();
        let per = 1 + planes;
        self.words = vec![0; stride * self.height as usize * per];
        let mut count = 0;
        for y in 0..self.height {
            for x in 0..self.width {
                let g = self.level(x, y);
                let base = (y as usize * stride + x as usize / 64) * per;
                let bit = 1u64 << (x % 64);
                if self.weight_of(g) > 0.0 {
                    self.words[base] |= bit;
                    count += 1;
                }
                for p in 0..planes {
                    if g >> p & 1 == 1 {
                        self.words[base + 1 + p] |= bit;
                    }
                }
            }
        }
        self.target_pixels = count;
    }

    /// Number of grey-level bit planes kept per word.
    fn planes(&self) -> usize {
        match self.kind {
            TargetKind::Mask => 1,
            TargetKind::WeightMap => 8,
        }
    }

    /// The target's name.
    pub fn name(&self) -> &str {
        &self.name
    }

    /// Mask or weight map.
    pub fn kind(&self) -> TargetKind {
        self.kind
    }

    /// Image width in pixels.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Image height in pixels.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// The camera the target is seen through.
    pub fn camera(&self) -> &Camera {
        &self.camera
    }

    /// World space to clip space for this image's size.
    pub fn view_projection(&self) -> Mat4 {
        self.view_projection
    }

    /// Weight of black (a mask's target pixels).
    pub fn on(&self) -> f32 {
        self.on
    }

    /// Weight of white (a mask's other pixels).
    pub fn off(&self) -> f32 {
        self.off
    }

    /// Grey level of pixel `(x, y)` (row 0 at the top) as scored: a mask's levels are 0
    /// or 255.
    ///
    /// # Panics
    /// If the pixel is outside the image.
    pub fn level(&self, x: u32, y: u32) -> u8 {
        assert!(x < self.width && y < self.height, "pixel inside the image");
        self.levels[(y * self.width + x) as usize]
    }

    /// The grey levels as scored, row by row from the top.
    pub fn levels(&self) -> &[u8] {
        &self.levels
    }

    fn weight_of(&self, g: u8) -> f64 {
        let (on, off) = (f64::from(self.on), f64::from(self.off));
        on + (off - on) * f64::from(g) / 255.0
    }

    /// Weight of pixel `(x, y)` (row 0 at the top).
    ///
    /// # Panics
    /// If the pixel is outside the image.
    pub fn weight(&self, x: u32, y: u32) -> f64 {
        self.weight_of(self.level(x, y))
    }

    /// Whether pixel `(x, y)` is a target pixel (positive weight).
    ///
    /// # Panics
    /// If the pixel is outside the image.
    pub fn is_target(&self, x: u32, y: u32) -> bool {
        self.weight(x, y) > 0.0
    }

    /// Number of target pixels `T`.
    pub fn target_pixels(&self) -> u64 {
        self.target_pixels
    }

    /// The sum of weights over pixels of which `covered` are covered, with grey levels
    /// summing to `level_sum`: `on * covered + (off - on) * level_sum / 255`.
    pub fn weighted_sum(&self, covered: u64, level_sum: u64) -> f64 {
        let (on, off) = (f64::from(self.on), f64::from(self.off));
        on * covered as f64 + (off - on) * level_sum as f64 / 255.0
    }

    /// Counts the covered pixels of one coverage word `w` with bits `bits`: (target
    /// pixels, sum of grey levels).
    #[inline]
    pub(super) fn count_word(&self, w: usize, bits: u64) -> (u32, u64) {
        match self.kind {
            TargetKind::Mask => {
                let t = &self.words[w * 2..w * 2 + 2];
                let on = (bits & t[0]).count_ones();
                let bright = (bits & t[1]).count_ones();
                (on, 255 * u64::from(bright))
            }
            TargetKind::WeightMap => {
                let t = &self.words[w * 9..w * 9 + 9];
                let on = (bits & t[0]).count_ones();
                let mut sum = 0u64;
                for (p, plane) in t[1..].iter().enumerate() {
                    sum += u64::from((bits & plane).count_ones()) << p;
                }
                (on, sum)
            }
        }
    }
}
