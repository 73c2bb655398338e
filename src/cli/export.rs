//! `shapegen export`: the model a saved genome derives, as a Wavefront OBJ (with its MTL)
//! or a binary glTF file.

use std::path::{Path, PathBuf};

use anyhow::Context;
use clap::Args;
use generators::{GeneratorVisitor, Published};
use shapegen::Grammar;
use shapegen::MeshLibrary;
use shapegen::export::{Palette, glb_bytes, write_mtl, write_obj};
use shapegen::genome::Limits;
use shapegen::scene::Scene;

use super::files::atomic_write;
use super::genomes::GenomeFile;

/// Arguments of `shapegen export`.
#[derive(Debug, Args)]
pub struct ExportArgs {
    /// The generator: spaceship, tree, city or building (default: the scene's, or else
    /// the one the genome file names). With --scene it must be the scene's.
    #[arg(long, short)]
    generator: Option<Published>,
    /// The genome file: a single genome or a set, in either JSON form.
    #[arg(long)]
    genome: PathBuf,
    /// Which genome of a set.
    #[arg(long, default_value_t = 0)]
    index: usize,
    /// A scene file (TOML) whose meshes to use (default: the generator's own meshes).
    #[arg(long)]
    scene: Option<PathBuf>,
    /// Where to write, in the format of its extension: `.obj` (with the material library
    /// `.mtl` beside it) or `.glb`.
    #[arg(long)]
    out: PathBuf,
}

/// The file formats `export` writes.
#[derive(Clone, Copy)]
enum Format {
    Obj,
    Glb,
}

impl Format {
    /// The format of `path`, by its extension.
    fn of(path: &Path) -> anyhow::Result<Format> {
        let extension = path.extension().and_then(|e| e.to_str()).unwrap_or("");
        match extension.to_ascii_lowercase().as_str() {
            "obj" => Ok(Format::Obj),
            "glb" => Ok(Format::Glb),
            _ => anyhow::bail!(
                "--out `{}`: the format follows the extension, which must be .obj or .glb",
                path.display()
            ),
        }
    }
}

/// Runs `shapegen export`.
pub fn run(args: &ExportArgs) -> anyhow::Result<()> {
    let format = Format::of(&args.out)?;
    let scene = args.scene.as_deref().map(Scene::load).transpose()?;
    let file = GenomeFile::read(&args.genome)?;
    let generator = match (&scene, args.generator) {
        (Some(scene), Some(generator)) if generator != scene.generator => anyhow::bail!(
            "--generator {generator} disagrees with the scene `{}`, whose generator is {}",
            scene.path.display(),
            scene.generator
        ),
        (Some(scene), _) => scene.generator,
        (None, Some(generator)) => generator,
        (None, None) => file.generator()?,
    };
    let meshes = match scene {
        Some(scene) => scene.meshes,
        None => generators::default_meshes(),
    };
    generator.visit(Export {
        args,
        file: &file,
        meshes: &meshes,
        format,
    })
}

struct Export<'a> {
    args: &'a ExportArgs,
    file: &'a GenomeFile,
    meshes: &'a MeshLibrary,
    format: Format,
}

impl GeneratorVisitor for Export<'_> {
    type Output = anyhow::Result<()>;

    fn visit<G: Grammar>(self, _: Limits) -> anyhow::Result<()> {
        let args = self.args;
        let genome = self.file.genome::<G>(args.index)?;
        let meshes = self.meshes.bind(G::GRAPH)?;
        let mut instances = Vec::new();
        genome.derive_into(&mut instances);
        if let Some(parent) = args.out.parent().filter(|p| !p.as_os_str().is_empty()) {
            std::fs::create_dir_all(parent)
                .with_context(|| format!("cannot create `{}`", parent.display()))?;
        }
        let palette = Palette::new();
        let written = match self.format {
            Format::Obj => {
                let mtl = args.out.with_extension("mtl");
                let mtl_name = mtl.file_name().unwrap_or_default().to_string_lossy();
                let mut obj_bytes = Vec::new();
                write_obj(&mut obj_bytes, &mtl_name, &instances, &meshes, &palette)?;
                let mut mtl_bytes = Vec::new();
                write_mtl(&mut mtl_bytes, &instances, &meshes, &palette)?;
                atomic_write(&mtl, &mtl_bytes)?;
                atomic_write(&args.out, &obj_bytes)?;
                format!("{} and {}", args.out.display(), mtl.display())
            }
            Format::Glb => {
                atomic_write(&args.out, &glb_bytes(&instances, &meshes, &palette)?)?;
                args.out.display().to_string()
            }
        };
        println!(
            "wrote {written}: {} genome {} of `{}`, {} genes, {} instances",
            G::GRAPH.name,
            args.index,
            args.genome.display(),
            genome.len(),
            instances.len()
        );
        Ok(())
    }
}
