"""impactlab from Python: the scene API of the C++ toolkit (docs/python.md).

    import impactlab
    run = impactlab.simulate("jin2003", V0=4.163, periods=100)
    run.events["t"], run.events["q"], run.meta["counts"]["impacts"]

Every function takes a scene (a built-in name, a path to a .toml file, or a
Scene from impactlab.scene) and the scene's keys as keyword arguments, the
dotted ones spelled with "__" (initial__theta=0.1) or passed as
**{"initial.theta": 0.1}. They are checked exactly as `impactlab ... --set`
checks them: bad input raises ValueError naming the key and the value, and a
key that the scene's model does not read gives an UnreadKeyWarning.
"""

import builtins
import math
import numbers
import os
import re
import sys
import warnings

import numpy as np

from . import _impactlab
from .explorer import Explorer, start_explorer

__all__ = [
    "Scene", "scenes", "scene", "simulate", "poincare", "sweep", "basins", "attractors",
    "periodic", "compare", "bench", "continue_", "explore", "Explorer", "EventArray", "Table",
    "Result", "RunResult", "SectionResult", "SweepResult", "BasinsResult", "AttractorsResult",
    "ComparisonResult", "WorkPrecisionResult", "ContinuationResult", "EVENT_KINDS",
    "PhysicalDiagnosticWarning", "UnreadKeyWarning", "__version__",
]


def __dir__():
    """The API (what __all__ lists), not the modules the package imports."""
    return sorted(__all__)

Scene = _impactlab.Scene

#: the toolkit's version, as meta.json's impactlab_version writes it
__version__ = _impactlab.version

#: names of the `kind` codes in an event array, by code
EVENT_KINDS = tuple(_impactlab.event_kind_names())


class PhysicalDiagnosticWarning(UserWarning):
    """A run stopped early by a physical diagnostic (the CLI's exit status 3)."""


class UnreadKeyWarning(UserWarning):
    """A key set that the scene's model does not read (jin2003's e_t under
    model = newton): the value changes nothing (the CLI's warning line)."""


class EventArray(np.ndarray):
    """The event log: a structured array with the columns of events.csv
    (`kind` holds codes; `kind_names()` gives their names)."""

    def kind_names(self):
        return np.array(EVENT_KINDS, dtype=object)[np.asarray(self["kind"], dtype=np.intp)]

    def __getattr__(self, name):
        # a column by attribute, as every result's fields (events.t)
        if name in (self.dtype.names or ()):
            return self[name]
        raise AttributeError("no column {!r}; the columns: {}".format(
            name, ", ".join(self.dtype.names or ())))

    def to_pandas(self):
        import pandas  # optional dependency

        frame = pandas.DataFrame({name: np.asarray(self[name]) for name in self.dtype.names})
        frame["kind"] = self.kind_names()
        return frame


class Table(dict):
    """Columns by name (a CSV file's: NumPy arrays, or lists of words), read
    as a dict (table["period"]) or as attributes (table.period); a column
    whose name is not an identifier ("initial.y") by its key only."""

    def __getattr__(self, name):
        try:
            return self[name]
        except KeyError:
            raise AttributeError("no column {!r}; the columns: {}".format(
                name, ", ".join(self))) from None

    def __dir__(self):
        return sorted(set(dir(dict)) | {name for name in self if name.isidentifier()})

    def to_pandas(self):
        import pandas  # optional dependency

        return pandas.DataFrame({name: np.asarray(column) for name, column in self.items()})


class Result:
    """A job's result: its fields as attributes (see docs/python.md).

    `plot()` draws what the CLI's --plot draws for the job, from the same
    numbers, with the plot scripts' own drawing functions (impactlab.figures):
    one figure, not two that can drift apart."""

    #: the figures plot() draws (`which`), the CLI's --plot's first; a result
    #: type of a job the CLI draws nothing for has none
    FIGURES = ()

    def __init__(self, **fields):
        self.__dict__.update(fields)

    def __repr__(self):
        return "{}({})".format(type(self).__name__, ", ".join(sorted(self.__dict__)))

    def plot(self, path=None, which=None, **extra):
        """The figure the CLI's --plot draws for this job, as a matplotlib
        Figure; with path, also written there as the CLI writes its PNG
        (whole or not at all). which: one of FIGURES (None: the first)."""
        if not self.FIGURES:
            raise TypeError("{} draws no figure (the CLI draws none for this job)".format(
                type(self).__name__))
        which = self.FIGURES[0] if which is None else which
        if which not in self.FIGURES:
            raise ValueError("which = {!r}: expected {}".format(which, " or ".join(
                repr(name) for name in self.FIGURES)))
        from .figures import plot_files  # matplotlib is needed only to draw

        figure = self._draw(which, **extra)
        if path is not None:
            plot_files.save_figure(figure, os.fspath(path))
        return figure

    def _run_record(self):
        """The scene's part of the run's record: what the figures' labels,
        units and titles are read from (meta.json's "scene")."""
        meta = self.__dict__.get("meta")
        return meta if meta and "scene" in meta else {"scene": self.scene.record()}


class RunResult(Result):
    """simulate's result; `meta` (meta.json's content) is made on first use.
    plot(): the coordinate against time with the walls, the impacts and the
    contact phases, and the phase portrait (needs simulate(..., sample=DT))."""

    FIGURES = ("simulation",)

    @property
    def meta(self):
        if "_meta" not in self.__dict__:
            self._meta = self._pending_record.meta()
        return self._meta

    def _run_record(self):
        return self.meta

    def _draw(self, which):
        from .figures import plot_simulation

        if len(self.trajectory.t) == 0:
            raise ValueError("plot: the run recorded no trajectory; simulate(..., sample=DT) "
                             "records one")
        events = {"kind": self.events.kind_names().astype(str), "t": self.events["t"],
                  "q": self.events["q"]}
        return plot_simulation.draw_simulation(
            {"t": self.trajectory.t, "q": self.trajectory.q, "qdot": self.trajectory.qdot},
            events, self.meta)


