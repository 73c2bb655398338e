//! The published shapegen generators: the spaceship, the three-branch tree and the city
//! of the ShapeGenetics paper, with the exact geometry, ranges and probabilities of the
//! original implementation, so that the paper's targets and cameras line up with them;
//! and a CGA-style building generator whose genomes are building programs.
//!
//! [`Published`] lists them and hands each, as a type, to a [`GeneratorVisitor`]: code
//! that works on every published generator (the facade's registry, which names them at
//! run time by their grammars' keys, benchmarks, tests).

mod meshes;
mod presets;
mod visitor;

pub use building::roofed::RoofedBuilding;
pub use meshes::{LEAF_OBJ, TRUNK_OBJ, default_meshes, low_poly_sphere};
pub use presets::Presets;
pub use visitor::GeneratorVisitor;

use shapegen_runtime::genome::Limits;

/// The published generators, one row each: its variant of [`Published`], the module that
/// holds it (declared here when the row names it with `mod`), its grammar, its genome
/// limits and its methods' presets. Everything that lists or dispatches on published
/// generators is derived from this table: [`Published`], [`Published::ALL`],
/// [`Published::paper_limits`], [`Published::presets`], [`Published::visit`], and through
/// them the facade's registry, the tool's generator list, the benchmarks and the tests
/// that run every generator.
///
/// A generator of one's own is a new module with its `generator!` and one row.
macro_rules! published {
    ($(
        $(#[$doc:meta])*
        $variant:ident $((mod $module:ident))? = $($grammar:ident)::+,
            limits $limits:expr, presets $presets:expr;
    )*) => {
        $($(pub mod $module;)?)*
        $($(pub use $module::$variant;)?)*

        /// One of the published generators.
        #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
        pub enum Published {
            $($(#[$doc])* $variant,)*
        }

        impl Published {
            /// All published generators.
            pub const ALL: [Published; [$(stringify!($variant)),*].len()] =
                [$(Published::$variant),*];

            /// The genome limits of the generator's paper scene ([`building::LIMITS`] for
            /// the buildings, which have none).
            pub const fn paper_limits(self) -> Limits {
                match self {
                    $(Published::$variant => $limits,)*
                }
            }

            /// Each method's settings for the generator's paper scene: the original's
            /// configuration files for the paper's generators; the buildings, which have
            /// no paper scene, breed with the thesis's GA and take the city's settings of
            /// the other methods.
            pub fn presets(self) -> Presets {
                match self {
                    $(Published::$variant => $presets(),)*
                }
            }

            /// Runs `visitor` with this generator's grammar type.
            pub fn visit<V: GeneratorVisitor>(self, visitor: V) -> V::Output {
                let limits = self.paper_limits();
                match self {
                    $(Published::$variant => visitor.visit::<$($grammar)::+>(limits),)*
                }
            }
        }
    };
}

published! {
    /// [`Spaceship`].
    Spaceship (mod spaceship) = spaceship::Spaceship,
        limits spaceship::PAPER_LIMITS, presets spaceship::presets;
    /// [`Tree`].
    Tree (mod tree) = tree::Tree, limits tree::PAPER_LIMITS, presets tree::presets;
    /// [`City`].
    City (mod city) = city::City, limits city::PAPER_LIMITS, presets city::presets;
    /// [`Building`].
    Building (mod building) = building::Building,
        limits building::LIMITS, presets building::presets;
    /// [`RoofedBuilding`].
    RoofedBuilding = building::roofed::RoofedBuilding,
        limits building::LIMITS, presets building::presets;
    /// [`LotBuilding`].
    LotBuilding (mod lot_building) = lot_building::LotBuilding,
        limits lot_building::LIMITS, presets building::presets;
    /// [`Cactus`].
    Cactus (mod cactus) = cactus::Cactus, limits cactus::LIMITS, presets cactus::presets;
}
