//! Every method returns a best model within the scene's limits, even when the fitness
//! rewards models shorter than `min_len` (as a target that nothing the generator draws
//! overlaps rewards the bare axiom): the record of a run takes a genome outside the
//! limits only until one within them is scored.

use generators::{GeneratorVisitor, Published};
use shapegen::optimize::{
    Best, Budget, FnEvaluator, McmcSettings, McmcVariant, Optimizer, RunResult, Silent,
    SmcSettings, SmcVariant,
};
use shapegen::registry::Registry;
use shapegen::scene::{Method, MethodJob, MethodSettings};
use shapegen::{Genome, Grammar, Limits};

/// A fitness for which shorter is better, or one for which the axiom alone (which
/// draws nothing) beats everything else.
#[derive(Clone, Copy, Debug)]
enum Fitness {
    Shorter,
    Empty,
}

impl Fitness {
    fn of<G: Grammar>(self, g: &Genome<G>) -> f64 {
        match self {
            Fitness::Shorter => -(g.len() as f64),
            Fitness::Empty if g.len() == 1 => 0.0,
            Fitness::Empty => -1.0,
        }
    }
}

/// Runs one method's optimizer for a few generations.
struct Search {
    limits: Limits,
    fitness: Fitness,
}

impl<G: Grammar> MethodJob<G> for Search {
    type Output = RunResult<G>;

    fn run<O: Optimizer<G, Record = Best<G>>>(self, settings: O::Settings) -> RunResult<G> {
        let fitness = self.fitness;
        O::new(settings, self.limits, 3)
            .unwrap()
            .run(
                &mut FnEvaluator(|g: &Genome<G>| fitness.of(g)),
                &Budget::generations(6),
                &mut Silent,
            )
            .unwrap()
    }
}

/// Every method's settings for `presets`, with both variants of SMC and RJMCMC.
fn every_method(presets: &shapegen::registry::Presets) -> Vec<MethodSettings> {
    let mut all = Vec::new();
    for method in Method::ALL {
        let settings = method.preset(presets);
        all.push(settings);
        match settings {
            MethodSettings::Smc(s) | MethodSettings::Sosmc(s) => {
                let variant = SmcVariant::Generative;
                let other = SmcSettings { variant, ..s };
                all.push(match settings {
                    MethodSettings::Smc(_) => MethodSettings::Smc(other),
                    _ => MethodSettings::Sosmc(other),
                });
            }
            MethodSettings::Rjmcmc(s) => all.push(MethodSettings::Rjmcmc(McmcSettings {
                variant: McmcVariant::Tempered,
                ..s
            })),
            _ => {}
        }
    }
    all
}

/// Checks every method on one published generator.
struct EveryMethod<'a>(&'a Registry);

impl GeneratorVisitor for EveryMethod<'_> {
    type Output = ();

    fn visit<G: Grammar>(self, paper: Limits) -> Self::Output {
        let limits = Limits::new(6, paper.max_len, paper.max_depth).unwrap();
        let presets = &self.0.find(G::GRAPH.key).unwrap().defaults.presets;
        for settings in every_method(presets) {
            for fitness in [Fitness::Shorter, Fitness::Empty] {
                let r = settings.run::<G, _>(Search { limits, fitness });
                let what = format!(
                    "{} with {settings:?} for {fitness:?}: {} genes, depth {}",
                    G::GRAPH.key,
                    r.best.len(),
                    r.best.depth()
                );
                assert!(r.best.validate_limits(&limits).is_ok(), "{what}");
                assert_eq!(r.best_fitness, fitness.of(&r.best), "{what}");
            }
        }
    }
}

#[test]
fn every_method_returns_a_best_within_the_limits() {
    let registry = Registry::published();
    for generator in Published::ALL {
        generator.visit(EveryMethod(&registry));
    }
}
