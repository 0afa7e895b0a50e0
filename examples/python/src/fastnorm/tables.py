"""fastnorm.tables: contact tables swept over many cases on any executor (docs/tables.md).

A table spec (JSON) names the kind of case (the static equilibrium of a loaded wheelset),
its axes (lateral shift y, yaw, load; any increasing nodes, finer near the flange where
wanted), the wheel/rail profile pairs (files or the built-in S1002/UIC60) and the solver.
``build`` cuts the cases into chunks, submits a window of them at a time to an executor (the
standard library's process pool, a Dask distributed client, or in-process) and writes each
finished chunk as one shard of the store, atomically, from the client alone. Running
``build`` again resumes: only chunks without a shard are computed. ``open`` gives the
(possibly partial) table as an xarray Dataset, ``export`` a netCDF-4 file, a binary file for
fastnorm::ContactTable (C++, C and fastnorm.ContactTable) or text columns.

Command line: ``python3 -m fastnorm.tables build SPEC STORE [--executor process|dask|serial]
[--workers N] [--scheduler-file F | --scheduler ADDRESS] [--retry-failed]``,
``status STORE``, ``export STORE OUT`` (OUT: name.nc, name.fntable, or a folder for text).

Every case is computed by a model reset before it (no history), so a table is bit for bit
the same whatever the executor, the order of the chunks or the faults on the way.
"""

import argparse
import builtins
import hashlib
import json
import os
import sys
import tempfile
import time

import numpy as np

from ._fastnorm import ContactTable, WheelsetContact, __version__

SPEC_FILE = "spec.json"
SHARDS = "shards"
FAILURES = "failures"
WHEELS = ("left", "right")
PATCHES = 2  # per wheel: tread first, then flange (docs/wheel-rail.md)
BUILT_IN_PAIR = "S1002/UIC60"

# Equilibrium.status as a number; 0: not computed.
STATUS_CODES = {"converged": 1, "lost contact": 2, "not converged": 3, "solver failed": 4, "flange climb": 5}

# Per case: (name, CF unit, long name, value of an Equilibrium).
CASE_OUTPUTS = (
    ("vertical", "m", "wheelset centre's vertical position (z down)", lambda e: e.pose.vertical_m),
    ("roll", "rad", "wheelset roll angle", lambda e: e.pose.roll_rad),
    ("vertical_force", "N", "vertical force the rails carry", lambda e: e.vertical_force_n),
    ("lateral_force", "N", "lateral force that holds the shift", lambda e: e.lateral_force_n),
)

# Per patch: (name, CF unit, long name, value of a Patch).
PATCH_OUTPUTS = (
    ("normal_force", "N", "normal force", lambda p: p.normal_force_n),
    ("contact_angle", "rad", "contact angle from the vertical, + towards the track centre",
     lambda p: p.contact_angle_rad),
    ("contact_y", "m", "lateral position of the contact reference point, track frame",
     lambda p: p.centre_m[1]),
    ("contact_z", "m", "vertical position of the contact reference point, track frame (z down)",
     lambda p: p.centre_m[2]),
    ("profile_y", "m", "wheel profile coordinate of the contact reference point", lambda p: p.profile_y_m),
    ("rolling_radius", "m", "wheel rolling radius at the contact reference point", lambda p: p.rolling_radius_m),
    ("max_pressure", "Pa", "largest pressure", lambda p: p.max_pressure_pa),
    ("max_pressure_lower_lobe", "Pa", "largest pressure of the pressure lobe at lower s",
     lambda p: lobe_maxima(p.solution.pressure_pa)[0]),
    ("max_pressure_upper_lobe", "Pa", "largest pressure of the pressure lobe at higher s",
     lambda p: lobe_maxima(p.solution.pressure_pa)[1]),
    ("area", "m2", "contact area", lambda p: p.contact_elements * p.grid.dx_m * p.grid.dy_m),
    ("length", "m", "extent of the contact area along the rolling direction", lambda p: _extent(p, 1, p.grid.dx_m)),
    ("width", "m", "extent of the contact area across", lambda p: _extent(p, 0, p.grid.dy_m)),
    ("stiffness", "N m-1", "normal contact stiffness dFn/d(approach)", lambda p: p.stiffness_n_per_m),
    ("approach", "m", "rigid interpenetration", lambda p: p.approach_m),
)


def _flat_outputs():
    """(name, unit) of every output in a ContactTable's order: the case outputs, then each
    patch output per wheel and patch (name_left0, ...)."""
    flat = [(name, unit) for name, unit, _, _ in CASE_OUTPUTS]
    for wheel in WHEELS:
        for patch in range(PATCHES):
            flat += [(f"{name}_{wheel}{patch}", unit) for name, unit, _, _ in PATCH_OUTPUTS]
    return flat


def _empty_arrays(cases, canonical=None):
    """The arrays of `cases` cases as a shard holds them: not computed (status 0, NaN); with the
    spec's shift_derivative_step, also the outputs' measured d/dy, and with its pressure_grid
    the patches' resampled pressures (float32)."""
    canonical = canonical or {}
    arrays = {"status": np.zeros(cases, np.int8), "patch_count": np.zeros((cases, len(WHEELS)), np.int8),
              "case_values": np.full((cases, len(CASE_OUTPUTS)), np.nan),
              "patch_values": np.full((cases, len(WHEELS), PATCHES, len(PATCH_OUTPUTS)), np.nan)}
    if "shift_derivative_step" in canonical:
        arrays["case_derivatives"] = np.full_like(arrays["case_values"], np.nan)
        arrays["patch_derivatives"] = np.full_like(arrays["patch_values"], np.nan)
    if "pressure_grid" in canonical:
        cells_x, cells_s = canonical["pressure_grid"]["cells"]
        arrays["pressure"] = np.full((cases, len(WHEELS), PATCHES, cells_s, cells_x), np.nan, np.float32)
    return arrays


