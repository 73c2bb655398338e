//! Building known genomes by hand: a root, then children attached to named slots.

use super::error::{GeneAt, GenomeError};
use super::packed::{DEPTH_CAP, Genome, node_of, parent_pos};
use super::validate::slot_at_in;
use crate::derive::{Grammar, NodeParams};
use crate::graph::{HEADER_WORDS, NodeDesc, SlotDesc};
use crate::param;

impl<G: Grammar> Genome<G> {
    /// A genome holding only its root, the axiom, with the parameters `params`.
    ///
    /// `P` is the parameter struct of the grammar's axiom node. Fails if `P` is another
    /// node's, or if a parameter lies outside its distribution.
    pub fn with_root<P: NodeParams>(params: P) -> Result<Self, GenomeError> {
        let graph = G::GRAPH;
        let node = node_for::<G, P>()?;
        if P::KIND != graph.axiom {
            return Err(GenomeError::WrongNode {
                place: format!("the root of `{}`", graph.name),
                expected: node_of::<G>(graph.axiom).name,
                given: node.name,
            });
        }
        let mut genome = Genome::from_parts(vec![0; node.gene_words() as usize], 1);
        genome.words[0] = P::KIND;
        params.write(&mut genome.words[(HEADER_WORDS + node.links) as usize..]);
        check_params(node, &genome.words, 0, 0)?;
        Ok(genome)
    }

    /// Attaches a new gene with the parameters `params` to the single slot `slot` of the
    /// gene at word `parent`; returns the new gene's word position.
    ///
    /// `P` is the parameter struct of the slot's node type. Fails if `parent` is not the
    /// start of a gene, the parent's node has no slot `slot` or it is an array slot (use
    /// [`attach_at`](Self::attach_at)), `P` is not the slot's node type, the slot already
    /// holds a child, a parameter lies outside its distribution, or the new gene would lie
    /// deeper than [`DEPTH_CAP`]. The genome is unchanged on error.
    ///
    /// O(G) to check `parent`; the gene itself is appended in O(1). Limits are not
    /// applied here: check them with [`validate_limits`](Self::validate_limits).
    ///
    /// ```
    /// use shapegen_runtime::genome::Genome;
    /// # shapegen_runtime::generator! {
    /// #     pub Chain {
    /// #         axiom Start;
    /// #         node Start { children { first: Seg = 0.9 } }
    /// #         node Seg {
    /// #             params { len: f32 ~ uniform(0.5, 1.5) }
    /// #             children { next: Seg = 0.5, side: Seg = 0.25 }
    /// #             derive(s) {
    /// #                 use shapegen_runtime::prelude::{CUBE, vec3};
    /// #                 let s = s.resize(vec3(1.0, len, 1.0));
    /// #                 s.emit(CUBE);
    /// #                 if let Some(next) = next {
    /// #                     s.translate(vec3(0.0, s.size().y, 0.0)).derive(next);
    /// #                 }
    /// #                 if let Some(side) = side {
    /// #                     s.rotate_z(0.5).translate(vec3(0.0, s.size().y, 0.0)).derive(side);
    /// #                 }
    /// #             }
    /// #         }
    /// #     }
    /// # }
    /// // `Chain`: Start -> first: Seg; Seg -> next: Seg, side: Seg; Seg has `len`.
    /// let mut g = Genome::<Chain>::with_root(Start {})?;
    /// let first = g.attach(0, "first", Seg { len: 1.0 })?;
    /// g.attach(first, "side", Seg { len: 0.5 })?;
    /// assert_eq!(g.to_string(), "Start @0\n  first: Seg @3 len=1.00\n    side: Seg @8 len=0.50\n");
    /// let err = g.attach(first, "side", Seg { len: 0.7 }).unwrap_err();
    /// assert_eq!(err.to_string(), "gene 1 (`Seg` @3): slot `side` already holds the gene @8");
    /// assert!(g.attach(first, "next", Seg { len: 9.0 }).is_err()); // outside [0.5, 1.5]
    /// # Ok::<(), shapegen_runtime::genome::GenomeError>(())
    /// ```
    pub fn attach<P: NodeParams>(
        &mut self,
        parent: u32,
        slot: &str,
        params: P,
    ) -> Result<u32, GenomeError> {
        self.attach_link(parent, slot, None, params)
    }

    /// As [`attach`](Self::attach), for link `index` of the array slot `slot` (index 0 of
    /// a single slot is the slot itself).
    pub fn attach_at<P: NodeParams>(
        &mut self,
        parent: u32,
        slot: &str,
        index: u32,
        params: P,
    ) -> Result<u32, GenomeError> {
        self.attach_link(parent, slot, Some(index), params)
    }

    /// The index of the gene starting at word `pos`, or an error if none starts there.
    pub(crate) fn gene_index(&self, pos: u32) -> Result<u32, GenomeError> {
        let mut at = 0u32;
        for index in 0..self.len {
            if at == pos {
                return Ok(index);
            }
            if at > pos {
                break;
            }
            at += node_of::<G>(self.words[at as usize]).gene_words();
        }
        Err(GenomeError::NotAGene {
            pos,
            words: self.words.len() as u32,
        })
    }

