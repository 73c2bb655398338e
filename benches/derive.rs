//! Derivation throughput: genomes per second and instances per second, single-threaded.

mod common;

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use generators::{GeneratorVisitor, Published};
use shapegen::Grammar;
use shapegen::genome::Limits;

struct DeriveBench<'a> {
    c: &'a mut Criterion,
}

impl GeneratorVisitor for DeriveBench<'_> {
    type Output = ();

    fn visit<G: Grammar>(self, paper: Limits) {
        let mut group = self.c.benchmark_group(format!("derive/{}", G::GRAPH.name));
        for genes in [10, 100, 1000] {
            // The city holds 201 genes at most (100 lots with a building each), so its
            // largest case is 201 genes.
            let genome = common::genome_of::<G>(genes, common::limits_for::<G>(genes, paper), 1);
            let genes = genome.len();
            let mut out = Vec::new();
            genome.derive_into(&mut out);
            group.throughput(Throughput::Elements(out.len() as u64));
            group.bench_with_input(BenchmarkId::new("genes", genes), &genome, |b, g| {
                b.iter(|| {
                    g.derive_into(&mut out);
                    out.len()
                })
            });
        }
        group.finish();
    }
}

fn derive(c: &mut Criterion) {
    for generator in Published::ALL {
        generator.visit(DeriveBench { c: &mut *c });
    }
}

criterion_group!(benches, derive);
criterion_main!(benches);