def pressure_grid_axes(pressure_grid):
    """The cell centres (x, s) of the spec's pressure_grid, in the patch's tangent plane about its
    contact reference point (m): x along the rolling direction, s across."""
    cells_x, cells_s = pressure_grid["cells"]
    length, width = pressure_grid["length_m"], pressure_grid["width_m"]
    return (length * ((np.arange(cells_x) + 0.5) / cells_x - 0.5),
            width * ((np.arange(cells_s) + 0.5) / cells_s - 0.5))


def _resample_pressure(patch, axes):
    """The patch's element pressures at the fixed cells' centres (s rows, x columns), bilinear
    between element centres, zero beyond the patch's grid (no contact there); float32. Not
    force-conserving: the force is normal_force."""
    grid = patch.grid
    padded = np.zeros((grid.my + 2, grid.mx + 2))
    padded[1:-1, 1:-1] = patch.solution.pressure_pa
    # The grid's coordinates are about its origin reference_m; the cells about the reference point.
    offset = np.asarray(patch.centre_m) - np.asarray(patch.reference_m)
    x = axes[0] + float(np.dot(offset, patch.e_x))
    s = axes[1] + float(np.dot(offset, patch.t_s))

    def split(coordinate, origin, step, count):
        # Index into the padded grid (1 + element index), clipped into its zero border.
        at = np.clip((coordinate - origin) / step + 1, 0, count + 1)
        lower = np.minimum(np.floor(at).astype(int), count)
        return lower, at - lower

    i, ti = split(x, grid.x0_m, grid.dx_m, grid.mx)
    j, tj = split(s, grid.y0_m, grid.dy_m, grid.my)
    i, ti, j, tj = i[None, :], ti[None, :], j[:, None], tj[:, None]
    value = ((1 - tj) * ((1 - ti) * padded[j, i] + ti * padded[j, i + 1]) +
             tj * ((1 - ti) * padded[j + 1, i] + ti * padded[j + 1, i + 1]))
    return value.astype(np.float32)


def lobe_maxima(pressure):
    """(lower, upper): the largest pressures of a patch's two pressure lobes across the rolling
    direction (docs/tables.md §3). Rows are strips at fixed s; q(s) is each row's largest
    pressure. With two or more local maxima of q, the two highest split the patch at the
    lowest q between them, and each side's largest q is its lobe's; with one, both are the
    patch's largest pressure. The larger of the two is always the patch's max_pressure; the
    point of the split is between nodes of a table, where two lobes' peaks can cross (a kink
    in max_pressure that no interpolant of it follows): the larger of the two lobes'
    interpolants follows it (docs/validation.md §8)."""
    row_peak = np.asarray(pressure).max(axis=1)
    rows = row_peak.size
    peaks = [j for j in range(rows) if row_peak[j] > 0 and (j == 0 or row_peak[j] >= row_peak[j - 1])
             and (j == rows - 1 or row_peak[j] > row_peak[j + 1])]
    if len(peaks) < 2:
        largest = float(row_peak.max())
        return largest, largest
    first, second = sorted(sorted(peaks, key=lambda j: -row_peak[j])[:2])
    split = first + int(np.argmin(row_peak[first:second + 1]))
    return float(row_peak[:split].max()), float(row_peak[split:].max())


def _extent(patch, axis, size):
    """Elements in contact along one grid axis (1: x, 0: across), times the element size."""
    in_contact = np.asarray(patch.solution.in_contact)
    touched = np.flatnonzero(in_contact.any(axis=1 - axis))
    return 0.0 if touched.size == 0 else float(touched[-1] - touched[0] + 1) * size


# ---------------------------------------------------------------------------------------------
# The spec


def _axis_nodes(value, name):
    """An axis of the spec: a list of nodes, or a list of {"start", "stop", "step"} pieces."""
    if not isinstance(value, list) or not value:
        raise ValueError(f"spec: {name} must be a non-empty list of numbers or of pieces")
    nodes = []
    for item in value:
        if isinstance(item, dict):
            try:
                start, stop, step = float(item["start"]), float(item["stop"]), float(item["step"])
            except (KeyError, TypeError, ValueError) as error:
                raise ValueError(f"spec: a piece of {name} needs numbers start, stop, step ({error})") from None
            if not step > 0 or not stop >= start:
                raise ValueError(f"spec: a piece of {name} needs step > 0 and stop >= start (got {item})")
            count = int(round((stop - start) / step))
            if not np.isclose(start + count * step, stop, rtol=0, atol=1e-9 * max(1.0, abs(stop))):
                raise ValueError(f"spec: a piece of {name}: (stop - start) must be a whole number of steps (got {item})")
            nodes.extend(start + step * np.arange(count + 1))
        else:
            nodes.append(float(item))
    # Pieces that meet share their node.
    merged = []
    for node in nodes:
        if merged and abs(node - merged[-1]) <= 1e-12 * max(1.0, abs(node)):
            continue
        merged.append(node)
    if not all(np.isfinite(merged)) or any(b <= a for a, b in zip(merged, merged[1:])):
        raise ValueError(f"spec: {name} must be finite and increase strictly (got {merged})")
    return [float(node) for node in merged]


