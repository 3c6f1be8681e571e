"""Every job's options are declared once, in the scene API's tables
(api/job_options.hpp): Python's keyword defaults agree with them, each
keyword is in its job's table, and bad input names the Python keyword."""
import inspect
import math

import pytest

import impactlab
from impactlab import _impactlab

#: the Python function of each job that Python offers
FUNCTIONS = {
    "simulate": impactlab.simulate,
    "poincare": impactlab.poincare,
    "sweep": impactlab.sweep,
    "basins": impactlab.basins,
    "attractors": impactlab.attractors,
    "periodic": impactlab.periodic,
    "continue": impactlab.continue_,
    "compare": impactlab.compare,
    "work_precision": impactlab.bench,
    "explore": impactlab.explore,
}

#: keywords that are not options of a job: the progress callback
NOT_OPTIONS = {"progress"}


def python_rows(job):
    return [row for row in _impactlab.job_options(job)
            if row["front_ends"] in ("both", "python") and not row["for_tests_only"]]


def test_every_job_with_python_options_has_a_function():
    for job in _impactlab.job_names():
        if python_rows(job):
            assert job in FUNCTIONS, job
        else:
            assert job not in FUNCTIONS, job


@pytest.mark.parametrize("job", sorted(FUNCTIONS))
def test_signature_defaults_agree_with_the_table(job):
    parameters = inspect.signature(FUNCTIONS[job]).parameters
    rows = python_rows(job)
    for row in rows:
        assert row["name"] in parameters, (job, row["name"])
        parameter = parameters[row["name"]]
        assert parameter.kind == inspect.Parameter.KEYWORD_ONLY, (job, row["name"])
        if row["required"]:
            assert parameter.default is inspect.Parameter.empty, (job, row["name"])
            continue
        default = parameter.default
        assert default == row["default"], (job, row["name"], default, row["default"])
        assert type(default) is type(row["default"]), (job, row["name"])
        if isinstance(default, float):
            assert row["lower"] <= default <= row["upper"]
    # and every keyword is an option of the job's table
    names = {row["name"] for row in rows}
    for name, parameter in parameters.items():
        if parameter.kind == inspect.Parameter.KEYWORD_ONLY and name not in NOT_OPTIONS:
            assert name in names, (job, name)


@pytest.mark.parametrize("job", sorted(FUNCTIONS))
def test_docstring_lists_the_options(job):
    doc = FUNCTIONS[job].__doc__
    for row in python_rows(job):
        assert "    {}: ".format(row["name"]) in doc, (job, row["name"])
    assert "`" not in doc.split("Options (")[1].split(":", 1)[1], doc  # mentions spelled


def test_library_names_options_by_their_python_keywords():
    with pytest.raises(ValueError) as raised:
        impactlab.continue_("linear_impact", param="omega=2:2.5", param2="omega=0.1:0.2")
    assert str(raised.value) == "param2 = omega: must differ from param's key"
    with pytest.raises(ValueError) as raised:
        impactlab.continue_("linear_impact", param="omega=2:2.5", curve="fold")
    assert str(raised.value) == "curve = fold: needs param2"


@pytest.mark.parametrize("call, message", [
    (lambda: impactlab.sweep("jin2003", param="omega=6:7:3", threads=2000),
     "threads = 2000: expected 1 to 1024"),
    (lambda: impactlab.sweep("jin2003", param="omega=6:7:3", period_tol=0.0),
     "period_tol = 0.0: must be > 0"),
    (lambda: impactlab.continue_("linear_impact", param="omega=2:3", max_points=1),
     "max_points = 1: expected a whole number >= 2"),
    (lambda: impactlab.continue_("linear_impact", param="omega=2:3", max_step=-1.0),
     "max_step = -1.0: must be >= 0"),
    (lambda: impactlab.periodic("jin2003", phase=7.0), "phase = 7.0: expected 0 to 6.28319 rad"),
])
def test_ranges_come_from_the_table(call, message):
    with pytest.raises(ValueError) as raised:
        call()
    assert str(raised.value) == message


def test_continue_tolerance_is_the_table_s():
    row = {r["name"]: r for r in _impactlab.job_options("continue")}["tolerance"]
    assert row["default"] == 1e-10
    assert not math.isinf(row["lower"]) and row["lower_open"]
