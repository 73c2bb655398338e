//! The volume scorer on the GPU counts exactly what it counts on the CPU.

use std::path::Path;

use glam::{Affine3A, Vec3};
use shapegen_runtime::genome::Limits;
use shapegen_runtime::gpu::{GpuContext, GpuError};
use shapegen_runtime::score::volume::{GpuVolumeScorer, Grid, VolumeCounts, VolumeScorer};
use shapegen_runtime::score::{Form, InstanceBatch, count_batch};
use shapegen_runtime::{CUBE, Grammar, Instance, Mesh, MeshLibrary};

use crate::GpuTest;
use crate::support::city_expanded::City;
use crate::support::scenes::{population, scenes};
use crate::support::spaceship_expanded::Spaceship;
use crate::support::volume_scenes::{
    aabb, block, city_tower_scorer, paper_ship_scorer, target, turned_box,
};

/// The tests of this module.
pub const TESTS: &[GpuTest] = &[
    (
        "volume::the_gpu_counts_exactly_what_the_cpu_counts",
        the_gpu_counts_exactly_what_the_cpu_counts,
    ),
    (
        "volume::the_gpu_refuses_meshes_other_than_boxes",
        the_gpu_refuses_meshes_other_than_boxes,
    ),
];

/// The CPU's counts of every model of `batch`.
fn cpu_counts(scorer: &VolumeScorer, batch: &InstanceBatch) -> Vec<VolumeCounts> {
    let mut out = vec![VolumeCounts::default(); batch.len()];
    count_batch(scorer, batch, &mut out);
    out
}

/// The GPU's counts of every model of `batch`, by a scorer of its own.
fn gpu_counts(gpu: &GpuContext, scorer: &VolumeScorer, batch: &InstanceBatch) -> Vec<VolumeCounts> {
    let mut out = vec![VolumeCounts::default(); batch.len()];
    GpuVolumeScorer::new(gpu, scorer)
        .unwrap()
        .count_batch(batch, &mut out)
        .unwrap();
    out
}

