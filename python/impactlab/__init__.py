"""impactlab from Python: the scene API of the C++ toolkit (docs/python.md).

    import impactlab
    run = impactlab.simulate("jin2003", V0=4.163, periods=100)
    run.events["t"], run.events["q"], run.meta["counts"]["impacts"]

Every function takes a scene (a built-in name, a path to a .toml file, or a
Scene from impactlab.scene) and the scene's keys as keyword arguments, the
dotted ones spelled with "__" (initial__theta=0.1) or passed as
**{"initial.theta": 0.1}. They are checked exactly as `impactlab ... --set`
checks them: bad input raises ValueError naming the key and the value.
"""

import math
import numbers
import warnings

import numpy as np

from . import _impactlab

__all__ = [
    "Scene", "scenes", "scene", "simulate", "poincare", "sweep", "basins", "periodic", "compare",
    "bench", "continue_", "EventArray", "PhysicalDiagnosticWarning",
]

Scene = _impactlab.Scene

#: names of the `kind` codes in an event array, by code
EVENT_KINDS = tuple(_impactlab.event_kind_names())


class PhysicalDiagnosticWarning(UserWarning):
    """A run stopped early by a physical diagnostic (the CLI's exit status 3)."""


class EventArray(np.ndarray):
    """The event log: a structured array with the columns of events.csv
    (`kind` holds codes; `kind_names()` gives their names)."""

    def kind_names(self):
        return np.array(EVENT_KINDS, dtype=object)[np.asarray(self["kind"], dtype=np.intp)]

    def to_pandas(self):
        import pandas  # optional dependency

        frame = pandas.DataFrame({name: np.asarray(self[name]) for name in self.dtype.names})
        frame["kind"] = self.kind_names()
        return frame


class Result:
    """A job's result: its fields as attributes (see docs/python.md)."""

    def __init__(self, **fields):
        self.__dict__.update(fields)

    def __repr__(self):
        return "{}({})".format(type(self).__name__, ", ".join(sorted(self.__dict__)))


class RunResult(Result):
    """simulate's result; `meta` (meta.json's content) is made on first use."""

    @property
    def meta(self):
        if "_meta" not in self.__dict__:
            self._meta = self._record.meta()
        return self._meta


def _assignment_text(key, value):
    """`value` as --set would spell it; ValueError for a type no key takes."""
    if isinstance(value, bool):
        raise ValueError("{} = {!r}: expected a number or a text value, not a bool".format(key, value))
    if isinstance(value, numbers.Integral):
        return str(int(value))
    if isinstance(value, numbers.Real):
        number = float(value)
        if not math.isfinite(number):
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
    """A scene with keys set: scene("jin2003", V0=4.163, omega=7)."""
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


def _number(key, value, positive=False, allow_zero=False):
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise ValueError("{} = {!r}: expected a number".format(key, value))
    number = float(value)
    if not math.isfinite(number):
        raise ValueError("{} = {!r}: not a finite number".format(key, value))
    if positive and not (number > 0.0 or (allow_zero and number == 0.0)):
        raise ValueError("{} = {!r}: must be > 0".format(key, value))
    return number


def _whole(key, value, lowest=0):
    if isinstance(value, bool) or not isinstance(value, numbers.Integral) or value < lowest:
        raise ValueError("{} = {!r}: expected a whole number >= {}".format(key, value, lowest))
    return int(value)


def _progress(progress, total_label):
    """The callback handed to the C++ job: None, the user's callable, or a tqdm bar."""
    if progress is None or progress is False:
        return None, None
    if progress is True:
        try:
            from tqdm.auto import tqdm
        except ImportError:
            return None, None
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


def _time_span(periods, t_end):
    if t_end is not None and periods is not None:
        raise ValueError("t_end = {!r}: give periods or t_end, not both".format(t_end))
    if t_end is not None:
        return 0.0, _number("t_end", t_end)
    return _number("periods", 100.0 if periods is None else periods, positive=True), 0.0


