//! The volume scorer on hand-computed scenes, the paper's spaceship target and random
//! populations.

mod support {
    pub mod city_expanded;
    pub mod original_volume;
    pub mod scenes;
    pub mod spaceship_expanded;
    pub mod volume_scenes;
}

use glam::{Affine3A, Quat, Vec3};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use shapegen_runtime::error_chain;
use shapegen_runtime::genome::Limits;
use shapegen_runtime::score::volume::{
    Grid, VolumeCounts, VolumeError, VolumeScorer, VoxelClasses,
};
use shapegen_runtime::score::{Form, Scorer, count_batch, smoothstep};
use shapegen_runtime::{BoundMeshes, CUBE, Grammar, Instance, Mesh, MeshId, MeshLibrary};
use support::city_expanded::City;
use support::original_volume as original;
use support::scenes::{population, scenes};
use support::spaceship_expanded::Spaceship;
use support::volume_scenes::{
    aabb, block, city_tower_scorer, paper_grid, paper_ship_scorer, target, turned_box,
};

fn cubes() -> BoundMeshes {
    MeshLibrary::new().bind_names("Boxes", &["cube"]).unwrap()
}

/// A 10^3 grid of unit voxels over [0, 10]^3 (centres at .5) with the target [0, 5]^3.
fn unit_scene(form: Form) -> VolumeScorer {
    let grid = Grid::new(Vec3::ZERO, Vec3::splat(10.0), [10, 10, 10]).unwrap();
    let t = target("corner", block(Vec3::ZERO, Vec3::splat(5.0)), 1.0, -1.0);
    VolumeScorer::new(grid, &[t], &cubes(), form).unwrap()
}

fn count(scorer: &VolumeScorer, instances: &[Instance]) -> VolumeCounts {
    scorer.count(instances, &mut scorer.scratch())
}

/// `[inside, outside, overlap_hits, overlap_voxels, out_of_grid_hits, span_out_of_grid]`.
fn summary(c: &VolumeCounts) -> [u64; 6] {
    [
        c.inside,
        c.outside,
        c.overlap_hits,
        c.overlap_voxels,
        c.out_of_grid_hits,
        c.span_out_of_grid,
    ]
}

#[test]
fn axis_aligned_box_covers_its_block() {
    let scorer = unit_scene(Form::Weighted { overlap: 0.0 });
    assert_eq!(scorer.target_voxels(), 125);
    // x centres 2.5, 3.5; y 2.5 ..= 5.5; z 4.5 ..= 6.5: 2 x 4 x 3 voxels, of which
    // those with y, z < 5 (2 x 3 x 1) are in the target.
    let b = aabb(Vec3::new(1.9, 2.2, 4.1), Vec3::new(4.1, 5.8, 7.3));
    let c = count(&scorer, &[b]);
    assert_eq!(summary(&c), [6, 18, 0, 0, 0, 0]);
    // Classes ascend by weight: -1 then 1.
    assert_eq!(scorer.classes().weights(), [-1.0, 1.0]);
    assert_eq!(c.classes[..3], [18, 6, 0]);
    assert_eq!(scorer.fitness(&c), 6.0 - 18.0);
}

#[test]
fn identical_boxes_overlap_by_their_voxel_count() {
    let scorer = unit_scene(Form::Weighted { overlap: 0.5 });
    let b = aabb(Vec3::new(1.9, 2.2, 4.1), Vec3::new(4.1, 5.8, 7.3));
    let c = count(&scorer, &[b, b]);
    assert_eq!(summary(&c), [6, 18, 24, 24, 0, 0]);
    // A third copy hits the 24 voxels once more each; they are still 24 voxels.
    let c = count(&scorer, &[b, b, b]);
    assert_eq!(summary(&c), [6, 18, 48, 24, 0, 0]);
    assert_eq!(scorer.fitness(&c), 6.0 - 18.0 - 0.5 * 48.0);
    // A rotated box overlaps itself exactly as much as it covers.
    let r = Instance {
        transform: Affine3A::from_scale_rotation_translation(
            Vec3::new(3.3, 1.7, 2.9),
            Quat::from_euler(glam::EulerRot::YXZ, 0.4, -0.7, 1.2),
            Vec3::new(4.9, 5.2, 5.1),
        ),
        mesh: CUBE,
    };
    let one = count(&scorer, &[r]);
    let two = count(&scorer, &[r, r]);
    assert!(one.inside + one.outside > 5);
    assert_eq!(two.overlap_hits, one.inside + one.outside);
    assert_eq!(two.overlap_voxels, one.inside + one.outside);
    assert_eq!([two.inside, two.outside], [one.inside, one.outside]);
}

