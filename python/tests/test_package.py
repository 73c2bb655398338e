"""The shapegen package: generators, genomes, models, scenes and their errors."""

import json

import numpy as np
import pytest

import shapegen
from conftest import cube


def test_the_published_generators_are_listed_by_name():
    names = shapegen.generators()
    # The paper's and the building generators first, in the table's order; any later
    # published generator after them.
    assert names[:6] == [
        "spaceship", "tree", "city", "building", "roofed_building", "lot_building",
    ]
    assert len(set(names)) == len(names)
    g = shapegen.generator("Spaceship")  # the grammar's name finds it too
    assert (g.name, g.grammar, g.parts) == ("spaceship", "Spaceship", ["cube"])
    assert g.limits == {"min_len": 4, "max_len": 100, "max_depth": 15}


def test_an_unknown_generator_names_the_known_ones():
    with pytest.raises(shapegen.GeneratorError, match="the generators are spaceship, tree"):
        shapegen.generator("spaceshp")
    assert issubclass(shapegen.GeneratorError, shapegen.ShapegenError)
    assert issubclass(shapegen.ShapegenError, ValueError)


def test_samples_depend_on_the_seed_only():
    g = shapegen.generator("city")
    a, b = g.sample(5, seed=3), g.sample(5, seed=3)
    assert a == b
    assert [x.to_json() for x in a] == [x.to_json() for x in b]
    assert a != g.sample(5, seed=4)
    assert all(1 <= len(x) <= g.limits["max_len"] for x in a)
    assert len(g.sample(3, seed=3, max_len=5)) == 3
    assert all(len(x) <= 5 for x in g.sample(20, seed=3, max_len=5))


def test_a_model_is_numpy_arrays_of_its_triangles_and_parts():
    g = shapegen.generator("lot_building")
    genome = g.sample(1, seed=2)[0]
    m = g.model(genome)
    assert m.vertices.dtype == np.float32 and m.vertices.ndim == 2 and m.vertices.shape[1] == 3
    assert m.faces.dtype == np.uint32 and m.faces.shape[1] == 3 and len(m.faces) > 0
    assert m.parts.dtype == np.uint32 and m.parts.shape == (len(m.faces),)
    assert m.faces.max() < len(m.vertices)
    assert m.parts.max() < len(m.part_names)
    assert m.part_colors.shape == (len(m.part_names), 3)
    assert {"wall", "roof"} <= {m.part_names[p] for p in np.unique(m.parts)}
    assert np.isfinite(m.vertices).all()
    assert m.instances > 0


def test_a_cube_model_is_twelve_triangles_per_box():
    g = shapegen.generator("spaceship")
    genome = g.sample(1, seed=1)[0]
    m = g.model(genome)
    assert len(m.faces) == 12 * m.instances
    assert len(m.vertices) == 24 * m.instances


def test_genomes_round_trip_through_both_json_forms():
    g = shapegen.generator("tree")
    genome = g.sample(1, seed=5)[0]
    packed = genome.to_json()
    nested = genome.to_json(nested=True)
    assert json.loads(packed)["generator"] == "tree"
    assert "tree" in json.loads(nested)
    assert g.genome(packed) == genome
    # The nested form is the tree: read back, its genes may be packed in another order.
    assert g.genome(nested).to_json(nested=True) == nested
    assert hash(g.genome(packed)) == hash(genome)


def test_a_bad_genome_raises_with_the_loaders_message():
    g = shapegen.generator("tree")
    with pytest.raises(shapegen.GenomeError):
        g.genome("{}")
    with pytest.raises(shapegen.GenomeError, match="spaceship"):
        g.genome(shapegen.generator("spaceship").sample(1)[0].to_json())
    city = shapegen.generator("city").sample(1)[0]
    with pytest.raises(shapegen.GenomeError, match="not of `tree`"):
        g.model(city)


def test_a_scene_file_opens_with_overrides(scenes):
    scene = shapegen.open_scene(scenes / "paper" / "spaceship_volume.toml", method="ga", seed=7)
    assert (scene.generator, scene.method, scene.seed) == ("spaceship", "ga", 7)
    assert scene.with_settings(method="smc").method == "smc"
    assert scene.with_settings(seed=8).seed == 8
    # As on the command line, a typed setting wins over a `set` of the same key.
    assert scene.with_settings(set=["optimizer.seed=9"]).seed == 7
    plain = shapegen.open_scene(scenes / "paper" / "spaceship_volume.toml")
    assert plain.with_settings(set=["optimizer.seed=9"]).seed == 9


