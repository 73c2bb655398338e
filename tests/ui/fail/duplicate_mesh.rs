use shapegen::prelude::*;

generator! {
    pub Tree {
        axiom Trunk;
        meshes { TRUNK = "trunk", BARK = "trunk" }
        node Trunk { derive(s) { s.emit(TRUNK); } }
    }
}

fn main() {}
