use shapegen::prelude::*;

generator! {
    pub Ship {
        node Start {}
    }
}

fn main() {}
