//! Scene files: the paper scenes load, and every kind of mistake is refused with the
//! file, the key and the reason.

mod support;

use std::fs;
use std::path::{Path, PathBuf};

use shapegen::scene::{Overrides, Scene, SceneError, ScorerGoal};

#[path = "scene/lots.rs"]
mod lots;

/// A folder with a target mesh (`cube.obj`), an 8 x 6 target image (`target.png`) and
/// whatever scene text a test writes.
pub(crate) struct Fixture {
    dir: tempfile::TempDir,
}

const VOLUME: &str = r#"
generator = "spaceship"
[limits]
min_len = 4
optimal_len = 10
max_len = 100
max_depth = 15
[volume]
grid = { min = [-1, -1, -1], max = [1, 1, 1], resolution = [8, 8, 8] }
[[volume.target]]
mesh = "cube.obj"
"#;

const SILHOUETTE: &str = r#"
generator = "city"
[limits]
min_len = 1
optimal_len = 100
max_len = 201
max_depth = 8
[[silhouette.target]]
image = "target.png"
camera = { phi = 0, theta = 0, radius = 5, lookat = [0, 0, 0], fov = 60, near = 0.1, far = 100, width = 8, height = 6 }
"#;

impl Fixture {
    fn new() -> Fixture {
        let dir = tempfile::tempdir().unwrap();
        fs::write(dir.path().join("cube.obj"), shapegen_cube_obj()).unwrap();
        image::GrayImage::from_fn(8, 6, |x, _| image::Luma([if x < 4 { 0 } else { 255 }]))
            .save(dir.path().join("target.png"))
            .unwrap();
        Fixture { dir }
    }

    fn path(&self) -> PathBuf {
        self.dir.path().join("scene.toml")
    }

    fn load(&self, text: &str) -> Result<Scene, SceneError> {
        fs::write(self.path(), text).unwrap();
        Scene::load(self.path())
    }

    /// Loads `text`, expecting an error about `key` whose message holds `reason`.
    fn refuses(&self, text: &str, key: &str, reason: &str) {
        let err = self.load(text).expect_err("the scene must be refused");
        let message = err.to_string();
        assert!(
            message.contains(&self.path().display().to_string()),
            "names the file: {message}"
        );
        assert!(message.contains(key), "names `{key}`: {message}");
        assert!(message.contains(reason), "says `{reason}`: {message}");
    }
}

fn shapegen_cube_obj() -> String {
    let mut obj = String::new();
    for i in 0..8 {
        let c = |bit: i32| if i & bit == 0 { -0.5 } else { 0.5 };
        obj += &format!("v {} {} {}\n", c(1), c(2), c(4));
    }
    // Faces of the cube on vertices numbered by their (x, y, z) bits, counter-clockwise
    // from outside.
    for f in [
        [1, 3, 7, 5],
        [2, 6, 8, 4],
        [1, 5, 6, 2],
        [3, 4, 8, 7],
        [1, 2, 4, 3],
        [5, 7, 8, 6],
    ] {
        obj += &format!("f {} {} {} {}\n", f[0], f[1], f[2], f[3]);
    }
    obj
}

#[test]
fn well_formed_scenes_load() {
    let fixture = Fixture::new();
    let volume = fixture.load(VOLUME).unwrap();
    assert_eq!(volume.generator, "spaceship");
    assert_eq!((volume.limits.min_len, volume.optimal_len), (4, Some(10)));
    assert!(matches!(volume.scorers(), [ScorerGoal::Volume(_)]));
    let silhouette = fixture.load(SILHOUETTE).unwrap();
    let [ScorerGoal::Silhouette(goal)] = silhouette.scorers() else {
        panic!("{:?}", silhouette.scorers());
    };
    assert_eq!(goal.targets.len(), 1);
}

#[test]
fn paper_scenes_load() {
    let scenes = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/paper");
    for name in ["spaceship_volume", "city_whale", "tree_sketch1"] {
        let scene = Scene::load(scenes.join(format!("{name}.toml")))
            .unwrap_or_else(|err| panic!("{name}: {err}"));
        assert_eq!(scene.limits.min_len, 4, "{name}");
    }
}

#[test]
fn unknown_keys_are_refused_with_their_line() {
    let fixture = Fixture::new();
    let text = VOLUME.replace("[volume]\n", "[volume]\ngird = 3\n");
    fixture.refuses(&text, "gird", "line 9");
    fixture.refuses(&format!("{VOLUME}\nseed = 1\n"), "seed", "unknown field");
}

#[test]
fn unknown_generators_are_refused() {
    let fixture = Fixture::new();
    let text = VOLUME.replace("\"spaceship\"", "\"castle\"");
    fixture.refuses(&text, "generator", &support::published_names());
}

#[test]
fn missing_files_are_refused() {
    let fixture = Fixture::new();
    fixture.refuses(
        &VOLUME.replace("cube.obj", "nowhere.obj"),
        "volume.target[0].mesh",
        "relative to the scene file",
    );
    fixture.refuses(
        &SILHOUETTE.replace("target.png", "nowhere.png"),
        "silhouette.target[0].image",
        "not a file",
    );
    let text = format!("{VOLUME}\n[meshes]\ntrunk = \"missing/trunk.obj\"\n");
    fixture.refuses(&text, "meshes.trunk", "not a file");
}

#[test]
fn bad_limits_are_refused() {
    let fixture = Fixture::new();
    fixture.refuses(
        &VOLUME.replace("max_len = 100", "max_len = 3"),
        "limits.max_len",
        "below limits.min_len",
    );
    fixture.refuses(
        &VOLUME.replace("optimal_len = 10", "optimal_len = 200"),
        "limits.optimal_len",
        "between",
    );
    fixture.refuses(
        &VOLUME.replace("max_depth = 15", "max_depth = 0"),
        "limits.max_depth",
        "at least 1",
    );
}

