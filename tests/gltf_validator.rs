//! Every exported `.glb` passes the Khronos glTF validator with no errors: an empty
//! model, cubes (one of them mirrored), a box next to generated walls, roof and windows
//! placed as facets, and random roofed buildings from the `generators` crate. Each file's
//! materials are named after exactly the meshes it uses. A broken file must be reported
//! with errors, so that the check can fail.
//!
//! The validator is the npm package `gltf-validator`, run with `node`:
//! `scripts/gltf-validator.sh` installs its pinned version into the target folder
//! (`target/gltf-validator`), where the test finds it; `SHAPEGEN_GLTF_VALIDATOR` names
//! the package's folder instead. Under its own harness so that a missing validator
//! shows: without it the tests are reported as ignored, after a line saying how to
//! install it, unless `SHAPEGEN_REQUIRE_GLTF_VALIDATOR=1` (as in CI, which installs it),
//! where they fail instead.

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use std::process::{Command, ExitCode};

use generators::building::{self, roofed::RoofedBuilding};
use glam::{Affine3A, Quat, Vec3, vec2, vec3};
use libtest_mimic::{Arguments, Failed, Trial};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use shapegen::export::{Model, Palette, glb_bytes};
use shapegen::geometry::{Mesh, MeshId, MeshLibrary, Polygon, RoofShape};
use shapegen::prelude::*;
use shapegen::{BoundMeshes, CUBE, Instance, Scope};

/// The node script that runs the validator on files and prints the reports as JSON.
const SCRIPT: &str = "tests/support/gltf-validate.js";