def test_settings_are_checked_by_name_and_type(scenes):
    path = scenes / "paper" / "spaceship_volume.toml"
    with pytest.raises(shapegen.ShapegenError, match="unknown setting `population`; the settings are method, seed"):
        shapegen.open_scene(path, population=3)
    with pytest.raises(shapegen.ShapegenError, match="seed must be a whole number >= 0"):
        shapegen.open_scene(path, seed=-1)
    with pytest.raises(shapegen.SceneError, match="--seconds"):
        shapegen.open_scene(path, seconds=-2.0)
    scene = shapegen.open_scene(path)
    with pytest.raises(shapegen.ShapegenError, match="unknown setting `seeds`"):
        scene.run(seeds=3)
    assert shapegen.open_scene(path, seed=None).seed == scene.seed


def test_scene_errors_name_the_file_and_the_key(scenes, tmp_path):
    with pytest.raises(shapegen.SceneError, match="nope.toml"):
        shapegen.open_scene(tmp_path / "nope.toml")
    bad = tmp_path / "bad.toml"
    bad.write_text('generator = "spaceship"\n[limits]\nmin_len = 1\nmax_len = 9\nmax_depth = 5\n[volume]\ngrid = { min = [0, 0, 0], max = [1, 1, 1], resolution = [4, 4, 4] }\n')
    with pytest.raises(shapegen.SceneError, match="volume.target"):
        shapegen.open_scene(bad)
    with pytest.raises(shapegen.ShapegenError, match="the methods are ga, smc"):
        shapegen.open_scene(scenes / "paper" / "spaceship_volume.toml", method="pso")
    with pytest.raises(shapegen.SceneError, match="optimizer.population"):
        shapegen.open_scene(
            scenes / "paper" / "spaceship_volume.toml", set=["optimizer.population=-3"]
        )


def test_a_volume_scene_from_arrays_scores_and_searches():
    v, f = cube(size=4.0, centre=(0.0, 2.0, 0.0))
    scene = shapegen.volume_scene(
        "spaceship", v, f, resolution=24, settings={"optimizer": {"method": "ga"}}
    )
    assert scene.method == "ga"
    genomes = scene.sample(4, seed=1)
    scores = scene.score(genomes)
    assert len(scores) == 4 and all(np.isfinite(scores))
    run = scene.run(evaluations=600, seed=1)
    assert run.best_fitness >= max(scores) or run.best_fitness == pytest.approx(scene.score([run.best])[0])
    assert scene.score([run.best])[0] == run.best_fitness


def test_mesh_arrays_are_checked():
    v, f = cube()
    with pytest.raises(shapegen.ShapegenError, match="vertices must be N x 3"):
        shapegen.volume_scene("spaceship", v[:, :2], f)
    with pytest.raises(shapegen.ShapegenError, match="faces must be M x 3"):
        shapegen.volume_scene("spaceship", v, np.zeros((2, 4), dtype=int))
    with pytest.raises(shapegen.ShapegenError, match="face 0 names vertex 99"):
        shapegen.volume_scene("spaceship", v, np.array([[0, 1, 99]]))
    with pytest.raises(shapegen.ShapegenError, match="non-finite"):
        shapegen.volume_scene("spaceship", np.full((8, 3), np.nan), f)
    with pytest.raises(shapegen.GeneratorError, match="unknown generator `rocket`"):
        shapegen.volume_scene("rocket", v, f)


def test_a_silhouette_scene_from_an_image_array():
    image = np.full((60, 80), 255, dtype=np.uint8)
    image[10:50, 20:60] = 0
    camera = {"phi": 0.0, "theta": 0.3, "radius": 30.0, "lookat": [0, 3, 0], "fov": 60,
              "near": 0.1, "far": 100, "width": 80, "height": 60}
    scene = shapegen.silhouette_scene("city", image, camera, settings={"optimizer": {"method": "ga"}})
    run = scene.run(evaluations=400, seed=2)
    assert np.isfinite(run.best_fitness)
    mask = image == 0
    same = shapegen.silhouette_scene("city", mask, camera, settings={"optimizer": {"method": "ga"}})
    assert same.score([run.best]) == scene.score([run.best])
    with pytest.raises(shapegen.SceneError, match="80 x 60"):
        shapegen.silhouette_scene("city", image[:, :70], camera)
    with pytest.raises(shapegen.ShapegenError, match="float64"):
        shapegen.silhouette_scene("city", image / 255.0, camera)


def test_a_scene_from_toml_takes_its_targets_from_arrays():
    v, f = cube(size=3.0, centre=(0, 1.5, 0))
    text = """
generator = "spaceship"
[limits]
min_len = 4
max_len = 60
max_depth = 12
[volume]
grid = { min = [-2, -1, -2], max = [2, 4, 2], resolution = [16, 20, 16] }
[[volume.target]]
mesh = "block"
[optimizer]
method = "random"
"""
    scene = shapegen.scene_from_toml(text, meshes={"block": (v, f)})
    assert scene.method == "random"
    assert scene.run(generations=2, seed=1).generations == 2
    with pytest.raises(shapegen.SceneError, match="block"):
        shapegen.scene_from_toml(text)