#[test]
fn empty_or_inverted_grids_are_refused() {
    let fixture = Fixture::new();
    fixture.refuses(
        &VOLUME.replace("max = [1, 1, 1]", "max = [1, -1, 1]"),
        "volume.grid",
        "min",
    );
    fixture.refuses(
        &VOLUME.replace("max = [1, 1, 1]", "max = [1, 1, -1]"),
        "volume.grid",
        "min",
    );
    fixture.refuses(
        &VOLUME.replace("resolution = [8, 8, 8]", "resolution = [8, 0, 8]"),
        "volume.grid",
        "resolution",
    );
    fixture.refuses(
        &VOLUME.replace("[[volume.target]]\nmesh = \"cube.obj\"\n", ""),
        "volume.target",
        "no target",
    );
}

#[test]
fn images_must_match_their_camera() {
    let fixture = Fixture::new();
    fixture.refuses(
        &SILHOUETTE.replace("width = 8", "width = 800"),
        "silhouette.target[0].image",
        "8 x 6 pixels but its camera renders 800 x 6",
    );
}

#[test]
fn cameras_are_checked() {
    let fixture = Fixture::new();
    fixture.refuses(
        &SILHOUETTE.replace("fov = 60, ", ""),
        "silhouette.target[0].camera",
        "also needs fov",
    );
    fixture.refuses(
        &SILHOUETTE.replace("near = 0.1", "near = -1"),
        "silhouette.target[0].camera",
        "near",
    );
    fixture.refuses(
        &SILHOUETTE.replace(
            "phi = 0, theta = 0, radius = 5, lookat = [0, 0, 0], fov = 60, near = 0.1, far = 100, ",
            "",
        ),
        "silhouette.target[0].camera",
        "no camera",
    );
}

#[test]
fn bad_values_are_refused() {
    let fixture = Fixture::new();
    fixture.refuses(
        &format!("{VOLUME}\n[fitness]\nlength = -1\n"),
        "fitness.length",
        ">= 0",
    );
    fixture.refuses(
        &VOLUME.replace("mesh = \"cube.obj\"", "mesh = \"cube.obj\"\ninside = nan"),
        "volume.target[0].inside",
        "finite",
    );
    fixture.refuses(
        &format!("{VOLUME}\n[fitness]\nform = \"fancy\"\n"),
        "form",
        "smooth",
    );
    let nothing = VOLUME.split("[volume]").next().unwrap();
    fixture.refuses(nothing, "volume", "nothing to score");
}

/// Scores the genome file beside each of the project's own scenes' targets with the
/// scene itself: each target was made from that genome, so it scores at the optimum.
#[test]
fn project_scenes_are_reachable() {
    use generators::GeneratorVisitor;
    use shapegen::genome::Limits;
    use shapegen::scene::{AnyCounts, BackendChoice, SceneScorer};
    use shapegen::score::InstanceBatch;
    use shapegen::{Genome, Grammar};

    /// A published generator's key, as scenes name it.
    struct Key;
    impl GeneratorVisitor for Key {
        type Output = &'static str;
        fn visit<G: Grammar>(self, _: Limits) -> Self::Output {
            G::GRAPH.key
        }
    }

    struct Check<'a>(&'a Scene, &'a Path);
    impl GeneratorVisitor for Check<'_> {
        type Output = (f64, shapegen::scene::SceneCounts);
        fn visit<G: Grammar>(self, _: Limits) -> Self::Output {
            let genome = Genome::<G>::load_json(self.1).unwrap();
            let scorer = SceneScorer::new::<G>(self.0).unwrap();
            let backend = scorer.on(BackendChoice::Cpu, None).unwrap();
            let mut batch = InstanceBatch::new();
            batch.push_genome(&genome);
            let mut counts = Vec::new();
            backend.count(&batch, &mut counts).unwrap();
            (
                scorer.fitness(&counts[0], genome.len()),
                counts.swap_remove(0),
            )
        }
    }

    let scenes = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes");
    // (scene, the genome its targets were made from, optimum)
    for (name, target, optimum) in [
        ("city_skyline", "city_skyline", 1.0),
        ("spaceship_fill", "spaceship_fill", 2.0),
        ("tree_sketch", "tree_sketch", 1.0),
        ("spaceship_fill2", "spaceship_fill2", 2.0),
        ("city_whale_view", "city_whale_view", 1.0),
        ("tree_sketch2", "tree_sketch2", 1.0),
        ("spaceship_views", "spaceship_fill2", 3.0),
    ] {
        let scene = Scene::load(scenes.join(format!("{name}.toml"))).unwrap();
        assert_eq!(scene.optimum, Some(optimum), "{name}");
        let genome = scenes.join(format!("targets/{target}.genome.json"));
        let generator = generators::Published::ALL
            .into_iter()
            .find(|g| g.visit(Key) == scene.generator)
            .unwrap_or_else(|| panic!("{name}: `{}` is not published", scene.generator));
        let (fitness, counts) = generator.visit(Check(&scene, &genome));
        for part in counts.parts() {
            match part {
                AnyCounts::Volume(v) => assert_eq!(
                    v.outside + v.out_of_grid_hits + v.span_out_of_grid,
                    0,
                    "{name}: {v:?}"
                ),
                AnyCounts::Silhouette(s) => {
                    for view in s.targets() {
                        assert_eq!(view.off_target, 0, "{name}: {s:?}");
                        assert!(view.on_target > 0, "{name}: {s:?}");
                    }
                }
                other => panic!("{name}: no other kind of scorer: {other:?}"),
            }
        }
        assert!(
            (fitness - optimum).abs() < 1e-3,
            "{name}: fitness {fitness}"
        );
        // In the IoU form, the target's own genome has IoU 1 in every view: it scores
        // `good` for each, the optimum.
        let iou = Overrides {
            sets: vec!["fitness.form=\"iou\"".into()],
            ..Overrides::default()
        };
        let registry = shapegen::registry::Registry::published();
        let scene = Scene::open(scenes.join(format!("{name}.toml")), &registry, &iou).unwrap();
        let (fitness, _) = generator.visit(Check(&scene, &genome));
        assert!(
            (fitness - optimum).abs() < 1e-3,
            "{name} in the IoU form: fitness {fitness}"
        );
        // In the F-score form (volumes only), its surface is the target's: F-score 1.
        if name.starts_with("spaceship_fill") {
            let fscore = Overrides {
                sets: vec!["fitness.form=\"fscore\"".into()],
                ..Overrides::default()
            };
            let path = scenes.join(format!("{name}.toml"));
            let scene = Scene::open(path, &registry, &fscore).unwrap();
            let (fitness, counts) = generator.visit(Check(&scene, &genome));
            let AnyCounts::Volume(v) = &counts.parts()[0] else {
                panic!("{name}: a volume scene");
            };
            assert!(
                v.surface > 0 && v.surface == v.surface_near,
                "{name}: {v:?}"
            );
            assert!(
                (fitness - optimum).abs() < 1e-3,
                "{name} in the F-score form: fitness {fitness}"
            );
        }
    }
}

