//! The self-contained report: the viewer's page with its styles, scripts, three.js
//! modules and the folder's files inline, so that it opens from `file://` with no
//! network and no server.

use std::collections::BTreeMap;
use std::path::Path;

use anyhow::Context;
use base64::Engine;
use base64::engine::general_purpose::STANDARD;

use super::assets::{MODULES, asset};
use super::listing::listing;

/// Largest total of folder files a report embeds, in bytes; beyond it the report is
/// refused rather than written unusably large.
const MAX_EMBEDDED: u64 = 256 << 20;

/// Whether the page uses the folder's file `name`: the numbers, tables and curves, the
/// models (best, front members, each compared or swept run's best) and the targets;
/// not the checkpoint or the genomes.
fn reported(name: &str) -> bool {
    let file = name.rsplit('/').next().unwrap_or(name);
    if file == "checkpoint.json"
        || file.ends_with(".genome.json")
        || file.ends_with(".genomes.json")
    {
        return false;
    }
    [".json", ".csv", ".glb", ".md"]
        .iter()
        .any(|ext| file.ends_with(ext))
        || matches!(file, "target.obj" | "target.png")
}

/// `text` with every `from` replaced by `to`; an error if it is not there, so that a
/// changed page or library fails loudly instead of writing a report that cannot load.
fn replace(text: &str, from: &str, to: &str, what: &str) -> anyhow::Result<String> {
    anyhow::ensure!(text.contains(from), "{what}: `{from}` not found");
    Ok(text.replace(from, to))
}

/// Text safe inside an inline `<script>` (no `</script` ends it early).
fn script_text(text: &str) -> String {
    text.replace("</script", "<\\/script")
}

fn asset_text(name: &str) -> anyhow::Result<String> {
    asset(name)
        .with_context(|| format!("embedded asset {name} missing"))?
        .text()
        .with_context(|| format!("embedded asset {name} does not unpack"))
}

/// The report page for `root`: `assets/viewer/index.html` with its stylesheets and
/// scripts inline, an import map of `data:` URLs for the three.js modules, and the
/// folder's files the page uses as base64 in `window.SHAPEGEN_FILES`.
///
/// # Errors
/// When `root` is not a folder, holds no output the page shows, a file cannot be read,
/// or the files exceed 256 MiB.
pub fn report_html(root: &Path) -> anyhow::Result<String> {
    anyhow::ensure!(
        root.is_dir(),
        "`{}` is not a folder: give a run's --out folder",
        root.display()
    );
    let names: Vec<String> = listing(root)
        .files
        .into_iter()
        .filter(|n| reported(n))
        .collect();
    anyhow::ensure!(
        names.iter().any(|n| {
            matches!(
                n.as_str(),
                "fitness.csv" | "front.csv" | "compare.csv" | "sweep.csv"
            )
        }),
        "`{}` holds none of fitness.csv, front.csv, compare.csv or sweep.csv: it is not the \
         folder of a run, a comparison or a study",
        root.display()
    );
    let files = embedded_files(root, names)?;
    let import_map = import_map()?;
    let mut page = asset_text("index.html")?;
    for (from, to) in inline_swaps(&files, &import_map)? {
        page = replace(&page, from, &to, "index.html")?;
    }
    Ok(page)
}

/// The files `names` of `root`, each as base64 by name.
///
/// # Errors
/// When a file cannot be read or the files exceed [`MAX_EMBEDDED`].
fn embedded_files(root: &Path, names: Vec<String>) -> anyhow::Result<BTreeMap<String, String>> {
    let mut total = 0;
    let mut files = BTreeMap::new();
    for name in names {
        let path = root.join(&name);
        let bytes =
            std::fs::read(&path).with_context(|| format!("cannot read `{}`", path.display()))?;
        total += bytes.len() as u64;
        anyhow::ensure!(
            total <= MAX_EMBEDDED,
            "the folder's files exceed {} MiB; a report would be too large to open",
            MAX_EMBEDDED >> 20
        );
        files.insert(name, STANDARD.encode(bytes));
    }
    Ok(files)
}

/// The import map of the three.js modules, each a `data:` URL of its rewritten text.
fn import_map() -> anyhow::Result<serde_json::Value> {
    let mut imports = BTreeMap::new();
    for module in MODULES {
        let mut text = asset_text(module.asset)?;
        for (from, to) in module.rewrites {
            text = replace(&text, from, to, module.asset)?;
        }
        imports.insert(
            module.key,
            format!("data:text/javascript;base64,{}", STANDARD.encode(text)),
        );
    }
    Ok(serde_json::json!({ "imports": imports }))
}

/// What `index.html` links to, each with its text inline: the stylesheets, the import
/// map, uPlot, and the viewer's script with the folder's `files` before it.
fn inline_swaps(
    files: &BTreeMap<String, String>,
    import_map: &serde_json::Value,
) -> anyhow::Result<[(&'static str, String); 5]> {
    Ok([
        (
            r#"<link rel="stylesheet" href="/assets/vendor/uplot/uPlot.min.css">"#,
            format!(
                "<style>{}</style>",
                asset_text("vendor/uplot/uPlot.min.css")?
            ),
        ),
        (
            r#"<link rel="stylesheet" href="/assets/viewer.css">"#,
            format!("<style>{}</style>", asset_text("viewer.css")?),
        ),
        (
            r#"<script type="importmap">{"imports": {"three": "/assets/vendor/three/three.module.js", "three/core": "/assets/vendor/three/three.core.js", "three/addons/": "/assets/vendor/three/addons/"}}</script>"#,
            format!(
                "<script type=\"importmap\">{}</script>",
                script_text(&import_map.to_string())
            ),
        ),
        (
            r#"<script src="/assets/vendor/uplot/uPlot.iife.min.js"></script>"#,
            format!(
                "<script>{}</script>",
                script_text(&asset_text("vendor/uplot/uPlot.iife.min.js")?)
            ),
        ),
        (
            r#"<script type="module" src="/assets/viewer.js"></script>"#,
            format!(
                "<script>window.SHAPEGEN_FILES = {};</script>\n<script type=\"module\">{}</script>",
                script_text(&serde_json::to_string(&files)?),
                script_text(&asset_text("viewer.js")?)
            ),
        ),
    ])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reports_what_the_page_shows() {
        for name in [
            "run.json",
            "fitness.csv",
            "best.glb",
            "front/model_003.glb",
            "runs/ga-0/best.glb",
            "target.png",
            "target.obj",
            "summary.md",
        ] {
            assert!(reported(name), "{name}");
        }
        for name in [
            "checkpoint.json",
            "best.genome.json",
            "front.genomes.json",
            "best.obj",
            "best.png",
            "report.html",
        ] {
            assert!(!reported(name), "{name}");
        }
    }

    #[test]
    fn refuses_a_folder_without_outputs() {
        let dir = tempfile::tempdir().unwrap();
        let err = report_html(dir.path()).unwrap_err().to_string();
        assert!(err.contains("fitness.csv"), "{err}");
        let err = report_html(&dir.path().join("missing"))
            .unwrap_err()
            .to_string();
        assert!(err.contains("not a folder"), "{err}");
    }
}