/// A test that runs the validator: its name and its body, which panics when it fails.
type ValidatorTest = (&'static str, fn(&Validator));

const TESTS: &[ValidatorTest] = &[
    ("an_empty_model_is_valid", an_empty_model_is_valid),
    ("cubes_are_valid", cubes_are_valid),
    (
        "facets_are_valid_with_a_material_per_facet_mesh",
        facets_are_valid_with_a_material_per_facet_mesh,
    ),
    (
        "non_finite_instances_are_left_out",
        non_finite_instances_are_left_out,
    ),
    (
        "random_roofed_buildings_are_valid",
        random_roofed_buildings_are_valid,
    ),
    ("broken_files_are_reported", broken_files_are_reported),
];

/// `node` and the validator's package folder.
struct Validator {
    node: PathBuf,
    package: PathBuf,
}

/// One file's report.
#[derive(Debug)]
struct Report {
    file: String,
    errors: u64,
    warnings: u64,
    infos: u64,
    hints: u64,
    /// The issues, each as `SEVERITY CODE at POINTER: MESSAGE`.
    messages: Vec<String>,
    /// Why the validator could not read the file at all, where it could not.
    rejected: Option<String>,
}

/// `node` (or `nodejs`) on the `PATH`.
fn node() -> Option<PathBuf> {
    let path = std::env::var_os("PATH")?;
    std::env::split_paths(&path)
        .flat_map(|dir| ["node", "nodejs"].map(|name| dir.join(name)))
        .find(|p| p.is_file())
}

/// The validator's package folder: `SHAPEGEN_GLTF_VALIDATOR`, else
/// `gltf-validator/node_modules/gltf-validator` in the target folder this test was built
/// in, or in the checkout's `target`, as `scripts/gltf-validator.sh` installs it.
fn package() -> Option<PathBuf> {
    if let Some(dir) = std::env::var_os("SHAPEGEN_GLTF_VALIDATOR") {
        let dir = PathBuf::from(dir);
        return dir.join("package.json").is_file().then_some(dir);
    }
    let installed = Path::new("gltf-validator/node_modules/gltf-validator");
    // This executable is TARGET/PROFILE/deps/NAME.
    let built_in = std::env::current_exe()
        .ok()
        .and_then(|exe| Some(exe.parent()?.parent()?.parent()?.to_owned()));
    let checkout = Path::new(env!("CARGO_MANIFEST_DIR")).join("target");
    built_in
        .into_iter()
        .chain([checkout])
        .map(|target| target.join(installed))
        .find(|dir| dir.join("package.json").is_file())
}

/// The validator, or why there is none.
fn validator() -> Result<Validator, String> {
    let node = node().ok_or("no node on the PATH (apt-get install nodejs npm)")?;
    let package = package().ok_or(
        "no gltf-validator package (scripts/gltf-validator.sh installs it into \
         target/gltf-validator; or set SHAPEGEN_GLTF_VALIDATOR to the package's folder)",
    )?;
    Ok(Validator { node, package })
}

fn main() -> ExitCode {
    let args = Arguments::from_args();
    let required = std::env::var("SHAPEGEN_REQUIRE_GLTF_VALIDATOR").as_deref() == Ok("1");
    let validator = validator();
    match &validator {
        Ok(v) => eprintln!(
            "glTF validator tests run with {} on {}",
            v.node.display(),
            v.package.display()
        ),
        Err(why) if required => {
            eprintln!("{why}; SHAPEGEN_REQUIRE_GLTF_VALIDATOR=1, so the glTF validator tests fail")
        }
        Err(why) => eprintln!("{why}; the glTF validator tests are ignored"),
    }
    let validator = validator.ok().map(std::sync::Arc::new);
    let trials = TESTS
        .iter()
        .map(|&(name, test)| match validator.clone() {
            Some(v) => Trial::test(name, move || {
                test(&v);
                Ok(())
            }),
            None => Trial::test(name, || Err(Failed::from("no glTF validator found")))
                .with_ignored_flag(!required),
        })
        .collect();
    libtest_mimic::run(&args, trials).exit_code()
}

impl Validator {
    /// Validates each named file, written into a fresh folder, and prints each report's
    /// counts and issues.
    fn validate(&self, files: &[(&str, &[u8])]) -> Vec<Report> {
        let dir = tempfile::tempdir().unwrap();
        let paths: Vec<PathBuf> = files
            .iter()
            .map(|(name, bytes)| {
                let path = dir.path().join(format!("{name}.glb"));
                std::fs::write(&path, bytes).unwrap();
                path
            })
            .collect();
        let output = Command::new(&self.node)
            .arg(Path::new(env!("CARGO_MANIFEST_DIR")).join(SCRIPT))
            .arg(&self.package)
            .args(&paths)
            .output()
            .expect("node runs");
        assert!(
            output.status.success(),
            "the validator script failed: {}",
            String::from_utf8_lossy(&output.stderr)
        );
        let out: serde_json::Value =
            serde_json::from_slice(&output.stdout).expect("the script prints JSON");
        let version = out["version"].as_str().unwrap_or("?");
        let reports: Vec<Report> = out["reports"]
            .as_array()
            .expect("reports")
            .iter()
            .map(report)
            .collect();
        assert_eq!(reports.len(), files.len());
        for r in &reports {
            match &r.rejected {
                Some(why) => println!("gltf-validator {version}: {}: rejected: {why}", r.file),
                None => println!(
                    "gltf-validator {version}: {}: {} errors, {} warnings, {} infos, {} hints",
                    r.file, r.errors, r.warnings, r.infos, r.hints
                ),
            }
            for m in &r.messages {
                println!("    {m}");
            }
        }
        reports
    }

    /// Validates each named file, which must have no errors, no warnings, and its
    /// materials, meshes and nodes named after exactly the meshes its instances use.
    fn assert_valid(&self, files: &[(&str, &[Instance], &BoundMeshes)]) {
        let glbs: Vec<Vec<u8>> = files
            .iter()
            .map(|(_, instances, meshes)| {
                glb_bytes(Model::new(instances, meshes, &Palette::new())).unwrap()
            })
            .collect();
        let named: Vec<(&str, &[u8])> = files
            .iter()
            .zip(&glbs)
            .map(|((name, ..), glb)| (*name, glb.as_slice()))
            .collect();
        for (r, ((name, instances, meshes), glb)) in
            self.validate(&named).iter().zip(files.iter().zip(&glbs))
        {
            assert_eq!(r.rejected, None, "{name}");
            assert_eq!(r.errors, 0, "{name}: {:#?}", r.messages);
            assert_eq!(r.warnings, 0, "{name}: {:#?}", r.messages);
            assert_names(name, glb, instances, meshes);
        }
    }
}

fn report(value: &serde_json::Value) -> Report {
    let issues = &value["report"]["issues"];
    let count = |key: &str| issues[key].as_u64().unwrap_or(0);
    let severity = ["error", "warning", "info", "hint"];
    let messages = issues["messages"]
        .as_array()
        .map(Vec::as_slice)
        .unwrap_or_default()
        .iter()
        .map(|m| {
            let level = m["severity"].as_u64().unwrap_or(0) as usize;
            format!(
                "{} {} at {}: {}",
                severity.get(level).unwrap_or(&"?"),
                m["code"].as_str().unwrap_or("?"),
                match (m["pointer"].as_str(), m["offset"].as_u64()) {
                    (Some(""), _) => "/".to_owned(),
                    (Some(pointer), _) => pointer.to_owned(),
                    (None, Some(offset)) => format!("byte {offset}"),
                    (None, None) => "-".to_owned(),
                },
                m["message"].as_str().unwrap_or("?"),
            )
        })
        .collect();
    Report {
        file: value["file"].as_str().unwrap_or("?").to_owned(),
        errors: count("numErrors"),
        warnings: count("numWarnings"),
        infos: count("numInfos"),
        hints: count("numHints"),
        messages,
        rejected: value["rejected"].as_str().map(str::to_owned),
    }
}

/// The names of the meshes `instances` use, in id order, as the exporter names them.
fn used_names(instances: &[Instance], meshes: &BoundMeshes) -> Vec<String> {
    let used: BTreeSet<MeshId> = instances.iter().map(|i| i.mesh).collect();
    used.into_iter()
        .map(|id| meshes.name(id).unwrap().to_owned())
        .collect()
}

/// The glb's materials, meshes and nodes are named after exactly the meshes used.
fn assert_names(name: &str, glb: &[u8], instances: &[Instance], meshes: &BoundMeshes) {
    let gltf = gltf::Gltf::from_slice(glb).unwrap_or_else(|e| panic!("{name}: {e}"));
    let expected = used_names(instances, meshes);
    let names = |it: &mut dyn Iterator<Item = Option<&str>>| -> Vec<String> {
        it.map(|n| n.expect("named").to_owned()).collect()
    };
    let materials = names(&mut gltf.materials().map(|m| m.name()));
    assert_eq!(materials, expected, "{name}: materials");
    assert_eq!(
        names(&mut gltf.meshes().map(|m| m.name())),
        expected,
        "{name}: meshes"
    );
    assert_eq!(
        names(&mut gltf.nodes().map(|n| n.name())),
        expected,
        "{name}: nodes"
    );
    // Each mesh's one primitive uses its own material.
    for mesh in gltf.meshes() {
        let primitive = mesh.primitives().next().expect("a primitive");
        assert_eq!(primitive.material().name(), mesh.name(), "{name}");
    }
}

/// The built-in cube alone.
fn cube_meshes() -> BoundMeshes {
    MeshLibrary::new().bind_names("Cubes", &["cube"]).unwrap()
}

fn an_empty_model_is_valid(v: &Validator) {
    let meshes = cube_meshes();
    v.assert_valid(&[("empty", &[], &meshes)]);
}

fn cubes_are_valid(v: &Validator) {
    let meshes = cube_meshes();
    let at = |transform| Instance {
        transform,
        mesh: CUBE,
    };
    let one = [at(Affine3A::IDENTITY)];
    let mirror = Affine3A::from_translation(vec3(3.0, 0.0, 0.0))
        * Affine3A::from_scale(vec3(-1.0, 1.0, 2.0));
    assert!(mirror.matrix3.determinant() < 0.0);
    let several = [
        at(Affine3A::from_translation(vec3(1.0, 2.0, 3.0))),
        at(Affine3A::from_scale_rotation_translation(
            vec3(2.0, 1.0, 0.5),
            Quat::from_rotation_y(1.0),
            vec3(-4.0, 0.5, 1.0),
        )),
        at(mirror),
    ];
    let mirrored = [at(mirror)];
    v.assert_valid(&[
        ("cube", &one, &meshes),
        ("cubes", &several, &meshes),
        ("mirrored_cube", &mirrored, &meshes),
    ]);
}

fn facets_are_valid_with_a_material_per_facet_mesh(v: &Validator) {
    let mut library = MeshLibrary::new();
    for name in ["wall", "roof", "window"] {
        library.register(name, Mesh::facet()).unwrap();
    }
    let meshes = library
        .bind_names("Facets", &["cube", "wall", "roof", "window"])
        .unwrap();
    let [wall, roof, window] = [1, 2, 3].map(MeshId);
    let l = Polygon::new([
        vec2(-4.0, -4.0),
        vec2(4.0, -4.0),
        vec2(4.0, 0.0),
        vec2(0.0, 0.0),
        vec2(0.0, 4.0),
        vec2(-4.0, 4.0),
    ])
    .unwrap();
    let house = Scope::UNIT.with_size(vec3(8.0, 6.0, 8.0));
    let mut model = vec![Instance {
        transform: Affine3A::from_scale_rotation_translation(
            vec3(3.0, 2.0, 3.0),
            Quat::IDENTITY,
            vec3(8.0, 1.0, 0.0),
        ),
        mesh: CUBE,
    }];
    assert_eq!(house.extrude_polygon(&l, 6.0, wall, &mut model), 20);
    house
        .roof_polygon(&l, RoofShape::Hip { pitch: 0.5 }, 0.3, roof, &mut model)
        .unwrap();
    // Windows: thin panes facing +z on the wall at z = 4 (the footprint's y = -4).
    let pane = Polygon::new([
        vec2(-0.5, -0.6),
        vec2(0.5, -0.6),
        vec2(0.5, 0.6),
        vec2(-0.5, 0.6),
    ])
    .unwrap()
    .extrude(0.05);
    for x in [-3.0, -1.0, 1.0, 3.0] {
        let at = Scope::UNIT.translate(vec3(x, 0.0, 4.0));
        assert!(at.surface(&pane, window, &mut model) > 0);
    }
    let walls_only: Vec<Instance> = model.iter().filter(|i| i.mesh == wall).cloned().collect();
    assert_eq!(
        used_names(&model, &meshes),
        ["cube", "wall", "roof", "window"]
    );
    v.assert_valid(&[("facets", &model, &meshes), ("walls", &walls_only, &meshes)]);
}

fn non_finite_instances_are_left_out(v: &Validator) {
    let mut library = MeshLibrary::new();
    library.register("wall", Mesh::facet()).unwrap();
    let meshes = library.bind_names("Broken", &["cube", "wall"]).unwrap();
    let wall = MeshId(1);
    let at = |transform, mesh| Instance { transform, mesh };
    let nan = Affine3A::from_translation(vec3(f32::NAN, 0.0, 0.0));
    // Finite, but the corners overflow to infinity.
    let huge = Affine3A::from_scale_rotation_translation(
        Vec3::splat(f32::MAX),
        Quat::IDENTITY,
        Vec3::splat(f32::MAX),
    );
    let model = [
        at(Affine3A::IDENTITY, CUBE),
        at(nan, CUBE),
        at(huge, CUBE),
        at(nan, wall),
        at(huge, wall),
    ];
    let glb = glb_bytes(Model::new(&model, &meshes, &Palette::new())).unwrap();
    let reports = v.validate(&[("non_finite", &glb)]);
    assert_eq!(
        (reports[0].errors, reports[0].warnings),
        (0, 0),
        "{:#?}",
        reports[0].messages
    );
    // The finite cube alone is left, and the wall, with no finite instance, not at all.
    let cube = glb_bytes(Model::new(&model[..1], &meshes, &Palette::new())).unwrap();
    assert!(glb == cube, "more than the finite cube exported");
    assert_names("non_finite", &glb, &model[..1], &meshes);
}

fn random_roofed_buildings_are_valid(v: &Validator) {
    let meshes = generators::default_meshes()
        .bind(RoofedBuilding::GRAPH)
        .unwrap();
    let mut ops = Operators::<RoofedBuilding>::new(building::LIMITS).unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(11);
    let mut roofs = BTreeSet::new();
    let buildings: Vec<(String, Vec<Instance>)> = (0..8)
        .map(|k| {
            let mut instances = Vec::new();
            ops.random(60, &mut rng).derive_into(&mut instances);
            assert!(!instances.is_empty());
            roofs.extend(instances.iter().map(|i| i.mesh).filter(|&m| m != CUBE));
            (format!("building_{k}"), instances)
        })
        .collect();
    assert!(roofs.len() >= 2, "the buildings use roof meshes: {roofs:?}");
    let files: Vec<(&str, &[Instance], &BoundMeshes)> = buildings
        .iter()
        .map(|(name, instances)| (name.as_str(), instances.as_slice(), &meshes))
        .collect();
    v.assert_valid(&files);
}

fn broken_files_are_reported(v: &Validator) {
    let meshes = cube_meshes();
    let cube = [Instance {
        transform: Affine3A::IDENTITY,
        mesh: CUBE,
    }];
    let glb = glb_bytes(Model::new(&cube, &meshes, &Palette::new())).unwrap();
    let truncated = &glb[..glb.len() / 2];
    // The JSON chunk starts at byte 20 with `{`: make it no JSON at all.
    let mut corrupted = glb.clone();
    assert_eq!(corrupted[20], b'{');
    corrupted[20..24].copy_from_slice(b"!!!!");
    // Well-formed JSON that misstates the data: the positions' minimum.
    let mut json: serde_json::Value = serde_json::from_slice(json_chunk(&glb)).unwrap();
    json["accessors"][0]["min"] = serde_json::json!([-9.0, -9.0, -9.0]);
    let wrong_min = with_json(&glb, &serde_json::to_vec(&json).unwrap());
    let reports = v.validate(&[
        ("truncated", truncated),
        ("corrupted", &corrupted),
        ("wrong_min", &wrong_min),
    ]);
    for r in &reports {
        assert!(
            r.rejected.is_some() || r.errors > 0,
            "{}: the validator found no error in a broken file",
            r.file
        );
    }
    assert!(
        reports[2]
            .messages
            .iter()
            .any(|m| m.contains("ACCESSOR_MIN_MISMATCH")),
        "{:#?}",
        reports[2].messages
    );
}

/// The JSON chunk of a GLB file, padding included.
fn json_chunk(glb: &[u8]) -> &[u8] {
    let length = u32::from_le_bytes(glb[12..16].try_into().unwrap()) as usize;
    assert_eq!(&glb[16..20], b"JSON");
    &glb[20..20 + length]
}

/// `glb` with its JSON chunk replaced by `json`, padded with spaces, the header's length
/// updated.
fn with_json(glb: &[u8], json: &[u8]) -> Vec<u8> {
    let rest = &glb[20 + json_chunk(glb).len()..];
    let mut json = json.to_vec();
    json.resize(json.len().next_multiple_of(4), b' ');
    let mut out = glb[..8].to_vec();
    let total = 12 + 8 + json.len() + rest.len();
    out.extend_from_slice(&(total as u32).to_le_bytes());
    out.extend_from_slice(&(json.len() as u32).to_le_bytes());
    out.extend_from_slice(b"JSON");
    out.extend_from_slice(&json);
    out.extend_from_slice(rest);
    out
}
