//! Target images as a scene reads them: decoded with the size checked first, then made
//! a silhouette target (a mask by every rule, a weight map) and a projection objective's
//! image.

#![no_main]

use glam::{Mat4, Vec2};
use libfuzzer_sys::fuzz_target;
use shapegen::scene::decode_image;
use shapegen_runtime::score::objective::{ProjectionMatch, View};
use shapegen_runtime::score::silhouette::{Camera, ImageTarget, MaskRule, Weighting};

fuzz_target!(|data: &[u8]| {
    let Ok(image) = decode_image(data) else {
        return;
    };
    let camera = || Camera::Matrices {
        view: Mat4::IDENTITY,
        projection: Mat4::IDENTITY,
    };
    let name = || "fuzz.png".to_owned();
    for rule in [
        MaskRule::RedZero,
        MaskRule::DarkerThan(128),
        MaskRule::OpaqueFrom(128),
        MaskRule::FarFrom {
            background: [255, 255, 255],
            tolerance: 32,
        },
    ] {
        let mask = Weighting::mask_by(rule, 1.0, -1.0);
        let _ = ImageTarget::new(name(), &image, camera(), mask);
    }
    let _ = ImageTarget::new(name(), &image, camera(), Weighting::weight_map(1.0, -1.0));
    let gray = image.into_luma8();
    let _ = ProjectionMatch::from_image(View::Top, Vec2::splat(-1.0), Vec2::splat(1.0), &gray);
});
