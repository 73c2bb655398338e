//! Reading genomes from JSON: the serialized form, then packing and checking it.

use serde::de::Error as _;
use serde::{Deserialize, Deserializer};
use serde_json::{Map, Value};

use super::{GenomeSet, JsonError, check_generator};
use crate::derive::Grammar;
use crate::genome::{Genome, node_of};
use crate::graph::{Distribution, HEADER_WORDS};

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
