//! The lot building on lots of every shape: random buildings on a random family of
//! simple polygons (rectilinear L, U, T and stepped outlines, star-shaped concave ones,
//! very thin ones, and outlines with collinear and repeated points) are closed surfaces
//! facing out, stand inside their lot plus the roofs' overhang, and fill as much of the
//! volume scorer's grid as they enclose.

use generators::lot_building::{self, LotBuilding};
use glam::{DVec2, DVec3, Vec3, dvec2};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use shapegen_runtime::geometry::{
    BoundMeshes, Mesh, Polygon, facet_triangles, open_edges, signed_volume,
};
use shapegen_runtime::prelude::*;
use shapegen_runtime::score::volume::{Fill, Grid, VolumeScorer, VolumeTarget};
use shapegen_runtime::score::{Form, Scorer};
use shapegen_runtime::{Instance, Site};

/// The largest overhang a roof of the grammar takes.
const OVERHANG: f64 = 0.8;

fn meshes() -> BoundMeshes {
    generators::default_meshes()
        .bind(LotBuilding::GRAPH)
        .expect("the default meshes hold the lot building's")
}

/// A rectilinear outline: a staircase of `steps` random steps up the right and back
/// down the left (L, U, T and stepped lots), about `size` across.
fn rectilinear(rng: &mut ChaCha8Rng, size: f64) -> Vec<DVec2> {
    let steps = rng.random_range(1..=3);
    let mut right = Vec::new();
    let mut left = Vec::new();
    let mut y = 0.0;
    for _ in 0..steps {
        let next = y + rng.random_range(0.25..1.0) * size / steps as f64;
        let (r, l) = (
            rng.random_range(0.2..0.5) * size,
            rng.random_range(0.2..0.5) * size,
        );
        right.extend([dvec2(r, y), dvec2(r, next)]);
        left.extend([dvec2(-l, y), dvec2(-l, next)]);
        y = next;
    }
    left.reverse();
    right.into_iter().chain(left).collect()
}

/// A star-shaped outline: `n` corners at random radii around the origin, in angle
/// order (concave where a radius dips).
fn star(rng: &mut ChaCha8Rng, size: f64) -> Vec<DVec2> {
    let n = rng.random_range(5..=12);
    (0..n)
        .map(|k| {
            let a = std::f64::consts::TAU * (k as f64 + rng.random_range(0.0..0.6)) / n as f64;
            let r = size * rng.random_range(0.25..0.5);
            dvec2(a.cos(), a.sin()) * r
        })
        .collect()
}

/// The family: rectilinear and star-shaped outlines, a thin bar, and outlines with a
/// repeated and a collinear point, turned by a random angle.
fn lots(seed: u64, count: usize) -> Vec<Polygon> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    (0..count)
        .map(|k| {
            let size = rng.random_range(8.0..24.0);
            let mut points = match k % 4 {
                0 => rectilinear(&mut rng, size),
                1 => star(&mut rng, size),
                2 => {
                    let w = rng.random_range(0.8..2.0);
                    vec![
                        dvec2(-size, -w),
                        dvec2(size, -w),
                        dvec2(size, w),
                        dvec2(-size, w),
                    ]
                }
                _ => {
                    let mut p = rectilinear(&mut rng, size);
                    // A repeated point, and a point halfway along the first edge.
                    p.insert(1, p[1]);
                    let mid = (p[0] + p[1]) / 2.0;
                    p.insert(1, mid);
                    p
                }
            };
            let turn = DVec2::from_angle(rng.random_range(0.0..std::f64::consts::TAU));
            for p in &mut points {
                *p = turn.rotate(*p);
            }
            Polygon::from_f64(&points).expect("the family's outlines are simple")
        })
        .collect()
}

/// Random buildings on `lot`, grown to about `genes` genes.
fn buildings(lot: &Polygon, seed: u64, count: usize, genes: u32) -> Vec<Vec<Instance>> {
    let site = Site::with_lot(lot.clone());
    let mut ops = Operators::<LotBuilding>::new(lot_building::LIMITS).unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    (0..count)
        .map(|_| {
            let mut out = Vec::new();
            ops.random(genes, &mut rng).derive_on(&site, &mut out);
            out
        })
        .collect()
}

