"""The wheelset contact model and the equilibrium through the module."""

import copy

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
    # The equilibrium is the model's own: evaluated at the pose found it carries the load
    # to the force tolerance (1e-6).
    again = model.evaluate(found.pose)
    assert -again.force_n[2] == pytest.approx(200e3, rel=1e-6)


def test_an_equilibrium_inside_a_force_jump_gives_its_best_pose():
    # The elliptic basis's force jumps by about 20 N across 4.7 nm here, across the load
    # (loads of 99.996 to 100.016 kN fall inside it): no pose carries 100.008 kN within 1e-6
    # of it. The search says so and gives its best pose.
    load = 1.00008e5
    model = fastnorm.WheelsetContact(solver="elliptic")
    found = model.equilibrium(load_n=load, lateral_shift_m=2e-3, yaw_rad=5e-3)
    assert not found.ok
    assert found.status == "not converged"
    assert "jump across the load" in found.message
    assert found.iterations < 12
    assert found.vertical_residual_n == pytest.approx(found.vertical_force_n - load, abs=1e-4)
    assert 1e-6 * load < abs(found.vertical_residual_n) < 2e-4 * load
    assert all(len(wheel.patches) == 1 for wheel in found.wheels)
    carried = sum(p.normal_force_n * np.cos(p.contact_angle_rad) for w in found.wheels for p in w.patches)
    assert carried == pytest.approx(found.vertical_force_n, rel=1e-12)


def test_a_wheelset_in_the_air_has_no_patches(model):
    result = model.evaluate(vertical_m=-2e-3)  # z is down: 2 mm above the rails
    assert all(not wheel.patches for wheel in result.wheels)
    assert np.array_equal(result.force_n, np.zeros(3))


def test_pressures_placed_in_the_track_frame_give_the_pressure_centre(model):
    result = model.evaluate(lateral_shift_m=4e-3, vertical_m=0.1e-3, yaw_rad=2e-3)
    for patch in (patch for wheel in result.wheels for patch in wheel.patches):
        grid = patch.grid
        pressure = patch.solution.pressure_pa  # [j, i]
        x = grid.x0_m + grid.dx_m * np.arange(grid.mx)
        s = grid.y0_m + grid.dy_m * np.arange(grid.my)
        # element [j, i] at reference + x_i e_x + s_j t_s
        points = (patch.reference_m[None, None, :] + x[None, :, None] * patch.e_x[None, None, :]
                  + s[:, None, None] * patch.t_s[None, None, :])
        centroid = (pressure[:, :, None] * points).sum(axis=(0, 1)) / pressure.sum()
        assert np.allclose(centroid, patch.pressure_centre_m, rtol=0, atol=1e-12)
        assert np.allclose(patch.force_n, -patch.normal_force_n * patch.normal, rtol=0,
                           atol=1e-9 * patch.normal_force_n)
        assert patch.contact_elements == int(patch.solution.in_contact.sum())


def test_a_failed_patch_solve_is_reported_with_its_wheel_and_patch():
    starved = fastnorm.WheelsetContact(solver="norm", elements=20, max_iterations=1)
    result = starved.evaluate(lateral_shift_m=3e-3, vertical_m=0.1e-3)
    assert not result.ok
    assert result.status.code == "patch failed"
    # the first patch, left wheel first, whose solve gave no usable answer
    usable = ("converged", "no contact", "cycled")
    failed = [(wheel.side, k, patch.solution.status) for wheel in result.wheels
              for k, patch in enumerate(wheel.patches) if patch.solution.status not in usable]
    assert failed
    side, index, status = failed[0]
    assert (result.status.wheel, result.status.patch, result.status.solver_status) == (side, index, status)
    assert f"{side} wheel, patch {index}" in result.status.message
    assert result.status.solver_status == "iteration limit"
    fine = fastnorm.WheelsetContact(solver="norm", elements=20).evaluate(lateral_shift_m=3e-3, vertical_m=0.1e-3)
    assert fine.ok and fine.status.code == "ok" and fine.status.wheel is None


