"""The expression evaluator: numbers, parameters, operators and functions.

Angles are in degrees. Every division by zero, domain error, overflow or
non-finite result is an ``EvaluationError`` at the position of the operator or
call that produced it, so that a NaN or an infinity never reaches the geometry.
"""

from __future__ import annotations

import math
from typing import Callable, Mapping

from castor.diagnostics import EvaluationError, Location
from castor.language.scene import Binary, Expr, Number, Param, Unary

_RAD = math.pi / 180.0


def _round(x: float) -> float:
    # C's round(): halves go away from zero (Python's round() goes to even).
    return math.copysign(math.floor(abs(x) + 0.5), x)


def _asin(x: float) -> float:
    if not -1.0 <= x <= 1.0:
        raise ValueError(f"asin is defined for -1..1, not {format_number(x)}")
    return math.asin(x) / _RAD


def _acos(x: float) -> float:
    if not -1.0 <= x <= 1.0:
        raise ValueError(f"acos is defined for -1..1, not {format_number(x)}")
    return math.acos(x) / _RAD


def _sqrt(x: float) -> float:
    if x < 0:
        raise ValueError(f"square root of a negative number ({format_number(x)})")
    return math.sqrt(x)


def _log(x: float) -> float:
    if x <= 0:
        raise ValueError(f"logarithm of a number that is not positive ({format_number(x)})")
    return math.log(x)


def _tan(x: float) -> float:
    if math.remainder(x - 90.0, 180.0) == 0.0:
        raise ValueError(f"tan is undefined at {format_number(x)} degrees")
    return math.tan(x * _RAD)


# name -> (function, minimum arguments, maximum arguments or None for any)
FUNCTIONS: dict[str, tuple[Callable[..., float], int, int | None]] = {
    "sin": (lambda x: math.sin(x * _RAD), 1, 1),
    "cos": (lambda x: math.cos(x * _RAD), 1, 1),
    "tan": (_tan, 1, 1),
    "asin": (_asin, 1, 1),
    "acos": (_acos, 1, 1),
    "atan": (lambda x: math.atan(x) / _RAD, 1, 1),
    "atan2": (lambda y, x: math.atan2(y, x) / _RAD, 2, 2),
    "sqrt": (_sqrt, 1, 1),
    "abs": (abs, 1, 1),
    "exp": (math.exp, 1, 1),
    "log": (_log, 1, 1),
    "floor": (lambda x: float(math.floor(x)), 1, 1),
    "ceil": (lambda x: float(math.ceil(x)), 1, 1),
    "round": (_round, 1, 1),
    "min": (min, 1, None),
    "max": (max, 1, None),
}


def arity_message(name: str, given: int) -> str | None:
    """The message for calling ``name`` with ``given`` arguments, or None if fine."""
    _, low, high = FUNCTIONS[name]
    if given >= low and (high is None or given <= high):
        return None
    if high is None:
        wanted = f"at least {low} argument{'s' if low > 1 else ''}"
    elif low == high:
        wanted = f"{low} argument{'s' if low > 1 else ''}"
    else:
        wanted = f"{low} to {high} arguments"
    return f"function '{name}' takes {wanted}, but {given} {'was' if given == 1 else 'were'} given"


def format_number(x: float) -> str:
    """A number as a person would write it: 3 rather than 3.0, 1.2 rather than the
    1.2000000000000002 that 0.4 * 3 computes (12 significant digits)."""
    if not math.isfinite(x):
        return repr(x)
    if x == int(x) and abs(x) < 1e15:
        return str(int(x))
    return f"{x:.12g}"


def _finite(value: float, location: Location, what: str) -> float:
    if math.isfinite(value):
        return value
    raise EvaluationError(f"{what} is not a finite number (overflow)", location)


def _binary(op: str, a: float, b: float, location: Location) -> float:
    try:
        if op == "+":
            r = a + b
        elif op == "-":
            r = a - b
        elif op == "*":
            r = a * b
        elif op == "/":
            if b == 0:
                raise EvaluationError("division by zero", location)
            r = a / b
        elif op == "%":
            if b == 0:
                raise EvaluationError("division by zero in '%' (remainder)", location)
            r = math.fmod(a, b)
            if r != 0 and (r < 0) != (b < 0):
                r += b
        else:  # '^'
            if a == 0 and b < 0:
                raise EvaluationError("division by zero (0 raised to a negative power)", location)
            if a < 0 and b != int(b):
                raise EvaluationError(
                    f"a negative number ({format_number(a)}) raised to a fractional power "
                    f"({format_number(b)}) has no real value", location)
            r = math.pow(a, b)
    except OverflowError:
        raise EvaluationError(f"overflow in '{op}'", location) from None
    return _finite(r, location, f"the result of '{op}'")


class UndefinedParameter(EvaluationError):
    """A parameter read where it has no value."""

    def __init__(self, name: str, location: Location):
        super().__init__(f"parameter '{name}' is not defined", location)
        self.name = name


def evaluate(expr: Expr, env: Mapping[str, float]) -> float:
    """The value of ``expr`` with the parameter values of ``env``."""
    kind = type(expr)
    if kind is Number:
        return expr.value
    if kind is Param:
        try:
            return env[expr.name]
        except KeyError:
            raise UndefinedParameter(expr.name, expr.location) from None
    if kind is Binary:
        return _binary(expr.op, evaluate(expr.left, env), evaluate(expr.right, env), expr.location)
    if kind is Unary:
        value = evaluate(expr.operand, env)
        return -value if expr.op == "-" else value
    # Call
    function = FUNCTIONS[expr.function][0]
    values = [evaluate(a, env) for a in expr.args]
    try:
        result = function(*values)
    except ValueError as exc:
        raise EvaluationError(f"{exc} in {expr.function}()", expr.location) from None
    except OverflowError:
        raise EvaluationError(f"overflow in {expr.function}()", expr.location) from None
    return _finite(float(result), expr.location, f"the result of {expr.function}()")
