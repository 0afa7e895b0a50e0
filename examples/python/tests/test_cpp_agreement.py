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


def printed_fields(output):
    """The key=value fields of a tool's line, as numbers where they are."""
    fields = {}
    for word in output.split():
        key, _, value = word.partition("=")
        try:
            fields[key] = float(value)
        except ValueError:
            fields[key] = value
    return fields


def test_a_cases_tangential_line_is_rolled_as_the_cpp_tool_rolls_it(peer_cases, fastnorm_solve, output_dir):
    # A case with a tangential line written by the module (all creepages, a spin centre off
    # the origin, rolling towards -x) reads back unchanged in both, and the module's exact
    # path gives fastnorm-solve's forces to the digits it prints (six).
    peer = fastnorm.read_case(str(peer_cases / "hertz_sphere_30x30.case"))
    rolling = fastnorm.CaseRolling(0.3, creepage_x=1e-3, creepage_y=-5e-4, spin_per_m=0.4, spin_centre_x_m=1e-4,
                                   spin_centre_y_m=-2e-4, rolling="-x")
    case = fastnorm.Case(peer.name, peer.grid, peer.material, peer.undeformed_distance_m,
                         normal_force_n=peer.normal_force_n, stated_approach_m=peer.stated_approach_m, rolling=rolling)
    path = output_dir / "rolling_by_python.case"
    fastnorm.write_case(str(path), case)
    back = fastnorm.read_case(str(path))
    for name in ["friction", "creepage_x", "creepage_y", "spin_per_m", "spin_centre_x_m", "spin_centre_y_m",
                 "rolling"]:
        assert getattr(back.rolling, name) == getattr(rolling, name), name

    run = subprocess.run([fastnorm_solve, "--quiet", str(path)], check=True, capture_output=True, text=True)
    cpp = printed_fields(run.stdout)
    python = fastnorm.roll_case(back, fastnorm.solve_case(back))
    assert python.ok and cpp["tangential"] == "converged"
    assert python.adhesion_elements > 0 and python.slip_elements > 0  # partial slip
    assert python.force_x_n == pytest.approx(cpp["fx"], rel=1e-5)
    assert python.force_y_n == pytest.approx(cpp["fs"], rel=1e-5)
    assert python.spin_moment_nm == pytest.approx(cpp["mn"], rel=1e-5)
    assert (python.adhesion_elements, python.slip_elements, python.sweeps) == (cpp["nadh"], cpp["nslip"], cpp["sweeps"])
    with pytest.raises(ValueError, match="tangential line"):
        fastnorm.roll_case(peer, fastnorm.solve_case(peer))


def test_a_case_rolling_names_bad_input():
    with pytest.raises(fastnorm.FastnormError, match="friction"):
        fastnorm.CaseRolling(0.0)
    with pytest.raises(fastnorm.FastnormError, match="spin_per_m"):
        fastnorm.CaseRolling(0.3, spin_per_m=float("nan"))
    with pytest.raises(fastnorm.FastnormError, match="rolling"):
        fastnorm.CaseRolling(0.3, rolling="x")
