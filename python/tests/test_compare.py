"""Comparisons of methods (`Scene.compare`): the tool's `shapegen compare` numbers, the
seeds of the runs, progress and mistakes."""

import csv
import json
import subprocess

import numpy as np
import pytest

import shapegen


def test_the_same_runs_and_summary_as_the_tool(scenes, tool, tmp_path):
    # A scene with an optimum, so that the summaries have their targets too.
    path = scenes / "spaceship_fill.toml"
    out = tmp_path / "compare"
    # An evaluation budget makes the runs exactly repeatable; the tool's wall budget is
    # long enough never to end one.
    subprocess.run(
        tool + ["compare", str(path), "--methods", "ga,random", "--runs", "2", "--seed", "3",
                "--seconds", "600", "--set", "optimizer.evaluations=1000", "--cpu",
                "--out", str(out)],
        check=True, capture_output=True,
    )
    seen = []
    done = shapegen.open_scene(path).compare(
        ["ga", "random"], runs=2, seed=3, evaluations=1000, backend="cpu",
        progress=lambda run: seen.append((run.method, run.run)),
    )
    assert done.complete and done.interrupted is None
    assert done.methods == ["ga", "random"] and done.seeds == [3, 4]
    assert done.optimum == 2.0 and done.seconds is None and done.backend == "CPU"
    # Run-major, as the tool runs them; progress saw each as it finished.
    order = [("ga", 0), ("random", 0), ("ga", 1), ("random", 1)]
    assert [(r.method, r.run) for r in done.runs] == order == seen

    with open(out / "runs.csv") as f:
        rows = list(csv.DictReader(f))
    assert len(rows) == len(done.runs)
    for row, run in zip(rows, done.runs):
        assert (row["method"], int(row["run"]), int(row["seed"])) == (run.method, run.run, run.seed)
        assert run.seed == 3 + run.run
        assert int(row["evaluations"]) == run.evaluations <= 1000
        assert float(row["best"]) == run.best_fitness
        assert int(row["genes"]) == run.metrics["genes"] == run.best.genes
        assert float(row["voxel_iou"]) == run.metrics["voxel_iou"]
        assert float(row["chamfer"]) == run.metrics["surface"]["chamfer"]
        saved = out / "runs" / f"{run.method}-{run.run}" / "best.genome.json"
        assert saved.read_text() == run.best.to_json()

    # Every history entry of compare.csv.
    curve = np.genfromtxt(out / "compare.csv", delimiter=",", skip_header=1, dtype=None,
                          encoding="utf-8", usecols=(0, 1, 4, 5))
    for run in done.runs:
        mine = [(int(e), float(b)) for m, r, e, b in curve if m == run.method and r == run.run]
        h = run.history
        assert mine == list(zip(h["evaluations"].tolist(), h["best"].tolist()))
        assert h["best"][-1] == run.best_fitness
        assert len(h["best"]) == run.generations + 1

    summary = json.loads((out / "summary.json").read_text())
    assert summary["seeds"] == done.seeds and summary["complete"]
    assert list(done.summaries) == ["ga", "random"]
    for tool_summary in summary["methods"]:
        ours = done.summaries[tool_summary["method"]]
        assert ours.method == tool_summary["method"]
        assert ours.runs == tool_summary["runs"] == 2
        assert ours.final_mean == tool_summary["final_mean"]
        assert ours.final_std == tool_summary["final_std"]
        assert list(ours.final_quartiles) == tool_summary["final_quartiles"]
        assert ours.best == tool_summary["best"] and ours.best_run == tool_summary["best_run"]
        assert ours.evaluations == tool_summary["evaluations"]
        assert ours.finals.tolist() == tool_summary["finals"]
        assert ours.metrics == tool_summary["metrics"]
        assert ours.targets == tool_summary["targets"]
        assert [t["fraction"] for t in ours.targets] == [0.9, 0.99, 0.999]
        assert ours.best == max(ours.finals) and ours.final_mean == np.mean(ours.finals)


def test_a_run_of_a_comparison_is_a_search_with_its_method_and_seed(scenes):
    scene = shapegen.open_scene(scenes / "paper" / "spaceship_volume.toml")
    done = scene.compare(["sosmc", "ga"], runs=2, seed=11, evaluations=800, threads=1)
    run = done.runs[3]
    assert (run.method, run.run, run.seed) == ("ga", 1, 12)
    # The method's own generation count is no limit in a comparison: give the search
    # more generations than the evaluation budget allows.
    alone = scene.run(method="ga", seed=12, evaluations=800, generations=10_000)
    assert alone.best == run.best and alone.best_fitness == run.best_fitness
    assert alone.evaluations == run.evaluations
    # Threads do not change the results.
    again = scene.compare(["sosmc", "ga"], runs=2, seed=11, evaluations=800)
    assert [r.best for r in again.runs] == [r.best for r in done.runs]


def test_progress_ends_a_comparison_and_its_exceptions_are_raised(scenes):
    scene = shapegen.open_scene(scenes / "paper" / "spaceship_volume.toml")
    done = scene.compare(["ga", "random"], runs=3, evaluations=300, progress=lambda run: False)
    assert not done.complete and len(done.runs) == 1 and done.interrupted is None
    assert done.summaries["ga"].runs == 1 and done.summaries["random"].runs == 0

    def fail(run):
        raise KeyError("enough")

    with pytest.raises(KeyError, match="enough"):
        scene.compare(["ga"], runs=2, evaluations=300, progress=fail)


def test_mistakes_are_named(scenes):
    scene = shapegen.open_scene(scenes / "paper" / "spaceship_volume.toml")
    with pytest.raises(shapegen.ShapegenError, match="listed twice"):
        scene.compare(["ga", "ga"], evaluations=300)
    with pytest.raises(shapegen.ShapegenError, match="not a method|pso"):
        scene.compare(["pso"], evaluations=300)
    with pytest.raises(shapegen.ShapegenError, match="would never end"):
        scene.compare(["ga"])
    with pytest.raises(shapegen.ShapegenError, match="at least 1 run"):
        scene.compare(["ga"], runs=0, evaluations=300)
    with pytest.raises(shapegen.ShapegenError, match="more than 0 seconds"):
        scene.compare(["ga"], seconds=0.0)
    with pytest.raises(shapegen.ShapegenError, match=r"\[\[objective\]\]"):
        shapegen.open_scene(scenes / "building.toml").compare(["ga"], evaluations=300)
