//! The silhouette scorer on the GPU agrees with the CPU up to pixels on edges.

use generators::{city, spaceship, tree};
use glam::{Affine3A, Mat3A, vec3};
use shapegen_runtime::geometry::{MeshId, RoofMeshes, RoofPiece, RoofShape};
use shapegen_runtime::gpu::GpuContext;
use shapegen_runtime::score::silhouette::{
    Camera, GpuSilhouetteScorer, ImageTarget, OrbitCamera, SilhouetteCounts, SilhouetteScorer,
    Weighting,
};
use shapegen_runtime::score::{InstanceBatch, count_batch};
use shapegen_runtime::{CUBE, Grammar, Scope};

use crate::GpuTest;
use crate::support::scenes::population;
use crate::support::silhouette_scenes::{SMOOTH, city_camera, tree_camera};
use crate::support::small_target;

/// The tests of this module.
pub const TESTS: &[GpuTest] = &[
    (
        "silhouette::gpu_matches_cpu_on_random_cities",
        gpu_matches_cpu_on_random_cities,
    ),
    (
        "silhouette::gpu_matches_cpu_on_random_cities_with_roofs",
        gpu_matches_cpu_on_random_cities_with_roofs,
    ),
    (
        "silhouette::gpu_matches_cpu_on_generated_facets",
        gpu_matches_cpu_on_generated_facets,
    ),
    (
        "silhouette::gpu_matches_cpu_on_lot_buildings",
        gpu_matches_cpu_on_lot_buildings,
    ),
    (
        "silhouette::gpu_matches_cpu_on_random_trees",
        gpu_matches_cpu_on_random_trees,
    ),
    (
        "silhouette::gpu_matches_cpu_on_random_spaceships_through_a_close_camera",
        gpu_matches_cpu_on_random_spaceships_through_a_close_camera,
    ),
    (
        "silhouette::gpu_matches_cpu_on_random_trees_against_a_shaped_target",
        gpu_matches_cpu_on_random_trees_against_a_shaped_target,
    ),
    (
        "silhouette::gpu_counts_a_batch_larger_than_one_chunk",
        gpu_counts_a_batch_larger_than_one_chunk,
    ),
];

/// The GPU's counts agree with the CPU's up to pixels whose centres lie within rounding
/// of an edge: at most 0.5% of the CPU's count plus 2 pixels per instance.
fn assert_close(what: &str, cpu: u64, gpu: u64, instances: usize) {
    let tolerance = cpu as f64 * 0.005 + 2.0 * instances as f64;
    assert!(
        (cpu as f64 - gpu as f64).abs() <= tolerance,
        "{what}: cpu {cpu}, gpu {gpu}, tolerance {tolerance}"
    );
}

fn compare_on_gpu(gpu: &GpuContext, scorer: &SilhouetteScorer, batch: &InstanceBatch) {
    let on_gpu = GpuSilhouetteScorer::new(gpu, scorer).unwrap();
    let mut cpu = vec![SilhouetteCounts::default(); batch.len()];
    count_batch(scorer, batch, &mut cpu);
    let mut out = vec![SilhouetteCounts::default(); batch.len()];
    on_gpu.count_batch(batch, &mut out).unwrap();
    let (mut exact, mut worst) = (0, 0);
    for (i, (c, g)) in cpu.iter().zip(&out).enumerate() {
        let n = batch.model(i).len();
        for (tc, tg) in c.targets().iter().zip(g.targets()) {
            let what = format!("model {i} ({n} instances)");
            assert_close(
                &format!("{what} covered"),
                tc.covered.into(),
                tg.covered.into(),
                n,
            );
            assert_close(
                &format!("{what} on"),
                tc.on_target.into(),
                tg.on_target.into(),
                n,
            );
            assert_close(
                &format!("{what} off"),
                tc.off_target.into(),
                tg.off_target.into(),
                n,
            );
            assert_close(
                &format!("{what} levels"),
                tc.level_sum / 255,
                tg.level_sum / 255,
                n + 1,
            );
            assert_eq!(tg.covered, tg.on_target + tg.off_target);
            worst = worst.max(tc.covered.abs_diff(tg.covered));
        }
        exact += usize::from(c == g);
    }
    eprintln!(
        "{exact} of {} models counted identically; covered pixels differ by at most {worst}",
        batch.len()
    );
    assert!(cpu.iter().any(|c| c.targets()[0].covered > 0));
    // The same batch again gives the same counts: bitsets are cleared between calls.
    let mut again = vec![SilhouetteCounts::default(); batch.len()];
    on_gpu.count_batch(batch, &mut again).unwrap();
    assert_eq!(out, again);
}