#[test]
fn boxes_out_of_the_grid_count_every_outside_hit() {
    let scorer = unit_scene(Form::Weighted { overlap: 0.0 });
    // x centres -2.5 ..= 1.5 (5, two in the grid), y -0.5, 0.5 (the row at -0.5 lies
    // wholly outside), z 2.5, 3.5: 20 hits, 4 in the grid.
    let b = aabb(Vec3::new(-2.9, -1.1, 2.2), Vec3::new(2.1, 0.9, 3.8));
    let c = count(&scorer, &[b]);
    // Its span, the voxels holding its extent: x -3 ..= 2 (6), y -2 ..= 0 (3), z 2, 3
    // (2), 36 voxels of which 3 x 1 x 2 lie in the grid: 30 outside, among them those
    // at y = -2 and x = 2 whose centres it does not cover.
    assert_eq!(summary(&c), [4, 0, 0, 0, 16, 30]);
    // Repeats outside count again, in both terms; overlap counts in-grid voxels only.
    let c = count(&scorer, &[b, b]);
    assert_eq!(summary(&c), [4, 0, 4, 4, 32, 60]);
    assert_eq!(scorer.fitness(&c), 4.0 - 32.0);
    // Wholly outside, beyond every side: 3 x 2 x 1 voxels.
    let far = aabb(Vec3::new(20.2, 20.2, 20.2), Vec3::new(22.8, 21.8, 20.8));
    assert_eq!(summary(&count(&scorer, &[far])), [0, 0, 0, 0, 6, 6]);
    let below = aabb(Vec3::new(2.2, 2.2, -3.8), Vec3::new(3.8, 3.8, -0.2));
    assert_eq!(summary(&count(&scorer, &[below])), [0, 0, 0, 0, 16, 16]);
    // A sliver between the centres -0.5 and 0.5 covers none, but its span is the
    // voxels x = -1, y 3, 4, z = 3, outside the grid.
    let sliver = aabb(Vec3::new(-0.4, 3.2, 3.2), Vec3::new(-0.1, 4.8, 3.8));
    assert_eq!(summary(&count(&scorer, &[sliver])), [0, 0, 0, 0, 0, 2]);
    // A face on the grid's boundary, x = 10, lies in voxel 10 as the span rounds it:
    // 2 x 2 voxels beyond the grid, though every centre it covers is inside.
    let flush = aabb(Vec3::new(8.25, 8.25, 8.25), Vec3::new(10.0, 9.75, 9.75));
    assert_eq!(summary(&count(&scorer, &[flush])), [0, 8, 0, 0, 0, 4]);
}

#[test]
fn smooth_form_reaches_good_when_filling_the_target_exactly() {
    let scorer = unit_scene(Form::Smooth {
        good: 2.0,
        bad: 15.0,
    });
    let exact = aabb(Vec3::splat(0.1), Vec3::splat(4.9));
    let c = count(&scorer, &[exact]);
    assert_eq!(summary(&c), [125, 0, 0, 0, 0, 0]);
    assert_eq!(scorer.fitness(&c), 2.0);
    // Half the target, and 125 voxels elsewhere (half of 2T): S(0, 2T, 125) = 1/2.
    let hand = |inside, outside| VolumeCounts {
        inside,
        outside,
        ..VolumeCounts::default()
    };
    let f = scorer.fitness(&hand(0, 125));
    assert!((f + 7.5).abs() < 1e-12, "{f}");
    // `off` is outside + overlap voxels + span voxels out of the grid: 125 again.
    let f = scorer.fitness(&VolumeCounts {
        overlap_voxels: 100,
        span_out_of_grid: 25,
        ..hand(125, 0)
    });
    assert!((f - (2.0 - 7.5)).abs() < 1e-12, "{f}");
    let f = scorer.fitness(&VolumeCounts {
        overlap_voxels: 40,
        span_out_of_grid: 10,
        ..hand(100, 50)
    });
    let expected = 2.0 * smoothstep(0.0, 125.0, 100.0) - 15.0 * smoothstep(0.0, 250.0, 100.0);
    assert_eq!(f, expected);
    // Hits beyond the first and covered points outside the grid are the weighted
    // form's terms: they change nothing here.
    let f = scorer.fitness(&VolumeCounts {
        overlap_hits: 1000,
        out_of_grid_hits: 1000,
        ..hand(125, 0)
    });
    assert_eq!(f, 2.0);
    assert_eq!(scorer.fitness(&hand(0, 250)), -15.0);
    assert_eq!(scorer.fitness(&hand(0, 0)), 0.0);
}