def _read_text(path, base):
    full = path if os.path.isabs(path) else os.path.join(base, path)
    with builtins.open(full, encoding="utf-8") as file:
        return file.read()


def canonical_spec(spec, base="."):
    """The spec with its axes as explicit nodes, the profiles' texts and hashes, and the fastnorm
    version: what a store keeps and what decides whether a build may resume into it.
    `spec`: a dict or the path of a JSON file (profile paths relative to it)."""
    if not isinstance(spec, dict):
        base = os.path.dirname(os.path.abspath(spec))
        with builtins.open(spec, encoding="utf-8") as file:
            spec = json.load(file)
    kind = spec.get("kind", "equilibrium")
    if kind != "equilibrium":
        raise ValueError(f"spec: kind must be 'equilibrium' (got {kind!r}); at-pose tables are not built yet")
    pairs = []
    for pair in spec.get("pairs", [{"name": BUILT_IN_PAIR}]):
        wheel, rail = pair.get("wheel"), pair.get("rail")
        if (wheel is None) != (rail is None):
            raise ValueError(f"spec: pair {pair.get('name')!r} must give both wheel and rail profiles, or neither")
        texts = None if wheel is None else [_read_text(wheel, base), _read_text(rail, base)]
        # The file name's ending tells the profile reader the format (.prw/.prr: SIMPACK).
        suffixes = None if wheel is None else [os.path.splitext(wheel)[1], os.path.splitext(rail)[1]]
        name = pair.get("name") or (BUILT_IN_PAIR if texts is None else
                                    f"{os.path.basename(wheel)}/{os.path.basename(rail)}")
        digest = hashlib.sha256(("built-in" if texts is None else "\0".join(texts + suffixes)).encode()).hexdigest()
        pairs.append({"name": name, "profiles": texts, "suffixes": suffixes, "sha256": digest})
    if len({p["name"] for p in pairs}) != len(pairs):
        raise ValueError("spec: pair names must differ")
    elements = int(spec.get("elements", 40))
    chunk_size = int(spec.get("chunk_size", 10))
    if elements < 4 or chunk_size < 1:
        raise ValueError("spec: elements must be >= 4 and chunk_size >= 1")
    optional = {}
    if spec.get("shift_derivative_step") is not None:
        step = float(spec["shift_derivative_step"])
        if not (np.isfinite(step) and 0 < step < 1e-3):
            raise ValueError(f"spec: shift_derivative_step must be a step in m between 0 and 1e-3 (got {step})")
        optional["shift_derivative_step"] = step  # only when set: older stores' specs stay equal
    if spec.get("pressure_grid") is not None:
        grid = spec["pressure_grid"]
        try:
            cells = [int(n) for n in grid["cells"]]
            length, width = float(grid["length_m"]), float(grid["width_m"])
        except (KeyError, TypeError, ValueError) as error:
            raise ValueError(f"spec: pressure_grid needs cells [nx, ns], length_m and width_m ({error})") from None
        if len(cells) != 2 or not all(2 <= n <= 512 for n in cells) or not (0 < length < 1 and 0 < width < 1):
            raise ValueError(f"spec: pressure_grid needs 2..512 cells a side and sizes in (0, 1) m (got {grid})")
        optional["pressure_grid"] = {"cells": cells, "length_m": length, "width_m": width}
    return {**optional,
        "fastnorm_version": __version__,
        "kind": kind,
        "lateral_shift_m": _axis_nodes(spec.get("lateral_shift_m"), "lateral_shift_m"),
        "yaw_rad": _axis_nodes(spec.get("yaw_rad", [0.0]), "yaw_rad"),
        "load_n": _axis_nodes(spec.get("load_n", [2e5]), "load_n"),
        "pairs": pairs,
        # CG by default: the exact answer, and an equilibrium that converges everywhere (the
        # elliptic basis's small jumps in Fn(z) stall the equilibrium's Newton at some yaws).
        "solver": str(spec.get("solver", "cg")),
        "elements": elements,
        "chunk_size": chunk_size,
    }


def spec_text(canonical):
    return json.dumps(canonical, sort_keys=True, separators=(",", ":"))


def case_shape(canonical):
    """(pairs, loads, yaws, shifts): the cases in the order chunks cut them (y fastest)."""
    return (len(canonical["pairs"]), len(canonical["load_n"]), len(canonical["yaw_rad"]),
            len(canonical["lateral_shift_m"]))


