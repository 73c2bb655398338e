"""Where a generator builds: a target is moved and scaled onto the box of the
generator's typical model, searched there, and the model found is moved back."""

import numpy as np


def typical_box(generator, samples=200, seed=1):
    """The centre and longest side of the generator's typical model: the medians over
    `samples` random models (as the tool's `fit` example places targets)."""
    centres, sides = [], []
    for genome in generator.sample(samples, seed=seed):
        v = generator.model(genome).vertices
        if len(v) == 0:
            continue
        lo, hi = v.min(axis=0), v.max(axis=0)
        centres.append((lo + hi) / 2.0)
        sides.append(float((hi - lo).max()))
    if not sides:
        return np.zeros(3), 1.0
    return np.median(np.array(centres), axis=0), float(np.median(sides))


class Placement:
    """p -> scale * p + offset, from the target's space (shapegen's axes) to where the
    generator builds; identity when `fit` is off."""

    def __init__(self, vertices, generator=None, fit=True):
        self.scale, self.offset = 1.0, np.zeros(3)
        if fit and generator is not None:
            lo, hi = vertices.min(axis=0), vertices.max(axis=0)
            centre, side = typical_box(generator)
            self.scale = side / max(float((hi - lo).max()), 1e-9)
            self.offset = centre - self.scale * (lo + hi) / 2.0

    def forward(self, points):
        return np.asarray(points, dtype=np.float64) * self.scale + self.offset

    def back(self, points):
        return (np.asarray(points, dtype=np.float64) - self.offset) / self.scale
