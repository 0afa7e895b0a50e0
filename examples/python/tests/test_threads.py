"""Solves release the GIL: threads share a solver or a wheelset model, or run a model each."""

import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor

import numpy as np

import fastnorm


def gaps(grid, count):
    # Ellipsoidal gaps of growing approach on the grid (m).
    x = grid.x0_m + grid.dx_m * np.arange(grid.mx)
    y = grid.y0_m + grid.dy_m * np.arange(grid.my)
    shape = x[None, :] ** 2 / (2 * 0.3) + y[:, None] ** 2 / (2 * 0.08)
    return [shape - approach for approach in np.linspace(20e-6, 60e-6, count)]


def test_threads_sharing_one_solver_get_the_serial_answers():
    grid = fastnorm.Grid(40, 30, 0.4e-3, 0.3e-3, -7.8e-3, -4.35e-3)
    material = fastnorm.Material(2.1e11, 0.28)
    problems = gaps(grid, 8)
    for name in ["norm", "elliptic", "polynomial-edge"]:
        solver = fastnorm.Solver(name, grid, material)
        serial = [solver.solve(h) for h in problems]
        with ThreadPoolExecutor(max_workers=4) as pool:
            threaded = list(pool.map(solver.solve, problems))
        for one, other in zip(serial, threaded):
            assert one.ok and one.status == other.status  # a reduced basis may end 'cycled', usable
            assert np.array_equal(one.pressure_pa, other.pressure_pa)
            assert one.normal_force_n == other.normal_force_n


def test_threads_calling_one_sequence_are_serialised():
    # solve_next keeps state: concurrent calls on one solver run one at a time (no crash, no
    # torn state); each answer is then one of NORM's, which does not depend on the start.
    grid = fastnorm.Grid(30, 24, 0.5e-3, 0.4e-3, -7.25e-3, -4.6e-3)
    material = fastnorm.Material(2.1e11, 0.3)
    problems = gaps(grid, 12)
    cold = fastnorm.Solver("norm", grid, material)
    sequence = fastnorm.Solver("norm", grid, material)
    with ThreadPoolExecutor(max_workers=4) as pool:
        answers = list(pool.map(lambda h: sequence.solve_next(h), problems))
    for h, answer in zip(problems, answers):
        reference = cold.solve(h)
        assert answer.status == "converged"
        assert np.array_equal(answer.in_contact, reference.in_contact)
        assert np.allclose(answer.pressure_pa, reference.pressure_pa, rtol=0, atol=1e-9 * reference.pressure_pa.max())
    assert sequence.normal_stiffness_n_per_m() > 0


def test_wheelset_models_in_threads_give_the_serial_answers():
    poses = [dict(lateral_shift_m=y, vertical_m=0.12e-3) for y in (-4e-3, -1e-3, 2e-3, 5e-3)]

    def run(pose):
        model = fastnorm.WheelsetContact(solver="elliptic", elements=24)
        return model.evaluate(**pose)

    serial = [run(pose) for pose in poses]
    with ThreadPoolExecutor(max_workers=2) as pool:
        threaded = list(pool.map(run, poses))
    for one, other in zip(serial, threaded):
        assert np.array_equal(one.force_n, other.force_n)
        assert np.array_equal(one.moment_nm, other.moment_nm)


# Four threads on one wheelset model, mixing evaluate with the calls that lock the model
# without solving (history, budget, reset); run in a child process, since a deadlock between
# the model's lock and the GIL would stop every thread of this one, the test's too.
SHARED_MODEL_SCRIPT = """
import threading
import fastnorm

model = fastnorm.WheelsetContact(solver="elliptic", elements=24)
poses = [dict(lateral_shift_m=y, vertical_m=0.12e-3) for y in (-3e-3, -1e-3, 1e-3, 3e-3)]
failures = []

def work(index):
    try:
        for step in range(12):
            pose = poses[(index + step) % len(poses)]
            if step % 3 == 1:
                model.save_history()
                model.iteration_budget = 0
            result = model.evaluate(**pose)
            assert result.ok and len(result.wheels) == 2, result.status
            if step % 3 == 2:
                model.restore_history()
            if step == 7 and index == 0:
                model.reset()
    except Exception as error:
        failures.append(repr(error))

threads = [threading.Thread(target=work, args=(index,)) for index in range(4)]
for thread in threads:
    thread.start()
for thread in threads:
    thread.join()
assert not failures, failures
print("done")
"""


def test_threads_sharing_one_wheelset_model_run_one_at_a_time():
    # evaluate converts the model's own result while the model stays locked, taking the GIL
    # back for the arrays; every other call releases the GIL before it waits for the lock.
    run = subprocess.run([sys.executable, "-c", SHARED_MODEL_SCRIPT], capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, run.stderr
    assert run.stdout.strip() == "done"
