//! Fits a published generator to your own target: a mesh (`.obj`, `.stl`, `.ply`,
//! `.gltf`, `.glb`) as a volume to fill, or a picture (`.png`) as a silhouette to
//! match. The target is placed where the generator builds (a mesh is scaled and moved so
//! that its bounding box matches that of the generator's typical model; a picture is seen
//! by a camera that frames such a model from the front), a scene is written for it, and
//! the hybrid method searches it with polishing of the continuous parameters. The output
//! folder gets the scene, the target as placed, the best model (`best.obj`, `best.glb`,
//! `best.genome.json`), its measures (`metrics.json`) and `compare.png`: the target beside
//! the best model.
//!
//! ```sh
//! cargo run --release --example fit -- scan.stl                        # spaceship, 30 s
//! cargo run --release --example fit -- sketch.png --generator tree --seconds 60
//! cargo run --release --example fit -- part.glb --winding --out out/part
//! ```
//!
//! Options: `--generator NAME` (spaceship for meshes, tree for pictures by default),
//! `--seconds N` (30), `--seed N` (1), `--out DIR` (`out/fit`), `--winding` (fill an
//! open or messy mesh by winding number instead of parity).

use std::path::PathBuf;
use std::time::Duration;

use anyhow::{Context, bail};
use generators::{GeneratorVisitor, Published};
use glam::{Affine3A, Vec3};
use image::{GenericImageView, RgbImage};
use rand::SeedableRng;
use shapegen::export::{Model, Palette, Preview, save_glb, save_obj};
use shapegen::genome::Limits;
use shapegen::geometry::MeshFormat;
use shapegen::ops::Operators;
use shapegen::optimize::{
    Control, GaSettings, Hybrid, HybridSettings, Optimizer, Settings, Snapshot,
};
use shapegen::scene::{BackendChoice, Metrics, Scene, SceneEvaluator, SceneScorer, ScorerGoal};
use shapegen::score::objective::Surface;
use shapegen::{Grammar, Instance, Mesh, MeshLibrary};

/// Random models of the generator whose bounds make its typical model.
const SAMPLES: usize = 200;
/// Voxels along the longest side of a volume target's grid.
const GRID_CELLS: f32 = 64.0;
/// The longest side of a picture target, in pixels.
const IMAGE_SIDE: u32 = 400;

/// What the command line asks for.
#[derive(Debug)]
struct Options {
    target: PathBuf,
    generator: String,
    seconds: u64,
    seed: u64,
    out: PathBuf,
    winding: bool,
}

impl Options {
    fn parse(args: impl IntoIterator<Item = String>) -> anyhow::Result<Options> {
        let mut args = args.into_iter();
        let (mut target, mut generator, mut seconds, mut seed, mut out, mut winding) =
            (None, None, 30, 1, PathBuf::from("out/fit"), false);
        while let Some(arg) = args.next() {
            let mut value =
                |name: &str| args.next().with_context(|| format!("{name} needs a value"));
            match arg.as_str() {
                "--generator" => generator = Some(value("--generator")?),
                "--seconds" => {
                    seconds = value("--seconds")?
                        .parse()
                        .context("--seconds takes whole seconds")?
                }
                "--seed" => {
                    seed = value("--seed")?
                        .parse()
                        .context("--seed takes a whole number")?
                }
                "--out" => out = value("--out")?.into(),
                "--winding" => winding = true,
                flag if flag.starts_with("--") => bail!(
                    "unknown option `{flag}`; the options are --generator, --seconds, --seed, --out and --winding"
                ),
                path => target = Some(PathBuf::from(path)),
            }
        }
        let target = target
            .context("give a target: a mesh (.obj, .stl, .ply, .gltf, .glb) or a picture (.png)")?;
        let is_mesh = MeshFormat::of_path(&target).is_some();
        let generator =
            generator.unwrap_or_else(|| if is_mesh { "spaceship" } else { "tree" }.into());
        Ok(Options {
            target,
            generator,
            seconds,
            seed,
            out,
            winding,
        })
    }
}

