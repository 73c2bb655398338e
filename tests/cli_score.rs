//! `shapegen score`, `target` and `render` end to end: reachable targets score as the
//! optimum, previews are written, mistakes are explained. That the GPU counts as the CPU
//! does is in `cli_gpu.rs`, under a harness that shows a missing adapter.

mod support;

use std::fs;
use std::path::Path;

use support::{SHIP_SCENE, UNIT_CUBE_OBJ, fails, ok, s, sample, score};

const CITY_SCENE: &str = r#"
generator = "city"
[limits]
min_len = 4
optimal_len = 100
max_len = 300
max_depth = 8
[silhouette]
[[silhouette.target]]
image = "TARGET"
camera = { phi = -3.05161, theta = 0.0479887, radius = 12.4346, lookat = [1.82669, 4.65407, -0.620025], fov = 60, near = 0.1, far = 100, width = 160, height = 120 }
"#;

/// Writes `text` as a scene whose target is `target`, and a copy aiming at a unit cube
/// (any target will do to make a target).
fn scenes(
    dir: &Path,
    name: &str,
    text: &str,
    target: &str,
    seed_target: &Path,
) -> (std::path::PathBuf, std::path::PathBuf) {
    let maker = dir.join(format!("{name}_maker.toml"));
    fs::write(&maker, text.replace("TARGET", s(seed_target))).unwrap();
    let scene = dir.join(format!("{name}.toml"));
    fs::write(&scene, text.replace("TARGET", target)).unwrap();
    (maker, scene)
}

#[test]
fn a_reachable_volume_target_is_filled_exactly() {
    let dir = tempfile::tempdir().unwrap();
    let genomes = sample("spaceship", "5", &dir.path().join("ships"));
    let cube = dir.path().join("cube.obj");
    fs::write(&cube, UNIT_CUBE_OBJ).unwrap();
    let (maker, scene) = scenes(dir.path(), "ship", SHIP_SCENE, "ship.obj", &cube);
    let out = ok(&[
        "target",
        s(&maker),
        "--genome",
        s(&genomes),
        "--index",
        "5",
        "--out",
        s(&dir.path().join("ship")),
    ]);
    assert!(out.contains("ship.obj"), "{out}");

    let lines = score(&scene, &genomes, "--cpu");
    assert_eq!(lines.len(), 6);
    let chosen = &lines[5]["volume"];
    let voxels: u64 = out
        .split('(')
        .nth(1)
        .unwrap()
        .split(' ')
        .next()
        .unwrap()
        .parse()
        .unwrap();
    assert_eq!(
        chosen["inside"], voxels,
        "the model covers all of its own target"
    );
    assert_eq!(chosen["outside"], 0);
    // Every line gives both notions of overlap and of reaching beyond the grid: hits
    // beyond each voxel's first and distinct voxels hit again; covered points outside
    // the grid and, as the original counts them, the instances' spans outside it.
    for line in &lines {
        let volume = line["volume"].as_object().unwrap();
        let mut keys: Vec<&str> = volume.keys().map(String::as_str).collect();
        keys.sort_unstable();
        assert_eq!(
            keys,
            [
                "inside",
                "out_of_grid_hits",
                "outside",
                "overlap_hits",
                "overlap_voxels",
                "span_out_of_grid"
            ]
        );
        let n = |k: &str| volume[k].as_u64().unwrap();
        assert!(n("overlap_voxels") <= n("overlap_hits"), "{volume:?}");
    }
    // Genome 1's wings reach x = ±5.95, beyond the grid, in boxes too thin to cover a
    // voxel centre there: no covered point outside the grid, but voxels of their spans.
    let wide = &lines[1]["volume"];
    assert_eq!(wide["out_of_grid_hits"], 0);
    assert!(wide["span_out_of_grid"].as_u64().unwrap() > 0, "{wide}");
    // The smooth form's optimum, less overlap and length terms.
    let f = lines[5]["fitness"].as_f64().unwrap();
    assert!(f > 1.5 && f <= 2.0, "fitness {f}");
    for (i, line) in lines.iter().enumerate().filter(|(i, _)| *i != 5) {
        assert!(
            line["fitness"].as_f64().unwrap() < f,
            "genome {i} scores below the one the target was made of"
        );
    }
}

