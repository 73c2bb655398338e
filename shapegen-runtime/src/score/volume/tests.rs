//! Coverage checked point by point against direct `f64` geometry.

use glam::{Affine3A, DVec3, EulerRot, Quat, Vec3};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

use super::Grid;
use super::parity::{Bounds, Voxelizer};
use super::quant::{Placement, quantize, usable_linear};
use crate::geometry::Mesh;

/// The lattice points the integer path covers for box `t`.
fn quantised_points(grid: &Grid, t: &Affine3A) -> Vec<[i64; 3]> {
    let Placement::Box(q) = quantize(grid, t) else {
        return Vec::new();
    };
    let mut out = Vec::new();
    for k in 0..q.extent[2] {
        for j in 0..q.extent[1] {
            if let Some((a, b)) = q.row(j, k) {
                for i in a..=b {
                    out.push([
                        i64::from(q.corner[0] + i),
                        i64::from(q.corner[1] + j),
                        i64::from(q.corner[2] + k),
                    ]);
                }
            }
        }
    }
    out
}

/// The local coordinates of lattice point `idx` in box `t`, and the world distance
/// from it to each face plane pair.
fn local(grid: &Grid, t: &Affine3A, idx: [i64; 3]) -> (DVec3, DVec3) {
    let (m, shift) = usable_linear(t.matrix3, Vec3::from(t.translation)).unwrap();
    let inv = m.inverse();
    let u = inv * (grid.centre(idx) - shift);
    let rows = inv.transpose();
    let dist = DVec3::new(
        ((u.x.abs() - 0.5) / rows.x_axis.length()).abs(),
        ((u.y.abs() - 0.5) / rows.y_axis.length()).abs(),
        ((u.z.abs() - 0.5) / rows.z_axis.length()).abs(),
    );
    (u, dist)
}

fn random_box(rng: &mut ChaCha8Rng) -> Affine3A {
    let size = Vec3::new(
        rng.random_range(0.05..2.5),
        rng.random_range(0.05..2.5),
        rng.random_range(0.05..2.5),
    );
    let angles = [0; 3].map(|_| rng.random_range(-3.2f32..3.2));
    let rotation = Quat::from_euler(EulerRot::XYZ, angles[0], angles[1], angles[2]);
    let centre = Vec3::new(
        rng.random_range(-2.5..2.5),
        rng.random_range(-2.5..2.5),
        rng.random_range(-2.5..2.5),
    );
    Affine3A::from_scale_rotation_translation(size, rotation, centre)
}

#[test]
fn rotated_boxes_match_point_in_box_except_at_faces() {
    let grid = Grid::new(Vec3::splat(-2.0), Vec3::new(2.0, 2.0, 3.0), [40, 36, 44]).unwrap();
    let tolerance = 1e-4 * grid.cell().min_element();
    let mut rng = ChaCha8Rng::seed_from_u64(11);
    let (mut points, mut disagreements) = (0usize, 0usize);
    for _ in 0..200 {
        let t = random_box(&mut rng);
        let mut covered = quantised_points(&grid, &t);
        covered.sort_unstable();
        // Brute force over a generous box around the instance.
        let reach = Vec3::from(t.matrix3.x_axis).abs()
            + Vec3::from(t.matrix3.y_axis).abs()
            + Vec3::from(t.matrix3.z_axis).abs();
        let c = Vec3::from(t.translation).as_dvec3();
        let lo = grid.to_lattice(c - reach.as_dvec3()).floor();
        let hi = grid.to_lattice(c + reach.as_dvec3()).ceil();
        let mut brute = Vec::new();
        for k in lo.z as i64..=hi.z as i64 {
            for j in lo.y as i64..=hi.y as i64 {
                for i in lo.x as i64..=hi.x as i64 {
                    let (u, _) = local(&grid, &t, [i, j, k]);
                    if u.abs().max_element() <= 0.5 {
                        brute.push([i, j, k]);
                    }
                }
            }
        }
        brute.sort_unstable();
        points += brute.len();
        for p in &covered {
            assert!(
                p[0] >= lo.x as i64 && p[0] <= hi.x as i64,
                "inside the search box"
            );
        }
        let mismatch = covered
            .iter()
            .filter(|p| brute.binary_search(p).is_err())
            .chain(brute.iter().filter(|p| covered.binary_search(p).is_err()));
        for &p in mismatch {
            let (_, dist) = local(&grid, &t, p);
            assert!(
                dist.min_element() <= tolerance,
                "point {p:?} of {t:?} is {} cells from a face",
                dist.min_element() / grid.cell().min_element()
            );
            disagreements += 1;
        }
    }
    assert!(points > 100_000, "the boxes cover enough to test: {points}");
    assert!(
        disagreements * 10_000 < points,
        "{disagreements} of {points}"
    );
}

