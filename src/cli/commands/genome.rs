//! `shapegen genome`: work on genome files; `convert` rewrites one in the other JSON form.

use std::path::PathBuf;

use anyhow::Context;
use clap::{Args, Subcommand, ValueEnum};
use shapegen::genome::GenomeSet;
use shapegen::{Genome, Grammar};

use crate::cli::files::atomic_write;
use crate::cli::generators::{Generators, Jobs, Visit};
use crate::cli::genomes::GenomeFile;
use crate::registry::Entry;

/// Arguments of `shapegen genome`.
#[derive(Debug, Args)]
pub struct GenomeArgs {
    #[command(subcommand)]
    command: GenomeCommand,
}

#[derive(Debug, Subcommand)]
enum GenomeCommand {
    /// Rewrite a genome file (a single genome or a set) in the other JSON form: the packed
    /// form (genes with relative offsets, as the commands write) or the nested form (the
    /// tree as nested objects, for reading and writing by hand).
    Convert(ConvertArgs),
}

/// Arguments of `shapegen genome convert`.
#[derive(Debug, Args)]
pub struct ConvertArgs {
    /// The genome file: a single genome or a set, in either form, of the generator it
    /// names.
    input: PathBuf,
    /// Where to write.
    #[arg(long)]
    out: PathBuf,
    /// The form to write (default: the one the file is not in).
    #[arg(long, value_enum)]
    to: Option<Form>,
}

/// A JSON form of genomes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
enum Form {
    /// Genes in buffer order with relative word offsets.
    Packed,
    /// The tree as nested objects, children under their slot names.
    Nested,
}

impl Form {
    fn name(self) -> &'static str {
        match self {
            Form::Packed => "packed",
            Form::Nested => "nested",
        }
    }
}

/// Runs `shapegen genome`.
pub fn run<J: Jobs>(args: &GenomeArgs, tool: &Generators<J>) -> anyhow::Result<()>
where
    for<'a> J::Job<'a>: From<Convert<'a>>,
{
    match &args.command {
        GenomeCommand::Convert(args) => convert(args, tool),
    }
}

fn convert<J: Jobs>(args: &ConvertArgs, tool: &Generators<J>) -> anyhow::Result<()>
where
    for<'a> J::Job<'a>: From<Convert<'a>>,
{
    let file = GenomeFile::read(&args.input)?;
    let to = args.to.unwrap_or(if file.layout.nested {
        Form::Packed
    } else {
        Form::Nested
    });
    tool.visit(
        &file.generator(tool.registry())?.name,
        Convert {
            args,
            file: &file,
            to,
        },
    )
}

/// The body of `shapegen genome convert`.
pub struct Convert<'a> {
    args: &'a ConvertArgs,
    file: &'a GenomeFile,
    to: Form,
}

impl Visit for Convert<'_> {
    fn visit<G: Grammar>(self, _: &Entry) -> anyhow::Result<()> {
        let (text, what) = if self.file.layout.set {
            let set = GenomeSet::<G>::new(self.file.genomes()?);
            let text = match self.to {
                Form::Packed => set.to_json(),
                Form::Nested => set.to_nested_json(),
            };
            let what = format!("a set of {} {} genomes", set.genomes.len(), G::GRAPH.name);
            (GenomeSet::<G>::from_json(&text).map(|_| text), what)
        } else {
            let genome = self.file.genome::<G>(0)?;
            let text = match self.to {
                Form::Packed => genome.to_json(),
                Form::Nested => genome.to_nested_json(),
            };
            let what = format!("a {} genome", G::GRAPH.name);
            (Genome::<G>::from_json(&text).map(|_| text), what)
        };
        // What is written must read back: a tree too deep for the nested form stays packed.
        let text = text.with_context(|| {
            format!(
                "cannot write `{}` in the {} form, which would not read back",
                self.args.out.display(),
                self.to.name()
            )
        })?;
        atomic_write(&self.args.out, text.as_bytes())?;
        println!(
            "wrote {what} in the {} form to {}",
            self.to.name(),
            self.args.out.display()
        );
        Ok(())
    }
}
