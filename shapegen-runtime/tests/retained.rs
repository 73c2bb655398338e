//! Incremental scoring: a child counted from its parent's kept state equals the child
//! counted from nothing, exactly, for every published generator and scorer, over random
//! operator sequences; and bred populations count the same at 1 and 2 threads.
//!
//! The number of sequences scales with `SHAPEGEN_PROPERTY_SCALE` (default 1; the debug
//! build of the tests runs a fifth of the release build's sequences).

mod support {
    pub mod breeding;
    pub mod city_expanded;
    pub mod objective_scenes;
    pub mod pavilions;
    pub mod scenes;
    pub mod silhouette_scenes;
    pub mod volume_scenes;
}

use generators::{building, city, spaceship, tree};
use glam::Vec3;
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use shapegen_runtime::evaluate::Bred;
use shapegen_runtime::ops::{OperatorVariant, Operators};
use shapegen_runtime::score::objective::ProjectionScorer;
use shapegen_runtime::score::retained::{InstanceDiff, RetainedScorer, Retention};
use shapegen_runtime::score::silhouette::{Camera, ImageTarget, SilhouetteScorer, Weighting};
use shapegen_runtime::score::volume::VolumeScorer;
use shapegen_runtime::score::{InstanceBatch, Scorer, count_batch};
use shapegen_runtime::{BoundMeshes, Genome, Grammar, Instance, Limits, MeshLibrary};
use support::breeding::{bred, sequences};
use support::scenes::scenes;
use support::silhouette_scenes::{SMOOTH, city_camera, tree_camera};
use support::volume_scenes::{
    aabb, block, city_tower_scorer, paper_grid, paper_ship_scorer, target, turned_box,
};

/// Operators applied per sequence, each to the previous child.
const STEPS: usize = 12;

fn derive<G: Grammar>(g: &Genome<G>, out: &mut Vec<Instance>) {
    g.derive_into(out);
}

/// Runs random operator sequences from random genomes: every child's counts from its
/// parent's state (updated along the whole sequence) equal its counts from nothing.
/// Returns the number of children checked.
fn check_sequences<G: Grammar, S: RetainedScorer>(
    name: &str,
    scorer: &S,
    limits: Limits,
    initial: u32,
    count: usize,
    seed: u64,
) -> usize {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut scratch = scorer.scratch();
    let (mut parent_instances, mut child_instances) = (Vec::new(), Vec::new());
    let mut diff = InstanceDiff::default();
    let mut checked = 0;
    for sequence in 0..count {
        let variant = if sequence % 2 == 0 {
            OperatorVariant::Weighted
        } else {
            OperatorVariant::Original
        };
        let mut ops = Operators::<G>::new(limits).unwrap().with_variant(variant);
        let mut genome = ops.random(initial, &mut rng);
        derive(&genome, &mut parent_instances);
        let mut state = scorer
            .count_retained(&parent_instances, &mut scratch)
            .unwrap();
        assert_eq!(
            scorer.state_counts(&state),
            scorer.count(&parent_instances, &mut scratch),
            "{name}: sequence {sequence}, the first genome"
        );
        for step in 0..STEPS {
            let child = bred(&mut ops, &genome, initial, &mut rng);
            derive(&child, &mut child_instances);
            diff.between(&parent_instances, &child_instances);
            scorer
                .update(&mut state, diff.removed(), diff.added(), &mut scratch)
                .unwrap();
            let full = scorer.count(&child_instances, &mut scratch);
            assert_eq!(
                scorer.state_counts(&state),
                full,
                "{name}: sequence {sequence}, step {step} ({} removed, {} added)\n{child:?}",
                diff.removed().len(),
                diff.added().len()
            );
            checked += 1;
            genome = child;
            std::mem::swap(&mut parent_instances, &mut child_instances);
        }
    }
    eprintln!("{name}: {count} sequences, {checked} children equal to their full counts");
    checked
}

