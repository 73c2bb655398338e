//! The original implementation's volume counting transcribed to Rust, operation by
//! operation in `f32` (products and sums rounded one at a time, in the order the source
//! writes them): `VoxelCoords` (`genetics/shared/utils/VoxelCoords.h`), the kernels
//! `d_calc_voxels_objects`, `ray_triangle_intersect` and `d_compare_voxels`
//! (`genetics/eval/gpuvolume/nvrtc_files/VolumeEvaluator.cu`) and what
//! `GpuVolumeEvaluator::calcObjectVoxels` makes of them, with each GPU thread's work
//! done one after another. The reference the volume scorer's counts are checked
//! against.

use glam::{Affine3A, Vec3};

/// `math::float4x4`, rows first.
type Mat4 = [[f32; 4]; 4];

/// `EPSILON` of `VolumeEvaluator.cu`.
const EPSILON: f32 = 0.000_000_1;

fn mul4(a: &Mat4, b: &Mat4) -> Mat4 {
    std::array::from_fn(|r| {
        std::array::from_fn(|c| {
            a[r][0] * b[0][c] + a[r][1] * b[1][c] + a[r][2] * b[2][c] + a[r][3] * b[3][c]
        })
    })
}

fn mat_vec(m: &Mat4, v: [f32; 4]) -> [f32; 4] {
    std::array::from_fn(|r| m[r][0] * v[0] + m[r][1] * v[1] + m[r][2] * v[2] + m[r][3] * v[3])
}

fn scale(s: [f32; 3]) -> Mat4 {
    [
        [s[0], 0.0, 0.0, 0.0],
        [0.0, s[1], 0.0, 0.0],
        [0.0, 0.0, s[2], 0.0],
        [0.0, 0.0, 0.0, 1.0],
    ]
}

fn translation(d: [f32; 3]) -> Mat4 {
    [
        [1.0, 0.0, 0.0, d[0]],
        [0.0, 1.0, 0.0, d[1]],
        [0.0, 0.0, 1.0, d[2]],
        [0.0, 0.0, 0.0, 1.0],
    ]
}

/// `PGA::VoxelCoords`.
pub struct VoxelCoords {
    voxels: [i32; 3],
    m: Mat4,
    m_inv: Mat4,
}

impl VoxelCoords {
    /// `VoxelCoords::init`.
    pub fn init(bb_min: Vec3, bb_max: Vec3, voxels: [i32; 3]) -> VoxelCoords {
        let size: [f32; 3] = std::array::from_fn(|a| (bb_max[a] - bb_min[a]) / voxels[a] as f32);
        // `bb_min * -1.0f` and `-1.0f * translation` are exact negations.
        let t: [f32; 3] = std::array::from_fn(|a| -bb_min[a] - size[a] / 2.0);
        let scaling = size.map(|s| 1.0 / s);
        let m = mul4(&scale(scaling), &translation(t));
        let m_inv = mul4(&translation(t.map(|x| -x)), &scale(size));
        VoxelCoords { voxels, m, m_inv }
    }

    /// `VoxelCoords::toVoxel`.
    pub fn to_voxel(&self, p: [f32; 3]) -> [i32; 3] {
        let x = mat_vec(&self.m, [p[0], p[1], p[2], 1.0]);
        std::array::from_fn(|a| ((x[a] / x[3]) + 0.5).floor() as i32)
    }

    /// `VoxelCoords::toWorld`.
    pub fn to_world(&self, c: [i32; 3]) -> [f32; 3] {
        let x = mat_vec(&self.m_inv, [c[0] as f32, c[1] as f32, c[2] as f32, 1.0]);
        std::array::from_fn(|a| x[a] / x[3])
    }

    /// `VoxelCoords::check`.
    pub fn check(&self, c: [i32; 3]) -> bool {
        (0..3).all(|a| c[a] >= 0 && c[a] < self.voxels[a])
    }

    /// `VoxelCoords::toIndex`, for coordinates that pass `check`.
    pub fn to_index(&self, c: [i32; 3]) -> usize {
        let [nx, ny, _] = self.voxels;
        (c[0] + nx * c[1] + ny * nx * c[2]) as usize
    }

    /// `VoxelCoords::numVoxels`.
    pub fn num_voxels(&self) -> usize {
        self.voxels.iter().map(|&n| n as usize).product()
    }
}

