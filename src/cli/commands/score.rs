//! `shapegen score`: the counts and fitness of saved genomes in a scene, or their
//! objective values in a scene with objectives.

use std::io::Write;
use std::path::PathBuf;

use anyhow::Context;
use clap::Args;
use serde::Serialize;
use shapegen::optimize::multi::MultiEvaluator;
use shapegen::scene::{ObjectiveEvaluator, Scene, SceneCounts, SceneScorer};
use shapegen::score::InstanceBatch;
use shapegen::{Genome, Grammar};

use crate::cli::backend::BackendArgs;
use crate::cli::generators::Visit;
use crate::cli::genomes::load_genomes;
use crate::registry::Entry;

use super::on_scene::OnScene;

/// Arguments of `shapegen score`.
#[derive(Debug, Args)]
pub struct ScoreArgs {
    /// The scene file (TOML).
    pub(super) scene: PathBuf,
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

/// The body of `shapegen score`.
pub type Score<'a> = OnScene<'a, ScoreArgs>;

impl Visit for Score<'_> {
    fn visit<G: Grammar>(self, _: &Entry) -> anyhow::Result<()> {
        let genomes = load_genomes::<G>(&self.args.genomes)?;
        if self.scene.objectives.is_some() {
            return objectives(self.scene, &genomes);
        }
        let gpu = self.args.backend.open();
        let scorer = SceneScorer::new::<G>(self.scene)?;
        let backend = scorer.on(self.args.backend.choice(), gpu.as_ref())?;
        eprintln!(
            "scoring {} genomes on {}",
            genomes.len(),
            backend.describe()
        );

        let mut batch = InstanceBatch::new().on_site(self.scene.site.clone());
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

/// One line of the output for a scene with objectives.
#[derive(Serialize)]
struct ObjectiveLine {
    genome: usize,
    genes: usize,
    objectives: serde_json::Map<String, serde_json::Value>,
}

/// Prints every genome's objective values, one JSON object per genome.
fn objectives<G: Grammar>(scene: &Scene, genomes: &[Genome<G>]) -> anyhow::Result<()> {
    let mut evaluator = ObjectiveEvaluator::new::<G>(scene)?;
    let names: Vec<&str> = evaluator.set().names().collect();
    eprintln!(
        "measuring {} genomes on {} objectives on the CPU",
        genomes.len(),
        names.len()
    );
    let mut values = vec![0.0; genomes.len() * names.len()];
    evaluator
        .evaluate(genomes, &mut values)
        .context("measuring failed")?;
    let mut out = std::io::stdout().lock();
    for (i, (genome, row)) in genomes.iter().zip(values.chunks(names.len())).enumerate() {
        let objectives = names
            .iter()
            .zip(row)
            .map(|(n, &v)| (n.to_string(), serde_json::json!(v)))
            .collect();
        let line = ObjectiveLine {
            genome: i,
            genes: genome.len(),
            objectives,
        };
        serde_json::to_writer(&mut out, &line)?;
        writeln!(out)?;
    }
    Ok(())
}