const OBJECTIVES: &str = r#"
generator = "building"
[limits]
min_len = 2
optimal_len = 60
max_len = 300
max_depth = 20
[[objective]]
name = "top"
kind = "top_match"
image = "target.png"
min = [-8, -6]
max = [8, 6]
[[objective]]
kind = "unique_normals"
[[objective]]
kind = "height"
target = 30
"#;

#[test]
fn objective_scenes_load() {
    use shapegen::optimize::Sense;
    use shapegen::optimize::multi::Ranking;
    use shapegen::score::objective::{Objective, UniqueNormals};

    let fixture = Fixture::new();
    let scene = fixture
        .load(&format!(
            "{OBJECTIVES}\n[selection]\nranking = \"summed_rank\"\ndiversity_penalty = 5\n\
             [optimizer]\npopulation = 40\nelitism = 4\narchive = 25\n"
        ))
        .unwrap();
    let goal = scene.objectives.as_ref().unwrap();
    let names: Vec<&str> = goal.set.names().collect();
    assert_eq!(names, ["top", "unique_normals", "height"]);
    assert_eq!(
        goal.set.senses(),
        [Sense::Maximize, Sense::Maximize, Sense::Minimize]
    );
    assert_eq!(
        goal.set.entries()[1].1,
        Objective::UniqueNormals(UniqueNormals { tolerance_deg: 1.0 })
    );
    let settings = scene.multi_settings().unwrap();
    assert_eq!(settings.selection.ranking, Ranking::SummedRank);
    assert_eq!(settings.selection.diversity_penalty, 5.0);
    assert_eq!((settings.ga.population, settings.ga.elitism), (40, 4));
    assert_eq!(settings.archive, 25);
    // The scene has no single fitness.
    let err = shapegen::scene::SceneScorer::new::<generators::Building>(&scene).unwrap_err();
    assert!(err.to_string().contains("multi-objective"), "{err}");

    // Defaults: Pareto ranking with the thesis's penalty and GA settings.
    let scene = fixture.load(OBJECTIVES).unwrap();
    let settings = scene.multi_settings().unwrap();
    assert_eq!(settings.selection.ranking, Ranking::Pareto);
    assert_eq!(settings.selection.diversity_penalty, 20.0);
    assert_eq!(settings.ga.population, 300);
    assert!(Scene::load(fixture.path()).unwrap().scorers().is_empty());
}

#[test]
fn every_kind_of_objective_reads_its_keys() {
    use shapegen::score::objective::{FootprintExcess, NormalSpread, Objective};

    let fixture = Fixture::new();
    let scene = fixture
        .load(&format!(
            "{OBJECTIVES}[[objective]]\nkind = \"normal_spread\"\ntolerance_deg = 5\n\
             [[objective]]\nkind = \"footprint_excess\"\nmin = [-4, -3]\nmax = [4, 3.5]\n"
        ))
        .unwrap();
    let set = &scene.objectives.as_ref().unwrap().set;
    assert_eq!(
        set.entries()[3..],
        [
            (
                "normal_spread".to_owned(),
                Objective::from(NormalSpread { tolerance_deg: 5.0 })
            ),
            (
                "footprint_excess".to_owned(),
                Objective::from(FootprintExcess {
                    min: glam::Vec2::new(-4.0, -3.0),
                    max: glam::Vec2::new(4.0, 3.5),
                })
            ),
        ]
    );
}

#[test]
fn bounding_box_objectives_read_their_target_size() {
    use shapegen::score::objective::{BoundingBox, Objective};

    let fixture = Fixture::new();
    let sized = |fields: &str| {
        format!("{OBJECTIVES}[[objective]]\nname = \"size\"\nkind = \"bounding_box\"\n{fields}\n")
    };
    let scene = fixture.load(&sized("target = [12, 30, 8.5]")).unwrap();
    let goal = scene.objectives.as_ref().unwrap();
    assert_eq!(
        goal.set.entries()[3],
        (
            "size".to_owned(),
            Objective::BoundingBox(BoundingBox {
                target: glam::Vec3::new(12.0, 30.0, 8.5),
            })
        )
    );
    assert_eq!(goal.set.senses()[3], shapegen::optimize::Sense::Minimize);

    fixture.refuses(
        &sized("target = [12, -30, 8.5]"),
        "objective[3].target",
        "`target` is -30; it must be a size: finite and at least 0 along x, y and z",
    );
    fixture.refuses(
        &sized("target = [12, 30]"),
        "objective[3]",
        "kind \"bounding_box\": invalid length 2",
    );
    fixture.refuses(
        &sized("size = [12, 30, 8.5]"),
        "objective[3]",
        "kind \"bounding_box\": unknown field `size`, expected `target`",
    );
    fixture.refuses(&sized(""), "objective[3]", "missing field `target`");
}

