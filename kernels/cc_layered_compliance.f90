! Surface compliance C(q) of a film bonded to a substrate (THEORY.md section 3):
!   C = N/D,  N = 1 + 4Bq x - AB x^2,  D = 1 - (A + B + 4Bq^2) x + AB x^2,  x = exp(-2q).
! The same formula serves the elastic substrate (alpha = mu1/mu0 > 0) and, through the
! coefficients of cc_rigid_substrate_compliance, the rigid substrate (alpha = 0).
!
! Cancellation-free form (the naive one loses up to 10 digits for extreme modulus ratios and
! for the incompressible film on a rigid substrate, where C ~ q^3). With
!   a' = 1 - A,  b' = 1 - B,  p = 1 + B,  1 - AB = alpha (1+g0)(1+g1) / ((1+alpha g0)(alpha+g1)),
!   y = 1 - x = -expm1(-2q),  P1 = exp(-q)(sinh q - q),  P2 = exp(-q)(sinh q + q),
!   S = 1 - x^2 - 4 q x = 2 x (sinh 2q - 2q),
! one has
!   N = S + (1 - AB) x^2 + 4 p q x
!   D = 4 P1 P2 + (a' + b') x y + a' b' x^2 + 4 b' q^2 x
! and every term is >= 0 for every admissible material pair (a', b', p, 1 - AB >= 0), so N
! and D, hence C, carry only rounding errors of a few ulps. For C - 1:
!   C - 1 = M/D,  M = x [ m0 + 4 B q (1 + q) + 2 A B y ],  m0 = A + B - 2AB = a' + b' - 2 a' b'.
module cc_layered_compliance
  use, intrinsic :: iso_c_binding, only: c_double
  use cc_elastic_constants, only: dp, material_pair, modulus_ratio
  use cc_power_series, only: series_product, series_quotient, exp_series
  implicit none
  private

  ! exp(x) - 1 without cancellation (C99 libm; Fortran has no intrinsic for it).
  interface
    pure function expm1(x) result(y) bind(C, name="expm1")
      import :: c_double
      real(c_double), value :: x
      real(c_double) :: y
    end function expm1
  end interface

  ! Coefficients of the closed form (see the module header).
  type, public :: layered_coefficients
    real(dp) :: a = 0.0_dp, b = 0.0_dp     ! A, B
    real(dp) :: ap = 1.0_dp, bp = 1.0_dp   ! a' = 1 - A, b' = 1 - B
    real(dp) :: p = 1.0_dp                 ! 1 + B
    real(dp) :: omab = 1.0_dp              ! 1 - A B
    real(dp) :: m0 = 0.0_dp                ! A + B - 2 A B
    real(dp) :: c_zero = 1.0_dp            ! C(0) = E1*/E0*
  end type layered_coefficients

  ! Beyond this q, x = exp(-2q) underflows and C = 1 to the last bit.
  real(dp), parameter, public :: q_saturation = 400.0_dp
  ! Highest Taylor order handled by layered_taylor.
  integer, parameter, public :: max_taylor_order = 15

  public :: elastic_substrate_coefficients, finish_coefficients
  public :: layered_compliance, layered_compliance_minus_one, layered_taylor, layered_series

