//! The published shapegen generators: the spaceship, the three-branch tree and the city
//! of the ShapeGenetics paper, with the exact geometry, ranges and probabilities of the
//! original implementation, so that the paper's targets and cameras line up with them;
//! and a CGA-style building generator whose genomes are building programs.
//!
//! [`Published`] lists them and hands each, as a type, to a [`GeneratorVisitor`]: code
//! that works on every published generator (the facade's registry, which names them at
//! run time by their grammars' keys, benchmarks, tests).

pub mod building;
pub mod city;
pub mod lot_building;
mod meshes;
pub mod spaceship;
pub mod tree;

use shapegen_runtime::Grammar;
use shapegen_runtime::genome::Limits;

pub use building::Building;
pub use building::roofed::RoofedBuilding;
pub use city::City;
pub use lot_building::LotBuilding;
pub use meshes::{LEAF_OBJ, TRUNK_OBJ, default_meshes, low_poly_sphere};
pub use spaceship::Spaceship;
pub use tree::Tree;

/// Code that works on any grammar, run by [`Published::visit`] with the grammar chosen at
/// run time.
pub trait GeneratorVisitor {
    /// What the visit returns.
    type Output;
    /// Runs with grammar `G`, whose published genome limits are `limits`.
    fn visit<G: Grammar>(self, limits: Limits) -> Self::Output;
}

/// One of the published generators.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Published {
    /// [`Spaceship`].
    Spaceship,
    /// [`Tree`].
    Tree,
    /// [`City`].
    City,
    /// [`Building`].
    Building,
    /// [`RoofedBuilding`].
    RoofedBuilding,
    /// [`LotBuilding`].
    LotBuilding,
}

impl Published {
    /// All published generators.
    pub const ALL: [Published; 6] = [
        Published::Spaceship,
        Published::Tree,
        Published::City,
        Published::Building,
        Published::RoofedBuilding,
        Published::LotBuilding,
    ];

    /// The genome limits of the generator's paper scene ([`building::LIMITS`] for the
    /// buildings, which have none).
    pub const fn paper_limits(self) -> Limits {
        match self {
            Published::Spaceship => spaceship::PAPER_LIMITS,
            Published::Tree => tree::PAPER_LIMITS,
            Published::City => city::PAPER_LIMITS,
            Published::Building | Published::RoofedBuilding => building::LIMITS,
            Published::LotBuilding => lot_building::LIMITS,
        }
    }

    /// Runs `visitor` with this generator's grammar type.
    pub fn visit<V: GeneratorVisitor>(self, visitor: V) -> V::Output {
        let limits = self.paper_limits();
        match self {
            Published::Spaceship => visitor.visit::<Spaceship>(limits),
            Published::Tree => visitor.visit::<Tree>(limits),
            Published::City => visitor.visit::<City>(limits),
            Published::Building => visitor.visit::<Building>(limits),
            Published::RoofedBuilding => visitor.visit::<RoofedBuilding>(limits),
            Published::LotBuilding => visitor.visit::<LotBuilding>(limits),
        }
    }
}