def all_chunks(canonical):
    """The chunks, (pair, number): a pair's cases in order, cut every chunk_size cases (a chunk
    never spans two pairs, so that a pair added to a store adds only its own chunks)."""
    per_pair = int(np.prod(case_shape(canonical)[1:]))
    count = -(-per_pair // canonical["chunk_size"])
    return [(pair, number) for pair in range(len(canonical["pairs"])) for number in range(count)]


def _cases_in(canonical, chunk):
    per_pair = int(np.prod(case_shape(canonical)[1:]))
    return min(canonical["chunk_size"], per_pair - chunk[1] * canonical["chunk_size"])


def _pair_key(pair):
    """A pair's name in shard file names: its name and profiles, hashed."""
    return hashlib.sha256((pair["name"] + "\0" + pair["sha256"]).encode()).hexdigest()[:16]


# ---------------------------------------------------------------------------------------------
# A chunk, on a worker

_models = {}  # (spec hash, pair index) -> WheelsetContact, one per worker process


def _model(canonical, digest, pair_index):
    key = (digest, pair_index)
    if key not in _models:
        pair = canonical["pairs"][pair_index]
        profiles = {}
        if pair["profiles"] is not None:
            # WheelsetContact reads files: each profile's text goes to a file named by its hash
            # (written once per machine, atomically, so that workers may race for it).
            for role, text, suffix in zip(("wheel", "rail"), pair["profiles"], pair["suffixes"]):
                path = os.path.join(tempfile.gettempdir(), f"fastnorm-profile-{pair['sha256'][:24]}-{role}{suffix}")
                if not os.path.exists(path):
                    _write_atomically(path, lambda file, t=text: file.write(t.encode()))
                profiles[f"{role}_profile"] = path
        _models[key] = WheelsetContact(solver=canonical["solver"], elements=canonical["elements"], **profiles)
    return _models[key]


def _faults():
    """Fault injection for the tests (docs/tables.md §2): FASTNORM_TABLE_FAULT names them."""
    return [fault for fault in os.environ.get("FASTNORM_TABLE_FAULT", "").split(",") if fault]


def compute_chunk(text, pair, number):
    """The arrays of chunk `number` of pair `pair`: runs on a worker. `text`: the canonical spec
    (spec_text), which carries the profiles' texts."""
    canonical = json.loads(text)
    digest = hashlib.sha256(text.encode()).hexdigest()
    for fault in _faults():
        # worker-exit-at=K:MARKER: the first worker to reach chunk K (of all_chunks) dies there, once.
        if fault.startswith("worker-exit-at="):
            at, marker = fault[len("worker-exit-at="):].split(":", 1)
            if all_chunks(canonical)[int(at)] == (pair, number) and not os.path.exists(marker):
                builtins.open(marker, "w").close()
                os._exit(17)
    shape = case_shape(canonical)[1:]
    total = int(np.prod(shape))
    first = number * canonical["chunk_size"]
    cases = range(first, min(first + canonical["chunk_size"], total))
    step = canonical.get("shift_derivative_step")
    arrays = _empty_arrays(len(cases), canonical)
    model = _model(canonical, digest, pair)
    for row, case in enumerate(cases):
        load, yaw, shift = np.unravel_index(case, shape)
        at = (canonical["load_n"][load], canonical["yaw_rad"][yaw], canonical["lateral_shift_m"][shift])
        found = _solve_case(model, *at, pressure_grid=canonical.get("pressure_grid"))
        for name, array in found.items():
            arrays[name][row] = array
        if step is None:
            continue
        # d/dy by central differences (docs/tables.md §1), where both neighbours converged with
        # the case's patches; NaN elsewhere, and the table estimates it (PCHIP).
        below, above = (_solve_case(model, at[0], at[1], at[2] + sign * step) for sign in (-1, 1))
        converged = STATUS_CODES["converged"]
        if all(c["status"] == converged and np.array_equal(c["patch_count"], found["patch_count"])
               for c in (found, below, above)):
            for name in ("case_values", "patch_values"):
                arrays[name.replace("values", "derivatives")][row] = (above[name] - below[name]) / (2 * step)
    return arrays


def _solve_case(model, load, yaw, shift, pressure_grid=None):
    """One case's arrays (as _empty_arrays' rows: values, and the pressures resampled on
    `pressure_grid` if given) from an equilibrium of a reset model: no history, so that the
    same case gives the same numbers in any chunk order."""
    model.reset()
    found = model.equilibrium(load_n=load, lateral_shift_m=shift, yaw_rad=yaw)
    spec = {"pressure_grid": pressure_grid} if pressure_grid is not None else None
    arrays = {name: array[0] for name, array in _empty_arrays(1, spec).items()}
    pressure_axes = pressure_grid_axes(pressure_grid) if pressure_grid is not None else None
    arrays["status"] = STATUS_CODES[found.status]
    arrays["case_values"][:] = [value(found) for _, _, _, value in CASE_OUTPUTS]
    for w, wheel in enumerate(found.wheels):
        arrays["patch_count"][w] = len(wheel.patches)
        for p, patch in enumerate(wheel.patches[:PATCHES]):
            arrays["patch_values"][w, p] = [value(patch) for _, _, _, value in PATCH_OUTPUTS]
            if pressure_axes is not None:
                arrays["pressure"][w, p] = _resample_pressure(patch, pressure_axes)
    return arrays


# ---------------------------------------------------------------------------------------------
# The store


def _shard_path(store, canonical, chunk):
    pair, number = chunk
    return os.path.join(store, SHARDS, f"{_pair_key(canonical['pairs'][pair])}-{number:06d}.npz")


def _failure_path(store, canonical, chunk):
    pair, number = chunk
    return os.path.join(store, FAILURES, f"{_pair_key(canonical['pairs'][pair])}-{number:06d}.txt")


def _umask():
    mask = os.umask(0)
    os.umask(mask)
    return mask


def _write_atomically(path, write):
    """Writes through a temporary name in the same folder, renamed into place when complete."""
    folder = os.path.dirname(path)
    handle, temporary = tempfile.mkstemp(dir=folder, prefix=".partial-", suffix=os.path.splitext(path)[1])
    try:
        os.chmod(temporary, 0o666 & ~_umask())  # mkstemp's 0600 would hide a store from a cluster's other users
        with os.fdopen(handle, "wb") as file:
            write(file)
            file.flush()
            os.fsync(file.fileno())
        os.replace(temporary, path)
    except BaseException:
        if os.path.exists(temporary):
            os.remove(temporary)
        raise


def _prepare_store(store, canonical):
    """Creates the store, or checks that the one there was made from the same spec, but for
    pairs added (whose chunks are then built)."""
    os.makedirs(os.path.join(store, SHARDS), exist_ok=True)
    os.makedirs(os.path.join(store, FAILURES), exist_ok=True)
    path = os.path.join(store, SPEC_FILE)
    text = spec_text(canonical)
    if os.path.exists(path):
        stored = read_spec(store)
        settings = {key: value for key, value in stored.items() if key != "pairs"}
        if settings != {key: value for key, value in canonical.items() if key != "pairs"}:
            raise ValueError(f"store {store!r} was built from another spec (axes, solver, elements, chunk size "
                             "or fastnorm version); build into a new store")
        kept = [_pair_key(pair) for pair in canonical["pairs"]]
        dropped = [pair["name"] for pair in stored["pairs"] if _pair_key(pair) not in kept]
        if dropped:
            raise ValueError(f"store {store!r} holds pairs the spec lacks ({', '.join(dropped)}): a spec may add "
                             "pairs to a store, not remove or change them")
    if not os.path.exists(path) or spec_text(read_spec(store)) != text:
        _write_atomically(path, lambda file: file.write(text.encode()))
    for leftover in os.listdir(os.path.join(store, SHARDS)):  # a killed client's partial write
        if leftover.startswith(".partial-"):
            os.remove(os.path.join(store, SHARDS, leftover))


def read_spec(store):
    with builtins.open(os.path.join(store, SPEC_FILE), encoding="utf-8") as file:
        return json.load(file)


def missing_chunks(store, canonical, retry_failed=False):
    chunks = []
    for chunk in all_chunks(canonical):
        if os.path.exists(_shard_path(store, canonical, chunk)):
            continue
        if os.path.exists(_failure_path(store, canonical, chunk)) and not retry_failed:
            continue
        chunks.append(chunk)
    return chunks


# ---------------------------------------------------------------------------------------------
# Executors: submit, and wait for the first of some futures to finish


class _Serial:
    """Computes at submission, in this process (the reference run)."""

    class Done:
        def __init__(self, function, args):
            try:
                self._value, self._error = function(*args), None
            except Exception as error:  # noqa: BLE001 - carried to the client as a failure
                self._value, self._error = None, error

        def result(self):
            if self._error is not None:
                raise self._error
            return self._value

    workers = 1

    def submit(self, function, *args):
        return self.Done(function, args)

    def wait_first(self, futures):
        return set(futures)

    def close(self):
        pass


def _exit_with_parent(parent):
    """In a pool's worker: exit when the client that started it is gone (a killed client's pool
    would otherwise wait for work forever)."""
    import threading

    def watch():
        while os.getppid() == parent:
            time.sleep(0.5)
        os._exit(0)

    threading.Thread(target=watch, daemon=True).start()


class _Processes:
    """The standard library's process pool; a pool broken by a dead worker is replaced and the
    chunks in flight submitted again."""

    def __init__(self, workers):
        import concurrent.futures
        self._futures = concurrent.futures
        self.workers = workers
        self._pool = self._new_pool()

    def _new_pool(self):
        return self._futures.ProcessPoolExecutor(max_workers=self.workers, initializer=_exit_with_parent,
                                                 initargs=(os.getpid(),))

    def submit(self, function, *args):
        return self._pool.submit(function, *args)

    def wait_first(self, futures):
        done, _ = self._futures.wait(futures, return_when=self._futures.FIRST_COMPLETED)
        return done

    def broken(self, error):
        return isinstance(error, self._futures.process.BrokenProcessPool)

    def restart(self):
        self._pool.shutdown(wait=False, cancel_futures=True)
        self._pool = self._new_pool()

    def close(self):
        self._pool.shutdown()


class _Dask:
    """A Dask distributed client: of a LocalCluster of single-thread workers, or of the cluster a
    scheduler file or address names (dask reruns a dead worker's tasks elsewhere)."""

    def __init__(self, workers, scheduler_file=None, scheduler=None):
        import distributed
        self._distributed = distributed
        self._cluster = None
        if scheduler_file:
            self._client = distributed.Client(scheduler_file=scheduler_file)
        elif scheduler:
            self._client = distributed.Client(scheduler)
        else:
            self._cluster = distributed.LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                                                     dashboard_address=None)
            self._client = distributed.Client(self._cluster)
        self.workers = max(1, len(self._client.scheduler_info().get("workers", {})) or workers)

    def submit(self, function, *args):
        return self._client.submit(function, *args, pure=False)

    def wait_first(self, futures):
        done, _ = self._distributed.wait(list(futures), return_when="FIRST_COMPLETED")
        return set(done)

    def close(self):
        self._client.close()
        if self._cluster is not None:
            self._cluster.close()


