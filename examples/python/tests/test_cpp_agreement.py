"""The module's answers are the C++ library's, bit for bit, on CONTACT's peer cases.

The C++ side is fastnorm-solve (the command-line tool), which writes its solution to a
.case file at full precision; the module reads that file and solves the same case itself.
"""

import subprocess

import numpy as np
import pytest

import fastnorm

CASES = ["hertz_sphere_30x30", "wr_y0.0_psi1.0_left", "wr_y3.0_psi0.0_right", "wr_y6.0_psi0.0_right"]
SOLVERS = ["norm", "cg", "elliptic", "polynomial:4", "polynomial-edge"]


def solved_by_cpp(fastnorm_solve, case_path, solver, output):
    subprocess.run([fastnorm_solve, "--solver", solver, "--quiet", "--write-case", str(output), str(case_path)],
                   check=True, capture_output=True, text=True)
    return fastnorm.read_case(str(output))


@pytest.mark.parametrize("solver", SOLVERS)
@pytest.mark.parametrize("name", CASES)
def test_solutions_equal_the_cpp_tool_bit_for_bit(peer_cases, fastnorm_solve, output_dir, name, solver):
    case_path = peer_cases / f"{name}.case"
    cpp = solved_by_cpp(fastnorm_solve, case_path, solver, output_dir / f"{name}.{solver.replace(':', '_')}.case")
    case = fastnorm.read_case(str(case_path))
    python = fastnorm.solve_case(case, solver=solver)

    assert python.ok
    assert python.pressure_pa.shape == (case.grid.my, case.grid.mx)
    assert np.array_equal(python.pressure_pa, cpp.result_pressure_pa)
    assert python.normal_force_n == cpp.result.normal_force_n
    assert python.approach_m == cpp.result.approach_m
    assert python.contact_count == cpp.result.contact_count
    assert python.iterations == cpp.result.iterations
    # The case itself came through unchanged.
    assert np.array_equal(cpp.undeformed_distance_m, case.undeformed_distance_m)


def test_norm_meets_contact_on_its_own_cases(peer_cases):
    # What the bit-for-bit comparison rests on: NORM against CONTACT's stored answers, to the
    # bounds of tests/norm/peer_cases.test.cpp (CONTACT solved to 1e-9 on the same grid).
    for case_path in sorted(peer_cases.glob("wr_*.case")):
        case = fastnorm.read_case(str(case_path))
        solution = fastnorm.solve_case(case)
        assert solution.status == "converged"
        assert solution.normal_force_n == pytest.approx(case.result.normal_force_n, rel=1e-7)
        peak = case.result_pressure_pa.max()
        assert np.abs(solution.pressure_pa - case.result_pressure_pa).max() < 1e-6 * peak
        assert np.array_equal(solution.in_contact, case.result_pressure_pa > 0)


def test_a_written_case_reads_back_unchanged(peer_cases, output_dir):
    case = fastnorm.read_case(str(peer_cases / "hertz_sphere_30x30.case"))
    solution = fastnorm.solve_case(case, solver="elliptic")
    path = output_dir / "written_by_python.case"
    fastnorm.write_case(str(path), case, solution)
    again = fastnorm.read_case(str(path))
    assert np.array_equal(again.undeformed_distance_m, case.undeformed_distance_m)
    assert np.array_equal(again.result_pressure_pa, solution.pressure_pa)
    assert again.normal_force_n == case.normal_force_n
    assert again.result.normal_force_n == solution.normal_force_n
    assert again.material.poisson_ratio_1 == case.material.poisson_ratio_1


def test_cases_print_their_key_figures(peer_cases):
    case = fastnorm.read_case(str(peer_cases / "hertz_sphere_30x30.case"))
    assert repr(case).startswith("Case('") and "grid=30x30" in repr(case)
    assert repr(case.result).startswith("CaseResult(normal_force_n=")