contains

  ! Coefficients for a film on an elastic substrate; alpha = mu1/mu0 is never formed when it
  ! exceeds 1 (its inverse is used), so extreme ratios neither overflow nor cancel.
  pure function elastic_substrate_coefficients(pair) result(coef)
    type(material_pair), intent(in) :: pair
    type(layered_coefficients) :: coef
    real(dp) :: g1, g0, g1m1, alpha, beta

    g1 = 3.0_dp - 4.0_dp * pair%nu1
    g0 = 3.0_dp - 4.0_dp * pair%nu0
    g1m1 = 2.0_dp * (1.0_dp - 2.0_dp * pair%nu1)       ! g1 - 1, exact for nu1 -> 1/2
    alpha = (pair%e1 / pair%e0) * ((1.0_dp + pair%nu0) / (1.0_dp + pair%nu1))
    if (alpha <= 1.0_dp) then
      coef%a = (alpha * g0 - g1) / (1.0_dp + alpha * g0)
      coef%b = (alpha - 1.0_dp) / (alpha + g1)
      coef%ap = (1.0_dp + g1) / (1.0_dp + alpha * g0)
      coef%bp = (1.0_dp + g1) / (alpha + g1)
      coef%p = (2.0_dp * alpha + g1m1) / (alpha + g1)
      coef%omab = alpha * (1.0_dp + g0) * (1.0_dp + g1) / ((1.0_dp + alpha * g0) * (alpha + g1))
    else
      beta = (pair%e0 / pair%e1) * ((1.0_dp + pair%nu1) / (1.0_dp + pair%nu0))
      coef%a = (g0 - g1 * beta) / (beta + g0)
      coef%b = (1.0_dp - beta) / (1.0_dp + g1 * beta)
      coef%ap = (1.0_dp + g1) * beta / (beta + g0)
      coef%bp = (1.0_dp + g1) * beta / (1.0_dp + g1 * beta)
      coef%p = (2.0_dp + g1m1 * beta) / (1.0_dp + g1 * beta)
      coef%omab = beta * (1.0_dp + g0) * (1.0_dp + g1) / ((beta + g0) * (1.0_dp + g1 * beta))
    end if
    call finish_coefficients(coef, modulus_ratio(pair))
  end function elastic_substrate_coefficients

  ! Derived coefficients common to every model.
  pure subroutine finish_coefficients(coef, c_zero)
    type(layered_coefficients), intent(inout) :: coef
    real(dp), intent(in) :: c_zero
    coef%m0 = coef%ap + coef%bp - 2.0_dp * coef%ap * coef%bp
    coef%c_zero = c_zero
  end subroutine finish_coefficients

  ! sinh(z) - z for 0 <= z < 2 by its series (no cancellation).
  elemental real(dp) function sinh_minus_z(z) result(s)
    real(dp), intent(in) :: z
    real(dp) :: z2, term
    integer :: k
    z2 = z * z
    term = z * z2 / 6.0_dp
    s = term
    do k = 2, 14
      term = term * z2 / real((2 * k) * (2 * k + 1), dp)
      s = s + term
    end do
  end function sinh_minus_z

  ! N, D and M of the module header at one q in [0, q_saturation).
  elemental subroutine layered_parts(coef, q, n, d, m)
    type(layered_coefficients), intent(in) :: coef
    real(dp), intent(in) :: q
    real(dp), intent(out) :: n, d, m
    real(dp) :: e, x, y, p1, p2, s, qx

    e = exp(-q)
    x = e * e
    y = -expm1(-2.0_dp * q)
    qx = q * x
    if (q < 2.0_dp) then
      p1 = e * sinh_minus_z(q)
    else
      p1 = 0.5_dp * y - q * e
    end if
    p2 = 0.5_dp * y + q * e
    if (q < 1.0_dp) then
      s = 2.0_dp * x * sinh_minus_z(2.0_dp * q)
    else
      s = y * (1.0_dp + x) - 4.0_dp * qx
    end if
    n = s + coef%omab * x * x + 4.0_dp * coef%p * qx
    d = 4.0_dp * p1 * p2 + (coef%ap + coef%bp) * x * y + coef%ap * coef%bp * x * x &
        + 4.0_dp * coef%bp * q * qx
    m = x * (coef%m0 + 4.0_dp * coef%b * q * (1.0_dp + q) + 2.0_dp * coef%a * coef%b * y)
  end subroutine layered_parts

  ! C(q) for q >= 0 (relative accuracy a few ulps for every q).
  elemental real(dp) function layered_compliance(coef, q) result(c)
    type(layered_coefficients), intent(in) :: coef
    real(dp), intent(in) :: q
    real(dp) :: n, d, m
    if (q >= q_saturation) then
      c = 1.0_dp
      return
    end if
    call layered_parts(coef, q, n, d, m)
    c = n / d
  end function layered_compliance

  ! C(q) - 1: from C where |C - 1| is not small (no cancellation then), else from M/D.
  elemental real(dp) function layered_compliance_minus_one(coef, q) result(f)
    type(layered_coefficients), intent(in) :: coef
    real(dp), intent(in) :: q
    real(dp) :: n, d, m, c
    if (q >= q_saturation) then
      f = 0.0_dp
      return
    end if
    call layered_parts(coef, q, n, d, m)
    c = n / d
    if (c < 0.5_dp .or. c > 2.0_dp) then
      f = c - 1.0_dp
    else
      f = m / d
    end if
  end function layered_compliance_minus_one

  ! ---- Taylor series ------------------------------------------------------------------

  ! sinh(c q) + sign * c q.
  pure function sinh_series(c, sign, kmax) result(w)
    real(dp), intent(in) :: c, sign
    integer, intent(in) :: kmax
    real(dp) :: w(0:kmax)
    real(dp) :: ek(0:kmax)
    integer :: k
    ek = exp_series(c, kmax)
    w = 0.0_dp
    do k = 3, kmax, 2
      w(k) = ek(k)
    end do
    if (kmax >= 1) w(1) = c + sign * c
  end function sinh_series

  ! Power series (orders 0..kmax) of M and D (module header), built term by term in the
  ! cancellation-free form. Both are entire functions of q.
  pure subroutine layered_series(coef, kmax, mser, dser)
    type(layered_coefficients), intent(in) :: coef
    integer, intent(in) :: kmax
    real(dp), intent(out) :: mser(0:kmax), dser(0:kmax)
    real(dp), dimension(0:kmax) :: e1, x, x2, y, p1, p2, bracket, q2x

    e1 = exp_series(-1.0_dp, kmax)
    x = exp_series(-2.0_dp, kmax)
    x2 = exp_series(-4.0_dp, kmax)
    y = -x
    y(0) = 0.0_dp
    p1 = series_product(e1, sinh_series(1.0_dp, -1.0_dp, kmax))
    p2 = series_product(e1, sinh_series(1.0_dp, 1.0_dp, kmax))
    q2x = 0.0_dp
    q2x(2:kmax) = x(0:kmax - 2)
    dser = 4.0_dp * series_product(p1, p2) + (coef%ap + coef%bp) * series_product(x, y) &
           + coef%ap * coef%bp * x2 + 4.0_dp * coef%bp * q2x
    bracket = 2.0_dp * coef%a * coef%b * y
    bracket(0) = bracket(0) + coef%m0
    bracket(1) = bracket(1) + 4.0_dp * coef%b
    bracket(2) = bracket(2) + 4.0_dp * coef%b
    mser = series_product(x, bracket)
  end subroutine layered_series

  ! Taylor coefficients f_0..f_order of f = C - 1 = M/D (order <= max_taylor_order).
  pure subroutine layered_taylor(coef, order, f)
    type(layered_coefficients), intent(in) :: coef
    integer, intent(in) :: order
    real(dp), intent(out) :: f(0:order)
    real(dp), dimension(0:max_taylor_order) :: mser, dser, full
    call layered_series(coef, max_taylor_order, mser, dser)
    full = series_quotient(mser, dser)
    f = full(0:order)
  end subroutine layered_taylor

end module cc_layered_compliance