#[test]
fn shaped_classes_cost_voxels_beside_the_target_by_their_distance() {
    let smooth = Form::Smooth {
        good: 2.0,
        bad: 15.0,
    };
    // Three layers of 5 x 5 voxels at x = 5, 6, 7: 1, 2 and 3 voxels from the target,
    // shares 1/4, 2/4 and 3/4 of the cost, rounded up to 4, 8 and 12 of 15 bands.
    let beside = aabb(Vec3::new(5.1, 0.1, 0.1), Vec3::new(7.9, 4.9, 4.9));
    let plain = unit_scene(smooth);
    let shaped = unit_scene(smooth).shaped(4.0).unwrap();
    assert_eq!(shaped.target_voxels(), 125);
    assert_eq!(shaped.classes().weight_at([4, 4, 4]), Some(1.0));
    assert_eq!(shaped.classes().weight_at([5, 0, 0]), Some(-(4.0 / 15.0)));
    assert_eq!(shaped.classes().weight_at([9, 9, 9]), Some(-1.0));
    let (c, p) = (count(&shaped, &[beside]), count(&plain, &[beside]));
    assert_eq!(summary(&c), summary(&p));
    assert_eq!(summary(&c), [0, 75, 0, 0, 0, 0]);
    let cost = 25.0 * (4.0 + 8.0 + 12.0) / 15.0;
    assert!((shaped.fitness(&c) + 15.0 * smoothstep(0.0, 250.0, cost)).abs() < 1e-12);
    assert_eq!(plain.fitness(&p), -15.0 * smoothstep(0.0, 250.0, 75.0));
    assert!(shaped.fitness(&c) > plain.fitness(&p));
    // Filling the target exactly is still the optimum.
    let exact = count(&shaped, &[aabb(Vec3::splat(0.1), Vec3::splat(4.9))]);
    assert_eq!(shaped.fitness(&exact), 2.0);

    let weighted = unit_scene(Form::Weighted { overlap: 0.0 })
        .shaped(4.0)
        .unwrap();
    let w = weighted.fitness(&count(&weighted, &[beside]));
    assert!((w + cost).abs() < 1e-12, "{w}");
}

#[test]
fn shaping_is_refused_where_it_has_no_meaning() {
    let reason =
        |scorer: VolumeScorer, radius: f64| error_chain(&scorer.shaped(radius).unwrap_err());
    let smooth = Form::Smooth {
        good: 1.0,
        bad: 1.0,
    };
    assert_eq!(
        reason(unit_scene(smooth), 0.0),
        "volume distance shaping: radius is 0; it must be a positive number of voxels"
    );
    assert!(reason(unit_scene(smooth), f64::NAN).contains("positive number of voxels"));
    let grid = Grid::new(Vec3::ZERO, Vec3::splat(10.0), [10, 10, 10]).unwrap();
    let away = target(
        "away",
        block(Vec3::splat(20.0), Vec3::splat(25.0)),
        1.0,
        -1.0,
    );
    let scorer = VolumeScorer::new(grid, &[away], &cubes(), smooth).unwrap();
    assert!(reason(scorer, 2.0).contains("no voxel is a target voxel"));
    // Ten nested shells of a 20^3 grid: 9 distinct negative weights and one positive
    // leave 15 / 9, fewer than 2 bands each.
    let grid = Grid::new(Vec3::ZERO, Vec3::splat(20.0), [20, 20, 20]).unwrap();
    let nested: Vec<_> = (0..10)
        .map(|i| {
            let lo = Vec3::splat(i as f32);
            target(
                &format!("t{i}"),
                block(lo, Vec3::splat(20.0) - lo),
                0.5,
                -1.0 - i as f64,
            )
        })
        .collect();
    let scorer = VolumeScorer::new(grid, &nested, &cubes(), smooth).unwrap();
    assert_eq!(scorer.classes().weights().len(), 10);
    assert!(reason(scorer, 2.0).contains("at least 2 bands"));
}

