"""Shared fixtures: the repository's scenes, and the `shapegen` tool to compare with."""

import os
import pathlib
import shutil
import subprocess

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]


@pytest.fixture
def scenes():
    """The repository's scenes folder."""
    return ROOT / "scenes"


@pytest.fixture(scope="session")
def tool():
    """The command that runs the `shapegen` tool: $SHAPEGEN_BIN, or `cargo run` in the
    repository. A missing tool fails the tests that need it."""
    binary = os.environ.get("SHAPEGEN_BIN")
    if binary:
        assert pathlib.Path(binary).is_file(), f"SHAPEGEN_BIN={binary} is not a file"
        return [binary]
    cargo = shutil.which("cargo")
    assert cargo, "the tool is needed: set SHAPEGEN_BIN to a built `shapegen`, or put cargo on PATH"
    subprocess.run([cargo, "build", "--quiet", "--bin", "shapegen"], cwd=ROOT, check=True)
    return [cargo, "run", "--quiet", "--bin", "shapegen", "--"]


def cube(size=1.0, centre=(0.0, 0.0, 0.0)):
    """A closed cube as (vertices, faces), faces counter-clockwise seen from outside."""
    import numpy as np

    h = size / 2.0
    v = np.array(
        [[x, y, z] for x in (-h, h) for y in (-h, h) for z in (-h, h)], dtype=np.float64
    ) + np.asarray(centre)
    f = np.array(
        [
            [0, 1, 3], [0, 3, 2],  # -x
            [4, 6, 7], [4, 7, 5],  # +x
            [0, 4, 5], [0, 5, 1],  # -y
            [2, 3, 7], [2, 7, 6],  # +y
            [0, 2, 6], [0, 6, 4],  # -z
            [1, 5, 7], [1, 7, 3],  # +z
        ]
    )
    return v, f
