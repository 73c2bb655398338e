//! `shapegen genome convert` and `shapegen export` end to end, and the other commands
//! reading genomes in the nested form.

mod support;

use std::fs;
use std::path::{Path, PathBuf};

use generators::spaceship::{Body, Start};
use generators::{Spaceship, Tree};
use shapegen::genome::GenomeSet;
use shapegen::prelude::Vec3;
use shapegen::scene::Scene;
use shapegen::{BoundMeshes, Genome, Grammar, Instance};
use support::{fails, ok, published_names, s};

/// Writes `count` sampled models of `generator` into `dir` and returns their genomes file.
fn sample(generator: &str, count: &str, dir: &Path) -> PathBuf {
    ok(&[
        "sample",
        "-g",
        generator,
        "-n",
        count,
        "-s",
        "7",
        "--genes",
        "12",
        "-o",
        s(dir),
    ]);
    dir.join("genomes.json")
}

fn convert(input: &Path, out: &Path, to: Option<&str>) -> String {
    let mut args = vec!["genome", "convert", s(input), "--out", s(out)];
    if let Some(to) = to {
        args.extend(["--to", to]);
    }
    ok(&args)
}

fn read(path: &Path) -> String {
    fs::read_to_string(path).unwrap()
}

#[test]
fn convert_rewrites_a_set_in_the_other_form_and_back_byte_for_byte() {
    let dir = tempfile::tempdir().unwrap();
    let packed = sample("spaceship", "5", &dir.path().join("ships"));
    let nested = dir.path().join("nested.json");
    let out = convert(&packed, &nested, None);
    assert_eq!(
        out.trim(),
        format!(
            "wrote a set of 5 Spaceship genomes in the nested form to {}",
            nested.display()
        )
    );
    let text = read(&nested);
    assert!(
        text.starts_with("{\n  \"generator\": \"spaceship\",\n  \"genomes\": [\n    {\n      \"tree\": {\n        \"node\": \"Start\",\n"),
        "{text}"
    );
    let original = GenomeSet::<Spaceship>::load(&packed).unwrap();
    let converted = GenomeSet::<Spaceship>::load(&nested).unwrap();
    assert_eq!(converted.genomes.len(), 5);
    for (a, b) in original.genomes.iter().zip(&converted.genomes) {
        assert_eq!(instances(a), instances(b), "the same trees");
    }

    // Back to the packed form, which is the default from the nested one.
    let repacked = dir.path().join("repacked.json");
    convert(&nested, &repacked, None);
    assert_eq!(
        GenomeSet::<Spaceship>::load(&repacked).unwrap(),
        converted,
        "the packed form of the nested trees, word for word"
    );
    // From here both forms convert into each other byte for byte.
    let nested_again = dir.path().join("nested_again.json");
    convert(&repacked, &nested_again, None);
    assert_eq!(read(&nested_again), text);
    let repacked_again = dir.path().join("repacked_again.json");
    convert(&nested_again, &repacked_again, Some("packed"));
    assert_eq!(read(&repacked_again), read(&repacked));
    // Asked for the form it is in, the file is rewritten as it is.
    let same = dir.path().join("same.json");
    convert(&repacked, &same, Some("packed"));
    assert_eq!(read(&same), read(&repacked));
}

