"""Contact tables (fastnorm.tables, docs/tables.md): a sweep that survives a dead worker and a
dead client, equal bit for bit to a serial run whatever the executor; the store's spec rules;
the exports (netCDF with units, the ContactTable file, text) against the store's numbers."""

import os
import pathlib
import shutil
import subprocess
import sys
import time

import numpy as np
import pytest

import fastnorm
from fastnorm import tables

# 400 equilibria (y -6…6 mm, 4 yaws, one load) in chunks of 10, as issue 30 sets the check.
SPEC = {
    "kind": "equilibrium",
    "lateral_shift_m": [float(y) for y in np.linspace(-6e-3, 6e-3, 100)],
    "yaw_rad": [0.0, 2e-3, 4e-3, 6e-3],
    "load_n": [2e5],
    "solver": "cg",
    "elements": 20,
    "chunk_size": 10,
}


def shard_bytes(store):
    folder = pathlib.Path(store) / tables.SHARDS
    return {path.name: path.read_bytes() for path in sorted(folder.iterdir())}


def no_partial_files(store):
    return not any(path.name.startswith(".") for path in pathlib.Path(store).rglob("*"))


@pytest.fixture(scope="module")
def serial_store(tmp_path_factory):
    store = tmp_path_factory.mktemp("tables") / "serial"
    written = tables.build(SPEC, str(store), executor="serial", progress=False)
    assert written == 40
    return store


def test_the_serial_table_is_complete_and_converged(serial_store):
    canonical, arrays = tables.load_arrays(str(serial_store))
    assert arrays["done"].all()
    assert np.all(arrays["status"] == tables.STATUS_CODES["converged"])
    # Every equilibrium carries its load (the equilibrium's force tolerance: 1e-6 relative).
    vertical_force = arrays["case_values"][..., 2]
    assert np.all(np.abs(vertical_force / 2e5 - 1) < 1e-6)
    assert np.all(arrays["patch_count"] >= 1)
    # The rolling radii: the nominal 0.45 m at the taping line (y = 0 holds the contact near
    # it), and a difference right − left that grows with the shift (the profiles' conicity).
    radius = tables.open(str(serial_store))["rolling_radius"].isel(pair=0, load=0, yaw=0, patch=0)
    centre = int(np.argmin(np.abs(np.array(SPEC["lateral_shift_m"]))))
    assert abs(radius.sel(wheel="left").values[centre] - 0.45) < 1e-3
    difference = (radius.sel(wheel="right") - radius.sel(wheel="left")).values
    assert np.all(np.diff(difference) > 0)


def test_the_larger_lobe_maximum_is_the_largest_pressure_of_every_patch(serial_store):
    # docs/tables.md §3: the two lobes' maxima split the patch; the larger is max_pressure.
    _, arrays = tables.load_arrays(str(serial_store))
    names = [name for name, *_ in tables.PATCH_OUTPUTS]
    values = arrays["patch_values"]
    solved = ~np.isnan(values[..., names.index("max_pressure")])
    lobes = np.maximum(values[..., names.index("max_pressure_lower_lobe")],
                       values[..., names.index("max_pressure_upper_lobe")])
    assert solved.sum() > 400
    np.testing.assert_array_equal(lobes[solved], values[..., names.index("max_pressure")][solved])
    assert np.isnan(lobes[~solved]).all()


