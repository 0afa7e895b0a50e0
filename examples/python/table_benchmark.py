"""Contact tables, measured (docs/tables.md §6, docs/performance.md §10): the throughput of a
sweep on two workers against one, and the accuracy of table lookups at cell midpoints against
direct evaluation. A benchmark, not a test: it prints figures.

    python3 table_benchmark.py throughput [--repeats 3] [--elements 30]
    python3 table_benchmark.py accuracy [--queries 300] [--elements 40] [--yaws 3] [--loads 3] [--store DIR]
                                        [--derivative-step M]
    python3 table_benchmark.py flange-steps [--elements 40] [--steps 0.05,0.025,0.0125] [--derivative-step M]
    python3 table_benchmark.py lobes [--region tread|flange] [--elements 40] [--derivative-step M]

throughput: 400 equilibria (y -6…6 mm, 4 yaws, one load, CG) built serially in this process,
by a process pool of two workers, by a Dask LocalCluster of two single-thread workers started
by the build (its start-up timed) and by the same on a cluster already running (as with
--scheduler-file), interleaved, each into a new store; medians of the wall times and their
ratios to serial.

accuracy: a table over y -4…4 mm by 0.25 mm and 4…7 mm by 0.05 mm on either side (where one
wheel is on its flange root or flange), yaw 0…8 mrad (--yaws nodes, 3: by 4 mrad) and load
150…250 kN (--loads nodes, 3: by 50 kN) evenly spaced (CG); at
random cell midpoints in all three axes a direct equilibrium beside the PCHIP and
multilinear lookups; per region (tread |y| < 4 mm, flange)
the largest, 95th-percentile and median differences: normal force per patch in units of the
table's largest normal force, contact angle in rad, largest pressure relative (as the
max_pressure output interpolated, and as the larger of the two lobes' interpolated maxima,
max_pressure_by_lobes: docs/tables.md §3), and where the largest lies. Midpoints whose cell
the topology guard refuses are counted, not compared.

flange-steps: what the y step must be just before flange climb. Tables over y 5.9…6.5 mm by
0.05, 0.025 and 0.0125 mm (yaw 4, 6, 8 mrad; load 150, 200, 250 kN); at every y midpoint,
yaw and load at their nodes, PCHIP against a direct equilibrium: the largest normal force
difference per patch (in units of 455 505 N, the accuracy table's largest patch force at 40
elements) and contact angle difference (rad), and where each lies; then every patch above
issue 30's 5e-4 and 1e-3 rad.

lobes: the largest pressure where two lobes' peaks cross between nodes. A table over the
tread, y -4…4 mm by 0.25 mm, or near the right flange, y 4…7 mm by 0.05 mm (--region; yaw 0, 4,
8 mrad; load 150, 200, 250 kN); at every y
midpoint, yaw and load at their nodes, PCHIP against a direct equilibrium: max_pressure
interpolated against the larger of the two lobes' interpolated maxima (docs/validation.md §8),
relative, per patch.

--derivative-step M: the tables are built with the spec's shift_derivative_step = M (m): the
outputs' d/dy measured by central differences at y ± M, which the lookups' cubics along y take
(docs/tables.md §1).
"""

import argparse
import os
import shutil
import tempfile
import time

import numpy as np

import fastnorm
from fastnorm import tables


def throughput(repeats, elements):
    spec = {"lateral_shift_m": [float(y) for y in np.linspace(-6e-3, 6e-3, 100)], "yaw_rad": [0.0, 2e-3, 4e-3, 6e-3],
            "load_n": [2e5], "solver": "cg", "elements": elements, "chunk_size": 10}
    running = tables.make_executor("dask", workers=2)
    ways = {"serial": dict(executor="serial"), "process2": dict(executor="process", workers=2),
            "dask2": dict(executor="dask", workers=2), "dask2_running": dict(executor=running)}
    seconds = {name: [] for name in ways}
    folder = tempfile.mkdtemp(prefix="fastnorm-table-bench-")
    try:
        for repeat in range(repeats):
            for name, how in ways.items():
                store = os.path.join(folder, f"{name}-{repeat}")
                start = time.perf_counter()
                tables.build(spec, store, progress=False, **how)
                seconds[name].append(time.perf_counter() - start)
    finally:
        running.close()
        shutil.rmtree(folder)
    serial = np.median(seconds["serial"])
    print(f"throughput cases=400 elements={elements} repeats={repeats} cores={os.cpu_count()}")
    for name, values in seconds.items():
        print(f"  {name}: median_s={np.median(values):.2f} ratio_to_serial={np.median(values) / serial:.3f} "
              f"spread={max(values) / min(values):.2f}")


# What accuracy and flange-steps compare per patch, each as a difference from a direct
# equilibrium: the normal force in units of a largest force, the angle in rad, pmax relative.
COMPARED = ("normal_force", "contact_angle", "max_pressure", "max_pressure_by_lobes")


