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