class SectionResult(Result):
    """poincare's result. plot(): the section points (which="section"), or
    the running estimates of the Lyapunov spectrum (which="lyapunov", with
    lyapunov_spectrum=True)."""

    FIGURES = ("section", "lyapunov")

    def _draw(self, which):
        from .figures import plot_lyapunov, plot_sweep

        if which == "section":
            return plot_sweep.draw_poincare({"q": self.q, "qdot": self.qdot}, self._run_record(),
                                            self.scene.main_coordinate)
        if "lyapunov_running" not in self.__dict__:
            raise ValueError("which = 'lyapunov': the run has no spectrum; "
                             "poincare(..., lyapunov_spectrum=True) computes one")
        running = {"t": self.lyapunov_running_t}
        for index in range(self.lyapunov_running.shape[1]):
            running["lambda{}".format(index + 1)] = self.lyapunov_running[:, index]
        return plot_lyapunov.draw_spectrum(running, self._run_record())


class SweepResult(Result):
    """sweep's result. plot(): the bifurcation diagram (1D) or the map of
    periods, Lyapunov exponents and sticking impacts (2D), with the points
    that stopped early or did not settle marked."""

    FIGURES = ("sweep",)

    def _draw(self, which):
        from .figures import plot_sweep

        if self.bifurcation is not None:
            return plot_sweep.draw_bifurcation(self.bifurcation, self.summary, self._run_record(),
                                               self.axes[0], self.scene.main_coordinate)
        return plot_sweep.draw_classes(self.summary, self._run_record(), *self.axes)


class BasinsResult(Result):
    """basins' result. plot(): the grid coloured by attractor, with a legend
    of the attractors."""

    FIGURES = ("basins",)

    def _draw(self, which):
        from .figures import plot_basins

        return plot_basins.draw_basins(self.grid, self.attractors, self._run_record(), *self.axes)


class AttractorsResult(Result):
    """attractors' result. plot(): the basin fractions stacked against the
    parameter, beside the attractors' section points coloured by id, with the
    appear, vanish, merge and split events marked."""

    FIGURES = ("attractors",)

    def _draw(self, which):
        from .figures import plot_attractors

        return plot_attractors.draw_attractors(self.attractors, self.points, self.meta,
                                               self.param, self.scene.main_coordinate)


class ComparisonResult(Result):
    """compare's result. plot(): the rates before impact, the contact
    intervals and the strobe section, one colour per model."""

    FIGURES = ("compare",)

    def _draw(self, which):
        from .figures import plot_compare, plot_files

        tables = [plot_files.parse_columns(text)
                  for text in (self.impacts_csv, self.contacts_csv, self.section_csv)]
        return plot_compare.draw_compare(*tables, self._run_record())


class WorkPrecisionResult(Result):
    """bench's result. plot(): the largest impact-time error against the CPU
    time and against the right-hand sides per impact, one line per method."""

    FIGURES = ("work_precision",)

    def _draw(self, which):
        from .figures import plot_bench

        rows = {"tool": ["impactlab"] * len(self.method), "method": self.method,
                "rtol": self.rtol, "max_time_error": self.impact_time_error,
                "seconds_per_impact": self.seconds_per_impact,
                "rhs_per_impact": self.rhs_per_impact, "compared_impacts": self.impacts_compared,
                "reference_impacts": np.full(len(self.method), self.reference_impacts)}
        reference = {"method": self.reference_method, "time_spread": 0.0,
                     "impacts_compared": self.reference_impacts}
        return plot_bench.draw_work_precision(rows, self.scene.name, reference)


class ContinuationResult(Result):
    """continue_'s result. plot(): the branches, stable solid, unstable
    dashed and without multipliers (an impulse on the friction cone's edge)
    dotted, with the located points (which="branches"; sweep=a 1D sweep's
    result draws its points underneath; y=another column of the branches,
    such as "state3", the rigid pendulum's spin, with y_label its axis
    label), the two-parameter curves
    (which="curve", with param2; sweep=a 2D sweep's result draws its period
    map underneath), or each grazing point's predicted scenario beside a 1D
    sweep through it (which="grazing"; an impact-section sweep's impact
    speeds are drawn under the prediction too)."""

    FIGURES = ("branches", "curve", "grazing")

    def _draw(self, which, sweep=None, y="q", y_label=None):
        from .figures import plot_continuation, plot_curve, plot_grazing

        if sweep is not None and not isinstance(sweep, SweepResult):
            raise ValueError("sweep = {!r}: expected a result of impactlab.sweep".format(sweep))
        record = self._run_record()
        if which == "branches":
            underneath = None
            if sweep is not None:
                if sweep.bifurcation is None:
                    raise ValueError("sweep: a 2D map; the branches are drawn over a 1D sweep")
                underneath = sweep.bifurcation
            return plot_continuation.draw_continuation(
                self.branches, self.points, record, self.parameter, self.scene.main_coordinate,
                underneath, y, y_label)
        if which == "grazing":
            if not self.grazing:
                raise ValueError("which = 'grazing': the run located no grazing point")
            if sweep is not None and sweep.bifurcation is None:
                raise ValueError("sweep: a 2D map; the grazing is drawn beside a 1D sweep")
            return plot_grazing.draw_grazing(
                self.grazing, record, self.parameter,
                None if sweep is None else plot_files_columns(sweep.bifurcation))
        if "curves" not in self.__dict__:
            raise ValueError("which = 'curve': the run followed no curve; continue_(..., "
                             "param2=...) follows one")
        if sweep is not None and sweep.bifurcation is not None:
            raise ValueError("sweep: a 1D sweep; the curve is drawn over a 2D map")
        second = self.parameter2
        kind = self.curves[0].get("type", "curve") if self.curves else "curve"
        return plot_curve.draw_curve(self.curves, kind, record, self.parameter, second,
                                     None if sweep is None else sweep.summary,
                                     self.__dict__.get("curve_points"))


def plot_files_columns(table):
    """A result's table as the plot scripts' columns (impactlab.figures.plot_files)."""
    from .figures import plot_files

    return plot_files.as_columns(table)


def _finite_float(value):
    """A real number as a finite float, or None where it has none (NaN, an
    infinity, an integer past the largest double such as 10**400)."""
    try:
        number = float(value)
    except OverflowError:
        return None
    return number if math.isfinite(number) else None


