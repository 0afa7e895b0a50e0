"""Plots of a contact patch with matplotlib: what a researcher looks at first.

pressure_map draws pressures with the true aspect ratio dx : dy, axes in mm along the
rolling direction x and the lateral y, and a colour bar in MPa. compare sets a reduced
solver's answer beside NORM's: both maps with NORM's contact outline over the reduced one,
the centre-strip pressure profiles, and the difference. traction_map draws a tangential
answer: the adhesion and slip areas and the traction vectors on the rail. table_slices draws
a contact table (fastnorm.tables.open) against the lateral shift, one line per yaw. Figures are made
without pyplot
(matplotlib.figure.Figure), so they work headless and in threads; save them with
figure.savefig(path) or give path=.
"""

import numpy as np
from matplotlib.figure import Figure
from matplotlib.lines import Line2D

__all__ = ["centre_strip", "compare", "contact_outline", "extent_mm", "pressure_map", "table_slices", "traction_map"]


def extent_mm(grid):
    """(left, right, bottom, top) of the grid's elements in mm, for imshow's extent."""
    x_left = (grid.x0_m - grid.dx_m / 2) * 1e3
    y_bottom = (grid.y0_m - grid.dy_m / 2) * 1e3
    return (x_left, x_left + grid.mx * grid.dx_m * 1e3, y_bottom, y_bottom + grid.my * grid.dy_m * 1e3)


def _centres_mm(grid):
    x = (grid.x0_m + grid.dx_m * np.arange(grid.mx)) * 1e3
    y = (grid.y0_m + grid.dy_m * np.arange(grid.my)) * 1e3
    return x, y


def _checked(grid, values, name):
    values = np.asarray(values)
    if values.shape != (grid.my, grid.mx):
        raise ValueError(f"{name} must have shape (my, mx) = ({grid.my}, {grid.mx}) of its grid, not {values.shape}")
    return values


def _axes(ax):
    if ax is not None:
        return ax
    return Figure(layout="constrained").add_subplot()


def pressure_map(grid, pressure_pa, ax=None, title=None, colorbar=True, **imshow_options):
    """Draws pressures (Pa, shape (my, mx)) on their grid in MPa; returns the Axes.

    Without ax a new Figure is made (ax.figure). imshow_options go to Axes.imshow.
    """
    pressure = _checked(grid, pressure_pa, "pressure_pa")
    ax = _axes(ax)
    options = {"cmap": "viridis", "interpolation": "nearest", "vmin": 0.0}
    options.update(imshow_options)
    image = ax.imshow(pressure / 1e6, origin="lower", extent=extent_mm(grid), aspect="equal", **options)
    ax.set_xlabel("x, rolling direction (mm)")
    ax.set_ylabel("y, lateral (mm)")
    if title:
        ax.set_title(title)
    if colorbar:
        ax.figure.colorbar(image, ax=ax, label="pressure (MPa)")
    return ax


def contact_outline(ax, grid, in_contact, label=None, **line_options):
    """Draws the boundary of a contact set (bool, shape (my, mx)) on ax; returns a legend handle."""
    contact = _checked(grid, in_contact, "in_contact").astype(float)
    style = {"colors": "white", "linewidths": 1.2}
    style.update(line_options)
    if contact.any() and not contact.all():
        x, y = _centres_mm(grid)
        ax.contour(x, y, contact, levels=[0.5], **style)
    colour = style["colors"]
    return Line2D([], [], color=colour if isinstance(colour, str) else colour[0],
                  linestyle=style.get("linestyles", "solid"), label=label)


def centre_strip(grid, pressure_pa):
    """The index j of the strip (row) that carries the most force: the centre strip of a patch."""
    return int(np.argmax(_checked(grid, pressure_pa, "pressure_pa").sum(axis=1)))


def compare(grid, reference, reduced, reference_name="NORM", reduced_name="reduced", path=None):
    """A reduced solver's answer against the reference (NORM) on the same grid; returns the Figure.

    reference, reduced: Solutions (pressure_pa and in_contact of shape (my, mx)). Panels:
    the reference map; the reduced map with the reference's contact outline (dashed) over
    its own; the pressure along x on the centre strip (the strip carrying the most of the
    reference's force) for both; the difference reduced - reference. Saved to path if given.
    """
    reference_pressure = _checked(grid, reference.pressure_pa, "reference.pressure_pa")
    reduced_pressure = _checked(grid, reduced.pressure_pa, "reduced.pressure_pa")
    figure = Figure(figsize=(12, 8), layout="constrained")
    (map_reference, map_reduced), (profile, difference_map) = figure.subplots(2, 2)
    peak = max(reference_pressure.max(), reduced_pressure.max()) / 1e6
    pressure_map(grid, reference_pressure, ax=map_reference, title=f"{reference_name}", vmax=peak)
    pressure_map(grid, reduced_pressure, ax=map_reduced, title=f"{reduced_name}, {reference_name} outline dashed",
                 vmax=peak)
    own = contact_outline(map_reduced, grid, reduced.in_contact, label=reduced_name)
    theirs = contact_outline(map_reduced, grid, reference.in_contact, label=reference_name, colors="red",
                             linestyles="dashed")
    map_reduced.legend(handles=[own, theirs], loc="upper right", fontsize="small")

    strip = centre_strip(grid, reference_pressure)
    x, y = _centres_mm(grid)
    profile.plot(x, reference_pressure[strip] / 1e6, "o-", markersize=3, label=reference_name)
    profile.plot(x, reduced_pressure[strip] / 1e6, "s--", markersize=3, label=reduced_name)
    profile.set_xlabel("x, rolling direction (mm)")
    profile.set_ylabel("pressure (MPa)")
    profile.set_title(f"centre strip, y = {y[strip]:.3g} mm")
    profile.legend()
    profile.grid(True, alpha=0.3)

    difference = (reduced_pressure - reference_pressure) / 1e6
    bound = max(float(np.abs(difference).max()), 1e-12)
    image = difference_map.imshow(difference, origin="lower", extent=extent_mm(grid), aspect="equal",
                                  cmap="RdBu_r", vmin=-bound, vmax=bound, interpolation="nearest")
    difference_map.set_xlabel("x, rolling direction (mm)")
    difference_map.set_ylabel("y, lateral (mm)")
    difference_map.set_title(f"{reduced_name} - {reference_name}")
    figure.colorbar(image, ax=difference_map, label="pressure difference (MPa)")
    if path is not None:
        figure.savefig(path)
    return figure