def simulate(scene_=None, *, periods=None, t_end=None, sample=None, progress=None, **keys):
    """One run of the scene (the CLI's `simulate`). Returns a Result with
    events (EventArray), trajectory (t, q, qdot arrays and mode list; with
    sample=DT), meta (meta.json's content) and termination."""
    loaded = scene(scene_ if scene_ is not None else "jin2003", **keys)
    periods, t_end = _time_span(periods, t_end)
    sample_step = 0.0 if sample is None else _number("sample", sample, positive=True)
    raw = _run(lambda callback: _impactlab.simulate(loaded, periods, t_end, sample_step, callback),
               progress, "simulate")
    result = RunResult(
        scene=loaded,
        events=raw["events"].view(EventArray),
        trajectory=Result(t=raw["samples_t"], q=raw["samples_q"], qdot=raw["samples_qdot"],
                          mode=raw["samples_mode"]),
        termination=raw["termination"], _record=raw["record"])
    _warn_if_stopped(result, "simulate")
    return result


def poincare(scene_=None, *, section="strobe", transient=100.0, transient_impacts=0, points=50,
             lyapunov=False, progress=None, **keys):
    """The scene's orbit on a Poincaré section (the CLI's `poincare`): t, q,
    qdot, wall arrays (poincare.csv's rows), phase, counts, Lyapunov exponent."""
    loaded = scene(scene_ if scene_ is not None else "jin2003", **keys)
    if not isinstance(section, str):
        raise ValueError("section = {!r}: expected text such as strobe or impact:+1".format(section))
    transient = _number("transient", transient)
    if not 0.0 <= transient <= 1e9:
        raise ValueError("transient = {!r}: expected 0 to 1e9 forcing periods".format(transient))
    transient_impacts = _whole("transient_impacts", transient_impacts)
    points = _whole("points", points, lowest=1)
    raw = _run(lambda callback: _impactlab.poincare(loaded, section, transient, transient_impacts,
                                                    points, bool(lyapunov), callback),
               progress, "poincare")
    raw["k"] = np.arange(len(raw["t"]))
    raw["phase"] = np.fmod(raw["omega"] * raw["t"], 2.0 * math.pi)
    result = Result(scene=loaded, **raw)
    _warn_if_stopped(result, "poincare")
    return result


def sweep(scene_=None, *, param, direction="up", threads=1, chunks=1, section="strobe",
          transient=100.0, transient_impacts=0, points=50, lyapunov=None, period_tol=1e-6,
          max_period=16, classification_tol="auto", progress=None, **keys):
    """A 1D bifurcation sweep (param="omega=FROM:TO:N") or a 2D map (a list of
    two). Returns bifurcation (1D: the rows of bifurcation.csv), summary (the
    rows of summary.csv, or of classes.csv for a 2D map), definition.
    classification_tol: "auto" (a 2D map integrates at the scene's
    integrator.classification_* unless an integrator key was set) or "off"
    (the scene's integrator); the CLI's --classification-tol."""
    loaded = scene(scene_ if scene_ is not None else "jin2003", **keys)
    params = [param] if isinstance(param, str) else list(param)
    if not params or not all(isinstance(p, str) for p in params):
        raise ValueError("param = {!r}: expected NAME=FROM:TO:N or a list of two".format(param))
    if lyapunov is not None and not isinstance(lyapunov, bool):
        raise ValueError("lyapunov = {!r}: expected True, False or None".format(lyapunov))
    for key, value in (("direction", direction), ("section", section),
                       ("classification_tol", classification_tol)):
        if not isinstance(value, str):
            raise ValueError("{} = {!r}: expected text".format(key, value))
    transient = _number("transient", transient)
    raw = _run(lambda callback: _impactlab.sweep(
        loaded, params, direction, _whole("chunks", chunks, 1), section, transient,
        _whole("transient_impacts", transient_impacts), _whole("points", points, 1), lyapunov,
        _number("period_tol", period_tol, positive=True), _whole("max_period", max_period, 1),
        classification_tol, _whole("threads", threads, 1), callback), progress, "sweep")
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
    return Result(scene=loaded, bifurcation=bifurcation, summary=summary,
                  definition=raw["definition"], wall_time_s=raw["wall_time_s"])


