! C(q), C(q) - 1 and the Taylor coefficients of C - 1 for any validated material pair:
! dispatches to the homogeneous, elastic-substrate and rigid-substrate models.
module cc_compliance_models
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use cc_elastic_constants, only: dp, material_pair, CC_OK, CC_ERR_ARGUMENT, &
                                  MODEL_HOMOGENEOUS, MODEL_ELASTIC_SUBSTRATE, MODEL_RIGID_SUBSTRATE
  use cc_layered_compliance, only: layered_coefficients, layered_compliance, &
                                   layered_compliance_minus_one, layered_taylor, layered_series, &
                                   elastic_substrate_coefficients, max_taylor_order
  use cc_rigid_substrate_compliance, only: rigid_substrate_coefficients
  use cc_homogeneous_compliance, only: homogeneous_coefficients, homogeneous_compliance
  implicit none
  private
  public :: coefficients_of, compliance, compliance_minus_one, compliance_taylor
  public :: compliance_series, max_taylor_order, valid_wavenumbers

contains

  pure function coefficients_of(pair) result(coef)
    type(material_pair), intent(in) :: pair
    type(layered_coefficients) :: coef
    select case (pair%model)
    case (MODEL_ELASTIC_SUBSTRATE)
      coef = elastic_substrate_coefficients(pair)
    case (MODEL_RIGID_SUBSTRATE)
      coef = rigid_substrate_coefficients(pair)
    case default
      coef = homogeneous_coefficients()
    end select
  end function coefficients_of

  ! Every q finite and >= 0 (the domain of every compliance routine).
  pure logical function valid_wavenumbers(q) result(ok)
    real(dp), intent(in) :: q(:)
    ok = all(ieee_is_finite(q))
    if (ok) ok = all(q >= 0.0_dp)
  end function valid_wavenumbers

  pure subroutine compliance(pair, q, c, status)
    type(material_pair), intent(in) :: pair
    real(dp), intent(in) :: q(:)
    real(dp), intent(out) :: c(size(q))
    integer, intent(out) :: status
    c = 0.0_dp
    status = CC_ERR_ARGUMENT
    if (.not. valid_wavenumbers(q)) return
    status = CC_OK
    if (pair%model == MODEL_HOMOGENEOUS) then
      c = homogeneous_compliance(q)
    else
      c = layered_compliance(coefficients_of(pair), q)
    end if
  end subroutine compliance

  pure subroutine compliance_minus_one(pair, q, f, status)
    type(material_pair), intent(in) :: pair
    real(dp), intent(in) :: q(:)
    real(dp), intent(out) :: f(size(q))
    integer, intent(out) :: status
    f = 0.0_dp
    status = CC_ERR_ARGUMENT
    if (.not. valid_wavenumbers(q)) return
    status = CC_OK
    if (pair%model /= MODEL_HOMOGENEOUS) f = layered_compliance_minus_one(coefficients_of(pair), q)
  end subroutine compliance_minus_one

  pure subroutine compliance_taylor(pair, order, f, status)
    type(material_pair), intent(in) :: pair
    integer, intent(in) :: order
    real(dp), intent(out) :: f(0:order)
    integer, intent(out) :: status
    f = 0.0_dp
    status = CC_ERR_ARGUMENT
    if (order < 0 .or. order > max_taylor_order) return
    status = CC_OK
    if (pair%model /= MODEL_HOMOGENEOUS) call layered_taylor(coefficients_of(pair), order, f)
  end subroutine compliance_taylor

  ! Power series of the numerator M and denominator D of f = C - 1 = M/D, orders 0..kmax
  ! (homogeneous: M = 0, D = 1).
  pure subroutine compliance_series(pair, kmax, mser, dser)
    type(material_pair), intent(in) :: pair
    integer, intent(in) :: kmax
    real(dp), intent(out) :: mser(0:kmax), dser(0:kmax)
    if (pair%model == MODEL_HOMOGENEOUS) then
      mser = 0.0_dp
      dser = 0.0_dp
      dser(0) = 1.0_dp
    else
      call layered_series(coefficients_of(pair), kmax, mser, dser)
    end if
  end subroutine compliance_series

end module cc_compliance_models
