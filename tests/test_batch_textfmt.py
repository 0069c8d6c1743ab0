"""The compiled CSV number formatter: the fewest of 15-17 digits that read back bit for bit."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from microslip.batch.textfmt import format_number, format_table, format_table_python

EDGES = [0.0, -0.0, np.nan, np.inf, -np.inf, 1e15, 1e14, 999999999999999.5, 99999999999999.95,
         1e16, 1e17, 9999999999999998.0, 0.99999999999999989, 1.0000000000000002, 2**53 + 2.0,
         1234567890123455.0, 0.5, 1e-5, 1e-4, 9.99999999999999e-5, 123456.0, 1e300, 5e-324,
         2.2250738585072014e-308, 1.7976931348623157e308, 2.5, 0.1, 0.3, 1 / 3, -7.25e-200,
         123456789012345.5, 0.000123456789012345]


def test_edge_cases_match_python() -> None:
    vals = np.array(EDGES)
    expected = "".join(format_number(v) + "\n" for v in EDGES).encode()
    assert bytes(format_table([vals])) == expected
    assert format_table_python([vals]) == expected


def test_random_magnitudes_and_ties_match_python() -> None:
    rng = np.random.default_rng(0)
    vals = np.concatenate([
        rng.random(20000) * 10.0 ** rng.integers(-300, 300, 20000),
        -rng.standard_normal(2000),
        np.round(rng.random(2000) * 1e6) / 1e3,  # short decimals
        rng.integers(0, 10**15, 2000).astype(float) + 0.5,  # exact halves
        rng.integers(10**15, 9 * 10**15, 2000).astype(float),  # integers near 2^53
        rng.integers(2**53, 2**57, 2000).astype(float),  # ties and near ties at 17 digits
        np.nextafter(rng.random(2000), 2.0),  # last-bit neighbours need all 17 digits
    ])
    cols = [vals[:13000], vals[13000:26000]]
    assert bytes(format_table(cols)) == format_table_python(cols)


@pytest.mark.slow
@settings(max_examples=150, deadline=None)
@given(st.lists(st.floats(allow_nan=True, allow_infinity=True, width=64), min_size=1,
                max_size=20))
def test_any_double(values: list[float]) -> None:
    expected = "".join(format_number(v) + "\n" for v in values).encode()
    assert bytes(format_table([values])) == expected


def test_rows_and_columns() -> None:
    out = bytes(format_table([[1.0, 2.0], [0.8, 0.8], [20000.0, 1e-7]]))
    assert out == b"1,0.8,20000\n2,0.8,1e-07\n"
    assert bytes(format_table([np.empty(0)])) == b""


def test_single_number_columns_repeat_on_every_row() -> None:
    rng = np.random.default_rng(2)
    cols = [rng.random(1000) * 1e4, 0.8, 20000.0, rng.standard_normal(1000), -1e-9, np.nan]
    assert bytes(format_table(cols)) == format_table_python(cols)
    assert bytes(format_table([[1.5, 2.5], 3.0])) == b"1.5,3\n2.5,3\n"


@pytest.mark.slow
@settings(max_examples=300, deadline=None)
@given(st.lists(st.floats(allow_nan=False, allow_infinity=True, width=64), min_size=1,
                max_size=20))
def test_written_numbers_read_back_bit_for_bit(values: list[float]) -> None:
    text = bytes(format_table([values])).decode()
    back = np.array([float(v) for v in text.split()])
    assert back.tobytes() == np.array(values).tobytes()
