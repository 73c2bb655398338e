//! Geometry: oriented scopes, mesh instances and the meshes they refer to, and the
//! polygons, prisms and roofs that rules build as geometry of their own.

mod face;
mod formats;
mod instance;
mod library;
mod mesh;
mod normals;
mod obj;
mod polygon;
mod roof;
mod scope;
mod solid;

mod split;

pub use face::{Face, Faces};
pub use formats::{MeshFormat, PointCloud};
pub use instance::{CUBE, Instance, MeshId};
pub use library::{BoundMeshes, MeshLibrary};
pub use mesh::{Mesh, MeshError};
pub use polygon::{Polygon, PolygonError};
pub use roof::{Roof, RoofError, RoofMeshes, RoofPiece, RoofShape};
pub use scope::Scope;
pub use split::{Axis, Part, Repeat, Split};
