//! Geometry: oriented scopes, mesh instances and the meshes they refer to.

mod instance;
mod scope;

pub use instance::{CUBE, Instance, MeshId};
pub use scope::Scope;
