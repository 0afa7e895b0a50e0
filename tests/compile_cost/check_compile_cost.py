#!/usr/bin/env python3
"""Compiles one translation unit and checks its compiler CPU time and peak memory against a
budget (docs/contributing.md, compile cost). The figures are read from getrusage of the
compiler's processes, so no timing tool is needed.

    check_compile_cost.py --cpu-seconds S --megabytes M -- COMPILER ARGS...
"""
import argparse
import resource
import subprocess
import sys


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cpu-seconds", type=float, required=True, help="budget of user + system CPU (s)")
    parser.add_argument("--megabytes", type=float, required=True, help="budget of peak resident memory (MB)")
    parser.add_argument("--label", default="translation unit", help="what is compiled, for the report")
    parser.add_argument("command", nargs=argparse.REMAINDER, help="-- then the compiler command")
    args = parser.parse_args()
    command = args.command[1:] if args.command[:1] == ["--"] else args.command
    if not command:
        parser.error("no compiler command after --")
    completed = subprocess.run(command)
    if completed.returncode != 0:
        print(f"compile cost: {args.label}: the compiler failed (exit {completed.returncode})", file=sys.stderr)
        return 1
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = usage.ru_utime + usage.ru_stime
    megabytes = usage.ru_maxrss / 1024  # kB on Linux
    within = cpu <= args.cpu_seconds and megabytes <= args.megabytes
    print(f"compile cost: {args.label}: cpu_s={cpu:.1f} (budget {args.cpu_seconds:g}) "
          f"peak_mb={megabytes:.0f} (budget {args.megabytes:g}) {'within' if within else 'OVER BUDGET'}")
    return 0 if within else 1


if __name__ == "__main__":
    sys.exit(main())
