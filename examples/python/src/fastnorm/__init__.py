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
