"""Place objects for a pick-and-place loop.

Reads a task folder (demonstrations and a problem), learns the rules,
synthesises the layout and prints, in the order a robot should place them,
where each object goes: bottom row first (south to north), west to east
within a row, so that every block is put down next to ones already there.

    python python/examples/pick_and_place.py examples/box-packing
"""

from __future__ import annotations

import sys
from pathlib import Path

import rccpack


def main(task: Path) -> int:
    demos = rccpack.load_scenes(task / "demos.json")
    problem = rccpack.load_scene(task / "problem.json")
    learned = rccpack.learn(demos)
    result = rccpack.synthesize(problem, learned.rules, like=demos, time_limit=30.0)
    if result.scene is None:
        print(f"no layout: {result.status.value} {result.conflict}", file=sys.stderr)
        return 2
    to_place = {o.id for o in problem.objects if not o.placed}
    targets = [o for o in result.scene.objects if o.id in to_place]
    targets.sort(key=lambda o: (o.y or 0, o.x or 0))
    print(f"# {len(targets)} objects, score {result.score:.3f}, {result.status.value}")
    print("# step  id     class  size      place at (x, y)   centre")
    for step, o in enumerate(targets, 1):
        assert o.x is not None and o.y is not None
        cx, cy = o.x + o.width / 2, o.y + o.height / 2
        print(f"{step:6d}  {o.id:<6} {o.cls:<6} {o.width}x{o.height:<6} ({o.x}, {o.y}){'':8} ({cx:g}, {cy:g})")
    return 0


if __name__ == "__main__":
    default = Path(__file__).resolve().parents[2] / "examples" / "box-packing"
    sys.exit(main(Path(sys.argv[1]) if len(sys.argv) > 1 else default))
