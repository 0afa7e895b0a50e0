"""The module and the C API give the same numbers, bit for bit: the wheelset model moving.

tests/cli/c_api_agreement.test.cpp holds the C API to the C++ library bit for bit; this
holds the module to the C API (loaded with ctypes from FASTNORM_C_LIBRARY, which CTest
sets), so all three agree: frames, signs, units and the order of patches and elements.
"""

import ctypes
import os

import numpy as np
import pytest

import fastnorm

Vec3 = ctypes.c_double * 3


class Grid(ctypes.Structure):
    _fields_ = [("mx", ctypes.c_int), ("my", ctypes.c_int)] + [(n, ctypes.c_double) for n in ("dx", "dy", "x0", "y0")]


class Material(ctypes.Structure):
    _fields_ = [(n, ctypes.c_double) for n in ("young_modulus_1", "poisson_ratio_1", "young_modulus_2",
                                               "poisson_ratio_2")]


class Options(ctypes.Structure):
    _fields_ = [("solver", ctypes.c_char_p), ("wheel_profile", ctypes.c_char_p), ("rail_profile", ctypes.c_char_p),
                ("nominal_radius", ctypes.c_double), ("gauge", ctypes.c_double), ("cant", ctypes.c_double),
                ("material", Material), ("elements", ctypes.c_int), ("stiffness", ctypes.c_int),
                ("max_iterations", ctypes.c_int), ("distance_tolerance", ctypes.c_double),
                ("friction", ctypes.c_double), ("creep_method", ctypes.c_int),
                ("distance_everywhere", ctypes.c_int), ("warm_solve_iterations", ctypes.c_int),
                ("tolerance", ctypes.c_double), ("gap_tolerance", ctypes.c_double),
                ("distance_node_spacing", ctypes.c_double)]


class Pose(ctypes.Structure):
    _fields_ = [(n, ctypes.c_double) for n in ("y", "z", "roll", "yaw")]


class Velocity(ctypes.Structure):
    _fields_ = [(n, ctypes.c_double) for n in ("forward", "lateral", "vertical", "roll_rate", "yaw_rate",
                                               "pitch_rate")]


class Creepage(ctypes.Structure):
    _fields_ = [(n, ctypes.c_double) for n in ("longitudinal", "lateral", "spin", "spin_centre_x", "spin_centre_y")]


class Tangential(ctypes.Structure):
    _fields_ = [(n, ctypes.c_int) for n in ("status", "sweeps", "adhesion_elements", "slip_elements")] + \
               [(n, ctypes.c_double) for n in ("force_x", "force_y", "spin_moment", "frictional_power_per_speed",
                                               "residual")]


class Patch(ctypes.Structure):
    _fields_ = [(n, ctypes.c_int) for n in ("status", "at_edge", "flange_climb", "history", "contact_elements")] + \
               [("grid", Grid)] + [(n, Vec3) for n in ("reference", "e_x", "t_s", "normal", "centre",
                                                       "pressure_centre")] + \
               [("profile_y", ctypes.c_double), ("normal_force", ctypes.c_double), ("force", Vec3), ("moment", Vec3)] + \
               [(n, ctypes.c_double) for n in ("contact_angle", "approach", "max_pressure", "stiffness")] + \
               [("creepage", Creepage), ("creep", Tangential), ("creep_force", Vec3)]


@pytest.fixture(scope="module")
def c_api():
    path = os.environ.get("FASTNORM_C_LIBRARY")
    if not path or not os.path.exists(path):
        pytest.skip("FASTNORM_C_LIBRARY does not name the C API's library (run the tests through CTest)")
    library = ctypes.CDLL(path)
    library.fastnorm_last_error.restype = ctypes.c_char_p
    return library


def require_ok(library, status):
    assert status == 0, library.fastnorm_last_error().decode()


