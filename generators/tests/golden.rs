//! The published generators against derivations made by the original implementation
//! itself (`golden/` beside this file, see its README): every genome there (random ones, and
//! ones made by the original's crossover and mutations) is built here node for node,
//! derived, and every instance's transform compared with the matrix the original
//! emitted, to 1e-4 of the matrix's largest entry.
//!
//! The original's instance order follows its work queue and child insertion order, which
//! a packed genome does not keep, so instances are matched as a set: each of the
//! original's instances, mesh by mesh, is paired with one of ours within the tolerance.
//! The matrices hold the scope frame times the scope size (or the frame alone for the
//! tree's unscaled leaves); the mesh normalisation the original applies at load time is
//! not part of them, nor of our transforms.

use std::path::Path;

use generators::{City, Spaceship, Tree, city, spaceship, tree};
use glam::{Affine3A, Vec2, Vec3};
use serde_json::Value;
use shapegen_runtime::derive::NodeParams;
use shapegen_runtime::genome::Genome;
use shapegen_runtime::{Grammar, Instance};

/// Relative tolerance on matrix entries.
const TOLERANCE: f32 = 1e-4;

/// The golden file `NAME.json.gz` beside this test, parsed; a missing or unreadable file
/// fails the test, naming it.
fn load(name: &str) -> Value {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("tests/golden/{name}.json.gz"));
    let file = std::fs::File::open(&path).unwrap_or_else(|e| {
        panic!(
            "the original's derivations `{}` are missing ({e}); they are part of the repository",
            path.display()
        )
    });
    serde_json::from_reader(flate2::read::GzDecoder::new(std::io::BufReader::new(file)))
        .unwrap_or_else(|e| panic!("`{}` is not gzip-compressed JSON: {e}", path.display()))
}

fn float(v: &Value) -> f32 {
    v.as_f64().expect("a number") as f32
}

fn vec3(v: &Value) -> Vec3 {
    let a = v.as_array().expect("an array of 3 numbers");
    Vec3::new(float(&a[0]), float(&a[1]), float(&a[2]))
}

fn vec2(v: &Value) -> Vec2 {
    let a = v.as_array().expect("an array of 2 numbers");
    Vec2::new(float(&a[0]), float(&a[1]))
}

fn param<'a>(node: &'a Value, name: &str) -> &'a Value {
    &node["params"][name]
}

fn children(node: &Value) -> &[Value] {
    node["children"].as_array().expect("children")
}

fn symbol(node: &Value) -> &str {
    node["symbol"].as_str().expect("a symbol name")
}

/// Builds one of the original's trees into a genome: `child` attaches one child node of
/// the original under our gene at `parent`.
fn build<G: Grammar, R: NodeParams>(
    tree: &Value,
    root: R,
    child: impl Fn(&mut Genome<G>, u32, &Value) -> u32 + Copy,
) -> Genome<G> {
    fn walk<G: Grammar>(
        genome: &mut Genome<G>,
        pos: u32,
        node: &Value,
        child: impl Fn(&mut Genome<G>, u32, &Value) -> u32 + Copy,
    ) {
        for c in children(node) {
            let at = child(genome, pos, c);
            walk(genome, at, c, child);
        }
    }
    let mut genome = Genome::<G>::with_root(root).expect("the root builds");
    walk(&mut genome, 0, tree, child);
    genome
}

fn spaceship_child(g: &mut Genome<Spaceship>, parent: u32, node: &Value) -> u32 {
    let size = vec3(param(node, "size"));
    let shift = || float(param(node, "forward/backward movement"));
    let attached = match symbol(node) {
        "B" => {
            let slot = if parent == 0 { "body" } else { "next" };
            g.attach(parent, slot, spaceship::Body { size })
        }
        "T" => g.attach(parent, "top", spaceship::Top { size }),
        "t" => g.attach(parent, "next", spaceship::TopNext { size }),
        "W" => g.attach(
            parent,
            "wing",
            spaceship::Wing {
                size,
                shift: shift(),
            },
        ),
        "w" => g.attach(
            parent,
            "next",
            spaceship::WingNext {
                size,
                shift: shift(),
            },
        ),
        other => panic!("unknown spaceship symbol {other}"),
    };
    attached.unwrap_or_else(|e| panic!("{}: {e}", symbol(node)))
}

