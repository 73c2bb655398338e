//! The viewer's page in a real browser: headless Chromium loads `shapegen view`'s page
//! for a finished run, for a running one, and a `report.html` from `file://`, and the
//! page must show the numbers of `summary.json`, one curve point per row of
//! `fitness.csv`, and a 3D canvas that is not blank; a multi-objective run's front, the
//! model of a chosen point, and the runs of a comparison and the cells of a study.
//!
//! Under its own harness so that a missing browser shows: without Chromium the tests are
//! reported as ignored, after a line saying so, unless `SHAPEGEN_REQUIRE_BROWSER=1` (as
//! in CI, which installs the distribution's `chromium`), where they fail instead.

mod support;

use std::fs;
use std::path::{Path, PathBuf};
use std::process::{Command, ExitCode};

use libtest_mimic::{Arguments, Failed, Trial};
use support::view::serve;
use support::{ok, s, skyline_scene};

/// The page's background (`BACKGROUND` in `assets/viewer/viewer.js`).
const BACKGROUND: [u8; 3] = [0xf2, 0xf2, 0xef];
/// The browser window.
const WINDOW: (u32, u32) = (1280, 900);

/// A test that drives the browser: its name and its body, which panics when it fails.
type BrowserTest = (&'static str, fn(&Path));

const TESTS: &[BrowserTest] = &[
    (
        "the_page_shows_a_finished_run",
        the_page_shows_a_finished_run,
    ),
    (
        "the_page_follows_a_running_run",
        the_page_follows_a_running_run,
    ),
    (
        "the_report_shows_the_run_offline",
        the_report_shows_the_run_offline,
    ),
    (
        "the_page_shows_a_front_a_comparison_and_a_study",
        the_page_shows_a_front_a_comparison_and_a_study,
    ),
];

/// The Chromium binary: `SHAPEGEN_CHROMIUM`, else `chromium` or `chromium-browser` on
/// the `PATH`.
fn chromium() -> Option<PathBuf> {
    if let Some(path) = std::env::var_os("SHAPEGEN_CHROMIUM") {
        return Some(PathBuf::from(path));
    }
    let path = std::env::var_os("PATH")?;
    std::env::split_paths(&path)
        .flat_map(|dir| ["chromium", "chromium-browser"].map(|name| dir.join(name)))
        .find(|p| p.is_file())
}

fn main() -> ExitCode {
    let args = Arguments::from_args();
    let required = std::env::var("SHAPEGEN_REQUIRE_BROWSER").as_deref() == Ok("1");
    let browser = chromium();
    match &browser {
        Some(path) => eprintln!("browser tests run on {}", path.display()),
        None if required => {
            eprintln!("no Chromium found; SHAPEGEN_REQUIRE_BROWSER=1, so the browser tests fail")
        }
        None => {
            eprintln!("no Chromium found (apt-get install chromium); the browser tests are ignored")
        }
    }
    let trials = TESTS
        .iter()
        .map(|&(name, test)| match browser.clone() {
            Some(path) => Trial::test(name, move || {
                test(&path);
                Ok(())
            }),
            None => Trial::test(name, || Err(Failed::from("no Chromium found")))
                .with_ignored_flag(!required),
        })
        .collect();
    libtest_mimic::run(&args, trials).exit_code()
}

/// Runs headless Chromium on `url` with a fresh profile, with `mode` (`--dump-dom` or
/// `--screenshot=FILE`) and `wait` (`--virtual-time-budget=MS` for a finished page,
/// shorter for one that follows a running run); returns what it printed.
fn browse(browser: &Path, url: &str, mode: &str, wait: &str) -> String {
    let profile = tempfile::tempdir().unwrap();
    let output = Command::new(browser)
        .args([
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--disable-background-networking",
            "--disable-component-update",
            "--disable-sync",
            "--no-first-run",
            "--hide-scrollbars",
            // No host but the test's server is reached: a page that needed anything
            // beyond this machine would show it.
            "--host-resolver-rules=MAP * ~NOTFOUND, EXCLUDE 127.0.0.1",
            &format!("--user-data-dir={}", profile.path().display()),
            &format!("--window-size={},{}", WINDOW.0, WINDOW.1),
            wait,
            mode,
            url,
        ])
        .output()
        .expect("Chromium runs");
    assert!(
        output.status.success(),
        "Chromium failed on {url}: {}",
        String::from_utf8_lossy(&output.stderr)
    );
    String::from_utf8_lossy(&output.stdout).into_owned()
}

/// The value of attribute `attribute` of the element with id `id` in `dom`.
fn attribute(dom: &str, id: &str, attribute: &str) -> Option<String> {
    let at = dom.find(&format!("id=\"{id}\""))?;
    let tag_start = dom[..at].rfind('<')?;
    let tag_end = at + dom[at..].find('>')?;
    let tag = &dom[tag_start..tag_end];
    let key = format!("{attribute}=\"");
    let start = tag.find(&key)? + key.len();
    let end = start + tag[start..].find('"')?;
    Some(tag[start..end].to_owned())
}

/// A short run of the small skyline scene into `dir/run`.
fn short_run(dir: &Path) -> PathBuf {
    let scene = skyline_scene(dir);
    let out = dir.join("run");
    ok(&["run", s(&scene), "--cpu", "--out", s(&out)]);
    out
}

/// Checks that the page in `dom` shows `run`'s summary and curve.
fn shows_the_run(dom: &str, run: &Path) {
    let summary: serde_json::Value =
        serde_json::from_str(&fs::read_to_string(run.join("summary.json")).unwrap()).unwrap();
    let shown = |id: &str| {
        attribute(dom, id, "data-value").unwrap_or_else(|| panic!("no #{id} value in the page"))
    };
    assert_eq!(shown("method"), summary["method"].as_str().unwrap());
    assert_eq!(shown("seed"), summary["seed"].to_string());
    assert_eq!(shown("generation"), summary["generations"].to_string());
    assert_eq!(shown("evaluations"), summary["evaluations"].to_string());
    let best: f64 = shown("best").parse().unwrap();
    assert_eq!(best, summary["best_fitness"].as_f64().unwrap());
    let elapsed: f64 = shown("elapsed").parse().unwrap();
    assert_eq!(elapsed, summary["elapsed_s"].as_f64().unwrap());

    let rows = fs::read_to_string(run.join("fitness.csv"))
        .unwrap()
        .lines()
        .count()
        - 1;
    assert!(rows > 1);
    assert_eq!(
        attribute(dom, "curve", "data-points").as_deref(),
        Some(rows.to_string().as_str())
    );
    assert_eq!(
        attribute(dom, "canvas", "data-model").as_deref(),
        Some("best.glb")
    );
}

/// Checks that a screenshot of the page at `url` has the model drawn: within the 3D
/// canvas (`rect` as the page reports it), a share of the pixels differ from the
/// background.
fn canvas_not_blank(browser: &Path, url: &str, rect: &str, wait: &str) {
    let dir = tempfile::tempdir().unwrap();
    let shot = dir.path().join("page.png");
    browse(
        browser,
        url,
        &format!("--screenshot={}", shot.display()),
        wait,
    );
    let image = image::open(&shot).unwrap().to_rgb8();
    let r: Vec<u32> = rect.split(',').map(|v| v.parse().unwrap()).collect();
    let (x0, y0, w, h) = (r[0], r[1], r[2], r[3]);
    assert!(w > 100 && h > 100, "canvas {rect}");
    assert!(x0 + w <= image.width() && y0 + h <= image.height());
    let mut drawn = 0;
    for y in y0..y0 + h {
        for x in x0..x0 + w {
            let p = image.get_pixel(x, y).0;
            if p.iter().zip(BACKGROUND).any(|(a, b)| a.abs_diff(b) > 24) {
                drawn += 1;
            }
        }
    }
    let share = drawn as f64 / f64::from(w * h);
    assert!(
        share > 0.02,
        "only {:.2} % of the canvas differs from the background",
        share * 100.0
    );
}

fn the_page_shows_a_finished_run(browser: &Path) {
    let dir = tempfile::tempdir().unwrap();
    let run = short_run(dir.path());
    let served = serve(&["view", s(&run)]);
    let url = format!("http://{}/", served.addr);
    let wait = "--virtual-time-budget=5000";
    let dom = browse(browser, &url, "--dump-dom", wait);
    shows_the_run(&dom, &run);
    assert_eq!(
        attribute(&dom, "status", "data-state").as_deref(),
        Some("finished")
    );
    let rect = attribute(&dom, "canvas", "data-rect").expect("the canvas's place");
    canvas_not_blank(browser, &url, &rect, wait);
}

fn the_page_follows_a_running_run(browser: &Path) {
    let dir = tempfile::tempdir().unwrap();
    let scene = skyline_scene(dir.path());
    let out = dir.path().join("run");
    let served = serve(&[
        "run",
        s(&scene),
        "--cpu",
        "--seconds",
        "120",
        "--generations",
        "100000",
        "--view",
        "--out",
        s(&out),
    ]);
    support::wait_for(&out.join("run.json"));
    // The page waits for each save of the run (a second or more apart, in real time,
    // whatever the virtual time) and pauses 0.2 s of virtual time after each: 0.5 s of
    // virtual time are the first load and two saves or more.
    let dom = browse(
        browser,
        &format!("http://{}/", served.addr),
        "--dump-dom",
        "--virtual-time-budget=500",
    );
    assert_eq!(
        attribute(&dom, "status", "data-state").as_deref(),
        Some("live"),
        "the page does not say the run is live"
    );
    let updates: u32 = attribute(&dom, "status", "data-updates")
        .expect("the page counts its updates")
        .parse()
        .unwrap();
    assert!(
        updates >= 2,
        "the page showed {updates} generations of a running run"
    );
    let live: serde_json::Value =
        serde_json::from_str(&fs::read_to_string(out.join("run.json")).unwrap()).unwrap();
    assert_eq!(live["running"], true);
}

fn the_report_shows_the_run_offline(browser: &Path) {
    let dir = tempfile::tempdir().unwrap();
    let run = short_run(dir.path());
    ok(&["report", s(&run)]);
    // Opened from a copy in another folder: it needs nothing beside it.
    let alone = dir.path().join("alone");
    fs::create_dir(&alone).unwrap();
    fs::copy(run.join("report.html"), alone.join("report.html")).unwrap();
    let url = format!("file://{}", alone.join("report.html").display());
    let wait = "--virtual-time-budget=5000";
    let dom = browse(browser, &url, "--dump-dom", wait);
    shows_the_run(&dom, &run);
    assert_eq!(
        attribute(&dom, "status", "data-state").as_deref(),
        Some("report")
    );
    let rect = attribute(&dom, "canvas", "data-rect").expect("the canvas's place");
    canvas_not_blank(browser, &url, &rect, wait);
}

/// The page `shapegen view` serves for `folder` (with `fragment` after its address),
/// once a finished folder's page has settled.
fn finished_page(browser: &Path, folder: &Path, fragment: &str) -> String {
    let served = serve(&["view", s(folder)]);
    let url = format!("http://{}/{fragment}", served.addr);
    browse(browser, &url, "--dump-dom", "--virtual-time-budget=5000")
}

fn the_page_shows_a_front_a_comparison_and_a_study(browser: &Path) {
    let dir = tempfile::tempdir().unwrap();
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));

    let front = dir.path().join("front");
    let scene = root.join("scenes/building.toml");
    ok(&[
        "run",
        s(&scene),
        "--cpu",
        "--generations",
        "2",
        "--out",
        s(&front),
    ]);
    // The front's members by the first objective, as the scatter shows them from the
    // left, with their numbers in `front.csv`.
    let table = fs::read_to_string(front.join("front.csv")).unwrap();
    let mut rows: Vec<(f64, String)> = table
        .lines()
        .skip(1)
        .map(|line| {
            let fields: Vec<&str> = line.split(',').collect();
            (fields[2].parse().unwrap(), fields[0].to_owned())
        })
        .collect();
    rows.sort_by(|a, b| a.0.total_cmp(&b.0));
    let dom = finished_page(browser, &front, "");
    assert_eq!(
        attribute(&dom, "front", "data-points"),
        Some(rows.len().to_string()),
        "one point per member of the front"
    );
    assert_eq!(
        attribute(&dom, "canvas", "data-model").as_deref(),
        Some("front/model_000.glb")
    );
    // A chosen point (`#point=K`, what a click on the K-th point from the left does)
    // shows its own model.
    assert!(rows.len() >= 2, "a front of {} members", rows.len());
    let point = rows.len() - 1;
    let dom = finished_page(browser, &front, &format!("#point={point}"));
    assert_eq!(
        attribute(&dom, "front", "data-point"),
        Some(point.to_string())
    );
    assert_eq!(
        attribute(&dom, "canvas", "data-model"),
        Some(format!("front/model_{:0>3}.glb", rows[point].1))
    );

    let compare = dir.path().join("compare");
    let scene = skyline_scene(dir.path());
    ok(&[
        "compare",
        s(&scene),
        "--methods",
        "ga",
        "--runs",
        "2",
        "--seconds",
        "0.3",
        "--cpu",
        "--out",
        s(&compare),
    ]);
    let dom = finished_page(browser, &compare, "");
    assert_eq!(
        dom.matches("<button>show</button>").count(),
        2,
        "a model button per run"
    );
    assert_eq!(
        attribute(&dom, "canvas", "data-model").as_deref(),
        Some("runs/ga-0/best.glb")
    );

    // A study: a model button per cell, and each cell's curve.
    let sweep = dir.path().join("sweep");
    ok(&[
        "sweep",
        s(&scene),
        "--grid",
        "optimizer.population=20,30,40",
        "--runs",
        "1",
        "--evaluations",
        "200",
        "--cpu",
        "--out",
        s(&sweep),
    ]);
    let dom = finished_page(browser, &sweep, "");
    assert_eq!(
        dom.matches("<button>show</button>").count(),
        3,
        "a model button per cell"
    );
    assert_eq!(
        attribute(&dom, "curve", "data-series").as_deref(),
        Some("3"),
        "a curve per cell"
    );
}