    fn attach_link<P: NodeParams>(
        &mut self,
        parent: u32,
        slot: &str,
        index: Option<u32>,
        params: P,
    ) -> Result<u32, GenomeError> {
        let parent_index = self.gene_index(parent)?;
        let pnode = node_of::<G>(self.words[parent as usize]);
        let sdesc = find_slot(pnode, slot)?;
        let link = slot_link(pnode, sdesc, index)?;
        let node = node_for::<G, P>()?;
        if P::KIND != sdesc.child {
            return Err(GenomeError::WrongNode {
                place: format!("slot `{}` of `{}`", sdesc.name, pnode.name),
                expected: node_of::<G>(sdesc.child).name,
                given: node.name,
            });
        }
        let parent_at = GeneAt {
            index: parent_index,
            pos: parent,
            node: pnode.name,
        };
        let link_word = (parent + HEADER_WORDS + link) as usize;
        if self.words[link_word] != 0 {
            return Err(GenomeError::Occupied {
                at: parent_at,
                slot: slot_at_in(sdesc, link),
                child: parent.wrapping_add(self.words[link_word]),
            });
        }
        let pos = self.words.len() as u32;
        let at = GeneAt {
            index: self.len,
            pos,
            node: node.name,
        };
        let depth = depth_of(&self.words, parent) + 1;
        if depth > DEPTH_CAP {
            return Err(GenomeError::TooDeep {
                at,
                depth,
                cap: DEPTH_CAP,
            });
        }

        self.words
            .resize(self.words.len() + node.gene_words() as usize, 0);
        let p = pos as usize;
        self.words[p] = P::KIND;
        self.words[p + 1] = (parent as i32 - pos as i32) as u32;
        params.write(&mut self.words[p + (HEADER_WORDS + node.links) as usize..]);
        if let Err(e) = check_params(node, &self.words, pos, self.len) {
            self.words.truncate(p);
            return Err(e);
        }
        self.words[link_word] = pos - parent;
        self.len += 1;
        Ok(pos)
    }
}

/// The slot of `node` named `slot`, or an error listing the node's slots.
fn find_slot<'g>(node: &'g NodeDesc, slot: &str) -> Result<&'g SlotDesc, GenomeError> {
    node.slots.iter().find(|s| s.name == slot).ok_or_else(|| {
        let valid = node
            .slots
            .iter()
            .map(|s| match s.count {
                1 => format!("`{}`", s.name),
                n => format!("`{}[{n}]`", s.name),
            })
            .collect::<Vec<_>>();
        GenomeError::UnknownSlot {
            node: node.name,
            slot: slot.to_owned(),
            valid: if valid.is_empty() {
                "none".to_owned()
            } else {
                valid.join(", ")
            },
        }
    })
}

/// The link of `node`'s slot `slot` that `index` names: none for a slot of one link,
/// one below the slot's count otherwise.
fn slot_link(node: &NodeDesc, slot: &SlotDesc, index: Option<u32>) -> Result<u32, GenomeError> {
    match index {
        None if slot.count != 1 => Err(GenomeError::NeedsIndex {
            node: node.name,
            slot: slot.name,
            count: slot.count,
        }),
        None => Ok(slot.first_link),
        Some(i) if i >= slot.count => Err(GenomeError::SlotIndex {
            node: node.name,
            slot: slot.name,
            index: i,
            count: slot.count,
        }),
        Some(i) => Ok(slot.first_link + i),
    }
}

/// The depth of the gene at `pos` in `words` (the root's is 1), up its parents.
fn depth_of(words: &[u32], pos: u32) -> u32 {
    let mut depth = 1;
    let mut up = pos;
    while up != 0 {
        up = parent_pos(words, up);
        depth += 1;
    }
    depth
}

/// The node type whose parameters `P` holds, if `P` fits one of `G`'s nodes.
fn node_for<G: Grammar, P: NodeParams>() -> Result<&'static NodeDesc, GenomeError> {
    G::GRAPH
        .node(P::KIND)
        .filter(|n| n.links == P::LINKS && n.param_words == P::WORDS)
        .ok_or(GenomeError::ForeignParams {
            kind: P::KIND,
            links: P::LINKS,
            words: P::WORDS,
            generator: G::GRAPH.name,
        })
}

/// Checks the parameters of the gene of type `node` at word `pos`, gene `index`.
fn check_params(node: &NodeDesc, words: &[u32], pos: u32, index: u32) -> Result<(), GenomeError> {
    let params = (pos + HEADER_WORDS + node.links) as usize;
    for p in node.params {
        param::check(&p.dist, &words[params + p.offset as usize..]).map_err(|reason| {
            GenomeError::Param {
                at: GeneAt {
                    index,
                    pos,
                    node: node.name,
                },
                param: p.name,
                reason,
            }
        })?;
    }
    Ok(())
}
