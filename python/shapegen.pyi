"""Controlled procedural modeling: search a procedural generator's derivation trees for
models that meet a goal.

A *generator* makes models; every model is a derivation tree, a *genome*. A *scene*
says what a search aims at (a volume to fill, silhouettes to match) and how it searches
(method, settings, seed, budget). `Scene.run` searches and returns the best genome;
`Scene.model` (or `Generator.model`) turns a genome into numpy arrays of triangles.

    import shapegen
    scene = shapegen.open_scene("scenes/paper/spaceship_volume.toml")
    run = scene.run(method="ga", seconds=10, seed=1)
    model = scene.model(run.best)
    model.vertices, model.faces, model.parts, model.part_names
"""

from os import PathLike
from pathlib import Path
from typing import Any, Callable, Dict, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

__version__: str

ArrayLike = npt.ArrayLike
Settings = Mapping[str, Any]

class ShapegenError(ValueError):
    """What shapegen refused or could not do; the message says what and why."""

class SceneError(ShapegenError):
    """A scene that cannot be read or used: the file, the key and the reason."""

class GenomeError(ShapegenError):
    """A genome that is not one of the generator's: the gene or path at fault."""

class SearchError(ShapegenError):
    """A search that could not start or go on."""

class GeneratorError(ShapegenError):
    """An unknown generator, or a name that cannot be registered."""

def generators() -> List[str]:
    """The names of the generators this module knows."""

def generator(name: str) -> Generator:
    """The generator named `name` (or whose grammar is `name`); `GeneratorError` names
    the known ones otherwise."""

def open_scene(
    path: Union[str, PathLike],
    *,
    method: Optional[str] = None,
    seed: Optional[int] = None,
    seconds: Optional[float] = None,
    evaluations: Optional[int] = None,
    generations: Optional[int] = None,
    set: Optional[Sequence[str]] = None,
) -> Scene:
    """Opens a scene file (TOML; paths in it are relative to its folder). The keyword
    arguments override its `[optimizer]` as the tool's flags do; `set` holds
    `key=value` overrides of any key, as the tool's `--set`."""

def resume(
    folder: Union[str, PathLike],
    *,
    threads: Optional[int] = None,
    progress: Optional[Callable[[Progress], Optional[bool]]] = None,
    backend: str = "auto",
    method: Optional[str] = None,
    seed: Optional[int] = None,
    seconds: Optional[float] = None,
    evaluations: Optional[int] = None,
    generations: Optional[int] = None,
    set: Optional[Sequence[str]] = None,
) -> Run:
    """Goes on with the search saved in run folder `folder` (its `checkpoint.json`,
    written by `Scene.run(checkpoint=...)` or by `shapegen run`) to its budget, saving
    there as it goes. The scene is the one the checkpoint names; the keyword arguments
    override the settings it started with, as the tool's flags do with `--resume`."""

def scene_from_toml(
    text: str,
    *,
    path: Optional[Union[str, PathLike]] = None,
    meshes: Optional[Mapping[str, Tuple[ArrayLike, ArrayLike]]] = None,
    images: Optional[Mapping[str, ArrayLike]] = None,
) -> Scene:
    """The scene written in `text`, read as if from `path` (`scene.toml` in the working
    folder by default). A `[[volume.target]] mesh` naming a key of `meshes` (vertices
    N x 3, faces M x 3) or a `[[silhouette.target]] image` naming a key of `images`
    takes the array instead of a file."""

def volume_scene(
    generator: str,
    vertices: ArrayLike,
    faces: ArrayLike,
    *,
    resolution: int = 64,
    margin: float = 0.05,
    target: Optional[Settings] = None,
    settings: Optional[Settings] = None,
) -> Scene:
    """A scene whose goal is to fill the mesh (vertices N x 3, faces M x 3 vertex
    indices, counter-clockwise seen from outside) with the generator's models: a voxel
    grid over the mesh's bounding box grown by `margin` of its size, `resolution` cubic
    voxels along its longest side. `target` adds keys of `[[volume.target]]` (`inside`,
    `outside`, `fill="winding"` for an open mesh), `settings` keys of the scene
    (`{"optimizer": {"method": "ga"}}`, `{"fitness": {"form": "iou"}}`, `{"limits":
    {...}}`; the generator's limits by default). The mesh is used where it is."""

def silhouette_scene(
    generator: str,
    image: ArrayLike,
    camera: Settings,
    *,
    target: Optional[Settings] = None,
    settings: Optional[Settings] = None,
) -> Scene:
    """A scene whose goal is the silhouette `image` seen through `camera`. The image is
    H x W `uint8` (the target black), H x W `bool` (the target `True`), or H x W x 3 /
    x 4 `uint8`. `camera` is a scene's camera table: `phi`, `theta`, `radius`,
    `lookat`, `fov`, `near`, `far`, `width`, `height` (an orbit camera), or `view` and
    `projection` (4 x 4 nested lists) with `width` and `height`; its size must be the
    image's. `target` adds keys of `[[silhouette.target]]` (`threshold`, `alpha`,
    `kind`), `settings` keys of the scene."""

