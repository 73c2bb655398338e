"""The search speed from Python against the tool's: the same scene, method, seed and
evaluation budget, run alternately in fresh processes; each pair must give the same best
genome. Prints one Markdown row per scene: the median wall time of the search (its
`elapsed_s`: the tool's summary.json, the package's Run) and of the whole process.

    python python/bench/speed.py target/release/shapegen [--repeats 5] [--threads 2]

Run it with the `shapegen` package installed from a release build (`pip install
./python`) and the tool built with `cargo build --release`.
"""

import argparse
import json
import pathlib
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = pathlib.Path(__file__).resolve().parents[2]

CASES = [
    ("scenes/paper/spaceship_volume.toml", "ga", 30000),
    ("scenes/paper/city_whale.toml", "ga", 30000),
    ("scenes/paper/tree_sketch1.toml", "ga", 20000),
    ("scenes/paper/spaceship_volume.toml", "hybrid", 30000),
]

PYTHON = """
import json, sys, shapegen
scene, method, evaluations, threads = sys.argv[1], sys.argv[2], int(sys.argv[3]), int(sys.argv[4])
run = shapegen.open_scene(scene).run(method=method, seed=1, evaluations=evaluations, threads=threads, backend="cpu")
print(json.dumps({"elapsed_s": run.elapsed_s, "genome": run.best.to_json(), "fitness": run.best_fitness}))
"""


def tool(binary, scene, method, evaluations, threads):
    with tempfile.TemporaryDirectory() as out:
        start = time.perf_counter()
        subprocess.run(
            [binary, "--threads", str(threads), "run", scene, "--method", method, "--seed", "1",
             "--evaluations", str(evaluations), "--cpu", "--out", out],
            check=True, capture_output=True,
        )
        wall = time.perf_counter() - start
        summary = json.loads((pathlib.Path(out) / "summary.json").read_text())
        genome = (pathlib.Path(out) / "best.genome.json").read_text()
        return summary["elapsed_s"], wall, genome, summary["best_fitness"]


def python(scene, method, evaluations, threads):
    start = time.perf_counter()
    done = subprocess.run(
        [sys.executable, "-c", PYTHON, scene, method, str(evaluations), str(threads)],
        check=True, capture_output=True, text=True,
    )
    wall = time.perf_counter() - start
    r = json.loads(done.stdout)
    return r["elapsed_s"], wall, r["genome"], r["fitness"]


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("tool")
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--threads", type=int, default=2)
    args = parser.parse_args()
    print("| scene | method | evaluations | best fitness | search: tool | search: Python | process: tool | process: Python |")
    print("|---|---|---|---|---|---|---|---|")
    for scene, method, evaluations in CASES:
        scene_path = str(ROOT / scene)
        t, p = [], []
        for _ in range(args.repeats):
            a = tool(args.tool, scene_path, method, evaluations, args.threads)
            b = python(scene_path, method, evaluations, args.threads)
            assert a[2] == b[2] and a[3] == b[3], f"{scene} {method}: the best genomes differ"
            t.append(a)
            p.append(b)
        med = lambda xs, i: statistics.median(x[i] for x in xs)
        print(f"| `{scene}` | {method} | {evaluations} | {t[0][3]:.4f} | {med(t, 0):.3f} s | {med(p, 0):.3f} s "
              f"| {med(t, 1):.3f} s | {med(p, 1):.3f} s |", flush=True)


if __name__ == "__main__":
    main()
