! A multibody code's wheel-rail contact, written the way its user routines are: Fortran,
! calling fastnorm's C API through the module fastnorm_c (fastnorm_c.f90, shipped with the
! C library; docs/bindings.md). The program finds the
! static equilibrium of a wheelset under 200 kN at y = 3 mm, then steps it through a small
! lateral oscillation at 30 m/s calling the user routine at every step, as an integrator
! would (contact and creep forces); and the creep forces of CONTACT's large-spin Hertz
! example by steady rolling.
! Run as a CTest test: it stops with an error when a call fails or a force is implausible.
module wheel_rail_contact
  use fastnorm_c
  implicit none
  type(c_ptr), save :: model = c_null_ptr
  character(kind=c_char, len=9), target, save :: solver_name = "elliptic" // c_null_char

contains

  ! Created once, at the first call of the user routine, and kept between steps.
  subroutine ensure_model()
    type(fastnorm_wheelset_options) :: options
    if (c_associated(model)) return
    call fastnorm_wheelset_options_default(options)
    options%solver = c_loc(solver_name)
    options%elements = 30
    options%friction = 0.3d0
    if (fastnorm_wheelset_create(options, model) /= fastnorm_ok) error stop "create: " // fastnorm_string(fastnorm_last_error())
  end subroutine

  ! The user routine: the contact force (N) and moment (N m) on the wheelset at its pose
  ! (m, rad; track frame, z down) moving forwards at 30 m/s, rolling, with lateral velocity
  ! vy (m/s): normal and creep forces.
  subroutine contact_user_routine(y, z, roll, yaw, vy, force, moment)
    real(c_double), intent(in) :: y, z, roll, yaw, vy
    real(c_double), intent(out) :: force(3), moment(3)
    call ensure_model()
    if (fastnorm_wheelset_evaluate_moving(model, fastnorm_pose(y, z, roll, yaw), &
                                          fastnorm_velocity(30d0, vy, 0d0, 0d0, 0d0, -30d0 / 0.45d0), force, &
                                          moment) /= fastnorm_ok) then
      error stop "evaluate: " // fastnorm_string(fastnorm_last_error())
    end if
  end subroutine

end module wheel_rail_contact

program user_routine
  use wheel_rail_contact
  implicit none
  real(c_double), parameter :: load = 2.0d5, y0 = 3.0d-3
  type(fastnorm_equilibrium) :: found
  real(c_double) :: force(3), moment(3), y
  type(fastnorm_patch) :: patch
  integer :: step

  call ensure_model()
  if (fastnorm_wheelset_equilibrium(model, load, y0, 0.0d0, found) /= fastnorm_ok) then
    error stop "equilibrium: " // fastnorm_string(fastnorm_last_error())
  end if
  if (found%status /= fastnorm_equilibrium_converged) error stop "equilibrium did not converge"
  print '(a, es12.5, a, es12.5, a, es12.5, a)', "equilibrium: z = ", found%pose%z, " m, roll = ", &
    found%pose%roll, " rad, vertical force ", found%vertical_force, " N"

  ! The equilibrium is the model's own: at its pose the rails carry the load.
  if (fastnorm_wheelset_evaluate(model, found%pose, force, moment) /= fastnorm_ok) error stop "evaluate"
  if (abs(-force(3) / load - 1) > 1.0d-6) error stop "vertical force at the equilibrium is off"
  do step = 0, 20
    y = y0 + 0.5d-3 * sin(0.3d0 * step)
    call contact_user_routine(y, found%pose%z, found%pose%roll, 0.0d0, 0.15d0 * cos(0.3d0 * step), force, moment)
    if (.not. (force(3) < 0 .and. abs(force(3)) < 10 * load)) error stop "implausible vertical force"
    if (fastnorm_wheelset_patch(model, 1_c_int, 0_c_int, patch) /= fastnorm_ok) error stop "patch"
    if (patch%creep%status /= fastnorm_converged) error stop "no creep forces"
    if (hypot(patch%creep%force_x, patch%creep%force_y) > 0.3d0 * patch%normal_force * (1 + 1d-12)) &
      error stop "creep force above mu Fn"
    print '(a, i3, a, f7.4, a, es12.5, a, es12.5, a, es12.5, a)', "step ", step, ": y = ", 1d3 * y, " mm, Fy = ", &
      force(2), " N, Fz = ", force(3), " N, right Fs = ", patch%creep%force_y, " N"
  end do
  call fastnorm_wheelset_destroy(model)
  call creep_forces_of_a_hertz_contact()
  call table_lookup()