def _assignment_text(key, value):
    """`value` as --set would spell it; ValueError for a type no key takes."""
    if isinstance(value, bool):
        raise ValueError("{} = {!r}: expected a number or a text value, not a bool".format(key, value))
    if isinstance(value, numbers.Integral):
        return str(int(value))
    if isinstance(value, numbers.Real):
        number = _finite_float(value)
        if number is None:
            raise ValueError("{} = {!r}: not a finite number".format(key, value))
        return repr(number)
    if isinstance(value, str):
        return value
    raise ValueError("{} = {!r}: expected a number or a text value, not {}".format(
        key, value, type(value).__name__))


def scenes():
    """The built-in scenes: a list of dicts with name, oscillator and description."""
    listed = []
    for name in _impactlab.builtin_scene_names():
        loaded = _impactlab.load_scene(name)
        listed.append({"name": name, "oscillator": loaded.oscillator,
                       "description": loaded.values().get("description", "")})
    return listed


def scene(name_or_scene="jin2003", **keys):
    """A scene with keys set: scene("jin2003", V0=4.163, omega=7). A key that
    the scene's model does not read (e_t under model = newton) is set with an
    UnreadKeyWarning."""
    loaded = _with_keys(name_or_scene, keys)
    _warn_unread_keys(loaded, keys)
    return loaded


def _with_keys(name_or_scene, keys):
    """The scene with `keys` set, without the unread-key warnings (compare runs
    models of its own list, each reading its own keys)."""
    if isinstance(name_or_scene, Scene):
        if not keys:
            return name_or_scene  # the jobs do not change a scene
        loaded = name_or_scene.copy()
    elif isinstance(name_or_scene, str):
        loaded = _impactlab.load_scene(name_or_scene)
    else:
        raise ValueError("scene = {!r}: expected a scene name, a path or a Scene".format(name_or_scene))
    for key, value in keys.items():
        dotted = key.replace("__", ".")
        _impactlab.apply_override(loaded, "{}={}".format(dotted, _assignment_text(dotted, value)))
    return loaded


def _warn_unread_keys(loaded, keys):
    """One UnreadKeyWarning per key of `keys` the scene's model does not read,
    worded by the scene API as the CLI's warning line."""
    dotted = [key.replace("__", ".") for key in keys]
    for line in _impactlab.unread_key_warnings(loaded, dotted):
        warnings.warn(line, UnreadKeyWarning, stacklevel=3)


#: every job's options, declared once in the scene API (api/job_options.hpp):
#: {job: {name: row}}, a row holding type, default, lower, upper, lower_open,
#: unit, help, choices, front_ends, required
_OPTIONS = {job: {row["name"]: row for row in _impactlab.job_options(job)}
            for job in _impactlab.job_names()}


def _default(job, name):
    """The keyword default of an option: its table's default (None: unset)."""
    return _OPTIONS[job][name]["default"]


def _spelled(text):
    """A help text with the options it names (`name`) as Python keywords."""
    return re.sub(r"`([A-Za-z0-9_]+)`", r"\1", text)


def _documented(job):
    """Appends the job's options (name, help, unit, default) to the docstring."""
    def document(function):
        lines = ["", "", "Options (the scene API's option table {!r}):".format(job)]
        for row in _OPTIONS[job].values():
            if row["front_ends"] == "cli" or row["for_tests_only"]:
                continue
            unit = " ({})".format(row["unit"]) if row["unit"] else ""
            default = "required" if row["required"] else "default {!r}".format(row["default"])
            lines.append("    {}: {}{}; {}".format(row["name"], _spelled(row["help"]), unit,
                                                  default))
        function.__doc__ = (function.__doc__ or "") + "\n".join(lines) + "\n"
        return function
    return document


def _number(key, value, row=None):
    """`value` as a float within the range of the option's table row."""
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise ValueError("{} = {!r}: expected a number".format(key, value))
    number = _finite_float(value)
    if number is None:
        raise ValueError("{} = {!r}: not a finite number".format(key, value))
    if row is None:
        return number
    lower, upper = row["lower"], row["upper"]
    if math.isinf(upper) and lower == 0.0:
        if row["lower_open"] and not number > 0.0:
            raise ValueError("{} = {!r}: must be > 0".format(key, value))
        if not row["lower_open"] and not number >= 0.0:
            raise ValueError("{} = {!r}: must be >= 0".format(key, value))
    elif not (lower <= number <= upper) or (row["lower_open"] and number == lower):
        raise ValueError("{} = {!r}: expected {:g} to {:g}{}".format(
            key, value, lower, upper, " " + row["unit"] if row["unit"] else ""))
    return number


def _whole(key, value, row):
    """`value` as an int within the range of the option's table row."""
    lowest = int(row["lower"])
    if isinstance(value, bool) or not isinstance(value, numbers.Integral) or value < lowest:
        raise ValueError("{} = {!r}: expected a whole number >= {}".format(key, value, lowest))
    if value > row["upper"]:
        raise ValueError("{} = {!r}: expected {} to {:.0f}".format(
            key, value, lowest, row["upper"]))
    return int(value)


def _option(job, name, value):
    """`value` checked against the option `name` of `job`'s table; ValueError naming it.
    None stays None where the option has no default (unset: the library's own rule)."""
    row = _OPTIONS[job][name]
    if value is None and row["default"] is None and not row["required"]:
        return None
    if row["type"] == "number":
        return _number(name, value, row)
    if row["type"] in ("integer", "count"):
        return _whole(name, value, row)
    if row["type"] == "flag":
        if not isinstance(value, bool):
            raise ValueError("{} = {!r}: expected True or False".format(name, value))
        return value
    if row["type"] == "text" and not isinstance(value, str):
        raise ValueError("{} = {!r}: expected text{}".format(
            name, value, " such as " + " or ".join(row["choices"]) if row["choices"] else ""))
    return value


def _batch(job, value):
    """The option `batch` of `job` as the library takes it: True or "on",
    False or "off"; ValueError naming it otherwise."""
    if isinstance(value, bool):
        return "on" if value else "off"
    if value not in _OPTIONS[job]["batch"]["choices"]:
        raise ValueError("batch = {!r}: expected True, False, \"on\" or \"off\"".format(value))
    return value


