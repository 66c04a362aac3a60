"""Scenes several test modules use."""

# one statement of 40,000 cubes: seconds of parsing, to show that stale work
# stops inside a statement (the language server's and the live preview's)
CUBES = 40_000
LONG = "big = $U(" + ", ".join(f"@t({k % 200}, {k // 200}, 0) !cu(1, 0, 0)"
                               for k in range(CUBES)) + ");\n> big;\n"
