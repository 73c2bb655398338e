use shapegen::prelude::*;

generator! {
    pub Ship {
        axiom Start;
        node Start { params { style: u32 ~ weighted([1.0, -2.0, 1.0]) } }
    }
}

fn main() {}
