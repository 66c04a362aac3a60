"""Messages a new user met (issue 18, item 15): what they say, in the user's words."""

import subprocess
import sys


def castor(text: str, *args: str):
    done = subprocess.run([sys.executable, "-m", "castor", "--no-cpp", *args], input=text,
                          capture_output=True, text=True, timeout=60)
    return done.returncode, done.stdout, done.stderr


def test_a_function_call_after_a_lowercase_name_says_it_names_an_object():
    status, out, err = castor("h = sqrt(-1);\n")
    first = err.splitlines()[0]
    assert first.startswith("<stdin>:1:5: error: "), err
    assert "function" in first and "'h'" in first and "lowercase" in first
    assert "H = sqrt(" in first  # what to write instead
    assert status == 1


def test_a_function_call_where_an_object_is_expected():
    status, out, err = castor("> @t(1, 0, 0) sin(30);\n")
    first = err.splitlines()[0]
    assert first.startswith("<stdin>:1:15: error: "), err
    assert "'sin' is a function" in first and "object" in first
    assert "uppercase" in first


def test_an_object_name_followed_by_parentheses():
    status, out, err = castor("a = !cu(1, 0, 0);\n> a(2);\n")
    first = err.splitlines()[0]
    assert first.startswith("<stdin>:2:3: error: "), err
    assert "'a' is an object" in first and "takes no arguments" in first


def test_dev_null_with_errors_is_not_said_to_be_left_out():
    status, out, err = castor("x\n", "-o", "/dev/null")
    assert status == 1
    assert "not written" not in err, err
    assert err.startswith("<stdin>:")
