//! The nested form: the derivation tree written as nested objects, a node's children under
//! their slot names, for people to read and write; described on
//! [`Genome::to_nested_json`](crate::genome::Genome::to_nested_json).

mod path;
mod read;
mod write;

pub(super) use read::{genome_from_nested, set_from_nested};
pub(super) use write::{genome_to_nested, set_to_nested};
