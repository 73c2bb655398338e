//! A saguaro cactus: a column of stacked segments from which arms reach out sideways and
//! turn upward, each arm a column of its own. A small generator whose models are tall,
//! branching silhouettes, for sketches and volumes that the tree's canopy does not fit.
//!
//! ```
//! use generators::Cactus;
//! use generators::cactus::LIMITS;
//! use rand::SeedableRng;
//! use shapegen_runtime::ops::Operators;
//!
//! let mut ops = Operators::<Cactus>::new(LIMITS)?;
//! let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(1);
//! let mut instances = Vec::new();
//! for _ in 0..50 {
//!     ops.random(20, &mut rng).derive_into(&mut instances);
//!     // Every box of a cactus stands on or above the ground.
//!     for i in &instances {
//!         let lowest = [-0.5f32, 0.5]
//!             .iter()
//!             .flat_map(|&y| [-0.5f32, 0.5].map(|x| (x, y)))
//!             .flat_map(|(x, y)| [-0.5f32, 0.5].map(|z| glam::vec3(x, y, z)))
//!             .map(|corner| i.transform.transform_point3(corner).y)
//!             .fold(f32::INFINITY, f32::min);
//!         assert!(lowest > -1e-4, "{lowest}");
//!     }
//! }
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use shapegen_runtime::generator;
use shapegen_runtime::genome::Limits;
use shapegen_runtime::prelude::*;

use crate::presets::Presets;

generator! {
    /// A saguaro cactus of stacked segments and upturned arms.
    pub Cactus {
        axiom Start;

        /// The ground: the trunk stands on the origin, one unit wide.
        node Start {
            children { trunk: Segment = 1.0 }
            derive(s) {
                if let Some(trunk) = trunk {
                    s.with_size(vec3(1.0, 0.0, 1.0)).derive(trunk);
                }
            }
        }

        /// A segment of a column, standing on the scope's centre, as wide as the scope
        /// times `taper` and `height` times as tall as wide; the next segment stands on it
        /// and its arms grow from its sides.
        node Segment {
            params {
                /// Width relative to the segment (or arm) below.
                taper: f32 ~ uniform(0.9, 1.0),
                /// Height relative to the segment's width.
                height: f32 ~ uniform(1.0, 2.0),
            }
            children { next: Segment = 0.6, arms: [Arm; 2] = 0.25 }
            derive(s) {
                let width = s.size().x * taper;
                let height = height * width;
                let body = s
                    .with_size(vec3(width, height, width))
                    .translate(vec3(0.0, height / 2.0, 0.0));
                body.emit(CUBE);
                if let Some(next) = next {
                    s.with_size(vec3(width, 0.0, width))
                        .translate(vec3(0.0, height, 0.0))
                        .derive(next);
                }
                for (_, arm) in arms.iter() {
                    body.derive(arm);
                }
            }
        }

        /// An arm: a horizontal piece from the middle of its segment outward, at a
        /// fraction `at` of the segment's height and turned by `turn` about it, thinner
        /// than the segment; the column of its `up` segment stands on its outer end.
        node Arm {
            params {
                /// Where along the segment's height the arm leaves it.
                at: f32 ~ uniform(0.5, 0.9),
                /// Turn about the segment's vertical axis.
                turn: f32 ~ degrees(0.0, 360.0),
                /// How far the arm reaches beyond the segment's side, relative to the
                /// segment's width.
                reach: f32 ~ uniform(0.3, 0.9),
                /// Thickness relative to the segment.
                thickness: f32 ~ uniform(0.45, 0.7),
            }
            children { up: Segment = 0.9 }
            derive(s) {
                let size = s.size();
                let t = size.x * thickness;
                let length = size.x * (0.5 + reach);
                let base = s
                    .translate(vec3(0.0, (at - 0.5) * size.y, 0.0))
                    .rotate_y(turn);
                base.with_size(vec3(length, t, t))
                    .translate(vec3(length / 2.0, 0.0, 0.0))
                    .emit(CUBE);
                if let Some(up) = up {
                    base.with_size(vec3(t, 0.0, t))
                        .translate(vec3(length - t / 2.0, t / 2.0, 0.0))
                        .derive(up);
                }
            }
        }
    }
}

/// The cactus's genome limits: 2 to 80 genes, depth 16.
pub const LIMITS: Limits = Limits {
    min_len: 2,
    max_len: 80,
    max_depth: 16,
};

/// Each method's own settings: the cactus has no paper scene.
pub fn presets() -> Presets {
    Presets::default()
}
