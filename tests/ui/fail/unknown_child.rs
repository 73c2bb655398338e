use shapegen::prelude::*;

generator! {
    pub Ship {
        axiom Start;
        node Start { children { body: Bdy = 1.0 } }
        node Body {}
    }
}

fn main() {}
