"""Searches: determinism, progress and stop, threads, and the tool's result."""

import json
import subprocess
import threading
import time

import numpy as np
import pytest

import shapegen


@pytest.fixture
def volume(scenes):
    return shapegen.open_scene(scenes / "paper" / "spaceship_volume.toml")


@pytest.mark.parametrize("method", ["ga", "smc", "sosmc", "rjmcmc", "hybrid", "random"])
def test_every_method_runs_and_repeats_by_seed(volume, method):
    a = volume.run(method=method, evaluations=1500, seed=3)
    b = volume.run(method=method, evaluations=1500, seed=3, threads=1)
    assert a.best == b.best
    assert a.best_fitness == b.best_fitness
    assert a.evaluations == b.evaluations <= 1500
    h = a.history
    assert set(h) == {"generation", "elapsed_s", "evaluations", "best", "mean", "std"}
    assert len(h["best"]) == a.generations + 1
    assert np.all(np.diff(h["best"]) >= 0)
    assert h["best"][-1] == a.best_fitness
    assert volume.score([a.best])[0] == a.best_fitness


def test_the_seed_changes_the_search(volume):
    a = volume.run(method="ga", evaluations=1500, seed=1)
    b = volume.run(method="ga", evaluations=1500, seed=2)
    assert a.best != b.best


def test_progress_sees_every_generation_and_can_stop(volume):
    seen = []

    def progress(p):
        seen.append((p.generation, p.evaluations, p.best_fitness, p.best))
        return p.generation < 4

    run = volume.run(method="ga", generations=50, seed=1, progress=progress)
    assert run.stopped == "interrupted"
    assert run.generations == 4
    assert [s[0] for s in seen] == [0, 1, 2, 3, 4]
    assert all(isinstance(s[3], shapegen.Genome) for s in seen)
    assert seen[-1][2] == run.best_fitness and seen[-1][3] == run.best


def test_an_exception_in_progress_stops_the_run_and_is_raised(volume):
    def progress(p):
        if p.generation == 2:
            raise KeyError("enough")

    with pytest.raises(KeyError, match="enough"):
        volume.run(method="ga", generations=50, seed=1, progress=progress)


def test_the_gil_is_released_while_searching(volume):
    ticks = []
    done = threading.Event()

    def tick():
        while not done.is_set():
            ticks.append(time.perf_counter())
            time.sleep(0.005)

    thread = threading.Thread(target=tick)
    thread.start()
    try:
        start = time.perf_counter()
        volume.run(method="ga", seconds=1.0, generations=1_000_000, seed=1)
        end = time.perf_counter()
    finally:
        done.set()
        thread.join()
    during = [t for t in ticks if start < t < end]
    assert len(during) > 20, f"the other thread ran {len(during)} times in {end - start:.2f} s"


def test_threads_must_be_positive_and_backends_named(volume):
    with pytest.raises(shapegen.ShapegenError, match="threads must be at least 1"):
        volume.run(generations=1, threads=0)
    with pytest.raises(shapegen.ShapegenError, match='"auto"'):
        volume.run(generations=1, backend="tpu")


@pytest.mark.parametrize(
    "scene,method",
    [("paper/spaceship_volume.toml", "ga"), ("paper/city_whale.toml", "hybrid"), ("paper/tree_sketch1.toml", "sosmc")],
)
def test_the_same_best_genome_as_the_tool(scenes, tool, tmp_path, scene, method):
    path = scenes / scene
    out = tmp_path / "run"
    subprocess.run(
        tool + ["run", str(path), "--method", method, "--seed", "5", "--evaluations", "3000",
                "--cpu", "--out", str(out)],
        check=True, capture_output=True,
    )
    summary = json.loads((out / "summary.json").read_text())
    run = shapegen.open_scene(path).run(method=method, seed=5, evaluations=3000, backend="cpu")
    assert run.best.to_json() == (out / "best.genome.json").read_text()
    assert run.best_fitness == summary["best_fitness"]
    assert (run.evaluations, run.generations) == (summary["evaluations"], summary["generations"])
    tool_curve = np.loadtxt(out / "fitness.csv", delimiter=",", skiprows=1, usecols=(0, 2, 3, 4))
    ours = run.history
    assert np.array_equal(tool_curve[:, 0], ours["generation"])
    assert np.array_equal(tool_curve[:, 1], ours["evaluations"])
    assert np.array_equal(tool_curve[:, 2], ours["best"])
    assert np.array_equal(tool_curve[:, 3], ours["mean"])


def test_a_stopped_search_resumes_to_the_same_end(volume, tmp_path):
    whole = volume.run(method="ga", generations=12, seed=4)
    stopped = volume.run(method="ga", generations=12, seed=4, checkpoint=tmp_path,
                         progress=lambda p: p.generation < 5)
    assert stopped.stopped == "interrupted" and stopped.generations == 5
    assert (tmp_path / "checkpoint.json").is_file()
    resumed = shapegen.resume(tmp_path)
    assert resumed.best == whole.best
    assert (resumed.best_fitness, resumed.evaluations, resumed.generations) == (
        whole.best_fitness, whole.evaluations, whole.generations)
    assert np.array_equal(resumed.history["best"], whole.history["best"])
    # The scene object goes on from a folder too.
    again = volume.run(method="ga", generations=12, seed=4, checkpoint=tmp_path, resume=True)
    assert again.best == whole.best


def test_resuming_needs_a_checkpoint(volume, tmp_path):
    with pytest.raises(shapegen.ShapegenError, match="give checkpoint="):
        volume.run(resume=True)
    with pytest.raises(shapegen.SearchError, match="is not a checkpoint"):
        shapegen.resume(tmp_path)
    volume.run(method="ga", generations=2, seed=1, checkpoint=tmp_path)
    with pytest.raises(shapegen.SearchError, match="not one of a smc run"):
        volume.run(method="smc", checkpoint=tmp_path, resume=True)


def test_the_tool_and_the_package_go_on_from_each_others_checkpoints(scenes, tool, tmp_path):
    path = scenes / "paper" / "city_whale.toml"
    scene = shapegen.open_scene(path, method="ga", seed=2)
    whole = scene.run(generations=20, backend="cpu")
    # Started by the tool, finished from Python.
    first = tmp_path / "tool-first"
    subprocess.run(tool + ["run", str(path), "--method", "ga", "--seed", "2", "--generations", "8",
                           "--cpu", "--out", str(first)], check=True, capture_output=True)
    assert shapegen.resume(first, generations=20, backend="cpu").best == whole.best
    # Started from Python, finished by the tool.
    second = tmp_path / "python-first"
    scene.run(generations=8, checkpoint=second, backend="cpu")
    subprocess.run(tool + ["run", "--resume", str(second), "--generations", "20", "--cpu"],
                   check=True, capture_output=True)
    assert (second / "best.genome.json").read_text() == whole.best.to_json()
