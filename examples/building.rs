//! Evolves buildings against three objectives at once: the project's
//! `scenes/building.toml` asks for a footprint seen from above and a silhouette seen from
//! the front (both of one building of the project's CGA-style generator) and for as many
//! distinct facets as possible. The multi-objective GA (Pareto ranking with crowding, a
//! penalty for clones) runs 60 generations of 300, or the time budget if that comes
//! first, and keeps every non-dominated building it finds: the whole trade-off, not one
//! weighted compromise.
//!
//! ```sh
//! cargo run --release --example building          # writes out/building
//! cargo run --release --example building -- 20    # a 20-second budget instead of 90
//! ```

use std::path::Path;
use std::time::Duration;

use anyhow::Context;
use generators::Building;
use shapegen::export::{Palette, Preview, save_glb};
use shapegen::optimize::Control;
use shapegen::optimize::multi::{MultiGa, MultiSnapshot};
use shapegen::optimize::{Optimizer, Settings};
use shapegen::scene::{ObjectiveEvaluator, Scene};

fn main() -> anyhow::Result<()> {
    let seconds: u64 = match std::env::args().nth(1) {
        Some(s) => s
            .parse()
            .context("the argument is the time budget in seconds")?,
        None => 90,
    };
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let out = root.join("out/building");
    std::fs::create_dir_all(&out)?;

    // The goal: the scene's objectives, measured on whole populations.
    let scene = Scene::load(root.join("scenes/building.toml"))?;
    let mut evaluator = ObjectiveEvaluator::new::<Building>(&scene)?;
    let names: Vec<&str> = evaluator.set().names().collect();
    println!("objectives: {}", names.join(", "));

    // The search: the scene's GA settings and selection, under a time budget.
    let settings = scene.multi_settings().context("a scene with objectives")?;
    let budget = settings
        .ga
        .budget()
        .and_wall_time(Duration::from_secs(seconds));
    let mut ga = MultiGa::<Building>::new(settings, scene.limits, scene.optimizer.seed)?;
    let mut progress = |s: &MultiSnapshot<'_, Building>| {
        if s.generation.is_multiple_of(10) {
            let best: Vec<String> = names
                .iter()
                .zip(s.best)
                .map(|(n, v)| format!("{n} {v:.3}"))
                .collect();
            println!(
                "generation {:>2}  {:>3} non-dominated  best {}",
                s.generation,
                s.front.len(),
                best.join(", ")
            );
        }
        Control::Continue
    };
    let result = ga.run(&mut evaluator, &budget, &mut progress)?;
    let elapsed = result.history.last().map_or(0.0, |h| h.elapsed_s);
    println!(
        "{} non-dominated buildings after {} generations, {} evaluations, {elapsed:.1} s",
        result.front.len(),
        result.generations,
        result.evaluations
    );

    // What was found: every building of the front as a model and a shaded picture,
    // named by its objective values.
    let meshes = evaluator.meshes();
    let palette = Palette::new();
    let mut instances = Vec::new();
    let mut csv = format!("model,{}\n", names.join(","));
    for (i, member) in result.front.iter().enumerate() {
        member.genome.derive_into(&mut instances);
        save_glb(
            out.join(format!("front_{i:03}.glb")),
            &instances,
            meshes,
            &palette,
        )?;
        Preview::framing(&instances, meshes, 400, 400)
            .render(&instances, meshes, &palette)?
            .save(out.join(format!("front_{i:03}.png")))?;
        let values: Vec<String> = member.values.iter().map(|v| format!("{v}")).collect();
        csv += &format!("{i},{}\n", values.join(","));
    }
    std::fs::write(out.join("front.csv"), csv)?;
    println!(
        "wrote front_NNN.glb, front_NNN.png and front.csv to {}",
        out.display()
    );
    Ok(())
}
