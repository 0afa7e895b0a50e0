"""Steady rolling from Python: CONTACT's large-spin Hertz example (docs/tangential.md §5, §8)."""

import numpy as np
import pytest

import fastnorm


def hertz_problem():
    # CONTACT's "fastsim" example: h = A1 x^2 + B1 y^2 on 44 x 44 elements of 0.4 x 0.2 mm
    # centred on the origin, G = 82 GPa, nu = 0.28, Fn = 82 kN.
    mx, my, dx, dy = 44, 44, 0.4e-3, 0.2e-3
    grid = fastnorm.Grid(mx, my, dx, dy, -(mx - 1) * dx / 2, -(my - 1) * dy / 2)
    material = fastnorm.Material(2 * 82e9 * 1.28, 0.28)
    x = grid.x0_m + dx * np.arange(mx)
    y = grid.y0_m + dy * np.arange(my)
    h = 0.8464 * x[None, :] ** 2 + 2.406 * y[:, None] ** 2
    normal = fastnorm.Solver("norm", grid, material).solve(h, normal_force_n=82e3)
    assert normal.ok
    return grid, material, normal


def test_steady_rolling_gives_contacts_large_spin_case():
    grid, material, normal = hertz_problem()
    answer = fastnorm.solve_steady_rolling(grid, material, normal, friction=0.3, creepage_y=-6.25e-4,
                                           spin_per_m=0.625)
    assert answer.ok
    # CONTACT (peer-tangential/hertz.tsv, fastsim case 1, exact): Fs = -14940 N, Mz = -48210 N mm,
    # 356 elements in adhesion, 920 in slip.
    mu_fn = 0.3 * 82e3
    assert abs(answer.force_y_n + 14940) <= 0.015 * mu_fn
    assert abs(answer.force_x_n) <= 1e-6 * mu_fn
    assert abs(answer.spin_moment_nm + 48.21) <= 0.02 * mu_fn * np.sqrt(8e-3 * 4e-3)
    assert (answer.adhesion_elements, answer.slip_elements) == (356, 920)
    assert answer.traction_x_pa.shape == grid.shape
    assert np.count_nonzero(answer.state == 1) == 356
    # The tractions add up to the forces.
    assert np.sum(answer.traction_y_pa) * grid.dx_m * grid.dy_m == pytest.approx(answer.force_y_n, rel=1e-12)
    assert "TangentialSolution(status='converged'" in repr(answer)


def test_steady_rolling_stops_by_contacts_rule_when_asked():
    # CONTACT's stopping rule at its EPS of 1e-5 (docs/tangential.md §7): fewer sweeps, the same
    # areas, forces within 1e-6 mu Fn of the default rule's; a sweep limit met first is reported.
    grid, material, normal = hertz_problem()
    creepage = dict(friction=0.3, creepage_y=-6.25e-4, spin_per_m=0.625)
    tight = fastnorm.solve_steady_rolling(grid, material, normal, **creepage)
    loose = fastnorm.solve_steady_rolling(grid, material, normal, **creepage, stop="rms_change", tolerance=1e-5)
    assert loose.ok and loose.residual <= 1e-5
    assert loose.sweeps < tight.sweeps
    assert (loose.adhesion_elements, loose.slip_elements) == (tight.adhesion_elements, tight.slip_elements)
    assert abs(loose.force_y_n - tight.force_y_n) <= 1e-6 * 0.3 * 82e3
    limited = fastnorm.solve_steady_rolling(grid, material, normal, **creepage, max_sweeps=3)
    assert limited.status == "iteration limit" and limited.sweeps == 3
    with pytest.raises(fastnorm.FastnormError, match="stop"):
        fastnorm.solve_steady_rolling(grid, material, normal, **creepage, stop="rms")
    with pytest.raises(fastnorm.FastnormError, match="tolerance"):
        fastnorm.solve_steady_rolling(grid, material, normal, **creepage, tolerance=2.0)
    with pytest.raises(fastnorm.FastnormError, match="max_sweeps"):
        fastnorm.solve_steady_rolling(grid, material, normal, **creepage, max_sweeps=0)


def test_steady_rolling_names_bad_input():
    grid, material, normal = hertz_problem()
    with pytest.raises(fastnorm.FastnormError, match="friction"):
        fastnorm.solve_steady_rolling(grid, material, normal, friction=-0.3, creepage_x=1e-3)
    with pytest.raises(fastnorm.FastnormError, match="rolling"):
        fastnorm.solve_steady_rolling(grid, material, normal, friction=0.3, rolling="+y")
