use shapegen::prelude::*;

generator! {
    pub Ship {
        axiom Start;
        node Start { children { body: Body = 1.0 } }
        node Body {}
        node Wing { children { next: Wing = 0.5 } }
    }
}

fn main() {}
