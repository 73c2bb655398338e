//! Checking a genome: every invariant of the packed layout, then the limits.

use super::error::{GeneAt, GenomeError, SlotAt};
use super::limits::Limits;
use super::packed::{DEPTH_CAP, Genome, depths, node_of};
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
    let tiling = Tiling::of::<G>(words)?;
    tiling.check_root::<G>()?;
    tiling.check_parents::<G>()?;
    let incoming = tiling.check_links::<G>()?;
    tiling.check_genes::<G>(&incoming)?;
    let actual = tiling.starts.len() as u32;
    if actual != len {
        return Err(GenomeError::CountMismatch {
            recorded: len,
            actual,
        });
    }
    Ok(())
}

/// A genome's buffer cut into genes: where each starts, checked by the passes of
/// [`validate_words`] in turn.
struct Tiling<'a> {
    words: &'a [u32],
    /// Per word, the index + 1 of the gene starting there (0: none).
    index_at: Vec<u32>,
    /// Where each gene starts, in buffer order.
    starts: Vec<u32>,
}

impl<'a> Tiling<'a> {
    /// Pass 1: the genes of `words` (not empty) tile the buffer.
    fn of<G: Grammar>(words: &'a [u32]) -> Result<Tiling<'a>, GenomeError> {
        let graph = G::GRAPH;
        let n = words.len();
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
        Ok(Tiling {
            words,
            index_at,
            starts,
        })
    }

    /// The gene starting at `pos`, named for people.
    fn at<G: Grammar>(&self, pos: usize) -> GeneAt {
        GeneAt {
            index: self.index_at[pos] - 1,
            pos: pos as u32,
            node: node_of::<G>(self.words[pos]).name,
        }
    }

    /// Whether a gene starts at word `target`.
    fn is_gene(&self, target: i64) -> bool {
        target >= 0 && (target as usize) < self.words.len() && self.index_at[target as usize] != 0
    }

    /// The root is the axiom and has no parent.
    fn check_root<G: Grammar>(&self) -> Result<(), GenomeError> {
        let graph = G::GRAPH;
        let words = self.words;
        if words[0] != graph.axiom {
            return Err(GenomeError::RootNotAxiom {
                node: node_of::<G>(words[0]).name,
                generator: graph.name,
                axiom: graph.node_unchecked(graph.axiom).name,
            });
        }
        if words[1] != 0 {
            return Err(GenomeError::RootHasParent {
                offset: words[1] as i32,
            });
        }
        Ok(())
    }

    /// Pass 2: every other gene's parent offset points back to a gene.
    fn check_parents<G: Grammar>(&self) -> Result<(), GenomeError> {
        for &pos in &self.starts[1..] {
            let pos = pos as usize;
            let offset = self.words[pos + 1] as i32;
            if offset >= 0 {
                return Err(GenomeError::ParentNotBefore {
                    at: self.at::<G>(pos),
                    offset,
                });
            }
            let target = pos as i64 + i64::from(offset);
            if !self.is_gene(target) {
                return Err(GenomeError::ParentNotGene {
                    at: self.at::<G>(pos),
                    offset,
                    target,
                });
            }
        }
        Ok(())
    }

    /// Pass 3: links point forward to genes of the slot's kind whose parent is the
    /// linking gene. Returns, per word, the links reaching the gene starting there.
    fn check_links<G: Grammar>(&self) -> Result<Vec<u32>, GenomeError> {
        let words = self.words;
        let mut incoming = vec![0u32; words.len()];
        for &pos in &self.starts {
            let pos = pos as usize;
            for slot in node_of::<G>(words[pos]).slots {
                for link in slot.first_link..slot.first_link + slot.count {
                    let offset = words[pos + (HEADER_WORDS + link) as usize] as i32;
                    if offset != 0 {
                        let child = self.check_link::<G>(pos, slot, link, offset)?;
                        incoming[child] += 1;
                    }
                }
            }
        }
        Ok(incoming)
    }

    /// One non-empty link of pass 3: link `link` of slot `slot` of the gene at `pos`,
    /// holding `offset`. Returns where its child starts.
    fn check_link<G: Grammar>(
        &self,
        pos: usize,
        slot: &SlotDesc,
        link: u32,
        offset: i32,
    ) -> Result<usize, GenomeError> {
        let words = self.words;
        let slot_at = slot_at_in(slot, link);
        if offset < 0 {
            return Err(GenomeError::LinkNotForward {
                at: self.at::<G>(pos),
                slot: slot_at,
                offset,
            });
        }
        let target = pos as i64 + i64::from(offset);
        if !self.is_gene(target) {
            return Err(GenomeError::LinkNotGene {
                at: self.at::<G>(pos),
                slot: slot_at,
                offset,
                target,
            });
        }
        let child = target as usize;
        if words[child] != slot.child {
            return Err(GenomeError::WrongChildKind {
                at: self.at::<G>(pos),
                slot: slot_at,
                child: self.at::<G>(child),
                expected: node_of::<G>(slot.child).name,
            });
        }
        let child_parent = child as i64 + i64::from(words[child + 1] as i32);
        if child_parent != pos as i64 {
            return Err(GenomeError::ForeignChild {
                at: self.at::<G>(pos),
                slot: slot_at,
                child: self.at::<G>(child),
                child_parent,
            });
        }
        Ok(child)
    }

    /// Pass 4, in buffer order so parents come first: each gene but the root linked
    /// back exactly once (`incoming`, from pass 3), its depth within [`DEPTH_CAP`], its
    /// parameters within their distributions.
    fn check_genes<G: Grammar>(&self, incoming: &[u32]) -> Result<(), GenomeError> {
        let words = self.words;
        let mut depth = vec![0u32; words.len()];
        for &pos in &self.starts {
            let pos = pos as usize;
            let node = node_of::<G>(words[pos]);
            if pos == 0 {
                depth[0] = 1;
            } else {
                let parent = (pos as i64 + i64::from(words[pos + 1] as i32)) as usize;
                if incoming[pos] != 1 {
                    return Err(GenomeError::NotLinkedBack {
                        at: self.at::<G>(pos),
                        parent: self.at::<G>(parent),
                        links: incoming[pos],
                    });
                }
                depth[pos] = depth[parent] + 1;
                if depth[pos] > DEPTH_CAP {
                    return Err(GenomeError::TooDeep {
                        at: self.at::<G>(pos),
                        depth: depth[pos],
                        cap: DEPTH_CAP,
                    });
                }
            }
            let params = pos + (HEADER_WORDS + node.links) as usize;
            for p in node.params {
                param::check(&p.dist, &words[params + p.offset as usize..]).map_err(|reason| {
                    GenomeError::Param {
                        at: self.at::<G>(pos),
                        param: p.name,
                        reason,
                    }
                })?;
            }
        }
        Ok(())
    }
}
