use shapegen::prelude::*;

generator! {
    pub Ship {
        axiom Start;
        axiom Body;
        node Start { children { body: Body = 1.0 } }
        node Body {}
    }
}

fn main() {}