def _refuse_excluded(job, given):
    """ValueError where two options of `given` (name -> value) that exclude
    each other are both away from their defaults, as the CLI refuses them."""
    for name, value in given.items():
        other = _OPTIONS[job][name]["excludes"]
        if other and other in given and value != _default(job, name) \
                and given[other] != _default(job, other):
            raise ValueError("{} = {!r}: excludes {} (given {!r})".format(
                name, value, other, given[other]))


class _PlainProgress:
    """A progress line on stderr ("sweep: 42%"), redrawn in place, where tqdm
    is not installed."""

    def __init__(self, label):
        self.label, self.shown = label, -1

    def update(self, fraction):
        percent = int(100 * fraction)
        if percent != self.shown:
            self.shown = percent
            sys.stderr.write("\r{}: {}%".format(self.label, percent))
            sys.stderr.flush()

    def close(self):
        if self.shown >= 0:
            sys.stderr.write("\n")
            sys.stderr.flush()


def _progress(progress, total_label):
    """The callback handed to the C++ job: None, the user's callable, a tqdm
    bar, or without tqdm a plain progress line."""
    if progress is None or progress is False:
        return None, None
    if progress is True:
        try:
            from tqdm.auto import tqdm
        except ImportError:
            line = _PlainProgress(total_label)
            return line.update, line
        bar = tqdm(total=100, desc=total_label, unit="%")

        def advance(fraction):
            bar.update(int(100 * fraction) - bar.n)

        return advance, bar
    if callable(progress):
        return progress, None
    raise ValueError("progress = {!r}: expected a callable, True or None".format(progress))


def _run(job, progress, label):
    callback, bar = _progress(progress, label)
    try:
        return job(callback)
    finally:
        if bar is not None:
            bar.close()


def _warn_if_stopped(result, what):
    if result.termination != "completed":
        warnings.warn("{} stopped early: {}".format(what, result.termination),
                      PhysicalDiagnosticWarning, stacklevel=3)


def _warn_of_unfinished_points(job, raw, table):
    """The CLI's warnings of a sweep's points that stopped early or did not
    settle (a gap, or a transient's label, in the diagram otherwise), with
    the column of `table` that says which. Issued from the job's caller."""
    for note, column in ((raw["unsettled"], "transient_end"), (raw["stopped"], "termination")):
        if note:
            warnings.warn("{}: {}; {}['{}'] says which".format(job, note, table, column),
                          PhysicalDiagnosticWarning, stacklevel=3)


def _time_span(job, periods, t_end):
    if t_end is not None and periods is not None:
        raise ValueError("t_end = {!r}: give periods or t_end, not both".format(t_end))
    if t_end is not None:
        return 0.0, _option(job, "t_end", t_end)
    return _option(job, "periods", 100.0 if periods is None else periods), 0.0


@_documented("simulate")
def simulate(scene_=None, *, periods=_default("simulate", "periods"),
             t_end=_default("simulate", "t_end"), sample=_default("simulate", "sample"),
             progress=None, **keys):
    """One run of the scene (the CLI's `simulate`). Returns a Result with
    events (EventArray), trajectory (t, q, qdot arrays and mode list; with
    sample=DT), meta (meta.json's content) and termination."""
    loaded = scene(scene_ if scene_ is not None else "jin2003", **keys)
    periods, t_end = _time_span("simulate", periods, t_end)
    sample_step = 0.0 if sample is None else _option("simulate", "sample", sample)
    raw = _run(lambda callback: _impactlab.simulate(loaded, periods, t_end, sample_step, callback),
               progress, "simulate")
    result = RunResult(
        scene=loaded,
        events=raw["events"].view(EventArray),
        trajectory=Result(t=raw["samples_t"], q=raw["samples_q"], qdot=raw["samples_qdot"],
                          mode=raw["samples_mode"]),
        termination=raw["termination"], _pending_record=raw["record"])
    _warn_if_stopped(result, "simulate")
    return result


@_documented("poincare")
def poincare(scene_=None, *, section=_default("poincare", "section"),
             transient=_default("poincare", "transient"),
             max_transient=_default("poincare", "max_transient"),
             transient_impacts=_default("poincare", "transient_impacts"),
             points=_default("poincare", "points"), lyapunov=_default("poincare", "lyapunov"),
             lyapunov_spectrum=_default("poincare", "lyapunov_spectrum"),
             progress=None, **keys):
    """The scene's orbit on a Poincaré section (the CLI's `poincare`): t, q,
    qdot, wall arrays (poincare.csv's rows), phase, counts, Lyapunov exponent.
    With lyapunov_spectrum=True also lyapunov_spectrum (λ1..λN, 1/time unit;
    -inf for a direction the contact collapses, nan where not computed:
    lyapunov_spectrum_note says why), lyapunov_spectrum_error (half the range
    of each running estimate over the last quarter of the periods), and the
    running estimate itself (lyapunov.csv's rows): lyapunov_running_t and
    lyapunov_running (shape (periods, N))."""
    loaded = scene(scene_ if scene_ is not None else "jin2003", **keys)
    section = _option("poincare", "section", section)
    transient = _option("poincare", "transient", transient)
    max_transient = _option("poincare", "max_transient", max_transient)
    transient_impacts = _option("poincare", "transient_impacts", transient_impacts)
    _refuse_excluded("poincare", {"transient": transient, "max_transient": max_transient,
                                  "transient_impacts": transient_impacts})
    points = _option("poincare", "points", points)
    spectrum = _option("poincare", "lyapunov_spectrum", lyapunov_spectrum)
    raw = _run(lambda callback: _impactlab.poincare(loaded, section, transient, max_transient,
                                                    transient_impacts, points, bool(lyapunov),
                                                    spectrum, callback),
               progress, "poincare")
    if spectrum:
        raw["lyapunov_running"] = raw["lyapunov_running"].reshape(
            len(raw["lyapunov_running_t"]), len(raw["lyapunov_spectrum"]))
    raw["k"] = np.arange(len(raw["t"]))
    raw["phase"] = np.fmod(raw["omega"] * raw["t"], 2.0 * math.pi)
    result = SectionResult(scene=loaded, **raw)
    _warn_if_stopped(result, "poincare")
    if result.transient_end == "not_settled":
        warnings.warn("poincare: the transient did not settle within max_transient = {:g} "
                      "forcing periods: the points may still be on their way to the "
                      "attractor".format(max_transient), PhysicalDiagnosticWarning, stacklevel=2)
    return result


