// The clip-space position of a vertex of a mesh instance, shared by the silhouette
// shaders so that they draw the same fragments: `position` moved by the instance's
// affine transform (its three rows) and projected by `view_projection`. The camera's
// clip space keeps z in [-w, w]; the hardware keeps z in [0, w]. This puts the near
// plane z = -w at 0 exactly and moves the far clip to z = 1023 w, far beyond any
// camera's far plane: triangles are clipped at the near plane only.
fn clip_position(
    view_projection: mat4x4<f32>,
    position: vec3<f32>,
    row0: vec4<f32>,
    row1: vec4<f32>,
    row2: vec4<f32>,
) -> vec4<f32> {
    let p = vec4<f32>(position, 1.0);
    let world = vec4<f32>(dot(row0, p), dot(row1, p), dot(row2, p), 1.0);
    var clip = view_projection * world;
    clip.z = (clip.z + clip.w) * (1.0 / 1024.0);
    return clip;
}