def test_h_interpolated_along_rows_moves_forces_by_at_most_stiffness_times_its_bound():
    pose = dict(lateral_shift_m=3e-3, vertical_m=0.1e-3, yaw_rad=2e-3)
    exact = fastnorm.WheelsetContact(solver="norm", elements=20, distance_tolerance_m=0.0).evaluate(**pose)
    rows = fastnorm.WheelsetContact(solver="norm", elements=20).evaluate(**pose)
    for wheel_exact, wheel_rows in zip(exact.wheels, rows.wheels):
        for a, b in zip(wheel_exact.patches, wheel_rows.patches):
            assert np.abs(a.undeformed_distance_m - b.undeformed_distance_m).max() <= 1e-10
            assert abs(a.normal_force_n - b.normal_force_n) <= 1e-8 * a.normal_force_n + a.stiffness_n_per_m * 1e-10


def test_evaluate_takes_the_pose_an_equilibrium_returns(model):
    found = model.equilibrium(load_n=200e3, lateral_shift_m=2e-3)
    by_pose = model.evaluate(found.pose)
    by_keywords = model.evaluate(lateral_shift_m=found.pose.lateral_shift_m, vertical_m=found.pose.vertical_m,
                                 roll_rad=found.pose.roll_rad, yaw_rad=found.pose.yaw_rad)
    assert np.array_equal(by_pose.force_n, by_keywords.force_n)


def test_every_result_object_prints_its_key_figures(model):
    result = model.evaluate(lateral_shift_m=3e-3, vertical_m=0.1e-3)
    found = model.equilibrium(load_n=200e3)
    patch = result.wheels[1].patches[0]
    texts = [repr(result), repr(result.status), repr(result.wheels[1]), repr(patch), repr(found), repr(found.pose),
             repr(patch.solution), repr(model), repr(patch.grid), repr(fastnorm.Material(2.1e11, 0.3)),
             repr(fastnorm.Solver("norm", patch.grid, fastnorm.Material(2.1e11, 0.3))),
             repr(fastnorm.Velocity(forward_m_per_s=30.0))]
    for text in texts:
        assert " object at 0x" not in text
    assert repr(result).startswith("WheelsetResult(patches=")
    assert "status='ok'" in repr(result)
    assert repr(found).startswith("Equilibrium(status='converged'")
    assert "normal_force_n=" in repr(patch)
    assert repr(model).startswith("WheelsetContact(solver='elliptic'")


def test_a_moving_wheelset_gets_creep_forces_on_every_patch():
    """With a Velocity every patch gets its creepages and strip theory's creep forces
    (docs/wheel-rail.md §10), included in its force."""
    moving = fastnorm.WheelsetContact(solver="elliptic", elements=30, friction=0.3)
    pose = moving.equilibrium(load_n=200e3, yaw_rad=3e-3).pose
    velocity = fastnorm.Velocity(forward_m_per_s=30.0, pitch_rate_rad_per_s=-30.0 / 0.45)
    still = moving.evaluate(pose)
    result = moving.evaluate(pose, velocity=velocity)
    assert result.ok
    for wheel, alone in zip(result.wheels, still.wheels):
        assert wheel.patches
        for patch, normal in zip(wheel.patches, alone.patches):
            assert normal.traction is None
            assert patch.traction.ok
            assert 2e-3 < patch.creepage_y < 4e-3  # yaw 3 mrad
            traction = patch.traction
            area = patch.grid.dx_m * patch.grid.dy_m
            assert traction.traction_x_pa.sum() * area == pytest.approx(traction.force_x_n, rel=1e-9)
            assert traction.traction_y_pa.sum() * area == pytest.approx(traction.force_y_n, rel=1e-9)
            assert traction.force_y_n < 0  # against eta > 0, on the rail
            creep = -(traction.force_x_n * patch.e_x + traction.force_y_n * patch.t_s)
            assert np.allclose(patch.creep_force_n, creep, rtol=1e-12, atol=1e-9)
            assert np.allclose(patch.force_n, normal.force_n + creep, rtol=1e-9, atol=1e-6)
            assert np.hypot(traction.force_x_n, traction.force_y_n) <= 0.3 * patch.normal_force_n * (1 + 1e-12)
            assert traction.adhesion_elements > 0 and traction.slip_elements > 0


