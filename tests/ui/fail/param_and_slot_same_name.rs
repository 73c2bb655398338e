use shapegen::prelude::*;

generator! {
    pub Ship {
        axiom Start;
        node Start {
            params { wing: f32 ~ uniform(0.0, 1.0) }
            children { wing: Wing = 0.5 }
        }
        node Wing {}
    }
}

fn main() {}