#[test]
fn objective_mistakes_are_refused() {
    let fixture = Fixture::new();
    fixture.refuses(
        &OBJECTIVES.replace("kind = \"height\"", "kind = \"tallness\""),
        "objective[2].kind",
        "`tallness`, expected one of `height`, `unique_normals`",
    );
    fixture.refuses(
        &OBJECTIVES.replace("target = 30", ""),
        "objective[2]",
        "kind \"height\": missing field `target`",
    );
    fixture.refuses(
        &OBJECTIVES.replace("target = 30", "target = 30\nimage = \"target.png\""),
        "objective[2]",
        "kind \"height\": unknown field `image`, expected `target`",
    );
    fixture.refuses(
        &OBJECTIVES.replace("max = [8, 6]", ""),
        "objective[0]",
        "kind \"top_match\": missing field `max`",
    );
    fixture.refuses(
        &OBJECTIVES.replace("kind = \"height\"\n", ""),
        "objective[2]",
        "missing field `kind`",
    );
    fixture.refuses(
        &OBJECTIVES.replace("name = \"top\"", "name = 3"),
        "objective[0].name",
        "string",
    );
    fixture.refuses(
        &OBJECTIVES.replace(
            "kind = \"unique_normals\"",
            "kind = \"unique_normals\"\nmax = [1, 1]",
        ),
        "objective[1]",
        "kind \"unique_normals\": unknown field `max`, expected `tolerance_deg`",
    );
    fixture.refuses(
        &OBJECTIVES.replace("image = \"target.png\"", "image = \"missing.png\""),
        "objective[0].image",
        "is not a file",
    );
    fixture.refuses(
        &OBJECTIVES.replace("max = [8, 6]", "max = [-9, 6]"),
        "objective[0].image",
        "area_min",
    );
    fixture.refuses(
        &OBJECTIVES.replace(
            "kind = \"unique_normals\"",
            "kind = \"unique_normals\"\nname = \"top\"",
        ),
        "objective",
        "two objectives are named `top`",
    );
    fixture.refuses(
        &OBJECTIVES.replace(
            "kind = \"unique_normals\"",
            "kind = \"unique_normals\"\ntolerance_deg = -1",
        ),
        "objective",
        "tolerance_deg",
    );
    fixture.refuses(
        &format!("{OBJECTIVES}\n[optimizer]\nmethod = \"rjmcmc\"\n"),
        "optimizer.method",
        "must be \"ga\"",
    );
    fixture.refuses(
        &format!("{OBJECTIVES}\n[optimizer]\narchive = 0\n"),
        "optimizer.archive",
        ">= 1",
    );
    fixture.refuses(
        &format!("{OBJECTIVES}\n[selection]\nranking = \"weighted_sum\"\nweights = [1, 2]\n"),
        "selection.weights",
        "one weight per objective",
    );
    fixture.refuses(
        &format!(
            "{OBJECTIVES}\n[volume]\ngrid = {{ min = [-1, -1, -1], max = [1, 1, 1], \
             resolution = [8, 8, 8] }}\n[[volume.target]]\nmesh = \"cube.obj\"\n"
        ),
        "objective",
        "not both",
    );
    fixture.refuses(
        &format!("{VOLUME}\n[selection]\nranking = \"pareto\"\n"),
        "selection",
        "the scene has none",
    );
    let err = fixture
        .load(&format!("{OBJECTIVES}\n[selection]\nranking = \"best\"\n"))
        .unwrap_err();
    assert!(err.to_string().contains("pareto"), "{err}");
}

/// The building scene's projection targets were made from the genome beside them, so
/// that genome matches both exactly.
#[test]
fn the_building_scene_is_reachable() {
    use generators::Building;
    use shapegen::optimize::multi::MultiEvaluator;
    use shapegen::scene::ObjectiveEvaluator;

    let scenes = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes");
    let scene = Scene::load(scenes.join("building.toml")).unwrap();
    let genome = shapegen::genome::GenomeSet::<Building>::from_json(
        &fs::read_to_string(scenes.join("targets/building.genome.json")).unwrap(),
    )
    .unwrap()
    .genomes
    .remove(0);
    let mut evaluator = ObjectiveEvaluator::new::<Building>(&scene).unwrap();
    let names: Vec<&str> = evaluator.set().names().collect();
    assert_eq!(names, ["top", "front", "facets"]);
    let mut values = [0.0; 3];
    MultiEvaluator::<Building>::evaluate(&mut evaluator, &[genome], &mut values).unwrap();
    assert_eq!(values[..2], [1.0, 1.0]);
    assert!(values[2] >= 6.0, "{values:?}");
}

#[test]
fn the_length_penalty_starts_at_min_len_unless_asked_otherwise() {
    let fixture = Fixture::new();
    // The original's rule: weight * S(min_len, max_len, genes).
    let scene = fixture.load(VOLUME).unwrap();
    assert_eq!((scene.length.from, scene.length.to), (4.0, 100.0));
    let text = VOLUME.replace(
        "[volume]",
        "[fitness]\nlength = 0.1\nlength_from = \"optimal_len\"\n[volume]",
    );
    let scene = fixture.load(&text).unwrap();
    assert_eq!((scene.length.from, scene.length.weight), (10.0, 0.1));
    // Without an optimal length there is nothing to start from.
    fixture.refuses(
        &text.replace("optimal_len = 10\n", ""),
        "fitness.length_from",
        "add it to [limits]",
    );
    fixture.refuses(
        &VOLUME.replace("[volume]", "[fitness]\nlength_from = \"max_len\"\n[volume]"),
        "length_from",
        "min_len",
    );
    // optimal_len may be left out altogether.
    let scene = fixture
        .load(&VOLUME.replace("optimal_len = 10\n", ""))
        .unwrap();
    assert_eq!(scene.optimal_len, None);
}

