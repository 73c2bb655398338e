//! The body of a command that opens one scene file as written and works on saved genomes
//! of its generator: `score`, `target` and `render`.

use std::path::Path;

use shapegen::scene::{Overrides, Scene};

use crate::cli::generators::{Generators, Jobs};

/// A command's arguments `A` and the scene they name, waiting for the grammar of the
/// scene's generator.
pub struct OnScene<'a, A> {
    /// The command's arguments.
    pub args: &'a A,
    /// The scene, opened as written.
    pub scene: &'a Scene,
}

/// Opens the scene file `path` as written (no overrides) and runs the body
/// `OnScene { args, scene }` with the grammar of the scene's generator.
pub fn visit_scene<J: Jobs, A: 'static>(
    path: &Path,
    args: &A,
    tool: &Generators<J>,
) -> anyhow::Result<()>
where
    for<'a> J::Job<'a>: From<OnScene<'a, A>>,
{
    let scene = Scene::open(path, tool.registry(), &Overrides::default())?;
    tool.visit(
        &scene.generator,
        OnScene {
            args,
            scene: &scene,
        },
    )
}