#[test]
fn parity_of_transformed_meshes_matches_point_in_box() {
    // The unit cube voxelized by parity as a mesh, under random transforms, against the
    // same f64 point-in-box test.
    let grid = Grid::new(Vec3::splat(-2.0), Vec3::splat(2.0), [30, 34, 38]).unwrap();
    let tolerance = 1e-6 * grid.cell().min_element();
    let cube = Mesh::unit_cube();
    let mut voxelizer = Voxelizer::default();
    let mut rng = ChaCha8Rng::seed_from_u64(5);
    let mut total = 0;
    for _ in 0..100 {
        let t = random_box(&mut rng);
        let (m, shift) = usable_linear(t.matrix3, Vec3::from(t.translation)).unwrap();
        let mut covered = Vec::new();
        voxelizer
            .run(
                &cube,
                |p| grid.to_lattice(m * p.as_dvec3() + shift),
                Bounds::Lattice,
                |j, k, a, b| {
                    covered.extend((a..=b).map(|i| [i, j, k]));
                },
            )
            .unwrap();
        for &p in &covered {
            let (u, dist) = local(&grid, &t, p);
            assert!(
                u.abs().max_element() <= 0.5 || dist.min_element() <= tolerance,
                "{p:?}"
            );
        }
        covered.sort_unstable();
        let before = covered.len();
        covered.dedup();
        assert_eq!(before, covered.len(), "each point once");
        let all = quantised_points(&grid, &t);
        for p in &all {
            let (_, dist) = local(&grid, &t, *p);
            assert!(
                covered.binary_search(p).is_ok()
                    || dist.min_element() <= 1e-4 * grid.cell().min_element()
            );
        }
        total += covered.len();
    }
    assert!(total > 10_000, "{total}");
}