#[test]
fn an_optimum_is_a_positive_number() {
    let fixture = Fixture::new();
    assert_eq!(fixture.load(VOLUME).unwrap().optimum, None);
    let with = |v: &str| VOLUME.replace("[volume]", &format!("[fitness]\noptimum = {v}\n[volume]"));
    assert_eq!(fixture.load(&with("2.5")).unwrap().optimum, Some(2.5));
    for bad in ["0.0", "-1.0", "nan", "inf"] {
        fixture.refuses(&with(bad), "fitness.optimum", "finite number > 0");
    }
    fixture.refuses(&with("\"high\""), "optimum", "");
}

#[test]
fn masks_take_the_original_rule_or_a_threshold() {
    let fixture = Fixture::new();
    // Columns 0-3 black, 4 dark grey (red 100), 5-7 white.
    image::GrayImage::from_fn(8, 6, |x, _| {
        image::Luma([match x {
            0..4 => 0,
            4 => 100,
            _ => 255,
        }])
    })
    .save(fixture.dir.path().join("target.png"))
    .unwrap();
    let targets = |text: &str| {
        let scene = fixture.load(text).unwrap();
        let [ScorerGoal::Silhouette(goal)] = scene.scorers() else {
            panic!("{:?}", scene.scorers());
        };
        goal.targets[0].target_pixels()
    };
    // The original's rule: red channel 0, so the grey column is not target.
    assert_eq!(targets(SILHOUETTE), 4 * 6);
    let with = |t: &str| {
        SILHOUETTE.replace(
            "image = \"target.png\"",
            &format!("image = \"target.png\"\n{t}"),
        )
    };
    assert_eq!(targets(&with("threshold = 128")), 5 * 6);
    assert_eq!(targets(&with("threshold = 100")), 4 * 6);
    fixture.refuses(&with("threshold = 0"), "threshold", "from 1 to 255");
    fixture.refuses(&with("threshold = 300"), "threshold", "from 1 to 255");
    fixture.refuses(
        &with("kind = \"weights\"\nthreshold = 128"),
        "threshold",
        "only a mask",
    );
}

#[test]
fn silhouette_targets_are_shaped_by_distance_when_asked() {
    let fixture = Fixture::new();
    let shaping = |radius: &str, target: &str| {
        SILHOUETTE
            .replace(
                "[[silhouette.target]]",
                &format!("[silhouette]\nshaping_radius = {radius}\n[[silhouette.target]]"),
            )
            .replace(
                "image = \"target.png\"",
                &format!("image = \"target.png\"\n{target}"),
            )
    };
    let scene = fixture.load(&shaping("2", "")).unwrap();
    let [ScorerGoal::Silhouette(goal)] = scene.scorers() else {
        panic!("{:?}", scene.scorers());
    };
    let target = &goal.targets[0];
    assert!(target.is_shaped());
    assert_eq!(target.target_pixels(), 4 * 6);
    // Columns 0-3 are the target; column 4 is 1 pixel away, 5 is 2 and 6, 7 further.
    let row: Vec<f64> = (0..8).map(|x| target.weight(x, 3)).collect();
    assert_eq!(row[..4], [1.0; 4]);
    assert!(row[4] < 0.0 && row[4] > -0.6 && row[5] == -1.0 && row[7] == -1.0);

    let plain = fixture.load(SILHOUETTE).unwrap();
    let [ScorerGoal::Silhouette(goal)] = plain.scorers() else {
        panic!("{:?}", plain.scorers());
    };
    assert!(!goal.targets[0].is_shaped());

    fixture.refuses(&shaping("0", ""), "silhouette.shaping_radius", "positive");
    fixture.refuses(
        &shaping("8", "kind = \"weights\""),
        "silhouette.shaping_radius",
        "needs a mask",
    );
    fixture.refuses(
        &shaping("8", "off = 0.5"),
        "silhouette.shaping_radius",
        "on > 0 > off",
    );
}

#[test]
fn volumes_are_shaped_by_distance_when_asked() {
    let fixture = Fixture::new();
    let shaping = |radius: &str| {
        VOLUME.replace(
            "[[volume.target]]",
            &format!("shaping_radius = {radius}\n[[volume.target]]"),
        )
    };
    let radius = |text: &str| {
        let scene = fixture.load(text).unwrap();
        let [ScorerGoal::Volume(goal)] = scene.scorers() else {
            panic!("{:?}", scene.scorers());
        };
        goal.shaping_radius
    };
    assert_eq!(radius(VOLUME), None);
    assert_eq!(radius(&shaping("2.5")), Some(2.5));
    fixture.refuses(
        &shaping("0"),
        "volume.shaping_radius",
        "positive number of voxels",
    );
    fixture.refuses(
        &shaping("-1"),
        "volume.shaping_radius",
        "positive number of voxels",
    );
}

