"""Scenes several test modules use."""

# one statement of 40,000 cubes: seconds of parsing, to show that stale work
# stops inside a statement (the language server's and the live preview's)
CUBES = 40_000
LONG = "big = $U(" + ", ".join(f"@t({k % 200}, {k // 200}, 0) !cu(1, 0, 0)"
                               for k in range(CUBES)) + ");\n> big;\n"


# a new user's two-storey house (issue 29's second trial): 10 x 6 m, walls 0.3,
# storeys at 0 and 3.2; a door, windows (sills 1.0, heads 2.2 below), a stair of
# 17 risers at x = 8.7 .. 9.7 under a well in the upper floor (0.25 thick, its
# underside at 2.95), a roof 0.3 on top at 6.4
TRIAL_HOUSE = """
#define BLANC 0.9, 0.9, 0.85
#define BLEU 0.2, 0.4, 0.9
#define GRIS 0.6, 0.6, 0.6
#define BOIS 0.5, 0.35, 0.2
N0 = 0;     // [storey "Ground"]
N1 = 3.2;   // [storey "Upper"]
L = 10;
P = 6;
E = 0.3;
ES = 0.25;
shell = $D(@h(L, P, N1) !cu(BLANC), @t(E, E, -0.1) @h(L - 2 * E, P - 2 * E, N1 + 0.2) !cu(BLANC));
door1 = @t(2, -0.1, 0) @h(1.0, E + 0.2, 2.2) !cu(BLEU);   // [door hinge=right swing=in]
win1 = $U[I = 0, 1](@t(5 + I * 3, -0.1, 1.0) @h(1.5, E + 0.2, 1.2) !cu(BLEU));  // [window]
walls0 = $D(shell, $U(door1, win1));  // [wall] ground walls
base = @t(0, 0, -ES) @h(L, P, ES) !cu(GRIS);  // [slab baseslab]
NR = 17;
G = 0.25;
step = @t(L - E - 1, E + 0.5 + I * G, 0) @h(1, G, (I + 1) * N1 / NR) !cu(BOIS);
stair = $U[I = 0, NR - 1](step);  // [stair straight_run_stair]
well = @t(L - E - 1.1, E + 0.5, N1 - ES - 0.1) @h(1.1, NR * G, ES + 0.2) !cu(GRIS);
floor1 = $D(@t(E, E, N1 - ES) @h(L - 2 * E, P - 2 * E, ES) !cu(GRIS), well);  // [slab floor]
win2 = $U[I = 0, 2](@t(1.5 + I * 3, -0.1, N1 + 0.9) @h(1.2, E + 0.2, 1.4) !cu(BLEU));  // [window]
walls1 = $D(@t(0, 0, N1) shell, win2);  // [wall] upper walls
roof = @t(0, 0, 2 * N1) @h(L, P, 0.3) !cu(GRIS);  // [slab roof]
house = $U(base, walls0, stair, floor1, walls1, roof);
> house;
"""
