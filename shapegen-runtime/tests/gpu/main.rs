//! The tests that need a GPU adapter, under their own harness so that a missing adapter
//! shows: without one every test is reported as ignored, after a line saying that no
//! adapter was found, unless `SHAPEGEN_REQUIRE_GPU=1` (as in CI, which installs a
//! software Vulkan driver), where every test fails instead.

#[path = "../support"]
mod support {
    pub mod breeding;
    pub mod city_expanded;
    pub mod lots;
    pub mod pavilions;
    pub mod scenes;
    pub mod silhouette_scenes;
    pub mod spaceship_expanded;
    pub mod volume_scenes;

    use shapegen_runtime::score::silhouette::{Camera, ImageTarget, Weighting};

    /// A published target image scaled down to 160 x 120 pixels, as a mask or as a
    /// weight map.
    pub fn small_target(scene: &str, file: &str, camera: Camera, weight_map: bool) -> ImageTarget {
        let path = scenes::scenes().join(scene).join(file);
        let image = image::open(&path).unwrap().resize_exact(
            160,
            120,
            image::imageops::FilterType::Triangle,
        );
        if weight_map {
            ImageTarget::new(
                file.to_owned(),
                &image,
                camera,
                Weighting::weight_map(1.0, -0.5),
            )
            .unwrap()
        } else {
            ImageTarget::new(file.to_owned(), &image, camera, Weighting::mask(1.0, -1.0)).unwrap()
        }
    }
}

mod context;
mod silhouette;
mod silhouette_retained;
mod volume;

use std::process::ExitCode;

use libtest_mimic::{Arguments, Failed, Trial};
use shapegen_runtime::gpu::GpuContext;

/// A GPU test: its name and its body, which panics when the test fails.
type GpuTest = (&'static str, fn(&GpuContext));

fn main() -> ExitCode {
    let args = Arguments::from_args();
    let tests = [
        context::TESTS,
        volume::TESTS,
        silhouette::TESTS,
        silhouette_retained::TESTS,
    ]
    .concat();
    let required = std::env::var("SHAPEGEN_REQUIRE_GPU").as_deref() == Ok("1");
    let gpu: Result<&'static GpuContext, String> = GpuContext::new()
        .map(|gpu| &*Box::leak(Box::new(gpu)))
        .map_err(|err| format!("no GPU adapter was found: {err}"));
    match &gpu {
        Ok(gpu) => eprintln!("GPU tests run on {}", gpu.describe()),
        Err(err) if required => eprintln!("{err}; SHAPEGEN_REQUIRE_GPU=1, so the GPU tests fail"),
        Err(err) => eprintln!("{err}; the GPU tests are ignored"),
    }
    let trials = tests
        .into_iter()
        .map(|(name, test)| match &gpu {
            Ok(gpu) => {
                let gpu = *gpu;
                Trial::test(name, move || {
                    test(gpu);
                    Ok(())
                })
            }
            Err(err) => {
                let err = err.clone();
                Trial::test(name, move || Err(Failed::from(err))).with_ignored_flag(!required)
            }
        })
        .collect();
    libtest_mimic::run(&args, trials).exit_code()
}
