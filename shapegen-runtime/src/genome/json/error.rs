//! What can be wrong with genome JSON: the packed form's errors name the gene by its
//! index, the nested form's name the node by its path from the root.

use std::io;
use std::path::PathBuf;

use crate::genome::error::GenomeError;
#[cfg(doc)]
use crate::genome::json::set::GenomeSet;
#[cfg(doc)]
use crate::genome::packed::Genome;
#[cfg(doc)]
use crate::graph::GeneratorGraph;

/// Why genome JSON could not be read or written.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum JsonError {
    /// The text is not JSON of the genome form (serde's message gives line and column).
    #[error("not a genome in JSON")]
    Syntax(#[from] serde_json::Error),
    /// The genome belongs to another grammar.
    #[error(
        "the genome is of generator `{found}`, but is being read as `{expected}` (also written `{also}`)"
    )]
    WrongGenerator {
        /// Generator named in the file.
        found: String,
        /// Generator it was read as, as files write it ([`GeneratorGraph::key`]).
        expected: &'static str,
        /// The other spelling that reads as it ([`GeneratorGraph::name`]).
        also: &'static str,
    },
    /// A gene names no node of the grammar.
    #[error("gene {gene}: `{node}` is not a node of `{generator}`; its nodes are: {valid}")]
    UnknownNode {
        /// Index of the gene.
        gene: u32,
        /// Node name found.
        node: String,
        /// Name of the grammar.
        generator: &'static str,
        /// The grammar's nodes.
        valid: String,
    },
    /// A gene has the wrong number of links for its node.
    #[error("gene {gene} (`{node}`): {found} links given, but `{node}` has {expected}: {slots}")]
    LinkCount {
        /// Index of the gene.
        gene: u32,
        /// Its node.
        node: &'static str,
        /// Links found.
        found: usize,
        /// Links of the node.
        expected: u32,
        /// The node's slots in link order.
        slots: String,
    },
    /// A parameter of the node is not given.
    #[error("gene {gene} (`{node}`): parameter `{param}` ({ty}) is missing")]
    MissingParam {
        /// Index of the gene.
        gene: u32,
        /// Its node.
        node: &'static str,
        /// The parameter.
        param: &'static str,
        /// The parameter's type.
        ty: &'static str,
    },
    /// A parameter is given that the node does not have.
    #[error(
        "gene {gene} (`{node}`): `{param}` is not a parameter of `{node}`; its parameters are: {valid}"
    )]
    ExtraParam {
        /// Index of the gene.
        gene: u32,
        /// Its node.
        node: &'static str,
        /// The name found.
        param: String,
        /// The node's parameters.
        valid: String,
    },
    /// A parameter's value is not of its type.
    #[error("gene {gene} (`{node}`): parameter `{param}` must be {expected}, not `{found}`")]
    MistypedParam {
        /// Index of the gene.
        gene: u32,
        /// Its node.
        node: &'static str,
        /// The parameter.
        param: &'static str,
        /// What it must be.
        expected: &'static str,
        /// The value found.
        found: String,
    },
    /// A node of the nested form is not an object.
    #[error(
        "at `{path}`: a node is an object with its type's name in `node` and, when it has \
         any, its `params` and `children`; found `{found}`"
    )]
    NotANode {
        /// Where the node is, from the root (see [`Genome::to_nested_json`]).
        path: String,
        /// The value found, shortened.
        found: String,
    },
    /// A node of the nested form has a key other than `node`, `params` and `children`.
    #[error(
        "at `{path}`: `{key}` is not a key of a node; a node has `node`, `params` and `children`"
    )]
    UnknownKey {
        /// Where the node is.
        path: String,
        /// The key found.
        key: String,
    },
    /// A node of the nested form does not name its node type.
    #[error("at `{path}`: the node does not name its type; give it as `\"node\": \"{expected}\"`")]
    NoNodeName {
        /// Where the node is.
        path: String,
        /// The node type its place holds.
        expected: &'static str,
    },
    /// A node's `node`, `params` or `children` is not of the JSON type it must be.
    #[error("at `{path}`: `{key}` must be {expected}, not `{found}`")]
    MistypedKey {
        /// Where the node is.
        path: String,
        /// The key: `node`, `params` or `children`.
        key: &'static str,
        /// What it must be.
        expected: &'static str,
        /// The value found, shortened.
        found: String,
    },
    /// A node of the nested form names no node type of the grammar.
    #[error("at `{path}`: `{node}` is not a node of `{generator}`; its nodes are: {valid}")]
    UnknownNodeAt {
        /// Where the node is.
        path: String,
        /// The name found.
        node: String,
        /// Name of the grammar.
        generator: &'static str,
        /// The grammar's nodes.
        valid: String,
    },
    /// The root of the nested form is not of the axiom's type.
    #[error("at `{path}`: the root must be the axiom `{axiom}`, not `{node}`")]
    NotTheAxiom {
        /// Where the node is: `tree`.
        path: String,
        /// The node type found.
        node: &'static str,
        /// The grammar's axiom.
        axiom: &'static str,
    },
    /// A node of the nested form hangs from a slot that holds another node type.
    #[error("at `{path}`: slot `{slot}` of `{parent}` holds `{expected}` nodes, not `{node}`")]
    WrongNodeAt {
        /// Where the node is.
        path: String,
        /// The slot.
        slot: &'static str,
        /// The parent's node type.
        parent: &'static str,
        /// The node type the slot holds.
        expected: &'static str,
        /// The node type found.
        node: &'static str,
    },
    /// A node of the nested form names a child slot its node type does not have.
    #[error("at `{path}`: `{slot}` is not a slot of `{node}`; its slots are: {valid}")]
    UnknownSlotAt {
        /// Where the node is.
        path: String,
        /// Its node type.
        node: &'static str,
        /// The slot name found.
        slot: String,
        /// The node type's slots, or "none".
        valid: String,
    },
    /// A single slot of the nested form holds a list.
    #[error("at `{path}`: slot `{slot}` of `{node}` holds one node or null, not a list")]
    NotSingle {
        /// Where the node is.
        path: String,
        /// Its node type.
        node: &'static str,
        /// The slot.
        slot: &'static str,
    },
    /// An array slot of the nested form holds something other than a list.
    #[error(
        "at `{path}`: slot `{slot}` of `{node}` is an array of {count}: give a list of up to \
         {count} nodes or nulls, not `{found}`"
    )]
    NotAList {
        /// Where the node is.
        path: String,
        /// Its node type.
        node: &'static str,
        /// The slot.
        slot: &'static str,
        /// Links in the array.
        count: u32,
        /// The value found, shortened.
        found: String,
    },
    /// An array slot of the nested form lists more entries than the array has.
    #[error(
        "at `{path}`: slot `{slot}` of `{node}` is an array of {count}, but {found} entries \
         are given"
    )]
    TooManyEntries {
        /// Where the node is.
        path: String,
        /// Its node type.
        node: &'static str,
        /// The slot.
        slot: &'static str,
        /// Links in the array.
        count: u32,
        /// Entries given.
        found: usize,
    },
    /// A parameter of a node of the nested form is not given.
    #[error("at `{path}`: parameter `{param}` ({ty}) is missing")]
    MissingParamAt {
        /// Where the node is.
        path: String,
        /// The parameter.
        param: &'static str,
        /// The parameter's type.
        ty: &'static str,
    },
    /// A node of the nested form gives a parameter its node type does not have.
    #[error("at `{path}`: `{param}` is not a parameter of `{node}`; its parameters are: {valid}")]
    ExtraParamAt {
        /// Where the node is.
        path: String,
        /// Its node type.
        node: &'static str,
        /// The name found.
        param: String,
        /// The node type's parameters, or "none".
        valid: String,
    },
    /// A parameter of a node of the nested form is not of its type.
    #[error("at `{path}`: parameter `{param}` must be {expected}, not `{found}`")]
    MistypedParamAt {
        /// Where the node is.
        path: String,
        /// The parameter.
        param: &'static str,
        /// What it must be.
        expected: &'static str,
        /// The value found.
        found: String,
    },
    /// A parameter of a node of the nested form lies outside its distribution.
    #[error("at `{path}`: parameter `{param}`: {reason}")]
    ParamOutOfRange {
        /// Where the node is.
        path: String,
        /// The parameter.
        param: &'static str,
        /// What is wrong, and the valid range.
        reason: String,
    },
    /// The nested form is nested deeper than JSON is read.
    #[error(
        "the nested form nests deeper than the {limit} levels JSON is read to (line {line}, \
         column {column}); a tree this deep is kept in the packed form"
    )]
    NestedTooDeep {
        /// Levels of JSON objects and arrays read at most.
        limit: u32,
        /// Line where the limit was passed.
        line: usize,
        /// Column where it was passed.
        column: usize,
    },
    /// The genes do not form a valid genome (offsets, links, parameter ranges...).
    #[error("invalid genome")]
    Invalid(#[from] GenomeError),
    /// A genome of a [`GenomeSet`] is wrong.
    #[error("genome {index} of the set")]
    InSet {
        /// Index of the genome in the set.
        index: usize,
        /// What is wrong with it.
        source: Box<JsonError>,
    },
    /// The content of a file is wrong.
    #[error("{}", path.display())]
    File {
        /// The file.
        path: PathBuf,
        /// What is wrong with its content.
        source: Box<JsonError>,
    },
    /// A file could not be read or written.
    #[error("{}", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// The system's error.
        source: io::Error,
    },
}
