// Incremental silhouette counting: every model keeps, in a slot of the GPU's memory, how
// many triangle fragments of its instances hit each pixel of each target. Drawing an
// instance adds 1 per fragment, drawing it "removed" subtracts 1; a pixel is covered
// while its count is above 0, so the fragment that takes it from 0 to 1 (or from 1 to 0)
// adds the pixel to (or takes it from) the model's counts. The counts change by exactly
// the difference between the covered pixels before and after, whatever order the
// fragments run in. Compiled after `clip.wgsl`, whose `clip_position` places the
// vertices as `silhouette.wgsl` does, so the same fragments are drawn.

// Mirrors `Params` in shapegen-runtime/src/score/silhouette/gpu_retained.rs.
struct Params {
    view_projection: mat4x4<f32>,
    // Image width and height in pixels.
    width: u32,
    height: u32,
    // Words from the start of a slot to this target's image, and words per slot.
    image_offset: u32,
    slot_words: u32,
    // The first slot of the bound page.
    first_slot: u32,
    // Number of targets, and this pass's target.
    targets: u32,
    target_index: u32,
    _pad: u32,
}

@group(0) @binding(0) var<uniform> params: Params;
// Per pixel, row by row from the top: grey level in bits 0-7, target pixel in bit 8.
@group(0) @binding(1) var<storage, read> pixels: array<u32>;
// One page of slots: per slot, every target's fragment counts, pixel by pixel.
@group(0) @binding(2) var<storage, read_write> slots: array<atomic<i32>>;
// Per (entry, target): the change of covered, on_target, level_sum; unused.
@group(0) @binding(3) var<storage, read_write> changes: array<atomic<i32>>;

struct VertexOut {
    @invariant @builtin(position) position: vec4<f32>,
    @location(0) @interpolate(flat) entry: u32,
    @location(1) @interpolate(flat) slot: u32,
    @location(2) @interpolate(flat) removed: u32,
}

@vertex
fn vs_main(
    @location(0) position: vec3<f32>,
    @location(1) row0: vec4<f32>,
    @location(2) row1: vec4<f32>,
    @location(3) row2: vec4<f32>,
    @location(4) entry: u32,
    @location(5) slot: u32,
    @location(6) removed: u32,
) -> VertexOut {
    let clip = clip_position(params.view_projection, position, row0, row1, row2);
    return VertexOut(clip, entry, slot, removed);
}

@fragment
fn fs_main(in: VertexOut) -> @location(0) vec4<f32> {
    let x = u32(in.position.x);
    let y = u32(in.position.y);
    if x < params.width && y < params.height {
        let cell = (in.slot - params.first_slot) * params.slot_words + params.image_offset
            + y * params.width + x;
        let pixel = pixels[y * params.width + x];
        let change = (in.entry * params.targets + params.target_index) * 4u;
        var step = 0i;
        if in.removed == 0u {
            if atomicAdd(&slots[cell], 1i) == 0i {
                step = 1i;
            }
        } else if atomicSub(&slots[cell], 1i) == 1i {
            step = -1i;
        }
        if step != 0i {
            atomicAdd(&changes[change], step);
            if (pixel & 256u) != 0u {
                atomicAdd(&changes[change + 1u], step);
            }
            atomicAdd(&changes[change + 2u], step * i32(pixel & 255u));
        }
    }
    return vec4<f32>(0.0);
}
