//! Parameters and slots may take any name, even those the expansion uses internally
//! (`gene`, `shape`, `params`), and raw identifiers; the graph stores names without `r#`.
#![deny(warnings, unused_qualifications)]

use shapegen::prelude::*;

generator! {
    pub Names {
        axiom Start;
        node Start {
            params { gene: f32 ~ uniform(0.0, 1.0), params: u32 ~ uniform(0..=3) }
            children { shape: Leaf = 1.0, r#type: Pass = 0.5 }
            derive(s) {
                let _: (f32, u32) = (gene, params);
                if let Some(shape) = shape {
                    s.derive(shape);
                }
                if let Some(t) = r#type {
                    s.derive(t);
                }
            }
        }
        node Leaf { params { r#gene: bool ~ bernoulli(1.0) } }
        // No `derive`: the default rule binds nothing of the user's.
        node Pass { children { shape: Leaf = 0.5, gene: Leaf = 0.5 } }
    }
}

fn main() {
    let start = &Names::GRAPH.nodes[0];
    assert_eq!(start.params[0].name, "gene");
    assert_eq!(start.slots[1].name, "type");
    assert_eq!(Names::GRAPH.nodes[1].params[0].name, "gene");
    let _ = Leaf { gene: true };
}
