//! Genomes as JSON, in two forms: the packed form ([`Genome::to_json`]), the genes as
//! stored, and the nested form ([`Genome::to_nested_json`]), the tree as nested objects,
//! for people to read and write. Reading takes either and tells them apart by their keys
//! (`shape`). The packed form is written in `write` and read in `read`, the nested form
//! both in `nested`; `params` reads parameters for both, and `error` says what can go
//! wrong.

mod error;
mod nested;
mod params;
mod read;
mod set;
mod shape;
mod write;

use std::path::Path;

pub use error::JsonError;
use nested::{genome_from_nested, genome_to_nested, set_from_nested, set_to_nested};
use read::{GenomeFields, SetFields, check_generator, genome_from_genes, read_set};
pub use set::GenomeSet;
pub use shape::JsonLayout;
use write::to_json_string;

use super::packed::Genome;
use crate::derive::Grammar;

impl<G: Grammar> Genome<G> {
    /// The genome in the packed form: its genes as stored, nodes and parameters by name,
    /// one gene a line. [`to_nested_json`](Self::to_nested_json) writes the other form,
    /// made for people to read and write; [`from_json`](Self::from_json) reads both.
    ///
    /// ```json
    /// {
    ///   "generator": "spaceship",
    ///   "genes": [
    ///     {"node": "Start", "parent": 0, "links": [3], "params": {}},
    ///     {"node": "Body", "parent": -3, "links": [0, 8, 0], "params": {"size": [0.83, 1.2, 0.7]}},
    ///     {"node": "Wing", "parent": -8, "links": [0], "params": {"size": [0.5, 0.3, 0.7], "shift": 0.1}}
    ///   ]
    /// }
    /// ```
    ///
    /// Genes are listed in buffer order. `parent` and `links` are the gene's relative word
    /// offsets exactly as stored (0: the root's parent, or an absent child); `links` has one
    /// entry per link of the node, array slots included, in declaration order. Parameters
    /// are keyed by name: `f32` as a number, `Vec2`/`Vec3` as arrays of numbers, `i32`/`u32`
    /// as integers, `bool` as `true`/`false`; angles in radians, as stored. Numbers are
    /// written as the shortest decimals that read back to the same `f32`, so a save and load
    /// round-trips exactly.
    ///
    /// Many genomes go in one file as a [`GenomeSet`]:
    /// `{"generator": "spaceship", "genomes": [{"genes": [...]}, ...]}`.
    ///
    /// Loading checks the generator's name, node names, the number of links, that each
    /// parameter is present, known and of its type, and then every layout invariant with
    /// [`Genome::validate`], parameter ranges included; errors name the gene by its index.
    /// Through serde ([`Deserialize`](serde::Deserialize)) only this form is read.
    ///
    /// ```
    /// use shapegen_runtime::genome::Genome;
    /// # shapegen_runtime::generator! {
    /// #     pub Chain {
    /// #         axiom Start;
    /// #         node Start { children { first: Seg = 0.9 } }
    /// #         node Seg {
    /// #             params { len: f32 ~ uniform(0.5, 1.5) }
    /// #             children { next: Seg = 0.5, side: Seg = 0.25 }
    /// #             derive(s) {
    /// #                 use shapegen_runtime::prelude::{CUBE, vec3};
    /// #                 let s = s.resize(vec3(1.0, len, 1.0));
    /// #                 s.emit(CUBE);
    /// #                 if let Some(next) = next {
    /// #                     s.translate(vec3(0.0, s.size().y, 0.0)).derive(next);
    /// #                 }
    /// #                 if let Some(side) = side {
    /// #                     s.rotate_z(0.5).translate(vec3(0.0, s.size().y, 0.0)).derive(side);
    /// #                 }
    /// #             }
    /// #         }
    /// #     }
    /// # }
    /// let mut g = Genome::<Chain>::with_root(Start {})?;
    /// g.attach(0, "first", Seg { len: 0.75 })?;
    /// let json = g.to_json();
    /// assert_eq!(json, r#"{
    ///   "generator": "chain",
    ///   "genes": [
    ///     {"node": "Start", "parent": 0, "links": [3], "params": {}},
    ///     {"node": "Seg", "parent": -3, "links": [0, 0], "params": {"len": 0.75}}
    ///   ]
    /// }
    /// "#);
    /// assert_eq!(Genome::<Chain>::from_json(&json)?, g);
    /// let err = Genome::<Chain>::from_json(&json.replace("0.75", "2.0")).unwrap_err();
    /// assert_eq!(
    ///     shapegen_runtime::error_chain(&err),
    ///     "invalid genome: gene 1 (`Seg` @3): parameter `len`: 2 is outside [0.5, 1.5]"
    /// );
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn to_json(&self) -> String {
        to_json_string(self, 2)
    }

