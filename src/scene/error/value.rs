//! Values of a scene that the runtime refuses, and files they name that cannot be used.

use shapegen_runtime::MeshError;
use shapegen_runtime::geometry::PolygonError;
use shapegen_runtime::optimize::SettingsError;
use shapegen_runtime::score::objective::ObjectiveError;
use shapegen_runtime::score::silhouette::{CameraError, TargetError};
use shapegen_runtime::score::volume::GridError;

use super::image::ImageError;
use super::lot::LotError;

/// Why the value of a scene's key cannot be used: the runtime's error about it, the
/// target image it names, or serde's message about a value of the wrong type.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum ValueError {
    /// A mesh file, or the meshes the generator needs (`meshes`,
    /// `volume.target[0].mesh`).
    #[error(transparent)]
    Mesh(#[from] MeshError),
    /// The voxel grid (`volume.grid`).
    #[error(transparent)]
    Grid(#[from] GridError),
    /// A camera (`silhouette.target[0].camera`).
    #[error(transparent)]
    Camera(#[from] CameraError),
    /// A target image's file (`silhouette.target[0].image`, `objective[0].image`).
    #[error(transparent)]
    Image(#[from] ImageError),
    /// A silhouette target made of its image (`silhouette.target[0].image`).
    #[error(transparent)]
    Target(#[from] TargetError),
    /// A scorer made of its table, for the generator's meshes (`volume`, `silhouette`).
    #[error(transparent)]
    Scorer(Box<dyn std::error::Error + Send + Sync>),
    /// An objective, or the set of them (`objective`, `objective[0].image`).
    #[error(transparent)]
    Objective(#[from] ObjectiveError),
    /// A lot's outline that is not a simple polygon (`lot.points`, `lot.geojson`).
    #[error(transparent)]
    Polygon(#[from] PolygonError),
    /// A lot's GeoJSON file that does not hold one polygon (`lot.geojson`).
    #[error(transparent)]
    Lot(#[from] LotError),
    /// A setting of the `[selection]` table (`selection.weights`).
    #[error(transparent)]
    Settings(#[from] SettingsError),
    /// A value of the wrong type, or a name that is not one of the valid ones, in serde's
    /// words, which say what is valid (`objective[0].name`, `objective[0].kind`).
    #[error("{}", .0.message())]
    Toml(toml::de::Error),
    /// A key of an `[[objective]]` table that its kind does not take, or takes as
    /// another type (`objective[0]`).
    #[error("kind \"{kind}\": {}", error.message())]
    ObjectiveKey {
        /// The table's `kind`.
        kind: String,
        /// Serde's message, which names the key and what is valid.
        error: toml::de::Error,
    },
}
