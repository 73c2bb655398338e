//! Running the `shapegen` binary from the command-line tests.

// Each test file uses the helpers it needs.
#![allow(dead_code)]

pub mod slurm;
pub mod view;

use std::fs;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// Runs `shapegen` with `args`.
pub fn shapegen(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_shapegen"))
        .args(args)
        .output()
        .expect("the shapegen binary runs")
}

/// Runs `shapegen` with `args`, which must succeed, and returns what it printed.
pub fn ok(args: &[&str]) -> String {
    let run = shapegen(args);
    assert!(
        run.status.success(),
        "shapegen {args:?} failed: {}",
        String::from_utf8_lossy(&run.stderr)
    );
    String::from_utf8(run.stdout).unwrap()
}

/// Runs `shapegen` with `args`, which must fail, and returns its error output.
pub fn fails(args: &[&str]) -> String {
    let run = shapegen(args);
    assert!(!run.status.success(), "shapegen {args:?} should fail");
    String::from_utf8(run.stderr).unwrap()
}

/// A path as a command-line argument.
pub fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// Starts `shapegen` with `args`, waits until `file` exists (at most a minute), runs
/// `meanwhile` while the process still runs, sends it SIGINT (as Ctrl-C does) and returns
/// what the process left: its status and its error output.
pub fn interrupt_when(args: &[&str], file: &Path, meanwhile: impl FnOnce()) -> Output {
    signal_when("INT", args, file, meanwhile)
}

/// As [`interrupt_when`], with signal `signal` (`INT`, `TERM`, `HUP`, `KILL`, ..).
///
/// The error output is read as it comes: a run's progress lines would otherwise fill
/// the pipe and stop the run before it writes `file`.
pub fn signal_when(signal: &str, args: &[&str], file: &Path, meanwhile: impl FnOnce()) -> Output {
    let mut child = start(args);
    let reader = drain_stderr(&mut child);
    wait_for(file);
    meanwhile();
    send(signal, &child);
    let status = child.wait().expect("the process ends");
    Output {
        status,
        stdout: Vec::new(),
        stderr: reader.join().expect("the reader ends"),
    }
}

/// Reads `child`'s piped error output as it comes, in a thread that returns it once the
/// process has closed it: unread, a run's progress lines fill the pipe and stop the run.
pub fn drain_stderr(child: &mut std::process::Child) -> std::thread::JoinHandle<Vec<u8>> {
    let mut stderr = child.stderr.take().expect("the error output is piped");
    std::thread::spawn(move || {
        let mut bytes = Vec::new();
        std::io::Read::read_to_end(&mut stderr, &mut bytes).expect("the error output reads");
        bytes
    })
}

/// Starts `shapegen` with `args` in the background, its error output piped.
pub fn start(args: &[&str]) -> std::process::Child {
    Command::new(env!("CARGO_BIN_EXE_shapegen"))
        .args(args)
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("the shapegen binary runs")
}