def _spectrum_columns(raw):
    """The columns lyapunov1..N of a sweep's or a map's rows (none where the
    spectrum was not asked for)."""
    dimension = raw["lyapunov_dimension"]
    if dimension == 0:
        return {}
    rows = raw["lyapunov_spectrum"].reshape(-1, dimension)
    return {"lyapunov{}".format(i + 1): rows[:, i].copy() for i in range(dimension)}


@_documented("sweep")
def sweep(scene_=None, *, param, direction=_default("sweep", "direction"),
          threads=_default("sweep", "threads"), batch=_default("sweep", "batch"),
          chunks=_default("sweep", "chunks"),
          section=_default("sweep", "section"), transient=_default("sweep", "transient"),
          max_transient=_default("sweep", "max_transient"),
          transient_impacts=_default("sweep", "transient_impacts"),
          points=_default("sweep", "points"), lyapunov=_default("sweep", "lyapunov"),
          lyapunov_spectrum=_default("sweep", "lyapunov_spectrum"),
          period_tol=_default("sweep", "period_tol"), max_period=_default("sweep", "max_period"),
          classification_tol=_default("sweep", "classification_tol"), progress=None, **keys):
    """A 1D bifurcation sweep (param="omega=FROM:TO:N") or a 2D map (a list of
    two). Returns bifurcation (1D: the rows of bifurcation.csv), summary (the
    rows of summary.csv, or of classes.csv for a 2D map), definition, run
    (meta.json's threads and batch_width: the lanes per thread).
    classification_tol: "auto" (a 2D map integrates at the scene's
    integrator.classification_* unless an integrator key was set) or "off"
    (the scene's integrator); the CLI's --classification-tol."""
    loaded = scene(scene_ if scene_ is not None else "jin2003", **keys)
    if isinstance(param, str):
        params = [param]
    elif isinstance(param, (list, tuple)) and param and all(isinstance(p, str) for p in param):
        params = list(param)
    else:
        raise ValueError("param = {!r}: expected NAME=FROM:TO:N or a list of two".format(param))
    if lyapunov is not None and not isinstance(lyapunov, bool):
        raise ValueError("lyapunov = {!r}: expected True, False or None".format(lyapunov))
    for key, value in (("direction", direction), ("section", section),
                       ("classification_tol", classification_tol),
                       ("lyapunov_spectrum", lyapunov_spectrum)):
        _option("sweep", key, value)
    checked = {key: _option("sweep", key, value) for key, value in (
        ("threads", threads), ("chunks", chunks), ("transient", transient),
        ("max_transient", max_transient), ("transient_impacts", transient_impacts),
        ("points", points),
        ("period_tol", period_tol), ("max_period", max_period))}
    _refuse_excluded("sweep", checked)
    raw = _run(lambda callback: _impactlab.sweep(
        loaded, params, direction, checked["chunks"], section, checked["transient"],
        checked["max_transient"], checked["transient_impacts"], checked["points"], lyapunov,
        lyapunov_spectrum, checked["period_tol"], checked["max_period"], classification_tol,
        checked["threads"], _batch("sweep", batch), callback),
        progress, "sweep")
    axes = raw["axes"]
    names = ["up" if d > 0 else "down" for d in raw["direction"]]
    summary = {axes[0]: raw["value"]}
    if len(params) == 2:
        summary[axes[1]] = raw["value2"]
        bifurcation = None
    else:
        summary["direction"] = names
        bifurcation = {axes[0]: raw["point_value"], "k": raw["point_k"], "t": raw["point_t"],
                       "q": raw["point_q"], "qdot": raw["point_qdot"], "wall": raw["point_wall"],
                       "direction": ["up" if d > 0 else "down" for d in raw["point_direction"]]}
    summary.update(period=raw["period"], impacts_per_period=raw["impacts_per_period"],
                   contact=raw["contact"], lyapunov=raw["lyapunov"],
                   termination=raw["termination"])
    if len(params) == 1:
        summary["points"] = raw["points"]
    summary["stick_fraction"] = raw["stick_fraction"]
    summary.update(transient_periods=raw["transient_periods"], transient_end=raw["transient_end"])
    summary.update(_spectrum_columns(raw))
    _warn_of_unfinished_points("sweep", raw, "summary")
    result = SweepResult(scene=loaded, axes=tuple(axes),
                         bifurcation=Table(bifurcation) if bifurcation else None,
                         summary=Table(summary), definition=raw["definition"],
                         wall_time_s=raw["wall_time_s"],
                         run={"threads": raw["threads"], "batch_width": raw["batch_width"]})
    if len(params) == 2:
        # the map's columns shaped like the map: [j, i] is the second key's
        # j-th value and the first key's i-th (classes.csv: the first fastest)
        counts = [axis["count"] for axis in raw["definition"]["axes"]]
        result.grids = Table({name: np.asarray(column, dtype=None if isinstance(
            column, np.ndarray) else object).reshape(counts[1], counts[0])
            for name, column in summary.items()})
    return result


