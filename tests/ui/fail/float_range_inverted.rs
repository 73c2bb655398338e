use shapegen::prelude::*;

generator! {
    pub Ship {
        axiom Start;
        node Start { params { shift: f32 ~ uniform(0.5, -0.5) } }
    }
}

fn main() {}
