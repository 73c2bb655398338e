//! The paper's three-branch tree generator ("v2", ShapeGenetics Fig. 1 and 7).
//!
//! Each branch has up to three children, one per third of the circle; a branch without
//! children ends in a leaf.

use shapegen_runtime::generator;
use shapegen_runtime::genome::Limits;
use shapegen_runtime::optimize::{GaSettings, McmcSettings, Order, SmcSettings};
use shapegen_runtime::prelude::*;

use crate::presets::Presets;

generator! {
    /// The tree of the paper's sketch scene.
    pub Tree {
        axiom Start;
        meshes {
            /// The branch and trunk mesh ([`TRUNK_OBJ`](crate::TRUNK_OBJ) in
            /// [`default_meshes`](crate::default_meshes)), scaled to each branch.
            TRUNK = "trunk",
            /// The leaf mesh ([`LEAF_OBJ`](crate::LEAF_OBJ) in
            /// [`default_meshes`](crate::default_meshes)), placed unscaled.
            LEAF = "leaf",
        }

        /// The axiom: a unit box at the origin.
        node Start {
            children { trunk: Trunk = 1.0 }
        }

        /// The trunk; branches grow from near its top.
        node Trunk {
            params {
                /// Size of the trunk.
                size: Vec3 ~ uniform([0.8, 1.4, 0.8], [0.8, 1.8, 0.8]),
            }
            children { b1: B1 = 1.0 / 3.0, b2: B2 = 1.0 / 3.0, b3: B3 = 1.0 / 3.0 }
            derive(s) {
                let s = s.resize(size);
                s.emit(TRUNK);
                grow_branches(s, b1, b2, b3);
            }
        }

        /// A branch turned into the first third of the circle.
        node B1 {
            params {
                /// Size relative to the branch (or trunk) it grows from.
                size: Vec3 ~ uniform([0.6, 0.6, 0.6], [0.7, 0.801, 0.7]),
                /// Turn about the parent's axis, within this branch's third of the circle.
                yaw: f32 ~ degrees(0.0, 120.0),
                /// Lean away from the parent's axis.
                tilt: f32 ~ degrees(35.0, 85.0),
                /// A small turn about the branch's own axis.
                twist: f32 ~ degrees(-3.0, 3.0),
            }
            children { b1: B1 = 1.0 / 3.0, b2: B2 = 1.0 / 3.0, b3: B3 = 1.0 / 3.0 }
            derive(s) { branch(s, size, yaw, tilt, twist, b1, b2, b3) }
        }

        /// A branch turned into the second third of the circle.
        node B2 {
            params {
                /// Size relative to the branch (or trunk) it grows from.
                size: Vec3 ~ uniform([0.6, 0.6, 0.6], [0.7, 0.801, 0.7]),
                /// Turn about the parent's axis, within this branch's third of the circle.
                yaw: f32 ~ degrees(120.0, 240.0),
                /// Lean away from the parent's axis.
                tilt: f32 ~ degrees(35.0, 85.0),
                /// A small turn about the branch's own axis.
                twist: f32 ~ degrees(-3.0, 3.0),
            }
            children { b1: B1 = 1.0 / 3.0, b2: B2 = 1.0 / 3.0, b3: B3 = 1.0 / 3.0 }
            derive(s) { branch(s, size, yaw, tilt, twist, b1, b2, b3) }
        }

        /// A branch turned into the last third of the circle.
        node B3 {
            params {
                /// Size relative to the branch (or trunk) it grows from.
                size: Vec3 ~ uniform([0.6, 0.6, 0.6], [0.7, 0.801, 0.7]),
                /// Turn about the parent's axis, within this branch's third of the circle.
                yaw: f32 ~ degrees(240.0, 360.0),
                /// Lean away from the parent's axis.
                tilt: f32 ~ degrees(35.0, 85.0),
                /// A small turn about the branch's own axis.
                twist: f32 ~ degrees(-3.0, 3.0),
            }
            children { b1: B1 = 1.0 / 3.0, b2: B2 = 1.0 / 3.0, b3: B3 = 1.0 / 3.0 }
            derive(s) { branch(s, size, yaw, tilt, twist, b1, b2, b3) }
        }
    }
}

