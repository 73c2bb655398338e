//! Point clouds as XYZ text; PLY point clouds go through the PLY reader that the
//! `ply_mesh` target covers.

#![no_main]

use libfuzzer_sys::fuzz_target;
use shapegen_runtime::geometry::PointCloud;

fuzz_target!(|data: &[u8]| {
    if let Ok(text) = std::str::from_utf8(data) {
        let _ = PointCloud::from_xyz_str("fuzz.xyz", text);
    }
});
