use shapegen::prelude::*;

generator! {
    pub Ship {
        axiom Start;
        node Start { params { size: f32 ~ weighted([1.0, 2.0]) } }
    }
}

fn main() {}
