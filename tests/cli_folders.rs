//! Output folders: one command at a time in each, a killed command's lock taken over,
//! another run's outputs refused unless `--resume` or `--force`, SIGTERM and SIGHUP
//! stopping a run as Ctrl-C does, a write that fails (a file-size limit, as on a full
//! disk) leaving every file as it was, and a read-only folder refused untouched.

mod support;

use std::collections::BTreeMap;
use std::fs::{self, Permissions};
use std::os::unix::fs::{MetadataExt, PermissionsExt};
use std::path::Path;
use std::process::Command;

use support::{
    drain_stderr, fails, ok, s, send, shapegen, signal_when, skyline_scene as scene, start,
    timeless_summary, wait_for,
};

/// Every file under `dir` (recursively) and its bytes.
fn snapshot(dir: &Path) -> BTreeMap<String, Vec<u8>> {
    let mut files = BTreeMap::new();
    for entry in fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            for (name, bytes) in snapshot(&path) {
                files.insert(format!("{}/{name}", path.display()), bytes);
            }
        } else {
            files.insert(path.display().to_string(), fs::read(&path).unwrap());
        }
    }
    files
}

/// A run that goes on until it is stopped, writing into `out`.
fn endless<'a>(scene: &'a Path, out: &'a Path) -> [&'a str; 7] {
    [
        "run",
        s(scene),
        "--cpu",
        "--generations",
        "1000000",
        "--out",
        s(out),
    ]
}

/// Runs `scene` for 3 generations into `out` and returns the folder's files.
fn three_generations(scene: &Path, out: &Path) -> BTreeMap<String, Vec<u8>> {
    ok(&[
        "run",
        s(scene),
        "--cpu",
        "--generations",
        "3",
        "--out",
        s(out),
    ]);
    snapshot(out)
}

/// Resumes the run in `out` on the CPU until it has made `generations` generations.
fn resume_to(out: &Path, generations: u64) {
    let generations = generations.to_string();
    ok(&[
        "run",
        "--resume",
        s(out),
        "--cpu",
        "--generations",
        &generations,
    ]);
}

/// The generation of the checkpoint in `out`.
fn checkpoint_generation(out: &Path) -> u64 {
    let text = fs::read_to_string(out.join("checkpoint.json")).unwrap();
    let checkpoint: serde_json::Value = serde_json::from_str(&text).unwrap();
    checkpoint["search"]["progress"]["generation"]
        .as_u64()
        .unwrap()
}

#[test]
fn a_folder_in_use_is_refused_with_its_holder_named() {
    let dir = tempfile::tempdir().unwrap();
    let scene = scene(dir.path());
    let out = dir.path().join("out");
    let mut first = start(&endless(&scene, &out));
    let stderr = drain_stderr(&mut first);
    wait_for(&out.join("checkpoint.json"));
    let holder = format!("is in use by pid {}", first.id());
    let seconds = ["--seconds", "1"];
    let others: [&[&str]; 4] = [
        &["run", "--resume", s(&out), "--cpu"],
        &["run", s(&scene), "--cpu", "--force", "--out", s(&out)],
        &[
            &["compare", s(&scene), "--methods", "ga", "--force"],
            &["--out", s(&out)][..],
            &seconds[..],
        ]
        .concat(),
        &[
            "sweep",
            s(&scene),
            "--grid",
            "optimizer.population=6,8",
            "--runs",
            "1",
            "--generations",
            "1",
            "--force",
            "--out",
            s(&out),
        ],
    ];
    for args in others {
        let err = fails(args);
        assert!(
            err.contains(&holder) && err.contains("--generations 1000000"),
            "{args:?}: {err}"
        );
    }
    send("INT", &first);
    let ended = first.wait().unwrap();
    stderr.join().unwrap();
    assert!(ended.success());
    assert!(!out.join("shapegen.lock").exists(), "the lock goes with it");
    let generations = checkpoint_generation(&out) + 1;
    resume_to(&out, generations);
}