#[test]
fn the_fscore_form_takes_its_threshold_from_the_targets_unless_given() {
    use shapegen::score::Form;
    let fixture = Fixture::new();
    let fscore = |extra: &str| {
        VOLUME.replace("[[volume.target]]", &format!("{extra}\n[[volume.target]]"))
            + "[fitness]\nform = \"fscore\"\n"
    };
    let threshold = |text: &str| {
        let scene = fixture.load(text).unwrap();
        let [ScorerGoal::Volume(goal)] = scene.scorers() else {
            panic!("{:?}", scene.scorers());
        };
        match goal.form {
            Form::FScore { good, threshold } => (good, threshold),
            form => panic!("{form:?}"),
        }
    };
    // The unit cube's diagonal, sqrt(3): 1 % of it, as runs report the F-score.
    let (good, t) = threshold(&fscore(""));
    assert_eq!(good, 1.0);
    assert!((t - 0.01 * 3f64.sqrt()).abs() < 1e-6, "{t}");
    assert_eq!(threshold(&fscore("fscore_threshold = 0.3")), (1.0, 0.3));
    fixture.refuses(
        &fscore("fscore_threshold = 0"),
        "volume.fscore_threshold",
        "not a distance above 0",
    );
    // Voxels of 0.25: 16 spans 64 of them.
    fixture.refuses(
        &fscore("fscore_threshold = 16"),
        "volume.fscore_threshold",
        "spans 64 voxels along x, where at most 63 are supported: give a threshold below 16",
    );
    fixture.refuses(
        &(SILHOUETTE.to_owned() + "[fitness]\nform = \"fscore\"\n"),
        "fitness.form",
        "`fscore` is for volume goals",
    );
}

#[test]
fn generator_meshes_are_normalized_unless_asked_otherwise() {
    let fixture = Fixture::new();
    // A 2 x 2 x 2 cube: normalized to unit extent, or kept as written.
    let big: String = shapegen_cube_obj()
        .lines()
        .map(|l| match l.strip_prefix("v ") {
            Some(v) => {
                let doubled: Vec<String> = v
                    .split_whitespace()
                    .map(|c| (2.0 * c.parse::<f32>().unwrap()).to_string())
                    .collect();
                format!("v {}\n", doubled.join(" "))
            }
            None => format!("{l}\n"),
        })
        .collect();
    fs::write(fixture.dir.path().join("big.obj"), big).unwrap();
    let extent = |entry: &str| {
        let scene = fixture
            .load(&format!("{VOLUME}\n[meshes]\ncube = {entry}\n"))
            .unwrap();
        let (lo, hi) = scene.meshes.get("cube").unwrap().bounds().unwrap();
        (hi - lo).x
    };
    assert_eq!(extent("\"big.obj\""), 1.0);
    assert_eq!(extent("{ path = \"big.obj\" }"), 1.0);
    assert_eq!(extent("{ path = \"big.obj\", normalize = false }"), 2.0);
    fixture.refuses(
        &format!("{VOLUME}\n[meshes]\ncube = {{ path = \"nowhere.obj\", normalize = false }}\n"),
        "meshes.cube",
        "not a file",
    );
}

#[test]
fn volume_targets_load_by_extension_and_fill_by_their_rule() {
    let fixture = Fixture::new();
    // The fixture's cube as ASCII STL, from the OBJ's own triangles.
    let cube = shapegen::Mesh::from_obj_str("cube", &shapegen_cube_obj()).unwrap();
    let mut stl = "solid cube\n".to_owned();
    for t in cube.triangles() {
        stl += "facet normal 0 0 0\nouter loop\n";
        for i in t {
            let p = cube.positions[i as usize];
            stl += &format!("vertex {} {} {}\n", p.x, p.y, p.z);
        }
        stl += "endloop\nendfacet\n";
    }
    fs::write(fixture.dir.path().join("cube.stl"), stl + "endsolid cube\n").unwrap();
    let voxels = |text: &str| {
        let scene = fixture.load(text).unwrap();
        let [ScorerGoal::Volume(goal)] = scene.scorers() else {
            panic!("{:?}", scene.scorers());
        };
        shapegen::score::volume::VoxelClasses::new(&goal.grid, &goal.targets)
            .unwrap()
            .voxels()
            .to_vec()
    };
    let obj = voxels(VOLUME);
    assert_eq!(obj.iter().filter(|&&c| c == 1).count(), 4 * 4 * 4);
    assert_eq!(voxels(&VOLUME.replace("cube.obj", "cube.stl")), obj);
    let winding = VOLUME.replace(
        "mesh = \"cube.obj\"",
        "mesh = \"cube.obj\"\nfill = \"winding\"",
    );
    assert_eq!(voxels(&winding), obj);

    fixture.refuses(
        &VOLUME.replace(
            "mesh = \"cube.obj\"",
            "mesh = \"cube.obj\"\nfill = \"flood\"",
        ),
        "fill",
        "parity",
    );
    fs::write(fixture.dir.path().join("cube.fbx"), "").unwrap();
    fixture.refuses(
        &VOLUME.replace("cube.obj", "cube.fbx"),
        "volume.target[0].mesh",
        ".obj, .stl, .ply, .gltf, .glb",
    );
    fs::write(
        fixture.dir.path().join("bad.ply"),
        "ply\nformat ascii 1.0\nend_header\n",
    )
    .unwrap();
    fixture.refuses(
        &VOLUME.replace("cube.obj", "bad.ply"),
        "volume.target[0].mesh",
        "no `vertex` element",
    );
}