fn main() -> anyhow::Result<()> {
    let options = Options::parse(std::env::args().skip(1))?;
    let published = Published::ALL
        .into_iter()
        .find(|g| g.visit(Key) == options.generator)
        .with_context(|| {
            let names: Vec<&str> = Published::ALL.iter().map(|g| g.visit(Key)).collect();
            format!(
                "no generator `{}`; the published ones are {}",
                options.generator,
                names.join(", ")
            )
        })?;
    published.visit(Fit(&options))
}

/// A published generator's key.
struct Key;

impl GeneratorVisitor for Key {
    type Output = &'static str;
    fn visit<G: Grammar>(self, _: Limits) -> &'static str {
        G::GRAPH.key
    }
}

/// The fit, run with the chosen generator.
struct Fit<'a>(&'a Options);

impl GeneratorVisitor for Fit<'_> {
    type Output = anyhow::Result<()>;

    fn visit<G: Grammar>(self, limits: Limits) -> anyhow::Result<()> {
        let o = self.0;
        std::fs::create_dir_all(&o.out)
            .with_context(|| format!("cannot create `{}`", o.out.display()))?;
        let typical = typical_box::<G>(limits, o.seed)?;
        let scene_path = write_scene::<G>(o, limits, typical)?;
        let scene = Scene::load(&scene_path)?;
        let scorer = SceneScorer::new::<G>(&scene)?;
        let backend = scorer.on(BackendChoice::Auto, None)?;
        println!(
            "fitting `{}` to {} on {}",
            G::GRAPH.key,
            o.target.display(),
            backend.describe()
        );

        let settings = HybridSettings {
            ga: GaSettings {
                polish: 16,
                ..GaSettings::default()
            },
            ..HybridSettings::default()
        };
        let mut hybrid = Hybrid::<G>::new(settings, scene.limits, o.seed)?;
        let budget = settings
            .budget()
            .and_wall_time(Duration::from_secs(o.seconds));
        let mut progress = |s: &Snapshot<'_, G>| {
            if s.generation.is_multiple_of(25) {
                println!(
                    "generation {:>4}  best {:.4}  {:>8} evaluations",
                    s.generation, s.best_fitness, s.evaluations
                );
            }
            Control::Continue
        };
        let result = hybrid.run(&mut SceneEvaluator::new(&backend), &budget, &mut progress)?;

        let meshes = scene.meshes.bind(G::GRAPH)?;
        let mut instances = Vec::new();
        result.best.derive_into(&mut instances);
        let palette = Palette::new();
        let model = Model::new(&instances, &meshes, &palette);
        save_obj(o.out.join("best"), model)?;
        save_glb(o.out.join("best.glb"), model)?;
        result.best.save_json(o.out.join("best.genome.json"))?;
        let metrics = Metrics::of(
            &scene,
            Some(&scorer),
            &meshes,
            result.best.len(),
            &instances,
        );
        std::fs::write(
            o.out.join("metrics.json"),
            serde_json::to_string_pretty(&metrics)?,
        )?;
        compare_picture(&scene, &scorer, &instances, &meshes)?.save(o.out.join("compare.png"))?;
        println!(
            "best fitness {:.4} after {} evaluations; {}; wrote scene.toml, best.obj, best.glb, \
             best.genome.json, metrics.json and compare.png to {}",
            result.best_fitness,
            result.evaluations,
            summary(&metrics),
            o.out.display()
        );
        Ok(())
    }
}

