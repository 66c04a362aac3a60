"""400 references to one tree: the tree is facetized once (its one union is
the only boolean operation), and the whole frame costs at most twice the
time of writing it.
"""

import time

from _common import runs_from_env

RUNS = runs_from_env(3)

SCENE = """
arbre = $U(@h(0.15, 0.15, 1.2) !cy(0.45, 0.3, 0.15), @t(0, 0, 1.8) @h(0.8) !sp(0.2, 0.55, 0.2));
rangee = $U[J = 0, 19](@t(2.5 * J, 0, 0) arbre);
> $U[I = 0, 19](@t(0, 2.5 * I, 0) rangee);
"""


def main() -> None:
    from castor.mesh.facetize import Facetizer
    from castor.language.parse import Parser
    from castor.language.reader import Chunk
    from castor.language.scene import Tables
    from castor.formats import cps

    best = None
    for _ in range(RUNS):
        tables = Tables(parameters={"TOLERANCE": 0.01})
        parser = Parser(tables)
        statements = []
        for number, line in enumerate(SCENE.strip().splitlines(), 1):
            for statement in parser.parse(Chunk(line, (("forest", number),), 0)):
                if hasattr(statement, "node"):
                    tables.objects[statement.name] = statement.node
                statements.append(statement)
        facetizer = Facetizer()
        started = time.perf_counter()
        frame = facetizer.frame(statements[-1].objects, {"TOLERANCE": 0.01}, 1, "forest:3", None)
        facetize = time.perf_counter() - started
        started = time.perf_counter()
        cps.export(frame)
        write = time.perf_counter() - started
        if best is None or facetize + write < best[0] + best[1]:
            best = (facetize, write, facetizer.counter.booleans, facetizer.primitive_count,
                    frame.polygon_count)
    facetize, write, booleans, primitives, polygons = best
    print(f"400 trees: {primitives} primitives, {booleans} boolean operation(s) sent to the "
          f"engine, {polygons} polygons")
    print(f"facetize {facetize:.3f} s, write {write:.3f} s: total / write = "
          f"{(facetize + write) / write:.2f} (target <= 2)")


if __name__ == "__main__":
    main()
