//! Reading a gene's parameters from JSON, shared by the packed and the nested form: each
//! parameter keyed by name, of its type, with no name the node does not have.

use serde_json::{Map, Value};

use crate::graph::{Distribution, NodeDesc};

/// Why a node's parameters could not be read; each form names the gene its own way.
pub(super) enum ParamError {
    /// A name that is not a parameter of the node.
    Extra {
        param: String,
        /// The node's parameters, or "none".
        valid: String,
    },
    /// A parameter of the node that is not given.
    Missing {
        param: &'static str,
        ty: &'static str,
    },
    /// A value not of its parameter's type.
    Mistyped {
        param: &'static str,
        expected: &'static str,
        found: String,
    },
}

/// Writes the parameters of a gene of type `node`, given by name in `params`, into `out`:
/// the gene's parameter words. Names the node lacks are refused first, then the node's
/// parameters are read in declaration order.
pub(super) fn read_params(
    node: &NodeDesc,
    params: &Map<String, Value>,
    out: &mut [u32],
) -> Result<(), ParamError> {
    if let Some(extra) = params
        .keys()
        .find(|k| node.params.iter().all(|p| p.name != *k))
    {
        return Err(ParamError::Extra {
            param: extra.clone(),
            valid: names_or_none(node.params.iter().map(|p| p.name)),
        });
    }
    for p in node.params {
        let value = params.get(p.name).ok_or(ParamError::Missing {
            param: p.name,
            ty: p.dist.type_name(),
        })?;
        read_value(&p.dist, value, &mut out[p.offset as usize..]).map_err(|expected| {
            ParamError::Mistyped {
                param: p.name,
                expected,
                found: value.to_string(),
            }
        })?;
    }
    Ok(())
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

/// Names in backquotes, separated by commas.
pub(super) fn names<S: AsRef<str>>(items: impl Iterator<Item = S>) -> String {
    items
        .map(|s| format!("`{}`", s.as_ref()))
        .collect::<Vec<_>>()
        .join(", ")
}

/// As [`names`], or "none" when there are none.
pub(super) fn names_or_none<S: AsRef<str>>(items: impl Iterator<Item = S>) -> String {
    let names = names(items);
    if names.is_empty() {
        "none".to_owned()
    } else {
        names
    }
}

/// A node type's child slots as people name them: `next`, and `lots[100]` for an array.
pub(super) fn slot_names(node: &NodeDesc) -> impl Iterator<Item = String> + '_ {
    node.slots.iter().map(|s| match s.count {
        1 => s.name.to_owned(),
        n => format!("{}[{n}]", s.name),
    })
}
