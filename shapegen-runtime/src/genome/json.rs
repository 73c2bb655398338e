//! Genomes as JSON; the format is described on [`Genome::to_json`].

use std::fmt;
use std::io;
use std::marker::PhantomData;
use std::path::{Path, PathBuf};

use serde::de::Error as _;
use serde::ser::{SerializeMap, SerializeSeq, SerializeStruct, SerializeTuple};
use serde::{Deserialize, Deserializer, Serialize, Serializer};
use serde_json::{Map, Value};

use super::error::GenomeError;
use super::{Genome, node_of};
use crate::derive::Grammar;
use crate::graph::{Distribution, HEADER_WORDS, NodeDesc};

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

// ---------------------------------------------------------------------------------------
// Writing

impl<G: Grammar> Serialize for Genome<G> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let mut st = s.serialize_struct("Genome", 2)?;
        st.serialize_field("generator", G::GRAPH.name)?;
        st.serialize_field("genes", &GenesOut::<G>(&self.words, PhantomData))?;
        st.end()
    }
}

impl<G: Grammar> Serialize for GenomeSet<G> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let mut st = s.serialize_struct("GenomeSet", 2)?;
        st.serialize_field("generator", G::GRAPH.name)?;
        st.serialize_field("genomes", &SetOut(&self.genomes))?;
        st.end()
    }
}

struct SetOut<'a, G>(&'a [Genome<G>]);

impl<G: Grammar> Serialize for SetOut<'_, G> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let mut seq = s.serialize_seq(Some(self.0.len()))?;
        for g in self.0 {
            seq.serialize_element(&GenesOnlyOut(GenesOut::<G>(&g.words, PhantomData)))?;
        }
        seq.end()
    }
}

struct GenesOnlyOut<'a, G>(GenesOut<'a, G>);

impl<G: Grammar> Serialize for GenesOnlyOut<'_, G> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let mut st = s.serialize_struct("Genome", 1)?;
        st.serialize_field("genes", &self.0)?;
        st.end()
    }
}

struct GenesOut<'a, G>(&'a [u32], PhantomData<fn() -> G>);

impl<G: Grammar> Serialize for GenesOut<'_, G> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let words = self.0;
        let mut seq = s.serialize_seq(None)?;
        let mut pos = 0u32;
        while (pos as usize) < words.len() {
            let node = node_of::<G>(words[pos as usize]);
            seq.serialize_element(&GeneOut { words, pos, node })?;
            pos += node.gene_words();
        }
        seq.end()
    }
}

struct GeneOut<'a> {
    words: &'a [u32],
    pos: u32,
    node: &'static NodeDesc,
}

impl Serialize for GeneOut<'_> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let p = self.pos as usize;
        let links = &self.words[p + HEADER_WORDS as usize..][..self.node.links as usize];
        let params = &self.words[p + (HEADER_WORDS + self.node.links) as usize..];
        let mut st = s.serialize_struct("Gene", 4)?;
        st.serialize_field("node", self.node.name)?;
        st.serialize_field("parent", &(self.words[p + 1] as i32))?;
        st.serialize_field("links", &LinksOut(links))?;
        st.serialize_field(
            "params",
            &ParamsOut {
                node: self.node,
                params,
            },
        )?;
        st.end()
    }
}

struct LinksOut<'a>(&'a [u32]);

impl Serialize for LinksOut<'_> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let mut seq = s.serialize_seq(Some(self.0.len()))?;
        for &w in self.0 {
            seq.serialize_element(&(w as i32))?;
        }
        seq.end()
    }
}

struct ParamsOut<'a> {
    node: &'static NodeDesc,
    params: &'a [u32],
}

impl Serialize for ParamsOut<'_> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let mut map = s.serialize_map(Some(self.node.params.len()))?;
        for p in self.node.params {
            let words = &self.params[p.offset as usize..][..p.dist.words() as usize];
            map.serialize_entry(p.name, &ValueOut(&p.dist, words))?;
        }
        map.end()
    }
}

struct ValueOut<'a>(&'a Distribution, &'a [u32]);

impl Serialize for ValueOut<'_> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let w = self.1;
        match self.0 {
            Distribution::Uniform { .. } | Distribution::Angle { .. } => {
                s.serialize_f32(f32::from_bits(w[0]))
            }
            Distribution::UniformVec2 { .. } | Distribution::UniformVec3 { .. } => {
                let mut t = s.serialize_tuple(w.len())?;
                for &x in w {
                    t.serialize_element(&f32::from_bits(x))?;
                }
                t.end()
            }
            Distribution::Int { .. } => s.serialize_i32(w[0] as i32),
            Distribution::Index { .. } | Distribution::Weighted { .. } => s.serialize_u32(w[0]),
            Distribution::Bernoulli { .. } => s.serialize_bool(w[0] != 0),
        }
    }
}

