//! [`ObjectiveError`]: why an objective could not be made.

use glam::Vec2;

/// Why an objective or a set of objectives cannot be built or used.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum ObjectiveError {
    /// A Chamfer objective's sample count is out of range.
    #[error("{samples} samples; a chamfer objective takes 1 to {max}")]
    Samples {
        /// Samples asked for.
        samples: usize,
        /// [`MAX_CHAMFER_SAMPLES`](super::MAX_CHAMFER_SAMPLES).
        max: usize,
    },
    /// A Chamfer objective's point cloud has no point.
    #[error("the point cloud has no points")]
    EmptyCloud,
    /// A projection target image has no pixel.
    #[error("the projection image is {width} x {height}; it must have at least one pixel")]
    EmptyImage {
        /// Image width.
        width: u32,
        /// Image height.
        height: u32,
    },
    /// A projection target image has too many pixels.
    #[error(
        "the projection image is {width} x {height}; at most {max} pixels are supported \
         (for example 4096 x 4096)"
    )]
    TooLarge {
        /// Image width.
        width: u32,
        /// Image height.
        height: u32,
        /// [`MAX_TARGET_PIXELS`](crate::score::silhouette::MAX_TARGET_PIXELS).
        max: u64,
    },
    /// A projection mask does not have one entry per pixel.
    #[error("the projection mask has {len} entries; a {width} x {height} image needs {}", *width as u64 * *height as u64)]
    MaskSize {
        /// Entries given.
        len: usize,
        /// Image width.
        width: u32,
        /// Image height.
        height: u32,
    },
    /// A projection area is not finite or has no extent.
    #[error(
        "the projection area runs from `area_min` {min} to `area_max` {max}; both must be \
         finite and `area_min` below `area_max` in each coordinate"
    )]
    Area {
        /// The corner given as smallest.
        min: Vec2,
        /// The corner given as largest.
        max: Vec2,
    },
    /// A footprint rectangle is not finite or inverted.
    #[error(
        "the footprint runs from `min` {min} to `max` {max} (x, z); both must be finite \
         and `min` at most `max` in each coordinate"
    )]
    Footprint {
        /// The corner given as smallest.
        min: Vec2,
        /// The corner given as largest.
        max: Vec2,
    },
    /// A number parameter is out of range.
    #[error("`{field}` is {value}; it must be {valid}")]
    Parameter {
        /// The parameter.
        field: &'static str,
        /// Its value.
        value: f32,
        /// What would be valid.
        valid: &'static str,
    },
    /// A name of a part is not the name of one of the grammar's meshes.
    #[error("no mesh is named `{name}`; the meshes are {meshes}")]
    UnknownPart {
        /// The name given.
        name: String,
        /// The meshes' names, quoted and listed.
        meshes: String,
    },
    /// A set of parts names no mesh.
    #[error("`{field}` names no mesh; name at least one")]
    NoParts {
        /// The parameter.
        field: &'static str,
    },
    /// An area share's `parts` has a mesh that its `of` lacks.
    #[error(
        "`parts` has a mesh that `of` lacks; the share is of the area of `of`, so list \
         every part there too"
    )]
    PartsOutsideOf,
    /// A set was given no objective.
    #[error("no objectives given; a set needs at least one")]
    NoObjectives,
    /// An objective of a set has an empty name.
    #[error("objective {index} has an empty name")]
    EmptyName {
        /// Its position in the set.
        index: usize,
    },
    /// Two objectives of a set have the same name.
    #[error("two objectives are named `{0}`; names must be unique")]
    DuplicateName(String),
    /// An objective of a set is invalid.
    #[error("objective `{name}`")]
    Entry {
        /// The objective's name.
        name: String,
        /// What is wrong with it.
        #[source]
        source: Box<ObjectiveError>,
    },
    /// Weights do not match the objectives.
    #[error("{given} weights given for {expected} objectives; give one per objective")]
    WeightCount {
        /// Weights given.
        given: usize,
        /// Objectives in the set.
        expected: usize,
    },
    /// A weight is infinite or NaN.
    #[error("the weight of objective `{name}` is {value}; it must be a finite number")]
    Weight {
        /// The objective's name.
        name: String,
        /// The weight.
        value: f64,
    },
    /// Values do not match the objectives.
    #[error("{given} values given for {expected} objectives; give one per objective")]
    ValueCount {
        /// Values given.
        given: usize,
        /// Objectives in the set.
        expected: usize,
    },
}

impl ObjectiveError {
    /// `Ok` when `value`, of the number parameter `field`, passes `ok`; otherwise the
    /// [`Parameter`](Self::Parameter) error that says it must be `valid`.
    pub(crate) fn check(
        field: &'static str,
        value: f32,
        ok: impl FnOnce(f32) -> bool,
        valid: &'static str,
    ) -> Result<(), ObjectiveError> {
        if ok(value) {
            return Ok(());
        }
        Err(ObjectiveError::Parameter {
            field,
            value,
            valid,
        })
    }
}