/// The original stores branch angles in degrees and turns them into radians as
/// `deg * pi / 180` in `f32`.
fn radians(degrees: f32) -> f32 {
    degrees * std::f32::consts::PI / 180.0
}

fn tree_child(g: &mut Genome<Tree>, parent: u32, node: &Value) -> u32 {
    let attached = match symbol(node) {
        "T" => g.attach(
            parent,
            "trunk",
            tree::Trunk {
                size: vec3(param(node, "size")),
            },
        ),
        branch @ ("b" | "n" | "m") => {
            let size = vec3(param(node, "branch_size"));
            let yaw = radians(float(param(node, "rotate_y")));
            let tilt = radians(float(param(node, "branch_rotate_z")));
            let twist = radians(float(param(node, "branch_rotate_y")));
            match branch {
                "b" => g.attach(
                    parent,
                    "b1",
                    tree::B1 {
                        size,
                        yaw,
                        tilt,
                        twist,
                    },
                ),
                "n" => g.attach(
                    parent,
                    "b2",
                    tree::B2 {
                        size,
                        yaw,
                        tilt,
                        twist,
                    },
                ),
                _ => g.attach(
                    parent,
                    "b3",
                    tree::B3 {
                        size,
                        yaw,
                        tilt,
                        twist,
                    },
                ),
            }
        }
        other => panic!("unknown tree symbol {other}"),
    };
    attached.unwrap_or_else(|e| panic!("{}: {e}", symbol(node)))
}

/// The original's building stores its sizes times 10 and scales them by 0.1 when
/// deriving; ours stores the scaled values.
fn city_child(g: &mut Genome<City>, parent: u32, node: &Value) -> u32 {
    let name = symbol(node);
    let attached = if let Some(lot) = name.strip_prefix("Lot_") {
        let (i, j) = lot.split_once('_').expect("Lot_i_j");
        let k = i.parse::<u32>().unwrap() + 10 * j.parse::<u32>().unwrap();
        assert_eq!(node["slot"].as_u64(), Some(k as u64), "{name}'s slot");
        g.attach_at(parent, "lots", k, city::Lot {})
    } else {
        assert_eq!(name, "Builing");
        g.attach(
            parent,
            "building",
            city::Building {
                footprint: 0.1 * vec2(param(node, "size")),
                height: 0.1 * float(param(node, "height")),
                floor_height: 0.1 * float(param(node, "floorheight")),
                rotation: float(param(node, "rotation")),
            },
        )
    };
    attached.unwrap_or_else(|e| panic!("{name}: {e}"))
}

/// The original's matrix of an instance, rows `[m11 m12 m13 m14]`, ... as an affine map.
fn matrix(instance: &Value) -> Affine3A {
    let rows = instance["matrix"].as_array().expect("matrix rows");
    let m = |r: usize, c: usize| float(&rows[r][c]);
    Affine3A::from_cols_array(&[
        m(0, 0),
        m(1, 0),
        m(2, 0),
        m(0, 1),
        m(1, 1),
        m(2, 1),
        m(0, 2),
        m(1, 2),
        m(2, 2),
        m(0, 3),
        m(1, 3),
        m(2, 3),
    ])
}

/// Whether `ours` equals `theirs` entry by entry within [`TOLERANCE`] of `theirs`'
/// largest entry.
fn close(ours: &Affine3A, theirs: &Affine3A) -> bool {
    let (a, b) = (ours.to_cols_array(), theirs.to_cols_array());
    let scale = b.iter().fold(1e-6_f32, |m, x| m.max(x.abs()));
    a.iter()
        .zip(&b)
        .all(|(x, y)| (x - y).abs() <= TOLERANCE * scale)
}

/// The mesh names of the golden file's shapes: the stems of their files.
fn expected_shapes(golden: &Value) -> Vec<String> {
    golden["shapes"]
        .as_array()
        .expect("shapes")
        .iter()
        .map(|s| {
            let file = Path::new(s["file"].as_str().expect("a shape file"));
            file.file_stem().unwrap().to_string_lossy().into_owned()
        })
        .collect()
}

