//! The volume scorer on the GPU counts exactly what it counts on the CPU.

use std::path::Path;

use generators::lot_building::LotBuilding;
use glam::{Affine3A, Vec3};
use shapegen_runtime::genome::Limits;
use shapegen_runtime::geometry::{MeshId, facet_transform};
use shapegen_runtime::gpu::GpuContext;
use shapegen_runtime::score::volume::{GpuVolumeScorer, Grid, VolumeCounts, VolumeScorer};
use shapegen_runtime::score::{Form, InstanceBatch, count_batch};
use shapegen_runtime::{CUBE, Grammar, Instance, Mesh, MeshLibrary};

use crate::GpuTest;
use crate::support::city_expanded::City;
use crate::support::lots::lot_buildings;
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
        "volume::the_gpu_counts_other_meshes_and_facets_exactly_as_the_cpu_does",
        the_gpu_counts_other_meshes_and_facets_exactly_as_the_cpu_does,
    ),
    (
        "volume::the_fscore_form_is_refused_on_the_gpu",
        the_fscore_form_is_refused_on_the_gpu,
    ),
];

/// The F-score form's surface counts are made on the CPU only: the GPU scorer says so
/// rather than count without them.
fn the_fscore_form_is_refused_on_the_gpu(gpu: &GpuContext) {
    let grid = Grid::new(Vec3::splat(-1.0), Vec3::splat(1.0), [8, 8, 8]).unwrap();
    let meshes = MeshLibrary::new().bind_names("Boxes", &["cube"]).unwrap();
    let form = Form::FScore {
        good: 1.0,
        threshold: 0.3,
    };
    let cube = target(
        "cube",
        block(Vec3::splat(-0.5), Vec3::splat(0.5)),
        1.0,
        -1.0,
    );
    let scorer = VolumeScorer::new(grid, &[cube], &meshes, form).unwrap();
    let Err(err) = GpuVolumeScorer::new(gpu, &scorer) else {
        panic!("the GPU counted the fscore form");
    };
    assert!(err.to_string().contains("CPU only"), "{err}");
}

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

/// Asserts that more than `n` of the models counted as `counts` are `such`.
fn assert_many(counts: &[VolumeCounts], n: usize, such: impl Fn(&VolumeCounts) -> bool) {
    let found = counts.iter().filter(|c| such(c)).count();
    assert!(
        found > n,
        "{found} of the models, not more than {n}: {counts:?}"
    );
}

/// A tetrahedron of facets, outward-wound, with its right-angle corner at `at` and legs
/// of `size`.
fn facet_tetrahedron(at: Vec3, size: f32) -> Vec<Instance> {
    let [p0, p1, p2, p3] = [Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::Z].map(|p| at + p * size);
    [[p0, p2, p1], [p0, p1, p3], [p0, p3, p2], [p1, p2, p3]]
        .into_iter()
        .map(|[a, b, c]| Instance {
            transform: facet_transform(a, b, c).unwrap(),
            mesh: FACET,
        })
        .collect()
}

const FACET: MeshId = MeshId(1);
const TRUNK: MeshId = MeshId(2);

