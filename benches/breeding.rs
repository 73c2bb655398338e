//! The four operators, each applied on its own to make one child, for the benchmarks of
//! scoring bred children.

use rand::Rng;
use shapegen::ops::Operators;
use shapegen::{Genome, Grammar};

/// One of the four operators.
#[derive(Clone, Copy)]
pub enum Op {
    /// `Operators::grow`.
    Grow,
    /// `Operators::cut`.
    Cut,
    /// `Operators::alter`.
    Alter,
    /// `Operators::crossover`.
    Crossover,
}

impl Op {
    /// The four, in this order.
    pub const ALL: [Op; 4] = [Op::Grow, Op::Cut, Op::Alter, Op::Crossover];

    /// The operator's name, for a benchmark's id.
    pub fn name(self) -> &'static str {
        match self {
            Op::Grow => "grow",
            Op::Cut => "cut",
            Op::Alter => "alter",
            Op::Crossover => "crossover",
        }
    }

    /// A child of `parent` by this operator (the crossover's partner a random genome of
    /// `initial` genes, its first child kept; the parent itself when no crossover
    /// point matches).
    pub fn child<G: Grammar>(
        self,
        ops: &mut Operators<G>,
        parent: &Genome<G>,
        initial: u32,
        rng: &mut impl Rng,
    ) -> Genome<G> {
        let mut child = parent.clone();
        match self {
            Op::Grow => {
                ops.grow(&mut child, rng);
            }
            Op::Cut => {
                ops.cut(&mut child, rng);
            }
            Op::Alter => {
                ops.alter(&mut child, rng);
            }
            Op::Crossover => {
                let other = ops.random(initial, rng);
                if let Some((a, _)) = ops.crossover(parent, &other, rng) {
                    child = a;
                }
            }
        }
        child
    }
}
