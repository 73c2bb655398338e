//! Evolves a city skyline toward a silhouette: the project's `scenes/city_skyline.toml`,
//! whose target is the skyline of one city of the published generator seen from the
//! south. The genetic algorithm starts from random cities and finds one whose silhouette
//! matches the target's: 400 generations of 100, under a second on two cores, or the
//! time budget if that comes first.
//!
//! ```sh
//! cargo run --release --example city            # writes out/city
//! cargo run --release --example city -- 20      # a 20-second budget instead of 60
//! ```

use std::path::Path;
use std::time::Duration;

use anyhow::Context;
use generators::City;
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
    let out = root.join("out/city");
    std::fs::create_dir_all(&out)?;

    // The goal: a scene file names the generator, the genome limits and the target.
    let scene = Scene::load(root.join("scenes/city_skyline.toml"))?;
    let scorer = SceneScorer::new::<City>(&scene)?;
    let backend = scorer.on(BackendChoice::Cpu, None)?;
    println!("scoring on {}", backend.describe());

    // The search: the paper's GA settings for its city scene, under a time budget.
    let settings = GaSettings {
        generations: 400,
        ..generators::city::paper_ga()
    };
    let mut ga = Ga::<City>::new(settings, scene.limits, 1)?;
    let budget = settings
        .budget()
        .and_wall_time(Duration::from_secs(seconds));
    let mut progress = |s: &Snapshot<'_, City>| {
        if s.generation.is_multiple_of(10) {
            println!(
                "generation {:>3}  best {:.4}  mean {:.4}  {:>6.0} evaluations/s",
                s.generation,
                s.best_fitness,
                s.mean,
                s.evaluations as f64 / s.elapsed.as_secs_f64().max(1e-9)
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

    // What was found: the model, a picture through the scene's camera, and the genome.
    let meshes = scene.meshes.bind(City::GRAPH)?;
    let mut instances = Vec::new();
    result.best.derive_into(&mut instances);
    let palette = Palette::new();
    let model = Model::new(&instances, &meshes, &palette);
    save_obj(out.join("best"), model)?;
    save_glb(out.join("best.glb"), model)?;
    result.best.save_json(out.join("best.genome.json"))?;
    let target = &scorer.silhouette().context("a silhouette scene")?.targets()[0];
    let preview = Preview {
        view_projection: target.view_projection(),
        width: target.width(),
        height: target.height(),
    };
    preview.render(model)?.save(out.join("best.png"))?;
    // The fitness curve, as `shapegen run` writes it, for the viewer.
    let mut curve = String::from("generation,elapsed_s,evaluations,best,mean,std\n");
    for h in &result.history {
        curve += &format!(
            "{},{:.3},{},{},{},{}\n",
            h.generation, h.elapsed_s, h.evaluations, h.best, h.mean, h.std
        );
    }
    std::fs::write(out.join("fitness.csv"), curve)?;
    println!(
        "wrote best.obj, best.glb, best.png, best.genome.json and fitness.csv to {}",
        out.display()
    );
    println!(
        "to look at it in the browser: cargo run --release -- view {}",
        out.display()
    );
    Ok(())
}