def basins(scene_, *, x, y, threads=1, section="strobe", transient=100.0,
           transient_impacts=0, points=50, lyapunov=False, period_tol=1e-6, max_period=16,
           attractor_tol=1e-4, progress=None, **keys):
    """Basins of attraction (the CLI's `basins`): every initial condition of
    the grid x="KEY=FROM:TO:N" (fastest) by y="KEY=FROM:TO:N", run from the
    scene's state with the two keys set, labelled by the attractor it settles
    on. Returns labels (attractor ids, shape (Ny, Nx)), x and y (the axis
    values), grid (the rows of basins.csv), attractors (a structured array:
    the rows of attractors.csv) and meta."""
    loaded = scene(scene_, **keys)
    for key, value in (("x", x), ("y", y), ("section", section)):
        if not isinstance(value, str):
            raise ValueError("{} = {!r}: expected text such as KEY=FROM:TO:N".format(key, value))
    if not isinstance(lyapunov, bool):
        raise ValueError("lyapunov = {!r}: expected True or False".format(lyapunov))
    raw = _run(lambda callback: _impactlab.basins(
        loaded, x, y, section, _number("transient", transient),
        _whole("transient_impacts", transient_impacts), _whole("points", points, 1), lyapunov,
        _number("period_tol", period_tol, positive=True), _whole("max_period", max_period, 1),
        _number("attractor_tol", attractor_tol, positive=True), _whole("threads", threads, 1),
        callback), progress, "basins")
    axes = raw["axes"]
    nx, ny = raw["counts"]
    grid = {axes[0]: raw["x"], axes[1]: raw["y"], "attractor": raw["attractor"],
            "period": raw["period"], "impacts_per_period": raw["impacts_per_period"],
            "contact": raw["contact"], "termination": raw["termination"]}
    columns = [("attractor", "attractor_id", "<i4"), ("period", "attractor_period", "<i4"),
               ("impacts_per_period", "attractor_impacts_per_period", "<f8"),
               ("contact", "attractor_contact", "<i4"), ("q", "attractor_q", "<f8"),
               ("qdot", "attractor_qdot", "<f8"),
               ("basin_points", "attractor_basin_points", "<i4")]
    attractors = np.empty(len(raw["attractor_id"]),
                          dtype=[(name, kind) for name, _, kind in columns])
    for name, source, _ in columns:
        attractors[name] = raw[source]
    result = Result(scene=loaded, axes=tuple(axes),
                    x=raw["x"][:nx].copy(), y=raw["y"][::nx].copy(),
                    labels=raw["attractor"].reshape(ny, nx), grid=grid, attractors=attractors,
                    meta=raw["meta"], wall_time_s=raw["wall_time_s"])
    return result


def periodic(scene_=None, *, period="auto", phase=0.0, transient=100.0, max_iterations=30,
             tolerance=1e-11, progress=None, **keys):
    """A period-n orbit by Newton shooting and its Floquet multipliers (the
    CLI's `periodic`). meta holds periodic.json's content."""
    loaded = scene(scene_ if scene_ is not None else "jin2003", **keys)
    if isinstance(period, bool) or not isinstance(period, (str, numbers.Integral)):
        raise ValueError("period = {!r}: expected auto or a whole number from 1 to 1000".format(period))
    phase = _number("phase", phase)
    if not 0.0 <= phase <= 6.283185307179586:
        raise ValueError("phase = {!r}: expected 0 to 2 pi".format(phase))
    raw = _run(lambda callback: _impactlab.periodic(
        loaded, str(period), phase, _number("transient", transient),
        _whole("max_iterations", max_iterations, 1), _number("tolerance", tolerance, positive=True),
        callback), progress, "periodic")
    meta = raw["meta"]
    result = Result(scene=loaded, meta=meta, converged=raw["converged"],
                    termination=raw["termination"], state=np.array(meta["state"]),
                    monodromy=np.array(meta["monodromy"]),
                    multipliers=np.array([complex(z["re"], z["im"])
                                          for z in meta["floquet_multipliers"]]))
    if not result.converged:
        warnings.warn("periodic: Newton shooting did not converge ({})".format(result.termination),
                      PhysicalDiagnosticWarning, stacklevel=2)
    return result


def compare(scene_=None, *, models="", periods=None, t_end=None, progress=None, **keys):
    """The scene under several impact models (the CLI's `compare`): runs (per
    model: events, meta), numbers (compare.json's numbers), summary (summary.md),
    and the CSV tables' text (impacts_csv, contacts_csv, section_csv)."""
    loaded = scene(scene_ if scene_ is not None else "jin2003", **keys)
    if not isinstance(models, (str, list, tuple)):
        raise ValueError("models = {!r}: expected a list of model names".format(models))
    model_list = models if isinstance(models, str) else ",".join(models)
    periods, t_end = _time_span(periods, t_end)
    raw = _run(lambda callback: _impactlab.compare(loaded, model_list, periods, t_end, callback),
               progress, "compare")
    for run in raw["runs"].values():
        run["events"] = run["events"].view(EventArray)
    return Result(scene=loaded, **raw)


