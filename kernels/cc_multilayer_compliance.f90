! Surface compliance C(q) of a stack of N layers (top first) on an elastic half-space or a
! rigid base, each interface bonded or frictionless (THEORY.md section 12). q = k T with T the
! total thickness; C is normalized by the TOP layer's E*, so C(inf) = 1, C(0) = E_top*/E_base*
! (0 on a rigid base).
!
! The module is not named cc_stack_compliance like its C entry point (fortran/cc_kernel_capi.f90):
! a module name may not equal a binding label (Fortran 2018 19.2).
!
! Method (section 12). State s = (U, W, tau_r, tau_z), z down, xi = k z, tau = (s_rz, s_zz)/(mu k)
! with mu the shear modulus of the layer the state lives in (so m = 1 in the A of section 12 and
! only nu enters; an interface rescales tau by mu_below/mu_above). The states admissible at the
! top of the part already crossed form a 2-D subspace of R^4, carried upward as a 4x2 basis in
! the chart whose two pivot rows have the largest 2x2 determinant, so every other entry is <= 1
! (compliance, stiffness or a mixed chart): section 12 measured 1.6e-12 for the compliance
! alone at sliding interfaces (which it cannot even represent: tau_r = 0 leaves U free) and
! 2e-15 for the smallest-entry chart. Across a layer of x = k h:
!   x < 1:  exact propagator s_top = expm(-A x) s_bottom (A^2 - I nilpotent, four coefficients);
!   x >= 1: local decaying exponentials (down pair referred to the layer top, up pair to its
!           bottom), so no exponential larger than 1 is formed.
! Section 12: either alone fails (exponentials only: 5e-5 on thin soft incompressible layers).
! When the top layer is thick, C - 1 is formed from the up pair's reflected part alone (the
! down pair alone gives C = 1 exactly), without cancellation where C ~ 1: its error is a few
! ulps of C - 1 plus a few ulps of exp(-2 q h_top/T) (the rounding of the subspace under the
! top layer), which only shows when the top layer is bonded to the same material.
! Measured against a 113-bit version of the direct global solve of
! tests/kernel/test_stack_compliance.cpp: C within 2e-15 over its random stacks, 1.6e-14 with
! ratios 1e-4..1e4, N <= 20, q 1e-4..1e4 (C - 1: 1.5e-13 relative where |C - 1| > 1e-20).
!
! One bonded layer goes through the closed form of section 3 (cc_compliance_models), so it
! equals cc_compliance bit for bit.
!
! Slip flag on the last layer above a rigid base: a frictionless rigid base, u_z = 0 and
! s_rz = 0 (section 12: one layer gives C = s(q)). No pattern of slip flags is rejected: for
! k > 0 every layer is held normally by the base and radially by its own elasticity (u_r is a
! J1(kr) field, never a rigid translation), and at q = 0 C = E_top*/E_base* (0 if rigid) for
! every pattern, so no configuration leaves the stack unsupported.
module cc_multilayer_compliance
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use cc_elastic_constants, only: dp, material_pair, make_material_pair, validate_modulus, &
                                  validate_poisson, CC_OK, CC_ERR_ARGUMENT, CC_ERR_FILM_MODULUS, &
                                  CC_ERR_FILM_POISSON, CC_ERR_SUBSTRATE_MODULUS, &
                                  CC_ERR_SUBSTRATE_POISSON, CC_ERR_THICKNESS, CC_ERR_LAYER_COUNT
  use cc_compliance_models, only: compliance, compliance_minus_one, valid_wavenumbers
  implicit none
  private

  ! Largest stack accepted (a graded coating approximated by layers needs tens).
  integer, parameter, public :: max_stack_layers = 1000
  ! Beyond x_top = k h_top = 400, C - 1 ~ x^2 exp(-2x) underflows: C = 1 exactly.
  real(dp), parameter :: x_saturation = 400.0_dp
  ! Thin/thick switch of section 12.
  real(dp), parameter :: x_thick = 1.0_dp

  ! Rows of a state.
  integer, parameter :: iu = 1, iw = 2, ir = 3, iz = 4

  ! A validated stack.
  type, public :: layer_stack
    integer :: n = 0
    logical :: rigid_base = .false.
    logical :: closed_form = .false.        ! one bonded layer: section 3
    type(material_pair) :: pair              ! used when closed_form
    real(dp) :: c_zero = 1.0_dp              ! C(0)
    real(dp) :: nu_base = 0.0_dp
    real(dp) :: q_small = 0.0_dp             ! below: small-q asymptote (stack_evaluate)
    real(dp), allocatable :: frac(:)         ! h_i / T
    real(dp), allocatable :: nu(:)
    real(dp), allocatable :: scale(:)        ! mu(below layer i) / mu_i (tau rescaling)
    logical, allocatable :: slip(:)          ! interface below layer i frictionless
  end type layer_stack

  ! A 2-D subspace of states: basis y with y(piv(b), :) = e_b.
  type :: subspace
    real(dp) :: y(4, 2) = 0.0_dp
    integer :: piv(2) = [ir, iz]
  end type subspace

  public :: make_layer_stack, stack_compliance, stack_compliance_minus_one, stack_evaluate

