//! The paper's city generator (ShapeGenetics Fig. 9): a 10 x 10 grid of lots, each of
//! which may hold one box building.

use shapegen_runtime::generator;
use shapegen_runtime::genome::Limits;
use shapegen_runtime::prelude::*;

/// Lots per side of the grid.
pub const GRID: usize = 10;
/// Distance between the centres of neighbouring lots.
pub const LOT_SPACING: f32 = 2.2;

generator! {
    /// The city of the paper's skyline scenes.
    pub City {
        axiom Start;

        /// The grid: lot `k` lies at row `k / 10`, column `k % 10`.
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

/// Centre of lot `k` on the ground plane, relative to the grid's centre.
pub fn lot_position(k: usize) -> Vec3 {
    let offset = -(GRID as f32 - 1.0) * LOT_SPACING / 2.0;
    vec3(
        offset + LOT_SPACING * (k / GRID) as f32,
        0.0,
        offset + LOT_SPACING * (k % GRID) as f32,
    )
}

/// The genome limits of the paper's city scene: length 4 to 300, depth 8.
pub const PAPER_LIMITS: Limits = Limits {
    min_len: 4,
    max_len: 300,
    max_depth: 8,
};
