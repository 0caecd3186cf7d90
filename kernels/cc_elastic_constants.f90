! Elastic constants of the film (index 1) and the substrate (index 0), their validation,
! and the status codes shared with the C interface (THEORY.md sections 1 and 3).
module cc_elastic_constants
  use, intrinsic :: iso_fortran_env, only: real64
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  implicit none
  private

  integer, parameter, public :: dp = real64

  ! Status codes: must match enum cc_status in fortran/include/coatcontact/cc_status.h.
  integer, parameter, public :: CC_OK = 0
  integer, parameter, public :: CC_INPUT_ERROR = 2           ! classes (cc_status_class)
  integer, parameter, public :: CC_NUMERICAL_ERROR = 3
  integer, parameter, public :: CC_INTERNAL_ERROR = 4
  integer, parameter, public :: CC_INTERRUPTED = 5
  integer, parameter, public :: CC_ERR_FILM_MODULUS = 101
  integer, parameter, public :: CC_ERR_FILM_POISSON = 102
  integer, parameter, public :: CC_ERR_SUBSTRATE_MODULUS = 103
  integer, parameter, public :: CC_ERR_SUBSTRATE_POISSON = 104
  integer, parameter, public :: CC_ERR_ARGUMENT = 105
  integer, parameter, public :: CC_ERR_FFT = 106
  integer, parameter, public :: CC_ERR_ALLOCATION = 107
  integer, parameter, public :: CC_ERR_ACCURACY = 108
  integer, parameter, public :: CC_ERR_THICKNESS = 109       ! a stack layer (THEORY.md section 12)
  integer, parameter, public :: CC_ERR_LAYER_COUNT = 110

  ! Substrate models.
  integer, parameter, public :: MODEL_HOMOGENEOUS = 0      ! film and substrate identical: C = 1
  integer, parameter, public :: MODEL_ELASTIC_SUBSTRATE = 1
  integer, parameter, public :: MODEL_RIGID_SUBSTRATE = 2

  ! A validated film/substrate pair.
  type, public :: material_pair
    real(dp) :: e1 = 1.0_dp, nu1 = 0.0_dp   ! film
    real(dp) :: e0 = 1.0_dp, nu0 = 0.0_dp   ! substrate (ignored when rigid)
    integer :: model = MODEL_HOMOGENEOUS
  end type material_pair

  public :: validate_modulus, validate_poisson, make_material_pair
  public :: reduced_modulus, shear_modulus, modulus_ratio

contains

  ! E must be finite and > 0.
  elemental logical function validate_modulus(e) result(ok)
    real(dp), intent(in) :: e
    ok = ieee_is_finite(e) .and. e > 0.0_dp
  end function validate_modulus

  ! -1 < nu <= 1/2 (nu = 1/2, incompressible, is allowed: THEORY.md section 3).
  elemental logical function validate_poisson(nu) result(ok)
    real(dp), intent(in) :: nu
    ok = ieee_is_finite(nu) .and. nu > -1.0_dp .and. nu <= 0.5_dp
  end function validate_poisson

  ! E* = E / (1 - nu^2).
  elemental real(dp) function reduced_modulus(e, nu) result(es)
    real(dp), intent(in) :: e, nu
    es = e / ((1.0_dp - nu) * (1.0_dp + nu))
  end function reduced_modulus

  ! mu = E / (2 (1 + nu)).
  elemental real(dp) function shear_modulus(e, nu) result(mu)
    real(dp), intent(in) :: e, nu
    mu = e / (2.0_dp * (1.0_dp + nu))
  end function shear_modulus

  ! E1*/E0* (0 for a rigid substrate) = C(0).
  pure real(dp) function modulus_ratio(pair) result(ratio)
    type(material_pair), intent(in) :: pair
    select case (pair%model)
    case (MODEL_RIGID_SUBSTRATE)
      ratio = 0.0_dp
    case (MODEL_HOMOGENEOUS)
      ratio = 1.0_dp
    case default
      ! Written as a product of ratios so that extreme moduli do not overflow.
      ratio = (pair%e1 / pair%e0) * (((1.0_dp - pair%nu0) * (1.0_dp + pair%nu0)) &
              / ((1.0_dp - pair%nu1) * (1.0_dp + pair%nu1)))
    end select
  end function modulus_ratio

  ! Validates the constants and selects the model. Identical film and substrate give the
  ! homogeneous model (C = 1 exactly).
  pure subroutine make_material_pair(e1, nu1, e0, nu0, rigid, pair, status)
    real(dp), intent(in) :: e1, nu1, e0, nu0
    logical, intent(in) :: rigid
    type(material_pair), intent(out) :: pair
    integer, intent(out) :: status

    status = CC_OK
    if (.not. validate_modulus(e1)) then
      status = CC_ERR_FILM_MODULUS
    else if (.not. validate_poisson(nu1)) then
      status = CC_ERR_FILM_POISSON
    else if (.not. rigid .and. .not. validate_modulus(e0)) then
      status = CC_ERR_SUBSTRATE_MODULUS
    else if (.not. rigid .and. .not. validate_poisson(nu0)) then
      status = CC_ERR_SUBSTRATE_POISSON
    end if
    if (status /= CC_OK) return

    pair%e1 = e1
    pair%nu1 = nu1
    if (rigid) then
      pair%e0 = huge(1.0_dp)
      pair%nu0 = 0.0_dp
      pair%model = MODEL_RIGID_SUBSTRATE
    else
      pair%e0 = e0
      pair%nu0 = nu0
      if (e1 == e0 .and. nu1 == nu0) then
        pair%model = MODEL_HOMOGENEOUS
      else
        pair%model = MODEL_ELASTIC_SUBSTRATE
      end if
    end if
  end subroutine make_material_pair

end module cc_elastic_constants
