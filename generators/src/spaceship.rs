//! The paper's spaceship generator (ShapeGenetics, Fig. 3): a chain of hull boxes with
//! optional mirrored wing chains and stacked towers, as the original's
//! `SpaceShipGrammar.cpp` derives it.
//!
//! Every `Body`, `Top` and `TopNext` gene emits one box in its own parameters, every
//! `Wing` and `WingNext` gene a mirrored pair of boxes, so every parameter of every gene
//! shapes the model.

use shapegen_runtime::generator;
use shapegen_runtime::genome::Limits;
use shapegen_runtime::ops::OperatorVariant;
use shapegen_runtime::optimize::{
    GaSettings, McmcSettings, McmcVariant, Order, ParentSelection, SmcSettings, SmcVariant,
};
use shapegen_runtime::prelude::*;

use crate::presets::Presets;

generator! {
    /// The spaceship of the paper's volume scene: a hull of boxes along +z, each of
    /// which may carry a mirrored pair of wings and a tower of tops.
    pub Spaceship {
        axiom Start;

        /// The axiom: a unit box at the origin, resized to the first hull box.
        node Start {
            children { body: Body = 1.0 }
            derive(s) {
                if let Some(body) = body {
                    s.resize(body.size).derive(body);
                }
            }
        }

        /// A hull box; the next hull box continues along +z.
        node Body {
            params {
                /// Size relative to the previous hull box (the first: to the unit box).
                size: Vec3 ~ uniform([0.6; 3], [1.5; 3]),
            }
            children { next: Body = 1.0 / 3.0, wing: Wing = 1.0 / 3.0, top: Top = 1.0 / 3.0 }
            derive(s) {
                let s = s.translate(vec3(0.0, 0.0, s.size().z / 2.0));
                s.emit(CUBE);
                if let Some(next) = next {
                    s.translate(vec3(0.0, 0.0, s.size().z / 2.0)).resize(next.size).derive(next);
                }
                if let Some(top) = top {
                    s.translate(vec3(0.0, s.size().y / 2.0, 0.0)).derive(top);
                }
                if let Some(wing) = wing {
                    // One gene, two wings: the left one is the right one turned about z.
                    s.translate(vec3(s.size().x / 2.0, 0.0, 0.0)).derive(wing);
                    s.rotate_z(std::f32::consts::PI)
                        .translate(vec3(s.size().x / 2.0, 0.0, 0.0))
                        .derive(wing);
                }
            }
        }

        /// The first box of a tower on a hull box.
        node Top {
            params {
                /// Size of the tower's first box relative to the hull box it stands on.
                size: Vec3 ~ uniform([0.3, 0.1, 0.3], [0.8, 0.2, 0.8]),
            }
            children { next: TopNext = 1.0 }
            derive(s) { tower_box(s.resize(size), next) }
        }

        /// A further box of a tower, stacked along +y.
        node TopNext {
            params {
                /// Size relative to the box below.
                size: Vec3 ~ uniform([0.6, 0.8, 0.6], [1.1, 1.1, 1.1]),
            }
            children { next: TopNext = 1.0 }
            derive(s) { tower_box(s, next) }
        }

        /// The first box of a wing, shifted along the hull by `shift` of its length.
        node Wing {
            params {
                /// Size of the wing's first box relative to the hull box.
                size: Vec3 ~ uniform([0.3, 0.2, 0.2], [1.2, 0.5, 1.0]),
                /// Shift of the box along the hull (+z), as a fraction of its length.
                shift: f32 ~ uniform(-0.5, 0.5),
            }
            children { next: WingNext = 1.0 }
            derive(s) { wing_box(s.resize(size), shift, next) }
        }

        /// A further box of a wing, continuing outwards along +x.
        node WingNext {
            params {
                /// Size relative to the previous box of the wing.
                size: Vec3 ~ uniform([0.6, 0.9, 0.7], [1.2, 1.0, 1.2]),
                /// Shift along the hull (+z) from the previous box, as a fraction of this
                /// box's length.
                shift: f32 ~ uniform(-0.5, 0.5),
            }
            children { next: WingNext = 0.9 }
            derive(s) { wing_box(s, shift, next) }
        }
    }
}