fn image_target(scene: &str, file: &str, camera: Camera) -> ImageTarget {
    let path = scenes().join(scene).join(file);
    let image = image::open(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    ImageTarget::new(file.to_owned(), &image, camera, Weighting::mask(1.0, -1.0)).unwrap()
}

/// The tree's meshes as the paper scene loads them: the published trunk and leaf,
/// normalized.
fn published_tree_meshes() -> BoundMeshes {
    let dir = scenes().join("tree_sketch1");
    let mut library = generators::default_meshes();
    for (name, file) in [("trunk", "trunk.obj"), ("leaf", "leaf.obj")] {
        library.register_obj(name, dir.join(file)).unwrap();
    }
    library.bind(tree::Tree::GRAPH).unwrap()
}

fn tree_sketch(meshes: &BoundMeshes) -> SilhouetteScorer {
    let t = image_target("tree_sketch1", "tree_target_sketch1.png", tree_camera());
    SilhouetteScorer::new(vec![t], meshes, SMOOTH).unwrap()
}

fn city_whale() -> SilhouetteScorer {
    let t = image_target("city_whale", "city_target_whale.png", city_camera());
    let meshes = MeshLibrary::new().bind(city::City::GRAPH).unwrap();
    SilhouetteScorer::new(vec![t], &meshes, SMOOTH).unwrap()
}

#[test]
fn tree_sketch_with_the_published_meshes() {
    let scorer = tree_sketch(&published_tree_meshes());
    check_sequences::<tree::Tree, _>(
        "tree, published meshes",
        &scorer,
        tree::PAPER_LIMITS,
        250,
        sequences(150),
        1,
    );
}

#[test]
fn tree_sketch_with_the_built_in_meshes() {
    let meshes = generators::default_meshes()
        .bind(tree::Tree::GRAPH)
        .unwrap();
    let scorer = tree_sketch(&meshes);
    check_sequences::<tree::Tree, _>(
        "tree, built-in meshes",
        &scorer,
        tree::PAPER_LIMITS,
        100,
        sequences(400),
        2,
    );
}

#[test]
fn city_whale_silhouette() {
    check_sequences::<city::City, _>(
        "city whale",
        &city_whale(),
        city::PAPER_LIMITS,
        50,
        sequences(600),
        3,
    );
}

#[test]
fn spaceship_volume() {
    let meshes = MeshLibrary::new()
        .bind(spaceship::Spaceship::GRAPH)
        .unwrap();
    let scorer = paper_ship_scorer(&meshes);
    check_sequences::<spaceship::Spaceship, _>(
        "spaceship volume",
        &scorer,
        spaceship::PAPER_LIMITS,
        50,
        sequences(600),
        4,
    );
}

#[test]
fn city_volume_with_overlaps() {
    let scorer = city_tower_scorer(paper_grid());
    check_sequences::<support::city_expanded::City, _>(
        "city volume",
        &scorer,
        city::PAPER_LIMITS,
        50,
        sequences(400),
        5,
    );
}

/// A volume scorer on the grid `(min, max, resolution)` toward the block `(lo, hi)`
/// (inside 1, outside -1), overlaps weighted 0.5.
fn block_volume(
    meshes: &BoundMeshes,
    (min, max, resolution): (Vec3, Vec3, [u32; 3]),
    (lo, hi): (Vec3, Vec3),
) -> VolumeScorer {
    let grid = shapegen_runtime::score::volume::Grid::new(min, max, resolution).unwrap();
    let t = target("block", block(lo, hi), 1.0, -1.0);
    let form = shapegen_runtime::score::Form::Weighted { overlap: 0.5 };
    VolumeScorer::new(grid, &[t], meshes, form).unwrap()
}

/// The building generator's meshes are not all boxes, so its volume counts take the
/// parity voxelizer; its silhouette seen from the front.
#[test]
fn building_volume_and_silhouette() {
    let meshes = generators::default_meshes()
        .bind(building::Building::GRAPH)
        .unwrap();
    let grid = (
        Vec3::new(-8.0, 0.0, -8.0),
        Vec3::new(8.0, 40.0, 8.0),
        [64, 160, 64],
    );
    let tower = (Vec3::new(-4.0, 0.0, -4.0), Vec3::new(4.0, 24.0, 4.0));
    let volume = block_volume(&meshes, grid, tower);
    check_sequences::<building::Building, _>(
        "building volume",
        &volume,
        building::LIMITS,
        30,
        sequences(150),
        6,
    );
    let camera = Camera::Orbit(shapegen_runtime::score::silhouette::OrbitCamera {
        phi: -std::f32::consts::FRAC_PI_2,
        theta: 0.2,
        radius: 60.0,
        lookat: Vec3::new(0.0, 15.0, 0.0),
        fov_degrees: 50.0,
        near: 0.1,
        far: 200.0,
    });
    let image = image::DynamicImage::ImageLuma8(image::GrayImage::from_fn(320, 240, |x, y| {
        image::Luma([if (100..220).contains(&x) && y > 60 {
            0
        } else {
            255
        }])
    }));
    let t = ImageTarget::new("front".into(), &image, camera, Weighting::mask(1.0, -1.0)).unwrap();
    let silhouette = SilhouetteScorer::new(vec![t], &meshes, SMOOTH).unwrap();
    check_sequences::<building::Building, _>(
        "building silhouette",
        &silhouette,
        building::LIMITS,
        30,
        sequences(150),
        7,
    );
}

/// Generated geometry: pavilions whose walls and roofs are facets, counted together by
/// winding number, next to boxes; a child's volume and silhouette counted from its
/// parent's state equal its counts from nothing.
#[test]
fn generated_facets_volume_and_silhouette() {
    let meshes = support::pavilions::meshes();
    let grid = (
        Vec3::new(-12.0, 0.0, -12.0),
        Vec3::new(12.0, 24.0, 12.0),
        [48, 48, 48],
    );
    let hall = (Vec3::new(-6.0, 0.0, -4.0), Vec3::new(6.0, 10.0, 4.0));
    let volume = block_volume(&meshes, grid, hall);
    let checked = check_sequences::<support::pavilions::Pavilions, _>(
        "pavilion volume",
        &volume,
        support::pavilions::LIMITS,
        3,
        sequences(100),
        11,
    );
    assert!(checked > 0);
    let t = support::pavilions::front_target();
    let silhouette = SilhouetteScorer::new(vec![t], &meshes, SMOOTH).unwrap();
    check_sequences::<support::pavilions::Pavilions, _>(
        "pavilion silhouette",
        &silhouette,
        support::pavilions::LIMITS,
        3,
        sequences(100),
        12,
    );
}

/// The projection objectives of the building scene, from above and from the front: a
/// model's projection counted instance by instance from its parent's kept counts equals
/// the whole model rasterized at once.
#[test]
fn building_projections() {
    let meshes = generators::default_meshes()
        .bind(building::Building::GRAPH)
        .unwrap();
    let [top, front] = support::objective_scenes::building_projections();
    for (name, projection, seed) in [("top", top, 8), ("front", front, 9)] {
        check_sequences::<building::Building, _>(
            &format!("building {name} projection"),
            &ProjectionScorer::new(projection, meshes.clone()),
            building::LIMITS,
            30,
            sequences(200),
            seed,
        );
    }
}

/// Breeds `generations` generations of a small GA-like population (children from
/// random parents by one operator each) and counts each with a [`Retention`] on a pool
/// of `threads` threads; returns every generation's counts.
fn bred_counts<G: Grammar, S: RetainedScorer<Counts: Default>>(
    scorer: &S,
    limits: Limits,
    initial: u32,
    threads: usize,
) -> Vec<Vec<S::Counts>> {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    pool.install(|| {
        let mut rng = ChaCha8Rng::seed_from_u64(99);
        let mut ops = Operators::<G>::new(limits).unwrap();
        let mut population: Vec<Genome<G>> =
            (0..12).map(|_| ops.random(initial, &mut rng)).collect();
        let mut retention = Retention::new();
        let mut all = Vec::new();
        for _ in 0..6 {
            let from: Vec<u32> = (0..10)
                .map(|_| rng.random_range(0..population.len() as u32))
                .collect();
            let children: Vec<Genome<G>> = from
                .iter()
                .map(|&p| bred(&mut ops, &population[p as usize], initial, &mut rng))
                .collect();
            let mut batch = InstanceBatch::new();
            for c in &children {
                batch.push_genome(c);
            }
            let mut counts = vec![S::Counts::default(); children.len()];
            let scorers = std::slice::from_ref(scorer);
            let lineage = Bred {
                children: &children,
                parents: &population,
                from: &from,
            };
            retention.count_bred(scorers, lineage, &batch, &mut counts);
            let mut full = vec![S::Counts::default(); children.len()];
            count_batch(scorer, &batch, &mut full);
            assert_eq!(counts, full, "{threads} threads");
            all.push(counts);
            // The next generation: two elites and the children.
            population.truncate(2);
            population.extend(children);
        }
        let stats = retention.stats();
        assert!(stats.incremental > stats.full, "{stats:?}");
        all
    })
}

#[test]
fn bred_populations_count_the_same_at_one_and_two_threads() {
    let scorer = city_whale();
    let one = bred_counts::<city::City, _>(&scorer, city::PAPER_LIMITS, 50, 1);
    let two = bred_counts::<city::City, _>(&scorer, city::PAPER_LIMITS, 50, 2);
    assert_eq!(one, two);
    let meshes = MeshLibrary::new()
        .bind(spaceship::Spaceship::GRAPH)
        .unwrap();
    let scorer = paper_ship_scorer(&meshes);
    let one = bred_counts::<spaceship::Spaceship, _>(&scorer, spaceship::PAPER_LIMITS, 50, 1);
    let two = bred_counts::<spaceship::Spaceship, _>(&scorer, spaceship::PAPER_LIMITS, 50, 2);
    assert_eq!(one, two);
}

/// A state is updated only from the instances it was counted from, so any base gives the
/// exact counts: here, each genome of a random population counted from its neighbour's
/// state.
#[test]
fn an_unrelated_base_still_gives_exact_counts() {
    let scorer = city_whale();
    let batch =
        support::scenes::population::<city::City>(sequences(20) + 1, city::PAPER_LIMITS, 60, 5);
    let mut scratch = scorer.scratch();
    let mut diff = InstanceDiff::default();
    for i in 1..batch.len() {
        let (a, b) = (batch.model(i - 1), batch.model(i));
        let mut state = scorer.count_retained(a, &mut scratch).unwrap();
        diff.between(a, b);
        scorer
            .update(&mut state, diff.removed(), diff.added(), &mut scratch)
            .unwrap();
        assert_eq!(
            scorer.state_counts(&state),
            scorer.count(b, &mut scratch),
            "genome {i}"
        );
    }
}

/// Instances that repeat or overlap: a voxel stays covered until the last instance over
/// it goes, and its overlap is counted while two or more remain.
#[test]
fn repeated_and_overlapping_instances() {
    let scorer = city_tower_scorer(paper_grid());
    let mut scratch = scorer.scratch();
    let slab = aabb(Vec3::new(-2.0, -1.0, 0.0), Vec3::new(2.0, 1.0, 3.0));
    let tall = aabb(Vec3::new(-1.0, -3.0, 1.0), Vec3::new(1.0, 3.0, 8.0));
    let turned = turned_box();
    let steps: [&[Instance]; 7] = [
        &[slab],
        &[slab, slab],
        &[slab, slab, tall],
        &[slab, tall, turned],
        &[tall, turned, turned],
        &[turned],
        &[],
    ];
    let mut state = scorer.count_retained(&[], &mut scratch).unwrap();
    let mut diff = InstanceDiff::default();
    let mut before: &[Instance] = &[];
    for (step, &now) in steps.iter().enumerate() {
        diff.between(before, now);
        scorer
            .update(&mut state, diff.removed(), diff.added(), &mut scratch)
            .unwrap();
        assert_eq!(
            scorer.state_counts(&state),
            scorer.count(now, &mut scratch),
            "step {step}"
        );
        before = now;
    }
    assert_eq!(scorer.state_counts(&state), scorer.count(&[], &mut scratch));
}