#[test]
fn weighted_form_sums_class_weights_on_hand_counts() {
    // Two overlapping targets: A = [0, 6]^3 (inside 2, outside -1) and B = [4, 10]^3
    // (inside 0.5, outside 0): weights -1 (neither), -0.5 (B only), 2 (A only), 2.5 (both).
    let grid = Grid::new(Vec3::ZERO, Vec3::splat(10.0), [10, 10, 10]).unwrap();
    let a = target("a", block(Vec3::ZERO, Vec3::splat(6.0)), 2.0, -1.0);
    let b = target("b", block(Vec3::splat(4.0), Vec3::splat(10.0)), 0.5, 0.0);
    let scorer =
        VolumeScorer::new(grid, &[a, b], &cubes(), Form::Weighted { overlap: 0.25 }).unwrap();
    let classes = scorer.classes();
    assert_eq!(classes.weights(), [-1.0, -0.5, 2.0, 2.5]);
    assert_eq!(classes.sizes(), [1000 - 216 - 216 + 8, 216 - 8, 216 - 8, 8]);
    assert_eq!(classes.weight_at([5, 5, 5]), Some(2.5));
    assert_eq!(classes.weight_at([9, 9, 0]), Some(-1.0));
    assert_eq!(scorer.target_voxels(), 216); // A's voxels; B alone weighs -0.5
    let mut hand = VolumeCounts {
        overlap_hits: 4,
        out_of_grid_hits: 10,
        ..VolumeCounts::default()
    };
    hand.classes[..4].copy_from_slice(&[3, 5, 7, 11]);
    let expected = -3.0 - 2.5 + 14.0 + 27.5 + 10.0 * (-1.0 + 0.0) - 0.25 * 4.0;
    assert_eq!(scorer.fitness(&hand), expected);
    // The smooth form's terms change nothing here.
    hand.overlap_voxels = 1000;
    hand.span_out_of_grid = 1000;
    assert_eq!(scorer.fitness(&hand), expected);
    // A box over [3.1, 6.9]^3 covers 4^3 voxels with centres 3.5 .. 6.5 per axis: 27
    // in A (3.5 ..= 5.5 on every axis), 27 in B, 8 in both.
    let c = count(&scorer, &[aabb(Vec3::splat(3.1), Vec3::splat(6.9))]);
    assert_eq!(c.classes[..4], [64 - 19 - 19 - 8, 19, 19, 8]);
    assert_eq!([c.inside, c.outside], [27, 37]);
}

#[test]
fn parity_voxelizes_the_cube_obj_exactly_and_the_spaceship_by_volume() {
    let cube = Mesh::from_obj(scenes().join("spaceship_volume/cube.obj")).unwrap();
    let grid = Grid::new(Vec3::splat(-1.0), Vec3::splat(1.0), [20, 20, 20]).unwrap();
    let classes = VoxelClasses::new(&grid, &[target("cube", cube.clone(), 1.0, 0.0)]).unwrap();
    assert_eq!(classes.target_voxels(), 1000);
    assert_eq!(classes.class_at([5, 5, 5]), Some(1));
    assert_eq!(classes.class_at([4, 5, 5]), Some(0));
    assert_eq!(classes.class_at([14, 14, 14]), Some(1));
    assert_eq!(classes.class_at([15, 14, 14]), Some(0));

    let ship = Mesh::from_obj(scenes().join("spaceship_volume/spaceship_target.obj")).unwrap();
    let volume: f64 = ship
        .triangles()
        .map(|t| {
            let [a, b, c] = t.map(|i| ship.positions[i as usize].as_dvec3());
            a.dot(b.cross(c)) / 6.0
        })
        .sum();
    let grid = Grid::new(
        Vec3::new(-5.0, -5.0, -2.0),
        Vec3::new(5.0, 5.0, 18.0),
        [100, 200, 100],
    )
    .unwrap();
    let t = VoxelClasses::new(&grid, &[target("ship", ship, 1.0, -1.0)])
        .unwrap()
        .target_voxels();
    let expected = volume.abs() / (0.1 * 0.05 * 0.2);
    assert!(
        (t as f64 - expected).abs() < 0.03 * expected,
        "{t} voxels for a volume of {expected} voxels"
    );

    // The OBJ cube is a box: it takes the integer path.
    let mut library = MeshLibrary::new();
    library.register("cube", cube).unwrap();
    let bound = library.bind_names("Boxes", &["cube"]).unwrap();
    let scorer = VolumeScorer::new(grid, &[], &bound, Form::Weighted { overlap: 0.0 }).unwrap();
    assert_eq!(scorer.is_box(CUBE), Some(true));
    assert_eq!(scorer.is_box(MeshId(1)), None);
}