#[test]
fn the_lock_of_a_killed_run_is_taken_over() {
    let dir = tempfile::tempdir().unwrap();
    let scene = scene(dir.path());
    let out = dir.path().join("out");
    let ended = signal_when(
        "KILL",
        &endless(&scene, &out),
        &out.join("checkpoint.json"),
        || {},
    );
    assert!(!ended.status.success());
    let lock = fs::read_to_string(out.join("shapegen.lock")).unwrap();
    let pid = serde_json::from_str::<serde_json::Value>(&lock).unwrap()["pid"].clone();
    let generations = checkpoint_generation(&out) + 1;
    let resumed = shapegen(&[
        "run",
        "--resume",
        s(&out),
        "--cpu",
        "--generations",
        &generations.to_string(),
    ]);
    let err = String::from_utf8_lossy(&resumed.stderr);
    assert!(resumed.status.success(), "{err}");
    assert!(
        err.contains("taking over") && err.contains(&format!("pid {pid} ")),
        "{err}"
    );
    assert!(!out.join("shapegen.lock").exists());
}

#[test]
fn another_runs_outputs_are_refused_unless_resumed_or_replaced() {
    let dir = tempfile::tempdir().unwrap();
    let scene = scene(dir.path());
    let out = dir.path().join("out");
    let run = ["run", s(&scene), "--cpu", "--out", s(&out)];
    ok(&run);
    fs::write(out.join("notes.txt"), "mine").unwrap();
    let before = snapshot(&out);
    let err = fails(&run);
    assert!(
        err.contains("holds the outputs of a run (checkpoint.json, summary.json)")
            && err.contains(&format!("--resume {}", out.display()))
            && err.contains("--force"),
        "{err}"
    );
    let err = fails(&[
        "compare",
        s(&scene),
        "--methods",
        "ga",
        "--seconds",
        "1",
        "--out",
        s(&out),
    ]);
    assert!(err.contains("holds the outputs of a run"), "{err}");
    let err = fails(&[
        "sweep",
        s(&scene),
        "--grid",
        "optimizer.population=6,8",
        "--runs",
        "1",
        "--generations",
        "1",
        "--out",
        s(&out),
    ]);
    assert!(err.contains("holds the outputs of a run"), "{err}");
    assert_eq!(snapshot(&out), before, "nothing was touched");

    // --force replaces the run, says what it removed, and leaves other files alone.
    let forced = shapegen(&[&run[..], &["--force", "--seed", "7"]].concat());
    let err = String::from_utf8_lossy(&forced.stderr);
    assert!(forced.status.success(), "{err}");
    assert!(
        err.contains("--force: replacing a run in")
            && err.contains("best.obj, best.png")
            && err.contains("checkpoint.json"),
        "{err}"
    );
    assert_eq!(timeless_summary(&out)["seed"], 7);
    assert_eq!(fs::read_to_string(out.join("notes.txt")).unwrap(), "mine");

    // A comparison's folder is refused to a run in turn.
    let compared = dir.path().join("compared");
    ok(&[
        "compare",
        s(&scene),
        "--methods",
        "ga",
        "--runs",
        "1",
        "--seconds",
        "0.2",
        "--cpu",
        "--out",
        s(&compared),
    ]);
    let err = fails(&["run", s(&scene), "--cpu", "--out", s(&compared)]);
    assert!(
        err.contains("holds the outputs of a comparison") && !err.contains("--resume"),
        "{err}"
    );
}

#[test]
fn sigterm_and_sighup_stop_a_run_as_ctrl_c_does() {
    let dir = tempfile::tempdir().unwrap();
    let scene = scene(dir.path());
    for signal in ["TERM", "HUP"] {
        let out = dir.path().join(signal);
        let ended = signal_when(
            signal,
            &endless(&scene, &out),
            &out.join("checkpoint.json"),
            || {},
        );
        let err = String::from_utf8_lossy(&ended.stderr);
        assert!(ended.status.success(), "SIG{signal}: {err}");
        let summary = timeless_summary(&out);
        assert_eq!(summary["stopped"], "interrupted", "SIG{signal}");
        assert!(!out.join("shapegen.lock").exists(), "SIG{signal}");
        let generations = summary["generations"].as_u64().unwrap() + 1;
        resume_to(&out, generations);
    }
}

