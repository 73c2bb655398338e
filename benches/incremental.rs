//! Scoring one GA child on the paper scenes, incrementally (from its parent's kept state)
//! against from nothing, per operator, on one thread.
//!
//! Each row cycles through 64 (parent, child) pairs: parents are random genomes of the
//! scene's initial length (`optimizer.initial_length`), or for the tree of 250 genes, the
//! size its search's trees grow to (its best has 396 genes after the published 1,500
//! generations), each child one operator applied to
//! a copy of its parent (the crossover's partner another random genome), with the
//! original's operators as the paper scenes use them. Both rows start from the child's
//! derived instances: `full` counts them ([`Scorer::count`] for every scorer of the
//! scene), `incremental` clones the parent's state, diffs the two instance lists and
//! updates the state ([`RetainedScorer`]), as the search does.

mod breeding;

use std::hint::black_box;
use std::path::Path;

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use shapegen::ops::{OperatorVariant, Operators};
use shapegen::registry::Registry;
use shapegen::scene::{AnyScorer, Method, MethodSettings, Overrides, Scene, SceneScorer};
use shapegen::score::Scorer;
use shapegen::score::retained::{InstanceDiff, RetainedScorer};
use shapegen::{Genome, Grammar, Instance};

use breeding::Op;

const PAIRS: usize = 64;

/// A parent's instances and kept states, and its child's instances.
struct Pair {
    parent: Vec<Instance>,
    states: Vec<<AnyScorer as RetainedScorer>::State>,
    child: Vec<Instance>,
}

fn pairs<G: Grammar>(
    scene: &Scene,
    scorers: &[AnyScorer],
    op: Op,
    length: Option<u32>,
) -> Vec<Pair> {
    let MethodSettings::Ga(ga) = scene.optimizer.settings else {
        panic!("the scene is opened with the GA");
    };
    let initial = length.unwrap_or(ga.initial_length);
    let mut ops = Operators::<G>::new(scene.limits)
        .unwrap()
        .with_variant(OperatorVariant::Original);
    let mut rng = ChaCha8Rng::seed_from_u64(17);
    let mut scratch: Vec<_> = scorers.iter().map(|s| s.scratch()).collect();
    (0..PAIRS)
        .map(|_| {
            let parent: Genome<G> = ops.random(initial, &mut rng);
            let child = op.child(&mut ops, &parent, initial, &mut rng);
            let (mut p, mut c) = (Vec::new(), Vec::new());
            parent.derive_into(&mut p);
            child.derive_into(&mut c);
            let states = scorers
                .iter()
                .zip(&mut scratch)
                .map(|(s, scratch)| s.count_retained(&p, scratch).unwrap())
                .collect();
            Pair {
                parent: p,
                states,
                child: c,
            }
        })
        .collect()
}

/// The rows of one scene, parents of `length` genes (the scene's initial length if
/// `None`).
fn scene_rows<G: Grammar>(c: &mut Criterion, file: &str, length: Option<u32>) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(file);
    // The GA's settings (its initial length), whatever method the scene names.
    let ga = Overrides {
        method: Some(Method::Ga),
        ..Overrides::default()
    };
    let scene = Scene::open(&path, &Registry::published(), &ga).unwrap();
    let scorer = SceneScorer::new::<G>(&scene).unwrap();
    let scorers = scorer.scorers();
    let name = path.file_stem().unwrap().to_string_lossy().into_owned();
    let mut group = c.benchmark_group(format!("incremental/{name}"));
    for op in Op::ALL {
        let pairs = pairs::<G>(&scene, scorers, op, length);
        let (changed, instances): (usize, usize) = pairs.iter().fold((0, 0), |(c, n), p| {
            let mut diff = InstanceDiff::default();
            diff.between(&p.parent, &p.child);
            (c + diff.len(), n + p.child.len())
        });
        eprintln!(
            "incremental/{name}/{}: {PAIRS} children, {:.1} instances each, {:.1} changed",
            op.name(),
            instances as f64 / PAIRS as f64,
            changed as f64 / PAIRS as f64
        );
        let mut scratch: Vec<_> = scorers.iter().map(|s| s.scratch()).collect();
        let mut next = 0;
        group.bench_function(BenchmarkId::new("full", op.name()), |b| {
            b.iter(|| {
                let pair = &pairs[next % PAIRS];
                next += 1;
                for (s, scratch) in scorers.iter().zip(&mut scratch) {
                    black_box(s.count(black_box(&pair.child), scratch));
                }
            })
        });
        let mut diff = InstanceDiff::default();
        group.bench_function(BenchmarkId::new("incremental", op.name()), |b| {
            b.iter(|| {
                let pair = &pairs[next % PAIRS];
                next += 1;
                diff.between(&pair.parent, black_box(&pair.child));
                for ((s, state), scratch) in scorers.iter().zip(&pair.states).zip(&mut scratch) {
                    let mut state = state.clone();
                    s.update(&mut state, diff.removed(), diff.added(), scratch)
                        .unwrap();
                    black_box(s.state_counts(&state));
                }
            })
        });
    }
    group.finish();
}

fn incremental(c: &mut Criterion) {
    scene_rows::<generators::Tree>(c, "scenes/paper/tree_sketch1.toml", Some(250));
    scene_rows::<generators::City>(c, "scenes/paper/city_whale.toml", None);
    scene_rows::<generators::Spaceship>(c, "scenes/paper/spaceship_volume.toml", None);
}

criterion_group!(benches, incremental);
criterion_main!(benches);