def bench(scene_=None, *, methods=None, rtols=(1e-6, 1e-8, 1e-10), atol_ratio=1e-2, periods=50.0,
          reference_periods=20.0, max_reference_impacts=20, repetitions=1, progress=None, **keys):
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
    rtol_list = [_number("rtols", r, positive=True) for r in rtols]
    raw = _run(lambda callback: _impactlab.bench(
        loaded, list(methods or []), rtol_list, _number("atol_ratio", atol_ratio, positive=True),
        _number("periods", periods, positive=True),
        _number("reference_periods", reference_periods, positive=True),
        _whole("max_reference_impacts", max_reference_impacts, 1),
        _whole("repetitions", repetitions, 1), callback), progress, "bench")
    return Result(scene=loaded, **raw)


def _parameter_range(param, key="param"):
    """NAME=FROM:TO as (name, from, to); the key and its range are checked by the job."""
    if isinstance(param, str):
        name, equals, span = param.partition("=")
        low, colon, high = span.partition(":")
        if name and equals and colon and ":" not in high:
            try:
                low, high = float(low), float(high)
            except ValueError:
                low = high = math.nan
            if not (math.isfinite(low) and math.isfinite(high)):
                raise ValueError("{} = {!r}: FROM and TO must be finite numbers".format(key, param))
            if low == high:
                raise ValueError("{} = {!r}: FROM and TO must differ".format(key, param))
            return name, low, high
    raise ValueError("{} = {!r}: expected NAME=FROM:TO".format(key, param))


def continue_(scene_=None, *, param, period=1, section="strobe", switch=False, start=None,
              transient=100.0, max_points=5000, tolerance=1e-10, max_step=0.0, param2=None,
              curve=None, progress=None, **keys):
    """Pseudo-arclength continuation of a period-n orbit in one scene key (the
    CLI's `continue`): branches (per branch: the columns of branch.csv, its
    period and why it stopped) and points (the rows of points.csv: folds,
    period doublings, Neimark-Sacker, grazing points, contact onset and end).
    section is strobe[:PHASE] or impact:WALL (WALL +1 or -1: the impact map,
    where q is the impact's forcing phase omega t mod 2 pi and qdot the rate
    just before it; start is then (phase, qdot)). The states and multipliers
    are N wide: N = 2 (q, qdot), or a model file's N states (q, qdot, state3,
    ...; multiplier1 ... multiplierN).
    param2="NAME=FROM:TO" (with curve= fold, period_doubling or grazing; else
    the first located point's type) follows that bifurcation's curve in the
    plane of the two keys from the point the branch located (the CLI's
    --param2 and --curve; on either section): curves is then a list of dicts with the columns of
    curve.csv, the first branch's curve first, then each doubled branch's
    (switch=True); curve_note says why there is none."""
    loaded = scene(scene_ if scene_ is not None else "linear_impact", **keys)
    name, low, high = _parameter_range(param)
    name2, low2, high2 = "", 0.0, 0.0
    if param2 is not None:
        name2, low2, high2 = _parameter_range(param2, "param2")
    if curve is not None and not isinstance(curve, str):
        raise ValueError("curve = {!r}: expected fold, period_doubling or grazing".format(curve))
    if not isinstance(section, str):
        raise ValueError("section = {!r}: expected text such as strobe, strobe:PHASE or impact:+1".format(section))
    if not isinstance(switch, bool):
        raise ValueError("switch = {!r}: expected True or False".format(switch))
    if start is not None:
        if not isinstance(start, (list, tuple, np.ndarray)):
            raise ValueError("start = {!r}: expected (q, qdot), or a model file's N states".format(start))
        start = [_number("start", value) for value in start]
    raw = _run(lambda callback: _impactlab.continue_(
        loaded, name, low, high, _whole("period", period, 1), section, switch, start,
        _number("transient", transient), _whole("max_points", max_points, 2),
        _number("tolerance", tolerance, positive=True),
        _number("max_step", max_step, positive=True, allow_zero=True), name2, low2, high2,
        curve or "", callback),
        progress, "continue")
    return Result(scene=loaded, parameter=name, **raw)
