//! Every method, run on a published generator with a fixed seed and a small budget, gives
//! exactly the result recorded from the code before the optimizers shared one driver: the
//! best fitness to the bit, the evaluations, the generations, and hashes of the best
//! genome's JSON and of the history without its wall times.
//!
//! Set `REGRESSION_PRINT=1` to print the values instead of checking them.

mod support {
    pub mod evaluators;
}

use generators::{City, Spaceship};
use shapegen_runtime::ops::OperatorVariant;
use shapegen_runtime::optimize::multi::{
    MultiEvaluator, MultiGa, MultiGaSettings, MultiHistoryEntry,
};
use shapegen_runtime::optimize::*;
use shapegen_runtime::prelude::*;
use support::evaluators::{BoxTarget, Skyline, timeless};

/// FNV-1a, stable across Rust versions (unlike `DefaultHasher`).
fn fnv(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |h, &b| {
        (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3)
    })
}

/// City on two objectives: tall buildings (maximized) and instances (minimized).
struct TallAndFew(Vec<Instance>);

impl MultiEvaluator<City> for TallAndFew {
    fn senses(&self) -> &[Sense] {
        &[Sense::Maximize, Sense::Minimize]
    }

    fn evaluate(&mut self, genomes: &[Genome<City>], out: &mut [f64]) -> Result<(), EvaluateError> {
        for (g, o) in genomes.iter().zip(out.chunks_exact_mut(2)) {
            g.derive_into(&mut self.0);
            let tall = self
                .0
                .iter()
                .filter(|i| i.transform.matrix3.y_axis.length() > 5.0)
                .count();
            o.copy_from_slice(&[tall as f64, self.0.len() as f64]);
        }
        Ok(())
    }
}

/// What a run is checked on.
#[derive(Debug, PartialEq, Eq)]
struct Outcome {
    best_bits: u64,
    evaluations: u64,
    generations: u64,
    genome_hash: u64,
    history_hash: u64,
}

fn outcome<G: Grammar>(r: &RunResult<G>) -> Outcome {
    let history = timeless(&r.history);
    Outcome {
        best_bits: r.best_fitness.to_bits(),
        evaluations: r.evaluations,
        generations: r.generations,
        genome_hash: fnv(serde_json::to_string(&r.best).unwrap().as_bytes()),
        history_hash: fnv(format!("{history:?}").as_bytes()),
    }
}

fn check(name: &str, got: Outcome, want: Outcome) {
    if std::env::var_os("REGRESSION_PRINT").is_some() {
        println!("{name}: {got:?}");
    } else {
        assert_eq!(got, want, "{name}");
    }
}

fn limits() -> Limits {
    Limits::new(1, 200, 12).unwrap()
}

#[test]
fn ga_both_operator_variants() {
    let want = [
        Outcome {
            best_bits: 4623507967449235456,
            evaluations: 294,
            generations: 11,
            genome_hash: 8711122248305110249,
            history_hash: 17239495617711528188,
        },
        Outcome {
            best_bits: 4622382067542392832,
            evaluations: 294,
            generations: 11,
            genome_hash: 15023418641712652046,
            history_hash: 7620854359040629333,
        },
    ];
    for (operators, want) in [OperatorVariant::Weighted, OperatorVariant::Original]
        .into_iter()
        .zip(want)
    {
        let settings = GaSettings {
            population: 30,
            elitism: 6,
            initial_length: 20,
            operators,
            ..generators::city::paper_ga()
        };
        let r = Ga::<City>::new(settings, limits(), 11)
            .unwrap()
            .run(
                &mut Skyline::new(),
                &Budget::generations(12).and_evaluations(300),
                &mut Silent,
            )
            .unwrap();
        check(&format!("ga {operators:?}"), outcome(&r), want);
    }
}

