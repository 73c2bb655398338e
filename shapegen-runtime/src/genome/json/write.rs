//! Writing the packed form: `Serialize` straight from the packed words, and a layout
//! that puts one gene on a line.

use std::io;
use std::marker::PhantomData;

use serde::ser::{SerializeMap, SerializeSeq, SerializeStruct, SerializeTuple};
use serde::{Serialize, Serializer};

use super::set::GenomeSet;
use crate::derive::Grammar;
use crate::genome::packed::{Genome, node_of};
use crate::graph::{Distribution, HEADER_WORDS, NodeDesc};

impl<G: Grammar> Serialize for Genome<G> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let mut st = s.serialize_struct("Genome", 2)?;
        st.serialize_field("generator", G::GRAPH.key)?;
        st.serialize_field("genes", &GenesOut::<G>(&self.words, PhantomData))?;
        st.end()
    }
}

impl<G: Grammar> Serialize for GenomeSet<G> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let mut st = s.serialize_struct("GenomeSet", 2)?;
        st.serialize_field("generator", G::GRAPH.key)?;
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

/// A gene's parameters by name: `node`'s parameters read from its parameter words.
pub(super) struct ParamsOut<'a> {
    pub(super) node: &'static NodeDesc,
    pub(super) params: &'a [u32],
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
pub(super) fn to_json_string<T: Serialize>(value: &T, pretty_depth: u32) -> String {
    let mut out = Vec::new();
    write_layout(value, pretty_depth, &mut out);
    out.push(b'\n');
    String::from_utf8(out).expect("serde_json writes UTF-8")
}

/// Appends `value` to `out` as JSON on one line, with a space after `,` and `:`.
pub(super) fn write_inline<T: Serialize>(value: &T, out: &mut Vec<u8>) {
    write_layout(value, 0, out);
}

fn write_layout<T: Serialize>(value: &T, pretty_depth: u32, out: &mut Vec<u8>) {
    let mut ser = serde_json::Serializer::with_formatter(
        out,
        Layout {
            depth: 0,
            pretty_depth,
            has_values: 0,
        },
    );
    value
        .serialize(&mut ser)
        .expect("genome serialization to memory cannot fail");
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
