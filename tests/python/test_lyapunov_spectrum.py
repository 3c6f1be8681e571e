"""The Lyapunov spectrum in Python: poincare(..., lyapunov_spectrum=True)
gives the numbers of the CLI's meta.json and lyapunov.csv, λ1 is the largest
exponent, a collapsed direction is -inf (never nan), sweep and basins rows
gain lyapunov1..N, and a bad value is a ValueError naming the keyword."""
import json
import math

import numpy as np
import pytest

import impactlab

from conftest import read_csv


def test_poincare_spectrum_is_the_clis(cli):
    result = impactlab.poincare("linear_impact", omega=2.6, points=200, lyapunov=True,
                                lyapunov_spectrum=True)
    assert result.lyapunov_spectrum.shape == (2,)
    assert result.lyapunov_spectrum[0] == pytest.approx(result.lyapunov, abs=1e-10)
    assert result.lyapunov_spectrum[0] > 0.05 > result.lyapunov_spectrum[1]
    assert result.lyapunov_running.shape == (200, 2)
    assert len(result.lyapunov_running_t) == 200
    np.testing.assert_array_equal(result.lyapunov_running[-1], result.lyapunov_spectrum)
    assert np.all(result.lyapunov_spectrum_error >= 0.0)

    out = cli("poincare", "linear_impact", "--set", "omega=2.6", "--points", "200",
              "--lyapunov-spectrum")
    meta = json.loads((out / "meta.json").read_text())
    assert meta["lyapunov_spectrum"] == list(result.lyapunov_spectrum)
    assert meta["lyapunov_spectrum_error"] == list(result.lyapunov_spectrum_error)
    lines = (out / "lyapunov.csv").read_text().splitlines()
    (out / "rows.csv").write_text("\n".join(lines[1:]) + "\n")
    rows = read_csv(out / "rows.csv")
    assert rows["t"] == list(result.lyapunov_running_t)
    assert rows["lambda2"] == list(result.lyapunov_running[:, 1])


def test_sticking_gives_minus_infinity_not_nan():
    result = impactlab.poincare("bouncing_ball", r=0.3, A=0.015, points=30,
                                lyapunov_spectrum=True)
    assert list(result.lyapunov_spectrum) == [-math.inf, -math.inf]
    assert not np.isnan(result.lyapunov_running).any()


def test_without_the_keyword_there_is_no_spectrum():
    result = impactlab.poincare("linear_impact", points=5)
    assert not hasattr(result, "lyapunov_spectrum")
    summary = impactlab.sweep("linear_impact", param="omega=2.5:2.6:2", points=5).summary
    assert "lyapunov1" not in summary


def test_sweep_and_basins_rows_gain_the_exponents():
    summary = impactlab.sweep("linear_impact", param="omega=2.5:2.7:3", points=40,
                              lyapunov=True, lyapunov_spectrum=True).summary
    np.testing.assert_allclose(summary["lyapunov1"], summary["lyapunov"], atol=1e-10, rtol=0)
    assert len(summary["lyapunov2"]) == 3
    grid = impactlab.basins("linear_impact", x="omega=2.5:2.6:2", y="initial.x=0:0.1:2",
                            points=20, lyapunov_spectrum=True).grid
    assert len(grid["lyapunov1"]) == 4 and len(grid["lyapunov2"]) == 4
    assert np.all(np.isfinite(grid["lyapunov2"]))


@pytest.mark.parametrize("function, arguments", [
    (impactlab.poincare, {}),
    (impactlab.sweep, {"param": "omega=2:2.1:2"}),
    (impactlab.basins, {"x": "omega=2:2.1:2", "y": "initial.x=0:0.1:2"}),
])
def test_bad_value_names_the_keyword(function, arguments):
    with pytest.raises(ValueError) as raised:
        function("linear_impact", lyapunov_spectrum="yes", **arguments)
    assert str(raised.value) == "lyapunov_spectrum = 'yes': expected True or False"