@_documented("basins")
def basins(scene_, *, x, y, threads=_default("basins", "threads"),
           batch=_default("basins", "batch"),
           section=_default("basins", "section"), transient=_default("basins", "transient"),
           max_transient=_default("basins", "max_transient"),
           transient_impacts=_default("basins", "transient_impacts"),
           points=_default("basins", "points"), lyapunov=_default("basins", "lyapunov"),
           lyapunov_spectrum=_default("basins", "lyapunov_spectrum"),
           period_tol=_default("basins", "period_tol"),
           max_period=_default("basins", "max_period"),
           attractor_tol=_default("basins", "attractor_tol"),
           entropy_box=_default("basins", "entropy_box"), progress=None, **keys):
    """Basins of attraction (the CLI's `basins`): every initial condition of
    the grid x="KEY=FROM:TO:N" (fastest) by y="KEY=FROM:TO:N", run from the
    scene's state with the two keys set, labelled by the attractor it settles
    on. Returns labels (attractor ids, shape (Ny, Nx)), x and y (the axis
    values), grid (the rows of basins.csv), attractors (a structured array:
    the rows of attractors.csv), basin_measures (the basin entropies and the
    uncertainty exponent, as meta.json's "basin_measures") and meta."""
    loaded = scene(scene_, **keys)
    for key, value in (("x", x), ("y", y), ("section", section), ("lyapunov", lyapunov),
                       ("lyapunov_spectrum", lyapunov_spectrum)):
        _option("basins", key, value)
    checked = {key: _option("basins", key, value) for key, value in (
        ("threads", threads), ("transient", transient), ("max_transient", max_transient),
        ("transient_impacts", transient_impacts), ("points", points), ("period_tol", period_tol),
        ("max_period", max_period),
        ("attractor_tol", attractor_tol), ("entropy_box", entropy_box))}
    _refuse_excluded("basins", checked)
    raw = _run(lambda callback: _impactlab.basins(
        loaded, x, y, section, checked["transient"], checked["max_transient"],
        checked["transient_impacts"], checked["points"], lyapunov, lyapunov_spectrum,
        checked["period_tol"], checked["max_period"], checked["attractor_tol"],
        checked["entropy_box"], checked["threads"], _batch("basins", batch), callback),
        progress, "basins")
    axes = raw["axes"]
    nx, ny = raw["counts"]
    grid = Table({axes[0]: raw["x"], axes[1]: raw["y"], "attractor": raw["attractor"],
                  "period": raw["period"], "impacts_per_period": raw["impacts_per_period"],
                  "contact": raw["contact"], "termination": raw["termination"],
                  "transient_end": raw["transient_end"]})
    grid.update(_spectrum_columns(raw))
    columns = [("attractor", "attractor_id", "<i4"), ("period", "attractor_period", "<i4"),
               ("impacts_per_period", "attractor_impacts_per_period", "<f8"),
               ("contact", "attractor_contact", "<i4"), ("q", "attractor_q", "<f8"),
               ("qdot", "attractor_qdot", "<f8"),
               ("basin_points", "attractor_basin_points", "<i4")]
    attractors = np.empty(len(raw["attractor_id"]),
                          dtype=[(name, kind) for name, _, kind in columns])
    for name, source, _ in columns:
        attractors[name] = raw[source]
    result = BasinsResult(scene=loaded, axes=tuple(axes),
                          x=raw["x"][:nx].copy(), y=raw["y"][::nx].copy(),
                          labels=raw["attractor"].reshape(ny, nx), grid=grid,
                          attractors=attractors, basin_measures=raw["meta"]["basin_measures"],
                          meta=raw["meta"], wall_time_s=raw["wall_time_s"])
    _warn_of_unfinished_points("basins", raw, "grid")
    return result


@_documented("attractors")
def attractors(scene_, *, param, samples=_default("attractors", "samples"),
               box=_default("attractors", "box"), seed=_default("attractors", "seed"),
               threads=_default("attractors", "threads"),
               batch=_default("attractors", "batch"),
               section=_default("attractors", "section"),
               transient=_default("attractors", "transient"),
               max_transient=_default("attractors", "max_transient"),
               transient_impacts=_default("attractors", "transient_impacts"),
               points=_default("attractors", "points"),
               lyapunov=_default("attractors", "lyapunov"),
               period_tol=_default("attractors", "period_tol"),
               max_period=_default("attractors", "max_period"),
               attractor_tol=_default("attractors", "attractor_tol"),
               match_tol=_default("attractors", "match_tol"), progress=None, **keys):
    """Attractors found and followed across a parameter (the CLI's
    `attractors`): at each value of param="NAME=FROM:TO:N", `samples` initial
    states drawn from the box (box="initial.theta=-0.05:0.05" or a list of
    such; None: the default box), each run to its attractor; the attractors
    are told apart by their section points and keep their ids along the
    parameter. Returns attractors (the rows of attractors.csv: features,
    basin fraction and its standard error), points (attractor_points.csv),
    samples (samples.csv), attractor_events (appear, vanish, merge, split:
    meta.json's "attractor_events") and meta."""
    loaded = scene(scene_, **keys)
    if box is None:
        boxes = []
    elif isinstance(box, str):
        boxes = [box]
    elif isinstance(box, (list, tuple)) and all(isinstance(b, str) for b in box):
        boxes = list(box)
    else:
        raise ValueError("box = {!r}: expected KEY=FROM:TO or a list of them".format(box))
    for key, value in (("param", param), ("section", section), ("lyapunov", lyapunov)):
        _option("attractors", key, value)
    checked = {key: _option("attractors", key, value) for key, value in (
        ("samples", samples), ("seed", seed), ("threads", threads), ("transient", transient),
        ("max_transient", max_transient), ("transient_impacts", transient_impacts),
        ("points", points), ("period_tol", period_tol), ("max_period", max_period),
        ("attractor_tol", attractor_tol), ("match_tol", match_tol))}
    _refuse_excluded("attractors", checked)
    raw = _run(lambda callback: _impactlab.attractors(
        loaded, param, checked["samples"], boxes, checked["seed"], section,
        checked["transient"], checked["max_transient"], checked["transient_impacts"],
        checked["points"], lyapunov, checked["period_tol"], checked["max_period"],
        checked["attractor_tol"], checked["match_tol"], checked["threads"],
        _batch("attractors", batch), callback),
        progress, "attractors")
    name = raw["param"]
    rows = dict(raw["attractors"])
    rows = {name: rows.pop("value"), **rows}
    points_raw = dict(raw["points"])
    point_rows = {name: points_raw.pop("value"), **points_raw}
    samples_raw = dict(raw["samples"])
    sample_rows = {name: samples_raw["value"], "sample": samples_raw["sample"]}
    for key, column in zip(samples_raw["box_keys"], samples_raw["box"]):
        sample_rows[key] = column
    for column in ("attractor", "period", "impacts_per_period", "contact", "termination",
                   "transient_end"):
        sample_rows[column] = samples_raw[column]
    result = AttractorsResult(scene=loaded, param=name, attractors=Table(rows),
                              points=Table(point_rows), samples=Table(sample_rows),
                              attractor_events=raw["meta"]["attractor_events"]["events"],
                              meta=raw["meta"], wall_time_s=raw["wall_time_s"])
    _warn_of_unfinished_points("attractors", raw, "samples")
    return result


