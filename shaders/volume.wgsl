// Volume scoring of box instances: one invocation per (instance, row) pair.
//
// Each box is a `QuantBox` quantised on the CPU (shapegen-runtime/src/score/volume/
// quant.rs); this shader evaluates exactly the same i32 formulas, so its counts equal the
// CPU's bit for bit. What the CPU rasterises itself (other meshes, facets) arrives as
// boxes without planes (all coefficients 0), whose every row covers its whole extent.
// Rows of a pass are numbered through all its boxes: box b owns rows
// `boxes[b].extent.w ..` (a prefix sum computed on the CPU), `nj * nk` of them.
//
// Per model of the pass, `covered` holds a bitset over the grid (32 voxels per word):
// atomicOr marks a row's voxels, and bits that were already set are overlap hits; those
// are marked in a second bitset, `again`, and the bits newly set there are voxels
// covered more than once, each counted once, by the one invocation that set it. Newly
// covered voxels are counted by class (4 bits per voxel in `classes`) in the
// invocation, then added to the model's counters: for each quantity two words, the low
// and high halves of a 64-bit count.

// Mirrors `QuantBox` in quant.rs (six vec4<i32>, 96 bytes).
struct QuantBox {
    // I0, J0, K0, and the model's index in the population.
    corner: vec4<i32>,
    // ni, nj, nk, and the box's first row in the pass.
    extent: vec4<i32>,
    // Per local axis a: A_a, B_a, C_a, D_a.
    axis_x: vec4<i32>,
    axis_y: vec4<i32>,
    axis_z: vec4<i32>,
    // H_x, H_y, H_z, 0.
    half: vec4<i32>,
}

// Mirrors `PassParams` in gpu.rs (48 bytes).
struct Params {
    // Grid resolution nx, ny, nz, and 0.
    res: vec4<i32>,
    // Rows in the pass.
    rows: u32,
    // Boxes in the pass.
    boxes: u32,
    // Workgroups along x in the dispatch.
    groups_x: u32,
    // Index of the pass's first model.
    first_model: u32,
    // u32 words of one model's bitset.
    words_per_model: u32,
    pad0: u32,
    pad1: u32,
    pad2: u32,
}

// Counters per model: 16 classes, overlap hits, out-of-grid hits, overlap voxels; two
// words each.
const COUNTERS: u32 = 38u;
const OVERLAP_HITS: u32 = 32u;
const OUT_OF_GRID_HITS: u32 = 34u;
const OVERLAP_VOXELS: u32 = 36u;
const WORKGROUP: u32 = 64u;

@group(0) @binding(0) var<uniform> params: Params;
@group(0) @binding(1) var<storage, read> boxes: array<QuantBox>;
@group(0) @binding(2) var<storage, read> classes: array<u32>;
@group(0) @binding(3) var<storage, read_write> covered: array<atomic<u32>>;
@group(0) @binding(4) var<storage, read_write> counts: array<atomic<u32>>;
@group(0) @binding(5) var<storage, read_write> again: array<atomic<u32>>;

// floor(n / d) for d > 0, as `floor_div` in quant.rs.
fn floor_div(n: i32, d: i32) -> i32 {
    let q = n / d;
    if (n % d != 0 && n < 0) {
        return q - 1;
    }
    return q;
}

// ceil(n / d) for d > 0, as `ceil_div` in quant.rs.
fn ceil_div(n: i32, d: i32) -> i32 {
    let q = n / d;
    if (n % d != 0 && n > 0) {
        return q + 1;
    }
    return q;
}

// Narrows [range.x, range.y] to the i where -h <= a i + (b j + c k + d) <= h, as
// `QuantBox::row` does for one axis; an empty result has range.x > range.y.
fn clip_axis(range: vec2<i32>, coeff: vec4<i32>, h: i32, j: i32, k: i32) -> vec2<i32> {
    let a = coeff.x;
    let r = coeff.y * j + coeff.z * k + coeff.w;
    var lo = range.x;
    var hi = range.y;
    if (a > 0) {
        lo = max(lo, ceil_div(-h - r, a));
        hi = min(hi, floor_div(h - r, a));
    } else if (a < 0) {
        lo = max(lo, ceil_div(r - h, -a));
        hi = min(hi, floor_div(r + h, -a));
    } else if (r < -h || r > h) {
        hi = lo - 1;
    }
    return vec2<i32>(lo, hi);
}

