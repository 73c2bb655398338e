//! Bred children counted on the GPU from their parents' kept slots
//! ([`GpuRetention`]) get exactly the counts the GPU gives them from nothing.

use generators::{city, tree};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use shapegen_runtime::evaluate::Bred;
use shapegen_runtime::gpu::GpuContext;
use shapegen_runtime::ops::Operators;
use shapegen_runtime::score::InstanceBatch;
use shapegen_runtime::score::retained::RetentionStats;
use shapegen_runtime::score::silhouette::{
    GpuRetention, GpuSilhouetteScorer, ImageTarget, SilhouetteCounts, SilhouetteScorer, Weighting,
};
use shapegen_runtime::{Genome, Grammar, Limits};

use crate::GpuTest;
use crate::support::breeding::{bred, sequences};
use crate::support::silhouette_scenes::{SMOOTH, city_camera, tree_camera};
use crate::support::small_target;

/// The tests of this module.
pub const TESTS: &[GpuTest] = &[
    (
        "silhouette_retained::bred_trees_count_as_from_nothing",
        bred_trees_count_as_from_nothing,
    ),
    (
        "silhouette_retained::bred_cities_through_two_targets_count_as_from_nothing",
        bred_cities_through_two_targets_count_as_from_nothing,
    ),
    (
        "silhouette_retained::past_the_memory_bound_children_count_from_nothing",
        past_the_memory_bound_children_count_from_nothing,
    ),
    (
        "silhouette_retained::slots_on_several_pages_count_as_from_nothing",
        slots_on_several_pages_count_as_from_nothing,
    ),
];

/// A search's breeding, with `retention` counting: `population` random genomes of
/// `initial` genes, then `generations` of children bred by random operators from random
/// parents, each generation's counts held to the GPU's counts from nothing; the next
/// parents are a quarter of the old ones and the first children, as a GA keeps elites.
fn breed<G: Grammar>(
    on_gpu: &GpuSilhouetteScorer<'_>,
    mut retention: GpuRetention,
    limits: Limits,
    (population, initial, generations): (usize, u32, usize),
    seed: u64,
) -> (RetentionStats, u64) {
    let mut ops = Operators::<G>::new(limits).unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut parents: Vec<Genome<G>> = (0..population)
        .map(|_| ops.random(initial, &mut rng))
        .collect();
    for generation in 0..generations {
        let from: Vec<u32> = (0..population)
            .map(|_| rng.random_range(0..population as u32))
            .collect();
        let children: Vec<Genome<G>> = from
            .iter()
            .map(|&p| bred(&mut ops, &parents[p as usize], initial, &mut rng))
            .collect();
        let mut batch = InstanceBatch::new();
        for child in &children {
            batch.push_genome(child);
        }
        let mut counts = vec![SilhouetteCounts::default(); children.len()];
        let lineage = Bred {
            children: &children,
            parents: &parents,
            from: &from,
        };
        retention
            .count_bred(on_gpu, lineage, &batch, &mut counts)
            .unwrap();
        let mut full = vec![SilhouetteCounts::default(); children.len()];
        on_gpu.count_batch(&batch, &mut full).unwrap();
        for (i, (kept, full)) in counts.iter().zip(&full).enumerate() {
            assert_eq!(kept, full, "generation {generation}, child {i}");
        }
        assert!(full.iter().any(|c| c.targets()[0].covered > 0));
        let elites = population / 4;
        parents.truncate(elites);
        parents.extend(children.into_iter().take(population - elites));
        assert!(retention.len() <= 2 * population);
    }
    let stats = retention.stats();
    eprintln!("{stats:?}, {} bytes of slots", retention.memory());
    (stats, retention.memory())
}

fn tree_scorer() -> SilhouetteScorer {
    let meshes = generators::default_meshes()
        .bind(tree::Tree::GRAPH)
        .unwrap();
    let target = small_target(
        "tree_sketch1",
        "tree_target_sketch1.png",
        tree_camera(),
        false,
    );
    SilhouetteScorer::new(vec![target], &meshes, SMOOTH).unwrap()
}