    /// The genome in the nested form: the derivation tree as nested objects, each node's
    /// children under their slot names, for people to read and to write by hand.
    ///
    /// ```json
    /// {
    ///   "generator": "spaceship",
    ///   "tree": {
    ///     "node": "Start",
    ///     "children": {
    ///       "body": {
    ///         "node": "Body",
    ///         "params": {"size": [0.83, 1.2, 0.7]},
    ///         "children": {
    ///           "wing": {"node": "Wing", "params": {"size": [0.5, 0.3, 0.7], "shift": 0.1}}
    ///         }
    ///       }
    ///     }
    ///   }
    /// }
    /// ```
    ///
    /// A node is `{"node": TYPE, "params": {NAME: VALUE, ...}, "children": {SLOT: CHILD,
    /// ...}}`; `params` may be left out when the node type has no parameters, `children`
    /// when the node has no children (the writer leaves them out then). A single slot holds
    /// a node, or `null` (or is left out) when it is empty. An array slot `[Node; N]` holds
    /// a list of at most N entries, each a node or `null`, for indices 0, 1, ...; a shorter
    /// list leaves the indices past its end empty, so a list may stop at its last child
    /// (`[null, null, {...}]` fills index 2 alone), and the writer stops it there; an array
    /// slot with no child may be `[]`, `null` or left out. A list longer than the array is
    /// refused. Parameter values are written as in the packed form
    /// ([`to_json`](Self::to_json)), numbers as the shortest decimals that read back to the
    /// same `f32`.
    ///
    /// Reading packs the tree in pre-order, each node's children in link order (slots in
    /// declaration order, an array's entries by index). A genome laid out that way, as
    /// every genome read from the nested form is, comes back word for word; a genome laid
    /// out otherwise (the genetic operators append genes wherever the tree grows) comes
    /// back as the same tree, which derives the same model, in that order.
    ///
    /// Reading checks the generator's name; each node's type name, that it is the type
    /// its slot holds (the axiom at the root), its slot names and list lengths, and each
    /// of its parameters' presence, type and range; and then every layout invariant with
    /// [`Genome::validate`]. Errors name the node by its path from the root: the root's
    /// type, then a step for each slot with its index in an array slot and the type of
    /// the node in it, as `Start > lots[3]: Lot > building: Building`. A node whose type is
    /// not known yet ends its path with its slot (`Start > body`); the root is then `tree`.
    ///
    /// JSON is read at most 128 levels deep, and each level of the tree takes two levels
    /// of JSON (three through an array slot), so a tree deeper than about 60 levels (about
    /// 40 through array slots) cannot be read back from this form and is kept in the packed
    /// one; reading it fails with [`JsonError::NestedTooDeep`].
    ///
    /// Many genomes go in one file as a [`GenomeSet`]:
    /// `{"generator": "spaceship", "genomes": [{"tree": {...}}, ...]}`.
    ///
    /// ```
    /// use shapegen_runtime::genome::Genome;
    /// # shapegen_runtime::generator! {
    /// #     pub Chain {
    /// #         axiom Start;
    /// #         node Start { children { first: Seg = 0.9 } }
    /// #         node Seg {
    /// #             params { len: f32 ~ uniform(0.5, 1.5) }
    /// #             children { next: Seg = 0.5, side: Seg = 0.25 }
    /// #             derive(s) {
    /// #                 use shapegen_runtime::prelude::{CUBE, vec3};
    /// #                 let s = s.resize(vec3(1.0, len, 1.0));
    /// #                 s.emit(CUBE);
    /// #                 if let Some(next) = next {
    /// #                     s.translate(vec3(0.0, s.size().y, 0.0)).derive(next);
    /// #                 }
    /// #                 if let Some(side) = side {
    /// #                     s.rotate_z(0.5).translate(vec3(0.0, s.size().y, 0.0)).derive(side);
    /// #                 }
    /// #             }
    /// #         }
    /// #     }
    /// # }
    /// // `Chain`: Start -> first: Seg; Seg -> next: Seg, side: Seg; Seg has `len`.
    /// let mut g = Genome::<Chain>::with_root(Start {})?;
    /// let first = g.attach(0, "first", Seg { len: 0.75 })?;
    /// g.attach(first, "side", Seg { len: 0.5 })?;
    /// let json = g.to_nested_json();
    /// assert_eq!(json, r#"{
    ///   "generator": "chain",
    ///   "tree": {
    ///     "node": "Start",
    ///     "children": {
    ///       "first": {
    ///         "node": "Seg",
    ///         "params": {"len": 0.75},
    ///         "children": {
    ///           "side": {"node": "Seg", "params": {"len": 0.5}}
    ///         }
    ///       }
    ///     }
    ///   }
    /// }
    /// "#);
    /// assert_eq!(Genome::<Chain>::from_json(&json)?, g);
    ///
    /// // Written by hand, on one line or many.
    /// let hand = r#"{"generator": "chain", "tree": {"node": "Start", "children": {
    ///     "first": {"node": "Seg", "params": {"len": 1.2}, "children": {
    ///         "next": {"node": "Seg", "params": {"len": 0.9}}}}}}}"#;
    /// assert_eq!(Genome::<Chain>::from_json(hand)?.len(), 3);
    /// let err = Genome::<Chain>::from_json(&hand.replace("next", "up")).unwrap_err();
    /// assert_eq!(
    ///     err.to_string(),
    ///     "at `Start > first: Seg`: `up` is not a slot of `Seg`; its slots are: `next`, `side`"
    /// );
    /// let err = Genome::<Chain>::from_json(&hand.replace("0.9", "2.5")).unwrap_err();
    /// assert_eq!(
    ///     err.to_string(),
    ///     "at `Start > first: Seg > next: Seg`: parameter `len`: 2.5 is outside [0.5, 1.5]"
    /// );
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn to_nested_json(&self) -> String {
        genome_to_nested(self)
    }

