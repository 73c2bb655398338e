use shapegen::prelude::*;

generator! {
    pub City {
        axiom Start;
        node Start { children { lots: [Lot; 0] = 0.33 } }
        node Lot {}
    }
}

fn main() {}
