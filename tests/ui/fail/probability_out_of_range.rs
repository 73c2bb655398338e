use shapegen::prelude::*;

generator! {
    pub Ship {
        axiom Start;
        node Start { children { body: Body = 1.5 } }
        node Body {}
    }
}

fn main() {}
