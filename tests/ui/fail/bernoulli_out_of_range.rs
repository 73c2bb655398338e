use shapegen::prelude::*;

generator! {
    pub Ship {
        axiom Start;
        node Start { params { mirrored: bool ~ bernoulli(50.0) } }
    }
}

fn main() {}
