"""The oracle's command line: many random scenes in batches, the figures, and
the smallest reproduction of each kind of failure."""

from __future__ import annotations

import argparse
import os
import sys
import time

from .check import FINER, check_scenes
from .evaluate import NOT_MADE
from .generate import scenes
from .judge import ORACLE_WRONG, UNSURE, kind_of
from .scene import scene_text
from .shrink import shrink


def main() -> None:
    parser = argparse.ArgumentParser(
        prog="python -m tests.oracle",
        description="A differential oracle for castor's geometry (LANGUAGE.md §3-§8).")
    parser.add_argument("--cases", type=int, default=300)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--batch", type=int, default=50)
    parser.add_argument("--no-sheets", action="store_true", help="skip the winding test")
    parser.add_argument("--no-shrink", action="store_true")
    parser.add_argument("--exact", action="store_true",
                        help="decide volume disagreements with exact booleans (needs pymeshlab)")
    parser.add_argument("--wide", action="store_true",
                        help="mix in coincident twins and turned rows (WideGenerator)")
    parser.add_argument("--smooth", action="store_true",
                        help="scenes with smooth solids (@s), judged as README says")
    parser.add_argument("--save", metavar="DIR", help="write each failing scene and its problems there")
    args = parser.parse_args()
    started = time.time()
    failures = []
    frames = 0
    for start in range(0, args.cases, args.batch):
        batch = scenes(min(args.batch, args.cases - start), args.seed * 1_000_003 + start,
                       args.wide, args.smooth)
        frames += sum(s.frames() for s in batch)
        found = check_scenes(batch, sheets=not args.no_sheets, exact=args.exact)
        if args.save:  # as they are found: a long run stopped early keeps them
            os.makedirs(args.save, exist_ok=True)
            for k, (scene, number, problems) in enumerate(found, len(failures)):
                with open(os.path.join(args.save, f"failure-{k:03d}.cas"), "w") as f:
                    f.write("".join(f"// frame {number}: {p}\n" for p in problems))
                    f.write(scene_text(scene))
        failures += found
        print(f"{start + len(batch)} scenes, {frames} frames, {len(failures)} failing frames, "
              f"{time.time() - started:.0f} s", file=sys.stderr)
    kinds: dict[str, list] = {}
    for scene, number, problems in failures:
        for p in problems:
            kinds.setdefault(kind_of(p), []).append((scene, number, p))
    print(f"{args.cases} scenes, {frames} frames, {len(failures)} failing frames "
          f"({time.time() - started:.0f} s); in {len(UNSURE)} frames manifold3d's own result "
          "held a sheet, and only castor's surface was judged (no area or box)"
          + (f"; {len(NOT_MADE)} smooth solids of the oracle refused by manifold3d "
             "(judged for their surface)" if args.smooth else "")
          + f"; {len(FINER)} smooth frames within the distance only at a tenth of the tolerance"
          + (f"; in {len(ORACLE_WRONG)} frames exact booleans gave castor's volume or area, "
             "not manifold3d's" if args.exact else ""))
    for kind, items in sorted(kinds.items(), key=lambda kv: -len(kv[1])):
        scenes_failing = len({id(s) for s, _, _ in items})
        print(f"\n== {kind}: {scenes_failing} scenes; e.g. frame {items[0][1]}: {items[0][2]}")
        if not args.no_shrink:
            small = shrink(items[0][0], kind, not args.no_sheets, args.exact)
            print(scene_text(small))
