//! glTF meshes, JSON or binary, as a scene's volume targets read them (embedded
//! buffers only: no folder to read external ones from).

#![no_main]

use libfuzzer_sys::fuzz_target;
use shapegen_runtime::geometry::Mesh;

fuzz_target!(|data: &[u8]| {
    let _ = Mesh::from_gltf_bytes("fuzz.glb", data, None);
});
