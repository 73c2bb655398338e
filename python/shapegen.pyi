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

`Scene.compare` runs several methods several times each, as `shapegen compare` does;
`Scene.run_front` searches a multi-objective scene's front, as `shapegen run` does.
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

class ComparedRun:
    """One finished run of a comparison: a search of the scene with its method and
    seed (`Scene.run(method=run.method, seed=run.seed)` with the comparison's budget
    repeats it)."""

    @property
    def method(self) -> str: ...
    @property
    def run(self) -> int:
        """The run's number among the method's runs, from 0."""
    @property
    def seed(self) -> int:
        """The comparison's base seed plus `run`."""
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
        """`"evaluations"` or `"time"`."""
    @property
    def history(self) -> Dict[str, np.ndarray]:
        """The fitness curve, as `Run.history`."""
    @property
    def metrics(self) -> Dict[str, Any]:
        """The best model's measures against the scene's targets, as the tool's
        `summary.json` gives them: `genes`, `instances`, `triangles`, and where the
        scene has such targets `voxel_iou`, `surface` (`chamfer`, `f_score`),
        `silhouette_iou` (per target image), `point_clouds`."""

class MethodSummary:
    """One method's summary over its runs, as the tool's `summary.json` gives it."""

    @property
    def method(self) -> str: ...
    @property
    def runs(self) -> int:
        """Its finished runs."""
    @property
    def final_mean(self) -> float:
        """The mean over runs of each run's final best fitness."""
    @property
    def final_std(self) -> float:
        """Their sample standard deviation (0 for one run)."""
    @property
    def final_quartiles(self) -> Tuple[float, float, float]:
        """Their first quartile, median and third quartile."""
    @property
    def best(self) -> float:
        """The best fitness of all runs (the worst is `finals.min()`)."""
    @property
    def best_run(self) -> Optional[int]:
        """The run that found it."""
    @property
    def evaluations(self) -> float:
        """The mean evaluations per run."""
    @property
    def finals(self) -> npt.NDArray[np.float64]:
        """Each run's final best fitness, by run."""
    @property
    def metrics(self) -> List[Dict[str, Any]]:
        """Each run's best model's measures, by run (as `ComparedRun.metrics`)."""
    @property
    def targets(self) -> Optional[List[Dict[str, Any]]]:
        """With the scene's optimum (`fitness.optimum`): per fraction of it (0.9, 0.99,
        0.999) its `level`, the `runs`, how many `reached` it, and the quartiles of the
        `seconds` and `evaluations` it took (`None` where too few reached it), as the
        tool's `targets.csv`; `None` without an optimum."""

class Comparison:
    """What `Scene.compare` did: every finished run and each method's summary."""

    @property
    def methods(self) -> List[str]:
        """The methods, in the order they ran."""
    @property
    def seeds(self) -> List[int]:
        """The seed of each run, by run number: the base seed and those after it."""
    @property
    def seconds(self) -> Optional[float]:
        """The wall-time budget of every run, if one was given."""
    @property
    def backend(self) -> str:
        """`"CPU"` or the GPU that counted."""
    @property
    def optimum(self) -> Optional[float]:
        """The scene's `fitness.optimum`, if it gives one."""
    @property
    def runs(self) -> List[ComparedRun]:
        """The finished runs, run-major (run 0 of every method, then run 1, ...): the
        rows of the tool's `runs.csv`."""
    @property
    def summaries(self) -> Dict[str, MethodSummary]:
        """Each method's summary by its name, in the order they ran: the `methods` of
        the tool's `summary.json`."""
    @property
    def complete(self) -> bool:
        """Whether every planned run finished."""
    @property
    def interrupted(self) -> Optional[Tuple[str, int]]:
        """The run `(method, run)` that was interrupted (not among `runs`), if any."""

class FrontMember:
    """A member of a multi-objective search's front."""

    @property
    def genome(self) -> Genome: ...
    @property
    def values(self) -> Dict[str, float]:
        """Its value of each objective, by name, in the scene's order."""

