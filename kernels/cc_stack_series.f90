! Power series at q = 0 of the numerator M and denominator D of f = C - 1 = M/D for a stack
! (THEORY.md section 12), for the end correction, the asymptotic series and the pole removal
! of the kernel table (fortran/cc_kernel_tables.f90).
!
! Why a series recursion: the table needs f^(k)(0)/k! up to k = 15, and differences or fits of
! real samples lose ~ (2^k)^2 of their accuracy; a Cauchy integral would need C at complex q.
! Instead the recursion of section 12 is run in truncated power series of q: every layer,
! thick or thin at any q, is crossed with its exact propagator expm(-A x), x = q h_i/T, whose
! series is entire (A^n x^n / n!), and the 4x2 basis of admissible states is carried without
! re-charting (a re-chart would divide series). At q = 0 the propagators are the identity, so
! no exponential growth enters the low-order coefficients. M and D are then entire series
! (minors of the surface basis), as compliance_series gives them for one film: a near zero
! of D (stiff layers) is removed by the same code as for one film.
module cc_stack_series
  use cc_elastic_constants, only: dp
  use cc_power_series, only: series_product
  use cc_multilayer_compliance, only: layer_stack
  implicit none
  private
  public :: stack_series

  integer, parameter :: iu = 1, iw = 2, ir = 3, iz = 4

contains

  ! M and D (orders 0..kmax) with f = C - 1 = M/D and D(0) > 0; a common factor q^j of M and D
  ! (sliding on a rigid base: C ~ q/2) is divided out.
  pure subroutine stack_series(stack, kmax, mser, dser)
    type(layer_stack), intent(in) :: stack
    integer, intent(in) :: kmax
    real(dp), intent(out) :: mser(0:kmax), dser(0:kmax)
    real(dp) :: y(4, 2, 0:kmax), v(4, 0:kmax), nu
    integer :: i, n, shift
    real(dp) :: big

    n = stack%n
    y = 0.0_dp
    if (stack%rigid_base) then
      if (stack%slip(n)) then
        y(iu, 1, 0) = 1.0_dp
        y(iz, 2, 0) = 1.0_dp
      else
        y(ir, 1, 0) = 1.0_dp
        y(iz, 2, 0) = 1.0_dp
      end if
    else
      nu = stack%nu_base
      y(iu, :, 0) = [-(1.0_dp - nu), 0.5_dp * (1.0_dp - 2.0_dp * nu)]
      y(iw, :, 0) = [0.5_dp * (1.0_dp - 2.0_dp * nu), -(1.0_dp - nu)]
      y(ir, :, 0) = [1.0_dp, 0.0_dp]
      y(iz, :, 0) = [0.0_dp, 1.0_dp]
    end if
    do i = n, 1, -1
      if (i < n .or. .not. stack%rigid_base) then
        if (stack%slip(i)) then
          ! the state with tau_r = 0 below; above: U free, (W, tau_z) continuous
          v = series_column(y(:, 1, :), y(ir, 2, :)) - series_column(y(:, 2, :), y(ir, 1, :))
          y = 0.0_dp
          y(iu, 1, 0) = 1.0_dp
          y(iw, 2, :) = v(iw, :)
          y(iz, 2, :) = stack%scale(i) * v(iz, :)
          call strip_column(y(:, 2, :))
        else
          y(ir:iz, :, :) = stack%scale(i) * y(ir:iz, :, :)
        end if
      end if
      call propagate(stack%nu(i), stack%frac(i), y)
      call strip_column(y(:, 1, :))
      call strip_column(y(:, 2, :))
    end do
    nu = stack%nu(1)
    dser = (1.0_dp - nu) * minor_series(y, iz, ir)
    mser = -minor_series(y, iw, ir) - dser
    ! common factors q^j (both leading coefficients at rounding level)
    do shift = 1, kmax
      big = max(maxval(abs(dser)), tiny(1.0_dp))
      if (abs(dser(0)) > 64.0_dp * epsilon(1.0_dp) * big) exit
      dser(0:kmax - 1) = dser(1:kmax)
      dser(kmax) = 0.0_dp
      mser(0:kmax - 1) = mser(1:kmax)
      mser(kmax) = 0.0_dp
    end do
    if (dser(0) < 0.0_dp) then
      dser = -dser
      mser = -mser
    end if
  end subroutine stack_series

  ! Series of each row of a column times a scalar series.
  pure function series_column(col, s) result(w)
    real(dp), intent(in) :: col(:, 0:), s(0:)
    real(dp) :: w(4, 0:ubound(s, 1))
    integer :: k
    do k = 1, 4
      w(k, :) = series_product(col(k, :), s)
    end do
  end function series_column

  ! A column whose constant term vanishes exactly (a slip interface right above another at
  ! q -> 0) is divided by q: the same direction of the subspace for q > 0.
  pure subroutine strip_column(col)
    real(dp), intent(inout) :: col(:, 0:)
    integer :: k, kmax
    kmax = ubound(col, 2)
    do k = 1, kmax
      if (any(col(:, 0) /= 0.0_dp) .or. all(col == 0.0_dp)) exit
      col(:, 0:kmax - 1) = col(:, 1:kmax)
      col(:, kmax) = 0.0_dp
    end do
  end subroutine strip_column

  pure function minor_series(y, a, b) result(d)
    real(dp), intent(in) :: y(:, :, 0:)
    integer, intent(in) :: a, b
    real(dp) :: d(0:ubound(y, 3))
    d = series_product(y(a, 1, :), y(b, 2, :)) - series_product(y(a, 2, :), y(b, 1, :))
  end function minor_series

  ! y <- expm(-A x) y with x = frac q: sum_n (-frac)^n A^n y / n!, the term n shifted by n.
  pure subroutine propagate(nu, frac, y)
    real(dp), intent(in) :: nu, frac
    real(dp), intent(inout) :: y(:, :, 0:)
    real(dp) :: t(4, 2, 0:ubound(y, 3)), acc(4, 2, 0:ubound(y, 3))
    real(dp) :: r, h
    integer :: n, kmax
    kmax = ubound(y, 3)
    r = nu / (1.0_dp - nu)
    h = (1.0_dp - 2.0_dp * nu) / (2.0_dp * (1.0_dp - nu))
    t = y
    acc = y
    do n = 1, kmax
      ! t <- (-frac/n) A t (section 12's A at m = 1), then shifted by one order
      t = (-frac / real(n, dp)) * apply_a_series(t)
      acc(:, :, n:kmax) = acc(:, :, n:kmax) + t(:, :, 0:kmax - n)
    end do
    y = acc
  contains
    pure function apply_a_series(s) result(z)
      real(dp), intent(in) :: s(:, :, 0:)
      real(dp) :: z(4, 2, 0:ubound(s, 3))
      z(iu, :, :) = s(iw, :, :) + s(ir, :, :)
      z(iw, :, :) = -r * s(iu, :, :) + h * s(iz, :, :)
      z(ir, :, :) = (2.0_dp / (1.0_dp - nu)) * s(iu, :, :) + r * s(iz, :, :)
      z(iz, :, :) = -s(ir, :, :)
    end function apply_a_series
  end subroutine propagate

end module cc_stack_series
