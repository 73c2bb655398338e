//! Reading the packed form: the genes as written, then packing and checking them.

use serde::de::Error as _;
use serde::{Deserialize, Deserializer};
use serde_json::{Map, Value};

use super::error::JsonError;
use super::params::{ParamError, names, read_params, slot_names};
use super::set::GenomeSet;
use crate::derive::Grammar;
use crate::genome::packed::{Genome, node_of};
use crate::graph::HEADER_WORDS;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct GenomeFields {
    pub(super) generator: String,
    pub(super) genes: Vec<GeneFields>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct SetFields {
    pub(super) generator: String,
    pub(super) genomes: Vec<GenesOnlyFields>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct GenesOnlyFields {
    pub(super) genes: Vec<GeneFields>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct GeneFields {
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
        genome_from_genes(fields.genes).map_err(|e| D::Error::custom(crate::error::error_chain(&e)))
    }
}

impl<'de, G: Grammar> Deserialize<'de> for GenomeSet<G> {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let fields = SetFields::deserialize(d)?;
        check_generator::<G>(&fields.generator).map_err(D::Error::custom)?;
        read_set(fields.genomes, |g| genome_from_genes(g.genes))
            .map_err(|e| D::Error::custom(crate::error::error_chain(&e)))
    }
}

/// Packs the genes read from JSON into a genome and validates it.
pub(super) fn genome_from_genes<G: Grammar>(
    genes: Vec<GeneFields>,
) -> Result<Genome<G>, JsonError> {
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
                    names(slot_names(node))
                },
            });
        }
        let pos = words.len();
        words.push(kind);
        words.push(g.parent as u32);
        words.extend(g.links.iter().map(|&l| l as u32));
        words.resize(pos + node.gene_words() as usize, 0);
        let params = pos + (HEADER_WORDS + node.links) as usize;
        read_params(node, &g.params, &mut words[params..]).map_err(|e| match e {
            ParamError::Extra { param, valid } => JsonError::ExtraParam {
                gene,
                node: node.name,
                param,
                valid,
            },
            ParamError::Missing { param, ty } => JsonError::MissingParam {
                gene,
                node: node.name,
                param,
                ty,
            },
            ParamError::Mistyped {
                param,
                expected,
                found,
            } => JsonError::MistypedParam {
                gene,
                node: node.name,
                param,
                expected,
                found,
            },
        })?;
    }
    let genome = Genome::from_parts(words, genes.len() as u32);
    genome.validate()?;
    Ok(genome)
}

/// The set of the genomes `read` makes of `entries`, in order; an entry that fails
/// fails the set, with its index.
pub(super) fn read_set<G: Grammar, T>(
    entries: impl IntoIterator<Item = T>,
    mut read: impl FnMut(T) -> Result<Genome<G>, JsonError>,
) -> Result<GenomeSet<G>, JsonError> {
    let genomes = entries
        .into_iter()
        .enumerate()
        .map(|(index, entry)| {
            read(entry).map_err(|e| JsonError::InSet {
                index,
                source: Box::new(e),
            })
        })
        .collect::<Result<_, _>>()?;
    Ok(GenomeSet::new(genomes))
}

/// Checks that a file written for the generator `found` is one of `G`.
pub(super) fn check_generator<G: Grammar>(found: &str) -> Result<(), JsonError> {
    if G::GRAPH.answers_to(found) {
        Ok(())
    } else {
        Err(JsonError::WrongGenerator {
            found: found.to_owned(),
            expected: G::GRAPH.key,
            also: G::GRAPH.name,
        })
    }
}
