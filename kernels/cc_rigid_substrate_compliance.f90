! Film bonded to a rigid substrate (THEORY.md section 3, alpha = mu1/mu0 = 0):
! A = -g1, B = -1/g1 with g1 = 3 - 4 nu1; C(0) = 0. Reduces to the rigid-base layer of
! Carbone and Mangialardi (JMPS 2008, eq. A.30). For nu1 = 1/2 (A = B = -1) C ~ q^3 at small q;
! the cancellation-free form of cc_layered_compliance keeps its relative accuracy.
module cc_rigid_substrate_compliance
  use cc_elastic_constants, only: dp, material_pair
  use cc_layered_compliance, only: layered_coefficients, finish_coefficients
  implicit none
  private
  public :: rigid_substrate_coefficients

contains

  pure function rigid_substrate_coefficients(pair) result(coef)
    type(material_pair), intent(in) :: pair
    type(layered_coefficients) :: coef
    real(dp) :: g1
    g1 = 3.0_dp - 4.0_dp * pair%nu1
    coef%a = -g1
    coef%b = -1.0_dp / g1
    coef%ap = 1.0_dp + g1
    coef%bp = (1.0_dp + g1) / g1
    coef%p = 2.0_dp * (1.0_dp - 2.0_dp * pair%nu1) / g1     ! 1 + B, exact for nu1 -> 1/2
    coef%omab = 0.0_dp                                      ! 1 - AB = 0 exactly
    call finish_coefficients(coef, 0.0_dp)
  end function rigid_substrate_coefficients

end module cc_rigid_substrate_compliance