fn gpu_matches_cpu_on_random_cities(gpu: &GpuContext) {
    let meshes = generators::default_meshes()
        .bind(city::City::GRAPH)
        .unwrap();
    let targets = vec![
        small_target("city_whale", "city_target_whale.png", city_camera(), false),
        small_target("city_whale", "city_target_whale.png", tree_camera(), true),
    ];
    let scorer = SilhouetteScorer::new(targets, &meshes, SMOOTH).unwrap();
    compare_on_gpu(
        gpu,
        &scorer,
        &population::<city::City>(40, city::PAPER_LIMITS, 50, 21),
    );
}

/// Random cities with a roof of every shape in turn on every box: the roof pieces'
/// sloped faces and gables take the GPU's instance path as the boxes do.
fn gpu_matches_cpu_on_random_cities_with_roofs(gpu: &GpuContext) {
    let mut library = generators::default_meshes();
    for piece in RoofPiece::ALL {
        library.register(piece.name(), piece.mesh()).unwrap();
    }
    let mut names: Vec<&str> = city::City::GRAPH.meshes.to_vec();
    let first = names.len() as u32;
    names.extend(RoofPiece::ALL.map(RoofPiece::name));
    let meshes = library.bind_names("City", &names).unwrap();
    let pieces = RoofMeshes {
        gable: MeshId(first),
        shed: MeshId(first + 1),
        pyramid: MeshId(first + 2),
        hip_end: MeshId(first + 3),
    };
    let shapes = [
        RoofShape::Gable { pitch: 0.6 },
        RoofShape::Hip { pitch: 0.5 },
        RoofShape::Pyramid { pitch: 0.8 },
        RoofShape::Shed { pitch: 0.3 },
        RoofShape::Flat { thickness: 0.2 },
    ];
    let plain = population::<city::City>(40, city::PAPER_LIMITS, 50, 25);
    let mut batch = InstanceBatch::new();
    let mut pieces_placed = 0;
    for m in 0..plain.len() {
        batch.push_with(|out| {
            for (k, i) in plain.model(m).iter().enumerate() {
                out.push(*i);
                let m3 = i.transform.matrix3;
                let size = vec3(m3.x_axis.length(), m3.y_axis.length(), m3.z_axis.length());
                if i.mesh != CUBE || size.min_element() <= 1e-3 {
                    continue;
                }
                let frame = Affine3A {
                    matrix3: m3 * Mat3A::from_diagonal(size.recip()),
                    translation: i.transform.translation,
                };
                let before = out.len();
                Scope::new(frame, size)
                    .roof(shapes[k % shapes.len()], 0.1, &pieces, out)
                    .unwrap();
                pieces_placed += out.len() - before;
            }
        });
    }
    assert!(pieces_placed > 100, "{pieces_placed} roof pieces");
    let targets = vec![small_target(
        "city_whale",
        "city_target_whale.png",
        city_camera(),
        false,
    )];
    let scorer = SilhouetteScorer::new(targets, &meshes, SMOOTH).unwrap();
    compare_on_gpu(gpu, &scorer, &batch);
}

/// Random pavilions: walls extruded from polygon footprints and straight-skeleton roofs,
/// placed as facets, take the GPU's instance path as fixed meshes do.
fn gpu_matches_cpu_on_generated_facets(gpu: &GpuContext) {
    use crate::support::pavilions::{LIMITS, Pavilions, front_target, meshes};
    let batch = population::<Pavilions>(40, LIMITS, 4, 31);
    let facets: usize = (0..batch.len()).map(|m| batch.model(m).len()).sum();
    assert!(facets > 2000, "{facets} instances");
    let scorer = SilhouetteScorer::new(vec![front_target()], &meshes(), SMOOTH).unwrap();
    compare_on_gpu(gpu, &scorer, &batch);
}

