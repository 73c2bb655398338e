//! The building scene's projection objectives (`scenes/building.toml`), for the
//! incremental-objective tests.

use std::path::Path;

use glam::Vec2;
use shapegen_runtime::score::objective::{ProjectionMatch, View};

/// The projection of `view` over `[min, max]` against the project's target image
/// `scenes/targets/{file}`, as a scene loads it.
fn projection(view: View, min: Vec2, max: Vec2, file: &str) -> ProjectionMatch {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../scenes/targets")
        .join(file);
    let image = image::open(&path)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
        .into_luma8();
    ProjectionMatch::from_image(view, min, max, &image).unwrap()
}

/// The building scene's footprint seen from above and silhouette seen from the front.
pub fn building_projections() -> [ProjectionMatch; 2] {
    [
        projection(
            View::Top,
            Vec2::splat(-8.0),
            Vec2::splat(8.0),
            "building_top.png",
        ),
        projection(
            View::Front,
            Vec2::new(-8.0, 0.0),
            Vec2::new(8.0, 40.0),
            "building_front.png",
        ),
    ]
}