/// Writes `value` as JSON, indented down to nesting level `pretty_depth` and on one line
/// below it.
fn to_json_string<T: Serialize>(value: &T, pretty_depth: u32) -> String {
    let mut out = Vec::new();
    let mut ser = serde_json::Serializer::with_formatter(
        &mut out,
        Layout {
            depth: 0,
            pretty_depth,
            has_values: 0,
        },
    );
    value
        .serialize(&mut ser)
        .expect("genome serialization to memory cannot fail");
    out.push(b'\n');
    String::from_utf8(out).expect("serde_json writes UTF-8")
}

/// A JSON layout: containers at nesting levels up to `pretty_depth` put each element on
/// its own indented line; deeper ones stay on one line, with a space after `,` and `:`.
struct Layout {
    depth: u32,
    pretty_depth: u32,
    /// Bit `d` set: the container at level `d` has had an element.
    has_values: u64,
}

impl Layout {
    fn open<W: ?Sized + io::Write>(&mut self, w: &mut W, bracket: &[u8]) -> io::Result<()> {
        self.depth += 1;
        self.has_values &= !(1 << self.depth.min(63));
        w.write_all(bracket)
    }

    fn close<W: ?Sized + io::Write>(&mut self, w: &mut W, bracket: &[u8]) -> io::Result<()> {
        if self.depth <= self.pretty_depth && self.has_values & (1 << self.depth.min(63)) != 0 {
            self.newline(w, self.depth - 1)?;
        }
        self.depth -= 1;
        w.write_all(bracket)
    }

    fn element<W: ?Sized + io::Write>(&mut self, w: &mut W, first: bool) -> io::Result<()> {
        if !first {
            w.write_all(b",")?;
        }
        if self.depth <= self.pretty_depth {
            self.has_values |= 1 << self.depth.min(63);
            self.newline(w, self.depth)
        } else if !first {
            w.write_all(b" ")
        } else {
            Ok(())
        }
    }

    fn newline<W: ?Sized + io::Write>(&self, w: &mut W, level: u32) -> io::Result<()> {
        w.write_all(b"\n")?;
        for _ in 0..level {
            w.write_all(b"  ")?;
        }
        Ok(())
    }
}

impl serde_json::ser::Formatter for Layout {
    fn begin_array<W: ?Sized + io::Write>(&mut self, w: &mut W) -> io::Result<()> {
        self.open(w, b"[")
    }
    fn end_array<W: ?Sized + io::Write>(&mut self, w: &mut W) -> io::Result<()> {
        self.close(w, b"]")
    }
    fn begin_array_value<W: ?Sized + io::Write>(
        &mut self,
        w: &mut W,
        first: bool,
    ) -> io::Result<()> {
        self.element(w, first)
    }
    fn begin_object<W: ?Sized + io::Write>(&mut self, w: &mut W) -> io::Result<()> {
        self.open(w, b"{")
    }
    fn end_object<W: ?Sized + io::Write>(&mut self, w: &mut W) -> io::Result<()> {
        self.close(w, b"}")
    }
    fn begin_object_key<W: ?Sized + io::Write>(
        &mut self,
        w: &mut W,
        first: bool,
    ) -> io::Result<()> {
        self.element(w, first)
    }
    fn begin_object_value<W: ?Sized + io::Write>(&mut self, w: &mut W) -> io::Result<()> {
        w.write_all(b": ")
    }
}