def test_fastsim_is_the_other_creep_method():
    pose = fastnorm.Pose(lateral_shift_m=0.0, vertical_m=0.1e-3, roll_rad=0.0, yaw_rad=3e-3)
    velocity = fastnorm.Velocity(forward_m_per_s=30.0, pitch_rate_rad_per_s=-30.0 / 0.45)
    strips = fastnorm.WheelsetContact(solver="elliptic", elements=30, friction=0.3).evaluate(pose, velocity=velocity)
    fastsim = fastnorm.WheelsetContact(solver="elliptic", elements=30, friction=0.3,
                                       creep_method="fastsim").evaluate(pose, velocity=velocity)
    for a, b in zip(strips.wheels, fastsim.wheels):
        for p, q in zip(a.patches, b.patches):
            assert p.normal_force_n == pytest.approx(q.normal_force_n, rel=1e-12)
            assert p.traction.force_y_n != q.traction.force_y_n
            assert abs(p.traction.force_y_n - q.traction.force_y_n) <= 0.1 * 0.3 * p.normal_force_n
    with pytest.raises(ValueError, match="creep_method"):
        fastnorm.WheelsetContact(solver="elliptic", elements=20, friction=0.3, creep_method="fast")


def test_creep_forces_need_friction_and_a_forward_speed():
    pose = fastnorm.Pose(lateral_shift_m=0.0, vertical_m=0.1e-3, roll_rad=0.0, yaw_rad=0.0)
    velocity = fastnorm.Velocity(forward_m_per_s=30.0, pitch_rate_rad_per_s=-30.0 / 0.45)
    with pytest.raises(ValueError, match="creep.friction"):
        fastnorm.WheelsetContact(solver="elliptic", elements=20).evaluate(pose, velocity=velocity)
    with pytest.raises(ValueError, match="velocity.forward"):
        fastnorm.WheelsetContact(solver="elliptic", elements=20, friction=0.3).evaluate(
            pose, velocity=fastnorm.Velocity(forward_m_per_s=0.0))


def test_an_iteration_budget_bounds_a_step_and_the_step_reports_its_work():
    pose = fastnorm.Pose(lateral_shift_m=2e-3, vertical_m=fastnorm.WheelsetContact(solver="elliptic", elements=20)
                         .equilibrium(load_n=2e5, lateral_shift_m=2e-3).pose.vertical_m)
    free = fastnorm.WheelsetContact(solver="elliptic", elements=20).evaluate(pose)
    ample = fastnorm.WheelsetContact(solver="elliptic", elements=20)
    ample.iteration_budget = 100000
    assert ample.iteration_budget == 100000
    result = ample.evaluate(pose)
    assert result.ok
    spent = [sum(patch.solution.iterations for patch in wheel.patches) for wheel in result.wheels]
    assert [wheel.iterations for wheel in result.wheels] == spent
    assert result.iterations == sum(spent) == free.iterations
    for wheel, reference in zip(result.wheels, free.wheels):
        for patch, expected in zip(wheel.patches, reference.patches):
            assert np.array_equal(patch.solution.pressure_pa, expected.solution.pressure_pa)
    tight = fastnorm.WheelsetContact(solver="elliptic", elements=20)
    tight.iteration_budget = 1
    cut = tight.evaluate(pose)
    # Each solve stops after its one iteration: at its iterate with every pressure positive
    # ('budget reached', usable), or, after a drop before any, at 'iteration limit' (failed).
    statuses = [patch.solution.status for wheel in cut.wheels for patch in wheel.patches]
    assert set(statuses) <= {"budget reached", "iteration limit"}
    assert cut.ok == ("iteration limit" not in statuses)
    if not cut.ok:
        assert cut.status.solver_status == "iteration limit"
    assert cut.iterations == sum(len(wheel.patches) for wheel in cut.wheels)
    with pytest.raises(ValueError, match="iterations must be >= 0"):
        tight.iteration_budget = -1


