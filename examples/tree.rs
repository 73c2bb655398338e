//! Evolves a tree that follows a sketch: the project's `scenes/tree_sketch.toml`, whose
//! target is the silhouette of one three-branch tree of the published generator. The
//! genetic algorithm runs the paper's tree settings (population 200, up to 1500
//! generations) within a time budget, and draws the best tree through the sketch's
//! camera with the sketch beneath it.
//!
//! ```sh
//! cargo run --release --example tree           # writes out/tree, one minute
//! cargo run --release --example tree -- 20     # a 20-second budget instead
//! ```

use std::path::Path;
use std::time::Duration;

use anyhow::Context;
use generators::Tree;
use image::Rgb;
use shapegen::Grammar;
use shapegen::export::{Model, Palette, Preview, save_glb, save_obj};
use shapegen::optimize::{Control, Ga, Snapshot};
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
    let out = root.join("out/tree");
    std::fs::create_dir_all(&out)?;

    // The goal: cover the sketch's black pixels and nothing else, through its camera.
    let scene = Scene::load(root.join("scenes/tree_sketch.toml"))?;
    let scorer = SceneScorer::new::<Tree>(&scene)?;
    let backend = scorer.on(BackendChoice::Auto, None)?;
    println!("scoring on {}", backend.describe());

    // The search: the paper's GA settings for its tree scene, under a time budget.
    let settings = generators::tree::paper_ga();
    let mut ga = Ga::<Tree>::new(settings, scene.limits, 1)?;
    let budget = settings
        .budget()
        .and_wall_time(Duration::from_secs(seconds));
    let mut last_report = 0.0;
    let mut progress = |s: &Snapshot<'_, Tree>| {
        let t = s.elapsed.as_secs_f64();
        if s.generation == 0 || t - last_report >= 5.0 {
            last_report = t;
            println!(
                "{t:>5.1} s  generation {:>4}  best {:.4}  mean {:.4}  {} genes",
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
        "best fitness {:.4} (optimum 1.0) after {} generations, {} evaluations, {elapsed:.1} s",
        result.best_fitness, result.generations, result.evaluations,
    );

    // What was found: the model, the genome, and the tree drawn over its sketch.
    let meshes = scene.meshes.bind(Tree::GRAPH)?;
    let mut instances = Vec::new();
    result.best.derive_into(&mut instances);
    let palette = Palette::new();
    let model = Model::new(&instances, &meshes, &palette);
    save_obj(out.join("best"), model)?;
    save_glb(out.join("best.glb"), model)?;
    result.best.save_json(out.join("best.genome.json"))?;
    let sketch = &scorer.silhouette().context("a silhouette scene")?.targets()[0];
    let preview = Preview {
        view_projection: sketch.view_projection(),
        width: sketch.width(),
        height: sketch.height(),
    };
    let mut picture = preview.render(model)?;
    let background = *picture.get_pixel(0, 0);
    for (x, y, pixel) in picture.enumerate_pixels_mut() {
        // Where the tree leaves the background bare, show the sketch in light grey.
        if *pixel == background && sketch.is_target(x, y) {
            *pixel = Rgb([200, 200, 200]);
        }
    }
    picture.save(out.join("best.png"))?;
    println!(
        "wrote best.obj, best.glb, best.png (over the sketch) and best.genome.json to {}",
        out.display()
    );
    Ok(())
}