// ---------------------------------------------------------------------------------------
// Reading

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct GenomeFields {
    generator: String,
    genes: Vec<GeneFields>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct SetFields {
    generator: String,
    genomes: Vec<GenesOnlyFields>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct GenesOnlyFields {
    genes: Vec<GeneFields>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct GeneFields {
    node: String,
    parent: i32,
    links: Vec<i32>,
    #[serde(default)]
    params: Map<String, Value>,
}

impl<'de, G: Grammar> Deserialize<'de> for Genome<G> {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let fields = GenomeFields::deserialize(d)?;
        check_generator::<G>(&fields.generator).map_err(D::Error::custom)?;
        genome_from_genes(fields.genes).map_err(D::Error::custom)
    }
}

impl<'de, G: Grammar> Deserialize<'de> for GenomeSet<G> {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let fields = SetFields::deserialize(d)?;
        check_generator::<G>(&fields.generator).map_err(D::Error::custom)?;
        let genomes = fields
            .genomes
            .into_iter()
            .enumerate()
            .map(|(index, g)| {
                genome_from_genes(g.genes).map_err(|e| {
                    D::Error::custom(JsonError::InSet {
                        index,
                        source: Box::new(e),
                    })
                })
            })
            .collect::<Result<_, _>>()?;
        Ok(GenomeSet { genomes })
    }
}

/// Packs the genes read from JSON into a genome and validates it.
fn genome_from_genes<G: Grammar>(genes: Vec<GeneFields>) -> Result<Genome<G>, JsonError> {
    let graph = G::GRAPH;
    let mut words = Vec::new();
    for (gene, g) in genes.iter().enumerate() {
        let gene = gene as u32;
        let kind = graph
            .kind_of(&g.node)
            .ok_or_else(|| JsonError::UnknownNode {
                gene,
                node: g.node.clone(),
                generator: graph.name,
                valid: names(graph.nodes.iter().map(|n| n.name)),
            })?;
        let node = node_of::<G>(kind);
        if g.links.len() != node.links as usize {
            return Err(JsonError::LinkCount {
                gene,
                node: node.name,
                found: g.links.len(),
                expected: node.links,
                slots: if node.slots.is_empty() {
                    "no slots".to_owned()
                } else {
                    names(node.slots.iter().map(|s| match s.count {
                        1 => s.name.to_owned(),
                        n => format!("{}[{n}]", s.name),
                    }))
                },
            });
        }
        if let Some(extra) = g
            .params
            .keys()
            .find(|k| node.params.iter().all(|p| p.name != *k))
        {
            return Err(JsonError::ExtraParam {
                gene,
                node: node.name,
                param: extra.clone(),
                valid: if node.params.is_empty() {
                    "none".to_owned()
                } else {
                    names(node.params.iter().map(|p| p.name))
                },
            });
        }
        let pos = words.len();
        words.push(kind);
        words.push(g.parent as u32);
        words.extend(g.links.iter().map(|&l| l as u32));
        words.resize(pos + node.gene_words() as usize, 0);
        let params = pos + (HEADER_WORDS + node.links) as usize;
        for p in node.params {
            let value = g.params.get(p.name).ok_or(JsonError::MissingParam {
                gene,
                node: node.name,
                param: p.name,
                ty: p.dist.type_name(),
            })?;
            read_value(&p.dist, value, &mut words[params + p.offset as usize..]).map_err(
                |expected| JsonError::MistypedParam {
                    gene,
                    node: node.name,
                    param: p.name,
                    expected,
                    found: value.to_string(),
                },
            )?;
        }
    }
    let genome = Genome::from_parts(words, genes.len() as u32);
    genome.validate()?;
    Ok(genome)
}

/// Writes a JSON value into parameter words; on a type mismatch, says what it must be.
fn read_value(dist: &Distribution, value: &Value, out: &mut [u32]) -> Result<(), &'static str> {
    let float = |v: &Value| v.as_f64().map(|x| (x as f32).to_bits());
    match dist {
        Distribution::Uniform { .. } | Distribution::Angle { .. } => {
            out[0] = float(value).ok_or("a number (f32)")?;
        }
        Distribution::UniformVec2 { .. } | Distribution::UniformVec3 { .. } => {
            let n = dist.words() as usize;
            let expected = if n == 2 {
                "an array of 2 numbers (Vec2)"
            } else {
                "an array of 3 numbers (Vec3)"
            };
            let items = value.as_array().filter(|a| a.len() == n).ok_or(expected)?;
            for (o, v) in out.iter_mut().zip(items) {
                *o = float(v).ok_or(expected)?;
            }
        }
        Distribution::Int { .. } => {
            let v = value.as_i64().and_then(|v| i32::try_from(v).ok());
            out[0] = v.ok_or("an integer (i32)")? as u32;
        }
        Distribution::Index { .. } | Distribution::Weighted { .. } => {
            let v = value.as_u64().and_then(|v| u32::try_from(v).ok());
            out[0] = v.ok_or("a non-negative integer (u32)")?;
        }
        Distribution::Bernoulli { .. } => {
            out[0] = u32::from(value.as_bool().ok_or("true or false (bool)")?);
        }
    }
    Ok(())
}

fn names<S: AsRef<str>>(items: impl Iterator<Item = S>) -> String {
    items
        .map(|s| format!("`{}`", s.as_ref()))
        .collect::<Vec<_>>()
        .join(", ")
}
