use shapegen::prelude::*;

generator! {
    pub Ship {
        axiom Start;
        node Start {
            params { size: Vec3 ~ uniform([1.5; 3], [0.6; 3]), turns: f64 ~ uniform(0.0, 1.0) }
            children { body: Bdy = 1.0, wing: Wing = 2.0 }
        }
        node Wing { params { shift: f32 ~ weighted([1.0]) } }
        node Wing {}
    }
}

fn main() {}