def make_executor(kind="process", workers=None, scheduler_file=None, scheduler=None):
    workers = workers or os.cpu_count() or 1
    if kind == "serial":
        return _Serial()
    if kind == "process":
        return _Processes(workers)
    if kind == "dask":
        return _Dask(workers, scheduler_file, scheduler)
    raise ValueError(f"executor must be 'process', 'dask' or 'serial' (got {kind!r})")


# ---------------------------------------------------------------------------------------------
# Progress


class _Progress:
    """A bar on a terminal, plain lines every `every` seconds otherwise."""

    def __init__(self, total_chunks, done_chunks, chunk_size, total_cases, stream=None, every=10.0):
        stream = stream or sys.stderr
        self.total_chunks, self.done_chunks = total_chunks, done_chunks
        self.total_cases, self.chunk_size = total_cases, chunk_size
        self.start, self.new_chunks, self.stream, self.every = time.monotonic(), 0, stream, every
        self.terminal = hasattr(stream, "isatty") and stream.isatty()
        self.last = -float("inf")

    def chunk_done(self):
        self.done_chunks += 1
        self.new_chunks += 1
        self.show()

    def line(self):
        elapsed = time.monotonic() - self.start
        cases = min(self.done_chunks * self.chunk_size, self.total_cases)
        rate = self.new_chunks * self.chunk_size / elapsed if elapsed > 0 else 0.0
        left = (self.total_cases - cases) / rate if rate > 0 else float("nan")
        return (f"chunks {self.done_chunks}/{self.total_chunks}  cases {cases}/{self.total_cases}  "
                f"{rate:.1f} cases/s  {_duration(left)} left")

    def show(self, final=False):
        now = time.monotonic()
        if self.terminal:
            width = 30
            filled = int(width * self.done_chunks / max(1, self.total_chunks))
            self.stream.write("\r[" + "#" * filled + "." * (width - filled) + "] " + self.line() +
                              ("\n" if final else ""))
            self.stream.flush()
        elif final or now - self.last >= self.every:
            self.stream.write(self.line() + "\n")
            self.stream.flush()
            self.last = now


