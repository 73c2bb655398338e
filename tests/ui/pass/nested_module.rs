//! A generator declared in a nested module that imports nothing: the expansion reaches
//! the runtime by its own path, and the user's rule bodies use full paths.
#![deny(warnings, unused_qualifications)]

mod outer {
    pub mod inner {
        shapegen::generator! {
            pub Nested {
                axiom Start;
                node Start {
                    params { size: Vec3 ~ uniform([1.0; 3], [2.0; 3]), turns: u32 ~ uniform(0..4) }
                    children { rest: [Part; 2] = 0.5, top: Part = 1.0 }
                    derive(s) {
                        let s = s.resize(size).rotate_y(turns as f32);
                        s.emit(shapegen::CUBE);
                        for (_, part) in rest.iter().chain(top.map(|t| (2, t))) {
                            s.derive(part);
                        }
                    }
                }
                node Part { params { on: bool ~ bernoulli(0.5) } }
            }
        }
    }
}

fn main() {
    use rand::SeedableRng;
    use shapegen::Grammar;

    let graph = outer::inner::Nested::GRAPH;
    assert_eq!(graph.nodes[0].links, 3);
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(1);
    let genome = shapegen::Genome::<outer::inner::Nested>::axiom(&mut rng);
    let mut out = Vec::new();
    genome.derive_into(&mut out);
    assert_eq!(out.len(), 1);
    let _ = outer::inner::Part { on: true };
}