contains

  ! Validates the layers (top first) and the base; status codes of cc_elastic_constants.
  ! A layer's bad E or nu reports the film codes, the base's the substrate codes.
  pure subroutine make_layer_stack(thickness, youngs, poisson, slip_below, base_rigid, e_base, &
                                   nu_base, stack, status)
    real(dp), intent(in) :: thickness(:), youngs(:), poisson(:)
    logical, intent(in) :: slip_below(:)
    logical, intent(in) :: base_rigid
    real(dp), intent(in) :: e_base, nu_base
    type(layer_stack), intent(out) :: stack
    integer, intent(out) :: status
    integer :: n, i
    real(dp) :: hmax, e_below, nu_below

    n = size(thickness)
    status = CC_ERR_LAYER_COUNT
    if (n < 1 .or. n > max_stack_layers) return
    status = CC_ERR_ARGUMENT
    if (size(youngs) /= n .or. size(poisson) /= n .or. size(slip_below) /= n) return
    status = CC_OK
    do i = 1, n
      if (.not. (ieee_is_finite(thickness(i)) .and. thickness(i) > 0.0_dp)) then
        status = CC_ERR_THICKNESS
      else if (.not. validate_modulus(youngs(i))) then
        status = CC_ERR_FILM_MODULUS
      else if (.not. validate_poisson(poisson(i))) then
        status = CC_ERR_FILM_POISSON
      end if
      if (status /= CC_OK) return
    end do
    if (.not. base_rigid) then
      if (.not. validate_modulus(e_base)) then
        status = CC_ERR_SUBSTRATE_MODULUS
      else if (.not. validate_poisson(nu_base)) then
        status = CC_ERR_SUBSTRATE_POISSON
      end if
      if (status /= CC_OK) return
    end if

    stack%n = n
    stack%rigid_base = base_rigid
    stack%nu_base = 0.0_dp
    if (.not. base_rigid) stack%nu_base = nu_base
    ! Scaled by the largest thickness first so that the sum cannot overflow.
    hmax = maxval(thickness)
    stack%frac = thickness / hmax
    stack%frac = stack%frac / sum(stack%frac)
    stack%nu = poisson
    stack%slip = slip_below
    stack%q_small = min(1.0e-20_dp, 1.0e-40_dp / minval(stack%frac))
    allocate(stack%scale(n))
    do i = 1, n
      if (i < n) then
        e_below = youngs(i + 1)
        nu_below = poisson(i + 1)
      else if (base_rigid) then
        stack%scale(i) = 1.0_dp       ! a rigid base's subspaces do not depend on the scale
        cycle
      else
        e_below = e_base
        nu_below = nu_base
      end if
      stack%scale(i) = (e_below / youngs(i)) * ((1.0_dp + poisson(i)) / (1.0_dp + nu_below))
    end do
    if (base_rigid) then
      stack%c_zero = 0.0_dp
    else
      ! Product of ratios, as modulus_ratio: extreme moduli neither overflow nor underflow.
      stack%c_zero = (youngs(1) / e_base) * (((1.0_dp - nu_base) * (1.0_dp + nu_base)) &
                     / ((1.0_dp - poisson(1)) * (1.0_dp + poisson(1))))
    end if
    ! One bonded layer: the closed form of section 3 (and its exact homogeneous case).
    stack%closed_form = n == 1 .and. .not. slip_below(1)
    if (stack%closed_form) then
      call make_material_pair(youngs(1), poisson(1), e_base, nu_base, base_rigid, stack%pair, &
                              status)
    end if
  end subroutine make_layer_stack

  ! C(q) at every q >= 0.
  pure subroutine stack_compliance(stack, q, c, status)
    type(layer_stack), intent(in) :: stack
    real(dp), intent(in) :: q(:)
    real(dp), intent(out) :: c(size(q))
    integer, intent(out) :: status
    real(dp) :: f(size(q))
    c = 0.0_dp
    status = CC_ERR_ARGUMENT
    if (stack%n < 1 .or. .not. valid_wavenumbers(q)) return
    if (stack%closed_form) then
      call compliance(stack%pair, q, c, status)
    else
      call stack_evaluate(stack, q, c, f)
      status = CC_OK
    end if
  end subroutine stack_compliance

  ! C(q) - 1 at every q >= 0, without cancellation where C ~ 1 (thick top layer).
  pure subroutine stack_compliance_minus_one(stack, q, f, status)
    type(layer_stack), intent(in) :: stack
    real(dp), intent(in) :: q(:)
    real(dp), intent(out) :: f(size(q))
    integer, intent(out) :: status
    real(dp) :: c(size(q))
    f = 0.0_dp
    status = CC_ERR_ARGUMENT
    if (stack%n < 1 .or. .not. valid_wavenumbers(q)) return
    if (stack%closed_form) then
      call compliance_minus_one(stack%pair, q, f, status)
    else
      call stack_evaluate(stack, q, c, f)
      status = CC_OK
    end if
  end subroutine stack_compliance_minus_one

  ! C and C - 1 at one q >= 0 by the recursion of section 12 (any stack, also one layer).
  ! Below q_small (x = k h < 1e-40 in the thinnest layer) products of x-sized entries would
  ! underflow: C is then its small-q asymptote, C(0) on an elastic base (C - C(0) = O(q) is
  ! below rounding there) and C(q_s) (q/q_s)^p on a rigid base, where C ~ q^p (p = 1..3, C is
  ! analytic at q = 0), p read off C(q_s)/C(q_s/10). Relative accuracy is kept to underflow.
  elemental subroutine stack_evaluate(stack, q, c, f)
    type(layer_stack), intent(in) :: stack
    real(dp), intent(in) :: q
    real(dp), intent(out) :: c, f
    real(dp) :: c_s, c_s10, f_s
    integer :: p

    if (q <= 0.0_dp .or. (q < stack%q_small .and. .not. stack%rigid_base)) then
      c = stack%c_zero
      f = stack%c_zero - 1.0_dp
    else if (q < stack%q_small) then
      call stack_recursion(stack, stack%q_small, c_s, f_s)
      call stack_recursion(stack, 0.1_dp * stack%q_small, c_s10, f_s)
      c = 0.0_dp
      if (c_s > 0.0_dp .and. c_s10 > 0.0_dp) then
        p = min(3, max(1, nint(log10(c_s / c_s10))))
        c = c_s * (q / stack%q_small)**p
      end if
      f = c - 1.0_dp
    else
      call stack_recursion(stack, q, c, f)
    end if
  end subroutine stack_evaluate

  ! The recursion of section 12 at one q >= q_small.
  pure subroutine stack_recursion(stack, q, c, f)
    type(layer_stack), intent(in) :: stack
    real(dp), intent(in) :: q
    real(dp), intent(out) :: c, f
    type(subspace) :: s
    real(dp) :: e(4, 2), nu1
    integer :: i, n

    n = stack%n
    if (q * stack%frac(1) >= x_saturation) then
      c = 1.0_dp
      f = 0.0_dp
      return
    end if
    s = base_subspace(stack)
    do i = n, 1, -1
      ! Interface below layer i (a rigid base's subspace is already in layer units).
      if (i < n .or. .not. stack%rigid_base) then
        if (stack%slip(i)) then
          call slip_interface(s, stack%scale(i))
        else
          s%y(ir:iz, :) = stack%scale(i) * s%y(ir:iz, :)
          call rechart(s)
        end if
      end if
      if (i > 1) then
        if (q * stack%frac(i) < x_thick) then
          call thin_layer(stack%nu(i), q * stack%frac(i), s)
        else
          call thick_layer(stack%nu(i), q * stack%frac(i), s, e)
        end if
        call rechart(s)
      end if
    end do
    nu1 = stack%nu(1)
    if (q * stack%frac(1) < x_thick) then
      call thin_layer(nu1, q * stack%frac(1), s)
      c = surface_compliance(s%y, nu1)
      f = c - 1.0_dp
    else
      call thick_layer(nu1, q * stack%frac(1), s, e)
      call surface_from_reflection(nu1, e, c, f)
    end if
  end subroutine stack_recursion

  ! Admissible states at the top of the base, in the base's own units (rigid: any units).
  pure function base_subspace(stack) result(s)
    type(layer_stack), intent(in) :: stack
    type(subspace) :: s
    real(dp) :: nu
    s%y = 0.0_dp
    if (stack%rigid_base) then
      if (stack%slip(stack%n)) then
        s%y(iu, 1) = 1.0_dp           ! u_z = 0, s_rz = 0: U and tau_z free
        s%y(iz, 2) = 1.0_dp
        s%piv = [iu, iz]
      else
        s%y(ir, 1) = 1.0_dp           ! u = 0: compliance F = 0
        s%y(iz, 2) = 1.0_dp
        s%piv = [ir, iz]
      end if
    else
      ! Half-space compliance of section 12 with m = 1.
      nu = stack%nu_base
      s%y(iu, :) = [-(1.0_dp - nu), 0.5_dp * (1.0_dp - 2.0_dp * nu)]
      s%y(iw, :) = [0.5_dp * (1.0_dp - 2.0_dp * nu), -(1.0_dp - nu)]
      s%y(ir, :) = [1.0_dp, 0.0_dp]
      s%y(iz, :) = [0.0_dp, 1.0_dp]
      s%piv = [ir, iz]
    end if
  end function base_subspace

  ! Re-expresses the basis in the chart whose pivot rows have the largest |det|: by Cramer's
  ! rule every other entry then has modulus <= 1.
  pure subroutine rechart(s)
    type(subspace), intent(inout) :: s
    integer, parameter :: pair_i(6) = [1, 1, 1, 2, 2, 3], pair_j(6) = [2, 3, 4, 3, 4, 4]
    real(dp) :: y1(4), y2(4), det(6), inv11, inv12, inv21, inv22, rd
    integer :: p, bi, bj, k
    y1 = s%y(:, 1)
    y2 = s%y(:, 2)
    do p = 1, 6
      det(p) = y1(pair_i(p)) * y2(pair_j(p)) - y2(pair_i(p)) * y1(pair_j(p))
    end do
    p = maxloc(abs(det), dim=1)
    bi = pair_i(p)
    bj = pair_j(p)
    rd = 1.0_dp / det(p)
    inv11 = y2(bj) * rd
    inv12 = -y2(bi) * rd
    inv21 = -y1(bj) * rd
    inv22 = y1(bi) * rd
    do k = 1, 4
      s%y(k, 1) = y1(k) * inv11 + y2(k) * inv21
      s%y(k, 2) = y1(k) * inv12 + y2(k) * inv22
    end do
    s%y(bi, :) = [1.0_dp, 0.0_dp]
    s%y(bj, :) = [0.0_dp, 1.0_dp]
    s%piv = [bi, bj]
  end subroutine rechart

  ! Frictionless interface (section 12): below, the state with tau_r = 0; above, tau_r = 0,
  ! W and tau_z continuous (tau_z rescaled by `scale`), U free.
  pure subroutine slip_interface(s, scale)
    type(subspace), intent(inout) :: s
    real(dp), intent(in) :: scale
    real(dp) :: v(4), w, t
    v = s%y(:, 1) * s%y(ir, 2) - s%y(:, 2) * s%y(ir, 1)
    if (v(iw) == 0.0_dp .and. v(iz) == 0.0_dp) then
      ! The subspace already has tau_r = 0 (a slip interface right above another at q -> 0):
      ! its (W, tau_z) part is one column.
      if (max(abs(s%y(iw, 1)), abs(s%y(iz, 1))) >= max(abs(s%y(iw, 2)), abs(s%y(iz, 2)))) then
        v = s%y(:, 1)
      else
        v = s%y(:, 2)
      end if
    end if
    w = v(iw)
    t = v(iz) * scale
    s%y = 0.0_dp
    s%y(iu, 1) = 1.0_dp
    if (abs(w) >= abs(t)) then
      s%y(iw, 2) = 1.0_dp
      s%y(iz, 2) = t / w
      s%piv = [iu, iw]
    else
      s%y(iw, 2) = w / t
      s%y(iz, 2) = 1.0_dp
      s%piv = [iu, iz]
    end if
  end subroutine slip_interface

  ! y <- A y with A of section 12 at m = 1 (layer units).
  pure function apply_a(nu, y) result(z)
    real(dp), intent(in) :: nu, y(4, 2)
    real(dp) :: z(4, 2)
    real(dp) :: r, h
    r = nu / (1.0_dp - nu)
    h = (1.0_dp - 2.0_dp * nu) / (2.0_dp * (1.0_dp - nu))
    z(iu, :) = y(iw, :) + y(ir, :)
    z(iw, :) = -r * y(iu, :) + h * y(iz, :)
    z(ir, :) = (2.0_dp / (1.0_dp - nu)) * y(iu, :) + r * y(iz, :)
    z(iz, :) = -y(ir, :)
  end function apply_a

  ! Through a layer of x < 1 with the exact propagator (not re-charted): since (A^2 - I)^2 = 0,
  !   expm(-A x) = c0 I - c1 A + c2 A^2 - c3 A^3,  c2 = x sinh x / 2,  c0 = cosh x - c2,
  !   c3 = (x cosh x - sinh x)/2 (its series: no cancellation),  c1 = sinh x - c3.
  ! (Section 12 lists these with + signs: they are those of expm(+A x); the state at the top
  ! is expm(-A x) times the state at the bottom.)
  pure subroutine thin_layer(nu, x, s)
    real(dp), intent(in) :: nu, x
    type(subspace), intent(inout) :: s
    real(dp) :: a1(4, 2), a2(4, 2), a3(4, 2), c0, c1, c2, c3, sh, x2, term
    integer :: k
    sh = sinh(x)
    x2 = x * x
    term = x * x2 / 6.0_dp                      ! k x^(2k+1)/(2k+1)! at k = 1
    c3 = term
    do k = 2, 12
      term = term * x2 * real(k, dp) / (real(k - 1, dp) * real((2 * k) * (2 * k + 1), dp))
      c3 = c3 + term
    end do
    c2 = 0.5_dp * x * sh
    c0 = cosh(x) - c2
    c1 = sh - c3
    a1 = apply_a(nu, s%y)
    a2 = apply_a(nu, a1)
    a3 = apply_a(nu, a2)
    s%y = c0 * s%y - c1 * a1 + c2 * a2 - c3 * a3
  end subroutine thin_layer

  ! Through a layer of x >= 1 with local decaying exponentials (section 12). In the layer
  ! (m = 1, g = 3 - 4 nu, e = exp(-x)) the down pair, referred to the top (s = 0 there), is
  !   e^-s [ (1, 1, -2, -2),  (s, g + s, -2(1 - 2nu + s), -2(2(1 - nu) + s)) ]
  ! and the up pair, its mirror image (U, -W, -tau_r, tau_z at -s'), referred to the bottom.
  ! The bottom state must lie in the subspace below: L (D_b c_d + U_b c_u) = 0 with L the two
  ! chart equations, so c_u = X c_d, X = -(L U_b)^-1 (L D_b), and the top states are
  ! D_t + U_t X (not re-charted). Returns `e` = U_t X, the part reflected by what lies below.
  pure subroutine thick_layer(nu, x, s, e)
    type(subspace), intent(inout) :: s
    real(dp), intent(in) :: nu, x
    real(dp), intent(out) :: e(4, 2)
    real(dp) :: dt(4, 2), ut(4, 2), db(4, 2), ub(4, 2), lmat(2, 4), lu(2, 2), ld(2, 2)
    real(dp) :: xm(2, 2), det, ex, xe, g, p, r
    integer :: k(2), a, j

    g = 3.0_dp - 4.0_dp * nu
    p = 1.0_dp - 2.0_dp * nu
    r = 2.0_dp * (1.0_dp - nu)
    ex = exp(-x)
    xe = x * ex
    dt = down_pair_at_top(nu)
    ub(:, 1) = [1.0_dp, -1.0_dp, 2.0_dp, -2.0_dp]
    ub(:, 2) = [0.0_dp, -g, 2.0_dp * p, -2.0_dp * r]
    db(:, 1) = ex * dt(:, 1)
    db(:, 2) = [xe, g * ex + xe, -2.0_dp * (p * ex + xe), -2.0_dp * (r * ex + xe)]
    ut(:, 1) = ex * ub(:, 1)
    ut(:, 2) = [xe, -(g * ex + xe), 2.0_dp * (p * ex + xe), -2.0_dp * (r * ex + xe)]

    ! Chart equations: y(k_a) = sum_b y(k_a, b) y(piv_b) for the two non-pivot rows k_a.
    a = 0
    do j = 1, 4
      if (j /= s%piv(1) .and. j /= s%piv(2)) then
        a = a + 1
        k(a) = j
      end if
    end do
    lmat = 0.0_dp
    do a = 1, 2
      lmat(a, k(a)) = 1.0_dp
      lmat(a, s%piv(1)) = -s%y(k(a), 1)
      lmat(a, s%piv(2)) = -s%y(k(a), 2)
    end do
    lu = matmul(lmat, ub)
    ld = matmul(lmat, db)
    det = lu(1, 1) * lu(2, 2) - lu(1, 2) * lu(2, 1)
    xm(1, :) = -(lu(2, 2) * ld(1, :) - lu(1, 2) * ld(2, :)) / det
    xm(2, :) = -(lu(1, 1) * ld(2, :) - lu(2, 1) * ld(1, :)) / det
    e = matmul(ut, xm)
    s%y = dt + e
  end subroutine thick_layer

  ! The down pair at its own origin: the decaying states of a half-space of this material.
  pure function down_pair_at_top(nu) result(dt)
    real(dp), intent(in) :: nu
    real(dp) :: dt(4, 2)
    dt(:, 1) = [1.0_dp, 1.0_dp, -2.0_dp, -2.0_dp]
    dt(:, 2) = [0.0_dp, 3.0_dp - 4.0_dp * nu, -2.0_dp * (1.0_dp - 2.0_dp * nu), &
                -4.0_dp * (1.0_dp - nu)]
  end function down_pair_at_top

  ! C from a basis of the surface states: the state with tau_r = 0, tau_z = 1 has
  ! W = minor(W, tau_r)/minor(tau_z, tau_r), and C = -W/(1 - nu_top) (section 12).
  pure real(dp) function surface_compliance(y, nu) result(c)
    real(dp), intent(in) :: y(4, 2), nu
    c = -minor(y, iw, ir) / ((1.0_dp - nu) * minor(y, iz, ir))
  end function surface_compliance

  pure real(dp) function minor(y, a, b) result(d)
    real(dp), intent(in) :: y(4, 2)
    integer, intent(in) :: a, b
    d = y(a, 1) * y(b, 2) - y(a, 2) * y(b, 1)
  end function minor

  ! C and C - 1 at the top of a thick top layer, whose surface states are D_t + e. With
  ! Phi = minor(W, tau_r) + (1 - nu) minor(tau_z, tau_r), C - 1 = -Phi / ((1 - nu) minor(tau_z,
  ! tau_r)), and Phi(D_t) = 4(1 - nu) - 4(1 - nu) = 0 exactly, so Phi is formed from its terms
  ! in e only: C - 1 keeps its relative accuracy however small it is.
  pure subroutine surface_from_reflection(nu, e, c, f)
    real(dp), intent(in) :: nu, e(4, 2)
    real(dp), intent(out) :: c, f
    real(dp) :: d(4, 2), y(4, 2), den, phi
    d = down_pair_at_top(nu)
    y = d + e
    den = (1.0_dp - nu) * minor(y, iz, ir)
    phi = minor_change(iw, ir) + (1.0_dp - nu) * minor_change(iz, ir)
    f = -phi / den
    c = -minor(y, iw, ir) / den
  contains
    ! minor(d + e) - minor(d) without forming either.
    pure real(dp) function minor_change(a, b) result(dm)
      integer, intent(in) :: a, b
      dm = y(a, 1) * e(b, 2) + e(a, 1) * d(b, 2) - y(a, 2) * e(b, 1) - e(a, 2) * d(b, 1)
    end function minor_change
  end subroutine surface_from_reflection

end module cc_multilayer_compliance