def _duration(seconds):
    if not np.isfinite(seconds):
        return "?"
    seconds = int(round(seconds))
    return f"{seconds // 3600}h{seconds // 60 % 60:02d}m{seconds % 60:02d}s" if seconds >= 3600 else \
        f"{seconds // 60}m{seconds % 60:02d}s"


# ---------------------------------------------------------------------------------------------
# Build, status, open, export


def build(spec, store, executor="process", workers=None, scheduler_file=None, scheduler=None, window=None,
          retry_failed=False, progress=True):
    """Builds (or resumes) the table of `spec` into the folder `store`. Returns the number of
    chunks written by this call. Failed chunks get a file in store/failures with the message;
    retry_failed submits them again."""
    canonical = spec if isinstance(spec, dict) and "fastnorm_version" in spec else canonical_spec(spec)
    _prepare_store(store, canonical)
    todo = missing_chunks(store, canonical, retry_failed)
    total_chunks = len(all_chunks(canonical))
    shown = _Progress(total_chunks, _count(store, SHARDS), canonical["chunk_size"],
                      int(np.prod(case_shape(canonical)))) if progress else None
    exit_after = [int(f.split("=")[1]) for f in _faults() if f.startswith("client-exit-after=")]
    text = spec_text(canonical)
    pool = make_executor(executor, workers, scheduler_file, scheduler) if isinstance(executor, str) else executor
    window = window or 4 * pool.workers
    written = 0
    try:
        queue = list(reversed(todo))
        in_flight = {}
        restarts = 0
        def start_again(chunk, error):
            """A process pool broken by a dead worker: a new pool, the chunks in flight again."""
            nonlocal restarts
            if not (isinstance(pool, _Processes) and pool.broken(error)) or restarts >= 3:
                return False
            restarts += 1
            queue.extend(in_flight.values())
            queue.append(chunk)
            in_flight.clear()
            pool.restart()
            return True

        while queue or in_flight:
            while queue and len(in_flight) < window:
                chunk = queue.pop()
                try:
                    in_flight[pool.submit(compute_chunk, text, *chunk)] = chunk
                except Exception as error:  # noqa: BLE001 - a broken pool refuses work at once
                    if not start_again(chunk, error):
                        raise
            for future in pool.wait_first(in_flight):
                chunk = in_flight.pop(future)
                try:
                    arrays = future.result()
                except Exception as error:  # noqa: BLE001 - recorded, the sweep goes on
                    if start_again(chunk, error):
                        break
                    _write_atomically(_failure_path(store, canonical, chunk),
                                      lambda file, e=error: file.write(f"{type(e).__name__}: {e}\n".encode()))
                    continue
                _write_atomically(_shard_path(store, canonical, chunk), lambda file, a=arrays: np.savez(file, **a))
                if os.path.exists(_failure_path(store, canonical, chunk)):
                    os.remove(_failure_path(store, canonical, chunk))
                written += 1
                if shown:
                    shown.chunk_done()
                if exit_after and written >= exit_after[0]:
                    os._exit(19)  # fault injection: the client dies with shards written
    finally:
        if isinstance(executor, str):
            pool.close()
    if shown:
        shown.show(final=True)
    return written


def _files(store, folder):
    """The shard or failure files of a store (not a partial write)."""
    return [os.path.join(store, folder, name) for name in os.listdir(os.path.join(store, folder))
            if not name.startswith(".")]


def _count(store, folder):
    return len(_files(store, folder))


def _cases_done(store, canonical):
    return sum(_cases_in(canonical, chunk) for chunk in all_chunks(canonical)
               if os.path.exists(_shard_path(store, canonical, chunk)))


