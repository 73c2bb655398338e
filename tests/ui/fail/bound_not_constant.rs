use shapegen::prelude::*;

generator! {
    pub Ship {
        axiom Start;
        node Start { params { size: f32 ~ uniform(0.5, f32::MAX.sqrt()) } }
    }
}

fn main() {}