def _direct(model, y, yaw, load):
    """The equilibrium at (y, yaw, load) from a reset model, or None (reported) if it did not converge."""
    model.reset()
    direct = model.equilibrium(load_n=load, lateral_shift_m=y, yaw_rad=yaw)
    if direct.status != "converged":
        print(f"  direct equilibrium at y={y:.6g} yaw={yaw:.3g} load={load:.6g}: {direct.status}")
        return None
    return direct


def _differences(names, outputs, direct, largest_force, y, yaw, load):
    """(where, {output: difference}) for each patch of `direct` against a lookup's `outputs`."""
    for w, wheel in enumerate(tables.WHEELS):
        for p, patch in enumerate(direct.wheels[w].patches[:tables.PATCHES]):
            at = {name: outputs[names.index(f"{name}_{wheel}{p}")]
                  for name in ("normal_force", "contact_angle", "max_pressure", "max_pressure_lower_lobe",
                               "max_pressure_upper_lobe")}
            by_lobes = max(at["max_pressure_lower_lobe"], at["max_pressure_upper_lobe"])
            yield (f"y={y * 1e3:.5g}mm yaw={yaw * 1e3:.3g}mrad load={load / 1e3:.4g}kN {wheel}{p}",
                   {"normal_force": abs(at["normal_force"] - patch.normal_force_n) / largest_force,
                    "contact_angle": abs(at["contact_angle"] - patch.contact_angle_rad),
                    "max_pressure": abs(at["max_pressure"] / patch.max_pressure_pa - 1),
                    "max_pressure_by_lobes": abs(by_lobes / patch.max_pressure_pa - 1)})


def accuracy(queries, elements, yaws, loads, store, derivative_step=None):
    spec = {"lateral_shift_m": [{"start": -7e-3, "stop": -4e-3, "step": 0.05e-3},
                                {"start": -4e-3, "stop": 4e-3, "step": 0.25e-3},
                                {"start": 4e-3, "stop": 7e-3, "step": 0.05e-3}],
            "yaw_rad": [float(v) for v in np.linspace(0.0, 8e-3, yaws)],
            "load_n": [float(v) for v in np.linspace(1.5e5, 2.5e5, loads)], "solver": "cg", "elements": elements,
            "chunk_size": 20, "shift_derivative_step": derivative_step}
    store = store or tempfile.mkdtemp(prefix="fastnorm-table-accuracy-")
    tables.build(spec, store, executor="process", workers=2, progress=False)
    table = tables.contact_table(store)
    canonical = tables.read_spec(store)
    axes = canonical["lateral_shift_m"], canonical["yaw_rad"], canonical["load_n"]
    names = table.output_names
    _, arrays = tables.load_arrays(store)
    largest_force = np.nanmax(arrays["patch_values"][..., 0])
    model = fastnorm.WheelsetContact(solver="cg", elements=elements)
    rng = np.random.default_rng(1)
    differences = {(region, how): {name: [] for name in COMPARED}
                   for region in ("tread", "flange") for how in ("pchip", "multilinear")}
    largest_at = {}  # (region, how, output) -> (difference, where)
    guarded = 0
    for _ in range(queries):
        i, k, m = (int(rng.integers(len(axis) - 1)) for axis in axes)
        y, yaw, load = ((axis[n] + axis[n + 1]) / 2 for axis, n in zip(axes, (i, k, m)))
        looked_up = {how: table.lookup(0, y, yaw, load, interpolation=how) for how in ("pchip", "multilinear")}
        if looked_up["pchip"][0] != "ok":
            guarded += 1
            continue
        direct = _direct(model, y, yaw, load)
        if direct is None:
            continue
        region = "tread" if abs(y) < 4e-3 else "flange"
        for how, (_, outputs) in looked_up.items():
            for where, patch_differences in _differences(names, outputs, direct, largest_force, y, yaw, load):
                for name, difference in patch_differences.items():
                    differences[(region, how)][name].append(difference)
                    if difference >= largest_at.get((region, how, name), (-1.0, ""))[0]:
                        largest_at[(region, how, name)] = (difference, where)
    print(f"accuracy queries={queries} elements={elements} yaws={yaws} loads={loads} "
          f"derivative_step={derivative_step} guarded={guarded} "
          f"largest_force_n={largest_force:.6g}")
    for (region, how), d in differences.items():
        for name, values in d.items():
            print(f"  {region} {how} {name}: patches={len(values)} max={max(values):.3g} "
                  f"p95={np.percentile(values, 95):.3g} median={np.median(values):.3g} "
                  f"largest_at {largest_at[(region, how, name)][1]}")