#[test]
fn buildings_on_every_lot_are_closed_and_stand_on_it() {
    let meshes = meshes();
    let mut built = 0;
    for (l, lot) in lots(7, 24).iter().enumerate() {
        let (_, eave) = lot.offset_at_most(OVERHANG);
        for (b, building) in buildings(lot, l as u64, 6, 30).iter().enumerate() {
            let what = format!("lot {l} ({} corners), building {b}", lot.len());
            assert!(!building.is_empty(), "{what}: empty");
            let triangles = facet_triangles(building, &meshes);
            assert_eq!(
                triangles.len(),
                building.len(),
                "{what}: every part a facet"
            );
            // Closed surfaces facing out: every edge run as often each way (storeys and
            // roofs that touch share edges, so an edge may be used four times).
            let open: Vec<_> = open_edges(&triangles)
                .into_iter()
                .filter(|e| e.net != 0)
                .collect();
            assert!(open.is_empty(), "{what}: open along {:?}", &open[..1]);
            let volume = signed_volume(&triangles);
            assert!(volume > 0.0, "{what}: volume {volume}");
            // On the ground, inside the lot plus the overhang.
            for p in triangles.iter().flatten() {
                assert!(p.y > -1e-4, "{what}: {p} below the ground");
                let map = dvec2(p.x, -p.z);
                assert!(eave.contains_f64(map, 1e-3), "{what}: {p} off the lot");
            }
            built += 1;
        }
    }
    assert_eq!(built, 24 * 6);
}

#[test]
fn every_roof_and_facade_node_is_grown() {
    // Over many random buildings, every node type appears, and every part is emitted.
    let lot = &lots(3, 1)[0];
    let mut parts = [0usize; 5];
    for building in buildings(lot, 5, 40, 40) {
        for i in &building {
            let k = [
                lot_building::WALL,
                lot_building::ROOF,
                lot_building::WINDOW,
                lot_building::DOOR,
                lot_building::SLAB,
            ]
            .iter()
            .position(|&m| m == i.mesh)
            .expect("a part of the grammar");
            parts[k] += 1;
        }
    }
    assert!(
        parts.iter().all(|&n| n > 0),
        "wall, roof, window, door, slab: {parts:?}"
    );
}

#[test]
fn the_volume_scorer_fills_what_a_building_encloses() {
    // A 0.25-unit grid: a voxel centre on the wrong side of the surface lies within half
    // a voxel diagonal of it, so the voxels counted differ from the enclosed volume by
    // at most the surface area times that distance.
    let meshes = meshes();
    let res = 96u32;
    let grid = Grid::new(
        Vec3::new(-12.013, -0.037, -12.029),
        Vec3::new(11.987, 23.963, 11.971),
        [res; 3],
    )
    .unwrap();
    let cell = grid.cell();
    let voxel = cell.x * cell.y * cell.z;
    let target = VolumeTarget {
        name: "block".into(),
        mesh: Mesh::unit_cube(),
        inside: 1.0,
        outside: -1.0,
        fill: Fill::Parity,
    };
    let scorer =
        VolumeScorer::new(grid, &[target], &meshes, Form::Weighted { overlap: 0.5 }).unwrap();
    let mut scratch = scorer.scratch();
    let l = lot_building::L_LOT.clone();
    let mut checked = 0;
    for building in buildings(&l, 9, 12, 30) {
        let triangles = facet_triangles(&building, &meshes);
        let (lo, hi) = bounds(&triangles);
        if lo.y < 0.0 || hi.y > 23.9 || lo.x < -11.9 || hi.x > 11.9 {
            continue;
        }
        let volume = signed_volume(&triangles);
        let area: f64 = triangles
            .iter()
            .map(|[a, b, c]| (*b - *a).cross(*c - *a).length() / 2.0)
            .sum();
        let counts = scorer.count(&building, &mut scratch);
        let covered = (counts.inside + counts.outside) as f64 * voxel;
        let slack = area * cell.length() / 2.0;
        assert!(
            (covered - volume).abs() <= slack,
            "covered {covered:.1}, enclosed {volume:.1}, slack {slack:.1}"
        );
        checked += 1;
    }
    assert!(checked >= 6, "only {checked} buildings fit the grid");
}

/// The box of the triangles' corners.
fn bounds(triangles: &[[DVec3; 3]]) -> (DVec3, DVec3) {
    triangles
        .iter()
        .flatten()
        .fold((DVec3::MAX, DVec3::MIN), |(lo, hi), &p| {
            (lo.min(p), hi.max(p))
        })
}