def traction_map(grid, tangential, ax=None, title=None, every=1, path=None):
    """Draws a tangential answer on its grid; returns the Axes.

    tangential: a TangentialSolution (solve_steady_rolling's, or a wheelset Patch.traction).
    The adhesion area light, the slip area dark (its state, 1 adhesion and 2 slip, as the
    image), and an arrow for the traction on the rail at every `every`-th element of each
    row and column in contact, in MPa with one scale for all (its key in the corner).
    Without ax a new Figure is made; saved to path if given.
    """
    state = _checked(grid, tangential.state, "tangential.state").astype(float)
    traction_x = _checked(grid, tangential.traction_x_pa, "tangential.traction_x_pa") / 1e6
    traction_y = _checked(grid, tangential.traction_y_pa, "tangential.traction_y_pa") / 1e6
    if int(every) < 1:
        raise ValueError(f"every must be a positive whole number, not {every}")
    every = int(every)
    ax = _axes(ax)
    shown = np.ma.masked_equal(state, 0.0)  # exterior left blank
    ax.imshow(shown, origin="lower", extent=extent_mm(grid), aspect="equal", cmap="Paired", vmin=0.5, vmax=2.5,
              interpolation="nearest")
    x, y = _centres_mm(grid)
    xx, yy = np.meshgrid(x, y)
    picked = np.zeros_like(state, dtype=bool)
    picked[::every, ::every] = True
    picked &= state > 0
    arrows = ax.quiver(xx[picked], yy[picked], traction_x[picked], traction_y[picked], angles="xy", color="black",
                       width=0.003)
    peak = float(np.hypot(traction_x, traction_y).max())
    if peak > 0:
        ax.quiverkey(arrows, 0.85, 1.02, peak, f"{peak:.3g} MPa", labelpos="E")
    ax.set_xlabel("x, rolling direction (mm)")
    ax.set_ylabel("y, lateral (mm)")
    adhesion = Line2D([], [], color=ax.images[-1].cmap(ax.images[-1].norm(1.0)), linewidth=6, label="adhesion")
    slip = Line2D([], [], color=ax.images[-1].cmap(ax.images[-1].norm(2.0)), linewidth=6, label="slip")
    ax.legend(handles=[adhesion, slip], loc="lower right", fontsize="small")
    if title:
        ax.set_title(title)
    if path is not None:
        ax.figure.savefig(path)
    return ax


def table_slices(dataset, pair=0, load=0, wheel="left", path=None):
    """A contact table's slices for one pair, load and wheel against the lateral shift, one line
    per yaw: the normal force, the contact angle and the largest pressure of each patch (tread
    solid, flange dashed; cases not computed or not converged left out). dataset: what
    fastnorm.tables.open returns; pair and load by position. Returns the Figure."""
    view = dataset.isel(pair=pair, load=load).sel(wheel=wheel)
    usable = (view["done"] & (view["status"] == 1)).values
    y_mm = view["y"].values * 1e3
    figure = Figure(figsize=(8, 9), layout="constrained")
    panels = figure.subplots(3, 1, sharex=True)
    quantities = (("normal_force", 1e-3, "normal force (kN)"), ("contact_angle", 1.0, "contact angle (rad)"),
                  ("max_pressure", 1e-6, "largest pressure (MPa)"))
    colours = [f"C{k}" for k in range(view.sizes["yaw"])]
    for ax, (name, scale, label) in zip(panels, quantities):
        for k, yaw in enumerate(view["yaw"].values):
            for patch, style in ((0, "-"), (1, "--")):
                values = np.where(usable[k], view[name].isel(yaw=k, patch=patch).values * scale, np.nan)
                ax.plot(y_mm, values, style, color=colours[k],
                        label=f"yaw {yaw * 1e3:g} mrad" if patch == 0 else None)
        ax.set_ylabel(label)
        ax.grid(True, alpha=0.3)
    panels[0].legend(fontsize="small")
    panels[0].set_title(f"{view['pair'].item()}, load {view['load'].item() / 1e3:g} kN, {wheel} wheel "
                        "(tread solid, flange dashed)")
    panels[-1].set_xlabel("wheelset lateral shift y (mm)")
    if path is not None:
        figure.savefig(path)
    return figure
