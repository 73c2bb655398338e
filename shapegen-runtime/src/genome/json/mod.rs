//! Genomes as JSON; the format is described on [`Genome::to_json`]. Writing lives in
//! `write`, reading and checking in `read`.

mod read;
mod write;

use std::fmt;
use std::io;
use std::path::{Path, PathBuf};

use read::{GenomeFields, SetFields, genome_from_genes};
use write::to_json_string;

use super::Genome;
use super::error::GenomeError;
use crate::derive::Grammar;

/// Why genome JSON could not be read or written.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum JsonError {
    /// The text is not JSON of the genome form (serde's message gives line and column).
    #[error("not a genome in JSON: {0}")]
    Syntax(#[from] serde_json::Error),
    /// The genome belongs to another grammar.
    #[error("the genome is of generator `{found}`, but is being read as `{expected}`")]
    WrongGenerator {
        /// Generator named in the file.
        found: String,
        /// Generator it was read as.
        expected: &'static str,
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
    /// The genes do not form a valid genome (offsets, links, parameter ranges...).
    #[error("invalid genome: {0}")]
    Invalid(#[from] GenomeError),
    /// A genome of a [`GenomeSet`] is wrong.
    #[error("genome {index} of the set: {source}")]
    InSet {
        /// Index of the genome in the set.
        index: usize,
        /// What is wrong with it.
        source: Box<JsonError>,
    },
    /// The content of a file is wrong.
    #[error("{}: {source}", path.display())]
    File {
        /// The file.
        path: PathBuf,
        /// What is wrong with its content.
        source: Box<JsonError>,
    },
    /// A file could not be read or written.
    #[error("{}: {source}", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// The system's error.
        source: io::Error,
    },
}

impl<G: Grammar> Genome<G> {
    /// The genome as readable JSON: nodes and parameters by name, one gene a line.
    ///
    /// ```json
    /// {
    ///   "generator": "Spaceship",
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
    /// `{"generator": "Spaceship", "genomes": [{"genes": [...]}, ...]}`.
    ///
    /// Loading checks the generator's name, node names, the number of links, that each
    /// parameter is present, known and of its type, and then every layout invariant with
    /// [`Genome::validate`], parameter ranges included; errors name the gene by its index.
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
    ///   "generator": "Chain",
    ///   "genes": [
    ///     {"node": "Start", "parent": 0, "links": [3], "params": {}},
    ///     {"node": "Seg", "parent": -3, "links": [0, 0], "params": {"len": 0.75}}
    ///   ]
    /// }
    /// "#);
    /// assert_eq!(Genome::<Chain>::from_json(&json)?, g);
    /// let err = Genome::<Chain>::from_json(&json.replace("0.75", "2.0")).unwrap_err();
    /// assert_eq!(
    ///     err.to_string(),
    ///     "invalid genome: gene 1 (`Seg` @3): parameter `len`: 2 is outside [0.5, 1.5]"
    /// );
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn to_json(&self) -> String {
        to_json_string(self, 2)
    }

    /// Reads a genome from JSON written by [`to_json`](Self::to_json) (or by hand),
    /// checking it fully.
    pub fn from_json(json: &str) -> Result<Self, JsonError> {
        let fields: GenomeFields = serde_json::from_str(json)?;
        check_generator::<G>(&fields.generator)?;
        genome_from_genes(fields.genes)
    }

    /// Writes the genome to the file `path` as [`to_json`](Self::to_json) does.
    pub fn save_json(&self, path: impl AsRef<Path>) -> Result<(), JsonError> {
        write_file(path.as_ref(), &self.to_json())
    }

    /// Reads a genome from the file `path`; errors name the file.
    pub fn load_json(path: impl AsRef<Path>) -> Result<Self, JsonError> {
        let path = path.as_ref();
        Self::from_json(&read_file(path)?).map_err(|e| in_file(path, e))
    }
}

/// Many genomes of one grammar, as saved in one file (`genomes.json`):
/// `{"generator": "Spaceship", "genomes": [{"genes": [...]}, ...]}`.
pub struct GenomeSet<G> {
    /// The genomes, in file order.
    pub genomes: Vec<Genome<G>>,
}

impl<G> Clone for GenomeSet<G> {
    fn clone(&self) -> Self {
        GenomeSet {
            genomes: self.genomes.clone(),
        }
    }
}

impl<G> PartialEq for GenomeSet<G> {
    fn eq(&self, other: &Self) -> bool {
        self.genomes == other.genomes
    }
}

impl<G: Grammar> fmt::Debug for GenomeSet<G> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("GenomeSet")
            .field("generator", &G::GRAPH.name)
            .field("genomes", &self.genomes)
            .finish()
    }
}

impl<G: Grammar> GenomeSet<G> {
    /// A set of the given genomes.
    pub fn new(genomes: Vec<Genome<G>>) -> Self {
        GenomeSet { genomes }
    }

    /// The set as readable JSON, one gene a line.
    pub fn to_json(&self) -> String {
        to_json_string(self, 4)
    }

    /// Reads a set from JSON, checking every genome fully.
    pub fn from_json(json: &str) -> Result<Self, JsonError> {
        let fields: SetFields = serde_json::from_str(json)?;
        check_generator::<G>(&fields.generator)?;
        let genomes = fields
            .genomes
            .into_iter()
            .enumerate()
            .map(|(index, g)| {
                genome_from_genes(g.genes).map_err(|e| JsonError::InSet {
                    index,
                    source: Box::new(e),
                })
            })
            .collect::<Result<_, _>>()?;
        Ok(GenomeSet { genomes })
    }

    /// Writes the set to the file `path`.
    pub fn save(&self, path: impl AsRef<Path>) -> Result<(), JsonError> {
        write_file(path.as_ref(), &self.to_json())
    }

    /// Reads a set from the file `path`; errors name the file.
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

fn check_generator<G: Grammar>(found: &str) -> Result<(), JsonError> {
    if found == G::GRAPH.name {
        Ok(())
    } else {
        Err(JsonError::WrongGenerator {
            found: found.to_owned(),
            expected: G::GRAPH.name,
        })
    }
}