#[test]
fn masks_pick_their_pixels_by_alpha_or_by_a_background_colour() {
    let fixture = Fixture::new();
    // Columns 0-2: a red object, opaque; 3: the same, half transparent; 4-7: a grey
    // backdrop (128, 128, 128) with noise of 10 on red, transparent.
    image::RgbaImage::from_fn(8, 6, |x, _| {
        image::Rgba(match x {
            0..3 => [200, 20, 20, 255],
            3 => [200, 20, 20, 100],
            _ => [128 + 10 * (x as u8 % 2), 128, 128, 0],
        })
    })
    .save(fixture.dir.path().join("photo.png"))
    .unwrap();
    let targets = |rule: &str| {
        let text = SILHOUETTE.replace(
            "image = \"target.png\"",
            &format!("image = \"photo.png\"\n{rule}"),
        );
        let scene = fixture.load(&text).unwrap();
        let [ScorerGoal::Silhouette(goal)] = scene.scorers() else {
            panic!("{:?}", scene.scorers());
        };
        goal.targets[0].target_pixels()
    };
    assert_eq!(targets("alpha = 255"), 3 * 6);
    assert_eq!(targets("alpha = 50"), 4 * 6);
    assert_eq!(targets("background = [128, 128, 128]"), 4 * 6);
    assert_eq!(
        targets("background = [128, 128, 128]\ntolerance = 5"),
        6 * 6
    );

    let with = |t: &str| {
        SILHOUETTE.replace(
            "image = \"target.png\"",
            &format!("image = \"target.png\"\n{t}"),
        )
    };
    fixture.refuses(&with("alpha = 0"), "alpha", "from 1 to 255");
    fixture.refuses(
        &with("alpha = 10\nthreshold = 10"),
        "alpha",
        "threshold and alpha are given; keep one",
    );
    fixture.refuses(&with("tolerance = 3"), "tolerance", "give the background");
    fixture.refuses(
        &with("background = [0, 300, 0]"),
        "background",
        "three values from 0 to 255",
    );
    fixture.refuses(
        &with("background = [0, 0, 0]\ntolerance = 500"),
        "tolerance",
        "441",
    );
    fixture.refuses(
        &with("kind = \"weights\"\nalpha = 128"),
        "alpha",
        "only a mask",
    );
}

#[test]
fn chamfer_objectives_read_their_point_cloud() {
    use shapegen::score::objective::Objective;

    let fixture = Fixture::new();
    fs::write(fixture.dir.path().join("scan.xyz"), "0 0 0\n1 0 0\n0 1 0\n").unwrap();
    let chamfer =
        |fields: &str| format!("{OBJECTIVES}[[objective]]\nkind = \"chamfer\"\n{fields}\n");
    let scene = fixture.load(&chamfer("points = \"scan.xyz\"")).unwrap();
    let goal = scene.objectives.as_ref().unwrap();
    let (name, Objective::Chamfer(c)) = &goal.set.entries()[3] else {
        panic!("{:?}", goal.set.entries());
    };
    assert_eq!(
        (name.as_str(), c.samples(), c.cloud().points.len()),
        ("chamfer", 512, 3)
    );

    fixture.refuses(
        &chamfer("points = \"scan.xyz\"\nsamples = 0"),
        "objective[3].samples",
        "takes 1 to 8192",
    );
    fixture.refuses(
        &chamfer("points = \"none.xyz\""),
        "objective[3].points",
        "none.xyz",
    );
    fs::write(fixture.dir.path().join("bad.xyz"), "0 0\n").unwrap();
    fixture.refuses(
        &chamfer("points = \"bad.xyz\""),
        "objective[3].points",
        "line 1",
    );
    fixture.refuses(
        &chamfer("points = \"cube.obj\""),
        "objective[3].points",
        ".xyz, .txt, .ply",
    );
    fixture.refuses(&chamfer(""), "objective[3]", "points");
}

/// A generator whose meshes are a building's parts, as a scene names them in
/// `area_share` and `roof_pitch` objectives.
mod house {
    use shapegen::geometry::{Mesh, MeshLibrary};
    use shapegen::prelude::*;
    use shapegen::registry::{AddGrammar, Defaults, Registry};

    /// A `w` by `h` quad in the plane `z`, facing `+z`.
    fn quad(w: f32, h: f32, z: f32) -> Mesh {
        Mesh {
            positions: vec![
                vec3(0.0, 0.0, z),
                vec3(w, 0.0, z),
                vec3(w, h, z),
                vec3(0.0, h, z),
            ],
            normals: vec![Vec3::Z; 4],
            indices: vec![0, 1, 2, 0, 2, 3],
        }
    }

    /// Two 45 degree slopes, 1 long, from eaves 1 apart at `y = 1` to a ridge at
    /// `y = 2`: a gable roof of area `2 sqrt 2`.
    fn gable() -> Mesh {
        Mesh {
            positions: vec![
                vec3(0.0, 1.0, 1.0),
                vec3(1.0, 1.0, 1.0),
                vec3(1.0, 2.0, 0.0),
                vec3(0.0, 2.0, 0.0),
                vec3(1.0, 1.0, -1.0),
                vec3(0.0, 1.0, -1.0),
            ],
            normals: vec![Vec3::Y; 6],
            indices: vec![0, 1, 2, 0, 2, 3, 4, 5, 3, 4, 3, 2],
        }
    }

    generator! {
        /// A house: a unit block of wall, a 1 x 1 window in front of it and a gable roof.
        pub House {
            axiom Lot;
            meshes {
                /// Walls (a unit cube).
                WALL = "wall",
                /// Roofs (facets).
                ROOF = "roof",
                /// Windows (facets).
                WINDOW = "window",
                /// Doors (facets).
                DOOR = "door",
            }
            /// The house.
            node Lot {
                derive(s) {
                    s.emit(WALL);
                    s.emit_surface(&quad(1.0, 1.0, 0.6), WINDOW);
                    s.emit_surface(&gable(), ROOF);
                }
            }
        }
    }

    /// The published generators and the house, its walls a unit cube and its other
    /// parts facets.
    pub fn registry() -> Registry {
        let mut meshes = MeshLibrary::new();
        meshes.register("wall", Mesh::unit_cube()).unwrap();
        for part in ["roof", "window", "door"] {
            meshes.register(part, Mesh::facet()).unwrap();
        }
        let mut registry = Registry::published();
        let defaults = Defaults {
            meshes,
            ..Defaults::default()
        };
        registry.add::<House>("house", defaults).unwrap();
        registry
    }
}

const HOUSE: &str = r#"
generator = "house"
[limits]
min_len = 1
max_len = 5
max_depth = 2
# The window-to-wall ratio.
[[objective]]
name = "wwr"
kind = "area_share"
parts = ["window", "door"]
of = ["wall", "window", "door"]
target = 0.4
# The roof's share of all the area.
[[objective]]
kind = "area_share"
parts = ["roof"]
target = 0.25
# The roof's pitch; its parts are `roof` unless given.
[[objective]]
kind = "roof_pitch"
target_deg = 30
"#;

