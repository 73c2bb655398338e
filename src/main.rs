//! The `shapegen` command-line tool, for the published generators.

fn main() -> std::process::ExitCode {
    shapegen::cli::Cli::new().published().run()
}
