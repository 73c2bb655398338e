//! shapegen: controlled procedural modeling.
pub use shapegen_runtime::*;
