#!/usr/bin/env python3
"""Compiles one translation unit and checks its compiler CPU time and peak memory against a
budget (docs/contributing.md, compile cost). The figures are read from getrusage of the
compiler's processes, so no timing tool is needed. The CPU budget is a multiple of the CPU
that compiling a yardstick (Eigen's dense module and FFT, yardstick.cpp) takes with the same
compiler and flags on the same machine, so that it holds on a slower machine as well.

    check_compile_cost.py --cpu-ratio R --yardstick FILE --megabytes M -- COMPILER ARGS... -c SOURCE -o OUT
"""
import argparse
import resource
import subprocess
import sys


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cpu-ratio", type=float, required=True,
                        help="budget of user + system CPU, in units of the yardstick's")
    parser.add_argument("--yardstick", required=True, help="source compiled first, with the same flags")
    parser.add_argument("--megabytes", type=float, required=True, help="budget of peak resident memory (MB)")
    parser.add_argument("--label", default="translation unit", help="what is compiled, for the report")
    parser.add_argument("command", nargs=argparse.REMAINDER, help="-- then the compiler command")
    args = parser.parse_args()
    command = args.command[1:] if args.command[:1] == ["--"] else args.command
    if not command:
        parser.error("no compiler command after --")
    if "-c" not in command or command.index("-c") + 1 >= len(command):
        parser.error("the compiler command needs -c SOURCE")
    source = command.index("-c") + 1
    yardstick = command[:source] + [args.yardstick] + ["-o", "/dev/null"]

    def cpu_of(compile_command):
        """Compiler CPU (s) of one command, and the largest resident set of any child so far (MB)."""
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        completed = subprocess.run(compile_command)
        if completed.returncode != 0:
            print(f"compile cost: {args.label}: the compiler failed (exit {completed.returncode}): "
                  f"{' '.join(compile_command)}", file=sys.stderr)
            return None, 0
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        cpu = (after.ru_utime + after.ru_stime) - (before.ru_utime + before.ru_stime)
        return cpu, after.ru_maxrss / 1024  # kB on Linux

    yardstick_cpu, _ = cpu_of(yardstick)
    if yardstick_cpu is None:
        return 1
    # The program second: ru_maxrss is the largest of all children, and the program's
    # compiler needs far more memory than the yardstick's.
    cpu, megabytes = cpu_of(command)
    if cpu is None:
        return 1
    budget = args.cpu_ratio * yardstick_cpu
    within = cpu <= budget and megabytes <= args.megabytes
    print(f"compile cost: {args.label}: cpu_s={cpu:.1f} ({cpu / yardstick_cpu:.1f} x the yardstick's "
          f"{yardstick_cpu:.2f} s; budget {args.cpu_ratio:g} x = {budget:.1f} s) "
          f"peak_mb={megabytes:.0f} (budget {args.megabytes:g}) {'within' if within else 'OVER BUDGET'}")
    return 0 if within else 1


if __name__ == "__main__":
    sys.exit(main())