/// The centre and the longest side of the generator's typical model: the medians over
/// [`SAMPLES`] random derivations.
fn typical_box<G: Grammar>(limits: Limits, seed: u64) -> anyhow::Result<(Vec3, f32)> {
    let mut ops = Operators::<G>::new(limits)?;
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
    let meshes = generators::default_meshes().bind(G::GRAPH)?;
    let (mut centres, mut sides) = (Vec::new(), Vec::new());
    let mut instances = Vec::new();
    for _ in 0..SAMPLES {
        ops.sample(&mut rng).derive_into(&mut instances);
        if let Some((lo, hi)) = Surface::from_instances(&instances, &meshes).bounds() {
            centres.push((lo + hi) / 2.0);
            sides.push((hi - lo).max_element());
        }
    }
    if centres.is_empty() {
        bail!(
            "the generator `{}` drew no model with a surface",
            G::GRAPH.key
        );
    }
    let median = |mut v: Vec<f32>| {
        v.sort_by(f32::total_cmp);
        v[v.len() / 2]
    };
    let centre = Vec3::new(
        median(centres.iter().map(|c| c.x).collect()),
        median(centres.iter().map(|c| c.y).collect()),
        median(centres.iter().map(|c| c.z).collect()),
    );
    Ok((centre, median(sides)))
}

/// `mesh` bound alone, and one instance of it where it stands.
fn alone(mesh: Mesh) -> anyhow::Result<(shapegen::BoundMeshes, [Instance; 1])> {
    let mut library = MeshLibrary::new();
    library.register("target", mesh)?;
    let bound = library.bind_names("Target", &["target"])?;
    let (id, _, _) = bound
        .iter()
        .find(|(_, name, _)| *name == "target")
        .context("the target is bound")?;
    let placed = [Instance {
        transform: Affine3A::IDENTITY,
        mesh: id,
    }];
    Ok((bound, placed))
}

/// Writes the target as placed and `scene.toml` into the output folder; returns the
/// scene's path.
fn write_scene<G: Grammar>(
    o: &Options,
    limits: Limits,
    (centre, side): (Vec3, f32),
) -> anyhow::Result<PathBuf> {
    let head = format!(
        "# Written by the fit example for {target}.\ngenerator = \"{key}\"\n\n[limits]\n\
         min_len = {min}\nmax_len = {max}\nmax_depth = {depth}\n\n[fitness]\nform = \"smooth\"\nlength = 0.1\n\n",
        target = o.target.display(),
        key = G::GRAPH.key,
        min = limits.min_len,
        max = limits.max_len,
        depth = limits.max_depth,
    );
    let goal = match MeshFormat::of_path(&o.target) {
        Some(_) => volume_goal(o, centre, side)?,
        None => silhouette_goal(o, centre, side)?,
    };
    let path = o.out.join("scene.toml");
    std::fs::write(&path, head + &goal)?;
    Ok(path)
}

/// `[volume]` for a mesh target scaled and moved onto the typical model's box, written
/// as `target.obj`.
fn volume_goal(o: &Options, centre: Vec3, side: f32) -> anyhow::Result<String> {
    let mut mesh = Mesh::load(&o.target)?;
    let (lo, hi) = mesh.bounds().context("the target mesh has no vertices")?;
    let scale = side / (hi - lo).max_element().max(f32::MIN_POSITIVE);
    let place = Affine3A::from_translation(centre)
        * Affine3A::from_scale(Vec3::splat(scale))
        * Affine3A::from_translation(-(lo + hi) / 2.0);
    for p in &mut mesh.positions {
        *p = place.transform_point3(*p);
    }
    let (lo, hi) = mesh.bounds().context("the placed target has vertices")?;
    let (bound, placed) = alone(mesh)?;
    save_obj(
        o.out.join("target"),
        Model::new(&placed, &bound, &Palette::new()),
    )?;
    let pad = (hi - lo) * 0.1 + Vec3::splat(side * 0.02);
    let (lo, hi) = (lo - pad, hi + pad);
    let cell = (hi - lo).max_element() / GRID_CELLS;
    let resolution = ((hi - lo) / cell).ceil().max(Vec3::splat(4.0));
    Ok(format!(
        "[volume]\ngrid = {{ min = [{}, {}, {}], max = [{}, {}, {}], resolution = [{}, {}, {}] }}\n\
         good = 2.0\nbad = 15.0\n\n[[volume.target]]\nmesh = \"target.obj\"\nfill = \"{}\"\n",
        lo.x,
        lo.y,
        lo.z,
        hi.x,
        hi.y,
        hi.z,
        resolution.x,
        resolution.y,
        resolution.z,
        if o.winding { "winding" } else { "parity" },
    ))
}

