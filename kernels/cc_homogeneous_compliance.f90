! Film and substrate of the same material: a homogeneous half-space, C(q) = 1 exactly
! (THEORY.md section 3, "C = 1 for identical materials"), so H = 0.
module cc_homogeneous_compliance
  use cc_elastic_constants, only: dp
  use cc_layered_compliance, only: layered_coefficients, finish_coefficients
  implicit none
  private
  public :: homogeneous_coefficients, homogeneous_compliance

contains

  ! A = B = 0: the closed form then gives C = 1 up to rounding; callers use the exact value.
  pure function homogeneous_coefficients() result(coef)
    type(layered_coefficients) :: coef
    coef%a = 0.0_dp
    coef%b = 0.0_dp
    coef%ap = 1.0_dp
    coef%bp = 1.0_dp
    coef%p = 1.0_dp
    coef%omab = 1.0_dp
    call finish_coefficients(coef, 1.0_dp)
  end function homogeneous_coefficients

  elemental real(dp) function homogeneous_compliance(q) result(c)
    real(dp), intent(in) :: q
    c = 1.0_dp + 0.0_dp * q
  end function homogeneous_compliance

end module cc_homogeneous_compliance
