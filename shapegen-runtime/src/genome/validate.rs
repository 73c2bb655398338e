//! Checking a genome: every invariant of the packed layout, then the limits.

use super::error::{GeneAt, GenomeError, SlotAt};
use super::{DEPTH_CAP, Genome, Limits, depths, node_of};
use crate::derive::Grammar;
use crate::graph::{HEADER_WORDS, NodeDesc, SlotDesc};
use crate::param;

impl<G: Grammar> Genome<G> {
    /// Checks every invariant of the packed layout (see the [module](super) docs):
    /// valid node kinds, the axiom at the root, genes tiling the buffer, each gene after
    /// its parent and linked from it on exactly one link of a slot that holds its kind,
    /// links landing on later genes of the slot's kind, the gene count, parameters within
    /// their distributions and depth at most [`DEPTH_CAP`].
    ///
    /// Genomes made through this crate's API are always valid; this is for genomes read
    /// from elsewhere and for tests. O(G) time and memory.
    pub fn validate(&self) -> Result<(), GenomeError> {
        validate_words::<G>(&self.words, self.len)
    }

    /// Checks the genome against `limits`: its length within `[min_len, max_len]` and its
    /// depth at most `max_depth`. The genome itself is assumed valid. O(G).
    pub fn validate_limits(&self, limits: &Limits) -> Result<(), GenomeError> {
        if self.len < limits.min_len {
            return Err(GenomeError::TooShort {
                len: self.len,
                min_len: limits.min_len,
            });
        }
        if self.len > limits.max_len {
            return Err(GenomeError::TooLong {
                len: self.len,
                max_len: limits.max_len,
            });
        }
        if limits.max_depth >= self.len {
            return Ok(()); // a tree of G genes is at most G deep
        }
        let mut depth = Vec::new();
        depths::<G>(&self.words, &mut depth);
        for (index, gene) in self.genes().enumerate() {
            let d = depth[gene.pos() as usize];
            if d > limits.max_depth {
                return Err(GenomeError::DeeperThanLimit {
                    at: GeneAt {
                        index: index as u32,
                        pos: gene.pos(),
                        node: self.node(gene).name,
                    },
                    depth: d,
                    max_depth: limits.max_depth,
                });
            }
        }
        Ok(())
    }

    /// Depth of the tree: 1 for the root alone. O(G).
    pub fn depth(&self) -> u32 {
        let mut depth = Vec::new();
        depths::<G>(&self.words, &mut depth)
    }
}

/// The link `link` of `node`, named for people.
pub(crate) fn slot_at(node: &NodeDesc, link: u32) -> SlotAt {
    let slot = node
        .slot_of_link(link)
        .expect("a link index below the node's link count");
    slot_at_in(slot, link)
}

/// The link `link` of a node, within its slot `slot`, named for people.
pub(crate) fn slot_at_in(slot: &SlotDesc, link: u32) -> SlotAt {
    SlotAt {
        slot: slot.name,
        index: (slot.count != 1).then(|| link - slot.first_link),
    }
}

