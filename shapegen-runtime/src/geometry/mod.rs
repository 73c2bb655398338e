//! Geometry: oriented scopes, mesh instances and the meshes they refer to.

mod face;
mod formats;
mod instance;
mod library;
mod mesh;
mod normals;
mod obj;
mod scope;

mod split;

pub use face::{Face, Faces};
pub use formats::{MeshFormat, PointCloud};
pub use instance::{CUBE, Instance, MeshId};
pub use library::{BoundMeshes, MeshLibrary};
pub use mesh::{Mesh, MeshError};
pub use scope::Scope;
pub use split::{Axis, Part, Repeat, Split};
