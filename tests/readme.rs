//! The README's commands run from a clone as written: every scene, script or example file
//! they name is in the repository, and every genome file or run folder they read was
//! written by a command before them (its `--out`).
//!
//! And `docs/architecture.md`'s lists of crates, methods, scorers, objectives and
//! published generators are those of the workspace and the tables.

use std::path::Path;

/// The shell lines of the README's `sh` blocks, continuation lines joined and comments
/// dropped.
fn commands(readme: &str) -> Vec<String> {
    let mut lines = Vec::new();
    let mut inside = false;
    let mut pending = String::new();
    for line in readme.lines() {
        if line.starts_with("```") {
            inside = line == "```sh";
            continue;
        }
        if !inside {
            continue;
        }
        let code = line.split(" #").next().unwrap_or("").trim();
        if code.starts_with('#') || code.is_empty() {
            continue;
        }
        match code.strip_suffix('\\') {
            Some(start) => pending.push_str(start),
            None => {
                pending.push_str(code);
                lines.push(std::mem::take(&mut pending));
            }
        }
    }
    lines
}

#[test]
fn the_readme_names_only_files_that_a_clone_has_or_that_it_writes_first() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let readme = std::fs::read_to_string(root.join("README.md")).expect("README.md reads");
    let commands = commands(&readme);
    assert!(commands.len() > 20, "{} commands found", commands.len());
    let mut written: Vec<String> = Vec::new();
    let mut checked = 0;
    for command in &commands {
        let words: Vec<&str> = command.split_whitespace().collect();
        for (i, word) in words.iter().enumerate() {
            let flag = i.checked_sub(1).map(|j| words[j]);
            let word = word.trim_matches('"');
            if flag == Some("--out") {
                continue;
            }
            let repository_file = ["scenes/", "examples/", "scripts/"]
                .iter()
                .any(|folder| word.starts_with(folder));
            if repository_file {
                assert!(
                    root.join(word).exists(),
                    "`{word}` in `{command}` is not in the repository"
                );
                checked += 1;
            }
            if matches!(flag, Some("--genome" | "--genomes" | "--resume")) {
                let made = written
                    .iter()
                    .any(|out| word == out || word.starts_with(&format!("{out}/")));
                assert!(
                    made || root.join(word).exists(),
                    "`{word}` in `{command}` is read before any command writes it"
                );
                checked += 1;
            }
        }
        for pair in words.windows(2) {
            if pair[0] == "--out" {
                written.push(pair[1].to_owned());
            }
        }
        if command.contains("--example city") {
            // The example's own outputs.
            written.extend(
                ["best.glb", "best.obj", "best.png", "best.genome.json"]
                    .map(|f| format!("out/city/{f}")),
            );
        }
    }
    assert!(checked >= 19, "{checked} paths checked");
}

/// The backticked names of the item `- **{label}**` of `docs/architecture.md`'s "What
/// the tables hold", in order.
fn listed(notes: &str, label: &str) -> Vec<String> {
    let section = notes
        .split("## What the tables hold")
        .nth(1)
        .expect("docs/architecture.md has its section \"What the tables hold\"");
    let start = section
        .find(&format!("- **{label}**"))
        .unwrap_or_else(|| panic!("the section lists the {label}"));
    let item = section[start..].split("\n- ").next().unwrap_or("");
    // Names follow the colon; the parenthesis before it names the table.
    let names = item.split_once("):").map_or(item, |(_, names)| names);
    names
        .split('`')
        .skip(1)
        .step_by(2)
        .map(str::to_owned)
        .collect()
}

#[test]
fn the_architecture_notes_list_what_the_tables_hold() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let notes = std::fs::read_to_string(root.join("docs/architecture.md"))
        .expect("docs/architecture.md reads");
    let methods: Vec<&str> = shapegen::scene::Method::ALL
        .iter()
        .map(|m| m.name())
        .collect();
    assert_eq!(listed(&notes, "Methods"), methods);
    let scorers: Vec<&str> = shapegen::scene::ScorerKind::ALL
        .iter()
        .map(|k| k.name())
        .collect();
    assert_eq!(listed(&notes, "Scorers"), scorers);
    let objectives = shapegen::score::objective::Objective::NAMES;
    assert_eq!(listed(&notes, "Objectives"), objectives);
    let registry = shapegen::registry::Registry::published();
    let generators: Vec<&str> = registry.entries().iter().map(|e| e.name.as_str()).collect();
    assert_eq!(listed(&notes, "Published generators"), generators);

    // The crates: the root package and every member of the workspace.
    let manifest = |dir: &Path| -> toml::Table {
        let text = std::fs::read_to_string(dir.join("Cargo.toml")).expect("Cargo.toml reads");
        text.parse().expect("Cargo.toml parses")
    };
    let name = |table: &toml::Table| table["package"]["name"].as_str().unwrap().to_owned();
    let workspace = manifest(root);
    let mut crates = vec![name(&workspace)];
    for member in workspace["workspace"]["members"].as_array().unwrap() {
        crates.push(name(&manifest(&root.join(member.as_str().unwrap()))));
    }
    let mut listed_crates = listed(&notes, "Crates");
    crates.sort();
    listed_crates.sort();
    assert_eq!(listed_crates, crates);
}
