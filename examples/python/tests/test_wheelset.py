"""The wheelset contact model and the equilibrium through the module."""

import numpy as np
import pytest

import fastnorm


@pytest.fixture(scope="module")
def model():
    return fastnorm.WheelsetContact(solver="elliptic", elements=30)


def test_every_patch_carries_what_its_pressures_sum_to(model):
    result = model.evaluate(lateral_shift_m=3e-3, vertical_m=0.1e-3)
    assert result.ok
    assert [wheel.side for wheel in result.wheels] == ["left", "right"]
    patches = [patch for wheel in result.wheels for patch in wheel.patches]
    assert patches, "the lowered wheelset touches its rails"
    for wheel in result.wheels:
        assert wheel.normal_force_n == pytest.approx(sum(p.normal_force_n for p in wheel.patches), rel=1e-12)
        assert np.allclose(wheel.force_n, sum((p.force_n for p in wheel.patches), np.zeros(3)), rtol=1e-12)
    for patch in patches:
        grid = patch.grid
        assert patch.solution.pressure_pa.shape == grid.shape
        area = grid.dx_m * grid.dy_m
        assert patch.solution.pressure_pa.sum() * area == pytest.approx(patch.normal_force_n, rel=1e-9)
        assert np.linalg.norm(patch.force_n) == pytest.approx(patch.normal_force_n, rel=1e-12)
        assert patch.stiffness_n_per_m > 0
        assert patch.undeformed_distance_m.min() == pytest.approx(-patch.approach_m, rel=1e-12)
    assert np.allclose(result.force_n, result.wheels[0].force_n + result.wheels[1].force_n, rtol=1e-12)


def test_the_equilibrium_carries_its_load(model):
    found = model.equilibrium(load_n=200e3, lateral_shift_m=3e-3)
    assert found.status == "converged", found.message
    assert found.vertical_force_n == pytest.approx(200e3, rel=1e-6)
    assert found.pose.lateral_shift_m == 3e-3
    assert all(len(wheel.patches) >= 1 for wheel in found.wheels)
    # The model evaluated at the pose found carries the same load up to discretisation: its
    # element sizes are chosen at y = 0, the equilibrium's near its pose (measured 1.4e-4).
    again = model.evaluate(lateral_shift_m=found.pose.lateral_shift_m, vertical_m=found.pose.vertical_m,
                           roll_rad=found.pose.roll_rad, yaw_rad=found.pose.yaw_rad)
    carried = sum(wheel.force_n[2] for wheel in again.wheels)
    assert -carried == pytest.approx(200e3, rel=2e-3)


def test_a_wheelset_in_the_air_has_no_patches(model):
    result = model.evaluate(vertical_m=-2e-3)  # z is down: 2 mm above the rails
    assert all(not wheel.patches for wheel in result.wheels)
    assert np.array_equal(result.force_n, np.zeros(3))
