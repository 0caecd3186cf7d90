! Truncated power series a(0:K) (a_k = coefficient of q^k): the arithmetic needed for the
! Taylor coefficients of C(q) - 1 and for removing a pole from them.
module cc_power_series
  use cc_elastic_constants, only: dp
  implicit none
  private
  public :: series_product, series_quotient, exp_series, series_value, series_slope, &
            series_deflate

contains

  pure function series_product(u, v) result(w)
    real(dp), intent(in) :: u(0:), v(0:)
    real(dp) :: w(0:ubound(u, 1))
    integer :: k
    do k = 0, ubound(u, 1)
      w(k) = sum(u(0:k) * v(k:0:-1))
    end do
  end function series_product

  ! u / v (v_0 /= 0).
  pure function series_quotient(u, v) result(w)
    real(dp), intent(in) :: u(0:), v(0:)
    real(dp) :: w(0:ubound(u, 1))
    integer :: k
    do k = 0, ubound(u, 1)
      w(k) = (u(k) - sum(w(0:k - 1) * v(k:1:-1))) / v(0)
    end do
  end function series_quotient

  ! exp(c q).
  pure function exp_series(c, kmax) result(w)
    real(dp), intent(in) :: c
    integer, intent(in) :: kmax
    real(dp) :: w(0:kmax)
    integer :: k
    w(0) = 1.0_dp
    do k = 1, kmax
      w(k) = w(k - 1) * c / real(k, dp)
    end do
  end function exp_series

  pure real(dp) function series_value(a, q) result(v)
    real(dp), intent(in) :: a(0:), q
    integer :: k
    v = 0.0_dp
    do k = ubound(a, 1), 0, -1
      v = v * q + a(k)
    end do
  end function series_value

  ! d/dq of the series at q.
  pure real(dp) function series_slope(a, q) result(v)
    real(dp), intent(in) :: a(0:), q
    integer :: k
    v = 0.0_dp
    do k = ubound(a, 1), 1, -1
      v = v * q + real(k, dp) * a(k)
    end do
  end function series_slope

  ! b = a / (q + q0) for an (entire, truncated) series a with a(-q0) = 0, by the backward
  ! recursion b_(k-1) = a_k - q0 b_k, which is stable for small q0 (the forward one divides
  ! by q0 at every step). The remainder a_0 - q0 b_0 (~ a(-q0)) is dropped.
  pure function series_deflate(a, q0) result(b)
    real(dp), intent(in) :: a(0:), q0
    real(dp) :: b(0:ubound(a, 1))
    integer :: k, kmax
    kmax = ubound(a, 1)
    b(kmax) = 0.0_dp
    do k = kmax, 1, -1
      b(k - 1) = a(k) - q0 * b(k)
    end do
  end function series_deflate

end module cc_power_series
