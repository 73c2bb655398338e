"""The README's Python example runs as written (from the repository's root folder)."""

import pathlib
import re

ROOT = pathlib.Path(__file__).resolve().parents[2]


def example():
    readme = (ROOT / "README.md").read_text()
    section = readme.split("## From Python and Blender", 1)[1]
    blocks = re.findall(r"```python\n(.*?)```", section, re.S)
    assert blocks, "the README's Python section has no python block"
    return blocks[0]


def test_the_readme_example_fits_a_spaceship_and_plots_its_curve(tmp_path, monkeypatch):
    import matplotlib

    matplotlib.use("Agg")
    (tmp_path / "scenes").symlink_to(ROOT / "scenes")
    monkeypatch.chdir(tmp_path)
    namespace = {}
    exec(compile(example(), "README.md", "exec"), namespace)
    run = namespace["run"]
    assert run.stopped == "time"
    assert run.best_fitness > 0.5  # the voxel IoU of the model found
    for name in ("spaceship.glb", "spaceship.genome.json", "fitness.png"):
        assert (tmp_path / name).stat().st_size > 0, name