class Generator:
    """A generator: random models, genomes read from JSON, models of genomes."""

    @property
    def name(self) -> str:
        """The name scenes use."""
    @property
    def grammar(self) -> str:
        """The grammar's name in Rust."""
    @property
    def parts(self) -> List[str]:
        """The generator's meshes (the parts of its models), by id."""
    @property
    def limits(self) -> Dict[str, int]:
        """`min_len`, `max_len`, `max_depth`: the limits random models keep."""
    def sample(
        self,
        count: int = 1,
        *,
        seed: int = 0,
        max_len: Optional[int] = None,
        max_depth: Optional[int] = None,
    ) -> List[Genome]:
        """Random models from the generator's own distribution, as `shapegen sample`
        draws them (model `i` from stream `i` of `seed`)."""
    def genome(self, json: str) -> Genome:
        """Reads a genome from JSON of either form, packed or nested."""
    def model(self, genome: Genome) -> Model:
        """The model of `genome` with the generator's own meshes."""

class Genome:
    """A derivation tree of one generator."""

    @property
    def generator(self) -> str:
        """The generator it belongs to."""
    @property
    def genes(self) -> int:
        """Its genes."""
    def to_json(self, *, nested: bool = False) -> str:
        """The packed JSON form, as the tool saves genomes (`best.genome.json`), or the
        nested form, made to be read and edited."""
    def __len__(self) -> int: ...
    def __eq__(self, other: object) -> bool:
        """Equal when the packed forms are: the same genes in the same order."""
    def __hash__(self) -> int: ...

class Model:
    """A model's triangles in world space, each with its part."""

    @property
    def vertices(self) -> npt.NDArray[np.float32]:
        """N x 3 vertex positions."""
    @property
    def faces(self) -> npt.NDArray[np.uint32]:
        """M x 3 vertex indices, counter-clockwise seen from outside."""
    @property
    def parts(self) -> npt.NDArray[np.uint32]:
        """M part indices into `part_names`, one per triangle."""
    @property
    def part_names(self) -> List[str]:
        """The generator's meshes, by id: one material per part."""
    @property
    def part_colors(self) -> npt.NDArray[np.float32]:
        """K x 3 linear RGB colours of the parts, as in the tool's exports."""
    @property
    def instances(self) -> int:
        """The mesh instances the model places."""

class Progress:
    """A generation of a search, as the progress callback sees it."""

    @property
    def generation(self) -> int:
        """Generations after the initial population (0: the initial population)."""
    @property
    def elapsed_s(self) -> float: ...
    @property
    def evaluations(self) -> int: ...
    @property
    def best_fitness(self) -> float: ...
    @property
    def mean(self) -> float:
        """The current population's mean fitness."""
    @property
    def best(self) -> Genome:
        """The best genome so far."""

class Run:
    """What a search found."""

    @property
    def best(self) -> Genome: ...
    @property
    def best_fitness(self) -> float: ...
    @property
    def evaluations(self) -> int: ...
    @property
    def generations(self) -> int: ...
    @property
    def elapsed_s(self) -> float: ...
    @property
    def stopped(self) -> str:
        """`"generations"`, `"evaluations"`, `"time"` or `"interrupted"`."""
    @property
    def backend(self) -> str:
        """`"CPU"` or the GPU that counted."""
    @property
    def history(self) -> Dict[str, np.ndarray]:
        """The fitness curve, one entry per generation: `generation`, `elapsed_s`,
        `evaluations`, `best`, `mean`, `std` (the tool's `fitness.csv`)."""

class Scene:
    """What a search aims at, and how it searches."""

    @property
    def generator(self) -> str: ...
    @property
    def path(self) -> Path:
        """The scene file, or the path its text was read as."""
    @property
    def method(self) -> str:
        """`ga`, `smc`, `sosmc`, `rjmcmc`, `hybrid` or `random`."""
    @property
    def seed(self) -> int: ...
    @property
    def limits(self) -> Dict[str, int]: ...
    def with_settings(
        self,
        *,
        method: Optional[str] = None,
        seed: Optional[int] = None,
        seconds: Optional[float] = None,
        evaluations: Optional[int] = None,
        generations: Optional[int] = None,
        set: Optional[Sequence[str]] = None,
    ) -> Scene:
        """The same scene with other settings (as `open_scene`'s)."""
    def run(
        self,
        *,
        method: Optional[str] = None,
        seed: Optional[int] = None,
        seconds: Optional[float] = None,
        evaluations: Optional[int] = None,
        generations: Optional[int] = None,
        set: Optional[Sequence[str]] = None,
        threads: Optional[int] = None,
        progress: Optional[Callable[[Progress], Optional[bool]]] = None,
        backend: str = "auto",
        checkpoint: Optional[Union[str, PathLike]] = None,
        resume: bool = False,
    ) -> Run:
        """Searches to the budget, with the GIL released (other Python threads run).
        The keyword arguments override the scene's settings as `open_scene`'s do; the
        same scene and seed give the tool's `shapegen run` result, for any `threads`.
        `progress(p)` is called after every generation; returning `False` stops the
        run, an exception it raises stops it and is raised here. `backend` is
        `"auto"` (a hardware GPU when there is one), `"cpu"` or `"gpu"`. With
        `checkpoint` (a folder) the search saves `checkpoint.json` there as the tool
        does (every second and at the end, replacing one there); with `resume=True`
        it goes on from the one there, ending as a search never interrupted."""
    def score(self, genomes: Sequence[Genome], *, backend: str = "auto") -> List[float]:
        """The fitness of each genome, as `shapegen score` gives it."""
    def sample(self, count: int = 1, *, seed: int = 0) -> List[Genome]:
        """Random models within the scene's limits."""
    def genome(self, json: str) -> Genome:
        """Reads a genome of the scene's generator from JSON."""
    def model(self, genome: Genome) -> Model:
        """The model of `genome` with the scene's meshes, on its lot."""