#[test]
fn other_meshes_are_voxelized_by_parity_like_boxes() {
    // The unit cube at twice the size is no box: it is voxelized by parity, and where no
    // face passes near a lattice point it covers what the box does.
    let mut library = MeshLibrary::new();
    let mut double = Mesh::unit_cube();
    double.positions.iter_mut().for_each(|p| *p *= 2.0);
    library.register("double", double).unwrap();
    let bound = library.bind_names("Mixed", &["cube", "double"]).unwrap();
    let grid = Grid::new(Vec3::ZERO, Vec3::splat(10.0), [10, 10, 10]).unwrap();
    let t = target("corner", block(Vec3::ZERO, Vec3::splat(5.0)), 1.0, -1.0);
    let scorer = VolumeScorer::new(grid, &[t], &bound, Form::Weighted { overlap: 0.0 }).unwrap();
    assert_eq!(scorer.is_box(MeshId(1)), Some(false));
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    for _ in 0..20 {
        use rand::RngExt;
        let transform = Affine3A::from_scale_rotation_translation(
            Vec3::new(
                rng.random_range(0.5..4.0),
                rng.random_range(0.5..4.0),
                rng.random_range(0.5..4.0),
            ),
            Quat::from_euler(
                glam::EulerRot::XYZ,
                rng.random_range(0.0..3.0),
                rng.random_range(0.0..3.0),
                0.3,
            ),
            Vec3::new(
                rng.random_range(-1.0..11.0),
                rng.random_range(-1.0..11.0),
                rng.random_range(-1.0..11.0),
            ),
        );
        let as_box = count(
            &scorer,
            &[Instance {
                transform,
                mesh: CUBE,
            }],
        );
        let half = transform * Affine3A::from_scale(Vec3::splat(0.5));
        let as_mesh = count(
            &scorer,
            &[Instance {
                transform: half,
                mesh: MeshId(1),
            }],
        );
        assert_eq!(as_box, as_mesh, "{transform:?}");
        let both = count(
            &scorer,
            &[
                Instance {
                    transform,
                    mesh: CUBE,
                },
                Instance {
                    transform: half,
                    mesh: MeshId(1),
                },
            ],
        );
        assert_eq!(both.overlap_hits, as_box.inside + as_box.outside);
        assert_eq!(both.overlap_voxels, as_box.inside + as_box.outside);
        assert_eq!(both.out_of_grid_hits, 2 * as_box.out_of_grid_hits);
        assert_eq!(both.span_out_of_grid, 2 * as_box.span_out_of_grid);
    }
    // Ids the grammar lacks cover nothing.
    let ghost = Instance {
        transform: Affine3A::IDENTITY,
        mesh: MeshId(7),
    };
    assert_eq!(count(&scorer, &[ghost]), VolumeCounts::default());
}

#[test]
fn errors_name_the_target_and_the_limit() {
    let grid = Grid::new(Vec3::ZERO, Vec3::new(18.0, 1.0, 1.0), [18, 1, 1]).unwrap();
    // Target i fills voxel i with weight 2^i: with no target on the last voxel, 17
    // targets make 18 distinct weights.
    let targets: Vec<_> = (0..17)
        .map(|i| {
            let lo = Vec3::new(i as f32 + 0.1, 0.1, 0.1);
            target(
                &format!("t{i}"),
                block(lo, lo + 0.8),
                f64::from(1u32 << i),
                0.0,
            )
        })
        .collect();
    let form = Form::Weighted { overlap: 0.0 };
    let err = VolumeScorer::new(grid, &targets, &cubes(), form).unwrap_err();
    assert!(
        matches!(err, VolumeError::TooManyClasses { classes: 18, .. }),
        "{err:?}"
    );
    let text = err.to_string();
    assert!(
        text.starts_with("volume targets `t0`, `t1`, `t2`"),
        "{text}"
    );
    assert!(
        text.contains("combine into 18 distinct voxel weights; at most 16 are supported"),
        "{text}"
    );
    let ok = VolumeScorer::new(grid, &targets[..15], &cubes(), form).unwrap();
    assert_eq!(ok.classes().weights().len(), 16);
    assert_eq!(ok.target_voxels(), 15);

    let nan = target("hull", Mesh::unit_cube(), 1.0, f64::NAN);
    let err = VolumeScorer::new(grid, &[nan], &cubes(), form)
        .map_err(|e| error_chain(&e))
        .unwrap_err();
    assert_eq!(
        err,
        "volume target `hull`: outside weight NaN is not finite (finite numbers only)"
    );
    let empty = target("nothing", Mesh::default(), 1.0, 0.0);
    let err = VolumeScorer::new(grid, &[empty], &cubes(), form)
        .map_err(|e| error_chain(&e))
        .unwrap_err();
    assert_eq!(
        err,
        "volume target `nothing`: mesh `nothing` has no triangles"
    );
    // An open mesh is no error.
    let mut open = Mesh::unit_cube();
    open.indices.truncate(6);
    assert!(VolumeScorer::new(grid, &[target("open", open, 1.0, 0.0)], &cubes(), form).is_ok());
}