#[test]
fn convert_takes_single_genomes_of_any_generator() {
    let dir = tempfile::tempdir().unwrap();
    let hand = dir.path().join("hand.json");
    fs::write(&hand, HAND_SHIP).unwrap();
    let packed = dir.path().join("hand.packed.json");
    let out = convert(&hand, &packed, None);
    assert!(
        out.contains("wrote a Spaceship genome in the packed form"),
        "{out}"
    );
    let genome = Genome::<Spaceship>::load_json(&packed).unwrap();
    assert_eq!(read(&packed), genome.to_json());
    assert_eq!(genome.len(), 4);
    // `HAND_SHIP` names its generator as the grammar (`Spaceship`); the file is written
    // with the name the tool knows it by, and a file written so converts as well.
    assert!(read(&packed).contains(r#""generator": "spaceship""#));
    let lower = dir.path().join("hand.lower.json");
    fs::write(
        &lower,
        HAND_SHIP.replace(r#""Spaceship""#, r#""spaceship""#),
    )
    .unwrap();
    let out = convert(&lower, &dir.path().join("lower.packed.json"), None);
    assert!(out.contains("wrote a Spaceship genome"), "{out}");
    assert_eq!(read(&dir.path().join("lower.packed.json")), read(&packed));
    let nested = dir.path().join("hand.nested.json");
    convert(&packed, &nested, Some("nested"));
    assert_eq!(read(&nested), genome.to_nested_json());

    // The file names its generator; the tree's converts as well.
    let trees = sample("tree", "2", &dir.path().join("trees"));
    let nested_trees = dir.path().join("trees.json");
    let out = convert(&trees, &nested_trees, None);
    assert!(out.contains("a set of 2 Tree genomes"), "{out}");
    let original = GenomeSet::<Tree>::load(&trees).unwrap();
    let converted = GenomeSet::<Tree>::load(&nested_trees).unwrap();
    for (a, b) in original.genomes.iter().zip(&converted.genomes) {
        assert_eq!(instances(a), instances(b));
    }
}

#[test]
fn convert_explains_its_mistakes() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out.json");
    let rocket = dir.path().join("rocket.json");
    fs::write(
        &rocket,
        r#"{"generator": "Rocket", "tree": {"node": "Start"}}"#,
    )
    .unwrap();
    let err = fails(&["genome", "convert", s(&rocket), "--out", s(&out)]);
    assert_eq!(
        err.trim(),
        format!(
            "error: `{}`: unknown generator `Rocket`; the generators are {}",
            rocket.display(),
            published_names()
        )
    );
    let nameless = dir.path().join("nameless.json");
    fs::write(&nameless, r#"{"genes": []}"#).unwrap();
    let err = fails(&["genome", "convert", s(&nameless), "--out", s(&out)]);
    assert_eq!(
        err.trim(),
        format!(
            "error: `{}` names no generator; a genome file names it as `\"generator\": \
             \"spaceship\"`",
            nameless.display()
        )
    );
    let missing = dir.path().join("missing.json");
    let err = fails(&["genome", "convert", s(&missing), "--out", s(&out)]);
    assert!(
        err.starts_with(&format!(
            "error: cannot read genomes `{}`: No such file",
            missing.display()
        )),
        "{err}"
    );
    // A mistake in the file names the node.
    let bad = dir.path().join("bad.json");
    fs::write(&bad, HAND_SHIP.replace("\"wing\"", "\"wings\"")).unwrap();
    let err = fails(&["genome", "convert", s(&bad), "--out", s(&out)]);
    assert_eq!(
        err.trim(),
        format!(
            "error: cannot load genomes `{}`: at `Start > body: Body`: `wings` is not a slot of \
             `Body`; its slots are: `next`, `wing`, `top`",
            bad.display()
        )
    );
    let err = fails(&[
        "genome",
        "convert",
        s(&bad),
        "--out",
        s(&out),
        "--to",
        "xml",
    ]);
    assert!(err.contains("invalid value 'xml' for '--to <TO>'"), "{err}");
    assert!(err.contains("[possible values: packed, nested]"), "{err}");

    // A tree too deep for the nested form stays packed, and nothing is written.
    let mut deep = Genome::<Spaceship>::with_root(Start {}).unwrap();
    let mut at = deep.attach(0, "body", Body { size: Vec3::ONE }).unwrap();
    for _ in 0..70 {
        at = deep.attach(at, "next", Body { size: Vec3::ONE }).unwrap();
    }
    let deep_path = dir.path().join("deep.json");
    deep.save_json(&deep_path).unwrap();
    let err = fails(&["genome", "convert", s(&deep_path), "--out", s(&out)]);
    assert!(
        err.starts_with(&format!(
            "error: cannot write `{}` in the nested form, which would not read back: the nested \
             form nests deeper than the 128 levels JSON is read to",
            out.display()
        )),
        "{err}"
    );
    assert!(!out.exists());
}

/// A spaceship written by hand in the nested form: four genes, five boxes.
const HAND_SHIP: &str = r#"{"generator": "Spaceship", "tree": {"node": "Start", "children": {
    "body": {"node": "Body", "params": {"size": [1.2, 1.0, 1.4]}, "children": {
        "wing": {"node": "Wing", "params": {"size": [0.6, 0.3, 0.7], "shift": -0.2}},
        "top": {"node": "Top", "params": {"size": [0.5, 0.15, 0.5]}}}}}}}"#;

const SHIP_SCENE: &str = r#"
generator = "spaceship"
[limits]
min_len = 1
optimal_len = 10
max_len = 100
max_depth = 15
[volume]
grid = { min = [-5, -5, -2], max = [5, 5, 18], resolution = [20, 20, 40] }
[[volume.target]]
mesh = "tetra.obj"
"#;

/// A tetrahedron: four corners, four faces.
const TETRA: &str = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";