@_documented("periodic")
def periodic(scene_=None, *, period=_default("periodic", "period"),
             phase=_default("periodic", "phase"), transient=_default("periodic", "transient"),
             max_iterations=_default("periodic", "max_iterations"),
             tolerance=_default("periodic", "tolerance"), all=_default("periodic", "all"),
             starts=_default("periodic", "starts"), box=_default("periodic", "box"),
             seed=_default("periodic", "seed"), progress=None, **keys):
    """A period-n orbit by Newton shooting and its Floquet multipliers (the
    CLI's `periodic`). meta holds periodic.json's content.

    With all=True, every orbit of the period that Newton shooting finds from
    `starts` initial states drawn from the box (box="initial.y=0:0.1" or a
    list of such; None: the default box), each start deflated by the orbits
    found before: orbits (orbits.csv's columns as a Table: id,
    minimal_period, the state by name, impacts, contact_phases, stable,
    multiplier1_re, multiplier1_im, ..., residual), multipliers (one complex
    array per orbit) and meta."""
    loaded = scene(scene_ if scene_ is not None else "jin2003", **keys)
    if isinstance(period, bool) or not isinstance(period, (str, numbers.Integral)):
        raise ValueError("period = {!r}: expected auto or a whole number from 1 to 1000".format(period))
    _option("periodic", "all", all)
    if all:
        return _periodic_orbits(loaded, period, phase, max_iterations, tolerance, starts, box,
                                seed, progress)
    checked = {key: _option("periodic", key, value) for key, value in (
        ("phase", phase), ("transient", transient), ("max_iterations", max_iterations),
        ("tolerance", tolerance))}
    raw = _run(lambda callback: _impactlab.periodic(
        loaded, str(period), checked["phase"], checked["transient"], checked["max_iterations"],
        checked["tolerance"], callback), progress, "periodic")
    meta = raw["meta"]
    result = Result(scene=loaded, meta=meta, converged=raw["converged"],
                    termination=raw["termination"], state=np.array(meta["state"]),
                    state_names=list(meta["state_names"]),
                    monodromy=np.array(meta["monodromy"]),
                    multipliers=np.array([complex(z["re"], z["im"])
                                          for z in meta["floquet_multipliers"]]))
    if not result.converged:
        # as the CLI says it: why, and how the period was chosen
        warnings.warn("periodic: Newton shooting did not converge ({}): {}; the period was {}"
                      .format(result.termination, meta["failure"],
                              meta["request"]["period_source"]),
                      PhysicalDiagnosticWarning, stacklevel=2)
    return result


def _box_list(box):
    """The box option as a list of KEY=FROM:TO texts (None: the default box)."""
    if box is None:
        return []
    if isinstance(box, str):
        return [box]
    if isinstance(box, (list, tuple)) and builtins.all(isinstance(b, str) for b in box):
        return list(box)
    raise ValueError("box = {!r}: expected KEY=FROM:TO or a list of them".format(box))


def _periodic_orbits(loaded, period, phase, max_iterations, tolerance, starts, box, seed,
                     progress):
    """periodic(all=True): every orbit of the period (see periodic)."""
    boxes = _box_list(box)
    checked = {key: _option("periodic", key, value) for key, value in (
        ("phase", phase), ("max_iterations", max_iterations), ("tolerance", tolerance),
        ("starts", starts), ("seed", seed))}
    raw = _run(lambda callback: _impactlab.periodic_orbits(
        loaded, str(period), checked["phase"], checked["max_iterations"], checked["tolerance"],
        checked["starts"], boxes, checked["seed"], callback), progress, "periodic")
    orbits = Table(raw["orbits"])
    dimension = sum(1 for name in orbits if name.startswith("multiplier") and name.endswith("_re"))
    multipliers = [np.array([complex(orbits["multiplier{}_re".format(k + 1)][row],
                                     orbits["multiplier{}_im".format(k + 1)][row])
                             for k in range(dimension)])
                   for row in range(len(orbits["id"]))]
    meta = raw["meta"]
    return Result(scene=loaded, meta=meta, orbits=orbits, multipliers=multipliers,
                  state_names=list(meta["state_names"]))


@_documented("compare")
def compare(scene_=None, *, models=_default("compare", "models"),
            periods=_default("compare", "periods"), t_end=_default("compare", "t_end"),
            progress=None, **keys):
    """The scene under several impact models (the CLI's `compare`): runs (per
    model: events, meta), numbers (compare.json's numbers), summary (summary.md),
    and the CSV tables' text (impacts_csv, contacts_csv, section_csv)."""
    loaded = _with_keys(scene_ if scene_ is not None else "jin2003", keys)
    if not isinstance(models, (str, list, tuple)):
        raise ValueError("models = {!r}: expected a list of model names".format(models))
    model_list = models if isinstance(models, str) else ",".join(models)
    periods, t_end = _time_span("compare", periods, t_end)
    raw = _run(lambda callback: _impactlab.compare(loaded, model_list, periods, t_end, callback),
               progress, "compare")
    for run in raw["runs"].values():
        run["events"] = run["events"].view(EventArray)
    return ComparisonResult(scene=loaded, **raw)


@_documented("work_precision")
def bench(scene_=None, *, methods=_default("work_precision", "methods"),
          rtols=_default("work_precision", "rtols"),
          atol_ratio=_default("work_precision", "atol_ratio"),
          periods=_default("work_precision", "periods"),
          reference_periods=_default("work_precision", "reference_periods"),
          max_reference_impacts=_default("work_precision", "max_reference_impacts"),
          repetitions=_default("work_precision", "repetitions"), progress=None, **keys):
    """Work against precision on one scene (what the CLI's `bench` measures on
    its fixed cases): per method and rtol, CPU and wall seconds per impact,
    right-hand sides and steps per impact, and the largest impact-time and
    impact-velocity errors against the reference (the closed form where the
    oscillator has one; else two methods at rtol 1e-14 trusted where they
    agree: the quad-precision Taylor stepper and rk8pd for the pendulum's
    Model N, as the CLI's bench, rk8pd and bulirsch_stoer otherwise)."""
    loaded = scene(scene_ if scene_ is not None else "jin2003", **keys)
    if methods is not None and (isinstance(methods, str) or
                                not all(isinstance(m, str) for m in methods)):
        raise ValueError("methods = {!r}: expected a list of stepper names".format(methods))
    rtol_list = [_number("rtols", r, _OPTIONS["work_precision"]["rtols"]) for r in rtols]
    checked = {key: _option("work_precision", key, value) for key, value in (
        ("atol_ratio", atol_ratio), ("periods", periods), ("reference_periods", reference_periods),
        ("max_reference_impacts", max_reference_impacts), ("repetitions", repetitions))}
    raw = _run(lambda callback: _impactlab.bench(
        loaded, list(methods or []), rtol_list, checked["atol_ratio"], checked["periods"],
        checked["reference_periods"], checked["max_reference_impacts"], checked["repetitions"],
        callback), progress, "bench")
    return WorkPrecisionResult(scene=loaded, **raw)