#[test]
fn counts_do_not_depend_on_threads_or_scratch_history() {
    let bound = MeshLibrary::new().bind(Spaceship::GRAPH).unwrap();
    let scorer = paper_ship_scorer(&bound);
    let batch = population::<Spaceship>(40, Limits::new(4, 100, 15).unwrap(), 50, 9);
    let run = |threads| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        let mut out = vec![VolumeCounts::default(); batch.len()];
        pool.install(|| count_batch(&scorer, &batch, &mut out));
        out
    };
    let one = run(1);
    assert_eq!(one, run(3));
    assert!(
        one.iter()
            .any(|c| c.inside > 0 && c.outside > 0 && c.overlap_voxels > 0)
    );
    // One scratch through the whole population, backwards, gives the same as fresh ones.
    let mut scratch = scorer.scratch();
    for i in (0..batch.len()).rev() {
        assert_eq!(
            scorer.count(batch.model(i), &mut scratch),
            one[i],
            "model {i}"
        );
    }
    // The city too.
    let city = population::<City>(10, Limits::new(4, 300, 8).unwrap(), 50, 4);
    let scene = Grid::new(
        Vec3::new(-12.0, -1.0, -12.0),
        Vec3::new(12.0, 11.0, 12.0),
        [48, 24, 48],
    )
    .unwrap();
    let scorer = city_tower_scorer(scene);
    let mut a = vec![VolumeCounts::default(); city.len()];
    let mut b = a.clone();
    rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap()
        .install(|| count_batch(&scorer, &city, &mut a));
    rayon::ThreadPoolBuilder::new()
        .num_threads(4)
        .build()
        .unwrap()
        .install(|| count_batch(&scorer, &city, &mut b));
    assert_eq!(a, b);
    assert!(a.iter().any(|c| c.inside > 0));
}

/// The triangles of the paper scene's `cube.obj`, the mesh the original places for
/// every spaceship box, in its file's order.
fn original_cube() -> Vec<[Vec3; 3]> {
    let cube = Mesh::from_obj(scenes().join("spaceship_volume/cube.obj")).unwrap();
    cube.triangles()
        .map(|t| t.map(|i| cube.positions[i as usize]))
        .collect()
}

#[test]
fn counts_equal_the_originals_on_random_spaceships() {
    let ship = Mesh::from_obj(scenes().join("spaceship_volume/spaceship_target.obj")).unwrap();
    let bound = MeshLibrary::new()
        .bind(generators::Spaceship::GRAPH)
        .unwrap();
    let (good, bad) = (2.0, 15.0);
    let grid = paper_grid();
    let scorer = VolumeScorer::new(
        grid,
        &[target("ship", ship, 1.0, -1.0)],
        &bound,
        Form::Smooth { good, bad },
    )
    .unwrap();
    let vc = original::VoxelCoords::init(grid.min(), grid.max(), [100, 200, 100]);
    let triangles = original_cube();
    let mut batch =
        population::<generators::Spaceship>(40, generators::spaceship::PAPER_LIMITS, 50, 1);
    // Hand-made: three copies of a rotated box, one poking out of the grid below and
    // beside it, one wholly outside, one flush with the grid's top face (none with a
    // face or a face's diagonal through voxel centres, where the two may differ).
    let r = turned_box();
    let out = aabb(Vec3::new(3.37, -6.13, -2.71), Vec3::new(5.83, -4.23, 1.33));
    let far = aabb(Vec3::splat(30.0), Vec3::splat(31.3));
    let flush = aabb(Vec3::new(-1.03, -0.97, 16.55), Vec3::new(1.07, 1.01, 18.0));
    // Voxels x 39 ..= 60, y 80 ..= 120 and z 100, one layer beyond the grid.
    assert_eq!(count(&scorer, &[flush]).span_out_of_grid, 22 * 41);
    batch.push_with(|m| m.extend([r, r, r, out, far, flush]));
    let t = scorer.target_voxels() as f64;
    let mut scratch = scorer.scratch();
    let (mut beyond, mut overlapping) = (0, 0);
    for i in 0..batch.len() {
        let model = batch.model(i);
        let transforms: Vec<Affine3A> = model.iter().map(|m| m.transform).collect();
        let theirs = original::count_model(&vc, &triangles, &transforms, |v| {
            scorer.classes().voxels()[v] == 1
        });
        let c = scorer.count(model, &mut scratch);
        let ours = original::Counts {
            good: c.inside,
            bad: c.outside,
            overlap: c.overlap_voxels,
            outside: c.span_out_of_grid,
        };
        assert_eq!(ours, theirs, "model {i}");
        // The original's rating, without its length term.
        let rating = good * smoothstep(0.0, t, theirs.good as f64)
            - bad
                * smoothstep(
                    0.0,
                    2.0 * t,
                    (theirs.bad + theirs.overlap + theirs.outside) as f64,
                );
        assert_eq!(scorer.fitness(&c), rating, "model {i}");
        beyond += usize::from(c.span_out_of_grid > c.out_of_grid_hits);
        overlapping += usize::from(c.overlap_hits > 0);
    }
    assert!(beyond > 10 && overlapping > 10, "{beyond} {overlapping}");
    let last = scorer.count(batch.model(batch.len() - 1), &mut scratch);
    assert!(last.overlap_hits > last.overlap_voxels, "{last:?}");
}

