//! [`ObjectiveKind`]: what one kind of objective declares (how it is read, checked and
//! measured), and [`ObjectiveSource`]: where its `[[objective]]` table is read.

use std::fmt::Debug;

use image::GrayImage;
use serde::de::DeserializeOwned;

use super::error::ObjectiveError;
use super::parts::Parts;
use super::projection::ProjectionMatch;
use super::scratch::ObjectiveScratch;
use super::surface::Surface;
use crate::evaluate::Sense;
use crate::geometry::PointCloud;

/// One kind of geometric objective: a raw value measured on a model's [`Surface`], better
/// in the direction [`SENSE`](Self::SENSE), read from an `[[objective]]` table of a scene
/// file as its [`File`](FromTable::File).
///
/// Each kind is one type in a file of its own, named by one row of the table of kinds
/// (`objective_kinds!`), which derives the [`Objective`](super::Objective) enum, its name
/// in scene files, the serde form of its table ([`ObjectiveFile`](super::ObjectiveFile))
/// and the dispatch to the kind's methods.
///
/// ```
/// use shapegen_runtime::evaluate::Sense;
/// use shapegen_runtime::score::objective::{Height, ObjectiveKind, ObjectiveScratch, Surface};
///
/// assert_eq!(Height::SENSE, Sense::Minimize);
/// let empty = Surface::new();
/// assert_eq!(Height { target: 3.0 }.measure(&empty, &mut ObjectiveScratch::default()), 3.0);
/// assert!(Height { target: f32::NAN }.validate().is_err());
/// ```
pub trait ObjectiveKind: FromTable {
    /// The direction in which its value is better.
    const SENSE: Sense;

    /// Checks the parameters (finite, in range); by default there is nothing to check.
    fn validate(&self) -> Result<(), ObjectiveError> {
        Ok(())
    }

    /// The raw value for `surface`. `scratch` may hold what was computed for this same
    /// surface by another objective (its distinct normals), which is reused.
    fn measure(&self, surface: &Surface, scratch: &mut ObjectiveScratch) -> f64;

    /// The projection it matches, for the kinds that are counted per pixel
    /// (incrementally for bred children, drawn in overlays); `None` by default.
    fn projection(&self) -> Option<&ProjectionMatch> {
        None
    }
}

/// How a kind of objective is made from its `[[objective]]` table: the table's form as
/// serde reads it, and its resolution.
pub trait FromTable: Sized {
    /// The keys of its `[[objective]]` table, less `kind` and `name`, as serde reads them
    /// (unknown keys refused).
    type File: DeserializeOwned + Debug;

    /// The objective a table describes: names of files and meshes resolved through
    /// `source`, whose errors name the key at fault.
    fn resolve<S: ObjectiveSource>(file: Self::File, source: &S) -> Result<Self, S::Error>;
}

/// A kind of objective whose table is the kind itself, as written: nothing in it names a
/// file or a mesh.
pub trait AsWritten: DeserializeOwned + Debug {}

impl<T: AsWritten> FromTable for T {
    type File = T;

    fn resolve<S: ObjectiveSource>(file: T, _: &S) -> Result<T, S::Error> {
        Ok(file)
    }
}

/// Where an `[[objective]]` table is read: the objective's name, the grammar's meshes
/// that parts name, the files the table names, and errors that name the table's keys.
///
/// ```
/// use image::GrayImage;
/// use shapegen_runtime::geometry::PointCloud;
/// use shapegen_runtime::score::objective::{Objective, ObjectiveError, ObjectiveFile, ObjectiveSource};
///
/// /// A table of a scene whose grammar has the meshes `wall` and `roof`.
/// struct Table;
///
/// impl ObjectiveSource for Table {
///     type Error = String;
///     fn name(&self) -> &str {
///         "pitch"
///     }
///     fn meshes(&self) -> &[&str] {
///         &["wall", "roof"]
///     }
///     fn image(&self, field: &str, path: &str) -> Result<GrayImage, String> {
///         Err(format!("{field}: no file {path}"))
///     }
///     fn point_cloud(&self, field: &str, path: &str) -> Result<PointCloud, String> {
///         Err(format!("{field}: no file {path}"))
///     }
///     fn refused(&self, field: &str, error: ObjectiveError) -> String {
///         format!("{field}: {error}")
///     }
/// }
///
/// let file: ObjectiveFile = toml::from_str("kind = \"roof_pitch\"\ntarget_deg = 30")?;
/// let pitch = file.resolve(&Table)?;
/// assert_eq!(pitch.name(), "roof_pitch");
///
/// let file: ObjectiveFile = toml::from_str("kind = \"roof_pitch\"\nparts = [\"tile\"]\ntarget_deg = 30")?;
/// assert_eq!(
///     file.resolve(&Table).unwrap_err(),
///     "parts: objective `pitch`", // its cause: no mesh is named `tile`
/// );
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub trait ObjectiveSource {
    /// An error that names the key at fault.
    type Error;

    /// The objective's name: its table's `name`, else its kind's.
    fn name(&self) -> &str;

    /// The names of the grammar's meshes, in id order, which parts are named among.
    fn meshes(&self) -> &[&str];

    /// The image of the file `path`, given as the key `field`, in grey levels.
    fn image(&self, field: &str, path: &str) -> Result<GrayImage, Self::Error>;

    /// The point cloud of the file `path`, given as the key `field`.
    fn point_cloud(&self, field: &str, path: &str) -> Result<PointCloud, Self::Error>;

    /// The error of the key `field`: `error`.
    fn refused(&self, field: &str, error: ObjectiveError) -> Self::Error;

    /// The meshes `wanted`, given as the key `field`: a name that is not one of the
    /// [`meshes`](Self::meshes) is an error of the key, naming the objective
    /// ([`ObjectiveError::Entry`]).
    fn parts(&self, field: &str, wanted: &[String]) -> Result<Parts, Self::Error> {
        Parts::named(wanted, self.meshes()).map_err(|err| {
            let entry = ObjectiveError::Entry {
                name: self.name().to_owned(),
                source: Box::new(err),
            };
            self.refused(field, entry)
        })
    }
}
