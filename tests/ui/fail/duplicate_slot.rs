use shapegen::prelude::*;

generator! {
    pub Ship {
        axiom Start;
        node Start { children { next: Start = 0.5, next: Start = 0.25 } }
    }
}

fn main() {}
