//! The spaceship of the paper, with every rule written out.
#![deny(warnings, unused_qualifications)]

use rand::SeedableRng;
use shapegen::prelude::*;

generator! {
    /// The spaceship generator of the ShapeGenetics paper.
    pub Spaceship {
        axiom Start;
        node Start {
            children { body: Body = 1.0 }
            derive(s) {
                if let Some(body) = body {
                    s.resize(body.size).derive(body);
                }
            }
        }
        node Body {
            params { size: Vec3 ~ uniform([0.6; 3], [1.5; 3]) }
            children { next: Body = 1.0 / 3.0, wing: Wing = 1.0 / 3.0, top: Top = 1.0 / 3.0 }
            derive(s) {
                let s = s.translate(vec3(0.0, 0.0, s.size().z / 2.0));
                s.emit(CUBE);
                if let Some(next) = next {
                    s.translate(vec3(0.0, 0.0, s.size().z / 2.0)).resize(next.size).derive(next);
                }
                if let Some(top) = top {
                    s.translate(vec3(0.0, s.size().y / 2.0, 0.0)).derive(top);
                }
                if let Some(wing) = wing {
                    s.translate(vec3(s.size().x / 2.0, 0.0, 0.0)).derive(wing);
                    s.rotate_z(std::f32::consts::PI)
                        .translate(vec3(s.size().x / 2.0, 0.0, 0.0))
                        .derive(wing);
                }
            }
        }
        node Top {
            params { size: Vec3 ~ uniform([0.3, 0.1, 0.3], [0.8, 0.2, 0.8]) }
            children { next: TopNext = 1.0 }
            derive(s) {
                if let Some(next) = next {
                    s.resize(size).derive(next);
                }
            }
        }
        node TopNext {
            params { size: Vec3 ~ uniform([0.6, 0.8, 0.6], [1.1, 1.1, 1.1]) }
            children { next: TopNext = 1.0 }
            derive(s) {
                let s = s.translate(vec3(0.0, s.size().y / 2.0, 0.0));
                s.emit(CUBE);
                if let Some(next) = next {
                    s.translate(vec3(0.0, s.size().y / 2.0, 0.0)).resize(next.size).derive(next);
                }
            }
        }
        node Wing {
            params {
                size: Vec3 ~ uniform([0.3, 0.2, 0.2], [1.2, 0.5, 1.0]),
                shift: f32 ~ uniform(-0.5, 0.5),
            }
            children { next: WingNext = 1.0 }
            derive(s) {
                let s = s.resize(size);
                let s = s.translate(vec3(0.0, 0.0, s.size().z * shift));
                if let Some(next) = next {
                    s.derive(next);
                }
            }
        }
        node WingNext {
            params {
                size: Vec3 ~ uniform([0.6, 0.9, 0.7], [1.2, 1.0, 1.2]),
                shift: f32 ~ uniform(-0.5, 0.5),
            }
            children { next: WingNext = 0.9 }
            derive(s) {
                let s = s.translate(vec3(s.size().x / 2.0, 0.0, 0.0));
                s.emit(CUBE);
                if let Some(next) = next {
                    let c = s.translate(vec3(s.size().x / 2.0, 0.0, 0.0)).resize(next.size);
                    c.translate(vec3(0.0, 0.0, c.size().z * next.shift)).derive(next);
                }
            }
        }
    }
}

fn main() {
    let graph = Spaceship::GRAPH;
    assert_eq!(graph.name, "Spaceship");
    assert_eq!(graph.nodes.len(), 6);
    assert_eq!(graph.nodes[graph.axiom as usize].name, "Start");
    assert_eq!(graph.nodes[1].slots[1].probability, 1.0f32 / 3.0);
    assert_eq!(graph.nodes[1].gene_words(), 2 + 3 + 3);
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(5);
    let genome = Genome::<Spaceship>::axiom(&mut rng);
    let mut out = Vec::new();
    genome.derive_into(&mut out);
    assert!(out.is_empty());
}
