use shapegen::prelude::*;

generator! {
    pub Ship {
        axiom Start;
        node Start { params { style: u32 ~ weighted([0.0, 0.0]) } }
    }
}

fn main() {}