/// Writes the spaceship scene with the tetrahedron as its `cube` mesh when `replace` is
/// set.
fn ship_scene(dir: &Path, replace: bool) -> PathBuf {
    fs::write(dir.join("tetra.obj"), TETRA).unwrap();
    let mut text = SHIP_SCENE.to_owned();
    if replace {
        text += "[meshes]\ncube = \"tetra.obj\"\n";
    }
    let path = dir.join("ship.toml");
    fs::write(&path, text).unwrap();
    path
}

/// JSON lines a command printed.
fn json_lines(out: &str) -> Vec<serde_json::Value> {
    out.lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect()
}

#[test]
fn score_and_render_read_the_nested_form() {
    let dir = tempfile::tempdir().unwrap();
    let packed = sample("spaceship", "3", &dir.path().join("ships"));
    let nested = dir.path().join("nested.json");
    convert(&packed, &nested, None);
    let scene = ship_scene(dir.path(), false);
    let score =
        |genomes: &Path| json_lines(&ok(&["score", s(&scene), "--genomes", s(genomes), "--cpu"]));
    let from_nested = score(&nested);
    assert_eq!(from_nested.len(), 3);
    assert_eq!(from_nested, score(&packed));
    assert!(from_nested[0]["instances"].as_u64().unwrap() > 0);

    let hand = dir.path().join("hand.json");
    fs::write(&hand, HAND_SHIP).unwrap();
    let lines = score(&hand);
    assert_eq!(lines.len(), 1);
    assert_eq!(lines[0]["genes"], 4);
    assert_eq!(
        lines[0]["instances"],
        instances(&Genome::<Spaceship>::from_json(HAND_SHIP).unwrap()).len()
    );

    let previews = dir.path().join("previews");
    let out = ok(&[
        "render",
        s(&scene),
        "--genomes",
        s(&nested),
        "--out",
        s(&previews),
        "--width",
        "64",
        "--height",
        "48",
    ]);
    assert!(out.contains("wrote 3 shaded previews"), "{out}");
    let mut written: Vec<_> = fs::read_dir(&previews)
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .collect();
    written.sort();
    assert_eq!(written, ["model_0.png", "model_1.png", "model_2.png"]);
}

fn instances<G: Grammar>(genome: &Genome<G>) -> Vec<Instance> {
    let mut out = Vec::new();
    genome.derive_into(&mut out);
    out
}

/// The vertices and triangles of `instances` drawn with `meshes`.
fn expected_counts(instances: &[Instance], meshes: &BoundMeshes) -> (usize, usize) {
    instances.iter().fold((0, 0), |(v, f), i| {
        let mesh = &meshes[i.mesh];
        (v + mesh.vertex_count(), f + mesh.triangle_count())
    })
}

/// The `v` and `f` lines of an OBJ file.
fn obj_counts(path: &Path) -> (usize, usize) {
    let text = read(path);
    let count = |prefix: &str| text.lines().filter(|l| l.starts_with(prefix)).count();
    (count("v "), count("f "))
}

/// Reads `path` as binary glTF (the `gltf` crate validates it) and returns its vertices
/// and triangles: the sums of its primitives' position counts and index counts over three.
fn glb_counts(path: &Path) -> (usize, usize) {
    let glb = gltf::Gltf::from_slice(&fs::read(path).unwrap()).expect("valid binary glTF");
    let mut counts = (0, 0);
    for primitive in glb.meshes().flat_map(|m| m.primitives()) {
        counts.0 += primitive.get(&gltf::Semantic::Positions).unwrap().count();
        let indices = primitive.indices().unwrap().count();
        assert_eq!(indices % 3, 0);
        counts.1 += indices / 3;
    }
    counts
}

#[test]
fn export_writes_the_model_as_obj_or_glb() {
    let dir = tempfile::tempdir().unwrap();
    let packed = sample("spaceship", "3", &dir.path().join("ships"));
    let nested = dir.path().join("nested.json");
    convert(&packed, &nested, None);
    let genome = &GenomeSet::<Spaceship>::load(&nested).unwrap().genomes[2];
    let model = instances(genome);
    let meshes = generators::default_meshes().bind(Spaceship::GRAPH).unwrap();
    let expected = expected_counts(&model, &meshes);
    assert!(expected.0 > 0);

    let obj = dir.path().join("models/ship.obj");
    let out = ok(&[
        "export",
        "--generator",
        "spaceship",
        "--genome",
        s(&nested),
        "--index",
        "2",
        "--out",
        s(&obj),
    ]);
    let mtl = dir.path().join("models/ship.mtl");
    assert_eq!(
        out.trim(),
        format!(
            "wrote {} and {}: Spaceship genome 2 of `{}`, {} genes, {} instances",
            obj.display(),
            mtl.display(),
            nested.display(),
            genome.len(),
            model.len()
        )
    );
    assert_eq!(obj_counts(&obj), expected);
    assert!(read(&obj).contains("mtllib ship.mtl\n"));
    assert!(read(&mtl).contains("newmtl cube\n"));

    // The generator may be left to the genome file; a single genome exports alone.
    let glb = dir.path().join("ship.glb");
    ok(&[
        "export",
        "--genome",
        s(&packed),
        "--index",
        "2",
        "--out",
        s(&glb),
    ]);
    assert_eq!(glb_counts(&glb), expected);
    let hand = dir.path().join("hand.json");
    fs::write(&hand, HAND_SHIP).unwrap();
    let hand_obj = dir.path().join("hand.obj");
    ok(&["export", "--genome", s(&hand), "--out", s(&hand_obj)]);
    let hand_model = instances(&Genome::<Spaceship>::from_json(HAND_SHIP).unwrap());
    assert_eq!(obj_counts(&hand_obj), expected_counts(&hand_model, &meshes));
}