/// Checks all layout invariants of the genome in `words`, which records `len` genes.
pub(crate) fn validate_words<G: Grammar>(words: &[u32], len: u32) -> Result<(), GenomeError> {
    let graph = G::GRAPH;
    if words.is_empty() {
        return Err(GenomeError::Empty {
            axiom: graph.node_unchecked(graph.axiom).name,
        });
    }
    let n = words.len();

    // Pass 1: genes tile the buffer; remember where each starts (index + 1, 0 = none).
    let mut index_at = vec![0u32; n];
    let mut starts = Vec::new();
    let mut pos = 0usize;
    while pos < n {
        let index = starts.len() as u32;
        let kind = words[pos];
        let node = graph.node(kind).ok_or(GenomeError::UnknownKind {
            index,
            pos: pos as u32,
            kind,
            generator: graph.name,
            kinds: graph.nodes.len() as u32,
        })?;
        let need = node.gene_words() as usize;
        if need > n - pos {
            return Err(GenomeError::Truncated {
                at: GeneAt {
                    index,
                    pos: pos as u32,
                    node: node.name,
                },
                need: need as u32,
                left: (n - pos) as u32,
            });
        }
        index_at[pos] = index + 1;
        starts.push(pos as u32);
        pos += need;
    }
    let at = |pos: usize| GeneAt {
        index: index_at[pos] - 1,
        pos: pos as u32,
        node: node_of::<G>(words[pos]).name,
    };
    let is_gene =
        |target: i64| target >= 0 && (target as usize) < n && index_at[target as usize] != 0;

    let root = node_of::<G>(words[0]);
    if words[0] != graph.axiom {
        return Err(GenomeError::RootNotAxiom {
            node: root.name,
            generator: graph.name,
            axiom: graph.node_unchecked(graph.axiom).name,
        });
    }
    if words[1] != 0 {
        return Err(GenomeError::RootHasParent {
            offset: words[1] as i32,
        });
    }

    // Pass 2: parent offsets point back to genes.
    for &pos in &starts[1..] {
        let pos = pos as usize;
        let offset = words[pos + 1] as i32;
        if offset >= 0 {
            return Err(GenomeError::ParentNotBefore {
                at: at(pos),
                offset,
            });
        }
        let target = pos as i64 + i64::from(offset);
        if !is_gene(target) {
            return Err(GenomeError::ParentNotGene {
                at: at(pos),
                offset,
                target,
            });
        }
    }

    // Pass 3: links point forward to genes of the slot's kind whose parent is this gene.
    // Count the links reaching each gene.
    let mut incoming = vec![0u32; n];
    for &pos in &starts {
        let pos = pos as usize;
        let node = node_of::<G>(words[pos]);
        for slot in node.slots {
            for link in slot.first_link..slot.first_link + slot.count {
                let offset = words[pos + (HEADER_WORDS + link) as usize] as i32;
                if offset == 0 {
                    continue;
                }
                let slot_at = slot_at_in(slot, link);
                if offset < 0 {
                    return Err(GenomeError::LinkNotForward {
                        at: at(pos),
                        slot: slot_at,
                        offset,
                    });
                }
                let target = pos as i64 + i64::from(offset);
                if !is_gene(target) {
                    return Err(GenomeError::LinkNotGene {
                        at: at(pos),
                        slot: slot_at,
                        offset,
                        target,
                    });
                }
                let child = target as usize;
                if words[child] != slot.child {
                    return Err(GenomeError::WrongChildKind {
                        at: at(pos),
                        slot: slot_at,
                        child: at(child),
                        expected: node_of::<G>(slot.child).name,
                    });
                }
                let child_parent = child as i64 + i64::from(words[child + 1] as i32);
                if child_parent != pos as i64 {
                    return Err(GenomeError::ForeignChild {
                        at: at(pos),
                        slot: slot_at,
                        child: at(child),
                        child_parent,
                    });
                }
                incoming[child] += 1;
            }
        }
    }

    // Pass 4, in buffer order so parents come first: each gene linked back exactly once,
    // depth, parameters.
    let mut depth = vec![0u32; n];
    for &pos in &starts {
        let pos = pos as usize;
        let node = node_of::<G>(words[pos]);
        if pos == 0 {
            depth[0] = 1;
        } else {
            let parent = (pos as i64 + i64::from(words[pos + 1] as i32)) as usize;
            if incoming[pos] != 1 {
                return Err(GenomeError::NotLinkedBack {
                    at: at(pos),
                    parent: at(parent),
                    links: incoming[pos],
                });
            }
            depth[pos] = depth[parent] + 1;
            if depth[pos] > DEPTH_CAP {
                return Err(GenomeError::TooDeep {
                    at: at(pos),
                    depth: depth[pos],
                    cap: DEPTH_CAP,
                });
            }
        }
        let params = pos + (HEADER_WORDS + node.links) as usize;
        for p in node.params {
            param::check(&p.dist, &words[params + p.offset as usize..]).map_err(|reason| {
                GenomeError::Param {
                    at: at(pos),
                    param: p.name,
                    reason,
                }
            })?;
        }
    }

    let actual = starts.len() as u32;
    if actual != len {
        return Err(GenomeError::CountMismatch {
            recorded: len,
            actual,
        });
    }
    Ok(())
}
