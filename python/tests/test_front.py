"""Multi-objective scenes (`Scene.run_front`): the tool's front, progress and mistakes."""

import csv
import json
import subprocess

import numpy as np
import pytest

import shapegen

# A short search of the building scene's three objectives.
SETTINGS = ["optimizer.population=40", "optimizer.archive=60"]


@pytest.fixture
def building(scenes):
    return scenes / "building.toml"


def test_the_same_front_as_the_tool(building, tool, tmp_path):
    out = tmp_path / "front"
    sets = [a for s in SETTINGS for a in ("--set", s)]
    subprocess.run(
        tool + ["run", str(building), "--seed", "4", "--generations", "3", *sets, "--out", str(out)],
        check=True, capture_output=True,
    )
    scene = shapegen.open_scene(building)
    assert scene.objectives == ["top", "front", "facets"]
    front = scene.run_front(seed=4, generations=3, set=SETTINGS, threads=1)
    assert front.objectives == ["top", "front", "facets"]
    assert front.kinds == ["top_match", "front_match", "unique_normals"]
    assert front.ranking == "pareto" and front.stopped == "generations"

    with open(out / "front.csv") as f:
        rows = list(csv.DictReader(f))
    assert len(front) == len(rows) == len(front.members) > 0
    values = front.values
    assert values.shape == (len(rows), 3) and values.dtype == np.float64
    for i, (row, member) in enumerate(zip(rows, front.members)):
        assert int(row["model"]) == i
        assert int(row["genes"]) == member.genome.genes
        tool_values = [float(row[name]) for name in front.objectives]
        assert list(member.values.values()) == tool_values == values[i].tolist()
        assert list(member.values) == front.objectives
    saved = json.loads((out / "front.genomes.json").read_text())
    assert saved["generator"] == "building"
    ours = [json.loads(g.to_json())["genes"] for g in front.genomes]
    assert ours == [g["genes"] for g in saved["genomes"]]

    summary = json.loads((out / "summary.json").read_text())
    assert (front.evaluations, front.generations) == (summary["evaluations"], summary["generations"])
    assert summary["front"] == len(front)
    history = np.genfromtxt(out / "history.csv", delimiter=",", names=True)
    h = front.history
    assert set(h) == {"generation", "elapsed_s", "evaluations", "front",
                      "best_top", "best_front", "best_facets"}
    for column in ("generation", "evaluations", "front", "best_top", "best_front", "best_facets"):
        assert np.array_equal(history[column], h[column]), column
    assert len(h["generation"]) == front.generations + 1

    models = front.models()
    assert len(models) == len(front)
    assert all(m.faces.shape[1] == 3 and len(m.faces) > 0 for m in models)
    # Threads do not change the front.
    again = scene.run_front(seed=4, generations=3, set=SETTINGS)
    assert again.genomes == front.genomes and np.array_equal(again.values, front.values)


def test_progress_sees_every_generation_and_can_stop(building):
    seen = []

    def progress(p):
        seen.append((p.generation, p.front, dict(p.best)))
        return p.generation < 1

    scene = shapegen.open_scene(building, set=SETTINGS)
    front = scene.run_front(generations=5, progress=progress)
    assert front.stopped == "interrupted" and front.generations == 1
    assert [s[0] for s in seen] == [0, 1]
    assert all(set(s[2]) == {"top", "front", "facets"} and s[1] > 0 for s in seen)


def test_one_search_for_each_kind_of_scene(building, scenes):
    with pytest.raises(shapegen.SceneError, match="run_front"):
        shapegen.open_scene(building).run(generations=1)
    volume = shapegen.open_scene(scenes / "paper" / "spaceship_volume.toml")
    assert volume.objectives == []
    with pytest.raises(shapegen.SceneError, match="Scene.run"):
        volume.run_front(generations=1)
