//! `shapegen export`: the model a saved genome derives, as a Wavefront OBJ (with its MTL)
//! or a binary glTF file.

use std::path::{Path, PathBuf};

use anyhow::Context;
use clap::Args;
use shapegen::Grammar;
use shapegen::MeshLibrary;
use shapegen::Site;
use shapegen::export::{Model, Palette, glb_bytes, write_mtl, write_obj};
use shapegen::scene::{Overrides, Scene};

use crate::cli::files::atomic_write;
use crate::cli::generators::{Generators, Jobs, Visit};
use crate::cli::genomes::GenomeFile;
use crate::registry::Entry;

/// Arguments of `shapegen export`.
#[derive(Debug, Args)]
pub struct ExportArgs {
    /// The generator, by name (default: the scene's, or else the one the genome file
    /// names). With --scene it must be the scene's.
    #[arg(long, short)]
    generator: Option<String>,
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
pub fn run<J: Jobs>(args: &ExportArgs, tool: &Generators<J>) -> anyhow::Result<()>
where
    for<'a> J::Job<'a>: From<Export<'a>>,
{
    let format = Format::of(&args.out)?;
    let scene = args
        .scene
        .as_deref()
        .map(|path| Scene::open(path, tool.registry(), &Overrides::default()))
        .transpose()?;
    let file = GenomeFile::read(&args.genome)?;
    let generator = match (&scene, &args.generator) {
        (Some(scene), Some(generator)) if !generator.eq_ignore_ascii_case(&scene.generator) => {
            anyhow::bail!(
                "--generator {generator} disagrees with the scene `{}`, whose generator is {}",
                scene.path.display(),
                scene.generator
            )
        }
        (Some(scene), _) => scene.generator.as_str(),
        (None, Some(generator)) => generator.as_str(),
        (None, None) => file.generator(tool.registry())?.name.as_str(),
    };
    tool.visit(
        generator,
        Export {
            args,
            file: &file,
            meshes: scene.as_ref().map(|s| &s.meshes),
            site: scene.as_ref().map_or(&Site::NONE, |s| &s.site),
            format,
        },
    )
}

/// The body of `shapegen export`.
pub struct Export<'a> {
    args: &'a ExportArgs,
    file: &'a GenomeFile,
    /// The scene's meshes, if a scene was given.
    meshes: Option<&'a MeshLibrary>,
    /// The scene's site, or none without a scene.
    site: &'a Site,
    format: Format,
}

impl Visit for Export<'_> {
    fn visit<G: Grammar>(self, entry: &Entry) -> anyhow::Result<()> {
        let args = self.args;
        let genome = self.file.genome::<G>(args.index)?;
        let meshes = self
            .meshes
            .unwrap_or(&entry.defaults.meshes)
            .bind(G::GRAPH)?;
        let mut instances = Vec::new();
        genome.derive_on(self.site, &mut instances);
        if let Some(parent) = args.out.parent().filter(|p| !p.as_os_str().is_empty()) {
            std::fs::create_dir_all(parent)
                .with_context(|| format!("cannot create `{}`", parent.display()))?;
        }
        let palette = Palette::new();
        let model = Model::new(&instances, &meshes, &palette);
        let written = match self.format {
            Format::Obj => {
                let mtl = args.out.with_extension("mtl");
                let mtl_name = mtl.file_name().unwrap_or_default().to_string_lossy();
                let mut obj_bytes = Vec::new();
                write_obj(&mut obj_bytes, &mtl_name, model)?;
                let mut mtl_bytes = Vec::new();
                write_mtl(&mut mtl_bytes, model)?;
                atomic_write(&mtl, &mtl_bytes)?;
                atomic_write(&args.out, &obj_bytes)?;
                format!("{} and {}", args.out.display(), mtl.display())
            }
            Format::Glb => {
                atomic_write(&args.out, &glb_bytes(model)?)?;
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
