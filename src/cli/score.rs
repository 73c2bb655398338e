//! `shapegen score`: the counts and fitness of saved genomes in a scene.

use std::io::Write;
use std::path::PathBuf;

use anyhow::Context;
use clap::Args;
use generators::GeneratorVisitor;
use serde::Serialize;
use shapegen::Grammar;
use shapegen::genome::Limits;
use shapegen::scene::{Scene, SceneCounts, SceneScorer};
use shapegen::score::InstanceBatch;

use super::backend::BackendArgs;
use super::genomes::load_genomes;

/// Arguments of `shapegen score`.
#[derive(Debug, Args)]
pub struct ScoreArgs {
    /// The scene file (TOML).
    scene: PathBuf,
    /// Genomes to score: a file written by `shapegen sample` or `shapegen run`.
    #[arg(long)]
    genomes: PathBuf,
    #[command(flatten)]
    backend: BackendArgs,
}

/// One line of the output.
#[derive(Serialize)]
struct Line<'a> {
    genome: usize,
    genes: usize,
    instances: usize,
    fitness: f64,
    #[serde(flatten)]
    counts: &'a SceneCounts,
}

/// Runs `shapegen score`.
pub fn run(args: &ScoreArgs) -> anyhow::Result<()> {
    let scene = Scene::load(&args.scene)?;
    scene.generator.visit(Score {
        args,
        scene: &scene,
    })
}

struct Score<'a> {
    args: &'a ScoreArgs,
    scene: &'a Scene,
}

impl GeneratorVisitor for Score<'_> {
    type Output = anyhow::Result<()>;

    fn visit<G: Grammar>(self, _: Limits) -> anyhow::Result<()> {
        let genomes = load_genomes::<G>(&self.args.genomes)?;
        let gpu = self.args.backend.open();
        let scorer = SceneScorer::new::<G>(self.scene)?;
        let backend = scorer.on(self.args.backend.choice(), gpu.as_ref())?;
        eprintln!(
            "scoring {} genomes on {}",
            genomes.len(),
            backend.describe()
        );

        let mut batch = InstanceBatch::new();
        for genome in &genomes {
            batch.push_genome(genome);
        }
        let mut counts = Vec::new();
        backend
            .count(&batch, &mut counts)
            .context("scoring failed")?;

        let mut out = std::io::stdout().lock();
        for (i, (genome, counts)) in genomes.iter().zip(&counts).enumerate() {
            let line = Line {
                genome: i,
                genes: genome.len(),
                instances: batch.model(i).len(),
                fitness: scorer.fitness(counts, genome.len()),
                counts,
            };
            serde_json::to_writer(&mut out, &line)?;
            writeln!(out)?;
        }
        Ok(())
    }
}
