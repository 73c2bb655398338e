//! Array slots and nodes without a `derive` section: the city of the paper.
#![deny(warnings, unused_qualifications)]

use shapegen::prelude::*;

generator! {
    /// A 10 x 10 grid of lots, each holding at most one building.
    pub City {
        axiom Start;
        node Start {
            children { lots: [Lot; 10 * 10] = 0.33 }
            derive(s) {
                assert_eq!(lots.len(), 100);
                assert!(!lots.is_empty());
                for (i, lot) in lots.iter() {
                    let (x, z) = ((i % 10) as f32, (i / 10) as f32);
                    s.translate(vec3(-9.9 + 2.2 * x, 0.0, -9.9 + 2.2 * z)).derive(lot);
                }
                if let Some(first) = lots.get(0) {
                    let _: &Lot = first.params();
                }
            }
        }
        // No `derive`: the lot derives its building in its own scope.
        node Lot { children { building: Building = 1.0 } }
        node Building {
            params {
                footprint: Vec2 ~ uniform([0.44; 2], [1.98; 2]),
                height: f32 ~ uniform(0.36, 10.0),
                rotation: f32 ~ radians(0.0, PI),
            }
            derive(s) {
                s.rotate_y(rotation)
                    .with_size(vec3(footprint.x, height, footprint.y))
                    .translate(vec3(0.0, height / 2.0, 0.0))
                    .emit(CUBE);
            }
        }
    }
}

fn main() {
    let start = &City::GRAPH.nodes[0];
    assert_eq!(start.links, 100);
    assert_eq!(start.slots[0].count, 100);
    assert_eq!(start.slots[0].first_link, 0);
    assert_eq!(start.slots[0].probability, 0.33);
    assert_eq!(City::GRAPH.nodes[1].gene_words(), 2 + 1);
    assert_eq!(City::GRAPH.nodes[2].param_words, 4);
    assert_eq!(City::GRAPH.nodes[2].params[2].offset, 3);
}
