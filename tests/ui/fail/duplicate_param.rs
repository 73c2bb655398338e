use shapegen::prelude::*;

generator! {
    pub Ship {
        axiom Start;
        node Start {
            params { size: Vec3 ~ uniform([0.5; 3], [1.0; 3]), size: f32 ~ uniform(0.0, 1.0) }
        }
    }
}

fn main() {}
