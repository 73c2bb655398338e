//! The readable dump of a genome: an indented tree of genes.
//!
//! ```text
//! Start @0
//!   body: Body @3 size=(0.83, 1.20, 0.70)
//!     next: Body @11 size=(1.02, 0.64, 1.31)
//!     wing: Wing @19 size=(0.52, 0.33, 0.71) shift=-0.12
//!       next: WingNext @25 size=(0.93, 0.95, 1.04) shift=0.31
//! ```
//!
//! `Display` rounds to two decimals; `Debug` prints a header line and the exact values.
//! Angles are shown in the unit they were declared in (`30.00°` or `0.52 rad`).

use std::fmt;

use super::error::SlotAt;
use super::packed::{Genome, node_of};
use super::validate::slot_at;
use crate::derive::Grammar;
use crate::graph::{AngleUnit, Distribution, HEADER_WORDS};
use crate::param::ParamValue;

impl<G: Grammar> fmt::Display for Genome<G> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write_tree::<G>(f, &self.words, false)
    }
}

impl<G: Grammar> fmt::Debug for Genome<G> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(
            f,
            "Genome<{}>: {} genes, {} words",
            G::GRAPH.name,
            self.len,
            self.words.len()
        )?;
        write_tree::<G>(f, &self.words, true)
    }
}

/// Writes the tree in `words` depth first, children in link order, one gene a line.
fn write_tree<G: Grammar>(f: &mut fmt::Formatter<'_>, words: &[u32], exact: bool) -> fmt::Result {
    if words.is_empty() {
        return writeln!(f, "(no genes)");
    }
    // (gene position, depth, link it hangs from)
    let mut stack: Vec<(u32, usize, Option<SlotAt>)> = vec![(0, 0, None)];
    while let Some((pos, depth, slot)) = stack.pop() {
        let node = node_of::<G>(words[pos as usize]);
        write!(f, "{:indent$}", "", indent = 2 * depth)?;
        if let Some(slot) = slot {
            match slot.index {
                Some(i) => write!(f, "{}[{i}]: ", slot.slot)?,
                None => write!(f, "{}: ", slot.slot)?,
            }
        }
        write!(f, "{} @{pos}", node.name)?;
        let params = &words[(pos + HEADER_WORDS + node.links) as usize..];
        for p in node.params {
            write!(f, " {}=", p.name)?;
            write_value(f, &p.dist, &params[p.offset as usize..], exact)?;
        }
        writeln!(f)?;
        for link in (0..node.links).rev() {
            let off = words[(pos + HEADER_WORDS + link) as usize];
            if off != 0 {
                stack.push((pos + off, depth + 1, Some(slot_at(node, link))));
            }
        }
    }
    Ok(())
}

/// Writes one parameter value.
fn write_value(
    f: &mut fmt::Formatter<'_>,
    dist: &Distribution,
    words: &[u32],
    exact: bool,
) -> fmt::Result {
    let num = |f: &mut fmt::Formatter<'_>, v: f32| {
        if exact {
            write!(f, "{v:?}")
        } else {
            write!(f, "{v:.2}")
        }
    };
    let list = |f: &mut fmt::Formatter<'_>, n: usize| {
        f.write_str("(")?;
        for (i, &w) in words[..n].iter().enumerate() {
            if i > 0 {
                f.write_str(", ")?;
            }
            num(f, f32::from_bits(w))?;
        }
        f.write_str(")")
    };
    match *dist {
        Distribution::Uniform { .. } => num(f, f32::read(words)),
        Distribution::Angle { unit, .. } => {
            let v = f32::read(words);
            match unit {
                AngleUnit::Degrees => {
                    num(f, v.to_degrees())?;
                    f.write_str("°")
                }
                AngleUnit::Radians => {
                    num(f, v)?;
                    f.write_str(" rad")
                }
            }
        }
        Distribution::UniformVec2 { .. } => list(f, 2),
        Distribution::UniformVec3 { .. } => list(f, 3),
        Distribution::Int { .. } => write!(f, "{}", i32::read(words)),
        Distribution::Index { .. } | Distribution::Weighted { .. } => {
            write!(f, "{}", u32::read(words))
        }
        Distribution::Bernoulli { .. } => write!(f, "{}", bool::read(words)),
    }
}
