//! Geometry: oriented scopes, mesh instances and the meshes they refer to, and the
//! polygons, prisms and roofs that rules build as geometry of their own, placed as
//! facets.

mod axis;
pub(crate) mod closed;
mod comp;
mod facade;
mod face;
mod facet;
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
mod weld;

pub use axis::Axis;
pub use closed::{OpenEdge, facet_triangles, open_edges, signed_volume};
pub use comp::Walls;
pub use facade::{Inset, Margins};
pub use face::{Face, Faces};
pub use facet::{FACET_CORNERS, emit_facets, facet_transform, is_facet};
pub use formats::{MeshFormat, PointCloud};
pub use instance::{CUBE, Instance, MeshId};
pub use library::{BoundMeshes, MeshLibrary};
pub use mesh::{Mesh, MeshError};
pub use polygon::{Polygon, PolygonError, Setback};
pub use roof::{Roof, RoofError, RoofMeshes, RoofPiece, RoofShape};
pub use scope::Scope;
pub use split::{Part, Repeat, Split};
