"""A search in a background thread: the interface goes on while it runs (the package
releases the GIL), and the best model so far is handed over for the scene."""

import queue
import threading


class Background:
    """Runs `scene.run(**settings)` in a thread. `latest()` gives the best genome found
    since the last call (or None); `stop()` ends the search after its generation."""

    def __init__(self, scene, **settings):
        self.scene = scene
        self.settings = settings
        self.found = queue.Queue()
        self.stopping = threading.Event()
        self.result = None
        self.error = None
        self.best_fitness = None
        self.generation = 0
        self.thread = threading.Thread(target=self._run, daemon=True)

    def start(self):
        self.thread.start()
        return self

    def _progress(self, p):
        if self.best_fitness is None or p.best_fitness > self.best_fitness:
            self.found.put(p.best)
        self.best_fitness = p.best_fitness
        self.generation = p.generation
        return not self.stopping.is_set()

    def _run(self):
        try:
            self.result = self.scene.run(progress=self._progress, **self.settings)
            self.found.put(self.result.best)
        except Exception as err:  # reported by the operator
            self.error = err

    def latest(self):
        best = None
        while True:
            try:
                best = self.found.get_nowait()
            except queue.Empty:
                return best

    def running(self):
        return self.thread.is_alive()

    def stop(self):
        self.stopping.set()

    def wait(self, timeout=None):
        self.thread.join(timeout)
        return not self.thread.is_alive()
