//! PLY meshes, ASCII or binary, as a scene's volume targets read them.

#![no_main]

use libfuzzer_sys::fuzz_target;
use shapegen_runtime::geometry::Mesh;

fuzz_target!(|data: &[u8]| {
    let _ = Mesh::from_ply_bytes("fuzz.ply", data);
});
