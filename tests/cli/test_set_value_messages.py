"""--set's messages in the words of a value on the command line (issue 29's
trial): '--set H=' said "expected an expression, found ';'", a ';' the user never
typed; '--set H=abc' suggested a parameter 'Abc' that has no value there."""

import pytest

from tests.support.cli import run_here

SCENE = "H = 1;\n> @s(H) !cu(1, 1, 1);\n"
KNOWS = "a --set value knows PI, TOLERANCE and the earlier --set parameters, not the scene's"


@pytest.mark.parametrize("given, message", [
    ("H=", "--set H=: no value after '='; give a number or an expression, such as --set H=3.2"),
    ("H=  ", "--set H=  : no value after '='; give a number or an expression, such as "
             "--set H=3.2"),
    ("H=1+", "--set H=1+: expected an expression, found the end of the value"),
    ("H=(2", "--set H=(2: expected ')', found the end of the value"),
    ("H=1 2", "--set H=1 2: expected an operator or the end of the value, found the number 2"),
    ("H=abc", f"--set H=abc: 'abc' is neither a number nor a parameter: --set takes a number, "
              f"such as --set H=3.2, or an expression; {KNOWS}"),
    ("H=Abc", f"--set H=Abc: parameter 'Abc' is not defined; {KNOWS}"),
    ("H=pi", "--set H=pi: 'pi' is not a parameter: parameter names start with an uppercase "
             "letter (PI)"),
])
def test_a_faulty_value_says_what_the_user_wrote(given, message):
    status, out, err = run_here("--no-cpp", "--set", given, stdin=SCENE)
    assert status == 2
    assert err.splitlines()[0] == f"castor: error: {message}"
    assert "';'" not in err


def test_good_values_still_work():
    status, out, err = run_here("--no-cpp", "--check", "--set", "W=2", "--set", "H=W*PI",
                                stdin=SCENE)
    assert status == 0, err
