//! Reading the nested form: the tree is walked from the root in pre-order, children in
//! link order, and each node is packed as it is reached, after the checks the packed form
//! makes; every fault names the node by its path.

use std::cmp::Reverse;

use serde::Deserialize;
use serde_json::{Map, Value};

use super::path::{PlaceId, Places};
use crate::derive::Grammar;
use crate::genome::json::error::JsonError;
use crate::genome::json::params::{ParamError, names, names_or_none, read_params, slot_names};
use crate::genome::json::read::{check_generator, read_set};
use crate::genome::json::set::GenomeSet;
use crate::genome::packed::{Genome, node_of};
use crate::graph::{HEADER_WORDS, NodeDesc, SlotDesc};
use crate::param;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct NestedFields {
    generator: String,
    tree: Value,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct NestedSetFields {
    generator: String,
    genomes: Vec<TreeFields>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct TreeFields {
    tree: Value,
}

/// Levels of nested objects and arrays `serde_json` reads at most.
const JSON_DEPTH_LIMIT: u32 = 128;

/// Longest value shown in an error, in characters.
const SHOWN_CHARS: usize = 60;

/// Reads a genome of the nested form.
pub(in crate::genome::json) fn genome_from_nested<G: Grammar>(
    json: &str,
) -> Result<Genome<G>, JsonError> {
    let fields: NestedFields = parse(json)?;
    check_generator::<G>(&fields.generator)?;
    genome_from_tree(&fields.tree)
}

/// Reads a set whose genomes are of the nested form.
pub(in crate::genome::json) fn set_from_nested<G: Grammar>(
    json: &str,
) -> Result<GenomeSet<G>, JsonError> {
    let fields: NestedSetFields = parse(json)?;
    check_generator::<G>(&fields.generator)?;
    read_set(&fields.genomes, |g| genome_from_tree(&g.tree))
}

/// Parses `json`, telling a text nested too deep for `serde_json` from other faults.
fn parse<'a, T: Deserialize<'a>>(json: &'a str) -> Result<T, JsonError> {
    serde_json::from_str(json).map_err(|e| {
        if e.is_syntax() && e.to_string().starts_with("recursion limit exceeded") {
            JsonError::NestedTooDeep {
                limit: JSON_DEPTH_LIMIT,
                line: e.line(),
                column: e.column(),
            }
        } else {
            JsonError::Syntax(e)
        }
    })
}

/// A node still to pack: its JSON, its place, and the link it hangs from.
struct Pending<'a> {
    value: &'a Value,
    place: PlaceId,
    hang: Option<Hang>,
}

/// Where a node hangs: the parent gene's word position and node type, the link and its
/// slot.
#[derive(Clone, Copy)]
struct Hang {
    parent: u32,
    parent_node: &'static NodeDesc,
    link: u32,
    slot: &'static SlotDesc,
}

/// Packs the tree whose root is `tree` and validates the genome. O(G) plus the size of
/// the JSON.
fn genome_from_tree<G: Grammar>(tree: &Value) -> Result<Genome<G>, JsonError> {
    let mut places = Places::default();
    let no_params = Map::new();
    let mut stack = vec![Pending {
        value: tree,
        place: places.root(),
        hang: None,
    }];
    let mut words = Vec::new();
    let mut len = 0u32;
    while let Some(p) = stack.pop() {
        let (kind, object) = node_kind::<G>(&p, &places)?;
        let node = node_of::<G>(kind);
        places.name(p.place, node.name);
        let pos = words.len() as u32;
        words.resize(words.len() + node.gene_words() as usize, 0);
        words[pos as usize] = kind;
        if let Some(h) = p.hang {
            words[pos as usize + 1] = (h.parent as i32 - pos as i32) as u32;
            words[(h.parent + HEADER_WORDS + h.link) as usize] = pos - h.parent;
        }
        let path = || places.path(p.place);
        let params = match object.get("params") {
            None => &no_params,
            Some(Value::Object(params)) => params,
            Some(other) => {
                return Err(JsonError::MistypedKey {
                    path: path(),
                    key: "params",
                    expected: "an object of parameter values by name",
                    found: brief(other),
                });
            }
        };
        let at = (pos + HEADER_WORDS + node.links) as usize;
        read_node_params(node, params, &mut words[at..], path)?;
        len += 1;

        let first_child = stack.len();
        push_children(node, object, pos, p.place, &mut places, &mut stack)?;
        stack[first_child..].sort_unstable_by_key(|c| Reverse(c.hang.map(|h| h.link)));
    }
    let genome = Genome::from_parts(words, len);
    genome.validate()?;
    Ok(genome)
}

/// The node kind of the pending node `p`, checked against its place, and its object.
fn node_kind<'a, G: Grammar>(
    p: &Pending<'a>,
    places: &Places,
) -> Result<(u32, &'a Map<String, Value>), JsonError> {
    let graph = G::GRAPH;
    let path = || places.path(p.place);
    let object = p.value.as_object().ok_or_else(|| JsonError::NotANode {
        path: path(),
        found: brief(p.value),
    })?;
    if let Some(key) = object
        .keys()
        .find(|k| !matches!(k.as_str(), "node" | "params" | "children"))
    {
        return Err(JsonError::UnknownKey {
            path: path(),
            key: key.clone(),
        });
    }
    let expected = p.hang.map_or(graph.axiom, |h| h.slot.child);
    let name = match object.get("node") {
        Some(Value::String(name)) => name,
        None => {
            return Err(JsonError::NoNodeName {
                path: path(),
                expected: node_of::<G>(expected).name,
            });
        }
        Some(other) => {
            return Err(JsonError::MistypedKey {
                path: path(),
                key: "node",
                expected: "the name of a node type, as a string",
                found: brief(other),
            });
        }
    };
    let kind = graph
        .kind_of(name)
        .ok_or_else(|| JsonError::UnknownNodeAt {
            path: path(),
            node: name.clone(),
            generator: graph.name,
            valid: names(graph.nodes.iter().map(|n| n.name)),
        })?;
    if kind != expected {
        let node = node_of::<G>(kind).name;
        let expected = node_of::<G>(expected).name;
        return Err(match p.hang {
            None => JsonError::NotTheAxiom {
                path: path(),
                node,
                axiom: expected,
            },
            Some(h) => JsonError::WrongNodeAt {
                path: path(),
                slot: h.slot.name,
                parent: h.parent_node.name,
                expected,
                node,
            },
        });
    }
    Ok((kind, object))
}

