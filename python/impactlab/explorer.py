"""The explorer from Python: `impactlab explore` started as a subprocess
for a notebook, shown inline as an IFrame of its page (impactlab.explore)."""
import os
import pathlib
import re
import shutil
import subprocess
import tempfile
import threading


def explorer_program():
    """The `impactlab` program that serves the page: $IMPACTLAB_CLI, else the
    one on PATH, else the one of the build tree this package was built in."""
    chosen = os.environ.get("IMPACTLAB_CLI")
    if chosen:
        return chosen
    on_path = shutil.which("impactlab")
    if on_path:
        return on_path
    built = pathlib.Path(__file__).resolve().parent.parent.parent / "impactlab"
    if built.is_file():
        return str(built)
    raise RuntimeError("explore needs the impactlab program: put it on PATH or set IMPACTLAB_CLI")


class Explorer:
    """A running explorer: `url` (with its token), shown inline in Jupyter as
    an IFrame of the page; stop() ends the server (as does leaving a `with`)."""

    def __init__(self, scene_source, port, height=1100, scene_folder=None):
        self.height = height
        self._scene_folder = scene_folder  # a Scene given as an object: its file's folder
        self._process = subprocess.Popen(
            [explorer_program(), "explore", scene_source, "--port", str(port)],
            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        self.url = None
        for line in self._process.stdout:
            match = re.search(r"http://127\.0\.0\.1:\d+/\?token=[0-9a-f]+", line)
            if match:
                self.url = match.group(0)
                break
        if self.url is None:
            message = self._process.stderr.read().strip()
            self._process.wait()
            raise ValueError(message.removeprefix("impactlab: ") or "explore did not start")
        # the server's later output is read away, so that a full pipe never stops it
        for stream in (self._process.stdout, self._process.stderr):
            threading.Thread(target=stream.read, daemon=True).start()

    @property
    def running(self):
        return self._process.poll() is None

    def stop(self):
        """Ends the server (its jobs with it)."""
        if self.running:
            self._process.terminate()
            try:
                self._process.wait(timeout=10)
            except subprocess.TimeoutExpired:
                self._process.kill()
                self._process.wait()
        if self._scene_folder is not None:
            self._scene_folder.cleanup()
            self._scene_folder = None

    def __enter__(self):
        return self

    def __exit__(self, *exception):
        self.stop()

    def __del__(self):
        if getattr(self, "_process", None) is not None:
            self.stop()

    def __repr__(self):
        return "Explorer({}, {})".format(self.url, "running" if self.running else "stopped")

    def _repr_html_(self):
        return ('<iframe src="{}" width="100%" height="{}" style="border: 1px solid #ddd">'
                '</iframe>'.format(self.url, self.height))


def start_explorer(scene, port):
    """An Explorer of `scene`: a built-in name, a path, or a Scene object
    (written to a scene file of its own for the server)."""
    if isinstance(scene, str):
        return Explorer(scene, port)
    folder = tempfile.TemporaryDirectory(prefix="impactlab-explore-")
    path = os.path.join(folder.name, "scene.toml")
    scene.save(path)
    return Explorer(path, port, scene_folder=folder)
