use shapegen::prelude::*;

generator! {
    pub Ship {
        axiom Start;
        node Start { child { body: Body = 1.0 } }
        node Body {}
    }
}

fn main() {}
