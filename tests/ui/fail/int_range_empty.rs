use shapegen::prelude::*;

generator! {
    pub Ship {
        axiom Start;
        node Start { params { floors: i32 ~ uniform(3..3) } }
    }
}

fn main() {}
