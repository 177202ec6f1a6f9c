"""Times python canopen's import_od on one EDS: prints the best of N runs in seconds.

Usage: eds_import.py FILE.eds RUNS
"""

import sys
import time

import canopen


def main():
    path, runs = sys.argv[1], int(sys.argv[2])
    best = float("inf")
    entries = 0
    for _ in range(runs):
        start = time.perf_counter()
        od = canopen.objectdictionary.import_od(path)
        best = min(best, time.perf_counter() - start)
        entries = sum(len(o) if hasattr(o, "subindices") else 1 for o in od.values())
    print(f"{best:.6f} {len(od)} {entries}")


if __name__ == "__main__":
    main()
