//! `shapegen target`: a reachable target made from a fixed derivation, through the
//! scene's own grid or cameras.

use std::path::{Path, PathBuf};

use anyhow::Context;
use clap::Args;
use image::{GrayImage, Luma};
use shapegen::Grammar;
use shapegen::Instance;
use shapegen::scene::{Scene, SceneScorer};
use shapegen::score::Scorer;
use shapegen::score::objective::{ObjectiveSet, Surface};

use crate::cli::generators::Visit;
use crate::cli::genomes::load_genome;
use crate::cli::overlay::{numbered, projections};
use crate::cli::voxels::voxel_surface_obj;
use crate::registry::Entry;

use super::on_scene::OnScene;

/// Arguments of `shapegen target`.
#[derive(Debug, Args)]
pub struct TargetArgs {
    /// The scene file (TOML) whose grid or cameras the target is made for.
    pub(super) scene: PathBuf,
    /// The genome to make the target of: a single genome or a set.
    #[arg(long)]
    genome: PathBuf,
    /// Which genome of a set.
    #[arg(long, default_value_t = 0)]
    index: usize,
    /// Where to write: a volume scene writes `PATH` as `.obj` (the surface of the voxels the
    /// model covers), a silhouette scene `PATH` as `.png` (black where the model covers,
    /// one file per camera, numbered when there are several), a scene with objectives
    /// `PATH` as `.png` for each top_match or front_match objective (numbered likewise).
    #[arg(long)]
    out: PathBuf,
}

/// The body of `shapegen target`.
pub type Target<'a> = OnScene<'a, TargetArgs>;

impl Visit for Target<'_> {
    fn visit<G: Grammar>(self, _: &Entry) -> anyhow::Result<()> {
        let args = self.args;
        let genome = load_genome::<G>(&args.genome, args.index)?;
        let mut instances = Vec::new();
        genome.derive_on(&self.scene.site, &mut instances);
        if let Some(parent) = args.out.parent().filter(|p| !p.as_os_str().is_empty()) {
            std::fs::create_dir_all(parent)
                .with_context(|| format!("cannot create `{}`", parent.display()))?;
        }
        if let Some(goal) = &self.scene.objectives {
            return projection_targets::<G>(self.scene, &goal.set, &instances, &args.out);
        }
        let scorer = SceneScorer::new::<G>(self.scene)?;

        if let Some(volume) = scorer.volume() {
            let mut covered = Vec::new();
            let counts = volume.coverage(&instances, &mut volume.scratch(), &mut covered);
            let voxels = counts.inside + counts.outside;
            anyhow::ensure!(
                voxels > 0,
                "the model covers no voxel of the scene's grid; pick another genome or grid"
            );
            let (obj, faces) = voxel_surface_obj(volume.grid(), &covered);
            let path = args.out.with_extension("obj");
            write(&path, obj.as_bytes())?;
            println!("wrote {} ({voxels} voxels, {faces} faces)", path.display());
        }
        if let Some(silhouette) = scorer.silhouette() {
            let targets = silhouette.targets();
            for (k, target) in targets.iter().enumerate() {
                let (w, h) = (target.width(), target.height());
                let mut mask = vec![false; w as usize * h as usize];
                silhouette.coverage_mask(k, &instances, &mut mask)?;
                let covered = mask.iter().filter(|&&c| c).count();
                anyhow::ensure!(
                    covered > 0,
                    "the model covers no pixel through camera {k}; pick another genome"
                );
                let image = GrayImage::from_fn(w, h, |x, y| {
                    Luma([if mask[(y * w + x) as usize] { 0 } else { 255 }])
                });
                let path = numbered(&args.out, k, targets.len(), "png");
                image
                    .save(&path)
                    .with_context(|| format!("cannot write `{}`", path.display()))?;
                println!(
                    "wrote {} ({covered} target pixels, {w} x {h})",
                    path.display()
                );
            }
        }
        Ok(())
    }
}

/// Writes the image of every projection objective of `set` for the model made of
/// `instances`, black where it covers: `out` as `.png`, numbered when there are several.
fn projection_targets<G: Grammar>(
    scene: &Scene,
    set: &ObjectiveSet,
    instances: &[Instance],
    out: &Path,
) -> anyhow::Result<()> {
    let meshes = scene.meshes.bind(G::GRAPH)?;
    let surface = Surface::from_instances(instances, &meshes);
    let views = projections(set);
    anyhow::ensure!(
        !views.is_empty(),
        "the scene has no top_match or front_match objective to make an image for"
    );
    for (k, (name, projection)) in views.iter().enumerate() {
        let image = projection.render(&surface);
        let covered = image.pixels().filter(|p| p.0[0] == 0).count();
        anyhow::ensure!(
            covered > 0,
            "the model covers no pixel of objective `{name}`'s area; pick another genome"
        );
        let path = numbered(out, k, views.len(), "png");
        image
            .save(&path)
            .with_context(|| format!("cannot write `{}`", path.display()))?;
        println!(
            "wrote {} for `{name}` ({covered} target pixels, {} x {})",
            path.display(),
            image.width(),
            image.height()
        );
    }
    Ok(())
}

fn write(path: &Path, bytes: &[u8]) -> anyhow::Result<()> {
    std::fs::write(path, bytes).with_context(|| format!("cannot write `{}`", path.display()))
}