#[test]
fn a_reachable_silhouette_target_is_matched_exactly() {
    let dir = tempfile::tempdir().unwrap();
    let genomes = sample("city", "9", &dir.path().join("cities"));
    let blank = dir.path().join("blank.png");
    image::GrayImage::from_pixel(160, 120, image::Luma([255]))
        .save(&blank)
        .unwrap();
    let (maker, scene) = scenes(dir.path(), "city", CITY_SCENE, "skyline.png", &blank);
    ok(&[
        "target",
        s(&maker),
        "--genome",
        s(&genomes),
        "--index",
        "2",
        "--out",
        s(&dir.path().join("skyline")),
    ]);
    let target = image::open(dir.path().join("skyline.png")).unwrap();
    assert_eq!((target.width(), target.height()), (160, 120));

    let lines = score(&scene, &genomes, "--cpu");
    let counts = &lines[2]["silhouette"][0];
    assert_eq!(counts["off_target"], 0);
    assert_eq!(counts["on_target"], counts["covered"]);
    let f = lines[2]["fitness"].as_f64().unwrap();
    assert!((f - 1.0).abs() < 0.05, "good * S(T, T) - length: {f}");
}

#[test]
fn previews_and_overlays_are_written() {
    let dir = tempfile::tempdir().unwrap();
    let genomes = sample("city", "3", &dir.path().join("cities"));
    let target = dir.path().join("half.png");
    image::GrayImage::from_fn(160, 120, |x, _| image::Luma([if x < 80 { 0 } else { 255 }]))
        .save(&target)
        .unwrap();
    let (_, scene) = scenes(dir.path(), "city", CITY_SCENE, "half.png", &target);
    let out = dir.path().join("render");
    ok(&[
        "render",
        s(&scene),
        "--genomes",
        s(&genomes),
        "--out",
        s(&out),
    ]);
    for i in 0..6 {
        let model = image::open(out.join(format!("model_{i}.png"))).unwrap();
        assert_eq!((model.width(), model.height()), (160, 120));
        let overlay = image::open(out.join(format!("overlay_{i}.png")))
            .unwrap()
            .to_rgb8();
        // The target is the left half: there, pixels are target (blue) or both (green);
        // on the right, model alone (red) or nothing (white).
        for (x, _, p) in overlay.enumerate_pixels() {
            let allowed: [[u8; 3]; 2] = if x < 80 {
                [[150, 170, 215], [40, 120, 60]]
            } else {
                [[225, 90, 70], [255, 255, 255]]
            };
            assert!(allowed.contains(&p.0), "pixel at x = {x}: {:?}", p.0);
        }
    }

    // A volume scene has no camera: previews frame each model.
    let ships = sample("spaceship", "4", &dir.path().join("ships"));
    let cube = dir.path().join("cube.obj");
    fs::write(&cube, UNIT_CUBE_OBJ).unwrap();
    let (_, ship_scene) = scenes(dir.path(), "ship", SHIP_SCENE, "cube.obj", &cube);
    let out = dir.path().join("ship_render");
    ok(&[
        "render",
        s(&ship_scene),
        "--genomes",
        s(&ships),
        "--out",
        s(&out),
        "--width",
        "64",
        "--height",
        "48",
    ]);
    let model = image::open(out.join("model_0.png")).unwrap();
    assert_eq!((model.width(), model.height()), (64, 48));
    assert!(!out.join("overlay_0.png").exists());
}

#[test]
fn mistakes_are_explained() {
    let dir = tempfile::tempdir().unwrap();
    let cities = sample("city", "1", &dir.path().join("cities"));
    let cube = dir.path().join("cube.obj");
    fs::write(&cube, UNIT_CUBE_OBJ).unwrap();
    let (_, scene) = scenes(dir.path(), "ship", SHIP_SCENE, "cube.obj", &cube);

    let err = fails(&["score", s(&scene), "--genomes", s(&cities)]);
    assert!(
        err.contains("genomes.json") && err.contains("`city`"),
        "{err}"
    );
    let err = fails(&["score", "nowhere.toml", "--genomes", s(&cities)]);
    assert!(err.contains("nowhere.toml"), "{err}");
    let err = fails(&[
        "target",
        s(&scene),
        "--genome",
        s(&cities),
        "--index",
        "9",
        "--out",
        "x",
    ]);
    assert!(err.contains("`city`") || err.contains("--index"), "{err}");
    let ships = sample("spaceship", "1", &dir.path().join("ships"));
    let err = fails(&[
        "target",
        s(&scene),
        "--genome",
        s(&ships),
        "--index",
        "6",
        "--out",
        "x",
    ]);
    assert!(
        err.contains("holds 6 genomes; --index must be below 6"),
        "{err}"
    );
    let err = fails(&["score", s(&scene), "--genomes", s(&ships), "--cpu", "--gpu"]);
    assert!(err.contains("cannot be used with"), "{err}");
}
