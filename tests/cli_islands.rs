//! `shapegen run --islands K` on one process: the same result at any thread count, one
//! island is the GA, a resumed run ends as an uninterrupted one, and mistakes are named.
//! Runs spread over MPI processes are tested in `cli_mpi.rs`.

mod support;

use std::fs;

use support::{fails, ok, s, skyline_scene, timeless_curve, timeless_summary};

#[test]
fn islands_do_not_depend_on_threads_and_one_island_is_the_ga() {
    let dir = tempfile::tempdir().unwrap();
    let scene = skyline_scene(dir.path());
    let run = |name: &str, threads: &str, extra: &[&str]| {
        let out = dir.path().join(name);
        let base = [
            "--threads",
            threads,
            "run",
            s(&scene),
            "--cpu",
            "--out",
            s(&out),
        ];
        ok(&[&base[..], extra].concat());
        out
    };
    let (one, two) = (
        run("one", "1", &["--islands", "4"]),
        run("two", "2", &["--islands", "4"]),
    );
    let summary = timeless_summary(&one);
    assert_eq!(summary, timeless_summary(&two));
    assert_eq!(timeless_curve(&one), timeless_curve(&two));
    assert_eq!(summary["evaluations"], 4 * 24 + 8 * 4 * 20);
    assert_eq!(summary["islands"]["count"], 4);
    assert_eq!(summary["processes"], 1);

    let (island, plain) = (
        run("island", "2", &["--islands", "1"]),
        run("plain", "2", &[]),
    );
    assert_eq!(timeless_curve(&island), timeless_curve(&plain));
    for file in ["best.genome.json", "best.obj"] {
        assert_eq!(
            fs::read_to_string(island.join(file)).unwrap(),
            fs::read_to_string(plain.join(file)).unwrap(),
            "{file}"
        );
    }
    assert!(timeless_summary(&plain).get("islands").is_none());
}

#[test]
fn an_island_run_resumes_exactly() {
    let dir = tempfile::tempdir().unwrap();
    let scene = skyline_scene(dir.path());
    let (whole, parts) = (dir.path().join("whole"), dir.path().join("parts"));
    // Migrations after generations 2, 4, 6 and 8, one of them in each part.
    let base = [
        "run",
        s(&scene),
        "--cpu",
        "--islands",
        "2",
        "--set",
        "islands.interval=2",
    ];
    ok(&[&base[..], &["--out", s(&whole)]].concat());
    ok(&[&base[..], &["--generations", "3", "--out", s(&parts)]].concat());
    ok(&["run", "--resume", s(&parts), "--cpu", "--generations", "8"]);
    assert_eq!(timeless_summary(&parts), timeless_summary(&whole));
    assert_eq!(timeless_curve(&parts), timeless_curve(&whole));
    assert_eq!(timeless_summary(&whole)["islands"]["interval"], 2);
}

#[test]
fn island_mistakes_are_explained() {
    let dir = tempfile::tempdir().unwrap();
    let scene = skyline_scene(dir.path());
    let out = dir.path().join("out");
    let cases: [(&[&str], &str); 6] = [
        (&["--islands", "0"], "`--islands`"),
        (&["--set", "islands.count=0"], "`islands.count`"),
        (
            &["--islands", "2", "--method", "rjmcmc"],
            "the island model runs the GA",
        ),
        (
            &["--islands", "2", "--set", "islands.migrants=24"],
            "must be less than the population",
        ),
        (
            &["--islands", "2", "--set", "islands.interval=0"],
            "`islands.interval`",
        ),
        (
            &["--set", "islands.travellers=1"],
            "unknown field `travellers`",
        ),
    ];
    for (extra, expected) in cases {
        let args = [&["run", s(&scene), "--cpu", "--out", s(&out)][..], extra].concat();
        let err = fails(&args);
        assert!(err.contains(expected), "{extra:?}: {err}");
        if !expected.contains("unknown") && !expected.contains("GA") {
            assert!(
                err.contains("at least 1") || err.contains("less than"),
                "{err}"
            );
        }
    }
}
