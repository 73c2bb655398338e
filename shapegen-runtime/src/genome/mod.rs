//! The packed genome: a derivation tree stored as genes back to back in one flat buffer
//! of 32-bit words.
//!
//! A gene holds, in order: its node kind; the relative offset (in words) to its parent
//! gene, 0 for the root; one relative offset per child link of its node type, 0 when the
//! child is absent; then its parameter words. Offsets are relative, so a gene's links stay
//! right wherever its subtree is copied as a block.
//!
//! Invariants, all checked by [`Genome::validate`]:
//! - the root is at word 0 and is of the grammar's axiom kind;
//! - every other gene lies after its parent, and its parent links to it on exactly one
//!   link, whose slot's node type is the gene's kind;
//! - genes tile the buffer exactly, each of its node type's size;
//! - parameters lie within their distributions;
//! - the tree's depth is at most [`DEPTH_CAP`].
//!
//! Genomes made through this crate's API (the builders [`Genome::with_root`] and
//! [`Genome::attach`], JSON loading, the genetic operators of [`crate::ops`]) always hold
//! these invariants. [`Limits`] bound a genome's length and depth further; the operators
//! keep their genomes within them.
//!
//! Genomes print as an indented tree ([`Display`](std::fmt::Display), and
//! [`Debug`](std::fmt::Debug) with exact parameter values) and load and save as JSON
//! ([`Genome::to_json`], [`Genome::from_json`], [`GenomeSet`]).

mod build;
mod display;
mod error;
mod fresh;
mod json;
mod limits;
mod packed;
pub(crate) mod validate;

pub use error::{GeneAt, GenomeError, SlotAt};
pub(crate) use fresh::FreshGenes;
pub use json::{GenomeSet, JsonError, JsonLayout};
pub use limits::{Limits, LimitsError};
pub use packed::{DEPTH_CAP, Genome};
pub(crate) use packed::{depths, node_of, parent_pos};
pub(crate) use validate::slot_at;
