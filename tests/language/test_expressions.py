"""Expressions: precedence, associativity, functions in degrees, errors at their position."""

import math

import pytest
from hypothesis import given, settings, strategies as st

from tests.support.cli import frames_of, run


def value_of(expr: str) -> float:
    """Evaluate expr by scaling a unit cube by it along x and reading the box."""
    frames = frames_of(f"V = {expr};\n> @h(V, 1, 1) !cu(1, 1, 1);\n")
    box = frames[0].box()
    return box[1][0] - box[0][0] if box[1][0] > 0 else -(box[1][0] - box[0][0])


@pytest.mark.parametrize("expr, expected", [
    ("-2^2", -4), ("2^3^2", 512), ("7 % -3", -2), ("-7 % 3", 2), ("atan2(1,1)", 45),
    ("1 + 2 * 3", 7), ("(1 + 2) * 3", 9), ("2^-1", 0.5), ("- -3", 3), ("10 - 4 - 3", 3),
    ("64 / 4 / 2", 8), ("sin(30)", 0.5), ("cos(60)", 0.5), ("acos(0)", 90), ("sqrt(16)", 4),
    ("max(1, 5, 3)", 5), ("min(4, 2, 8)", 2), ("round(2.5)", 3), ("round(-2.5)", -3),
    ("floor(-1.5)", -2), ("ceil(1.2)", 2), ("abs(-3)", 3), ("exp(0)", 1), ("log(exp(2))", 2),
    ("PI", math.pi), ("1e3", 1000), (".5", 0.5), ("1.", 1), ("2.5E-2", 0.025),
])
def test_expression_values(expr, expected):
    assert value_of(expr) == pytest.approx(expected, rel=1e-12)


@pytest.mark.parametrize("line, column, message", [
    ("X = 1 / 0;", 7, "division by zero"),
    ("X = sqrt(-1);", 5, "square root of a negative number"),
    ("X = log(0);", 5, "logarithm"),
    ("X = 10 ^ 400;", 8, "overflow"),
    ("X = exp(1000);", 5, "overflow"),
    ("X = 1e999;", 5, "too large"),
    ("X = sin(1, 2);", 5, "takes 1 argument, but 2 were given"),
    ("X = Y + 1;", 5, "parameter 'Y' is not defined"),
    ("X = (-8) ^ (1/3);", 10, "fractional power"),
    ("X = 5 % 0;", 7, "division by zero"),
    ("X = foo(1);", 5, "unknown function 'foo'"),
])
def test_expression_errors(line, column, message):
    status, out, err = run("--no-cpp", stdin=line + "\n")
    assert status == 1
    first = err.splitlines()[0]
    assert first.startswith(f"<stdin>:1:{column}: error: "), first
    assert message in first


def test_undefined_parameter_in_object_points_at_its_use():
    scene = "a = @t(1, 0, 0) @h(L) !cu(1, 1, 1);\n> a;\n"
    status, out, err = run("--no-cpp", stdin=scene)
    assert status == 1
    assert err.splitlines()[0] == "<stdin>:1:20: error: parameter 'L' is not defined"


@settings(max_examples=20, deadline=None)
@given(st.integers(-50, 50), st.integers(1, 20), st.integers(-9, 9))
def test_arithmetic_matches_python(a, b, c):
    expected = a * b - c + (a % b) - 2 ** (b % 5)
    expr = f"{a} * {b} - ({c}) + ({a} % {b}) - 2 ^ ({b} % 5)"
    got = value_of(f"({expr}) + 1000")
    assert got == pytest.approx(expected + 1000)
