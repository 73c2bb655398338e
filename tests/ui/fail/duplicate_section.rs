use shapegen::prelude::*;

generator! {
    pub Ship {
        axiom Start;
        node Start {
            params { a: f32 ~ uniform(0.0, 1.0) }
            params { b: f32 ~ uniform(0.0, 1.0) }
        }
    }
}

fn main() {}
