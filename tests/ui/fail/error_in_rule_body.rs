//! Mistakes in a rule's body are the compiler's, reported on the user's own tokens.
use shapegen::prelude::*;

generator! {
    pub Ship {
        axiom Start;
        node Start {
            params { size: Vec3 ~ uniform([0.5; 3], [1.0; 3]) }
            derive(s) {
                let count: u32 = size;
                s.emit(CUBE);
                let _ = count;
            }
        }
    }
}

fn main() {}
