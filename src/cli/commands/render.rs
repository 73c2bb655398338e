//! `shapegen render`: shaded previews of saved genomes, and overlays of model and target.

use std::path::PathBuf;

use anyhow::Context;
use clap::Args;
use rayon::prelude::*;
use shapegen::Grammar;
use shapegen::export::{Model, Palette, Preview};
use shapegen::scene::SceneScorer;
use shapegen::score::objective::Surface;

use crate::cli::generators::Visit;
use crate::cli::genomes::load_genomes;
use crate::cli::overlay::{numbered, overlay, projection_overlay, projections};
use crate::registry::Entry;

use super::on_scene::OnScene;

/// Arguments of `shapegen render`.
#[derive(Debug, Args)]
pub struct RenderArgs {
    /// The scene file (TOML): its first camera frames the previews.
    pub(super) scene: PathBuf,
    /// The genomes to draw: a single genome or a set.
    #[arg(long)]
    genomes: PathBuf,
    /// Folder to write into; created if missing.
    #[arg(long)]
    out: PathBuf,
    /// Preview width and height for scenes without a camera.
    #[arg(long, value_name = "W", default_value_t = 800, value_parser = clap::value_parser!(u32).range(1..))]
    width: u32,
    /// Preview height for scenes without a camera.
    #[arg(long, value_name = "H", default_value_t = 600, value_parser = clap::value_parser!(u32).range(1..))]
    height: u32,
}

/// The body of `shapegen render`.
pub type Render<'a> = OnScene<'a, RenderArgs>;

impl Visit for Render<'_> {
    fn visit<G: Grammar>(self, _: &Entry) -> anyhow::Result<()> {
        let args = self.args;
        let genomes = load_genomes::<G>(&args.genomes)?;
        let scorer = match self.scene.objectives {
            Some(_) => None,
            None => Some(SceneScorer::new::<G>(self.scene)?),
        };
        let meshes = self.scene.meshes.bind(G::GRAPH)?;
        std::fs::create_dir_all(&args.out)
            .with_context(|| format!("cannot create `{}`", args.out.display()))?;
        let targets = scorer
            .as_ref()
            .and_then(SceneScorer::silhouette)
            .map(|s| s.targets())
            .unwrap_or_default();
        let has_overlays = !targets.is_empty()
            || self
                .scene
                .objectives
                .as_ref()
                .is_some_and(|goal| !projections(&goal.set).is_empty());
        let width = genomes.len().saturating_sub(1).max(1).ilog10() as usize + 1;
        let palette = Palette::new();

        genomes
            .par_iter()
            .enumerate()
            .try_for_each_init(Vec::new, |instances, (i, genome)| {
                genome.derive_on(&self.scene.site, instances);
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
                    .render(Model::new(instances, &meshes, &palette))?
                    .save(&path)
                    .with_context(|| format!("cannot write `{}`", path.display()))?;
                if let Some(goal) = &self.scene.objectives {
                    let surface = Surface::from_instances(instances, &meshes);
                    let views = projections(&goal.set);
                    for (k, (_, projection)) in views.iter().enumerate() {
                        let stem = args.out.join(format!("overlay_{i:0width$}"));
                        let path = numbered(&stem, k, views.len(), "png");
                        projection_overlay(projection, &surface)
                            .save(&path)
                            .with_context(|| format!("cannot write `{}`", path.display()))?;
                    }
                }
                if let Some(silhouette) = scorer.as_ref().and_then(SceneScorer::silhouette) {
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
        let overlays = if !has_overlays {
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
