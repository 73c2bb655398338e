use shapegen::prelude::*;

generator! {
    pub Ship {
        axiom Start;
        node Start { children { body: Body = 0.0 / 0.0 } }
        node Body {}
    }
}

fn main() {}
