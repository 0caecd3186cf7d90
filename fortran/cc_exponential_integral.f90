! exp(z) E1(z) for complex z with Re z > 0: the transform of a damped pole,
!   int_0^inf exp(-w q) / (q + q0) dq = exp(w q0) E1(w q0),  Re w > 0, q0 > 0,
! used by cc_kernel_tables to remove the pole of C(q) - 1 close to q = 0 (stiff films).
! |z| <= 5: power series (Abramowitz & Stegun 5.1.11); |z| > 5: continued fraction
! (A&S 5.1.22, modified Lentz), which converges fast there.
module cc_exponential_integral
  use cc_elastic_constants, only: dp
  implicit none
  private
  public :: scaled_e1

  real(dp), parameter :: euler_gamma = 0.577215664901532860606512090082402431_dp

contains

  elemental complex(dp) function scaled_e1(z) result(v)
    complex(dp), intent(in) :: z
    complex(dp) :: term, total, b, c, d, delta
    real(dp), parameter :: tiny_value = 1.0e-300_dp
    integer :: k

    if (abs(z) <= 5.0_dp) then
      ! E1(z) = -gamma - log z - sum_k (-z)^k / (k k!)
      term = (1.0_dp, 0.0_dp)
      total = (0.0_dp, 0.0_dp)
      do k = 1, 200
        term = -term * z / real(k, dp)
        total = total + term / real(k, dp)
        ! |term| < 1e-18 |total|, without square roots
        if (squared(term) < 1.0e-36_dp * squared(total)) exit
      end do
      v = exp(z) * (-euler_gamma - log(z) - total)
    else
      ! exp(z) E1(z) = 1/(z+1- 1/(z+3- 4/(z+5- ...)))
      b = z + 1.0_dp
      c = cmplx(1.0_dp / tiny_value, 0.0_dp, dp)
      d = 1.0_dp / b
      v = d
      do k = 1, 500
        b = b + 2.0_dp
        d = 1.0_dp / (b - real(k * k, dp) * d)
        c = b - real(k * k, dp) / c
        delta = c * d
        v = v * delta
        if (abs(delta - 1.0_dp) < 1.0e-16_dp) exit
      end do
    end if
  end function scaled_e1

  elemental real(dp) function squared(z) result(s)
    complex(dp), intent(in) :: z
    s = real(z, dp)**2 + aimag(z)**2
  end function squared

end module cc_exponential_integral
