//! `shapegen render`: shaded previews of saved genomes, and overlays of model and target.

use std::path::PathBuf;

use anyhow::Context;
use clap::Args;
use generators::GeneratorVisitor;
use image::{Rgb, RgbImage};
use rayon::prelude::*;
use shapegen::Grammar;
use shapegen::export::{Palette, Preview};
use shapegen::genome::Limits;
use shapegen::scene::{Scene, SceneScorer};
use shapegen::score::silhouette::ImageTarget;

use super::genomes::load_genomes;
use super::target::numbered;

/// Arguments of `shapegen render`.
#[derive(Debug, Args)]
pub struct RenderArgs {
    /// The scene file (TOML): its first camera frames the previews.
    scene: PathBuf,
    /// The genomes to draw: a single genome or a set.
    #[arg(long)]
    genomes: PathBuf,
    /// Folder to write into; created if missing.
    #[arg(long)]
    out: PathBuf,
    /// Preview width and height for scenes without a camera.
    #[arg(long, value_name = "W", default_value_t = 800)]
    width: u32,
    /// Preview height for scenes without a camera.
    #[arg(long, value_name = "H", default_value_t = 600)]
    height: u32,
}

/// Overlay colours: target alone, model alone, both.
const TARGET: Rgb<u8> = Rgb([150, 170, 215]);
const MODEL: Rgb<u8> = Rgb([225, 90, 70]);
const BOTH: Rgb<u8> = Rgb([40, 120, 60]);
const NEITHER: Rgb<u8> = Rgb([255, 255, 255]);

/// Runs `shapegen render`.
pub fn run(args: &RenderArgs) -> anyhow::Result<()> {
    anyhow::ensure!(
        args.width > 0 && args.height > 0,
        "--width and --height must be at least 1"
    );
    let scene = Scene::load(&args.scene)?;
    scene.generator.visit(Render {
        args,
        scene: &scene,
    })
}

struct Render<'a> {
    args: &'a RenderArgs,
    scene: &'a Scene,
}

impl GeneratorVisitor for Render<'_> {
    type Output = anyhow::Result<()>;

    fn visit<G: Grammar>(self, _: Limits) -> anyhow::Result<()> {
        let args = self.args;
        let genomes = load_genomes::<G>(&args.genomes)?;
        let scorer = SceneScorer::new::<G>(self.scene)?;
        let meshes = self.scene.meshes.bind(G::GRAPH)?;
        std::fs::create_dir_all(&args.out)
            .with_context(|| format!("cannot create `{}`", args.out.display()))?;
        let targets = scorer
            .silhouette
            .as_ref()
            .map(|s| s.targets())
            .unwrap_or_default();
        let width = genomes.len().saturating_sub(1).max(1).ilog10() as usize + 1;
        let palette = Palette::new();

        genomes
            .par_iter()
            .enumerate()
            .try_for_each_init(Vec::new, |instances, (i, genome)| {
                genome.derive_into(instances);
                let preview = match targets.first() {
                    Some(t) => Preview {
                        view_projection: t.view_projection(),
                        width: t.width(),
                        height: t.height(),
                    },
                    None => Preview::framing(instances, &meshes, args.width, args.height),
                };
                let path = args.out.join(format!("model_{i:0width$}.png"));
                preview
                    .render(instances, &meshes, &palette)?
                    .save(&path)
                    .with_context(|| format!("cannot write `{}`", path.display()))?;
                if let Some(silhouette) = &scorer.silhouette {
                    for (k, target) in targets.iter().enumerate() {
                        let (w, h) = (target.width(), target.height());
                        let mut mask = vec![false; w as usize * h as usize];
                        silhouette.coverage_mask(k, instances, &mut mask)?;
                        let overlay = overlay(target, &mask);
                        let stem = args.out.join(format!("overlay_{i:0width$}"));
                        let path = numbered(&stem, k, targets.len(), "png");
                        overlay
                            .save(&path)
                            .with_context(|| format!("cannot write `{}`", path.display()))?;
                    }
                }
                anyhow::Ok(())
            })?;
        let overlays = if targets.is_empty() {
            ""
        } else {
            " and overlays (target blue, model red, both green)"
        };
        println!(
            "wrote {} shaded previews{overlays} to {}",
            genomes.len(),
            args.out.display()
        );
        Ok(())
    }
}

/// The overlay of a model's coverage `mask` on `target`: target alone blue, model alone
/// red, both green, neither white.
pub fn overlay(target: &ImageTarget, mask: &[bool]) -> RgbImage {
    let w = target.width();
    RgbImage::from_fn(w, target.height(), |x, y| {
        match (target.is_target(x, y), mask[(y * w + x) as usize]) {
            (true, true) => BOTH,
            (true, false) => TARGET,
            (false, true) => MODEL,
            (false, false) => NEITHER,
        }
    })
}