/// Waits until `file` exists, at most a minute.
pub fn wait_for(file: &Path) {
    let start = std::time::Instant::now();
    while !file.exists() {
        assert!(
            start.elapsed().as_secs() < 60,
            "`{}` was not written",
            file.display()
        );
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
}

/// Sends `signal` to `child`.
pub fn send(signal: &str, child: &std::process::Child) {
    let kill = Command::new("kill")
        .args([&format!("-{signal}"), &child.id().to_string()])
        .status()
        .expect("kill runs");
    assert!(kill.success());
}

/// A run's `summary.json` without its wall time, which differs between runs.
pub fn timeless_summary(dir: &Path) -> serde_json::Value {
    let text = fs::read_to_string(dir.join("summary.json")).expect("summary.json");
    let mut summary: serde_json::Value = serde_json::from_str(&text).expect("JSON");
    let object = summary.as_object_mut().expect("an object");
    object.remove("elapsed_s");
    object.remove("peak_rss_bytes");
    // How children were counted (from their parents or from nothing) depends on where a
    // run was resumed, never what they were counted to.
    object.remove("incremental");
    summary
}

/// A run's `fitness.csv` without its `elapsed_s` column, which differs between runs.
pub fn timeless_curve(dir: &Path) -> Vec<String> {
    timeless_table(dir, "fitness.csv")
}

/// A run's table `file` (`fitness.csv`, `history.csv`) without its second column,
/// `elapsed_s`, which differs between runs.
pub fn timeless_table(dir: &Path, file: &str) -> Vec<String> {
    let text = fs::read_to_string(dir.join(file)).expect(file);
    assert!(text.starts_with("generation,elapsed_s,"), "{file}: {text}");
    text.lines()
        .map(|l| {
            let mut cells: Vec<&str> = l.split(',').collect();
            cells.remove(1);
            cells.join(",")
        })
        .collect()
}

/// Checks the chart `name` (`compare.png`, say) in `dir`: a PNG of `size` pixels and,
/// beside it, its SVG (`compare.svg`) holding each of `texts` (a title, an axis title,
/// a legend entry) as text. Returns the SVG.
pub fn chart(dir: &Path, name: &str, size: (u32, u32), texts: &[&str]) -> String {
    let png = image::open(dir.join(name)).unwrap_or_else(|e| panic!("{name}: {e}"));
    assert_eq!((png.width(), png.height()), size, "{name}");
    let svg_name = name.replace(".png", ".svg");
    let svg = fs::read_to_string(dir.join(&svg_name)).unwrap_or_else(|e| panic!("{svg_name}: {e}"));
    assert!(svg.starts_with("<svg"), "{svg_name}");
    for text in texts {
        let escaped = text
            .replace('&', "&amp;")
            .replace('<', "&lt;")
            .replace('>', "&gt;");
        assert!(
            svg.contains(&format!(">\n{escaped}\n<")),
            "no `{text}` in {svg_name}"
        );
    }
    svg
}

/// The JSON lines `shapegen score` prints.
pub fn score(scene: &Path, genomes: &Path, backend: &str) -> Vec<serde_json::Value> {
    ok(&["score", s(scene), "--genomes", s(genomes), backend])
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect()
}

pub fn sample(generator: &str, seed: &str, dir: &Path) -> PathBuf {
    ok(&[
        "sample",
        "-g",
        generator,
        "-n",
        "6",
        "-s",
        seed,
        "-o",
        s(dir),
    ]);
    dir.join("genomes.json")
}

pub const SHIP_SCENE: &str = r#"
generator = "spaceship"
[limits]
min_len = 4
optimal_len = 10
max_len = 100
max_depth = 15
[fitness]
length = 0.1
[volume]
grid = { min = [-5, -5, -2], max = [5, 5, 18], resolution = [40, 40, 80] }
good = 2.0
bad = 15.0
[[volume.target]]
mesh = "TARGET"
"#;

/// A unit cube centred at the origin, as OBJ.
pub const UNIT_CUBE_OBJ: &str = "v -0.5 -0.5 -0.5\nv 0.5 -0.5 -0.5\nv 0.5 0.5 -0.5\nv -0.5 0.5 -0.5\nv -0.5 -0.5 0.5\nv 0.5 -0.5 0.5\nv 0.5 0.5 0.5\nv -0.5 0.5 0.5\nf 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 3 4 8 7\nf 2 3 7 6\nf 1 5 8 4\n";

/// Writes [`SHIP_SCENE`] with a unit cube as its target into `dir`: a spaceship scene
/// whose runs are quick. Returns the scene's path.
pub fn cube_ship_scene(dir: &Path) -> PathBuf {
    fs::write(dir.join("cube.obj"), UNIT_CUBE_OBJ).unwrap();
    let path = dir.join("ship.toml");
    fs::write(&path, SHIP_SCENE.replace("TARGET", "cube.obj")).unwrap();
    path
}

/// A sweep's `sweep.csv` in `dir` without its `seconds` column (wall time differs
/// between runs), as rows of fields, the header first.
pub fn sweep_rows_without_seconds(dir: &Path) -> Vec<Vec<String>> {
    let csv = fs::read_to_string(dir.join("sweep.csv")).expect("sweep.csv");
    let rows: Vec<Vec<String>> = csv
        .lines()
        .map(|l| l.split(',').map(str::to_owned).collect())
        .collect();
    let seconds = rows[0]
        .iter()
        .position(|c| c == "seconds")
        .expect("a seconds column");
    rows.into_iter()
        .map(|mut r| {
            r.remove(seconds);
            r
        })
        .collect()
}

/// A small city scene (24 cities, 8 generations) at 160 x 90 whose target is the silhouette of a sampled city.
pub fn skyline_scene(dir: &Path) -> PathBuf {
    let text = r#"
generator = "city"
[limits]
min_len = 4
optimal_len = 100
max_len = 201
max_depth = 8
[fitness]
length = 0.02
[silhouette]
[[silhouette.target]]
image = "skyline.png"
camera = { phi = -1.5708, theta = 0.06, radius = 25, lookat = [0, 4.2, 0], fov = 45, near = 0.1, far = 200, width = 160, height = 90 }
[optimizer]
method = "ga"
population = 24
elitism = 4
initial_length = 40
generations = 8
"#;
    let path = dir.join("skyline.toml");
    fs::write(&path, text).unwrap();
    image::GrayImage::from_pixel(160, 90, image::Luma([255]))
        .save(dir.join("skyline.png"))
        .unwrap();
    ok(&[
        "sample",
        "-g",
        "city",
        "-n",
        "1",
        "-s",
        "3",
        "-o",
        s(&dir.join("c")),
    ]);
    let genomes = dir.join("c/genomes.json");
    ok(&[
        "target",
        s(&path),
        "--genome",
        s(&genomes),
        "--out",
        s(&dir.join("skyline.png")),
    ]);
    path
}

/// The published generators' names as messages list them: "spaceship, tree, ... and
/// lot_building", from `Published::ALL`.
pub fn published_names() -> String {
    struct Key;
    impl generators::GeneratorVisitor for Key {
        type Output = &'static str;
        fn visit<G: shapegen::Grammar>(self, _: shapegen::genome::Limits) -> &'static str {
            G::GRAPH.key
        }
    }
    let names: Vec<&str> = generators::Published::ALL
        .iter()
        .map(|g| g.visit(Key))
        .collect();
    let (last, rest) = names.split_last().expect("there are published generators");
    format!("{} and {last}", rest.join(", "))
}