fn house_scene(text: &str) -> Result<Scene, SceneError> {
    Scene::parse_in(
        text,
        Path::new("house.toml"),
        &house::registry(),
        &Overrides::default(),
    )
}

/// Loads `text` for the house, expecting an error about `key` whose message holds each
/// of `reasons`.
fn house_refuses(text: &str, key: &str, reasons: &[&str]) {
    let err = house_scene(text).expect_err("the scene must be refused");
    let message = err.to_string();
    assert!(message.starts_with("scene `house.toml`: "), "{message}");
    assert!(
        message.contains(&format!("`{key}`: ")),
        "names `{key}`: {message}"
    );
    for reason in reasons {
        assert!(message.contains(reason), "says `{reason}`: {message}");
    }
}

/// Part objectives load with their parts resolved against the generator's meshes, and
/// measure the house's derived model exactly.
#[test]
fn part_objectives_load_and_measure_the_generators_parts() {
    use shapegen::optimize::Sense;
    use shapegen::optimize::multi::MultiEvaluator;
    use shapegen::scene::ObjectiveEvaluator;
    use shapegen::score::objective::{AreaShare, Objective, Parts, RoofPitch};

    let scene = house_scene(HOUSE).unwrap();
    let set = &scene.objectives.as_ref().unwrap().set;
    let names: Vec<&str> = set.names().collect();
    assert_eq!(names, ["wwr", "area_share", "roof_pitch"]);
    assert_eq!(set.senses(), [Sense::Minimize; 3]);
    let meshes = ["cube", "wall", "roof", "window", "door"];
    let parts = |wanted: &[&str]| Parts::named(wanted, &meshes).unwrap();
    assert_eq!(
        set.entries()[0].1,
        Objective::AreaShare(AreaShare {
            parts: parts(&["window", "door"]),
            of: Some(parts(&["wall", "window", "door"])),
            target: 0.4,
        })
    );
    assert_eq!(
        set.entries()[1].1,
        Objective::AreaShare(AreaShare {
            parts: parts(&["roof"]),
            of: None,
            target: 0.25,
        })
    );
    assert_eq!(
        set.entries()[2].1,
        Objective::RoofPitch(RoofPitch {
            parts: parts(&["roof"]),
            target_deg: 30.0,
        })
    );

    let mut evaluator = ObjectiveEvaluator::new::<house::House>(&scene).unwrap();
    let genome = shapegen::Genome::<house::House>::axiom(&mut rand::rng());
    let mut values = [0.0; 3];
    MultiEvaluator::<house::House>::evaluate(&mut evaluator, &[genome], &mut values).unwrap();
    // Wall 6, window 1, roof 2 sqrt 2, all slopes at 45 degrees.
    let roof = 2.0 * 2f64.sqrt();
    let expected = [
        1.0 / 7.0 - f64::from(0.4f32),
        roof / (7.0 + roof) - 0.25,
        15.0,
    ];
    for (value, want) in values.iter().zip(expected) {
        assert!(
            (value - want.abs()).abs() < 1e-12,
            "{values:?} against {expected:?}"
        );
    }
}

#[test]
fn part_objective_mistakes_are_refused() {
    let listed = "the meshes are `cube`, `wall`, `roof`, `window` and `door`";
    house_refuses(
        &HOUSE.replace("[\"window\", \"door\"]", "[\"windw\", \"door\"]"),
        "objective[0].parts",
        &["objective `wwr`: no mesh is named `windw`", listed],
    );
    house_refuses(
        &HOUSE.replace("of = [\"wall\",", "of = [\"facade\","),
        "objective[0].of",
        &["objective `wwr`: no mesh is named `facade`", listed],
    );
    house_refuses(
        &HOUSE.replace("target_deg = 30", "target_deg = 30\nparts = [\"attic\"]"),
        "objective[2].parts",
        &["objective `roof_pitch`: no mesh is named `attic`", listed],
    );
    house_refuses(
        &HOUSE.replace("target = 0.4", "target = 1.5"),
        "objective",
        &["objective `wwr`: `target` is 1.5; it must be a share from 0 to 1"],
    );
    house_refuses(
        &HOUSE.replace("target = 0.25", "target = nan"),
        "objective",
        &["objective `area_share`: `target` is NaN"],
    );
    house_refuses(
        &HOUSE.replace("target_deg = 30", "target_deg = 95"),
        "objective",
        &["objective `roof_pitch`: `target_deg` is 95; it must be an angle from 0 to 90 degrees"],
    );
    house_refuses(
        &HOUSE.replace("target_deg = 30", "target_deg = -5"),
        "objective",
        &["`target_deg` is -5"],
    );
    house_refuses(
        &HOUSE.replace("parts = [\"roof\"]", "parts = []"),
        "objective",
        &["objective `area_share`: `parts` names no mesh"],
    );
    house_refuses(
        &HOUSE.replace(
            "parts = [\"window\", \"door\"]",
            "parts = [\"window\", \"roof\"]",
        ),
        "objective",
        &["objective `wwr`: `parts` has a mesh that `of` lacks"],
    );
    house_refuses(
        &HOUSE.replace("target = 0.25\n", ""),
        "objective[1]",
        &["kind \"area_share\": missing field `target`"],
    );
    house_refuses(
        &HOUSE.replace("target_deg = 30", "target = 30"),
        "objective[2]",
        &["kind \"roof_pitch\": unknown field `target`, expected `parts` or `target_deg`"],
    );
    house_refuses(
        &HOUSE.replace("parts = [\"roof\"]", "parts = \"roof\""),
        "objective[1]",
        &["kind \"area_share\"", "sequence"],
    );
}
