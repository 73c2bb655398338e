// Silhouette counting: every model's instances are drawn through a target's camera, and
// each fragment marks its pixel in the model's coverage bitset; the invocation that set
// a pixel's bit adds the pixel to the model's counts. No depth test, no colour written.
// Compiled after `clip.wgsl`, whose `clip_position` places the vertices.

// Mirrors `Params` in shapegen-runtime/src/score/silhouette/gpu.rs.
struct Params {
    view_projection: mat4x4<f32>,
    // Image width and height in pixels.
    width: u32,
    height: u32,
    // 32-bit words per bitset row, and per model's bitset.
    row_words: u32,
    image_words: u32,
    // Global index of the first model whose bitset is at the start of `coverage`.
    first_model: u32,
    // Number of targets, and this pass's target.
    targets: u32,
    target_index: u32,
    _pad: u32,
}

@group(0) @binding(0) var<uniform> params: Params;
// Per pixel, row by row from the top: grey level in bits 0-7, target pixel in bit 8.
@group(0) @binding(1) var<storage, read> pixels: array<u32>;
// One bitset per model of the chunk.
@group(0) @binding(2) var<storage, read_write> coverage: array<atomic<u32>>;
// Per (model, target): covered, on_target, level_sum, unused.
@group(0) @binding(3) var<storage, read_write> counts: array<atomic<u32>>;

struct VertexOut {
    @invariant @builtin(position) position: vec4<f32>,
    @location(0) @interpolate(flat) model: u32,
}

@vertex
fn vs_main(
    @location(0) position: vec3<f32>,
    @location(1) row0: vec4<f32>,
    @location(2) row1: vec4<f32>,
    @location(3) row2: vec4<f32>,
    @location(4) model: u32,
) -> VertexOut {
    let clip = clip_position(params.view_projection, position, row0, row1, row2);
    return VertexOut(clip, model);
}

@fragment
fn fs_main(in: VertexOut) -> @location(0) vec4<f32> {
    let x = u32(in.position.x);
    let y = u32(in.position.y);
    if x < params.width && y < params.height {
        let word = (in.model - params.first_model) * params.image_words + y * params.row_words + x / 32u;
        let bit = 1u << (x % 32u);
        let old = atomicOr(&coverage[word], bit);
        if (old & bit) == 0u {
            let pixel = pixels[y * params.width + x];
            let slot = (in.model * params.targets + params.target_index) * 4u;
            atomicAdd(&counts[slot], 1u);
            if (pixel & 256u) != 0u {
                atomicAdd(&counts[slot + 1u], 1u);
            }
            atomicAdd(&counts[slot + 2u], pixel & 255u);
        }
    }
    return vec4<f32>(0.0);
}