/// The in-grid voxels whose centres the original counts for box `t`.
fn original_coverage(
    vc: &original::VoxelCoords,
    triangles: &[[Vec3; 3]],
    t: &Affine3A,
) -> Vec<usize> {
    let mut volume = vec![0u32; vc.num_voxels()];
    original::calc_voxels_object(vc, &original::place(t, triangles), &mut volume);
    (0..volume.len()).filter(|&v| volume[v] > 0).collect()
}

/// The in-grid voxels whose centres the scorer counts for box `t`.
fn our_coverage(scorer: &VolumeScorer, t: &Affine3A) -> Vec<usize> {
    let mut covered = Vec::new();
    let one = [Instance {
        transform: *t,
        mesh: CUBE,
    }];
    scorer.coverage(&one, &mut scorer.scratch(), &mut covered);
    (0..covered.len() * 64)
        .filter(|&v| covered[v / 64] & 1 << (v % 64) != 0)
        .collect()
}

#[test]
fn boxes_cover_the_centres_the_original_covers_but_for_ties() {
    let triangles = original_cube();
    let grid = Grid::new(Vec3::ZERO, Vec3::splat(10.0), [10, 10, 10]).unwrap();
    let vc = original::VoxelCoords::init(grid.min(), grid.max(), [10, 10, 10]);
    let scorer = VolumeScorer::new(grid, &[], &cubes(), Form::Weighted { overlap: 0.0 }).unwrap();
    let index = |i, j, k| grid.index([i, j, k]).unwrap();
    let block = |lo: [i64; 3], hi: [i64; 3]| -> Vec<usize> {
        let mut v = Vec::new();
        for k in lo[2]..=hi[2] {
            for j in lo[1]..=hi[1] {
                for i in lo[0]..=hi[0] {
                    v.push(index(i, j, k));
                }
            }
        }
        v.sort_unstable();
        v
    };
    // Faces through centres (at .5): ours covers the closed box. The original's ray
    // along +y from a centre on the bottom face meets it (a crossing at t = 0 counts)
    // and the top face: it covers y in (y_min, y_max].
    let b = aabb(Vec3::new(1.25, 1.5, 1.25), Vec3::new(3.75, 3.5, 4.25));
    assert_eq!(
        our_coverage(&scorer, &b.transform),
        block([1, 1, 1], [3, 3, 3])
    );
    assert_eq!(
        original_coverage(&vc, &triangles, &b.transform),
        block([1, 2, 1], [3, 3, 3])
    );
    // On the faces along the ray, x = 1.5 and 3.5, the ray meets the top face on its
    // edge (a barycentric coordinate of 0 counts): both cover x in the closed range.
    let c = aabb(Vec3::new(1.5, 1.25, 1.25), Vec3::new(3.5, 3.75, 4.25));
    assert_eq!(
        our_coverage(&scorer, &c.transform),
        block([1, 1, 1], [3, 3, 3])
    );
    assert_eq!(
        original_coverage(&vc, &triangles, &c.transform),
        block([1, 1, 1], [3, 3, 3])
    );
    // A box whose faces' diagonals (x = z in cube.obj's triangulation of the top and
    // bottom faces) pass through centres: the ray meets both triangles of the top face
    // there, parity leaves the centres out.
    let d = aabb(Vec3::splat(1.0), Vec3::splat(4.0));
    let ours = our_coverage(&scorer, &d.transform);
    assert_eq!(ours, block([1, 1, 1], [3, 3, 3]));
    let diagonal: Vec<usize> = ours
        .iter()
        .copied()
        .filter(|&v| grid.voxel(v)[0] == grid.voxel(v)[2])
        .collect();
    assert_eq!(diagonal.len(), 9);
    let theirs: Vec<usize> = ours
        .iter()
        .copied()
        .filter(|v| !diagonal.contains(v))
        .collect();
    assert_eq!(original_coverage(&vc, &triangles, &d.transform), theirs);

    // Anywhere else the two agree: random boxes, rotated or not, of any size, where a
    // disagreement is a centre the original decides otherwise within 1e-4 of a voxel
    // (a face or a face's diagonal passes by it).
    let grid = Grid::new(
        Vec3::new(-2.0, -2.0, -2.0),
        Vec3::new(2.0, 2.0, 3.0),
        [40, 36, 44],
    )
    .unwrap();
    let vc = original::VoxelCoords::init(grid.min(), grid.max(), [40, 36, 44]);
    let scorer = VolumeScorer::new(grid, &[], &cubes(), Form::Weighted { overlap: 0.0 }).unwrap();
    let cell = grid.cell().as_vec3();
    let mut rng = ChaCha8Rng::seed_from_u64(23);
    let (mut centres, mut ties, mut snapped_ties) = (0, 0, 0);
    for n in 0..120 {
        use rand::RngExt;
        // Every other box axis-aligned with faces on multiples of half a voxel, where
        // centres on faces are common.
        let snap = n % 2 == 0;
        let pick = |rng: &mut ChaCha8Rng, lo: f32, hi: f32, step: f32| {
            let x = rng.random_range(lo..hi);
            if snap { (x / step).round() * step } else { x }
        };
        let t = if snap {
            let lo = Vec3::new(
                pick(&mut rng, -2.5, 1.0, cell.x / 2.0),
                pick(&mut rng, -2.5, 1.0, cell.y / 2.0),
                pick(&mut rng, -2.5, 2.0, cell.z / 2.0),
            );
            let size = Vec3::new(
                pick(&mut rng, 0.05, 1.5, cell.x / 2.0),
                pick(&mut rng, 0.05, 1.5, cell.y / 2.0),
                pick(&mut rng, 0.05, 1.5, cell.z / 2.0),
            );
            aabb(lo, lo + size).transform
        } else {
            let a = [0; 3].map(|_| rng.random_range(-3.2f32..3.2));
            Affine3A::from_scale_rotation_translation(
                Vec3::new(
                    rng.random_range(0.05..1.5),
                    rng.random_range(0.05..1.5),
                    rng.random_range(0.05..1.5),
                ),
                Quat::from_euler(glam::EulerRot::XYZ, a[0], a[1], a[2]),
                Vec3::new(
                    rng.random_range(-2.5..2.5),
                    rng.random_range(-2.5..2.5),
                    rng.random_range(-2.5..3.5),
                ),
            )
        };
        let placed = original::place(&t, &triangles);
        let ours = our_coverage(&scorer, &t);
        let theirs = original_coverage(&vc, &triangles, &t);
        centres += theirs.len();
        let mismatch = ours
            .iter()
            .filter(|v| theirs.binary_search(v).is_err())
            .chain(theirs.iter().filter(|v| ours.binary_search(v).is_err()));
        for &v in mismatch {
            let [i, j, k] = grid.voxel(v).map(|x| x as i32);
            let centre = vc.to_world([i, j, k]);
            let decided = original::inside(centre, &placed);
            let flips = (0..3).any(|a| {
                [-1.0, 1.0].into_iter().any(|sign| {
                    let mut p = centre;
                    p[a] += sign * 1e-4 * cell[a];
                    original::inside(p, &placed) != decided
                })
            });
            assert!(flips, "box {n} {t:?}: voxel {:?} is no tie", [i, j, k]);
            ties += 1;
            snapped_ties += usize::from(snap);
        }
    }
    assert!(centres > 20_000, "{centres}");
    assert!(ties > 0 && ties * 20 < centres, "{ties} ties of {centres}");
    assert_eq!(
        ties, snapped_ties,
        "boxes in general position agree everywhere"
    );
}

