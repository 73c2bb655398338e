//! The paper's city generator (ShapeGenetics Fig. 9): 100 lots on a grid, each of which
//! may hold one box building, placed as the original's `CityGrammar.cpp` places them.
//!
//! The original makes each lot a symbol of its own, `Lot_i_j`, created in the order
//! `k = i + 10 j` with symbol id `k + 4` (ids 0 to 3 are taken by other symbols), and
//! places a lot by its *symbol id*: at grid cell `(id % 10, id / 10)`. So the grid is
//! shifted by four cells against a centred 10 x 10 grid, and the last four lots lie on an
//! eleventh row. [`lot_position`] reproduces this bit for bit; lot `k` of the `lots` array
//! is the original's `Lot_i_j` with `k = i + 10 j`.

use shapegen_runtime::generator;
use shapegen_runtime::genome::Limits;
use shapegen_runtime::optimize::{GaSettings, McmcSettings, Order, SmcSettings};
use shapegen_runtime::prelude::*;

use crate::presets::Presets;

/// Lots per row of the grid (the original's `GridX`).
pub const GRID: usize = 10;
/// Distance between the centres of neighbouring lots.
pub const LOT_SPACING: f32 = 2.2;

generator! {
    /// The city of the paper's skyline scenes.
    pub City {
        axiom Start;

        /// The city: lot `k` lies at [`lot_position`]`(k)`.
        node Start {
            children { lots: [Lot; 100] = 0.33 }
            derive(s) {
                for (k, lot) in lots.iter() {
                    s.translate(lot_position(k)).derive(lot);
                }
            }
        }

        /// A lot: holds its building.
        node Lot {
            children { building: Building = 1.0 }
        }

        /// A box building standing on its lot, turned about the vertical.
        node Building {
            params {
                /// Width (x) and depth (z) of the building.
                footprint: Vec2 ~ uniform([0.44; 2], [1.98; 2]),
                /// Height of the building.
                height: f32 ~ uniform(0.36, 10.0),
                /// Height of one storey, for detailed facades; the box building does not
                /// use it.
                floor_height: f32 ~ uniform(0.24, 0.36),
                /// Turn about the vertical.
                rotation: f32 ~ radians(0.0, PI),
            }
            derive(s) {
                s.rotate_y(rotation)
                    .with_size(vec3(footprint.x, height, footprint.y))
                    .translate(vec3(0.0, height / 2.0, 0.0))
                    .emit(CUBE);
            }
        }
    }
}

/// Symbol id of the original's first lot, `Lot_0_0`; lot `k` has id `k + FIRST_LOT_ID`.
pub const FIRST_LOT_ID: usize = 4;

/// Centre of lot `k` on the ground plane, as the original computes it: the lot's grid
/// cell is `(cx, cz) = ((k + 4) % 10, (k + 4) / 10)`, and each coordinate is
/// `0.1 * -99 + 0.1 * (22 * c)` in `f32` (the original's base size of 22 and output scale
/// of 0.1), so x and z run from -9.9 in steps of 2.2.
///
/// ```
/// use generators::city::lot_position;
/// use glam::vec3;
///
/// assert_eq!(lot_position(0), vec3(0.1 * -99.0 + 0.1 * 88.0, 0.0, 0.1 * -99.0)); // Lot_0_0
/// assert!(lot_position(6).abs_diff_eq(vec3(-9.9, 0.0, -7.7), 1e-6)); // Lot_6_0
/// assert!(lot_position(99).abs_diff_eq(vec3(-3.3, 0.0, 12.1), 1e-6)); // Lot_9_9
/// ```
pub fn lot_position(k: usize) -> Vec3 {
    let id = k + FIRST_LOT_ID;
    let start = 0.1_f32 * ((1.0 - GRID as f32) * 0.5 * BASE_SIZE);
    let coordinate = |cell: usize| start + 0.1_f32 * (cell as f32 * BASE_SIZE);
    vec3(coordinate(id % GRID), 0.0, coordinate(id / GRID))
}

/// The original's lot size before its output scale of 0.1: lots are
/// [`LOT_SPACING`] apart.
const BASE_SIZE: f32 = 22.0;

/// The genome limits of the paper's city scene: length 4 to 300, depth 8.
pub const PAPER_LIMITS: Limits = Limits {
    min_len: 4,
    max_len: 300,
    max_depth: 8,
};

/// The original's GA settings for the paper's city-skyline (whale) scene, as its
/// `run/experiments/city_whale/ga.cfg` sets them: population 100, elitism 30, initial
/// length 50, 100 generations, mutation 30% split 45 / 45 / 10, tournament of 10, the
/// original's operators.
pub fn paper_ga() -> GaSettings {
    GaSettings {
        population: 100,
        initial_length: 50,
        generations: 100,
        ..crate::spaceship::paper_ga()
    }
}

/// The original's SMC or SOSMC settings for the paper's city-whale scene
/// (`city_whale/smc.cfg`, `sosmc.cfg`): 100 particles, 100 steps; the rest as the
/// spaceship's ([`crate::spaceship::paper_smc`]).
pub fn paper_smc(order: Order) -> SmcSettings {
    SmcSettings {
        particles: 100,
        steps: 100,
        ..crate::spaceship::paper_smc(order)
    }
}

/// The original's RJMCMC settings for the paper's city-whale scene (`city_whale/mh.cfg`):
/// 50 chains, 200 iterations, initial length 50; the rest as the spaceship's
/// ([`crate::spaceship::paper_rjmcmc`]).
pub fn paper_rjmcmc() -> McmcSettings {
    McmcSettings {
        chains: 50,
        iterations: 200,
        ..crate::spaceship::paper_rjmcmc()
    }
}

/// Each method's settings for the paper's city scene: [`paper_ga`], [`paper_smc`] and
/// [`paper_rjmcmc`].
pub fn presets() -> Presets {
    Presets::paper(paper_ga(), paper_smc, paper_rjmcmc())
}