fn the_gpu_counts_other_meshes_and_facets_exactly_as_the_cpu_does(gpu: &GpuContext) {
    // Trees: trunks and leaves are meshes of their own, voxelized by parity.
    let meshes = generators::default_meshes()
        .bind(generators::tree::Tree::GRAPH)
        .unwrap();
    let grid = Grid::new(
        Vec3::new(-2.0, 0.0, -2.0),
        Vec3::new(2.0, 5.0, 2.0),
        [24, 30, 24],
    )
    .unwrap();
    let trunk = target(
        "trunk",
        block(Vec3::new(-0.5, 0.0, -0.5), Vec3::new(0.5, 2.0, 0.5)),
        1.0,
        -1.0,
    );
    let scorer =
        VolumeScorer::new(grid, &[trunk], &meshes, Form::Weighted { overlap: 0.5 }).unwrap();
    let trees = population::<generators::tree::Tree>(30, generators::tree::PAPER_LIMITS, 150, 5);
    let cpu = cpu_counts(&scorer, &trees);
    assert_many(&cpu, 10, |c| c.inside > 0 && c.outside > 0);
    assert_many(&cpu, 5, |c| c.out_of_grid_hits > 0);
    assert_many(&cpu, 5, |c| c.overlap_voxels > 0);
    assert_eq!(cpu, gpu_counts(gpu, &scorer, &trees));

    // Lot buildings: generated surfaces, their facets voxelized together by winding
    // number, on a grid that cuts them.
    let buildings = lot_buildings(30, 41);
    let meshes = generators::default_meshes()
        .bind(LotBuilding::GRAPH)
        .unwrap();
    let grid = Grid::new(
        Vec3::new(-6.0, -0.5, -5.0),
        Vec3::new(6.0, 7.0, 5.0),
        [36, 22, 30],
    )
    .unwrap();
    let mass = target(
        "mass",
        block(Vec3::new(-5.0, 0.0, -4.0), Vec3::new(2.0, 4.0, 4.0)),
        1.0,
        -1.0,
    );
    let scorer =
        VolumeScorer::new(grid, &[mass], &meshes, Form::Weighted { overlap: 0.5 }).unwrap();
    let cpu = cpu_counts(&scorer, &buildings);
    assert_many(&cpu, 10, |c| c.inside > 0 && c.outside > 0);
    assert_many(&cpu, 5, |c| c.out_of_grid_hits > 0);
    assert_many(&cpu, 5, |c| c.span_out_of_grid > 0);
    let mut on_gpu = GpuVolumeScorer::new(gpu, &scorer).unwrap();
    let mut out = vec![VolumeCounts::default(); buildings.len()];
    on_gpu.count_batch(&buildings, &mut out).unwrap();
    assert_eq!(cpu, out);
    on_gpu.limit_models_per_pass(4);
    out.fill(VolumeCounts::default());
    on_gpu.count_batch(&buildings, &mut out).unwrap();
    assert_eq!(cpu, out);

    // Boxes, a solid mesh and facets in one model: a cube, a trunk through it, a facet
    // tetrahedron over both and a copy of it (covered twice by winding number), one
    // open facet (covers nothing), and a tetrahedron too large to rasterise.
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../generators/meshes");
    let mut library = MeshLibrary::new();
    library.register("facet", Mesh::facet()).unwrap();
    library
        .register_obj("trunk", dir.join("trunk.obj"))
        .unwrap();
    let meshes = library
        .bind_names("Mixed", &["cube", "facet", "trunk"])
        .unwrap();
    let grid = Grid::new(Vec3::splat(-2.0), Vec3::splat(2.0), [20, 20, 20]).unwrap();
    let core = target(
        "core",
        block(Vec3::splat(-1.0), Vec3::splat(1.0)),
        1.0,
        -1.0,
    );
    let scorer =
        VolumeScorer::new(grid, &[core], &meshes, Form::Weighted { overlap: 0.5 }).unwrap();
    let cube = aabb(Vec3::splat(-0.8), Vec3::splat(0.6));
    let trunk = Instance {
        transform: Affine3A::from_scale_rotation_translation(
            Vec3::new(1.5, 3.0, 1.5),
            glam::Quat::from_rotation_z(0.4),
            Vec3::new(0.2, -1.0, 0.1),
        ),
        mesh: TRUNK,
    };
    let tetra = facet_tetrahedron(Vec3::new(-0.9, -0.3, -1.1), 2.6);
    let mut mixed = InstanceBatch::new();
    mixed.push_with(|out| {
        out.extend([cube, trunk]);
        out.extend(tetra.iter().chain(&tetra));
    });
    mixed.push_with(|out| out.extend(tetra.iter().take(1)));
    mixed.push_with(|out| {
        out.push(cube);
        out.extend(facet_tetrahedron(Vec3::splat(-1e6), 3e6));
    });
    mixed.push_with(|out| out.extend(facet_tetrahedron(Vec3::new(1.0, 1.0, 1.0), 2.0)));
    let cpu = cpu_counts(&scorer, &mixed);
    assert!(
        cpu[0].overlap_voxels > 0 && cpu[0].inside > 0 && cpu[0].outside > 0,
        "{:?}",
        cpu[0]
    );
    assert_eq!((cpu[1].inside, cpu[1].outside), (0, 0), "{:?}", cpu[1]);
    assert!(cpu[2].out_of_grid_hits > 1_000_000_000, "{:?}", cpu[2]);
    assert!(
        cpu[3].out_of_grid_hits > 0 && cpu[3].span_out_of_grid > 0,
        "{:?}",
        cpu[3]
    );
    assert_eq!(cpu, gpu_counts(gpu, &scorer, &mixed));
}
