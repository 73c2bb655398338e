//! Evolves a spaceship that fills a volume: the project's `scenes/spaceship_fill.toml`,
//! whose target is the volume of one spaceship of the published generator, voxelized on
//! the paper's grid. The genetic algorithm runs the paper's spaceship settings for 300
//! generations (a second or two on two cores), or the time budget if that comes first.
//!
//! ```sh
//! cargo run --release --example spaceship          # writes out/spaceship
//! cargo run --release --example spaceship -- 5     # a 5-second budget instead of 60
//! ```

use std::path::Path;
use std::time::Duration;

use anyhow::Context;
use generators::Spaceship;
use shapegen::Grammar;
use shapegen::export::{Model, Palette, Preview, save_glb, save_obj};
use shapegen::optimize::{Control, Ga, GaSettings, Snapshot};
use shapegen::optimize::{Optimizer, Settings};
use shapegen::scene::{BackendChoice, Scene, SceneEvaluator, SceneScorer};

fn main() -> anyhow::Result<()> {
    let seconds: u64 = match std::env::args().nth(1) {
        Some(s) => s
            .parse()
            .context("the argument is the time budget in seconds")?,
        None => 60,
    };
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let out = root.join("out/spaceship");
    std::fs::create_dir_all(&out)?;

    // The goal: fill the target volume, stay out of the rest of the grid, keep genomes
    // near 40 genes. The scene file says all of it; the backend voxelizes the target.
    let scene = Scene::load(root.join("scenes/spaceship_fill.toml"))?;
    let scorer = SceneScorer::new::<Spaceship>(&scene)?;
    let backend = scorer.on(BackendChoice::Auto, None)?;
    println!("scoring on {}", backend.describe());

    // The search: the paper's GA settings for its spaceship scene, for longer.
    let settings = GaSettings {
        generations: 300,
        ..generators::spaceship::paper_ga()
    };
    let mut ga = Ga::<Spaceship>::new(settings, scene.limits, 1)?;
    let budget = settings
        .budget()
        .and_wall_time(Duration::from_secs(seconds));
    let mut progress = |s: &Snapshot<'_, Spaceship>| {
        if s.generation.is_multiple_of(25) {
            println!(
                "generation {:>3}  best {:.4}  mean {:.4}  {} genes",
                s.generation,
                s.best_fitness,
                s.mean,
                s.best.len()
            );
        }
        Control::Continue
    };
    let result = ga.run(&mut SceneEvaluator::new(&backend), &budget, &mut progress)?;
    let elapsed = result.history.last().map_or(0.0, |h| h.elapsed_s);
    println!(
        "best fitness {:.4} (optimum 2.0) after {} generations, {} evaluations, {elapsed:.1} s",
        result.best_fitness, result.generations, result.evaluations,
    );

    // What was found: the model, a shaded picture framing it, and the genome.
    let meshes = scene.meshes.bind(Spaceship::GRAPH)?;
    let mut instances = Vec::new();
    result.best.derive_into(&mut instances);
    let palette = Palette::new();
    let model = Model::new(&instances, &meshes, &palette);
    save_obj(out.join("best"), model)?;
    save_glb(out.join("best.glb"), model)?;
    result.best.save_json(out.join("best.genome.json"))?;
    Preview::framing(&instances, &meshes, 800, 600)
        .render(model)?
        .save(out.join("best.png"))?;
    println!(
        "wrote best.obj, best.glb, best.png and best.genome.json to {}",
        out.display()
    );
    Ok(())
}