/// The F-score form's surface counts (`surface.rs`), against their definition.
mod fscore {
    use glam::{Affine3A, Quat, Vec3};
    use rand::{RngExt, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    use super::super::counts::VolumeCounts;
    use super::super::grid::Grid;
    use super::super::scorer::VolumeScorer;
    use super::super::surface::*;
    use super::super::target::{Fill, VolumeTarget};
    use crate::geometry::{CUBE, Instance, Mesh, MeshLibrary};
    use crate::score::form::Form;
    use crate::score::retained::RetainedScorer;
    use crate::score::scorer::Scorer;

    /// A box target of the given half-size and centre.
    fn box_target(half: Vec3, centre: Vec3) -> VolumeTarget {
        let mut mesh = Mesh::unit_cube();
        for p in &mut mesh.positions {
            *p = *p * 2.0 * half + centre;
        }
        VolumeTarget {
            name: "box".into(),
            mesh,
            inside: 1.0,
            outside: -1.0,
            fill: Fill::Parity,
        }
    }

    fn random_box(rng: &mut ChaCha8Rng) -> Instance {
        let size = Vec3::new(
            rng.random_range(0.1..1.5),
            rng.random_range(0.1..1.5),
            rng.random_range(0.1..1.5),
        );
        let turn = Quat::from_rotation_z(rng.random_range(-0.6f32..0.6));
        let centre = Vec3::new(
            rng.random_range(-1.6..1.6),
            rng.random_range(-1.6..1.6),
            rng.random_range(-1.6..1.6),
        );
        Instance {
            transform: Affine3A::from_scale_rotation_translation(size, turn, centre),
            mesh: CUBE,
        }
    }

    /// The F-score counts of `covered` on `scorer`'s grid, by the definition: face
    /// neighbours and every pair of surface voxels.
    fn by_definition(scorer: &VolumeScorer, covered: &[u64], threshold: f64) -> [u64; 3] {
        let grid = scorer.grid();
        let cell = grid.cell().to_array();
        let target: Vec<u64> = {
            let mut inside = vec![0u64; covered.len()];
            for (v, &c) in scorer.classes().voxels().iter().enumerate() {
                if scorer.classes().is_target(usize::from(c)) {
                    set(&mut inside, v);
                }
            }
            surface_voxels(grid, &inside)
        };
        let model = surface_voxels(grid, covered);
        let voxels = |bits: &[u64]| -> Vec<[i64; 3]> {
            (0..grid.voxel_count() as usize)
                .filter(|&v| get(bits, v))
                .map(|v| grid.voxel(v))
                .collect()
        };
        let (s, t) = (voxels(&model), voxels(&target));
        let near = |a: &[i64; 3], b: &[[i64; 3]]| {
            b.iter()
                .any(|b| within(cell, [a[0] - b[0], a[1] - b[1], a[2] - b[2]], threshold))
        };
        [
            s.len() as u64,
            s.iter().filter(|a| near(a, &t)).count() as u64,
            t.iter().filter(|a| near(a, &s)).count() as u64,
        ]
    }

    fn surface_of(c: &VolumeCounts) -> [u64; 3] {
        [c.surface, c.surface_near, c.target_surface_near]
    }

    #[test]
    fn surface_counts_are_those_of_the_definition_counted_from_nothing_or_kept() {
        let meshes = MeshLibrary::new().bind_names("Boxes", &["cube"]).unwrap();
        // Rows of 70 voxels cross words; rows of 5 share them; voxels of three sizes.
        for (resolution, threshold) in [([70, 9, 8], 0.45), ([5, 31, 13], 0.3), ([12, 10, 9], 0.05)]
        {
            let grid = Grid::new(Vec3::splat(-2.0), Vec3::new(2.0, 2.0, 2.5), resolution).unwrap();
            let target = box_target(Vec3::new(1.1, 0.7, 0.9), Vec3::new(0.2, -0.1, 0.3));
            let form = Form::FScore {
                good: 1.0,
                threshold,
            };
            let scorer = VolumeScorer::new(grid, &[target], &meshes, form).unwrap();
            let mut rng = ChaCha8Rng::seed_from_u64(resolution[0] as u64);
            let mut scratch = scorer.scratch();
            let mut covered = Vec::new();
            let mut seen = [0; 3];
            for _ in 0..12 {
                let n = rng.random_range(1..5);
                let model: Vec<Instance> = (0..n).map(|_| random_box(&mut rng)).collect();
                let counts = scorer.coverage(&model, &mut scratch, &mut covered);
                let expected = by_definition(&scorer, &covered, threshold);
                assert_eq!(surface_of(&counts), expected, "{resolution:?}, {n} boxes");
                seen = [0, 1, 2].map(|i| seen[i] + expected[i]);
                // Kept: the parent's state with one box replaced counts the child.
                let mut state = scorer.count_retained(&model, &mut scratch).unwrap();
                assert_eq!(surface_of(&scorer.state_counts(&state)), expected);
                let mut child = model.clone();
                child[0] = random_box(&mut rng);
                scorer
                    .update(&mut state, &model[..1], &child[..1], &mut scratch)
                    .unwrap();
                let full = scorer.count(&child, &mut scratch);
                assert_eq!(scorer.state_counts(&state), full);
                assert_eq!(
                    surface_of(&full),
                    by_definition(
                        &scorer,
                        &{
                            scorer.coverage(&child, &mut scratch, &mut covered);
                            covered.clone()
                        },
                        threshold
                    )
                );
            }
            assert!(seen.iter().all(|&n| n > 0), "{resolution:?}: {seen:?}");
        }
    }

    #[test]
    fn the_target_itself_scores_good_and_nothing_scores_zero() {
        let meshes = MeshLibrary::new().bind_names("Boxes", &["cube"]).unwrap();
        let grid = Grid::new(Vec3::splat(-1.0), Vec3::splat(1.0), [8, 8, 8]).unwrap();
        let target = box_target(Vec3::splat(0.5), Vec3::ZERO);
        let form = Form::FScore {
            good: 2.0,
            threshold: 0.2,
        };
        let scorer = VolumeScorer::new(grid, &[target], &meshes, form).unwrap();
        let mut scratch = scorer.scratch();
        // The 4^3 target voxels: their 56 outer voxels are its surface.
        assert_eq!(scorer.target_surface_voxels(), Some(56));
        let exact = [Instance {
            transform: Affine3A::IDENTITY,
            mesh: CUBE,
        }];
        assert_eq!(scorer.fitness(&scorer.count(&exact, &mut scratch)), 2.0);
        assert_eq!(scorer.fitness(&scorer.count(&[], &mut scratch)), 0.0);
        // A box one voxel (0.25) larger each way, 6^3 voxels: its 152 surface voxels lie
        // a voxel beyond the target's, outside the threshold of 0.2.
        let larger = [Instance {
            transform: Affine3A::from_scale(Vec3::splat(1.5)),
            mesh: CUBE,
        }];
        let counts = scorer.count(&larger, &mut scratch);
        assert_eq!(surface_of(&counts), [152, 0, 0]);
        assert_eq!(scorer.fitness(&counts), 0.0);
        // With a threshold of a voxel, the 96 voxels of its faces are within reach of
        // the target's surface, those of its 12 edges and 8 corners are not; every
        // target surface voxel has one of its face voxels a voxel away.
        let reach = |threshold| {
            let form = Form::FScore {
                good: 2.0,
                threshold,
            };
            let target = box_target(Vec3::splat(0.5), Vec3::ZERO);
            VolumeScorer::new(grid, &[target], &meshes, form).unwrap()
        };
        let one = reach(0.25);
        let counts = one.count(&larger, &mut scratch);
        assert_eq!(surface_of(&counts), [152, 96, 56]);
        let precision = 96.0 / 152.0;
        let f = 2.0 * precision / (precision + 1.0);
        assert_eq!(one.fitness(&counts), 2.0 * f);
        // With the diagonal of a voxel, all are.
        let diagonal = reach(0.25 * 3f64.sqrt() + 1e-9);
        let counts = diagonal.count(&larger, &mut scratch);
        assert_eq!(surface_of(&counts), [152, 152, 56]);
        assert_eq!(diagonal.fitness(&counts), 2.0);
    }

    #[test]
    fn thresholds_that_are_no_distance_or_too_wide_are_refused() {
        let meshes = MeshLibrary::new().bind_names("Boxes", &["cube"]).unwrap();
        let grid = Grid::new(Vec3::splat(-1.0), Vec3::splat(1.0), [200, 4, 4]).unwrap();
        for (threshold, says) in [
            (0.0, "not a distance"),
            (f64::NAN, "not a distance"),
            (0.65, "spans 65 voxels of 0.01 along x; at most 63"),
        ] {
            let form = Form::FScore {
                good: 1.0,
                threshold,
            };
            let target = box_target(Vec3::splat(0.5), Vec3::ZERO);
            let err = VolumeScorer::new(grid, &[target], &meshes, form)
                .unwrap_err()
                .to_string();
            assert!(err.contains(says), "{err}");
        }
    }
}