class FrontProgress:
    """A generation of a multi-objective search, as the progress callback sees it."""

    @property
    def generation(self) -> int:
        """Generations after the initial population (0: the initial population)."""
    @property
    def elapsed_s(self) -> float: ...
    @property
    def evaluations(self) -> int: ...
    @property
    def front(self) -> int:
        """Members of the front so far."""
    @property
    def best(self) -> Dict[str, float]:
        """Per objective, the best value evaluated so far."""

class Front:
    """What `Scene.run_front` found: the front of non-dominated models."""

    @property
    def objectives(self) -> List[str]:
        """The objectives' names, in the scene's order."""
    @property
    def kinds(self) -> List[str]:
        """Their kinds, as scene files name them (`top_match`, ...)."""
    @property
    def senses(self) -> List[str]:
        """`"maximize"` or `"minimize"`, per objective."""
    @property
    def ranking(self) -> str:
        """The selection's ranking (`pareto`, `weighted_sum`, ...)."""
    @property
    def members(self) -> List[FrontMember]:
        """Best first by the first objective (then the others): the order of the
        tool's `front.csv` and `front.genomes.json`."""
    @property
    def values(self) -> npt.NDArray[np.float64]:
        """N x K objective values: a row per member, a column per objective."""
    @property
    def genomes(self) -> List[Genome]:
        """The members' genomes, in order."""
    def models(self) -> List[Model]:
        """The members' models with the scene's meshes, on its lot, in order."""
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
    def history(self) -> Dict[str, np.ndarray]:
        """One entry per generation: `generation`, `elapsed_s`, `evaluations`, `front`
        (its size) and `best_NAME` per objective (the tool's `history.csv`)."""
    def __len__(self) -> int: ...

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
    @property
    def objectives(self) -> List[str]:
        """The `[[objective]]` names of a multi-objective scene, searched by
        `run_front`; empty for a scene with one fitness."""
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
        it goes on from the one there, ending as a search never interrupted. A
        multi-objective scene raises `SceneError`: `run_front` searches it."""
    def compare(
        self,
        methods: Optional[Sequence[str]] = None,
        *,
        runs: int = 3,
        seed: Optional[int] = None,
        seconds: Optional[float] = None,
        evaluations: Optional[int] = None,
        set: Optional[Sequence[str]] = None,
        threads: Optional[int] = None,
        progress: Optional[Callable[[ComparedRun], Optional[bool]]] = None,
        backend: str = "auto",
    ) -> Comparison:
        """Compares `methods` (every method by default) as `shapegen compare` does:
        `runs` runs of each, run `r` of every method on seed `seed + r` (the scene's
        seed by default), run-major, each to `seconds` of wall time and to the
        evaluation budget (`evaluations`, or the scene's; give one or both), the
        methods' own generation counts no limit. Each method takes its settings as
        `run(method=...)` would; `set` overrides keys, read as each method's.
        `progress(run)` is called after every finished run; returning `False` ends the
        comparison there, an exception it raises ends it and is raised here. The
        numbers are those of the tool's `runs.csv` and `summary.json` for the same
        scene, seed and evaluation budget."""
    def run_front(
        self,
        *,
        seed: Optional[int] = None,
        seconds: Optional[float] = None,
        evaluations: Optional[int] = None,
        generations: Optional[int] = None,
        set: Optional[Sequence[str]] = None,
        threads: Optional[int] = None,
        progress: Optional[Callable[[FrontProgress], Optional[bool]]] = None,
    ) -> Front:
        """Searches a multi-objective scene's front (its `[[objective]]` tables) with
        the multi-objective GA, as `shapegen run` does, to the budget (the keyword
        arguments override the scene's settings as `run`'s do), on the CPU with the
        GIL released. The same scene and seed give the front the tool writes
        (`front.csv`, `front.genomes.json`), for any `threads`. `progress(p)` is
        called after every generation; returning `False` stops the search."""
    def score(self, genomes: Sequence[Genome], *, backend: str = "auto") -> List[float]:
        """The fitness of each genome, as `shapegen score` gives it."""
    def sample(self, count: int = 1, *, seed: int = 0) -> List[Genome]:
        """Random models within the scene's limits."""
    def genome(self, json: str) -> Genome:
        """Reads a genome of the scene's generator from JSON."""
    def model(self, genome: Genome) -> Model:
        """The model of `genome` with the scene's meshes, on its lot."""
