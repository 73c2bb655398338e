use shapegen::prelude::*;

generator! {
    pub Ship {
        axiom Start;
        node Start { params { floors: u32 ~ uniform(5..=2) } }
    }
}

fn main() {}
