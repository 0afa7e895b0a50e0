"""fastnorm: the normal contact problem between wheel and rail.

Kalker's NORM, a conjugate-gradient solver and the reduced strip-basis solvers of
Giner-Navarro et al. (Wear 2023) on a regular grid; .case files; the wheelset contact model
of the time loop (with creep forces when given a Velocity) and the static equilibrium of a
loaded wheelset (S1002 on UIC60 by default); steady rolling with friction.

Units are SI and named in the keywords: m, Pa, N, rad. Arrays over a grid have shape
(my, mx): row j is strip j, along the rolling direction x. Bad input raises FastnormError,
a ValueError whose message names the argument. fastnorm.plot draws pressure maps.

    import fastnorm
    case = fastnorm.read_case("hertz_sphere_30x30.case")
    solution = fastnorm.solve_case(case, solver="elliptic")
    print(solution.status, solution.normal_force_n, solution.pressure_pa.shape)
"""

from ._fastnorm import (
    Case,
    CaseResult,
    CaseRolling,
    ContactTable,
    Equilibrium,
    FastnormError,
    Grid,
    Material,
    Patch,
    Pose,
    Solution,
    Solver,
    StepStatus,
    TangentialSolution,
    Velocity,
    Wheel,
    WheelsetContact,
    WheelsetResult,
    __version__,
    read_case,
    solve_steady_rolling,
    write_case,
)

__all__ = [
    "Case",
    "CaseResult",
    "CaseRolling",
    "ContactTable",
    "Equilibrium",
    "FastnormError",
    "Grid",
    "Material",
    "Patch",
    "Pose",
    "Solution",
    "Solver",
    "StepStatus",
    "TangentialSolution",
    "Velocity",
    "Wheel",
    "WheelsetContact",
    "WheelsetResult",
    "__version__",
    "read_case",
    "roll_case",
    "solve_case",
    "solve_steady_rolling",
    "write_case",
]


def solve_case(case, solver="norm", **options):
    """Solves a Case as its control line says (force or approach) with the named solver.

    options go to Solver (max_iterations, tolerance). Returns the Solution.
    """
    return Solver(solver, case.grid, case.material, **options).solve(
        case.undeformed_distance_m, normal_force_n=case.normal_force_n
    )


def roll_case(case, normal):
    """Steady rolling of a Case's tangential line (case.rolling) on its normal Solution `normal`.

    What fastnorm-solve does with such a case: the exact path, the creepages about the line's
    spin centre, its rolling direction. Returns the TangentialSolution.
    """
    rolling = case.rolling
    if rolling is None:
        raise ValueError("case.rolling is None: the case has no tangential line")
    return solve_steady_rolling(case.grid, case.material, normal, friction=rolling.friction,
                                creepage_x=rolling.creepage_x, creepage_y=rolling.creepage_y,
                                spin_per_m=rolling.spin_per_m, spin_centre_x_m=rolling.spin_centre_x_m,
                                spin_centre_y_m=rolling.spin_centre_y_m, rolling=rolling.rolling)