/// Buildings on an L-shaped lot, their walls, windows, doors and roofs all generated
/// facets: a site's lot reaches the GPU through the batch as it reaches the CPU.
fn gpu_matches_cpu_on_lot_buildings(gpu: &GpuContext) {
    use generators::lot_building::LotBuilding;

    let batch = crate::support::lots::lot_buildings(30, 41);
    let facets: usize = (0..batch.len()).map(|m| batch.model(m).len()).sum();
    assert!(facets > 10_000, "{facets} instances");
    let meshes = generators::default_meshes()
        .bind(LotBuilding::GRAPH)
        .unwrap();
    let target = crate::support::pavilions::front_target();
    let scorer = SilhouetteScorer::new(vec![target], &meshes, SMOOTH).unwrap();
    compare_on_gpu(gpu, &scorer, &batch);
}

/// Compares the CPU and the GPU on 30 random trees against `target`, from `seed`.
fn compare_random_trees(gpu: &GpuContext, target: ImageTarget, seed: u64) {
    let meshes = generators::default_meshes()
        .bind(tree::Tree::GRAPH)
        .unwrap();
    let scorer = SilhouetteScorer::new(vec![target], &meshes, SMOOTH).unwrap();
    compare_on_gpu(
        gpu,
        &scorer,
        &population::<tree::Tree>(30, tree::PAPER_LIMITS, 150, seed),
    );
}

fn tree_sketch() -> ImageTarget {
    small_target(
        "tree_sketch1",
        "tree_target_sketch1.png",
        tree_camera(),
        false,
    )
}

fn gpu_matches_cpu_on_random_trees(gpu: &GpuContext) {
    compare_random_trees(gpu, tree_sketch(), 22);
}

fn gpu_matches_cpu_on_random_trees_against_a_shaped_target(gpu: &GpuContext) {
    compare_random_trees(gpu, tree_sketch().shaped(12.0).unwrap(), 23);
}

fn gpu_matches_cpu_on_random_spaceships_through_a_close_camera(gpu: &GpuContext) {
    // Close enough that some hulls reach behind the near plane.
    let camera = Camera::Orbit(OrbitCamera {
        phi: 0.7,
        theta: 0.35,
        radius: 6.0,
        lookat: vec3(0.0, 0.4, 4.0),
        fov_degrees: 70.0,
        near: 0.5,
        far: 50.0,
    });
    let meshes = generators::default_meshes()
        .bind(spaceship::Spaceship::GRAPH)
        .unwrap();
    let targets = vec![small_target(
        "tree_sketch1",
        "tree_target_sketch1.png",
        camera,
        true,
    )];
    let scorer = SilhouetteScorer::new(targets, &meshes, SMOOTH).unwrap();
    compare_on_gpu(
        gpu,
        &scorer,
        &population::<spaceship::Spaceship>(40, spaceship::PAPER_LIMITS, 50, 23),
    );
}

fn gpu_counts_a_batch_larger_than_one_chunk(gpu: &GpuContext) {
    let meshes = generators::default_meshes()
        .bind(city::City::GRAPH)
        .unwrap();
    // 4096 x 4096 pixels: 2 MiB of bitset per model, so 64 models per 128 MiB binding.
    let camera = city_camera();
    let image = image::DynamicImage::ImageLuma8(image::GrayImage::from_fn(4096, 4096, |x, _| {
        image::Luma([(x / 16) as u8])
    }));
    let target = ImageTarget::new(
        "big".into(),
        &image,
        camera,
        Weighting::weight_map(1.0, -1.0),
    )
    .unwrap();
    let scorer = SilhouetteScorer::new(vec![target], &meshes, SMOOTH).unwrap();
    let on_gpu = GpuSilhouetteScorer::new(gpu, &scorer).unwrap();
    assert_eq!(on_gpu.bitset_bytes(), 2 << 20);
    let batch = population::<city::City>(on_gpu.chunk_size() + 3, city::PAPER_LIMITS, 20, 24);
    let mut cpu = vec![SilhouetteCounts::default(); batch.len()];
    count_batch(&scorer, &batch, &mut cpu);
    let mut out = vec![SilhouetteCounts::default(); batch.len()];
    on_gpu.count_batch(&batch, &mut out).unwrap();
    for (i, (c, g)) in cpu.iter().zip(&out).enumerate() {
        let n = batch.model(i).len();
        assert_close(
            &format!("model {i}"),
            c.targets()[0].covered.into(),
            g.targets()[0].covered.into(),
            4 * n,
        );
    }
    let err = on_gpu.count_batch(&batch, &mut out[1..]).unwrap_err();
    assert!(err.to_string().contains("give one per model"), "{err}");
}