/// Reads the parameters of a node of type `node` into its parameter words `out` and
/// checks them against their distributions.
fn read_node_params(
    node: &NodeDesc,
    params: &Map<String, Value>,
    out: &mut [u32],
    path: impl Fn() -> String,
) -> Result<(), JsonError> {
    read_params(node, params, out).map_err(|e| match e {
        ParamError::Extra { param, valid } => JsonError::ExtraParamAt {
            path: path(),
            node: node.name,
            param,
            valid,
        },
        ParamError::Missing { param, ty } => JsonError::MissingParamAt {
            path: path(),
            param,
            ty,
        },
        ParamError::Mistyped {
            param,
            expected,
            found,
        } => JsonError::MistypedParamAt {
            path: path(),
            param,
            expected,
            found,
        },
    })?;
    for p in node.params {
        param::check(&p.dist, &out[p.offset as usize..]).map_err(|reason| {
            JsonError::ParamOutOfRange {
                path: path(),
                param: p.name,
                reason,
            }
        })?;
    }
    Ok(())
}

/// The error for a `children` key `name` that is no slot of `node` (at place `place`).
fn unknown_slot(node: &NodeDesc, name: &str, places: &Places, place: PlaceId) -> JsonError {
    JsonError::UnknownSlotAt {
        path: places.path(place),
        node: node.name,
        slot: name.to_owned(),
        valid: names_or_none(slot_names(node)),
    }
}

/// Pushes the children written in `object`'s `children`, of the node of type `node` at
/// word `pos` and place `place`, onto `stack`.
fn push_children<'a>(
    node: &'static NodeDesc,
    object: &'a Map<String, Value>,
    pos: u32,
    place: PlaceId,
    places: &mut Places,
    stack: &mut Vec<Pending<'a>>,
) -> Result<(), JsonError> {
    let children = match object.get("children") {
        None => return Ok(()),
        Some(Value::Object(children)) => children,
        Some(other) => {
            return Err(JsonError::MistypedKey {
                path: places.path(place),
                key: "children",
                expected: "an object of child nodes by slot name",
                found: brief(other),
            });
        }
    };
    for (name, value) in children {
        let slot = node
            .slots
            .iter()
            .find(|s| s.name == name)
            .ok_or_else(|| unknown_slot(node, name, places, place))?;
        let hang = |index: u32| Hang {
            parent: pos,
            parent_node: node,
            link: slot.first_link + index,
            slot,
        };
        match value {
            Value::Null => {}
            Value::Array(_) if slot.count == 1 => {
                return Err(JsonError::NotSingle {
                    path: places.path(place),
                    node: node.name,
                    slot: slot.name,
                });
            }
            Value::Array(entries) => {
                if entries.len() > slot.count as usize {
                    return Err(JsonError::TooManyEntries {
                        path: places.path(place),
                        node: node.name,
                        slot: slot.name,
                        count: slot.count,
                        found: entries.len(),
                    });
                }
                for (index, entry) in (0u32..).zip(entries) {
                    if !entry.is_null() {
                        stack.push(Pending {
                            value: entry,
                            place: places.child(place, slot.name, Some(index)),
                            hang: Some(hang(index)),
                        });
                    }
                }
            }
            _ if slot.count != 1 => {
                return Err(JsonError::NotAList {
                    path: places.path(place),
                    node: node.name,
                    slot: slot.name,
                    count: slot.count,
                    found: brief(value),
                });
            }
            _ => stack.push(Pending {
                value,
                place: places.child(place, slot.name, None),
                hang: Some(hang(0)),
            }),
        }
    }
    Ok(())
}

/// `value` as compact JSON, cut short after [`SHOWN_CHARS`] characters.
fn brief(value: &Value) -> String {
    let text = value.to_string();
    match text.char_indices().nth(SHOWN_CHARS) {
        Some((at, _)) => format!("{}...", &text[..at]),
        None => text,
    }
}