#[test]
fn export_draws_with_the_scene_meshes() {
    let dir = tempfile::tempdir().unwrap();
    let hand = dir.path().join("hand.json");
    fs::write(&hand, HAND_SHIP).unwrap();
    let model = instances(&Genome::<Spaceship>::from_json(HAND_SHIP).unwrap());
    let scene = ship_scene(dir.path(), true);
    let meshes = Scene::load(&scene)
        .unwrap()
        .meshes
        .bind(Spaceship::GRAPH)
        .unwrap();
    let expected = expected_counts(&model, &meshes);
    let cubes = generators::default_meshes().bind(Spaceship::GRAPH).unwrap();
    assert_ne!(
        expected,
        expected_counts(&model, &cubes),
        "the scene's meshes differ from the generator's own"
    );

    let obj = dir.path().join("ship.obj");
    ok(&[
        "export",
        "--scene",
        s(&scene),
        "--genome",
        s(&hand),
        "--out",
        s(&obj),
    ]);
    assert_eq!(obj_counts(&obj), expected);
    let glb = dir.path().join("ship.glb");
    ok(&[
        "export",
        "--scene",
        s(&scene),
        "--generator",
        "spaceship",
        "--genome",
        s(&hand),
        "--out",
        s(&glb),
    ]);
    assert_eq!(glb_counts(&glb), expected);
}

#[test]
fn export_explains_its_mistakes() {
    let dir = tempfile::tempdir().unwrap();
    let hand = dir.path().join("hand.json");
    fs::write(&hand, HAND_SHIP).unwrap();
    let scene = ship_scene(dir.path(), false);
    let out = dir.path().join("model.obj");

    let err = fails(&[
        "export",
        "--genome",
        s(&hand),
        "--out",
        s(&dir.path().join("model.stl")),
    ]);
    assert_eq!(
        err.trim(),
        format!(
            "error: --out `{}`: the format follows the extension, which must be .obj or .glb",
            dir.path().join("model.stl").display()
        )
    );
    let err = fails(&[
        "export",
        "--generator",
        "rocket",
        "--genome",
        s(&hand),
        "--out",
        s(&out),
    ]);
    assert!(
        err.contains(&format!(
            "error: unknown generator `rocket`; the generators are {}",
            published_names()
        )),
        "{err}"
    );
    let err = fails(&[
        "export",
        "--scene",
        s(&scene),
        "--generator",
        "city",
        "--genome",
        s(&hand),
        "--out",
        s(&out),
    ]);
    assert_eq!(
        err.trim(),
        format!(
            "error: --generator city disagrees with the scene `{}`, whose generator is spaceship",
            scene.display()
        )
    );
    let err = fails(&[
        "export",
        "--generator",
        "city",
        "--genome",
        s(&hand),
        "--out",
        s(&out),
    ]);
    assert_eq!(
        err.trim(),
        format!(
            "error: cannot load genomes `{}`: the genome is of generator `Spaceship`, but is \
             being read as `city` (also written `City`)",
            hand.display()
        )
    );
    let missing = dir.path().join("missing.json");
    let err = fails(&["export", "--genome", s(&missing), "--out", s(&out)]);
    assert!(
        err.starts_with(&format!(
            "error: cannot read genomes `{}`: No such file",
            missing.display()
        )),
        "{err}"
    );
    let err = fails(&[
        "export",
        "--genome",
        s(&hand),
        "--index",
        "1",
        "--out",
        s(&out),
    ]);
    assert_eq!(
        err.trim(),
        format!(
            "error: `{}` holds 1 genomes; --index must be below 1",
            hand.display()
        )
    );
    assert!(!out.exists());
}
