//! Geometry: oriented scopes, mesh instances and the meshes they refer to.

mod face;
mod instance;
mod scope;
mod split;

pub use face::{Face, Faces};
pub use instance::{CUBE, Instance, MeshId};
pub use scope::Scope;
pub use split::{Axis, Part, Repeat, Split};