/// The rule shared by the three branch nodes: place the branch on its parent, emit it,
/// then grow its children from it, or end it with a leaf when it has none.
#[allow(clippy::too_many_arguments)]
fn branch<'a>(
    s: Shape<'a, Tree>,
    size: Vec3,
    yaw: f32,
    tilt: f32,
    twist: f32,
    b1: Option<Child<'a, B1>>,
    b2: Option<Child<'a, B2>>,
    b3: Option<Child<'a, B3>>,
) {
    let s = s.rotate_y(yaw);
    let s = s
        .translate(vec3(0.0, 0.38 * s.size().y, 0.0))
        .rotate_z(tilt)
        .resize(size);
    let s = s
        .translate(vec3(0.0, s.size().y / 2.0, 0.0))
        .rotate_y(twist);
    s.emit(TRUNK);
    if b1.is_none() && b2.is_none() && b3.is_none() {
        s.translate(vec3(0.0, 0.75 * s.size().y, 0.0))
            .emit_unscaled(LEAF);
    } else {
        grow_branches(s, b1, b2, b3);
    }
}

/// Derives each present branch child from the same scope.
fn grow_branches<'a>(
    s: Shape<'a, Tree>,
    b1: Option<Child<'a, B1>>,
    b2: Option<Child<'a, B2>>,
    b3: Option<Child<'a, B3>>,
) {
    if let Some(b) = b1 {
        s.derive(b);
    }
    if let Some(b) = b2 {
        s.derive(b);
    }
    if let Some(b) = b3 {
        s.derive(b);
    }
}

/// The genome limits of the paper's tree scene: length 4 to 400, depth 12.
pub const PAPER_LIMITS: Limits = Limits {
    min_len: 4,
    max_len: 400,
    max_depth: 12,
};

/// The original's GA settings for the paper's tree-sketch scene, as its
/// `run/experiments/tree_sketch1/ga.cfg` sets them: population 200, elitism 30, initial
/// length 250, 1500 generations, mutation 30% split 35 / 35 / 30, tournament of 10, the
/// original's operators.
pub fn paper_ga() -> GaSettings {
    GaSettings {
        population: 200,
        initial_length: 250,
        generations: 1500,
        grow_weight: 35.0,
        cut_weight: 35.0,
        alter_weight: 30.0,
        ..crate::spaceship::paper_ga()
    }
}

/// The original's SMC or SOSMC settings for the paper's tree-sketch scene
/// (`tree_sketch1/smc.cfg`, `sosmc.cfg`): 1000 particles, 500 steps; the rest as the
/// spaceship's ([`crate::spaceship::paper_smc`]).
pub fn paper_smc(order: Order) -> SmcSettings {
    SmcSettings {
        particles: 1000,
        steps: 500,
        ..crate::spaceship::paper_smc(order)
    }
}

/// The original's RJMCMC settings for the paper's tree-sketch scene
/// (`tree_sketch1/mh.cfg`): 100 chains, 3000 iterations, initial length 150; the rest
/// as the spaceship's ([`crate::spaceship::paper_rjmcmc`]).
pub fn paper_rjmcmc() -> McmcSettings {
    McmcSettings {
        chains: 100,
        iterations: 3000,
        initial_length: 150,
        ..crate::spaceship::paper_rjmcmc()
    }
}

/// Each method's settings for the paper's tree-sketch scene: [`paper_ga`], [`paper_smc`]
/// and [`paper_rjmcmc`].
pub fn presets() -> Presets {
    Presets::paper(paper_ga(), paper_smc, paper_rjmcmc())
}