contains

  ! A contact table written here from docs/tables.md's description of the file (stream
  ! access), read and looked up through the API: y = (-1, 0, 2) mm, yaw = (0, 10) mrad, one
  ! load, one output fn = 1000 + 2e5 y + 3e3 yaw (N), which both interpolations give back.
  subroutine table_lookup()
    real(c_double), parameter :: shifts(3) = [-1d-3, 0d0, 2d-3], yaws(2) = [0d0, 1d-2], table_load = 1d5
    character(kind=c_char, len=*), parameter :: path = "user_routine_test.fntable" // c_null_char
    character(kind=c_char, len=*), parameter :: fn_name = "fn_n" // c_null_char
    type(c_ptr) :: table, name, unit
    real(c_double) :: out(1)
    integer(c_int) :: pairs, outputs, index, found, interpolation
    integer :: file, i, j
    open(newunit=file, file=path(1:len(path) - 1), access="stream", form="unformatted", status="replace")
    write(file) "FNTABLE" // c_null_char
    write(file) 1_c_int32_t, 1_c_int32_t, 3_c_int32_t, 2_c_int32_t, 1_c_int32_t, 1_c_int32_t
    write(file) shifts, yaws, table_load
    write(file) 11_c_int32_t, "S1002/UIC60", 4_c_int32_t, "fn_n", 1_c_int32_t, "N"
    write(file) ((1000 + 2d5 * shifts(i) + 3d3 * yaws(j), i = 1, 3), j = 1, 2)
    write(file) (1_c_int32_t, i = 1, 6)
    close(file)

    if (fastnorm_table_read(path, table) /= fastnorm_ok) error stop "table: " // fastnorm_string(fastnorm_last_error())
    if (fastnorm_table_info(table, pairs, outputs) /= fastnorm_ok .or. pairs /= 1 .or. outputs /= 1) &
      error stop "table info"
    if (fastnorm_table_output_index(table, fn_name, index) /= fastnorm_ok .or. index /= 0) error stop "output index"
    if (fastnorm_table_output_name(table, 0_c_int, name, unit) /= fastnorm_ok) error stop "output name"
    if (fastnorm_string(name) /= "fn_n" .or. fastnorm_string(unit) /= "N") error stop "output name or unit"
    do interpolation = fastnorm_table_multilinear, fastnorm_table_pchip
      if (fastnorm_table_lookup(table, 0_c_int, -0.4d-3, 3d-3, table_load, interpolation, out, found) /= fastnorm_ok) &
        error stop "lookup: " // fastnorm_string(fastnorm_last_error())
      if (found /= fastnorm_table_found) error stop "lookup found nothing"
      if (abs(out(1) - (1000 + 2d5 * (-0.4d-3) + 3d3 * 3d-3)) > 1d-9) error stop "lookup is not the linear data"
      if (fastnorm_table_lookup(table, 0_c_int, 3d-3, 3d-3, table_load, interpolation, out, found) /= fastnorm_ok &
          .or. found /= fastnorm_table_out_of_range) error stop "out of range not reported"
    end do
    print '(a, f10.4, a)', "table lookup: fn = ", out(1), " N"
    call fastnorm_table_destroy(table)
    open(newunit=file, file=path(1:len(path) - 1), status="old")
    close(file, status="delete")
  end subroutine

  ! CONTACT's large-spin Hertz example (docs/tangential.md §5): NORM in force control, then
  ! steady rolling; CONTACT's exact answer is Fs = -14940 N, Mz = -48.21 N m, 356 elements in
  ! adhesion and 920 in slip.
  subroutine creep_forces_of_a_hertz_contact()
    integer, parameter :: n = 44
    type(fastnorm_grid) :: grid
    type(fastnorm_material) :: material
    type(fastnorm_result) :: normal
    type(fastnorm_tangential_result) :: rolling
    type(c_ptr) :: norm
    real(c_double) :: h(n * n), pressure(n * n), traction_x(n * n), traction_y(n * n), x, yl
    character(kind=c_char, len=5), target :: norm_name = "norm" // c_null_char
    integer :: i, j
    grid = fastnorm_grid(n, n, 0.4d-3, 0.2d-3, -(n - 1) * 0.4d-3 / 2, -(n - 1) * 0.2d-3 / 2)
    material = fastnorm_material(2 * 82d9 * 1.28d0, 0.28d0, 2 * 82d9 * 1.28d0, 0.28d0)
    do j = 0, n - 1
      do i = 0, n - 1
        x = grid%x0 + grid%dx * i
        yl = grid%y0 + grid%dy * j
        h(1 + i + n * j) = 0.8464d0 * x * x + 2.406d0 * yl * yl
      end do
    end do
    if (fastnorm_solver_create(norm_name, grid, material, c_null_ptr, norm) /= fastnorm_ok) &
      error stop "solver: " // fastnorm_string(fastnorm_last_error())
    if (fastnorm_solve_force(norm, h, 82.0d3, pressure, normal) /= fastnorm_ok) &
      error stop "normal: " // fastnorm_string(fastnorm_last_error())
    call fastnorm_solver_destroy(norm)
    if (fastnorm_steady_rolling(grid, material, pressure, 0.3d0, fastnorm_creepage(0d0, -6.25d-4, 0.625d0, 0d0, 0d0), &
                                1_c_int, c_null_ptr, traction_x, traction_y, rolling) /= fastnorm_ok) &
      error stop "steady rolling: " // fastnorm_string(fastnorm_last_error())
    print '(a, es12.5, a, es12.5, a, i4, a, i4)', "steady rolling: Fs = ", rolling%force_y, " N, Mz = ", &
      rolling%spin_moment, " N m, adhesion ", rolling%adhesion_elements, ", slip ", rolling%slip_elements
    if (abs(rolling%force_y + 14940) > 0.015d0 * 0.3d0 * 82d3) error stop "Fs is not CONTACT's"
    if (rolling%adhesion_elements /= 356 .or. rolling%slip_elements /= 920) error stop "areas are not CONTACT's"
  end subroutine

end program user_routine
