//! Every method scores only genomes within the limits it keeps (`Settings::kept_limits`:
//! the scene's, or fewer where a method follows the original's rules), and returns the
//! best of them, even when the fitness rewards models shorter than `min_len` (as a target
//! that nothing the generator draws overlaps rewards the bare axiom).

use generators::{GeneratorVisitor, Published};
use shapegen::optimize::{
    Best, Budget, FnEvaluator, McmcSettings, McmcVariant, Optimizer, RunResult, Settings, Silent,
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
    /// The run's result, and the limits the method keeps.
    type Output = (RunResult<G>, Limits);

    fn run<O: Optimizer<G, Record = Best<G>>>(self, settings: O::Settings) -> Self::Output {
        let fitness = self.fitness;
        let kept = settings.kept_limits(self.limits);
        let mut scored = 0;
        let evaluate = |g: &Genome<G>| {
            // Every genome scored keeps the limits the method keeps.
            if let Err(e) = g.validate_limits(&kept) {
                panic!("scored outside {kept:?}: {e}");
            }
            scored += 1;
            fitness.of(g)
        };
        let result = O::new(settings, self.limits, 3)
            .unwrap()
            .run(
                &mut FnEvaluator(evaluate),
                &Budget::generations(6),
                &mut Silent,
            )
            .unwrap();
        assert!(scored > 0);
        (result, kept)
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
                let (r, kept) = settings.run::<G, _>(Search { limits, fitness });
                let what = format!(
                    "{} with {settings:?} for {fitness:?}: {} genes, depth {}",
                    G::GRAPH.key,
                    r.best.len(),
                    r.best.depth()
                );
                assert!(r.best.validate_limits(&kept).is_ok(), "{what}");
                assert_eq!(r.best_fitness, fitness.of(&r.best), "{what}");
                // The best is the best scored: never below a generation's best or mean.
                for h in &r.history {
                    assert!(h.best >= h.mean, "{what}: {h:?}");
                }
                let top = r.history.iter().map(|h| h.best).fold(f64::MIN, f64::max);
                assert_eq!(r.best_fitness, top, "{what}");
            }
        }
    }
}

#[test]
fn every_method_scores_within_the_limits_it_keeps_and_returns_the_best_it_scored() {
    let registry = Registry::published();
    for generator in Published::ALL {
        generator.visit(EveryMethod(&registry));
    }
}