// The covered i (relative to the corner) of row (j, k) of box `q`.
fn row_interval(q: QuantBox, j: i32, k: i32) -> vec2<i32> {
    var range = vec2<i32>(0, q.extent.x - 1);
    range = clip_axis(range, q.axis_x, q.half.x, j, k);
    range = clip_axis(range, q.axis_y, q.half.y, j, k);
    range = clip_axis(range, q.axis_z, q.half.z, j, k);
    return range;
}

// Adds v to the 64-bit counter at word `at`.
fn add64(at: u32, v: u32) {
    if (v == 0u) {
        return;
    }
    let old = atomicAdd(&counts[at], v);
    if (old > 0xffffffffu - v) {
        atomicAdd(&counts[at + 1u], 1u);
    }
}

// The box owning pass row `row`: the last with extent.w <= row.
fn find_box(row: u32) -> u32 {
    var lo = 0u;
    var hi = params.boxes - 1u;
    while (lo < hi) {
        let mid = (lo + hi + 1u) / 2u;
        if (u32(boxes[mid].extent.w) <= row) {
            lo = mid;
        } else {
            hi = mid - 1u;
        }
    }
    return lo;
}

@compute @workgroup_size(64)
fn count_rows(@builtin(workgroup_id) group: vec3<u32>, @builtin(local_invocation_index) lane: u32) {
    let row = (group.y * params.groups_x + group.x) * WORKGROUP + lane;
    if (row >= params.rows) {
        return;
    }
    let q = boxes[find_box(row)];
    let local_row = i32(row - u32(q.extent.w));
    let j = local_row % q.extent.y;
    let k = local_row / q.extent.y;
    let range = row_interval(q, j, k);
    if (range.x > range.y) {
        return;
    }
    let model = u32(q.corner.w);
    let base = model * COUNTERS;
    let first = q.corner.x + range.x;
    let last = q.corner.x + range.y;
    let len = u32(last - first + 1);
    let jj = q.corner.y + j;
    let kk = q.corner.z + k;
    let res = params.res;
    if (jj < 0 || jj >= res.y || kk < 0 || kk >= res.z) {
        add64(base + OUT_OF_GRID_HITS, len);
        return;
    }
    let a = max(first, 0);
    let b = min(last, res.x - 1);
    if (a > b) {
        add64(base + OUT_OF_GRID_HITS, len);
        return;
    }
    add64(base + OUT_OF_GRID_HITS, len - u32(b - a + 1));

    var per_class: array<u32, 16>;
    var overlap_hits = 0u;
    var overlap_voxels = 0u;
    let row_base = u32((jj + res.y * kk) * res.x);
    let bits = (model - params.first_model) * params.words_per_model;
    let v0 = row_base + u32(a);
    let v1 = row_base + u32(b);
    for (var w = v0 / 32u; w <= v1 / 32u; w++) {
        var mask = 0xffffffffu;
        if (w == v0 / 32u) {
            mask &= 0xffffffffu << (v0 % 32u);
        }
        if (w == v1 / 32u) {
            mask &= 0xffffffffu >> (31u - v1 % 32u);
        }
        let old = atomicOr(&covered[bits + w], mask);
        let repeated = old & mask;
        if (repeated != 0u) {
            overlap_hits += countOneBits(repeated);
            let before = atomicOr(&again[bits + w], repeated);
            overlap_voxels += countOneBits(repeated & ~before);
        }
        var fresh = mask & ~old;
        while (fresh != 0u) {
            let bit = firstTrailingBit(fresh);
            let v = w * 32u + bit;
            let cls = (classes[v / 8u] >> ((v % 8u) * 4u)) & 15u;
            per_class[cls] += 1u;
            fresh &= fresh - 1u;
        }
    }
    add64(base + OVERLAP_HITS, overlap_hits);
    add64(base + OVERLAP_VOXELS, overlap_voxels);
    for (var c = 0u; c < 16u; c++) {
        add64(base + 2u * c, per_class[c]);
    }
}