@_documented("continue")
def continue_(scene_=None, *, param, period=_default("continue", "period"),
              section=_default("continue", "section"), switch=_default("continue", "switch"),
              start=_default("continue", "start"), transient=_default("continue", "transient"),
              max_points=_default("continue", "max_points"),
              tolerance=_default("continue", "tolerance"),
              max_step=_default("continue", "max_step"), param2=_default("continue", "param2"),
              curve=_default("continue", "curve"), all=_default("continue", "all"),
              starts=_default("continue", "starts"), box=_default("continue", "box"),
              seed=_default("continue", "seed"),
              no_normal_forms=_default("continue", "no_normal_forms"), progress=None, **keys):
    """Pseudo-arclength continuation of a period-n orbit in one scene key (the
    CLI's `continue`): branches (per branch: the columns of branch.csv, its
    period and why it stopped) and points (the rows of points.csv: folds,
    period doublings, Neimark-Sacker, grazing points, contact onset and end,
    chatter onset).
    section is strobe[:PHASE] or impact:WALL (WALL +1 or -1: the impact map,
    where q is the impact's forcing phase omega t mod 2 pi and qdot the rate
    just before it; start is then (phase, qdot)). The states and multipliers
    are N wide: N = 2 (q, qdot), or a model file's N states (q, qdot, state3,
    ...; multiplier1 ... multiplierN).
    param2="NAME=FROM:TO" (with curve= fold, period_doubling, grazing,
    contact_onset, contact_end, contact_boundary (the pendulum's
    V0*omega = g), neimark_sacker or chatter_onset, a type the branch has no located point of
    raising ValueError naming curve; else the first located fold, period
    doubling or grazing) follows that bifurcation's curve in the
    plane of the two keys from the point the branch located (the CLI's
    --param2 and --curve; on either section): curves is then a list of dicts with the columns of
    curve.csv, the first branch's curve first, then each doubled branch's
    (switch=True); curve_note says why there is none; curve_points holds the
    codimension-two points located on them (curve_points.csv's columns: on a
    grazing curve, grazing_period_doubling, grazing_fold and
    grazing_scenario_change; on a fold curve, cusp; on a Neimark-Sacker
    curve, resonance_1_1 and resonance_1_2; on a period-doubling curve,
    degenerate_period_doubling; on a fold or period-doubling curve that runs
    into a graze, grazing_fold or grazing_period_doubling).
    all=True continues every orbit of the period that periodic(all=True) finds
    at FROM (from `starts` states drawn from `box`, seeded by `seed`): each
    branch then has `orbit` (the id of the orbit it continues), and the result
    has orbits (periodic.json's list) and not_continued (why an orbit was not:
    on a branch already continued).
    Each located grazing point carries its discontinuity map and normal form
    (docs/analysis.md): points has points.csv's columns scenario,
    impacting_side, impact_speed_coefficient (the first impact past the graze
    at speed c sqrt|p - p_g|), period_one_speed_slope and period_one_side, and
    grazing is the list of grazing.json's entries (the map's and the normal
    form's coefficients, the scenario, the normal form's attractor at 25
    distances); no_normal_forms=True skips them, and the kick signs a grazing
    curve watches at each point."""
    loaded = scene(scene_ if scene_ is not None else "linear_impact", **keys)
    # NAME=FROM:TO is read by the scene API (continuation_job), as the CLI's
    for key, value in (("param", param), ("param2", param2), ("curve", curve),
                       ("section", section), ("switch", switch)):
        if value is not None:
            _option("continue", key, value)
    if start is not None:
        if not isinstance(start, (list, tuple, np.ndarray)):
            raise ValueError("start = {!r}: expected (q, qdot), or a model file's N states".format(start))
        start = [_number("start", value) for value in start]
        if not start:  # the scene API reads an empty start as none given
            raise ValueError("start = 0 numbers: expected Q,QDOT (a model file: its N states)")
    _option("continue", "all", all)
    _option("continue", "no_normal_forms", no_normal_forms)
    boxes = _box_list(box)
    checked = {key: _option("continue", key, value) for key, value in (
        ("period", period), ("transient", transient), ("max_points", max_points),
        ("tolerance", tolerance), ("max_step", max_step), ("starts", starts), ("seed", seed))}
    raw = _run(lambda callback: _impactlab.continue_(
        loaded, param, param2 or "", curve or "", checked["period"], section, switch,
        start or [], checked["transient"], checked["max_points"], checked["tolerance"],
        checked["max_step"], all, checked["starts"], boxes, checked["seed"],
        bool(no_normal_forms), callback),
        progress, "continue")
    # branch.csv's, points.csv's and curve.csv's columns as tables
    raw["branches"] = [Table(branch) for branch in raw["branches"]]
    raw["points"] = Table(raw["points"])
    if "curves" in raw:
        raw["curves"] = [Table(curve) for curve in raw["curves"]]
        raw["curve_points"] = Table(raw["curve_points"])
    return ContinuationResult(scene=loaded, **raw)


@_documented("explore")
def explore(scene_=None, *, port=_default("explore", "port")):
    """The explorer's page (the CLI's `explore`) for the scene: time series,
    phase portrait, section, orbit diagram, periodic orbits, export. Starts
    `impactlab explore` on 127.0.0.1 and returns an Explorer: shown inline in
    Jupyter (an IFrame), its url to open elsewhere, stop() to end it."""
    port = _option("explore", "port", port)
    return start_explorer(scene_ if scene_ is not None else "jin2003", port)