#[test]
fn the_iou_form_is_good_times_the_voxel_iou_and_counts_what_lies_beyond_the_grid() {
    use shapegen_runtime::score::metrics::voxel_iou;
    let scorer = unit_scene(Form::Iou { good: 3.0 });
    let cube = aabb;
    let fitness = |model: &[Instance]| {
        let counts = scorer.count(model, &mut scorer.scratch());
        (scorer.fitness(&counts), voxel_iou(&scorer, &counts))
    };
    // The target itself: IoU 1.
    assert_eq!(fitness(&[cube(Vec3::ZERO, Vec3::splat(5.0))]), (3.0, 1.0));
    // Two fifths of it: 50 of its 125 voxels.
    let (f, iou) = fitness(&[cube(Vec3::ZERO, Vec3::new(2.0, 5.0, 5.0))]);
    assert_eq!((f, iou), (3.0 * (50.0 / 125.0), 50.0 / 125.0));
    // The target and 25 voxels beside it: 125 / 150.
    let (f, iou) = fitness(&[cube(Vec3::ZERO, Vec3::new(6.0, 5.0, 5.0))]);
    assert_eq!((f, iou), (3.0 * (125.0 / 150.0), 125.0 / 150.0));
    // Nothing: 0.
    assert_eq!(fitness(&[]), (0.0, 0.0));
    // The target and a box beyond the grid: the report's IoU is 1 on the grid, the
    // fitness counts the covered points beyond it in the union.
    let beyond = cube(Vec3::splat(20.0), Vec3::splat(22.0));
    let (f, iou) = fitness(&[cube(Vec3::ZERO, Vec3::splat(5.0)), beyond]);
    assert_eq!(iou, 1.0);
    assert!(f < 3.0 && f > 0.0, "{f}");
}