/// `[silhouette]` for a picture target, shrunk to at most [`IMAGE_SIDE`] pixels a side
/// and written as `target.png`, seen by a camera that frames the typical model from the
/// front. Its dark pixels are the target, or its opaque ones when it has transparency.
fn silhouette_goal(o: &Options, centre: Vec3, side: f32) -> anyhow::Result<String> {
    let picture = image::open(&o.target)
        .with_context(|| format!("cannot read the picture `{}`", o.target.display()))?;
    let (w, h) = picture.dimensions();
    let scale = (IMAGE_SIDE as f32 / w.max(h) as f32).min(1.0);
    let (w, h) = (
        ((w as f32 * scale) as u32).max(8),
        ((h as f32 * scale) as u32).max(8),
    );
    let picture = picture.resize_exact(w, h, image::imageops::FilterType::Triangle);
    let transparent = picture.pixels().any(|(_, _, p)| p[3] < 255);
    picture.to_rgba8().save(o.out.join("target.png"))?;
    // The model's box fills about 80 % of the picture's height at a 60 degree field of view.
    let radius = side / 0.8 / (2.0 * 30f32.to_radians().tan()) + side / 2.0;
    Ok(format!(
        "[silhouette]\ngood = 1.0\nbad = 1.0\n\n[[silhouette.target]]\nimage = \"target.png\"\n{}\n\
         camera = {{ phi = 1.5708, theta = 0.0, radius = {radius}, lookat = [{}, {}, {}], fov = 60, \
         near = 0.1, far = {}, width = {w}, height = {h} }}\n",
        if transparent {
            "alpha = 128"
        } else {
            "threshold = 128"
        },
        centre.x,
        centre.y,
        centre.z,
        (radius + side) * 4.0,
    ))
}

/// The target beside the best model: for a volume, both rendered from one camera that
/// frames them; for a silhouette, the target picture beside the model seen through its
/// camera.
fn compare_picture(
    scene: &Scene,
    scorer: &SceneScorer,
    instances: &[Instance],
    meshes: &shapegen::BoundMeshes,
) -> anyhow::Result<RgbImage> {
    let palette = Palette::new();
    let volume = scene.scorers().iter().find_map(|goal| match goal {
        ScorerGoal::Volume(volume) => volume.targets.first().map(|t| &t.mesh),
        _ => None,
    });
    let (left, right) = if let Some(target) = volume {
        let (bound, placed) = alone(target.clone())?;
        let preview = Preview::framing(&placed, &bound, 480, 360);
        (
            preview.render(Model::new(&placed, &bound, &palette))?,
            preview.render(Model::new(instances, meshes, &palette))?,
        )
    } else {
        let target = &scorer.silhouette().context("a silhouette scene")?.targets()[0];
        let preview = Preview {
            view_projection: target.view_projection(),
            width: target.width(),
            height: target.height(),
        };
        let image = RgbImage::from_fn(target.width(), target.height(), |x, y| {
            image::Rgb(if target.weight(x, y) > 0.0 {
                [30, 30, 30]
            } else {
                [240, 240, 236]
            })
        });
        (
            image,
            preview.render(Model::new(instances, meshes, &palette))?,
        )
    };
    let mut both = RgbImage::from_pixel(
        left.width() + right.width(),
        left.height().max(right.height()),
        image::Rgb([255, 255, 255]),
    );
    image::imageops::replace(&mut both, &left, 0, 0);
    image::imageops::replace(&mut both, &right, i64::from(left.width()), 0);
    Ok(both)
}

