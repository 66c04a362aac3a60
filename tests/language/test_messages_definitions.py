"""Messages about a faulty definition and a colour out of range (issue 18, item 15)."""

from tests.support.cli import run


def test_a_use_of_an_object_whose_definition_had_a_syntax_error_says_so():
    scene = "a = $U(!cu(1, 0, 0) !sp(0, 1, 0));\n> a;\n// b\nb = @t(1, 2) !cu(1, 1, 1);\n> b;\n"
    for options in ([], ["--no-cpp"]):
        status, _, err = run("--check", *options, stdin=scene)
        assert status == 1
        assert "<stdin>:2:3: error: object 'a' is not defined (its definition had errors)" in err
        assert "<stdin>:5:3: error: object 'b' is not defined (its definition had errors)" in err


def test_an_undefined_object_with_no_faulty_definition_is_only_undefined():
    _, _, err = run("--check", stdin="x = !cu(1, 1, 1);\n> y;\n")
    assert "object 'y' is not defined" in err
    assert "had errors" not in err


def test_a_later_good_definition_is_used_again():
    status, _, err = run("--check", stdin="a = !cu(1, 1, 1;\na = !cu(1, 1, 1);\n> a;\n")
    assert status == 1  # the first definition's own error
    assert "object 'a' is not defined" not in err


def test_only_a_whole_number_up_to_255_suggests_a_byte():
    for value, hint in (("200", "write 200/255"), ("255", "write 255/255"), ("1.8", None),
                        ("2.5", None), ("256", None), ("-3", None)):
        _, _, err = run("--check", stdin=f"> !cu({value}, 0, 0);\n")
        assert f"colour component red = {value} of !cu is outside 0..1" in err, err
        if hint is None:
            assert "/255" not in err, err
        else:
            assert hint in err, err
