! A multibody code's wheel-rail contact, written the way its user routines are: Fortran,
! calling fastnorm's C API through the module fastnorm_c (fastnorm_c.f90, shipped with the
! C library; docs/bindings.md). The program finds the
! static equilibrium of a wheelset under 200 kN at y = 3 mm, then steps it through a small
! lateral oscillation calling the user routine at every step, as an integrator would.
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
    if (fastnorm_wheelset_create(options, model) /= fastnorm_ok) error stop "create: " // fastnorm_string(fastnorm_last_error())
  end subroutine

  ! The user routine: the contact force (N) and moment (N m) on the wheelset at its pose
  ! (m, rad; track frame, z down).
  subroutine contact_user_routine(y, z, roll, yaw, force, moment)
    real(c_double), intent(in) :: y, z, roll, yaw
    real(c_double), intent(out) :: force(3), moment(3)
    call ensure_model()
    if (fastnorm_wheelset_evaluate(model, fastnorm_pose(y, z, roll, yaw), force, moment) /= fastnorm_ok) then
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
  integer :: step

  call ensure_model()
  if (fastnorm_wheelset_equilibrium(model, load, y0, 0.0d0, found) /= fastnorm_ok) then
    error stop "equilibrium: " // fastnorm_string(fastnorm_last_error())
  end if
  if (found%status /= fastnorm_equilibrium_converged) error stop "equilibrium did not converge"
  print '(a, es12.5, a, es12.5, a, es12.5, a)', "equilibrium: z = ", found%pose%z, " m, roll = ", &
    found%pose%roll, " rad, vertical force ", found%vertical_force, " N"

  do step = 0, 20
    y = y0 + 0.5d-3 * sin(0.3d0 * step)
    call contact_user_routine(y, found%pose%z, found%pose%roll, 0.0d0, force, moment)
    if (step == 0) then
      ! The equilibrium is the model's own: at its pose the rails carry the load.
      if (abs(-force(3) / load - 1) > 1.0d-6) error stop "vertical force at the equilibrium is off"
    end if
    if (.not. (force(3) < 0 .and. abs(force(3)) < 10 * load)) error stop "implausible vertical force"
    print '(a, i3, a, f7.4, a, es12.5, a, es12.5, a)', "step ", step, ": y = ", 1d3 * y, " mm, Fy = ", &
      force(2), " N, Fz = ", force(3), " N"
  end do
  call fastnorm_wheelset_destroy(model)
end program user_routine
