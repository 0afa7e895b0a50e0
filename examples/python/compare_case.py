#!/usr/bin/env python3
"""Solves a .case file with full NORM and a reduced solver and draws them side by side.

    PYTHONPATH=build/release/python python3 examples/python/compare_case.py CASE [--solver NAME] [--out FILE]

Prints both forces and the largest pressure difference, and writes the figure of
fastnorm.plot.compare (both maps, NORM's outline over the reduced one, the centre strip,
the difference) to FILE (default compare.png).
"""

import argparse
import time

import numpy as np

import fastnorm
import fastnorm.plot


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("case", help="the .case file (docs/case-format.md)")
    parser.add_argument("--solver", default="elliptic", help="the reduced solver (default elliptic)")
    parser.add_argument("--out", default="compare.png", help="the figure to write (default compare.png)")
    arguments = parser.parse_args()
    try:
        case = fastnorm.read_case(arguments.case)
        answers = {}
        for name in ("norm", arguments.solver):
            solver = fastnorm.Solver(name, case.grid, case.material)
            start = time.perf_counter()
            answers[name] = solver.solve(case.undeformed_distance_m, normal_force_n=case.normal_force_n)
            seconds = time.perf_counter() - start
            answer = answers[name]
            approach = f", approach {answer.approach_m * 1e6:.5g} um" if case.normal_force_n else ""
            print(f"{name:>16}: {answer.status}, Fn = {answer.normal_force_n:.6g} N{approach}, "
                  f"{answer.contact_count} elements in contact, {seconds:.3g} s")
    except ValueError as error:
        parser.error(str(error))
    norm, reduced = answers["norm"], answers[arguments.solver]
    peak = norm.pressure_pa.max()
    print(f"force difference {reduced.normal_force_n / norm.normal_force_n - 1:+.3e} of NORM's; "
          f"largest pressure difference {np.abs(reduced.pressure_pa - norm.pressure_pa).max() / peak:.3e} of its peak")
    fastnorm.plot.compare(case.grid, norm, reduced, reduced_name=arguments.solver, path=arguments.out)
    print(f"figure: {arguments.out}")


if __name__ == "__main__":
    main()