fn the_gpu_counts_exactly_what_the_cpu_counts(gpu: &GpuContext) {
    let ship = Mesh::from_obj(scenes().join("spaceship_volume/spaceship_target.obj")).unwrap();
    // A grid smaller than many ships, so that they poke out on every side.
    let grid = Grid::new(
        Vec3::new(-2.0, -1.0, -1.0),
        Vec3::new(2.0, 1.5, 6.0),
        [33, 21, 47],
    )
    .unwrap();
    let targets = [
        target("ship", ship, 1.0, -1.0),
        target(
            "nose",
            block(Vec3::new(-0.5, -0.5, 4.0), Vec3::new(0.5, 0.5, 6.0)),
            0.5,
            0.0,
        ),
    ];
    let bound = MeshLibrary::new().bind(Spaceship::GRAPH).unwrap();
    let scorer = VolumeScorer::new(
        grid,
        &targets,
        &bound,
        Form::Smooth {
            good: 2.0,
            bad: 15.0,
        },
    )
    .unwrap();
    assert!(scorer.classes().weights().len() >= 3);
    let mut batch = population::<Spaceship>(60, Limits::new(4, 100, 15).unwrap(), 50, 21);
    // Hand-made models: empty, overlapping copies, a box far out, one too large to
    // rasterise, a flat one.
    batch.push_with(|_| {});
    let r = turned_box();
    let far = aabb(Vec3::splat(30.0), Vec3::splat(31.3));
    let huge = Instance {
        transform: Affine3A::from_scale(Vec3::splat(1e4)),
        mesh: CUBE,
    };
    let flat = Instance {
        transform: Affine3A::from_scale(Vec3::new(1.0, 0.0, 1.0)),
        mesh: CUBE,
    };
    batch.push_with(|out| out.extend([r, r, r, far, huge, flat]));

    let cpu = cpu_counts(&scorer, &batch);
    assert!(cpu.iter().filter(|c| c.out_of_grid_hits > 0).count() > 10);
    assert!(
        cpu.iter()
            .filter(|c| c.span_out_of_grid > c.out_of_grid_hits)
            .count()
            > 10
    );
    assert!(cpu.iter().filter(|c| c.overlap_voxels > 0).count() > 10);
    assert!(cpu.iter().any(|c| c.overlap_hits > c.overlap_voxels));
    assert!(
        cpu.iter()
            .filter(|c| c.classes[..3].iter().all(|&n| n > 0))
            .count()
            > 3
    );
    let mut gpu_scorer = GpuVolumeScorer::new(gpu, &scorer).unwrap();
    let mut out = vec![VolumeCounts::default(); batch.len()];
    gpu_scorer.count_batch(&batch, &mut out).unwrap();
    for (i, (c, g)) in cpu.iter().zip(&out).enumerate() {
        assert_eq!(c, g, "model {i}");
    }
    // In passes of 7 models, twice over with the same buffers.
    gpu_scorer.limit_models_per_pass(7);
    assert_eq!(gpu_scorer.models_per_pass(), 7);
    for _ in 0..2 {
        out.fill(VolumeCounts::default());
        gpu_scorer.count_batch(&batch, &mut out).unwrap();
        assert_eq!(cpu, out);
    }

    // Shaped by distance: more classes, counted the same on both.
    let shaped = scorer.clone().shaped(3.0).unwrap();
    assert!(shaped.classes().weights().len() > scorer.classes().weights().len());
    let cpu = cpu_counts(&shaped, &batch);
    assert!(cpu.iter().filter(|c| c.outside > 0).count() > 10);
    assert_eq!(cpu, gpu_counts(gpu, &shaped, &batch));

    // The city, on a grid around its middle lots.
    let city = population::<City>(30, Limits::new(4, 300, 8).unwrap(), 50, 8);
    let grid = Grid::new(
        Vec3::new(-6.0, 0.0, -6.0),
        Vec3::new(6.0, 6.0, 6.0),
        [40, 20, 40],
    )
    .unwrap();
    let scorer = city_tower_scorer(grid);
    let cpu = cpu_counts(&scorer, &city);
    assert!(cpu.iter().any(|c| c.span_out_of_grid > 0 && c.inside > 0));
    assert!(cpu.iter().any(|c| c.overlap_voxels > 0));
    let out = gpu_counts(gpu, &scorer, &city);
    assert_eq!(cpu, out);

    // The paper's spaceships on the paper's grid, whose thin wing boxes are one lattice
    // point thick.
    let bound = MeshLibrary::new()
        .bind(generators::Spaceship::GRAPH)
        .unwrap();
    let scorer = paper_ship_scorer(&bound);
    let ships = population::<generators::Spaceship>(30, generators::spaceship::PAPER_LIMITS, 50, 2);
    let cpu = cpu_counts(&scorer, &ships);
    assert!(cpu.iter().filter(|c| c.span_out_of_grid > 0).count() > 5);
    assert!(cpu.iter().filter(|c| c.overlap_voxels > 0).count() > 5);
    let out = gpu_counts(gpu, &scorer, &ships);
    assert_eq!(cpu, out);
}

fn the_gpu_refuses_meshes_other_than_boxes(gpu: &GpuContext) {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../generators/meshes");
    let mut library = MeshLibrary::new();
    library
        .register_obj("trunk", dir.join("trunk.obj"))
        .unwrap();
    library.register_obj("leaf", dir.join("leaf.obj")).unwrap();
    let bound = library
        .bind_names("Tree", &["cube", "trunk", "leaf"])
        .unwrap();
    let grid = Grid::new(Vec3::splat(-1.0), Vec3::splat(1.0), [8, 8, 8]).unwrap();
    let scorer = VolumeScorer::new(grid, &[], &bound, Form::Weighted { overlap: 0.0 }).unwrap();
    let err = GpuVolumeScorer::new(gpu, &scorer).unwrap_err();
    assert!(matches!(err, GpuError::Unsupported(_)), "{err:?}");
    assert_eq!(
        err.to_string(),
        "not supported on the GPU: mesh `trunk` (id 1) is not the unit cube; only box meshes \
         are counted on the GPU, count this grammar on the CPU"
    );
}