def status(store, stream=None):
    """Prints how far a store is (it may be being built elsewhere): chunks and cases done of
    the total, failures, the rate over the shards' times and the time left at that rate."""
    stream = stream or sys.stdout
    canonical = read_spec(store)
    total_chunks = len(all_chunks(canonical))
    total_cases = int(np.prod(case_shape(canonical)))
    shards = _files(store, SHARDS)
    failed = _count(store, FAILURES)
    cases = _cases_done(store, canonical)
    times = sorted(os.path.getmtime(path) for path in shards)
    rate = (len(times) - 1) * canonical["chunk_size"] / (times[-1] - times[0]) if len(times) > 1 and \
        times[-1] > times[0] else float("nan")
    left = (total_cases - cases) / rate if np.isfinite(rate) and rate > 0 else float("nan")
    stream.write(f"store {store}: chunks {len(shards)}/{total_chunks}  cases {cases}/{total_cases}  "
                 f"failed chunks {failed}  {rate:.1f} cases/s  {_duration(left)} left\n")
    return {"chunks": len(shards), "total_chunks": total_chunks, "cases": cases, "total_cases": total_cases,
            "failed_chunks": failed}


def load_arrays(store):
    """The store's arrays over (pair, load, yaw, y[, wheel, patch]) and the done mask; cases of
    missing chunks are NaN (status 0)."""
    canonical = read_spec(store)
    shape = case_shape(canonical)
    total = int(np.prod(shape))
    per_pair = int(np.prod(shape[1:]))
    arrays = _empty_arrays(total, canonical)
    arrays["done"] = np.zeros(total, bool)
    size = canonical["chunk_size"]
    for chunk in all_chunks(canonical):
        path = _shard_path(store, canonical, chunk)
        if not os.path.exists(path):
            continue
        with np.load(path) as shard:
            first = chunk[0] * per_pair + chunk[1] * size
            rows = slice(first, first + len(shard["status"]))
            for name in shard.files:
                arrays[name][rows] = shard[name]
            arrays["done"][rows] = True
    return canonical, {name: array.reshape(shape + array.shape[1:]) for name, array in arrays.items()}


def open(store):  # noqa: A001 - fastnorm.tables.open, as xarray.open_dataset
    """The (possibly partial) table as an xarray.Dataset with CF units and a `done` mask."""
    import xarray as xr
    canonical, arrays = load_arrays(store)
    dims = ("pair", "load", "yaw", "y")
    patch_dims = dims + ("wheel", "patch")
    data = {
        "done": (dims, arrays["done"], {"long_name": "case computed", "units": "1"}),
        "status": (dims, arrays["status"], {
            "long_name": "equilibrium status", "units": "1",
            "flag_values": np.array(list(STATUS_CODES.values()), np.int8),
            "flag_meanings": " ".join(name.replace(" ", "_") for name in STATUS_CODES)}),
        "patch_count": (dims + ("wheel",), arrays["patch_count"], {"long_name": "contact patches", "units": "1"}),
    }
    for k, (name, unit, long_name, _) in enumerate(CASE_OUTPUTS):
        data[name] = (dims, arrays["case_values"][..., k], {"long_name": long_name, "units": unit})
    for k, (name, unit, long_name, _) in enumerate(PATCH_OUTPUTS):
        data[name] = (patch_dims, arrays["patch_values"][..., k], {"long_name": long_name, "units": unit})
    if "case_derivatives" in arrays:
        derivative = " measured along y by central differences (NaN: not measured)"
        per_metre = lambda unit: "m-1" if unit == "1" else f"{unit} m-1"  # noqa: E731
        for k, (name, unit, long_name, _) in enumerate(CASE_OUTPUTS):
            data[f"{name}_dy"] = (dims, arrays["case_derivatives"][..., k],
                                  {"long_name": f"d({long_name})/dy{derivative}", "units": per_metre(unit)})
        for k, (name, unit, long_name, _) in enumerate(PATCH_OUTPUTS):
            data[f"{name}_dy"] = (patch_dims, arrays["patch_derivatives"][..., k],
                                  {"long_name": f"d({long_name})/dy{derivative}", "units": per_metre(unit)})
    if "pressure" in arrays:
        data["pressure"] = (patch_dims + ("pressure_s", "pressure_x"), arrays["pressure"], {
            "long_name": "pressure resampled on the fixed patch grid about the contact reference point "
                         "(bilinear between element centres; NaN: no such patch)", "units": "Pa"})
    coords = {
        "pair": ("pair", [p["name"] for p in canonical["pairs"]], {"long_name": "wheel/rail profile pair",
                                                                  "units": "1"}),
        "load": ("load", canonical["load_n"], {"long_name": "vertical load on the wheelset", "units": "N"}),
        "yaw": ("yaw", canonical["yaw_rad"], {"long_name": "wheelset yaw angle", "units": "rad"}),
        "y": ("y", canonical["lateral_shift_m"], {"long_name": "wheelset lateral shift", "units": "m"}),
        "wheel": ("wheel", list(WHEELS), {"long_name": "wheel of the wheelset", "units": "1"}),
        "patch": ("patch", np.arange(PATCHES), {"long_name": "patch of the wheel, tread first", "units": "1"}),
    }
    if "pressure" in arrays:
        pressure_x, pressure_s = pressure_grid_axes(canonical["pressure_grid"])
        coords["pressure_x"] = ("pressure_x", pressure_x, {
            "long_name": "resampled pressure's cell centre along the rolling direction", "units": "m"})
        coords["pressure_s"] = ("pressure_s", pressure_s, {
            "long_name": "resampled pressure's cell centre across, in the tangent plane", "units": "m"})
    dataset = xr.Dataset(data, coords=coords)
    dataset.attrs.update({"title": "fastnorm contact table", "kind": canonical["kind"],
                          "fastnorm_version": canonical["fastnorm_version"], "solver": canonical["solver"],
                          "elements": canonical["elements"], "Conventions": "CF-1.8"})
    return dataset


