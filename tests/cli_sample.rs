//! `shapegen sample` end to end: the files it writes, their determinism at any thread
//! count, and its errors.

mod support;

use std::fs;
use std::path::Path;

use support::{published_names, shapegen};

use generators::{City, Spaceship, Tree};
use shapegen::Grammar;
use shapegen::genome::GenomeSet;

fn sample(generator: &str, threads: &str, out: &Path) {
    let out_arg = out.to_str().unwrap();
    let run = shapegen(&[
        "--threads",
        threads,
        "sample",
        "--generator",
        generator,
        "--count",
        "12",
        "--seed",
        "42",
        "--out",
        out_arg,
    ]);
    assert!(
        run.status.success(),
        "shapegen sample failed: {}",
        String::from_utf8_lossy(&run.stderr)
    );
}

/// The sorted file names of `dir` and their contents.
fn files(dir: &Path) -> Vec<(String, Vec<u8>)> {
    let mut files: Vec<_> = fs::read_dir(dir)
        .unwrap()
        .map(|e| {
            let e = e.unwrap();
            (
                e.file_name().into_string().unwrap(),
                fs::read(e.path()).unwrap(),
            )
        })
        .collect();
    files.sort();
    files
}

fn check_generator<G: Grammar>(name: &str) {
    let tmp = tempfile::tempdir().unwrap();
    let (one, two) = (tmp.path().join("one"), tmp.path().join("two"));
    sample(name, "1", &one);
    sample(name, "2", &two);

    let written = files(&one);
    // 12 models as .obj + .mtl + .glb, and genomes.json.
    assert_eq!(written.len(), 12 * 3 + 1);
    assert!(written.iter().any(|(n, _)| n == "model_00.glb"));
    assert!(written.iter().any(|(n, _)| n == "model_11.obj"));
    for (n, bytes) in &written {
        if n.ends_with(".glb") {
            assert_eq!(&bytes[..4], b"glTF", "{n} is not binary glTF");
        }
    }
    assert!(
        written == files(&two),
        "{name}: 1 and 2 threads wrote different files"
    );

    let set = GenomeSet::<G>::load(one.join("genomes.json")).unwrap();
    assert_eq!(set.genomes.len(), 12);
    let mut instances = Vec::new();
    for genome in &set.genomes {
        genome.validate().unwrap();
        genome.derive_into(&mut instances);
    }
    // Uncontrolled models differ from one another.
    assert!(set.genomes.windows(2).any(|w| w[0] != w[1]));
}

#[test]
fn spaceship_samples_are_identical_at_any_thread_count() {
    check_generator::<Spaceship>("spaceship");
}

#[test]
fn tree_samples_are_identical_at_any_thread_count() {
    check_generator::<Tree>("tree");
}

#[test]
fn city_samples_are_identical_at_any_thread_count() {
    check_generator::<City>("city");
}

#[test]
fn another_seed_gives_other_models() {
    let tmp = tempfile::tempdir().unwrap();
    let dirs = [tmp.path().join("a"), tmp.path().join("b")];
    for (seed, dir) in ["1", "2"].iter().zip(&dirs) {
        let run = shapegen(&[
            "sample",
            "-g",
            "spaceship",
            "-n",
            "3",
            "-s",
            seed,
            "-o",
            dir.to_str().unwrap(),
        ]);
        assert!(run.status.success());
    }
    let read = |d: &Path| fs::read_to_string(d.join("genomes.json")).unwrap();
    assert_ne!(read(&dirs[0]), read(&dirs[1]));
}

#[test]
fn bad_input_is_refused_with_a_clear_message() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("out");
    let out = out.to_str().unwrap();
    let unknown = format!(
        "unknown generator `house`; the generators are {}",
        published_names()
    );
    let cases: [(&[&str], &str); 4] = [
        (&["sample", "-g", "house", "-o", out], &unknown),
        (
            &["sample", "-g", "tree", "--max-depth", "0", "-o", out],
            "--max-depth",
        ),
        (
            &["--threads", "0", "sample", "-g", "tree", "-o", out],
            "--threads",
        ),
        (
            &["sample", "-g", "city", "--genes", "500", "-o", out],
            "--genes 500 must lie between 1 and the largest genome, 300 genes",
        ),
    ];
    for (args, expected) in cases {
        let run = shapegen(args);
        assert!(!run.status.success(), "{args:?} succeeded");
        let stderr = String::from_utf8_lossy(&run.stderr);
        assert!(stderr.contains(expected), "{args:?}: {stderr}");
    }

    // An output path that is a file.
    let file = tmp.path().join("file");
    fs::write(&file, "").unwrap();
    let run = shapegen(&["sample", "-g", "city", "-o", file.to_str().unwrap()]);
    assert!(!run.status.success());
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(stderr.contains(file.to_str().unwrap()), "{stderr}");
}

#[test]
fn genes_grows_models_to_a_length() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().to_str().unwrap();
    let run = shapegen(&[
        "sample", "-g", "tree", "-n", "5", "--genes", "150", "-o", out,
    ]);
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let set = GenomeSet::<Tree>::load(tmp.path().join("genomes.json")).unwrap();
    // Random genomes are grown to a length drawn around the one asked for; drawn from
    // the generator's own distribution, trees are a few dozen genes.
    let mean = set.genomes.iter().map(|g| g.len()).sum::<usize>() / set.genomes.len();
    assert!((100..=200).contains(&mean), "mean length {mean}");
}
