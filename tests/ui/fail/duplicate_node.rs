use shapegen::prelude::*;

generator! {
    pub Ship {
        axiom Start;
        node Start { children { body: Body = 1.0 } }
        node Body {}
        node Body {}
    }
}

fn main() {}
