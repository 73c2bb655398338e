use shapegen::prelude::*;

generator! {
    pub Ship {
        axiom Strat;
        node Start {}
    }
}

fn main() {}