/// One box of a tower (the original's `TopRuleRecursion`), its scope already sized: it
/// stands on the scope's centre, and the next box, sized by its own parameter, stands on
/// it.
fn tower_box<'a>(s: Shape<'a, Spaceship>, next: Option<Child<'a, TopNext>>) {
    let s = s.translate(vec3(0.0, s.size().y / 2.0, 0.0));
    s.emit(CUBE);
    if let Some(next) = next {
        s.translate(vec3(0.0, s.size().y / 2.0, 0.0))
            .resize(next.size)
            .derive(next);
    }
}

/// One box of a wing (the original's `WingRule` shift followed by
/// `WingRuleRecursion`), its scope already sized: shifted along the hull by `shift` of its
/// length, it continues outwards from the scope's centre, and the next box, sized by its
/// own parameter, continues outwards from it.
fn wing_box<'a>(s: Shape<'a, Spaceship>, shift: f32, next: Option<Child<'a, WingNext>>) {
    let s = s.translate(vec3(0.0, 0.0, s.size().z * shift));
    let s = s.translate(vec3(s.size().x / 2.0, 0.0, 0.0));
    s.emit(CUBE);
    if let Some(next) = next {
        s.translate(vec3(s.size().x / 2.0, 0.0, 0.0))
            .resize(next.size)
            .derive(next);
    }
}

/// The genome limits of the paper's spaceship scene: length 4 to 100, depth 15.
pub const PAPER_LIMITS: Limits = Limits {
    min_len: 4,
    max_len: 100,
    max_depth: 15,
};

/// The original's GA settings for the paper's spaceship-volume scene, as its
/// `run/experiments/spaceship_volume/ga.cfg` sets them: population 150, elitism 30,
/// initial length 50, 130 generations, mutation (`basic_prob`) 30% split grow / cut /
/// alter (`permutate`) 45 / 45 / 10, parents by 10-tournament and roulette, the original's
/// operators.
pub fn paper_ga() -> GaSettings {
    GaSettings {
        population: 150,
        elitism: 30,
        initial_length: 50,
        generations: 130,
        mutation_probability: 0.3,
        grow_weight: 45.0,
        cut_weight: 45.0,
        alter_weight: 10.0,
        tournament: 10,
        selection: ParentSelection::TournamentRoulette,
        operators: OperatorVariant::Original,
        cross_array_index: false,
        // The original has no polishing.
        ..GaSettings::default()
    }
}

/// The original's SMC (`Order::Chromosome`) or SOSMC (`Order::Stochastic`) settings for
/// the paper's spaceship scene (`spaceship_volume/smc.cfg`, `sosmc.cfg`): the original
/// variant, 500 particles, 40 steps, no step back (the files give no `basic_prob`). The
/// generative variant's field holds its default: 64 grows per step.
pub fn paper_smc(order: Order) -> SmcSettings {
    SmcSettings {
        particles: 500,
        steps: 40,
        order,
        variant: SmcVariant::Original,
        step_back_probability: 0.0,
        max_grows_per_step: 64,
        // The original has no polishing.
        ..SmcSettings::default()
    }
}

/// The original's RJMCMC settings for the paper's spaceship scene
/// (`spaceship_volume/mh.cfg`): the original variant, 70 chains, 250 iterations, initial
/// length 50, jump and diffusion 50 / 50. The tempered variant's fields hold its own
/// defaults: delayed rejection 1, annealing by 1.1 every 10 iterations, acceptance 70%
/// hot and 1% cold.
pub fn paper_rjmcmc() -> McmcSettings {
    McmcSettings {
        variant: McmcVariant::Original,
        chains: 70,
        iterations: 250,
        initial_length: 50,
        jump_probability: 0.5,
        ..McmcSettings::default()
    }
}

/// Each method's settings for the paper's spaceship scene: [`paper_ga`], [`paper_smc`]
/// and [`paper_rjmcmc`].
pub fn presets() -> Presets {
    Presets::paper(paper_ga(), paper_smc, paper_rjmcmc())
}
