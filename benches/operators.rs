//! Cost of the genetic operators and of random-genome creation, single-threaded, under
//! both rule sets (`weighted`, the default, and `original`, the original implementation's).
//!
//! Each iteration of grow, cut and alter first restores the same genome into one reused,
//! cache-warm buffer (`clone_from`) and then applies the operator, so every iteration does
//! the same work; `restore` measures that restoring alone, to subtract.

mod common;

use criterion::measurement::WallTime;
use criterion::{BenchmarkGroup, BenchmarkId, Criterion, criterion_group, criterion_main};
use generators::{GeneratorVisitor, Published};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use shapegen::Grammar;
use shapegen::genome::Limits;
use shapegen::ops::{OperatorVariant, Operators};

struct OperatorBench<'a> {
    c: &'a mut Criterion,
}

impl GeneratorVisitor for OperatorBench<'_> {
    type Output = ();

    fn visit<G: Grammar>(self, paper: Limits) {
        for variant in OperatorVariant::ALL {
            let mut group =
                self.c
                    .benchmark_group(format!("operators/{}/{}", G::GRAPH.name, variant.name()));
            bench_variant::<G>(&mut group, paper, variant);
            group.finish();
        }
    }
}

/// The operator rows of grammar `G` under `variant`.
fn bench_variant<G: Grammar>(
    group: &mut BenchmarkGroup<'_, WallTime>,
    paper: Limits,
    variant: OperatorVariant,
) {
    for genes in [100, 1000] {
        let limits = common::limits_for::<G>(genes, paper);
        let a = common::genome_of::<G>(genes, limits, 1);
        let b = common::genome_of::<G>(genes, limits, 2);
        let genes = a.len();
        let mut ops = Operators::<G>::new(Limits {
            min_len: 1,
            max_len: limits.max_len + 1,
            ..limits
        })
        .expect("benchmark limits are valid")
        .with_variant(variant);
        let mut rng = ChaCha8Rng::seed_from_u64(3);
        let id = |name: &str| BenchmarkId::new(name, genes);

        let mut g = a.clone();
        group.bench_function(id("restore"), |bench| bench.iter(|| g.clone_from(&a)));
        group.bench_function(id("grow"), |bench| {
            bench.iter(|| {
                g.clone_from(&a);
                ops.grow(&mut g, &mut rng)
            })
        });
        group.bench_function(id("cut"), |bench| {
            bench.iter(|| {
                g.clone_from(&a);
                ops.cut(&mut g, &mut rng)
            })
        });
        group.bench_function(id("alter"), |bench| {
            bench.iter(|| {
                g.clone_from(&a);
                ops.alter(&mut g, &mut rng)
            })
        });
        group.bench_function(id("crossover"), |bench| {
            bench.iter(|| ops.crossover(&a, &b, &mut rng))
        });
        group.bench_function(id("random"), |bench| {
            bench.iter(|| ops.random(genes as u32, &mut rng))
        });
    }
}

fn operators(c: &mut Criterion) {
    for generator in Published::ALL {
        generator.visit(OperatorBench { c: &mut *c });
    }
}

criterion_group!(benches, operators);
criterion_main!(benches);
