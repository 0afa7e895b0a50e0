"""Bad input raises ValueError (fastnorm.FastnormError) whose message names the argument."""

import math

import numpy as np
import pytest

import fastnorm

GRID = fastnorm.Grid(8, 6, 1e-4, 2e-4)
STEEL = fastnorm.Material(2.1e11, 0.3)


def sphere_gap(grid, approach_m=1e-5, radius_m=0.005):
    x = grid.x0_m + grid.dx_m * (np.arange(grid.mx) - (grid.mx - 1) / 2)
    y = grid.y0_m + grid.dy_m * (np.arange(grid.my) - (grid.my - 1) / 2)
    return (x[None, :] ** 2 + y[:, None] ** 2) / (2 * radius_m) - approach_m


@pytest.mark.parametrize(
    "make, named",
    [
        (lambda: fastnorm.Grid(0, 3, 1e-3, 1e-3), "mx"),
        (lambda: fastnorm.Grid(3, 3, -1e-3, 1e-3), "dx"),
        (lambda: fastnorm.Grid(3, 3, 1e-3, math.nan), "dy"),
        (lambda: fastnorm.Material(2.1e11, 0.7), "poisson_ratio"),
        (lambda: fastnorm.Material(-1.0, 0.3), "young_modulus"),
        (lambda: fastnorm.Solver("nrm", GRID, STEEL), "unknown solver 'nrm'"),
        (lambda: fastnorm.Solver("cg", GRID, STEEL, tolerance=-1.0), "tolerance"),
        (lambda: fastnorm.Solver("elliptic", GRID, STEEL, tolerance=1e-6), "'elliptic' is an active-set solver"),
        (lambda: fastnorm.Solver("cg", GRID, STEEL, gap_tolerance=1e-6), "gap_tolerance"),
        (lambda: fastnorm.Solver("norm", GRID, STEEL, gap_tolerance=-1.0), "gap_tolerance"),
        (lambda: fastnorm.WheelsetContact(solver="polynomial", tolerance=1e-6), "active-set solver"),
        (lambda: fastnorm.Solver("norm", GRID, STEEL, max_iterations=-2), "max_iterations"),
        (lambda: fastnorm.Solver("norm", GRID, STEEL).solve(np.zeros((8, 6))), "undeformed_distance_m"),
        (lambda: fastnorm.Solver("norm", GRID, STEEL).solve(np.zeros(48)), "undeformed_distance_m"),
        (lambda: fastnorm.Solver("norm", GRID, STEEL).solve(np.full((6, 8), np.nan)), "undeformed_distance"),
        (lambda: fastnorm.Solver("norm", GRID, STEEL).solve(sphere_gap(GRID), normal_force_n=-5.0), "normal_force"),
        (lambda: fastnorm.Solver("norm", GRID, STEEL).solve(sphere_gap(GRID), normal_force_n=math.inf),
         "normal_force"),
        (lambda: fastnorm.Solver("norm", GRID, STEEL).normal_stiffness_n_per_m(), "solve_next"),
        (lambda: fastnorm.read_case("/nonexistent/fastnorm.case"), "/nonexistent/fastnorm.case"),
        (lambda: fastnorm.Case("c", GRID, fastnorm.Material(2e11, 0.3, 2.1e11, 0.3), sphere_gap(GRID)), "material"),
        (lambda: fastnorm.write_case("/nonexistent/x.case", fastnorm.Case("c", GRID, STEEL, sphere_gap(GRID))),
         "path"),
        (lambda: fastnorm.WheelsetContact(elements=2), "elements"),
        (lambda: fastnorm.WheelsetContact(distance_tolerance_m=-1e-10), "tolerance"),
        (lambda: fastnorm.WheelsetContact(distance_node_spacing_m=0.0), "node_spacing"),
        (lambda: fastnorm.WheelsetContact(nominal_radius_m=-0.45), "nominal_radius must be positive"),
        (lambda: fastnorm.WheelsetContact(gauge_m=math.nan), "gauge must be positive"),
        (lambda: fastnorm.WheelsetContact(wheel_profile="/nonexistent.prw"), "/nonexistent.prw"),
        (lambda: fastnorm.WheelsetContact(solver="elliptic").evaluate(lateral_shift_m=0.5), "y must lie"),
        (lambda: fastnorm.WheelsetContact(solver="elliptic").evaluate(yaw_rad=math.nan), "yaw"),
        (lambda: fastnorm.WheelsetContact(solver="elliptic").equilibrium(load_n=-1.0), "load"),
    ],
)
def test_bad_input_raises_value_error_naming_it(make, named):
    with pytest.raises(ValueError) as raised:
        make()
    assert isinstance(raised.value, fastnorm.FastnormError)
    assert named in str(raised.value)


def test_wrong_types_raise_type_error():
    with pytest.raises(TypeError):
        fastnorm.Grid("8", 6, 1e-4, 2e-4)
    with pytest.raises(TypeError):
        fastnorm.Solver("norm", GRID, STEEL).solve(sphere_gap(GRID), 100.0)  # normal_force_n is keyword-only


def test_a_good_problem_is_solved():
    # The counterpart of the cases above: the same grid and gap are accepted and solved.
    solution = fastnorm.Solver("norm", GRID, STEEL).solve(sphere_gap(GRID))
    assert solution.status == "converged"
    assert solution.normal_force_n > 0
    assert solution.pressure_pa.shape == GRID.shape == (6, 8)
