"""Parameter validation and report verdicts."""

import numpy as np
import pytest

from mechlib.params import check_choice, check_float, check_increasing, check_int, check_matrix
from mechlib.reporting import report


def test_checks_accept_good_values() -> None:
    assert check_int("n", 3, low=1, high=5) == 3
    assert check_float("a", 0.5, low=0.0, high=1.0, low_open=True) == 0.5
    assert check_choice("m", "ridge", ("ridge", "lasso")) == "ridge"
    np.testing.assert_array_equal(check_increasing("amps", [0.1, 1], low=0.0), [0.1, 1.0])


@pytest.mark.parametrize(
    ("call", "exc", "message"),
    [
        (
            lambda: check_int("n_random_designs", 0, low=1, high=100),
            ValueError,
            r"n_random_designs must be in \[1, 100\], got 0",
        ),
        (lambda: check_int("seed", 1.5, low=0), TypeError, "seed must be an integer >= 0, got 1.5"),
        (lambda: check_int("seed", True), TypeError, "seed must be an integer"),
        (
            lambda: check_float("alpha", 0.0, low=0.0, high=0.5, low_open=True),
            ValueError,
            r"alpha must be in \(0.0, 0.5\], got 0.0",
        ),
        (lambda: check_float("alpha", "x"), TypeError, "alpha must be a real number"),
        (lambda: check_float("sigma", float("inf")), ValueError, "sigma must be finite"),
        (
            lambda: check_increasing("amps", [1.0, 0.1], low=0.0, high=50.0, low_open=True),
            ValueError,
            r"amps must list at least 2 strictly increasing values in \(0.0, 50.0\], "
            r"got \[1.0, 0.1\]",
        ),
        (lambda: check_increasing("amps", [0.5]), ValueError, "amps must list at least 2"),
        (
            lambda: check_increasing("amps", [0.5, 60.0], high=50.0),
            ValueError,
            "amps must be <= 50",
        ),
        (
            lambda: check_choice("penalty", "l3", ("ridge", "lasso")),
            ValueError,
            r"penalty must be one of \['ridge', 'lasso'\], got 'l3'",
        ),
        (
            lambda: check_matrix("poses", [[1.0, 2.0], [3.0]]),
            ValueError,
            r"poses must be a 2-D array of numbers with rows of equal length, got \[\[1.0, 2.0\]",
        ),
        (lambda: check_matrix("poses", [1.0, 2.0]), ValueError, "poses must be a 2-D array"),
    ],
)
def test_bad_values_name_the_parameter_and_range(call, exc, message) -> None:
    with pytest.raises(exc, match=message):
        call()


def test_verdicts_follow_the_numbers() -> None:
    row = report.compare_row("T", "q", [1.00, 2.00], [1.004, 2.0], resolution=0.005)
    assert row["verdict"] == "reproduced"
    row = report.compare_row("T", "q", [1.0], [1.01], resolution=0.005, rtol=0.01)
    assert row["verdict"] == "within tolerance (1 %)"
    row = report.compare_row("T", "q", [1.0], [1.2], rtol=0.01, cause="a reason")
    assert row["verdict"] == "diverges: a reason" and row["max_rel_diff"] == pytest.approx(0.2)
    with pytest.raises(ValueError, match="a cause must be given"):
        report.compare_row("T", "q", [1.0], [1.2])


def test_table_number_format_shows_round_off_as_zero_but_not_nan() -> None:
    fmt = report.float_format(6, zero_below=1e-9)
    assert [fmt(v) for v in (123456.7, -1e-12, 2e-9, float("nan"))] == [
        "123457",
        "0",
        "2e-09",
        "nan",
    ]
    assert report.float_format(3)(0.0) == "0" and report.float_format(3)(1e-20) == "1e-20"
    with pytest.raises(ValueError, match="digits must be in"):
        report.float_format(0)
