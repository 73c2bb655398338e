use shapegen::prelude::*;

const HALF: f32 = 0.5;

generator! {
    pub Ship {
        axiom Start;
        node Start { children { body: Body = HALF } }
        node Body {}
    }
}

fn main() {
    let _ = HALF;
}