def two_bumps(rows, columns, lower_peak, upper_peak, lower_row, upper_row):
    """A pressure field (rows across s, columns along x) of two elliptic bumps, each its
    peak at the given row and the middle column."""
    s = np.arange(rows)[:, None]
    x = (np.arange(columns)[None, :] - columns // 2) / (columns / 2)
    field = np.zeros((rows, columns))
    for peak, row in ((lower_peak, lower_row), (upper_peak, upper_row)):
        field = np.maximum(field, peak * np.sqrt(np.clip(1 - x**2 - ((s - row) / 4.0)**2, 0, None)))
    return field


def test_lobe_maxima_follow_position_not_size():
    # The lobe at lower s is the first output whichever is higher; a dip between them splits.
    assert tables.lobe_maxima(two_bumps(24, 15, 700.0, 900.0, 6, 15)) == (700.0, 900.0)
    assert tables.lobe_maxima(two_bumps(24, 15, 900.0, 700.0, 6, 15)) == (900.0, 700.0)
    # Three lobes: the two highest split at the lowest row maximum between them; the third,
    # lowest, lies on the side it lies on.
    three = np.maximum(two_bumps(40, 15, 800.0, 600.0, 6, 18), two_bumps(40, 15, 0.0, 500.0, 0, 30))
    assert tables.lobe_maxima(three) == (800.0, 600.0)
    # One lobe (a single bump, or a plateau): both outputs are the patch's largest pressure.
    assert tables.lobe_maxima(two_bumps(24, 15, 900.0, 0.0, 10, 10)) == (900.0, 900.0)
    assert tables.lobe_maxima(np.full((5, 4), 3.0)) == (3.0, 3.0)
    assert tables.lobe_maxima(np.zeros((5, 4))) == (0.0, 0.0)


def test_a_worker_killed_mid_sweep_costs_its_chunk_only(serial_store, tmp_path, monkeypatch):
    marker = tmp_path / "worker-died"
    # The worker that reaches chunk 16 (40 % of the 40) dies there; dask runs it elsewhere.
    monkeypatch.setenv("FASTNORM_TABLE_FAULT", f"worker-exit-at=16:{marker}")
    store = tmp_path / "dask"
    written = tables.build(SPEC, str(store), executor="dask", workers=2, progress=False)
    assert marker.exists()
    assert written == 40
    assert shard_bytes(store) == shard_bytes(serial_store)
    assert no_partial_files(store)


def test_a_process_pool_broken_by_a_dead_worker_is_replaced(serial_store, tmp_path, monkeypatch):
    marker = tmp_path / "worker-died"
    monkeypatch.setenv("FASTNORM_TABLE_FAULT", f"worker-exit-at=16:{marker}")
    store = tmp_path / "processes"
    assert tables.build(SPEC, str(store), executor="process", workers=2, progress=False) == 40
    assert marker.exists()
    assert shard_bytes(store) == shard_bytes(serial_store)


def test_a_killed_client_loses_nothing_written_and_resumes_with_the_missing_chunks(serial_store, tmp_path):
    spec = tmp_path / "spec.json"
    spec.write_text(__import__("json").dumps(SPEC))
    store = tmp_path / "resumed"
    environment = dict(os.environ, FASTNORM_TABLE_FAULT="client-exit-after=20")
    killed = subprocess.run([sys.executable, "-B", "-m", "fastnorm.tables", "build", str(spec), str(store),
                             "--executor", "process", "--workers", "2"], env=environment, capture_output=True)
    assert killed.returncode == 19, killed.stderr.decode()
    assert len(shard_bytes(store)) == 20
    canonical = tables.canonical_spec(str(spec))
    assert len(tables.missing_chunks(str(store), canonical)) == 20
    # Resuming submits only the 20 missing chunks, and the store is the serial run's.
    assert tables.build(str(spec), str(store), executor="process", workers=2, progress=False) == 20
    assert shard_bytes(store) == shard_bytes(serial_store)
    assert no_partial_files(store)
    assert tables.build(str(spec), str(store), executor="serial", progress=False) == 0


def test_a_cluster_started_from_a_scheduler_file_gives_the_same_table(serial_store, tmp_path):
    scheduler_file = tmp_path / "scheduler.json"
    dask = shutil.which("dask-scheduler"), shutil.which("dask-worker")
    assert all(dask), "dask-scheduler and dask-worker (python3-distributed) must be installed"
    started = [subprocess.Popen([dask[0], "--scheduler-file", str(scheduler_file), "--port", "0",
                                 "--dashboard-address", ":0"], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)]
    try:
        for _ in range(600):
            if scheduler_file.exists():
                break
            time.sleep(0.05)
        for _ in range(2):
            started.append(subprocess.Popen([dask[1], "--scheduler-file", str(scheduler_file), "--nthreads", "1",
                                             "--nworkers", "1", "--dashboard-address", ":0"],
                                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL))
        import distributed
        with distributed.Client(scheduler_file=str(scheduler_file)) as client:
            client.wait_for_workers(2, timeout=120)
        store = tmp_path / "cluster"
        written = tables.build(SPEC, str(store), executor="dask", scheduler_file=str(scheduler_file), progress=False)
        assert written == 40
        assert shard_bytes(store) == shard_bytes(serial_store)
    finally:
        for process in reversed(started):
            process.terminate()
        for process in started:
            process.wait(timeout=60)


SMALL = dict(SPEC, lateral_shift_m=[-2e-3, 0.0, 2e-3], yaw_rad=[0.0, 4e-3], chunk_size=4)


def test_a_store_refuses_another_spec_and_takes_an_added_pair(tmp_path):
    store = str(tmp_path / "store")
    first = dict(SMALL, pairs=[{"name": "A"}])
    assert tables.build(first, store, executor="serial", progress=False) == 2
    before = shard_bytes(store)
    with pytest.raises(ValueError, match="another spec"):
        tables.build(dict(first, elements=24), store, executor="serial", progress=False)
    with pytest.raises(ValueError, match="pairs the spec lacks"):
        tables.build(dict(first, pairs=[{"name": "B"}]), store, executor="serial", progress=False)
    # Adding a pair computes that pair's chunks only; the first pair's shards stay as they were.
    assert tables.build(dict(first, pairs=[{"name": "A"}, {"name": "B"}]), store, executor="serial",
                        progress=False) == 2
    after = shard_bytes(store)
    assert len(after) == 4 and all(after[name] == content for name, content in before.items())
    dataset = tables.open(store)
    assert list(dataset["pair"].values) == ["A", "B"]
    # The same built-in profiles under two names: the same numbers.
    np.testing.assert_array_equal(dataset["normal_force"].sel(pair="A"), dataset["normal_force"].sel(pair="B"))


def test_profile_files_travel_with_the_tasks(tmp_path):
    folder = pathlib.Path(os.environ.get("FASTNORM_PROFILES_DIR") or
                          pathlib.Path(__file__).resolve().parents[3].parent / "shared" / "profiles")
    wheel, rail = folder / "MBench_S1002_v3.prw", folder / "MBench_UIC60_v3.prr"
    if not wheel.exists():
        if os.environ.get("FASTNORM_REQUIRE_SHARED"):
            pytest.fail(f"{wheel} is absent (FASTNORM_REQUIRE_SHARED is set)")
        pytest.skip(f"{wheel} is absent")
    spec = dict(SMALL, pairs=[{"name": "Manchester", "wheel": str(wheel), "rail": str(rail)}])
    store = str(tmp_path / "files")
    assert tables.build(spec, store, executor="process", workers=2, progress=False) == 2
    # The same pair evaluated here directly from the files.
    model = fastnorm.WheelsetContact(solver="cg", elements=20, wheel_profile=str(wheel), rail_profile=str(rail))
    found = model.equilibrium(load_n=2e5, lateral_shift_m=2e-3, yaw_rad=4e-3)
    dataset = tables.open(store)
    assert dataset["vertical"].sel(pair="Manchester", load=2e5, yaw=4e-3, y=2e-3).item() == found.pose.vertical_m


def test_exports_carry_the_store_numbers_and_units(serial_store, tmp_path):
    import netCDF4
    netcdf = tmp_path / "table.nc"
    tables.export(str(serial_store), str(netcdf))
    with netCDF4.Dataset(netcdf) as read:
        for name, variable in read.variables.items():
            assert "units" in variable.ncattrs(), name
        assert read["normal_force"].dimensions == ("pair", "load", "yaw", "y", "wheel", "patch")
    dataset = tables.open(str(serial_store))
    _, arrays = tables.load_arrays(str(serial_store))

    binary = tmp_path / "table.fntable"
    tables.export(str(serial_store), str(binary))
    table = fastnorm.ContactTable.read(str(binary))
    column = table.output_names.index("normal_force_left0")
    topology = tables.topology_codes(arrays["status"], arrays["patch_count"])
    # At a node of solved cases both interpolations give the store's number exactly.
    for k, yaw in enumerate(SPEC["yaw_rad"]):
        for i in (3, 50, 77):
            y = SPEC["lateral_shift_m"][i]
            expected = dataset["normal_force"].sel(yaw=yaw, y=y, wheel="left", patch=0, load=2e5).item()
            for how in ("multilinear", "pchip"):
                status, outputs = table.lookup(0, y, yaw, 2e5, interpolation=how)
                if topology[0, 0, k, i] < 0:
                    assert status != "ok"
                    continue
                if status == "ok":  # a node belongs to the cell above it, which may change topology
                    assert outputs[column] == expected

    text = tmp_path / "text"
    tables.export(str(serial_store), str(text))
    (written,) = list(text.iterdir())
    rows = np.loadtxt(written)
    assert rows.shape[0] == 400
    np.testing.assert_array_equal(rows[:, 3], arrays["case_values"][0, 0, :, :, 0].reshape(-1))


def test_status_reports_a_partial_store(tmp_path, capsys):
    store = str(tmp_path / "partial")
    tables.build(SMALL, store, executor="serial", progress=False)
    os.remove(next(iter(pathlib.Path(store, tables.SHARDS).iterdir())))
    figures = tables.status(store)
    assert figures["chunks"] == 1 and figures["total_chunks"] == 2 and figures["total_cases"] == 6
    assert "chunks 1/2" in capsys.readouterr().out
    assert not tables.open(store)["done"].values.all()


def test_table_slices_are_drawn(serial_store, output_dir):
    from fastnorm import plot
    path = output_dir / "table_slices.png"
    figure = plot.table_slices(tables.open(str(serial_store)), wheel="right", path=str(path))
    assert path.stat().st_size > 10000
    lines = figure.axes[0].get_lines()
    assert len(lines) == 2 * len(SPEC["yaw_rad"])  # tread and flange per yaw
    np.testing.assert_allclose(lines[0].get_xdata(), np.array(SPEC["lateral_shift_m"]) * 1e3)


def test_the_guard_refuses_the_cell_of_flange_onset(tmp_path):
    # Past y = 6.25 mm the equilibrium of S1002 on UIC60 at 200 kN is flange climb (CG, 20
    # elements): the cell that spans the onset is refused, the cells beyond hold failed cases.
    spec = dict(SMALL, lateral_shift_m=[{"start": 5.5e-3, "stop": 7.5e-3, "step": 0.25e-3}], yaw_rad=[0.0, 4e-3])
    store = str(tmp_path / "onset")
    tables.build(spec, store, executor="serial", progress=False)
    _, arrays = tables.load_arrays(store)
    status = arrays["status"][0, 0]
    climbing = status == tables.STATUS_CODES["flange climb"]
    assert climbing.any() and not climbing.all()
    onset = int(np.argmax(climbing[0]))  # the first node of flange climb at yaw 0
    nodes = tables.read_spec(store)["lateral_shift_m"]
    table = tables.contact_table(store)
    for how in ("multilinear", "pchip"):
        assert table.lookup(0, 0.5 * (nodes[onset - 2] + nodes[onset - 1]), 2e-3, 2e5, interpolation=how)[0] == "ok"
        assert table.lookup(0, 0.5 * (nodes[onset - 1] + nodes[onset]), 2e-3, 2e5,
                            interpolation=how) == ("topology change", None)
        assert table.lookup(0, 0.5 * (nodes[onset] + nodes[onset + 1]), 2e-3, 2e5, interpolation=how)[0] in (
            "failed case", "topology change")


def test_progress_is_shown_as_plain_lines_off_a_terminal(tmp_path, capsys):
    tables.build(SMALL, str(tmp_path / "progress"), executor="serial")
    printed = capsys.readouterr().err
    assert "chunks 1/2  cases 4/6" in printed and "chunks 2/2  cases 6/6" in printed
    assert "\r" not in printed  # no bar when stderr is not a terminal


def test_measured_shift_derivatives_are_central_differences_that_the_table_takes(tmp_path):
    # docs/tables.md §1: with shift_derivative_step the build solves y ± step beside each case
    # and stores d/dy; the table's cubic along y then takes them at its nodes.
    step = 3e-6
    spec = dict(SMALL, lateral_shift_m=[4.0e-3, 4.25e-3, 4.5e-3], yaw_rad=[4e-3], shift_derivative_step=step)
    store = str(tmp_path / "measured")
    tables.build(spec, store, executor="serial", progress=False)
    canonical, arrays = tables.load_arrays(store)
    assert canonical["shift_derivative_step"] == step
    assert "shift_derivative_step" not in tables.canonical_spec(SMALL)  # older stores' specs unchanged
    force = [name for name, *_ in tables.PATCH_OUTPUTS].index("normal_force")
    right = tables.WHEELS.index("right")
    model = fastnorm.WheelsetContact(solver="cg", elements=SMALL["elements"])

    def direct(y):
        model.reset()
        return model.equilibrium(load_n=2e5, lateral_shift_m=y, yaw_rad=4e-3).wheels[right].patches[0].normal_force_n

    nodes = spec["lateral_shift_m"]
    measured = arrays["patch_derivatives"][0, 0, 0, :, right, 0, force]
    for i, y in enumerate(nodes):
        assert measured[i] == pytest.approx((direct(y + step) - direct(y - step)) / (2 * step), rel=1e-12)
    values = arrays["patch_values"][0, 0, 0, :, right, 0, force]
    assert (np.diff(values) > 0).all()

    # Between two nodes the lookup is the cubic Hermite form of their values and measured slopes
    # (within Fritsch and Carlson's limit here: no clipping).
    secants = np.diff(values) / np.diff(nodes)
    assert (measured[:2] > 0).all() and (measured[:2] < 3 * secants.min()).all()
    table = tables.contact_table(store)
    column = table.output_names.index("normal_force_right0")
    width = nodes[1] - nodes[0]
    status, outputs = table.lookup(0, 0.5 * (nodes[0] + nodes[1]), 4e-3, 2e5)
    assert status == "ok"
    hermite = 0.5 * (values[0] + values[1]) + width / 8 * (measured[0] - measured[1])
    assert outputs[column] == pytest.approx(hermite, rel=1e-12)

    binary = tmp_path / "measured.fntable"
    tables.export(store, str(binary))
    assert fastnorm.ContactTable.read(str(binary)).lookup(0, 0.5 * (nodes[0] + nodes[1]), 4e-3, 2e5)[1][column] == \
        outputs[column]
    netcdf = tmp_path / "measured.nc"
    tables.export(store, str(netcdf))
    import netCDF4
    with netCDF4.Dataset(netcdf) as read:
        assert read["normal_force_dy"].units == "N m-1"
        assert read["normal_force_dy"].dimensions == ("pair", "load", "yaw", "y", "wheel", "patch")


def test_pressure_fields_are_resampled_on_a_fixed_patch_grid(tmp_path):
    # docs/tables.md §3: with pressure_grid each patch's pressure is kept on fixed cells about
    # its contact reference point, float32: its sum times a cell's area is the patch's normal
    # force to the resampling's accuracy, and its peak is the element pressures' peak or below.
    grid = {"cells": [48, 40], "length_m": 0.024, "width_m": 0.030}
    spec = dict(SMALL, lateral_shift_m=[0.0, 2e-3], yaw_rad=[0.0], pressure_grid=grid)
    store = str(tmp_path / "pressure")
    tables.build(spec, store, executor="serial", progress=False)
    canonical, arrays = tables.load_arrays(store)
    assert canonical["pressure_grid"] == grid
    assert "pressure_grid" not in tables.canonical_spec(SMALL)
    pressure = arrays["pressure"]
    assert pressure.dtype == np.float32 and pressure.shape == (1, 1, 1, 2, 2, 2, 40, 48)
    cell_area = grid["length_m"] / 48 * grid["width_m"] / 40
    force = [name for name, *_ in tables.PATCH_OUTPUTS].index("normal_force")
    peak = [name for name, *_ in tables.PATCH_OUTPUTS].index("max_pressure")
    for i in range(2):
        for w in range(2):
            field, values = pressure[0, 0, 0, i, w, 0], arrays["patch_values"][0, 0, 0, i, w, 0]
            assert field.sum(dtype=np.float64) * cell_area == pytest.approx(values[force], rel=0.02)
            assert 0.8 * values[peak] < field.max() <= values[peak] * (1 + 1e-6)
            assert field[0].max() == 0 and field[:, 0].max() == 0  # the cells reach past the patch
            # No second patch on the tread: NaN there.
            assert np.isnan(pressure[0, 0, 0, i, w, 1]).all()
    dataset = tables.open(store)
    assert dataset["pressure"].attrs["units"] == "Pa"
    assert dataset["pressure_x"].attrs["units"] == "m" and dataset.sizes["pressure_x"] == 48
    np.testing.assert_allclose(dataset["pressure_x"].values[[0, -1]], [-0.012 + 0.00025, 0.012 - 0.00025])