@pytest.mark.parametrize("method, c_method", [("strip_theory", 0), ("fastsim", 1)])
def test_the_moving_wheelset_gives_the_c_apis_numbers(c_api, method, c_method):
    python = fastnorm.WheelsetContact(solver="elliptic", elements=30, friction=0.3, creep_method=method)
    options = Options()
    c_api.fastnorm_wheelset_options_default(ctypes.byref(options))
    options.solver = b"elliptic"
    options.elements = 30
    options.friction = 0.3
    options.creep_method = c_method
    model = ctypes.c_void_p()
    require_ok(c_api, c_api.fastnorm_wheelset_create(ctypes.byref(options), ctypes.byref(model)))
    try:
        # A short lateral run, yawed, loaded as the equilibrium finds it and lowered a little
        # more at each step; moving at 30 m/s with lateral and yaw rates.
        velocity = dict(forward_m_per_s=30.0, lateral_m_per_s=0.05, yaw_rate_rad_per_s=0.01,
                        pitch_rate_rad_per_s=-30.0 / 0.45)
        start = fastnorm.WheelsetContact(solver="elliptic", elements=20).equilibrium(load_n=2e5, yaw_rad=1e-3).pose
        for step, y in enumerate([0.0, 1e-3, 2e-3, 4e-3]):
            pose = fastnorm.Pose(lateral_shift_m=y, vertical_m=start.vertical_m + 1e-6 * step, roll_rad=start.roll_rad,
                                 yaw_rad=1e-3)
            result = python.evaluate(pose, velocity=fastnorm.Velocity(**velocity))
            assert result.ok
            force, moment = Vec3(), Vec3()
            c_pose = Pose(pose.lateral_shift_m, pose.vertical_m, pose.roll_rad, pose.yaw_rad)
            c_velocity = Velocity(30.0, 0.05, 0.0, 0.0, 0.01, -30.0 / 0.45)
            require_ok(c_api, c_api.fastnorm_wheelset_evaluate_moving(model, ctypes.byref(c_pose),
                                                                      ctypes.byref(c_velocity), force, moment))
            assert list(force) == list(result.force_n)
            assert list(moment) == list(result.moment_nm)
            for w, wheel in enumerate(result.wheels):
                count = ctypes.c_int()
                require_ok(c_api, c_api.fastnorm_wheelset_patch_count(model, w, ctypes.byref(count)))
                assert count.value == len(wheel.patches) >= 1
                for k, patch in enumerate(wheel.patches):
                    c = Patch()
                    require_ok(c_api, c_api.fastnorm_wheelset_patch(model, w, k, ctypes.byref(c)))
                    assert c.normal_force == patch.normal_force_n
                    assert list(c.force) == list(patch.force_n)
                    assert list(c.moment) == list(patch.moment_nm)
                    assert list(c.creep_force) == list(patch.creep_force_n)
                    assert (c.creepage.longitudinal, c.creepage.lateral, c.creepage.spin) == \
                        (patch.creepage_x, patch.creepage_y, patch.spin_per_m)
                    traction = patch.traction
                    assert (c.creep.force_x, c.creep.force_y, c.creep.spin_moment) == \
                        (traction.force_x_n, traction.force_y_n, traction.spin_moment_nm)
                    assert (c.creep.adhesion_elements, c.creep.slip_elements) == \
                        (traction.adhesion_elements, traction.slip_elements)
                    assert c.creep.adhesion_elements > 0 and c.creep.slip_elements > 0  # partial slip
                    shape = (c.grid.my, c.grid.mx)
                    tx, ts = np.empty(shape), np.empty(shape)
                    require_ok(c_api, c_api.fastnorm_wheelset_patch_traction(
                        model, w, k, tx.ctypes.data_as(ctypes.POINTER(ctypes.c_double)),
                        ts.ctypes.data_as(ctypes.POINTER(ctypes.c_double))))
                    assert np.array_equal(tx, traction.traction_x_pa)
                    assert np.array_equal(ts, traction.traction_y_pa)
    finally:
        c_api.fastnorm_wheelset_destroy(model)


class SolverOptions(ctypes.Structure):
    _fields_ = [("max_iterations", ctypes.c_int), ("tolerance", ctypes.c_double), ("gap_tolerance", ctypes.c_double)]


class Result(ctypes.Structure):
    _fields_ = [(n, ctypes.c_int) for n in ("status", "iterations", "contact_count", "at_edge")] + \
               [(n, ctypes.c_double) for n in ("normal_force", "approach", "residual")]


@pytest.mark.parametrize("name, settings", [("elliptic", dict(gap_tolerance=1e-2)), ("cg", dict(tolerance=1e-4))])
def test_a_solvers_tolerances_give_the_c_apis_numbers(c_api, name, settings):
    # A sphere of radius 10 mm pressed with 2 kN (Hertz radius 0.5 mm) on 24 x 24 elements.
    grid = fastnorm.Grid(24, 24, 1e-4, 1e-4, -11.5e-4, -11.5e-4)
    x = grid.x0_m + grid.dx_m * np.arange(grid.mx)
    y = grid.y0_m + grid.dy_m * np.arange(grid.my)
    h = np.ascontiguousarray((x[None, :] ** 2 + y[:, None] ** 2) / (2 * 0.01))
    steel = fastnorm.Material(2.1e11, 0.3)
    python = fastnorm.Solver(name, grid, steel, **settings).solve(h, normal_force_n=2e3)
    assert python.iterations != fastnorm.Solver(name, grid, steel).solve(h, normal_force_n=2e3).iterations
    c_grid = Grid(grid.mx, grid.my, grid.dx_m, grid.dy_m, grid.x0_m, grid.y0_m)
    c_steel = Material(2.1e11, 0.3, 2.1e11, 0.3)
    options = SolverOptions(0, settings.get("tolerance", 0.0), settings.get("gap_tolerance", 0.0))
    solver = ctypes.c_void_p()
    require_ok(c_api, c_api.fastnorm_solver_create(name.encode(), ctypes.byref(c_grid), ctypes.byref(c_steel),
                                                   ctypes.byref(options), ctypes.byref(solver)))
    pressure, result = np.empty(grid.shape), Result()
    try:
        double_p = ctypes.POINTER(ctypes.c_double)
        require_ok(c_api, c_api.fastnorm_solve_force(solver, h.ctypes.data_as(double_p), ctypes.c_double(2e3),
                                                     pressure.ctypes.data_as(double_p), ctypes.byref(result)))
    finally:
        c_api.fastnorm_solver_destroy(solver)
    assert result.iterations == python.iterations
    assert np.array_equal(pressure, python.pressure_pa)
