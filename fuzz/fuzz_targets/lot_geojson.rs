//! Lots as a scene's `[lot] geojson` file gives them: the GeoJSON text, then the
//! polygon, its prism and its roofs, as a building generator builds on it.

#![no_main]

use std::path::Path;

use libfuzzer_sys::fuzz_target;
use shapegen::scene::geojson_outline;
use shapegen_runtime::geometry::{Polygon, RoofShape};

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let Ok(ring) = geojson_outline(Path::new("fuzz.geojson"), text) else {
        return;
    };
    // Lots of many points are the same code at a larger size; keep the runs quick.
    if ring.len() > 64 {
        return;
    }
    let Ok(lot) = Polygon::from_f64(&ring) else {
        return;
    };
    let _ = lot.extrude(3.0);
    let pitch = 0.6;
    for shape in [
        RoofShape::Flat { thickness: 0.3 },
        RoofShape::Shed { pitch },
        RoofShape::Gable { pitch },
        RoofShape::Hip { pitch },
        RoofShape::Pyramid { pitch },
    ] {
        let _ = lot.roof(shape, 0.5);
    }
    let _ = lot.offset(-0.5);
});