def topology_codes(status_codes, patch_count):
    """The ContactTable topology of each case: 16 × left patches + right patches for a converged
    equilibrium, −status otherwise (docs/tables.md §4)."""
    codes = 16 * patch_count[..., 0].astype(np.int32) + patch_count[..., 1]
    return np.where(status_codes == STATUS_CODES["converged"], codes, -np.maximum(status_codes, 1).astype(np.int32))


def contact_table(store):
    """The store as a fastnorm.ContactTable: the case outputs, then per wheel and patch the patch
    outputs (name_left0 ...); a patch a case lacks reads 0 (its topology code says it is absent)."""
    canonical, arrays = load_arrays(store)
    names, units = zip(*_flat_outputs())
    shape = arrays["status"].shape
    patch_part = np.nan_to_num(arrays["patch_values"], nan=0.0).reshape(shape + (-1,))
    values = np.concatenate([arrays["case_values"], patch_part], axis=-1)
    topology = topology_codes(arrays["status"], arrays["patch_count"])
    topology = np.where(arrays["done"], topology, -127)
    values = np.where((topology >= 0)[..., None], values, np.nan)
    measured = None
    if "case_derivatives" in arrays:  # an absent patch's 0 has no measured slope: NaN, PCHIP's 0
        measured = np.concatenate([arrays["case_derivatives"], arrays["patch_derivatives"].reshape(shape + (-1,))],
                                  axis=-1)
    return ContactTable(lateral_shift_m=canonical["lateral_shift_m"], yaw_rad=canonical["yaw_rad"],
                        load_n=canonical["load_n"], pair_names=[p["name"] for p in canonical["pairs"]],
                        output_names=list(names), output_units=list(units), values=values, topology=topology,
                        measured_shift_derivatives=measured)


def export(store, out):
    """Writes the table: OUT ending .nc as netCDF-4 (compressed, chunked), .fntable as the binary
    file of fastnorm::ContactTable, anything else as a folder of text columns per pair and load."""
    if out.endswith(".nc"):
        dataset = open(store)
        encoding = {name: {"zlib": True, "complevel": 4} for name in dataset.data_vars}
        dataset.to_netcdf(out, engine="netcdf4", format="NETCDF4", encoding=encoding)
    elif out.endswith(".fntable"):
        contact_table(store).write(out)
    else:
        _export_text(store, out)


def _export_text(store, folder):
    canonical, arrays = load_arrays(store)
    os.makedirs(folder, exist_ok=True)
    columns = ["y_m", "yaw_rad", "status"] + [f"{name}_{unit.replace(' ', '.')}" for name, unit in _flat_outputs()]
    for p, pair in enumerate(canonical["pairs"]):
        for l, load in enumerate(canonical["load_n"]):
            safe = "".join(c if c.isalnum() or c in "-_." else "_" for c in pair["name"])
            path = os.path.join(folder, f"{safe}_load{load:g}N.txt")
            with builtins.open(path, "w", encoding="utf-8") as file:
                file.write("# fastnorm contact table " + pair["name"] + f", load {load:g} N; NaN: not computed "
                           "or no such patch\n# " + " ".join(columns) + "\n")
                for k, yaw in enumerate(canonical["yaw_rad"]):
                    for i, y in enumerate(canonical["lateral_shift_m"]):
                        row = [y, yaw, arrays["status"][p, l, k, i]] + list(arrays["case_values"][p, l, k, i]) + \
                              list(arrays["patch_values"][p, l, k, i].reshape(-1))
                        file.write(" ".join(repr(float(v)) for v in row) + "\n")


def main(argv=None):
    parser = argparse.ArgumentParser(prog="fastnorm-table", description=__doc__.split("\n\n")[0])
    commands = parser.add_subparsers(dest="command", required=True)
    make = commands.add_parser("build", help="build or resume a table into a store")
    make.add_argument("spec")
    make.add_argument("store")
    make.add_argument("--executor", default="process", choices=["process", "dask", "serial"])
    make.add_argument("--workers", type=int, default=None, help="processes, or LocalCluster workers (default: cores)")
    make.add_argument("--scheduler-file", default=None, help="dask: the cluster of this scheduler file (SLURM sites)")
    make.add_argument("--scheduler", default=None, help="dask: the scheduler's address (e.g. an SSH cluster's)")
    make.add_argument("--window", type=int, default=None, help="chunks in flight at most (default 4 x workers)")
    make.add_argument("--retry-failed", action="store_true", help="submit failed chunks again")
    show = commands.add_parser("status", help="how far a store is")
    show.add_argument("store")
    write = commands.add_parser("export", help="write a store as .nc, .fntable or a folder of text")
    write.add_argument("store")
    write.add_argument("out")
    args = parser.parse_args(argv)
    try:
        if args.command == "build":
            executor = "dask" if (args.scheduler_file or args.scheduler) else args.executor
            build(args.spec, args.store, executor=executor, workers=args.workers, scheduler_file=args.scheduler_file,
                  scheduler=args.scheduler, window=args.window, retry_failed=args.retry_failed)
            status(args.store)
        elif args.command == "status":
            status(args.store)
        else:
            export(args.store, args.out)
    except (ValueError, OSError) as error:
        print(f"fastnorm-table: {error}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