    /// Reads a genome from JSON of either form, written by [`to_json`](Self::to_json),
    /// by [`to_nested_json`](Self::to_nested_json) or by hand, checking it fully. The
    /// form is told by its keys: `genes` for the packed form, `tree` for the nested one;
    /// errors are those of the form found.
    pub fn from_json(json: &str) -> Result<Self, JsonError> {
        if JsonLayout::of(json).nested {
            return genome_from_nested(json);
        }
        let fields: GenomeFields = serde_json::from_str(json)?;
        check_generator::<G>(&fields.generator)?;
        genome_from_genes(fields.genes)
    }

    /// Writes the genome to the file `path` as [`to_json`](Self::to_json) does.
    pub fn save_json(&self, path: impl AsRef<Path>) -> Result<(), JsonError> {
        write_file(path.as_ref(), &self.to_json())
    }

    /// Reads a genome of either form from the file `path`; errors name the file.
    pub fn load_json(path: impl AsRef<Path>) -> Result<Self, JsonError> {
        let path = path.as_ref();
        Self::from_json(&read_file(path)?).map_err(|e| in_file(path, e))
    }
}

impl<G: Grammar> GenomeSet<G> {
    /// The set in the packed form, one gene a line.
    pub fn to_json(&self) -> String {
        to_json_string(self, 4)
    }

    /// The set in the nested form, each genome's tree as
    /// [`Genome::to_nested_json`] writes it.
    pub fn to_nested_json(&self) -> String {
        set_to_nested(self)
    }

    /// Reads a set from JSON of either form, checking every genome fully. A set is in
    /// the nested form when any of its genomes has a `tree`, and then all must.
    pub fn from_json(json: &str) -> Result<Self, JsonError> {
        if JsonLayout::of(json).nested {
            return set_from_nested(json);
        }
        let fields: SetFields = serde_json::from_str(json)?;
        check_generator::<G>(&fields.generator)?;
        read_set(fields.genomes, |g| genome_from_genes(g.genes))
    }

    /// Writes the set to the file `path`.
    pub fn save(&self, path: impl AsRef<Path>) -> Result<(), JsonError> {
        write_file(path.as_ref(), &self.to_json())
    }

    /// Reads a set of either form from the file `path`; errors name the file.
    pub fn load(path: impl AsRef<Path>) -> Result<Self, JsonError> {
        let path = path.as_ref();
        Self::from_json(&read_file(path)?).map_err(|e| in_file(path, e))
    }
}

fn read_file(path: &Path) -> Result<String, JsonError> {
    std::fs::read_to_string(path).map_err(|source| JsonError::Io {
        path: path.to_owned(),
        source,
    })
}

fn write_file(path: &Path, json: &str) -> Result<(), JsonError> {
    std::fs::write(path, json).map_err(|source| JsonError::Io {
        path: path.to_owned(),
        source,
    })
}

fn in_file(path: &Path, e: JsonError) -> JsonError {
    JsonError::File {
        path: path.to_owned(),
        source: Box::new(e),
    }
}