def test_a_per_solve_cap_bounds_warm_solves_only():
    pose = fastnorm.Pose(lateral_shift_m=2e-3, vertical_m=fastnorm.WheelsetContact(solver="elliptic", elements=20)
                         .equilibrium(load_n=2e5, lateral_shift_m=2e-3).pose.vertical_m)
    free = fastnorm.WheelsetContact(solver="elliptic", elements=20).evaluate(pose)
    capped = fastnorm.WheelsetContact(solver="elliptic", elements=20, warm_solve_iterations=1)
    first = capped.evaluate(pose)  # cold: not capped, the free model's answer
    assert first.ok and first.iterations == free.iterations
    # Warm steps of 20 um: each stopped at the cap's first settled iterate, or converged.
    statuses = set()
    for step in range(1, 31):
        moved = fastnorm.Pose(lateral_shift_m=pose.lateral_shift_m + 20e-6 * step, vertical_m=pose.vertical_m)
        result = capped.evaluate(moved)
        assert result.ok
        statuses |= {patch.solution.status for wheel in result.wheels for patch in wheel.patches}
    assert statuses <= {"budget reached", "converged"} and "budget reached" in statuses
    with pytest.raises(ValueError, match="warm_solve_iterations must be >= 0"):
        fastnorm.WheelsetContact(solver="elliptic", elements=20, warm_solve_iterations=-1)


def test_trial_steps_restored_give_the_untried_models_answers():
    # docs/wheel-rail.md §9: save at the accepted step, a trial far off, restore, the next step.
    tried = fastnorm.WheelsetContact(solver="elliptic", elements=20)
    plain = fastnorm.WheelsetContact(solver="elliptic", elements=20)
    with pytest.raises(ValueError, match="no history saved"):
        tried.restore_history()
    start = [model.equilibrium(load_n=2e5, lateral_shift_m=1e-3).pose for model in (tried, plain)][0]
    for step in range(1, 4):
        pose = fastnorm.Pose(lateral_shift_m=start.lateral_shift_m + 0.3e-3 * step, vertical_m=start.vertical_m,
                             roll_rad=start.roll_rad)
        tried.save_history()
        tried.evaluate(fastnorm.Pose(lateral_shift_m=pose.lateral_shift_m + 1.5e-3, vertical_m=start.vertical_m + 3e-5,
                                     roll_rad=start.roll_rad))
        tried.restore_history()
        result, expected = tried.evaluate(pose), plain.evaluate(pose)
        assert result.ok and all(wheel.patches for wheel in result.wheels)
        assert np.array_equal(result.force_n, expected.force_n)
        for wheel, reference in zip(result.wheels, expected.wheels):
            for patch, other in zip(wheel.patches, reference.patches):
                assert np.array_equal(patch.solution.pressure_pa, other.solution.pressure_pa)


def test_copies_step_on_their_own_as_models_that_took_the_same_calls():
    # docs/wheel-rail.md §9, "Models of a vehicle": a copy shares its original's tables, not its state.
    original = fastnorm.WheelsetContact(solver="elliptic", elements=20)
    alone = fastnorm.WheelsetContact(solver="elliptic", elements=20)
    start = [model.equilibrium(load_n=2e5, lateral_shift_m=1e-3).pose for model in (original, alone)][0]
    original.iteration_budget = 1000
    alone.iteration_budget = 1000
    original.save_history()
    copies = [original.copy(), copy.copy(original), copy.deepcopy(original)]
    assert all(repr(made) == repr(original) and made.iteration_budget == 1000 for made in copies)
    # The original moves far off first: its copies answer from the history they were made with.
    original.evaluate(fastnorm.Pose(lateral_shift_m=start.lateral_shift_m + 2e-3, vertical_m=start.vertical_m,
                                    roll_rad=start.roll_rad))
    poses = [fastnorm.Pose(lateral_shift_m=start.lateral_shift_m + 0.3e-3 * step, vertical_m=start.vertical_m,
                           roll_rad=start.roll_rad, yaw_rad=1e-3 * step) for step in range(1, 4)]
    expected = [alone.evaluate(pose) for pose in poses]
    for made in copies:
        for pose, reference_result in zip(poses, expected):
            result = made.evaluate(pose)
            assert result.ok and np.array_equal(result.force_n, reference_result.force_n)
            for wheel, reference in zip(result.wheels, reference_result.wheels):
                assert len(wheel.patches) == len(reference.patches)
                for patch, other in zip(wheel.patches, reference.patches):
                    assert np.array_equal(patch.solution.pressure_pa, other.solution.pressure_pa)
    # The saved history came with them: back to the equilibrium, the first step again.
    for made in copies:
        made.restore_history()
        assert np.array_equal(made.evaluate(poses[0]).force_n, expected[0].force_n)
