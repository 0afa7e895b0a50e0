"""The plotting helpers write figures with the true aspect ratio and labelled axes."""

import numpy as np
import pytest

import fastnorm
import fastnorm.plot


def test_compare_writes_the_four_panels(peer_cases, output_dir):
    case = fastnorm.read_case(str(peer_cases / "wr_y3.0_psi0.0_right.case"))
    norm = fastnorm.solve_case(case)
    elliptic = fastnorm.solve_case(case, solver="elliptic")
    path = output_dir / "compare_wr_y3_right.png"
    if path.exists():
        path.unlink()
    figure = fastnorm.plot.compare(case.grid, norm, elliptic, reduced_name="elliptic", path=str(path))
    assert path.stat().st_size > 10_000
    reference_map, reduced_map, profile, difference = figure.axes[:4]
    for ax in (reference_map, reduced_map, difference):
        assert ax.get_aspect() == 1.0  # data units are mm on both axes: dx : dy as it is
        assert ax.get_xlabel() == "x, rolling direction (mm)"
        assert ax.get_ylabel() == "y, lateral (mm)"
    assert profile.get_ylabel() == "pressure (MPa)"
    # The profile shows the centre strip of both answers.
    strip = fastnorm.plot.centre_strip(case.grid, norm.pressure_pa)
    drawn = [line.get_ydata() for line in profile.get_lines()]
    assert np.array_equal(drawn[0], norm.pressure_pa[strip] / 1e6)
    assert np.array_equal(drawn[1], elliptic.pressure_pa[strip] / 1e6)
    colour_bars = [ax.get_ylabel() for ax in figure.axes[4:]]
    assert "pressure (MPa)" in colour_bars and "pressure difference (MPa)" in colour_bars


def test_pressure_map_of_a_wheelset_patch(output_dir):
    model = fastnorm.WheelsetContact(solver="elliptic", elements=30)
    patch = model.evaluate(lateral_shift_m=2e-3, vertical_m=0.1e-3).wheels[1].patches[0]
    ax = fastnorm.plot.pressure_map(patch.grid, patch.solution.pressure_pa, title="right wheel")
    path = output_dir / "patch_right.png"
    ax.figure.savefig(path)
    assert path.stat().st_size > 5_000
    left, right, bottom, top = fastnorm.plot.extent_mm(patch.grid)
    assert right - left == pytest.approx(patch.grid.mx * patch.grid.dx_m * 1e3)
    assert top - bottom == pytest.approx(patch.grid.my * patch.grid.dy_m * 1e3)
    image = ax.get_images()[0]
    assert np.array_equal(image.get_array(), patch.solution.pressure_pa / 1e6)


def test_a_map_of_the_wrong_shape_is_refused():
    grid = fastnorm.Grid(4, 3, 1e-3, 1e-3)
    with pytest.raises(ValueError, match="pressure_pa must have shape"):
        fastnorm.plot.pressure_map(grid, np.zeros((4, 3)))


def test_traction_map_of_a_rolling_wheelset_patch(output_dir):
    model = fastnorm.WheelsetContact(solver="elliptic", elements=30, friction=0.3)
    velocity = fastnorm.Velocity(forward_m_per_s=30.0, pitch_rate_rad_per_s=-30.0 / 0.45, lateral_m_per_s=0.05)
    patch = model.evaluate(lateral_shift_m=2e-3, vertical_m=0.1e-3, velocity=velocity).wheels[1].patches[0]
    traction = patch.traction
    path = output_dir / "traction_right.png"
    if path.exists():
        path.unlink()
    ax = fastnorm.plot.traction_map(patch.grid, traction, title="right wheel", every=2, path=str(path))
    assert path.stat().st_size > 5_000
    assert ax.get_aspect() == 1.0
    # The areas as the image (exterior masked), an arrow per picked element in contact.
    image = ax.get_images()[0]
    assert np.array_equal(image.get_array().filled(0), traction.state.astype(float))
    arrows = ax.collections[0]
    picked = np.zeros(traction.state.shape, dtype=bool)
    picked[::2, ::2] = True
    picked &= traction.state > 0
    assert len(arrows.U) == picked.sum() > 0
    assert np.allclose(arrows.U, traction.traction_x_pa[picked] / 1e6)
    assert np.allclose(arrows.V, traction.traction_y_pa[picked] / 1e6)
    with pytest.raises(ValueError, match="every"):
        fastnorm.plot.traction_map(patch.grid, traction, every=0)