/// Derives `genome` and checks its instances against the original's `expected`, mesh by
/// mesh as sets. Returns how many instances were compared.
fn check_instances<G: Grammar>(
    id: &str,
    genome: &Genome<G>,
    expected: &Value,
    golden: &Value,
) -> usize {
    let mut ours: Vec<Instance> = Vec::new();
    genome.derive_into(&mut ours);
    let theirs = expected["instances"].as_array().expect("instances");
    assert_eq!(
        ours.len(),
        theirs.len(),
        "{id}: {} instances derived, the original emitted {}",
        ours.len(),
        theirs.len()
    );
    // The original's shapes are its mesh files; ours are meshes by name.
    let mesh_of_shape: Vec<u32> = expected_shapes(golden)
        .iter()
        .map(|name| {
            G::GRAPH
                .meshes
                .iter()
                .position(|m| m == name)
                .unwrap_or_else(|| panic!("{id}: the original's mesh {name} is not one of ours"))
                as u32
        })
        .collect();
    let mut used = vec![false; ours.len()];
    for (n, t) in theirs.iter().enumerate() {
        let shape = mesh_of_shape[t["shape"].as_u64().expect("shape") as usize];
        let m = matrix(t);
        let found = (0..ours.len())
            .find(|&i| !used[i] && ours[i].mesh.0 == shape && close(&ours[i].transform, &m));
        let Some(i) = found else {
            let nearest = ours.iter().filter(|o| o.mesh.0 == shape).min_by(|a, b| {
                let d = |o: &Instance| {
                    (Vec3::from(o.transform.translation) - Vec3::from(m.translation)).length()
                };
                d(a).total_cmp(&d(b))
            });
            panic!(
                "{id}: the original's instance {n} (mesh {shape}) {m:?} has no match; \
                 the nearest of ours is {nearest:?}"
            );
        };
        used[i] = true;
    }
    theirs.len()
}

/// Checks every genome of `generator`'s golden file; `child` builds one node.
fn check_all<G: Grammar, R: NodeParams>(
    generator: &str,
    root: R,
    child: impl Fn(&mut Genome<G>, u32, &Value) -> u32 + Copy,
) {
    let golden = load(generator);
    let genomes = golden["genomes"].as_array().expect("genomes");
    assert_eq!(genomes.len(), 45);
    let mut compared = 0;
    for g in genomes {
        let id = g["id"].as_str().expect("id");
        let genome = build(&g["tree"], root, child);
        assert_eq!(
            genome.len() as u64,
            g["length"].as_u64().unwrap(),
            "{id}: genes"
        );
        genome
            .validate()
            .unwrap_or_else(|e| panic!("{id}: invalid genome: {e}"));
        compared += check_instances(id, &genome, g, &golden);
    }
    let expected: u64 = genomes
        .iter()
        .map(|g| g["instance_count"].as_u64().unwrap())
        .sum();
    assert_eq!(compared as u64, expected);
}

#[test]
fn spaceship_derives_as_the_original() {
    check_all::<Spaceship, _>("spaceship", spaceship::Start {}, spaceship_child);
}

#[test]
fn tree_derives_as_the_original() {
    check_all::<Tree, _>("tree", tree::Start {}, tree_child);
}

#[test]
fn city_derives_as_the_original() {
    check_all::<City, _>("city", city::Start {}, city_child);
}

/// Every generator mesh of the paper's scenes, normalized at load time as the original
/// does, has the original's bounding box after normalization (`meshes.json`).
#[test]
fn generator_meshes_are_normalized_as_the_original() {
    let meshes = load("meshes");
    let scenes = Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/paper");
    let mut checked = 0;
    for shapes in meshes["generators"]
        .as_object()
        .expect("generators")
        .values()
    {
        for shape in shapes.as_array().expect("shapes") {
            let file = scenes.join(shape["file"].as_str().expect("file"));
            let mesh = shapegen_runtime::Mesh::from_obj_normalized(&file)
                .unwrap_or_else(|e| panic!("{e}"));
            let (lo, hi) = mesh.bounds().expect("vertices");
            let after = &shape["bbox_after"];
            for (ours, theirs) in [(lo, &after["min"]), (hi, &after["max"])] {
                let theirs = vec3(theirs);
                assert!(
                    ours.abs_diff_eq(theirs, 1e-6),
                    "{}: {ours} against the original's {theirs}",
                    file.display()
                );
            }
            checked += 1;
        }
    }
    assert_eq!(checked, 5);
}
