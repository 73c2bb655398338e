//! After a mistake the macro still declares the generator, its parameter structs and its
//! meshes, so the code using them reports nothing more than the mistake.
use rand::SeedableRng;
use shapegen::prelude::*;

generator! {
    pub Ship {
        axiom Start;
        meshes { HULL = "hull" }
        node Start {
            children { body: Body = 1.5 }
            derive(s) {
                if let Some(body) = body {
                    s.resize(body.size).derive(body);
                }
            }
        }
        node Body {
            params { size: Vec3 ~ uniform([0.6; 3], [1.5; 3]), shift: f32 ~ uniform(-0.5, 0.5) }
            derive(s) {
                s.translate(vec3(0.0, 0.0, shift)).emit(HULL);
            }
        }
    }
}

fn body_volume(body: &Body) -> f32 {
    body.size.x * body.size.y * body.size.z + body.shift
}

fn main() {
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(1);
    let genome = Genome::<Ship>::axiom(&mut rng);
    let mut out = Vec::new();
    genome.derive_into(&mut out);
    let _ = (Ship::GRAPH.name, HULL, body_volume(&Body { size: Vec3::ONE, shift: 0.0 }));
}
