//! A voxel set as a closed surface mesh: the faces between covered and empty voxels,
//! written as OBJ, so that voxelizing the file again gives back exactly the same voxels.

use std::collections::HashMap;
use std::fmt::Write as _;

use shapegen::score::volume::Grid;

/// The OBJ text of the boundary of the voxels whose bits are set in `covered` (voxel `v`
/// is bit `v % 64` of word `v / 64`, numbered as [`Grid::index`] numbers them), with
/// outward, counter-clockwise quads and shared vertices. Returns the text and the number
/// of faces.
pub fn voxel_surface_obj(grid: &Grid, covered: &[u64]) -> (String, usize) {
    let res = grid.resolution().map(i64::from);
    let is_covered = |idx: [i64; 3]| {
        grid.index(idx)
            .is_some_and(|v| covered.get(v / 64).is_some_and(|w| w >> (v % 64) & 1 == 1))
    };
    let mut vertices: HashMap<[i64; 3], usize> = HashMap::new();
    let mut positions = String::new();
    let mut faces = String::new();
    let mut count = 0;
    let mut vertex = |corner: [i64; 3], positions: &mut String| {
        let next = vertices.len() + 1;
        *vertices.entry(corner).or_insert_with(|| {
            let p =
                grid.min().as_dvec3() + grid.cell() * glam::DVec3::from(corner.map(|c| c as f64));
            // Shortest decimals that read back to the same f32.
            let _ = writeln!(positions, "v {} {} {}", p.x as f32, p.y as f32, p.z as f32);
            next
        })
    };
    for k in 0..res[2] {
        for j in 0..res[1] {
            for i in 0..res[0] {
                let idx = [i, j, k];
                if !is_covered(idx) {
                    continue;
                }
                for axis in 0..3 {
                    for positive in [false, true] {
                        let mut neighbour = idx;
                        neighbour[axis] += if positive { 1 } else { -1 };
                        if is_covered(neighbour) {
                            continue;
                        }
                        let (b, c) = ((axis + 1) % 3, (axis + 2) % 3);
                        let mut base = idx;
                        base[axis] += i64::from(positive);
                        let at = |db: i64, dc: i64| {
                            let mut p = base;
                            p[b] += db;
                            p[c] += dc;
                            p
                        };
                        let mut quad = [at(0, 0), at(1, 0), at(1, 1), at(0, 1)];
                        if !positive {
                            quad.reverse();
                        }
                        let ids = quad.map(|corner| vertex(corner, &mut positions));
                        let _ = writeln!(faces, "f {} {} {} {}", ids[0], ids[1], ids[2], ids[3]);
                        count += 1;
                    }
                }
            }
        }
    }
    (
        format!("# voxel surface: {count} faces\n{positions}{faces}"),
        count,
    )
}
