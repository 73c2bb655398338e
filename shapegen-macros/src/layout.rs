//! Gene layout: where each child link and parameter word sits in a gene.
//!
//! A gene is [`HEADER_WORDS`](crate::model::HEADER_WORDS) header words (kind, parent offset), then one word per child
//! link (slots in declaration order, an array slot `[Node; N]` taking `N` consecutive
//! links), then the parameters' words in declaration order (`Vec2` 2 words, `Vec3` 3,
//! every other type 1). The runtime reads the same numbers from the generator graph, and
//! the expansion asserts at compile time that the graph is consistent with the runtime's
//! own word sizes.

use crate::model::{Node, ParamType};

/// The layout of one node type's genes.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct NodeLayout {
    /// Number of child links.
    pub links: u32,
    /// Index of each slot's first link.
    pub first_links: Vec<u32>,
    /// Number of parameter words.
    pub words: u32,
    /// Word offset of each parameter among the parameter words.
    pub offsets: Vec<u32>,
}

/// Prefix sums: the start of each item and the total.
fn starts(sizes: impl IntoIterator<Item = u32>) -> (Vec<u32>, u32) {
    let mut total = 0u32;
    let starts = sizes
        .into_iter()
        .map(|n| {
            let at = total;
            total = total.saturating_add(n);
            at
        })
        .collect();
    (starts, total)
}

/// Word offsets of parameters of types `types`, and the words they take together.
pub fn param_offsets(types: impl IntoIterator<Item = ParamType>) -> (Vec<u32>, u32) {
    starts(types.into_iter().map(ParamType::words))
}

/// The layout of `node`, when every parameter type and slot length is known.
pub fn node_layout(node: &Node) -> Option<NodeLayout> {
    let counts: Option<Vec<u32>> = node.slots.iter().map(|s| s.count()).collect();
    let types: Option<Vec<ParamType>> = node.params.iter().map(|p| p.ty).collect();
    let (first_links, links) = starts(counts?);
    let (offsets, words) = param_offsets(types?);
    Some(NodeLayout {
        links,
        first_links,
        words,
        offsets,
    })
}

/// Number of links of `node`, when every slot's length is known.
pub fn links(node: &Node) -> Option<u32> {
    node.slots.iter().map(|s| s.count()).sum()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::check::check;
    use crate::ctxt::Ctxt;
    use crate::parse::parse_input;
    use quote::quote;

    #[test]
    fn offsets_follow_declaration_order() {
        let (offsets, words) = param_offsets([
            ParamType::Vec3,
            ParamType::F32,
            ParamType::Vec2,
            ParamType::Bool,
            ParamType::U32,
        ]);
        assert_eq!(offsets, [0, 3, 4, 6, 7]);
        assert_eq!(words, 8);
    }

    #[test]
    fn array_slots_take_consecutive_links() {
        let cx = Ctxt::default();
        let input = parse_input(
            quote! {
                krate; G {
                    axiom City;
                    node City {
                        params { seed: u32 ~ uniform(0..10), size: Vec2 ~ uniform([0.0; 2], [1.0; 2]) }
                        children { lots: [Lot; 100] = 0.33, park: Lot = 0.5, rows: [Lot; 3] = 1.0 }
                    }
                    node Lot { params { h: f32 ~ uniform(0.0, 1.0) } }
                }
            },
            &cx,
        )
        .unwrap();
        let g = check(&input.generator, &cx);
        assert!(cx.finish().is_empty());
        let city = node_layout(&g.nodes[0]).unwrap();
        assert_eq!(
            city,
            NodeLayout {
                links: 104,
                first_links: vec![0, 100, 101],
                words: 3,
                offsets: vec![0, 1],
            }
        );
        let lot = node_layout(&g.nodes[1]).unwrap();
        assert_eq!((lot.links, lot.words), (0, 1));
    }
}
