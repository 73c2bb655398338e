"""The `pagoda` module: a crate's own generator, with the whole shapegen API."""

import numpy as np

import pagoda


def test_the_module_knows_its_generator_and_the_published_ones():
    assert pagoda.generators()[-1] == "pagoda"
    assert "spaceship" in pagoda.generators()
    g = pagoda.generator("Pagoda")
    assert (g.name, g.grammar, g.parts) == ("pagoda", "Pagoda", ["cube"])


def test_its_models_are_arrays_and_repeat_by_seed():
    g = pagoda.generator("pagoda")
    a, b = g.sample(4, seed=2), g.sample(4, seed=2)
    assert a == b
    m = g.model(a[0])
    assert m.vertices.shape == (24 * m.instances, 3)
    assert m.faces.shape == (12 * m.instances, 3)
    assert m.instances >= 2  # the podium and a storey at least
    nested = a[0].to_json(nested=True)
    assert g.genome(nested).to_json(nested=True) == nested


def test_a_search_fills_a_box_with_a_pagoda():
    v = np.array([[x, y, z] for x in (-3, 3) for y in (0, 8) for z in (-3, 3)], dtype=float)
    f = np.array([[0, 1, 3], [0, 3, 2], [4, 6, 7], [4, 7, 5], [0, 4, 5], [0, 5, 1],
                  [2, 3, 7], [2, 7, 6], [0, 2, 6], [0, 6, 4], [1, 5, 7], [1, 7, 3]])
    scene = pagoda.volume_scene("pagoda", v, f, resolution=24, settings={"optimizer": {"method": "ga"}})
    run = scene.run(evaluations=1500, seed=1)
    again = scene.run(evaluations=1500, seed=1, threads=1)
    assert run.best == again.best
    assert run.best_fitness > run.history["best"][0]
    try:
        scene.model(pagoda.generator("spaceship").sample(1)[0])
    except pagoda.GenomeError as err:
        assert "not of `pagoda`" in str(err)
    else:
        raise AssertionError("a spaceship is not a pagoda")
