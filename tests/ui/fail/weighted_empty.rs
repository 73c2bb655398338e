use shapegen::prelude::*;

generator! {
    pub Ship {
        axiom Start;
        node Start { params { style: u32 ~ weighted([]) } }
    }
}

fn main() {}
