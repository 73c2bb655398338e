//! OBJ meshes as a scene's `[meshes]` and volume targets read them: as given and
//! normalized to the unit cube.

#![no_main]

use libfuzzer_sys::fuzz_target;
use shapegen_runtime::geometry::Mesh;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let _ = Mesh::from_obj_str("fuzz", text);
    let _ = Mesh::from_obj_str_normalized("fuzz", text);
});
