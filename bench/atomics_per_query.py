#!/usr/bin/python3
"""Atomic read-modify-writes a thread executed (x86 instructions with a lock prefix, and xchg with memory, which
locks implicitly), from a callgrind profile of that thread: each instruction with its object, function and count,
and the count per query. An atomic on a query's path is where threads sharing a checker may meet (a counter, a
reference count, a lock, the allocator's arena); helgrind and DRD do not report atomics, this does.

    valgrind --tool=callgrind --separate-threads=yes --dump-instr=yes --compress-strings=no --compress-pos=no \\
        --callgrind-out-file=cg.out build/bench/meshgap_bench_stress --queries 20000 --threads 2 --fast-every 0
    bench/atomics_per_query.py cg.out-02 --queries 10000

(cg.out-01 is the main thread, -02 and -03 the two workers, each of which asked half the queries.) Needs objdump.
"""
import argparse
import collections
import re
import subprocess


def executed(path):
    """{(object, address): (count, function)} of every instruction in a callgrind file (absolute positions)."""
    counts, functions = collections.defaultdict(int), {}
    obj = fn = None
    call_cost = False
    with open(path) as f:
        for line in f:
            if line.startswith("ob="):
                obj = line[3:].strip()
            elif line.startswith("fn="):
                fn = line[3:].strip()
            elif line.startswith("calls="):
                call_cost = True  # the next cost line is the call's inclusive cost, not an instruction's own
            elif line.startswith("0x"):
                if call_cost:
                    call_cost = False
                    continue
                fields = line.split()
                key = (obj, int(fields[0], 16))
                counts[key] += int(fields[-1])
                functions[key] = fn
    return counts, functions


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("profile", help="one thread's callgrind file (--separate-threads=yes)")
    parser.add_argument("--queries", type=float, default=1.0, help="queries that thread asked (for the per-query column)")
    args = parser.parse_args()
    counts, functions = executed(args.profile)
    by_object = collections.defaultdict(set)
    for obj, address in counts:
        by_object[obj].add(address)
    rows = []
    for obj, addresses in by_object.items():
        try:
            text = subprocess.run(["objdump", "-d", "--no-show-raw-insn", obj], capture_output=True, text=True).stdout
        except OSError:
            continue
        for line in text.splitlines():
            m = re.match(r"\s*([0-9a-f]+):\s+(.*)", line)
            if m and re.match(r"(lock\b|xchg\s.*\()", m.group(2)):
                address = int(m.group(1), 16)
                if address in addresses:
                    key = (obj, address)
                    rows.append((counts[key], functions[key], obj.split("/")[-1], m.group(2).split("#")[0].strip()))
    print("%10s %10s  %-24s %-36s %s" % ("count", "per query", "object", "instruction", "function"))
    total = 0
    for count, fn, obj, instruction in sorted(rows, reverse=True):
        total += count
        print("%10d %10.4f  %-24s %-36s %s" % (count, count / args.queries, obj, instruction, fn[:120]))
    print("atomic read-modify-writes: %d, %.4f per query" % (total, total / args.queries))


if __name__ == "__main__":
    main()
