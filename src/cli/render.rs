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
use shapegen::score::objective::{Objective, ObjectiveSet, ProjectionMatch, Surface};
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
        let scorer = match self.scene.objectives {
            Some(_) => None,
            None => Some(SceneScorer::new::<G>(self.scene)?),
        };
        let meshes = self.scene.meshes.bind(G::GRAPH)?;
        std::fs::create_dir_all(&args.out)
            .with_context(|| format!("cannot create `{}`", args.out.display()))?;
        let targets = scorer
            .as_ref()
            .and_then(|s| s.silhouette.as_ref())
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
                if let Some(silhouette) = scorer.as_ref().and_then(|s| s.silhouette.as_ref()) {
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

/// The projection objectives of `set`, under their names.
pub fn projections(set: &ObjectiveSet) -> Vec<(&str, &ProjectionMatch)> {
    set.entries()
        .iter()
        .filter_map(|(name, objective)| match objective {
            Objective::Projection(p) => Some((name.as_str(), p)),
            _ => None,
        })
        .collect()
}

/// The overlay of a model's coverage `mask` on `target`: target alone blue, model alone
/// red, both green, neither white.
pub fn overlay(target: &ImageTarget, mask: &[bool]) -> RgbImage {
    let w = target.width();
    overlay_with(w, target.height(), |x, y| {
        (target.is_target(x, y), mask[(y * w + x) as usize])
    })
}

/// The overlay of a model's orthographic projection on a projection objective's target,
/// coloured as [`overlay`]'s.
pub fn projection_overlay(projection: &ProjectionMatch, surface: &Surface) -> RgbImage {
    let covered = projection.render(surface);
    overlay_with(projection.width(), projection.height(), |x, y| {
        (projection.mask(x, y), covered.get_pixel(x, y).0[0] == 0)
    })
}

/// An overlay picture from `(is target, is covered)` per pixel.
fn overlay_with(width: u32, height: u32, pixel: impl Fn(u32, u32) -> (bool, bool)) -> RgbImage {
    RgbImage::from_fn(width, height, |x, y| match pixel(x, y) {
        (true, true) => BOTH,
        (true, false) => TARGET,
        (false, true) => MODEL,
        (false, false) => NEITHER,
    })
}
