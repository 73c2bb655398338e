//! A `meshes` block: constants for the meshes a generator emits besides the cube.
#![deny(warnings, unused_qualifications)]

use shapegen::prelude::*;

generator! {
    pub Tree {
        axiom Trunk;
        meshes {
            /// The branch mesh.
            TRUNK = "trunk",
            LEAF = "leaf",
        }
        node Trunk {
            children { branch: Branch = 0.5 }
            derive(s) {
                s.emit(TRUNK);
                match branch {
                    Some(b) => s.translate(vec3(0.0, s.size().y, 0.0)).derive(b),
                    None => s.emit_unscaled(LEAF),
                }
            }
        }
        node Branch {
            children { next: Branch = 0.5 }
            derive(s) {
                s.emit(TRUNK);
                s.emit(CUBE);
                if let Some(next) = next {
                    s.derive(next);
                }
            }
        }
    }
}

fn main() {
    assert_eq!(Tree::GRAPH.meshes, ["cube", "trunk", "leaf"]);
    assert_eq!(CUBE, MeshId(0));
    assert_eq!(TRUNK, MeshId(1));
    assert_eq!(LEAF, MeshId(2));
}