/// A file-size limit makes writes fail as a full disk does (EFBIG rather than ENOSPC):
/// the run fails naming the file, every file of the folder is left as it was (the
/// checkpoint included, no temporary or lock file left), and the run then goes on from
/// that checkpoint to the same end as a run never stopped.
#[test]
fn a_write_that_fails_leaves_every_file_as_it_was() {
    let dir = tempfile::tempdir().unwrap();
    let scene = scene(dir.path());
    let (whole, parts) = (dir.path().join("whole"), dir.path().join("parts"));
    ok(&["run", s(&scene), "--cpu", "--out", s(&whole)]);
    let before = three_generations(&scene, &parts);
    // At most one 512-byte block per file (dash's unit; bash's is 1024): the lock file
    // fits, the run's models and checkpoint do not.
    let limited = Command::new("sh")
        .args([
            "-c",
            r#"ulimit -f 1; trap "" XFSZ; exec "$0" "$@""#,
            env!("CARGO_BIN_EXE_shapegen"),
            "run",
            "--resume",
            s(&parts),
            "--cpu",
            "--generations",
            "8",
        ])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&limited.stderr);
    assert!(!limited.status.success(), "{err}");
    assert!(
        err.contains(&format!("cannot write `{}/", parts.display()))
            && err.contains("File too large")
            && err.contains("left as it was"),
        "{err}"
    );
    assert_eq!(snapshot(&parts), before, "every file as it was");
    ok(&["run", "--resume", s(&parts), "--cpu", "--generations", "8"]);
    assert_eq!(timeless_summary(&parts), timeless_summary(&whole));
    assert_eq!(
        fs::read_to_string(parts.join("best.genome.json")).unwrap(),
        fs::read_to_string(whole.join("best.genome.json")).unwrap()
    );
}

/// A read-only folder: resuming the run in it fails at its lock, saying the folder is not
/// writable, and leaves every file as it was. Permissions do not bind root, so as root the
/// command runs as the user `nobody` (through util-linux's `setpriv`), from a link to the
/// binary inside the test's folder, which that user can reach.
#[test]
fn a_read_only_folder_is_refused_and_left_as_it_was() {
    let dir = tempfile::tempdir().unwrap();
    let scene = scene(dir.path());
    let parts = dir.path().join("parts");
    let before = three_generations(&scene, &parts);
    let bin = dir.path().join("shapegen");
    if fs::hard_link(env!("CARGO_BIN_EXE_shapegen"), &bin).is_err() {
        fs::copy(env!("CARGO_BIN_EXE_shapegen"), &bin).unwrap();
    }
    fs::set_permissions(dir.path(), Permissions::from_mode(0o755)).unwrap();
    fs::set_permissions(&parts, Permissions::from_mode(0o555)).unwrap();
    let root = fs::metadata("/proc/self").unwrap().uid() == 0;
    let mut command = match root {
        true => {
            let mut setpriv = Command::new("setpriv");
            setpriv.args(["--reuid=65534", "--regid=65534", "--clear-groups"]);
            setpriv.arg(&bin);
            setpriv
        }
        false => Command::new(&bin),
    };
    let resumed = command
        .args(["run", "--resume", s(&parts), "--cpu", "--generations", "6"])
        .output()
        .expect("setpriv (util-linux) runs the command as another user when tests run as root");
    fs::set_permissions(&parts, Permissions::from_mode(0o755)).unwrap();
    let err = String::from_utf8_lossy(&resumed.stderr);
    assert!(!resumed.status.success(), "{err}");
    assert!(
        err.contains(&format!("`{}` is not writable", parts.display()))
            && err.contains("nothing in it was changed")
            && err.contains("Permission denied"),
        "{err}"
    );
    assert_eq!(snapshot(&parts), before, "every file as it was");
}
