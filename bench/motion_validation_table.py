#!/usr/bin/env python3
"""Reads the line `ClearanceMotionValidator.*` of meshgap_tests prints (1,500 random motions, each checked densely
by the exact collision test as the oracle; the test fails if an accepted motion collides) and writes it as a table:
the certified validator against OMPL's discrete one on the same motions.

    build/tests/meshgap_tests --gtest_filter='ClearanceMotionValidator.*' | python3 bench/motion_validation_table.py
"""
import re
import sys

LINE = re.compile(r'^motions (\d+): accepted (\d+), refused though free (\d+), refused by a probe (\d+); clearance '
                  r'queries (\d+) and probes (\d+) vs discrete state checks (\d+); collisions the discrete validator '
                  r'missed: (\d+)$')


def main():
    found = [LINE.match(line.strip()) for line in sys.stdin]
    found = [m for m in found if m]
    if len(found) != 1:
        print('motion_validation_table.py: expected one summary line from the test, got %d' % len(found),
              file=sys.stderr)
        return 1
    motions, accepted, refusedFree, byProbe, queries, probes, checks, missed = (int(g) for g in found[0].groups())
    print('%d random motions (%d accepted by the certified validator, %d refused; %d of the refusals by a probe), each '
          'also checked densely at 1/1000 of the motion by the exact collision test:' %
          (motions, accepted, motions - accepted, byProbe))
    print()
    print('| validator | motions accepted that collide | free motions refused | queries |')
    print('|---|---|---|---|')
    print('| `ClearanceMotionValidator` (certified clearance, conservative advancement) | 0 | %d | %s clearance queries '
          'and %s probes |' % (refusedFree, format(queries, ','), format(probes, ',')))
    print('| OMPL `DiscreteMotionValidator` (default resolution) | %d | 0 | %s state checks |' %
          (missed, format(checks, ',')))
    return 0


if __name__ == '__main__':
    sys.exit(main())