#[test]
fn smc_and_sosmc_both_variants() {
    let want = [
        Outcome {
            best_bits: 4617315517961601024,
            evaluations: 264,
            generations: 10,
            genome_hash: 3939229097042858477,
            history_hash: 17130620413223421019,
        },
        Outcome {
            best_bits: 4621819117588971520,
            evaluations: 264,
            generations: 10,
            genome_hash: 12342590915289218177,
            history_hash: 8040290443546235320,
        },
        Outcome {
            best_bits: 4617315517961601024,
            evaluations: 264,
            generations: 10,
            genome_hash: 8320711979411910514,
            history_hash: 11393561947858530537,
        },
        Outcome {
            best_bits: 4621819117588971520,
            evaluations: 264,
            generations: 10,
            genome_hash: 1904014923420052385,
            history_hash: 2994886994982155504,
        },
    ];
    let runs = [Order::Chromosome, Order::Stochastic]
        .into_iter()
        .flat_map(|order| SmcVariant::ALL.map(|variant| (order, variant)));
    for ((order, variant), want) in runs.zip(want) {
        let settings = SmcSettings {
            particles: 24,
            variant,
            ..generators::city::paper_smc(order)
        };
        let r = Smc::<City>::new(settings, limits(), 5)
            .unwrap()
            .run(&mut Skyline::new(), &Budget::generations(10), &mut Silent)
            .unwrap();
        check(&format!("smc {order:?} {variant:?}"), outcome(&r), want);
    }
}

#[test]
fn rjmcmc_both_variants() {
    let want = [
        Outcome {
            best_bits: 13839978483096223744,
            evaluations: 200,
            generations: 19,
            genome_hash: 15053218249678525549,
            history_hash: 16897701208759641825,
        },
        Outcome {
            best_bits: 13840672394655563776,
            evaluations: 191,
            generations: 17,
            genome_hash: 13981445911360642010,
            history_hash: 4791450258450708585,
        },
    ];
    for (variant, want) in McmcVariant::ALL.into_iter().zip(want) {
        let settings = McmcSettings {
            variant,
            chains: 10,
            initial_length: 15,
            ..generators::spaceship::paper_rjmcmc()
        };
        let r = Mcmc::<Spaceship>::new(settings, Limits::new(1, 120, 10).unwrap(), 3)
            .unwrap()
            .run(
                &mut BoxTarget::new(),
                &Budget::generations(25).and_evaluations(200),
                &mut Silent,
            )
            .unwrap();
        check(&format!("mcmc {variant:?}"), outcome(&r), want);
    }
}

#[test]
fn multi_ga() {
    let ga = GaSettings {
        population: 30,
        elitism: 4,
        initial_length: 20,
        ..GaSettings::default()
    };
    let settings = MultiGaSettings {
        ga,
        ..MultiGaSettings::thesis()
    };
    let r = MultiGa::<City>::new(settings, limits(), 9)
        .unwrap()
        .run(
            &mut TallAndFew(Vec::new()),
            &Budget::generations(10),
            &mut Silent,
        )
        .unwrap();
    let front: Vec<_> = r
        .front
        .iter()
        .map(|m| (serde_json::to_string(&m.genome).unwrap(), m.values.clone()))
        .collect();
    let history: Vec<&MultiHistoryEntry> = r.history.iter().collect();
    let timeless: Vec<_> = history
        .iter()
        .map(|h| {
            (
                h.generation,
                h.evaluations,
                h.front,
                h.best.iter().map(|b| b.to_bits()).collect::<Vec<_>>(),
            )
        })
        .collect();
    let got = (
        r.front.len(),
        r.evaluations,
        r.generations,
        fnv(format!("{front:?}").as_bytes()),
        fnv(format!("{timeless:?}").as_bytes()),
    );
    if std::env::var_os("REGRESSION_PRINT").is_some() {
        println!("multi: {got:?}");
    } else {
        assert_eq!(got, (8, 290, 10, 14161112382572258028, 6318843112498127409));
    }
}