def _along_y(spec, largest_force):
    """Builds the table of `spec` (on two workers, in a temporary store) and yields, at every
    y midpoint with yaw and load at their nodes, None where the topology guard refuses the
    cell, else the (where, differences) of _differences for each patch of a direct
    equilibrium (none if it did not converge), the lookups PCHIP."""
    store = tempfile.mkdtemp(prefix="fastnorm-table-")
    try:
        tables.build(spec, store, executor="process", workers=2, progress=False)
        table, shifts = tables.contact_table(store), tables.read_spec(store)["lateral_shift_m"]
    finally:
        shutil.rmtree(store)
    model = fastnorm.WheelsetContact(solver="cg", elements=spec["elements"])
    for yaw in spec["yaw_rad"]:
        for load in spec["load_n"]:
            for i in range(len(shifts) - 1):
                y = (shifts[i] + shifts[i + 1]) / 2
                status, outputs = table.lookup(0, y, yaw, load, interpolation="pchip")
                if status != "ok":
                    yield None
                    continue
                direct = _direct(model, y, yaw, load)
                if direct is not None:
                    yield from _differences(table.output_names, outputs, direct, largest_force, y, yaw, load)


def flange_steps(elements, steps, derivative_step=None):
    for step in steps:
        spec = {"lateral_shift_m": [{"start": 5.9e-3, "stop": 6.5e-3, "step": step}], "yaw_rad": [4e-3, 6e-3, 8e-3],
                "load_n": [1.5e5, 2e5, 2.5e5], "solver": "cg", "elements": elements, "chunk_size": 20,
                "shift_derivative_step": derivative_step}
        largest = {"normal_force": (0.0, ""), "contact_angle": (0.0, "")}
        target = {"normal_force": 5e-4, "contact_angle": 1e-3}  # issue 30's
        over = {name: [] for name in largest}
        compared = guarded = 0
        for patch in _along_y(spec, 455505.0):
            if patch is None:
                guarded += 1
                continue
            where, patch_differences = patch
            compared += 1
            for name in largest:
                if patch_differences[name] > largest[name][0]:
                    largest[name] = (patch_differences[name], where)
                if patch_differences[name] > target[name]:
                    over[name].append(f"{patch_differences[name]:.3g} at {where}")
        print(f"flange_steps elements={elements} step_mm={step * 1e3:.4g} derivative_step={derivative_step} "
              f"compared={compared} guarded={guarded} "
              f"normal_force_max={largest['normal_force'][0]:.3g} at {largest['normal_force'][1]} "
              f"contact_angle_max={largest['contact_angle'][0]:.3g} at {largest['contact_angle'][1]}", flush=True)
        for name, misses in over.items():
            print(f"  {name} above {target[name]:g}: {len(misses)} of {compared}" + "".join(f"\n    {m}" for m in misses))


LOBE_REGIONS = {"tread": {"start": -4e-3, "stop": 4e-3, "step": 0.25e-3},
                "flange": {"start": 4e-3, "stop": 7e-3, "step": 0.05e-3}}


def lobes(elements, region, derivative_step=None):
    spec = {"lateral_shift_m": [LOBE_REGIONS[region]], "yaw_rad": [0.0, 4e-3, 8e-3],
            "load_n": [1.5e5, 2e5, 2.5e5], "solver": "cg", "elements": elements, "chunk_size": 20,
            "shift_derivative_step": derivative_step}
    compared = {"max_pressure": [], "max_pressure_by_lobes": []}
    largest_at = {}
    for where, patch_differences in filter(None, _along_y(spec, 1.0)):
        for name, values in compared.items():
            values.append(patch_differences[name])
            if patch_differences[name] >= largest_at.get(name, (-1.0, ""))[0]:
                largest_at[name] = (patch_differences[name], where)
    for name, values in compared.items():
        print(f"lobes region={region} elements={elements} derivative_step={derivative_step} {name}: patches={len(values)} max={max(values):.3g} "
              f"p95={np.percentile(values, 95):.3g} median={np.median(values):.3g} largest_at {largest_at[name][1]}")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("what", choices=["throughput", "accuracy", "flange-steps", "lobes"])
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--queries", type=int, default=300)
    parser.add_argument("--elements", type=int, default=None, help="default 30 (throughput), 40 (the others)")
    parser.add_argument("--yaws", type=int, default=3, help="accuracy: yaw nodes over 0…8 mrad")
    parser.add_argument("--loads", type=int, default=3, help="accuracy: load nodes over 150…250 kN")
    parser.add_argument("--store", default=None, help="accuracy: build into (or reuse) this store")
    parser.add_argument("--region", choices=sorted(LOBE_REGIONS), default="tread", help="lobes: where")
    parser.add_argument("--steps", default="0.05,0.025,0.0125", help="flange-steps: the y steps (mm)")
    parser.add_argument("--derivative-step", type=float, default=None,
                        help="build with shift_derivative_step = this (m): d/dy measured at y ± it")
    args = parser.parse_args()
    if args.what == "throughput":
        throughput(args.repeats, args.elements or 30)
    elif args.what == "lobes":
        lobes(args.elements or 40, args.region, args.derivative_step)
    elif args.what == "flange-steps":
        flange_steps(args.elements or 40, [float(step) * 1e-3 for step in args.steps.split(",")], args.derivative_step)
    else:
        accuracy(args.queries, args.elements or 40, args.yaws, args.loads, args.store, args.derivative_step)


if __name__ == "__main__":
    main()
