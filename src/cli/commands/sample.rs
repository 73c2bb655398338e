//! `shapegen sample`: random models of a generator, from its own distribution.

use std::fs;
use std::path::{Path, PathBuf};

use anyhow::Context;
use clap::Args;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;
use shapegen::export::{Model, Palette, save_glb, save_obj};
use shapegen::genome::{GenomeSet, Limits};
use shapegen::ops::Operators;
use shapegen::{Genome, Grammar};

use crate::cli::generators::{Generators, Jobs, Visit};
use crate::registry::Entry;

/// Arguments of `shapegen sample`.
#[derive(Debug, Args)]
pub struct SampleArgs {
    /// The generator, by name (a published one, such as spaceship, tree, city or
    /// building; an unknown name lists them all).
    #[arg(long, short)]
    generator: String,
    /// How many models to write.
    #[arg(long, short = 'n', default_value_t = 10)]
    count: u32,
    /// Seed of the random streams; the same seed writes the same files.
    #[arg(long, short, default_value_t = 1)]
    seed: u64,
    /// Folder to write into; created if missing.
    #[arg(long, short)]
    out: PathBuf,
    /// Largest genome, in genes (default: the generator's, for the published ones their
    /// paper scene's).
    #[arg(long, value_name = "GENES")]
    max_len: Option<u32>,
    /// Deepest derivation tree (default: the generator's).
    #[arg(long, value_name = "LEVELS")]
    max_depth: Option<u32>,
    /// Grow each model to about this many genes (the optimizers' initial population)
    /// instead of drawing it from the generator's own distribution, whose models are
    /// often small.
    #[arg(long, value_name = "GENES")]
    genes: Option<u32>,
}

/// Runs `shapegen sample`.
pub fn run<J: Jobs>(args: &SampleArgs, tool: &Generators<J>) -> anyhow::Result<()>
where
    for<'a> J::Job<'a>: From<Sample<'a>>,
{
    tool.visit(&args.generator, Sample { args })
}

/// The body of `shapegen sample`.
pub struct Sample<'a> {
    args: &'a SampleArgs,
}

impl Visit for Sample<'_> {
    fn visit<G: Grammar>(self, entry: &Entry) -> anyhow::Result<()> {
        let args = self.args;
        let own = entry.defaults.limits;
        let limits = Limits {
            min_len: 1,
            max_len: args.max_len.unwrap_or(own.max_len),
            max_depth: args.max_depth.unwrap_or(own.max_depth),
        };
        let ops = Operators::<G>::new(limits).context("bad --max-len or --max-depth")?;
        if let Some(genes) = args.genes {
            anyhow::ensure!(
                (1..=limits.max_len).contains(&genes),
                "--genes {genes} must lie between 1 and the largest genome, {} genes",
                limits.max_len
            );
        }
        let meshes = entry
            .defaults
            .meshes
            .bind(G::GRAPH)
            .context("the generator's meshes")?;
        fs::create_dir_all(&args.out)
            .with_context(|| format!("could not create {}", args.out.display()))?;

        let genomes: Vec<Genome<G>> = (0..args.count)
            .into_par_iter()
            .map_init(
                || ops.clone(),
                |ops, i| {
                    let rng = &mut model_rng(args.seed, i);
                    match args.genes {
                        Some(genes) => ops.random(genes, rng),
                        None => ops.sample(rng),
                    }
                },
            )
            .collect();

        let width = digits(args.count);
        let palette = Palette::default();
        genomes
            .par_iter()
            .enumerate()
            .try_for_each_init(Vec::new, |instances, (i, genome)| {
                genome.derive_into(instances);
                let stem = args.out.join(format!("model_{i:0width$}"));
                let model = Model::new(instances, &meshes, &palette);
                save_obj(&stem, model)?;
                save_glb(stem.with_extension("glb"), model)?;
                anyhow::Ok(())
            })?;

        let path = args.out.join("genomes.json");
        GenomeSet::new(genomes).save(&path)?;
        report(&args.out, args.count, G::GRAPH.name);
        Ok(())
    }
}

/// The random stream of model `index`: one ChaCha stream per model, so the models do
/// not depend on how work is spread over threads.
fn model_rng(seed: u64, index: u32) -> ChaCha8Rng {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    rng.set_stream(u64::from(index));
    rng
}

/// Number of decimal digits of the largest model index.
fn digits(count: u32) -> usize {
    count.saturating_sub(1).max(1).ilog10() as usize + 1
}

fn report(out: &Path, count: u32, name: &str) {
    println!(
        "wrote {count} {name} models (.obj, .glb) and genomes.json to {}",
        out.display()
    );
}
