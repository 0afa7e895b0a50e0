! fastnorm_c.f90: the C API of fastnorm (fastnorm_c.h) for Fortran 2003 and later, through
! iso_c_binding: every constant, struct and function of the header, with the header's names.
! Shipped with the C library (installed beside fastnorm_c.h); compile it with your code, it
! needs nothing but the library. Strings going in are C strings: append c_null_char.
! fastnorm_string turns a returned C string (last error, status name, version) into a
! Fortran one. Units are SI; arrays over a grid hold element k = i + mx*j, i along x.
module fastnorm_c
  use iso_c_binding
  implicit none

  ! Return codes.
  integer(c_int), parameter :: fastnorm_ok = 0, fastnorm_error_argument = 1, fastnorm_error_memory = 2, &
                               fastnorm_error_internal = 3, fastnorm_error_patch_failed = 4
  ! How a solve ended.
  integer(c_int), parameter :: fastnorm_not_solved = 0, fastnorm_converged = 1, fastnorm_no_contact = 2, &
                               fastnorm_iteration_limit = 3, fastnorm_cycled = 4, fastnorm_numerical_issue = 5, &
                               fastnorm_budget_reached = 6
  ! A patch's history against the previous evaluate.
  integer(c_int), parameter :: fastnorm_patch_continued = 0, fastnorm_patch_appeared = 1, &
                               fastnorm_patch_merged = 2, fastnorm_patch_split = 3
  ! How an evaluate ended.
  integer(c_int), parameter :: fastnorm_step_not_solved = 0, fastnorm_step_ok = 1, fastnorm_step_patch_failed = 2
  ! The fast tangential methods of the wheelset model.
  integer(c_int), parameter :: fastnorm_strip_theory = 0, fastnorm_fastsim = 1
  integer(c_int), parameter :: fastnorm_stop_largest_change = 0, fastnorm_stop_rms_change = 1
  ! How an equilibrium search ended.
  integer(c_int), parameter :: fastnorm_equilibrium_not_solved = 0, fastnorm_equilibrium_converged = 1, &
                               fastnorm_equilibrium_lost_contact = 2, fastnorm_equilibrium_not_converged = 3, &
                               fastnorm_equilibrium_solver_failed = 4, fastnorm_equilibrium_flange_climb = 5
  ! Contact tables: the interpolations, and what a lookup found.
  integer(c_int), parameter :: fastnorm_table_multilinear = 0, fastnorm_table_pchip = 1
  integer(c_int), parameter :: fastnorm_table_found = 0, fastnorm_table_out_of_range = 1, &
                               fastnorm_table_topology_change = 2, fastnorm_table_failed_case = 3

  type, bind(c) :: fastnorm_grid
    integer(c_int) :: mx, my
    real(c_double) :: dx, dy, x0, y0
  end type

  type, bind(c) :: fastnorm_material
    real(c_double) :: young_modulus_1, poisson_ratio_1, young_modulus_2, poisson_ratio_2
  end type

  type, bind(c) :: fastnorm_result
    integer(c_int) :: status, iterations, contact_count, at_edge
    real(c_double) :: normal_force, approach, residual
  end type

  type, bind(c) :: fastnorm_solver_options
    integer(c_int) :: max_iterations
    real(c_double) :: tolerance      ! CG only; 0: the default
    real(c_double) :: gap_tolerance  ! NORM and the reduced solvers only; 0: the default
  end type

  ! Creepages of the rail (body 1) against the wheel: xi, eta, phi (rad/m), spin centre (m).
  type, bind(c) :: fastnorm_creepage
    real(c_double) :: longitudinal, lateral, spin, spin_centre_x, spin_centre_y
  end type

  type, bind(c) :: fastnorm_tangential_result
    integer(c_int) :: status, sweeps, adhesion_elements, slip_elements
    real(c_double) :: force_x, force_y, spin_moment, frictional_power_per_speed, residual
  end type
  type, bind(c) :: fastnorm_tangential_options
    integer(c_int) :: stop        ! fastnorm_stop_largest_change (0, default) or fastnorm_stop_rms_change
    integer(c_int) :: max_sweeps  ! 0: the default
    real(c_double) :: tolerance   ! 0: the default
  end type

  type, bind(c) :: fastnorm_wheelset_options
    type(c_ptr) :: solver, wheel_profile, rail_profile  ! C strings (c_loc of a null-terminated string)
    real(c_double) :: nominal_radius, gauge, cant
    type(fastnorm_material) :: material
    integer(c_int) :: elements, stiffness, max_iterations
    real(c_double) :: distance_tolerance
    real(c_double) :: friction  ! mu of the creep forces of fastnorm_wheelset_evaluate_moving; 0: none
    integer(c_int) :: creep_method  ! FASTNORM_STRIP_THEORY (default) or FASTNORM_FASTSIM
    integer(c_int) :: distance_everywhere  ! 1: h on every element; 0 (default): where it can touch
    integer(c_int) :: warm_solve_iterations  ! cap of each warm patch solve; 0 (default): none
    real(c_double) :: tolerance, gap_tolerance  ! of each patch solve, as in fastnorm_solver_options
    real(c_double) :: distance_node_spacing  ! between the exact nodes of h along a row (m, default 3e-3)
  end type

  type, bind(c) :: fastnorm_pose
    real(c_double) :: y, z, roll, yaw
  end type

  type, bind(c) :: fastnorm_velocity
    real(c_double) :: forward, lateral, vertical, roll_rate, yaw_rate, pitch_rate
  end type

  type, bind(c) :: fastnorm_patch
    integer(c_int) :: status, at_edge, flange_climb, history, contact_elements
    type(fastnorm_grid) :: grid
    real(c_double) :: reference(3), e_x(3), t_s(3), normal(3), centre(3), pressure_centre(3)
    real(c_double) :: profile_y, normal_force, force(3), moment(3), contact_angle, approach, max_pressure, stiffness
    type(fastnorm_creepage) :: creepage          ! after fastnorm_wheelset_evaluate_moving
    type(fastnorm_tangential_result) :: creep    ! creep forces on the rail, patch frame
    real(c_double) :: creep_force(3)             ! on the wheel, track frame
  end type

  type, bind(c) :: fastnorm_step_status
    integer(c_int) :: code, wheel, patch, solver_status
  end type

  type, bind(c) :: fastnorm_equilibrium
    integer(c_int) :: status, iterations
    type(fastnorm_pose) :: pose
    real(c_double) :: vertical_force, lateral_force
    integer(c_int) :: patch_count(2)
  end type

  interface
    type(c_ptr) function fastnorm_last_error() bind(c)
      import :: c_ptr
    end function
    type(c_ptr) function fastnorm_status_name(status) bind(c)
      import :: c_ptr, c_int
      integer(c_int), value :: status
    end function
    type(c_ptr) function fastnorm_version() bind(c)
      import :: c_ptr
    end function

    integer(c_int) function fastnorm_solver_create(name, grid, material, options, solver) bind(c)
      import :: c_int, c_char, c_ptr, fastnorm_grid, fastnorm_material
      character(kind=c_char), intent(in) :: name(*)
      type(fastnorm_grid), intent(in) :: grid
      type(fastnorm_material), intent(in) :: material
      type(c_ptr), value :: options  ! c_loc of a fastnorm_solver_options, or c_null_ptr
      type(c_ptr), intent(out) :: solver
    end function
    subroutine fastnorm_solver_destroy(solver) bind(c)
      import :: c_ptr
      type(c_ptr), value :: solver
    end subroutine
    integer(c_int) function fastnorm_solve_approach(solver, h, pressure, result) bind(c)
      import :: c_int, c_ptr, c_double, fastnorm_result
      type(c_ptr), value :: solver
      real(c_double), intent(in) :: h(*)
      real(c_double), intent(out) :: pressure(*)
      type(fastnorm_result), intent(out) :: result
    end function
    integer(c_int) function fastnorm_solve_force(solver, h, normal_force, pressure, result) bind(c)
      import :: c_int, c_ptr, c_double, fastnorm_result
      type(c_ptr), value :: solver
      real(c_double), intent(in) :: h(*)
      real(c_double), value :: normal_force
      real(c_double), intent(out) :: pressure(*)
      type(fastnorm_result), intent(out) :: result
    end function
    integer(c_int) function fastnorm_solve_next(solver, h, normal_force, pressure, result) bind(c)
      import :: c_int, c_ptr, c_double, fastnorm_result
      type(c_ptr), value :: solver
      real(c_double), intent(in) :: h(*)
      real(c_double), value :: normal_force
      real(c_double), intent(out) :: pressure(*)
      type(fastnorm_result), intent(out) :: result
    end function
    integer(c_int) function fastnorm_normal_stiffness(solver, stiffness) bind(c)
      import :: c_int, c_ptr, c_double
      type(c_ptr), value :: solver
      real(c_double), intent(out) :: stiffness
    end function
    integer(c_int) function fastnorm_steady_rolling(grid, material, pressure, friction, creepage, rolling, &
                                                     options, traction_x, traction_y, result) bind(c)
      import :: c_int, c_double, c_ptr, fastnorm_grid, fastnorm_material, fastnorm_creepage, &
                fastnorm_tangential_result
      type(fastnorm_grid), intent(in) :: grid
      type(fastnorm_material), intent(in) :: material
      real(c_double), intent(in) :: pressure(*)
      real(c_double), value :: friction
      type(fastnorm_creepage), intent(in) :: creepage
      integer(c_int), value :: rolling
      type(c_ptr), value :: options  ! c_loc of a fastnorm_tangential_options, or c_null_ptr
      real(c_double), intent(out) :: traction_x(*), traction_y(*)
      type(fastnorm_tangential_result), intent(out) :: result
    end function

    integer(c_int) function fastnorm_case_read(path, problem) bind(c)
      import :: c_int, c_char, c_ptr
      character(kind=c_char), intent(in) :: path(*)
      type(c_ptr), intent(out) :: problem
    end function
    subroutine fastnorm_case_destroy(problem) bind(c)
      import :: c_ptr
      type(c_ptr), value :: problem
    end subroutine
    integer(c_int) function fastnorm_case_info(problem, grid, material, force_control, control_value) bind(c)
      import :: c_int, c_ptr, c_double, fastnorm_grid, fastnorm_material
      type(c_ptr), value :: problem
      type(fastnorm_grid), intent(out) :: grid
      type(fastnorm_material), intent(out) :: material
      integer(c_int), intent(out) :: force_control
      real(c_double), intent(out) :: control_value
    end function
    integer(c_int) function fastnorm_case_undeformed_distance(problem, h) bind(c)
      import :: c_int, c_ptr, c_double
      type(c_ptr), value :: problem
      real(c_double), intent(out) :: h(*)
    end function
    integer(c_int) function fastnorm_case_result(problem, pressure, result) bind(c)
      import :: c_int, c_ptr, c_double, fastnorm_result
      type(c_ptr), value :: problem
      real(c_double), intent(out) :: pressure(*)
      type(fastnorm_result), intent(out) :: result
    end function
    integer(c_int) function fastnorm_case_rolling(problem, friction, creepage, rolling) bind(c)
      import :: c_int, c_ptr, c_double, fastnorm_creepage
      type(c_ptr), value :: problem
      real(c_double), intent(out) :: friction
      type(fastnorm_creepage), intent(out) :: creepage
      integer(c_int), intent(out) :: rolling
    end function
    integer(c_int) function fastnorm_case_write(path, name, grid, material, force_control, control_value, h, &
                                                pressure, result) bind(c)
      import :: c_int, c_char, c_ptr, c_double, fastnorm_grid, fastnorm_material
      character(kind=c_char), intent(in) :: path(*), name(*)
      type(fastnorm_grid), intent(in) :: grid
      type(fastnorm_material), intent(in) :: material
      integer(c_int), value :: force_control
      real(c_double), value :: control_value
      real(c_double), intent(in) :: h(*)
      type(c_ptr), value :: pressure, result  ! both c_null_ptr, or c_loc of the pressures and a fastnorm_result
    end function

    subroutine fastnorm_wheelset_options_default(options) bind(c)
      import :: fastnorm_wheelset_options
      type(fastnorm_wheelset_options), intent(out) :: options
    end subroutine
    integer(c_int) function fastnorm_wheelset_create(options, model) bind(c)
      import :: c_int, c_ptr, fastnorm_wheelset_options
      type(fastnorm_wheelset_options), intent(in) :: options
      type(c_ptr), intent(out) :: model
    end function
    subroutine fastnorm_wheelset_destroy(model) bind(c)
      import :: c_ptr
      type(c_ptr), value :: model
    end subroutine
    integer(c_int) function fastnorm_wheelset_copy(model, copy) bind(c)
      import :: c_int, c_ptr
      type(c_ptr), value :: model
      type(c_ptr), intent(out) :: copy
    end function
    integer(c_int) function fastnorm_wheelset_evaluate(model, pose, force, moment) bind(c)
      import :: c_int, c_ptr, c_double, fastnorm_pose
      type(c_ptr), value :: model
      type(fastnorm_pose), intent(in) :: pose
      real(c_double), intent(out) :: force(3), moment(3)
    end function
    integer(c_int) function fastnorm_wheelset_evaluate_moving(model, pose, velocity, force, moment) bind(c)
      import :: c_int, c_ptr, c_double, fastnorm_pose, fastnorm_velocity
      type(c_ptr), value :: model
      type(fastnorm_pose), intent(in) :: pose
      type(fastnorm_velocity), intent(in) :: velocity
      real(c_double), intent(out) :: force(3), moment(3)
    end function
    integer(c_int) function fastnorm_wheelset_step_status(model, status) bind(c)
      import :: c_int, c_ptr, fastnorm_step_status
      type(c_ptr), value :: model
      type(fastnorm_step_status), intent(out) :: status
    end function
    integer(c_int) function fastnorm_wheelset_set_iteration_budget(model, iterations) bind(c)
      import :: c_int, c_ptr
      type(c_ptr), value :: model
      integer(c_int), value :: iterations
    end function
    integer(c_int) function fastnorm_wheelset_iterations(model, iterations) bind(c)
      import :: c_int, c_ptr
      type(c_ptr), value :: model
      integer(c_int), intent(out) :: iterations
    end function
    integer(c_int) function fastnorm_wheelset_reset(model) bind(c)
      import :: c_int, c_ptr
      type(c_ptr), value :: model
    end function
    integer(c_int) function fastnorm_wheelset_save_history(model) bind(c)
      import :: c_int, c_ptr
      type(c_ptr), value :: model
    end function
    integer(c_int) function fastnorm_wheelset_restore_history(model) bind(c)
      import :: c_int, c_ptr
      type(c_ptr), value :: model
    end function
    integer(c_int) function fastnorm_wheelset_patch_count(model, wheel, count) bind(c)
      import :: c_int, c_ptr
      type(c_ptr), value :: model
      integer(c_int), value :: wheel
      integer(c_int), intent(out) :: count
    end function
    integer(c_int) function fastnorm_wheelset_patch(model, wheel, patch, out) bind(c)
      import :: c_int, c_ptr, fastnorm_patch
      type(c_ptr), value :: model
      integer(c_int), value :: wheel, patch
      type(fastnorm_patch), intent(out) :: out
    end function
    integer(c_int) function fastnorm_wheelset_patch_pressure(model, wheel, patch, pressure) bind(c)
      import :: c_int, c_ptr, c_double
      type(c_ptr), value :: model
      integer(c_int), value :: wheel, patch
      real(c_double), intent(out) :: pressure(*)
    end function
    integer(c_int) function fastnorm_wheelset_patch_traction(model, wheel, patch, traction_x, traction_s) bind(c)
      import :: c_int, c_ptr, c_double
      type(c_ptr), value :: model
      integer(c_int), value :: wheel, patch
      real(c_double), intent(out) :: traction_x(*), traction_s(*)
    end function
    integer(c_int) function fastnorm_wheelset_equilibrium(model, load, y, yaw, result) bind(c)
      import :: c_int, c_ptr, c_double, fastnorm_equilibrium
      type(c_ptr), value :: model
      real(c_double), value :: load, y, yaw
      type(fastnorm_equilibrium), intent(out) :: result
    end function

    integer(c_int) function fastnorm_table_read(path, table) bind(c)
      import :: c_int, c_char, c_ptr
      character(kind=c_char), intent(in) :: path(*)
      type(c_ptr), intent(out) :: table
    end function
    subroutine fastnorm_table_destroy(table) bind(c)
      import :: c_ptr
      type(c_ptr), value :: table
    end subroutine
    integer(c_int) function fastnorm_table_info(table, pairs, outputs) bind(c)
      import :: c_int, c_ptr
      type(c_ptr), value :: table
      integer(c_int), intent(out) :: pairs, outputs
    end function
    integer(c_int) function fastnorm_table_output_index(table, name, index) bind(c)
      import :: c_int, c_char, c_ptr
      type(c_ptr), value :: table
      character(kind=c_char), intent(in) :: name(*)
      integer(c_int), intent(out) :: index
    end function
    ! name and unit: C strings owned by the table (fastnorm_string reads them).
    integer(c_int) function fastnorm_table_output_name(table, index, name, unit) bind(c)
      import :: c_int, c_ptr
      type(c_ptr), value :: table
      integer(c_int), value :: index
      type(c_ptr), intent(out) :: name, unit
    end function
    integer(c_int) function fastnorm_table_lookup(table, pair, y, yaw, load, interpolation, out, found) bind(c)
      import :: c_int, c_ptr, c_double
      type(c_ptr), value :: table
      integer(c_int), value :: pair
      real(c_double), value :: y, yaw, load
      integer(c_int), value :: interpolation
      real(c_double), intent(inout) :: out(*)
      integer(c_int), intent(out) :: found
    end function

    pure integer(c_size_t) function c_strlen(text) bind(c, name="strlen")
      import :: c_ptr, c_size_t
      type(c_ptr), value :: text
    end function
  end interface

contains

  ! A C string returned by the library (fastnorm_last_error(), ...) as a Fortran string.
  function fastnorm_string(text) result(value)
    type(c_ptr), intent(in) :: text
    character(len=:), allocatable :: value
    character(kind=c_char), pointer :: characters(:)
    integer :: n
    if (.not. c_associated(text)) then
      value = ""
      return
    end if
    n = int(c_strlen(text))
    call c_f_pointer(text, characters, [n])
    allocate(character(len=n) :: value)
    value = transfer(characters(1:n), value)
  end function

end module fastnorm_c