/// The measures in a line.
fn summary(m: &Metrics) -> String {
    match (m.voxel_iou, &m.surface, m.silhouette_iou.first()) {
        (Some(iou), Some(s), _) => format!(
            "voxel IoU {iou:.3}, Chamfer {:.4}, F-score {:.3}",
            s.chamfer, s.f_score
        ),
        (Some(iou), None, _) => format!("voxel IoU {iou:.3}"),
        (_, _, Some(view)) => format!("silhouette IoU {:.3}", view.iou),
        _ => format!("{} instances", m.instances),
    }
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    use super::*;

    fn options(args: &[&str]) -> anyhow::Result<Options> {
        Options::parse(args.iter().map(|s| s.to_string()))
    }

    #[test]
    fn options_choose_the_generator_by_the_target_and_refuse_mistakes() {
        assert_eq!(options(&["scan.stl"]).unwrap().generator, "spaceship");
        assert_eq!(options(&["sketch.png"]).unwrap().generator, "tree");
        let o = options(&[
            "a.glb",
            "--generator",
            "city",
            "--seconds",
            "5",
            "--winding",
        ])
        .unwrap();
        assert_eq!(
            (o.generator.as_str(), o.seconds, o.winding),
            ("city", 5, true)
        );
        assert!(
            options(&[])
                .unwrap_err()
                .to_string()
                .contains("give a target")
        );
        assert!(
            options(&["a.stl", "--fast"])
                .unwrap_err()
                .to_string()
                .contains("unknown option")
        );
        assert!(options(&["a.stl", "--seconds", "x"]).is_err());
    }

    /// A spaceship target from the project's reachable scene, as STL, and a tree's
    /// silhouette: each fits for a second, writing every file, and the mesh is placed on
    /// the generator's typical box.
    #[test]
    fn a_mesh_and_a_picture_fit_and_write_every_file() {
        let root = Path::new(env!("CARGO_MANIFEST_DIR"));
        let dir = tempfile::tempdir().unwrap();
        let target = Mesh::load(root.join("scenes/targets/spaceship_fill2.obj")).unwrap();
        let mut stl = String::from("solid t\n");
        for t in target.triangles() {
            stl += "facet normal 0 0 0\nouter loop\n";
            for i in t {
                let p = target.positions[i as usize];
                stl += &format!("vertex {} {} {}\n", p.x, p.y, p.z);
            }
            stl += "endloop\nendfacet\n";
        }
        let stl_path = dir.path().join("ship.stl");
        std::fs::write(&stl_path, stl + "endsolid t\n").unwrap();
        for (target, generator) in [
            (stl_path, "spaceship"),
            (root.join("scenes/targets/tree_sketch2.png"), "tree"),
        ] {
            let out = dir.path().join(generator);
            let o = Options {
                target,
                generator: generator.into(),
                seconds: 1,
                seed: 1,
                out: out.clone(),
                winding: false,
            };
            let published = Published::ALL
                .into_iter()
                .find(|g| g.visit(Key) == generator)
                .unwrap();
            published.visit(Fit(&o)).unwrap();
            for file in [
                "scene.toml",
                "best.obj",
                "best.glb",
                "best.genome.json",
                "metrics.json",
                "compare.png",
            ] {
                assert!(out.join(file).is_file(), "{generator}: {file}");
            }
            let metrics: serde_json::Value =
                serde_json::from_str(&std::fs::read_to_string(out.join("metrics.json")).unwrap())
                    .unwrap();
            let iou = metrics["voxel_iou"]
                .as_f64()
                .or(metrics["silhouette_iou"][0]["iou"].as_f64())
                .unwrap();
            assert!(iou > 0.2, "{generator}: {metrics}");
        }
    }
}
