use shapegen::prelude::*;

generator! {
    pub Ship {
        axiom Start;
        node Start { params { size: Vec3 ~ uniform([0.3, 0.8, 0.3], [0.8, 0.2, 0.8]) } }
    }
}

fn main() {}
