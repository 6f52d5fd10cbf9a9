#!/usr/bin/env python3
"""How far two `railwear contact --json` outputs of one scene are apart (docs/library.md, "The
curved operator's products in one pass"): the count of numbers that differ, the largest relative
moves |a - b| / max(|a|, |b|) with their values (times, `time_ms` and `stages`, left out), and
the normal solver's iterations of both.

  python3 tests/tools/contact_json_moves.py BEFORE.json AFTER.json [LABEL]

A number near zero (a lateral force of a symmetric patch, a contact point's x) moves by 100 %
when its rounding noise changes: read the values printed beside each move.
"""
import json
import sys


def numbers(x, path=""):
    if isinstance(x, dict):
        for k, v in x.items():
            if k not in ("time_ms", "stages"):
                yield from numbers(v, f"{path}.{k}")
    elif isinstance(x, list):
        for i, v in enumerate(x):
            yield from numbers(v, f"{path}[{i}]")
    elif isinstance(x, (int, float)) and not isinstance(x, bool):
        yield path, x


def main(before, after, label):
    with open(before) as f:
        a = json.load(f)
    with open(after) as f:
        b = json.load(f)
    na, nb = dict(numbers(a)), dict(numbers(b))
    if na.keys() != nb.keys():
        sys.exit(f"{label}: the outputs have different fields")
    moves = sorted(((abs(na[k] - nb[k]) / max(abs(na[k]), abs(nb[k])), k)
                    for k in na if na[k] != nb[k]), reverse=True)
    iterations = [(k, na[k], nb[k]) for k in na if k.endswith(".iterations")]
    print(f"{label}: {len(moves)} of {len(na)} numbers differ; iterations "
          + ", ".join(f"{x} -> {y}" for _, x, y in iterations))
    for m, k in moves[:3]:
        print(f"  {m:.1e} {k}: {na[k]!r} -> {nb[k]!r}")


if __name__ == "__main__":
    if len(sys.argv) not in (3, 4):
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2], sys.argv[3] if len(sys.argv) == 4 else sys.argv[2])
