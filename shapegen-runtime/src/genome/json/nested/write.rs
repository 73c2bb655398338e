//! Writing the nested form: a node with children opens a block, one child a line (empty
//! entries of an array slot ten to a line); a node without children fits on one line;
//! parameters always sit on one line, written as the packed form writes them.

use crate::derive::Grammar;
use crate::genome::json::set::GenomeSet;
use crate::genome::json::write::{ParamsOut, write_inline};
use crate::genome::packed::{Genome, node_of};
use crate::graph::HEADER_WORDS;

/// Most empty entries of an array slot written on one line.
const NULLS_A_LINE: u32 = 10;

/// The genome in the nested form.
pub(in crate::genome::json) fn genome_to_nested<G: Grammar>(genome: &Genome<G>) -> String {
    let mut out = Vec::new();
    header::<G>(&mut out);
    out.extend_from_slice(b",\n  \"tree\": ");
    write_node::<G>(&genome.words, 0, 1, &mut out);
    out.extend_from_slice(b"\n}\n");
    String::from_utf8(out).expect("the nested form is written as UTF-8")
}

/// The set in the nested form.
pub(in crate::genome::json) fn set_to_nested<G: Grammar>(set: &GenomeSet<G>) -> String {
    let mut out = Vec::new();
    header::<G>(&mut out);
    out.extend_from_slice(b",\n  \"genomes\": [");
    for (i, genome) in set.genomes.iter().enumerate() {
        if i > 0 {
            out.push(b',');
        }
        out.extend_from_slice(b"\n    {\n      \"tree\": ");
        write_node::<G>(&genome.words, 0, 3, &mut out);
        out.extend_from_slice(b"\n    }");
    }
    if !set.genomes.is_empty() {
        newline(&mut out, 1);
    }
    out.extend_from_slice(b"]\n}\n");
    String::from_utf8(out).expect("the nested form is written as UTF-8")
}

/// Opens the top object and names the generator.
fn header<G: Grammar>(out: &mut Vec<u8>) {
    out.extend_from_slice(b"{\n  \"generator\": ");
    quoted(out, G::GRAPH.key);
}

/// Writes the subtree of the gene at word `pos`, its opening brace where `out` ends and
/// its lines indented one level deeper than `level`.
fn write_node<G: Grammar>(words: &[u32], pos: u32, level: u32, out: &mut Vec<u8>) {
    let node = node_of::<G>(words[pos as usize]);
    let links = &words[(pos + HEADER_WORDS) as usize..][..node.links as usize];
    let params = ParamsOut {
        node,
        params: &words[(pos + HEADER_WORDS + node.links) as usize..],
    };
    out.extend_from_slice(b"{");
    if links.iter().all(|&l| l == 0) {
        out.extend_from_slice(b"\"node\": ");
        quoted(out, node.name);
        if !node.params.is_empty() {
            out.extend_from_slice(b", \"params\": ");
            write_inline(&params, out);
        }
        out.push(b'}');
        return;
    }
    newline(out, level + 1);
    out.extend_from_slice(b"\"node\": ");
    quoted(out, node.name);
    if !node.params.is_empty() {
        out.push(b',');
        newline(out, level + 1);
        out.extend_from_slice(b"\"params\": ");
        write_inline(&params, out);
    }
    out.push(b',');
    newline(out, level + 1);
    out.extend_from_slice(b"\"children\": {");
    let mut first = true;
    for slot in node.slots {
        let slot_links = &links[slot.first_link as usize..][..slot.count as usize];
        let Some(last) = slot_links.iter().rposition(|&l| l != 0) else {
            continue;
        };
        if !first {
            out.push(b',');
        }
        first = false;
        newline(out, level + 2);
        quoted(out, slot.name);
        out.extend_from_slice(b": ");
        if slot.count == 1 {
            write_node::<G>(words, pos + slot_links[0], level + 2, out);
            continue;
        }
        // An array slot: entries up to the last child, runs of nulls ten to a line.
        out.push(b'[');
        let mut i = 0;
        while i <= last {
            if i > 0 {
                out.push(b',');
            }
            newline(out, level + 3);
            if slot_links[i] == 0 {
                out.extend_from_slice(b"null");
                let mut on_line = 1;
                while slot_links[i + 1] == 0 && on_line < NULLS_A_LINE {
                    out.extend_from_slice(b", null");
                    on_line += 1;
                    i += 1;
                }
            } else {
                write_node::<G>(words, pos + slot_links[i], level + 3, out);
            }
            i += 1;
        }
        newline(out, level + 2);
        out.push(b']');
    }
    newline(out, level + 1);
    out.push(b'}');
    newline(out, level);
    out.push(b'}');
}

/// A name of the grammar (an identifier: nothing to escape) in quotes.
fn quoted(out: &mut Vec<u8>, name: &str) {
    out.push(b'"');
    out.extend_from_slice(name.as_bytes());
    out.push(b'"');
}

/// A line break and the indentation of `level`.
fn newline(out: &mut Vec<u8>, level: u32) {
    out.push(b'\n');
    for _ in 0..level {
        out.extend_from_slice(b"  ");
    }
}