fn sub(a: [f32; 3], b: [f32; 3]) -> [f32; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn cross(a: [f32; 3], b: [f32; 3]) -> [f32; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn dot(a: [f32; 3], b: [f32; 3]) -> f32 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// `ray_triangle_intersect` (Möller–Trumbore).
fn ray_triangle_intersect(o: [f32; 3], d: [f32; 3], tri: &[[f32; 3]; 3]) -> bool {
    let [v0, v1, v2] = *tri;
    let e1 = sub(v1, v0);
    let e2 = sub(v2, v0);
    let p = cross(d, e2);
    let det = dot(e1, p);
    if det > -EPSILON && det < EPSILON {
        return false;
    }
    let t = sub(o, v0);
    let q = cross(t, e1);
    // `result * 1.0f/det` is `(result * 1.0f) / det`.
    let [rx, ry, rz] = [dot(e2, q), dot(t, p), dot(d, q)].map(|x| x * 1.0 / det);
    // As written: a NaN coordinate is no miss.
    #[allow(clippy::manual_range_contains)]
    let mut miss = ry < 0.0 || ry > 1.0;
    miss |= rz < 0.0 || (ry + rz) > 1.0;
    miss |= rx < 0.0;
    !miss
}

/// The triangles of `mesh` placed by `t` as `instance * float4(v, 1.0f)` places them,
/// the matrix's rows being those of `t`.
pub fn place(t: &Affine3A, triangles: &[[Vec3; 3]]) -> Vec<[[f32; 3]; 3]> {
    let m = &t.matrix3;
    let rows: [[f32; 4]; 3] =
        std::array::from_fn(|r| [m.x_axis[r], m.y_axis[r], m.z_axis[r], t.translation[r]]);
    triangles
        .iter()
        .map(|tri| {
            tri.map(|v| {
                std::array::from_fn(|r| {
                    rows[r][0] * v.x + rows[r][1] * v.y + rows[r][2] * v.z + rows[r][3] * 1.0
                })
            })
        })
        .collect()
}

/// Whether the ray from `centre` along +y crosses `placed` an odd number of times: the
/// inner loop of `d_calc_voxels_objects`.
pub fn inside(centre: [f32; 3], placed: &[[[f32; 3]; 3]]) -> bool {
    let mut hits = false;
    for tri in placed {
        if ray_triangle_intersect(centre, [0.0, 1.0, 0.0], tri) {
            hits = !hits;
        }
    }
    hits
}

/// `d_calc_voxels_objects` for one instance (one block): adds 1 to `voxel_volume` at
/// each in-grid voxel of the instance's span whose centre is inside it, and returns how
/// many voxels of the span are outside the grid.
pub fn calc_voxels_object(
    vc: &VoxelCoords,
    placed: &[[[f32; 3]; 3]],
    voxel_volume: &mut [u32],
) -> u64 {
    let first = vc.to_voxel(placed[0][0]);
    let (mut s_min, mut s_max) = (first, first);
    for tri in placed {
        for v in tri {
            let c = vc.to_voxel(*v);
            for a in 0..3 {
                s_min[a] = s_min[a].min(c[a]);
                s_max[a] = s_max[a].max(c[a]);
            }
        }
    }
    let span: [i64; 3] = std::array::from_fn(|a| i64::from(s_max[a] - s_min[a]) + 1);
    let num_voxels = span[0] * span[1] * span[2];
    assert!(num_voxels < 1 << 31, "the original's int would overflow");
    let mut outside = 0;
    for index in 0..num_voxels {
        let coord = [
            index % span[0],
            index / span[0] % span[1],
            index / (span[0] * span[1]),
        ];
        let voxel: [i32; 3] = std::array::from_fn(|a| coord[a] as i32 + s_min[a]);
        if !vc.check(voxel) {
            outside += 1;
        } else if inside(vc.to_world(voxel), placed) {
            voxel_volume[vc.to_index(voxel)] += 1;
        }
    }
    outside
}

/// What `calcObjectVoxels` leaves for the rating: `_good_voxels`, `_bad_voxels`, the
/// distinct voxels `d_compare_voxels` counts as overlap, and the kernel's
/// `outside_voxels` (the original adds the last two into `_overlap_voxels`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Counts {
    pub good: u64,
    pub bad: u64,
    pub overlap: u64,
    pub outside: u64,
}

/// `calcObjectVoxels` for a model of instances of one mesh, `triangles`, against the
/// target voxels `target(voxel index)`.
pub fn count_model(
    vc: &VoxelCoords,
    triangles: &[[Vec3; 3]],
    instances: &[Affine3A],
    target: impl Fn(usize) -> bool,
) -> Counts {
    let mut volume = vec![0u32; vc.num_voxels()];
    let mut counts = Counts::default();
    for t in instances {
        counts.outside += calc_voxels_object(vc, &place(t, triangles), &mut volume);
    }
    for (index, &n) in volume.iter().enumerate() {
        let (v_t, v_o) = (target(index), n != 0);
        if v_t && v_o {
            counts.good += 1;
        } else if v_o && !v_t {
            counts.bad += 1;
        }
        if n > 1 {
            counts.overlap += 1;
        }
    }
    counts
}
