//! Doc comments and attributes pass through to the generated items.
#![deny(warnings, unused_qualifications)]

use shapegen::prelude::*;

generator! {
    /// A generator with documentation everywhere.
    #[derive(Debug, Default, Clone, Copy)]
    pub(crate) Documented {
        axiom Root;
        meshes {
            /// A mesh.
            #[allow(dead_code)]
            PANEL = "panel",
        }
        /// The root node.
        #[derive(Default)]
        node Root {
            params {
                /// How tall the root is.
                #[allow(dead_code)]
                height: f32 ~ uniform(1.0, 2.0),
            }
            children {
                /// The only child.
                leaf: Leaf = 0.5,
            }
            derive(s) {
                if let Some(leaf) = leaf {
                    s.translate(vec3(0.0, height, 0.0)).derive(leaf);
                }
            }
        }
        /// A leaf.
        node Leaf {}
    }
}

fn main() {
    let g = Documented;
    assert_eq!(format!("{g:?}"), "Documented");
    assert_eq!(Root::default().height, 0.0);
    assert_eq!(Leaf {}, Leaf {});
}