fn bred_trees_count_as_from_nothing(gpu: &GpuContext) {
    let scorer = tree_scorer();
    let on_gpu = GpuSilhouetteScorer::new(gpu, &scorer).unwrap();
    let retention = GpuRetention::new(&on_gpu).unwrap();
    assert_eq!(retention.slot_bytes(), 160 * 120 * 4);
    let generations = sequences(20);
    let (stats, memory) = breed::<tree::Tree>(
        &on_gpu,
        retention,
        tree::PAPER_LIMITS,
        (16, 120, generations),
        31,
    );
    assert!(stats.incremental >= 8 * generations as u64, "{stats:?}");
    // Pages of 64 slots, allocated as needed: 16 parents and 16 children take one.
    assert_eq!(memory, 64 * 160 * 120 * 4);
    // Only the parents that have children are counted, once each.
    assert!((1..=16).contains(&stats.parents_counted), "{stats:?}");
    assert!(
        stats.changed_instances < stats.child_instances / 2,
        "{stats:?}"
    );
}

fn bred_cities_through_two_targets_count_as_from_nothing(gpu: &GpuContext) {
    let meshes = generators::default_meshes()
        .bind(city::City::GRAPH)
        .unwrap();
    let targets = vec![
        small_target("city_whale", "city_target_whale.png", city_camera(), false),
        small_target("city_whale", "city_target_whale.png", tree_camera(), true),
    ];
    let scorer = SilhouetteScorer::new(targets, &meshes, SMOOTH).unwrap();
    let on_gpu = GpuSilhouetteScorer::new(gpu, &scorer).unwrap();
    let retention = GpuRetention::new(&on_gpu).unwrap();
    let generations = sequences(20);
    let (stats, _) = breed::<city::City>(
        &on_gpu,
        retention,
        city::PAPER_LIMITS,
        (16, 40, generations),
        32,
    );
    assert!(stats.incremental >= 8 * generations as u64, "{stats:?}");
}

fn past_the_memory_bound_children_count_from_nothing(gpu: &GpuContext) {
    let scorer = tree_scorer();
    let on_gpu = GpuSilhouetteScorer::new(gpu, &scorer).unwrap();
    // Room for 10 slots in all, where 16 parents and 16 children would want 32.
    let retention = GpuRetention::new(&on_gpu).unwrap();
    let bound = 10 * retention.slot_bytes();
    let (stats, memory) = breed::<tree::Tree>(
        &on_gpu,
        retention.with_max_bytes(bound),
        tree::PAPER_LIMITS,
        (16, 120, 5),
        33,
    );
    assert!(stats.incremental > 0, "{stats:?}");
    assert!(stats.full > 0, "{stats:?}");
    assert_eq!(memory, 10 * 160 * 120 * 4);
}

fn slots_on_several_pages_count_as_from_nothing(gpu: &GpuContext) {
    let meshes = generators::default_meshes()
        .bind(city::City::GRAPH)
        .unwrap();
    // 2048 x 2048 pixels: 16 MiB per slot, so at most 8 slots per 128 MiB binding.
    let image = image::DynamicImage::ImageLuma8(image::GrayImage::from_fn(2048, 2048, |x, _| {
        image::Luma([(x / 8) as u8])
    }));
    let target = ImageTarget::new(
        "big".into(),
        &image,
        city_camera(),
        Weighting::weight_map(1.0, -1.0),
    )
    .unwrap();
    let scorer = SilhouetteScorer::new(vec![target], &meshes, SMOOTH).unwrap();
    let on_gpu = GpuSilhouetteScorer::new(gpu, &scorer).unwrap();
    let retention = GpuRetention::new(&on_gpu).unwrap();
    assert_eq!(retention.slot_bytes(), 16 << 20);
    let (stats, memory) =
        breed::<city::City>(&on_gpu, retention, city::PAPER_LIMITS, (8, 20, 3), 34);
    assert!(stats.incremental > 0, "{stats:?}");
    // Up to 8 parents and 8 children, 8 slots per page: two pages or three.
    assert!(memory >= 2 * 8 * (16 << 20), "{memory}");
}
