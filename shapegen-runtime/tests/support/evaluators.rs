//! Cheap deterministic evaluators computed from the derived instances of the published
//! generators, and the history compared between runs, shared by the optimizer tests.

use generators::{City, Spaceship};
use glam::Vec3;
use shapegen_runtime::optimize::{EvaluateError, Evaluator, HistoryEntry};
use shapegen_runtime::{Genome, Instance};

/// City: buildings taller than 5 count 1 each, shorter ones cost 0.3 each.
pub struct Skyline {
    instances: Vec<Instance>,
    /// The calls of `evaluate`.
    pub calls: u64,
    /// The genomes scored by `evaluate`.
    pub genomes: u64,
}

impl Skyline {
    pub fn new() -> Self {
        Skyline {
            instances: Vec::new(),
            calls: 0,
            genomes: 0,
        }
    }

    pub fn score(&mut self, g: &Genome<City>) -> f64 {
        g.derive_into(&mut self.instances);
        self.instances
            .iter()
            .map(|i| {
                if i.transform.matrix3.y_axis.length() > 5.0 {
                    1.0
                } else {
                    -0.3
                }
            })
            .sum()
    }
}

impl Evaluator<City> for Skyline {
    fn evaluate(&mut self, genomes: &[Genome<City>], out: &mut [f64]) -> Result<(), EvaluateError> {
        self.calls += 1;
        self.genomes += genomes.len() as u64;
        for (g, o) in genomes.iter().zip(out) {
            *o = self.score(g);
        }
        Ok(())
    }
}

/// Spaceship: minus the L1 distance of the model's bounding box to a target box.
pub struct BoxTarget {
    instances: Vec<Instance>,
}

impl BoxTarget {
    pub const MIN: Vec3 = Vec3::new(-2.0, -0.5, -4.0);
    pub const MAX: Vec3 = Vec3::new(2.0, 0.5, 4.0);

    pub fn new() -> Self {
        BoxTarget {
            instances: Vec::new(),
        }
    }
}

impl Evaluator<Spaceship> for BoxTarget {
    fn evaluate(
        &mut self,
        genomes: &[Genome<Spaceship>],
        out: &mut [f64],
    ) -> Result<(), EvaluateError> {
        for (g, o) in genomes.iter().zip(out) {
            g.derive_into(&mut self.instances);
            let (mut lo, mut hi) = (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY));
            for i in &self.instances {
                let m = i.transform.matrix3;
                let half = (m.x_axis.abs() + m.y_axis.abs() + m.z_axis.abs()) * 0.5;
                let c = Vec3::from(i.transform.translation);
                lo = lo.min(c - Vec3::from(half));
                hi = hi.max(c + Vec3::from(half));
            }
            *o = if self.instances.is_empty() {
                -100.0
            } else {
                -f64::from(
                    (lo - BoxTarget::MIN).abs().element_sum()
                        + (hi - BoxTarget::MAX).abs().element_sum(),
                )
            };
        }
        Ok(())
    }
}

/// The history without wall-clock times, which differ between runs.
pub fn timeless(h: &[HistoryEntry]) -> Vec<(u64, u64, u64, u64, u64)> {
    h.iter()
        .map(|e| {
            (
                e.generation,
                e.evaluations,
                e.best.to_bits(),
                e.mean.to_bits(),
                e.std.to_bits(),
            )
        })
        .collect()
}
