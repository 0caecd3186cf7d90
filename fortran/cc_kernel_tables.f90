! Tables of the kernel H(u) = int_0^inf f(q) cos(qu) dq, f = C - 1 (THEORY.md section 4), and of
! its antiderivative H1(u) = int_0^u H = int_0^inf f(q) sin(qu)/q dq, for one material pair.
!
! Method. The trapezoid rule in q (one FFTW DCT-I for H, one DST-I for H1) is limited by
! aliasing, and the aliasing comes from the kink of the even extension of f at q = 0 (odd
! Taylor terms f_1, f_3, ...; they also make H decay only like u^-2). We subtract
!   s(q) = exp(-b q) (c0 + c1 q + c3 q^3 + c5 q^5),
! whose value and first, third and fifth derivatives at 0 match those of f, and whose
! transforms are analytic:
!   int_0^inf q^n e^{-bq} cos(qu) dq = n! Re (b - iu)^-(n+1)
!   int_0^inf q^(n-1) e^{-bq} sin(qu) dq = (n-1)! Im (b - iu)^-n,   int_0^inf e^{-bq} sin(qu)/q dq = atan(u/b).
! The remainder r = f - s has r(0) = r'(0) = r'''(0) = r^(5)(0) = 0, so the even extension of r
! and the odd extension of r/q are smooth through C^6 and the aliasing error is
! ~ 7! |r_7| / (P - u)^8 with period P = 2 pi / dq (negligible). H and H1 are tabulated on
! [0, u_max] with step du and interpolated with 12-point Lagrange stencils (variant 0; the
! independent grid variants, see grid_parameters, use others) (H is analytic in
! |Im u| < 2 because f ~ q^2 exp(-2q)); beyond u_max the asymptotic series
!   H  ~ sum_k (-1)^(k+1) (2k+1)! f_(2k+1) / u^(2k+2)
!   H1 ~ (pi/2) f_0 + sum_k (-1)^k (2k)! f_(2k+1) / u^(2k+1)
! (integration by parts at q = 0; f_k = f^(k)(0)/k!) is used.
!
! Stiff films (E1*/E0* >~ 10) add a difficulty: D(q) has a real zero at q = -q0 with
! q0 ~ 0.5 E0*/E1* (5e-5 for a ratio 1e4), a pole of f with a small residue R that makes the
! Taylor radius at 0 tiny (f_k ~ R/q0^(k+1)) although f is smooth on [0, inf). A grid with
! dq > q0 cannot resolve it, and the 1/u asymptotics only start at u >> 1/q0. So the pole is
! removed first, with a damping factor and an analytic transform:
!   p(q) = R exp(-2q) / (q + q0),   int_0^inf p cos(qu) dq = R Re J,
!   int_0^inf p sin(qu)/q dq = (R/q0) (atan(u/2) - Im J),   J = exp(w q0) E1(w q0), w = 2 - iu,
! and everything above (Taylor matching by s, asymptotics) applies to f - p, whose Taylor
! coefficients come from the stable deflation of the series of M and D by (q + q0).
module cc_kernel_tables
  use, intrinsic :: iso_c_binding
  use cc_elastic_constants, only: dp, material_pair, CC_OK, CC_ERR_FFT, CC_ERR_ALLOCATION, &
                                  CC_ERR_ACCURACY, MODEL_HOMOGENEOUS
  use cc_compliance_models, only: compliance_minus_one, compliance_taylor, compliance_series, &
                                  max_taylor_order
  use cc_power_series, only: series_value, series_slope, series_deflate, series_quotient, &
                             series_product, exp_series
  use cc_exponential_integral, only: scaled_e1
  use cc_multilayer_compliance, only: layer_stack, stack_compliance_minus_one
  use cc_stack_series, only: stack_series
  implicit none
  private

  ! FFTW's planner (plan creation and destruction) is not thread-safe; execution is.
  interface
    subroutine cc_planner_lock() bind(C, name="cc_planner_lock")
    end subroutine cc_planner_lock
    subroutine cc_planner_unlock() bind(C, name="cc_planner_unlock")
    end subroutine cc_planner_unlock
  end interface
  include 'fftw3.f03'

  real(dp), parameter :: pi = 3.14159265358979323846264338327950288_dp

  ! Grid of variant 0 (cc_kernel_table_create): N = 2^17 trapezoid panels, period
  ! P = 2 pi / dq = 4 u_max, so dq = 6.1e-4, q_max = N dq = 80.4 (f ~ q^2 e^{-2q} and
  ! s ~ q^5 e^{-bq}, b >= 1, are below 1e-25 there), du = pi / (N dq) = P / (2N) = 0.0390625
  ! (exact in binary). Variants 1 to 3 (grid_parameters) are independent tables of the
  ! same H for a-posteriori estimates of the table's effect on its users: other N, period,
  ! u-step and range, and another Lagrange stencil, so that their interpolation, FFT
  ! rounding and aliasing errors differ from variant 0's.
  integer, parameter, public :: n_grid_variants = 4
  integer, parameter :: max_stencil = 16
  ! Poles closer to 0 than this are removed analytically; the damping rate of p(q).
  real(dp), parameter :: pole_threshold = 0.05_dp
  ! Compact grids (u_range, build_table): their short range and period need a Taylor radius
  ! >~ 1, so poles up to this are removed (stiff films, E1*/E0* >~ 2).
  real(dp), parameter :: compact_pole_threshold = 0.5_dp
  ! Smallest compact grid: 2^11 panels (times a stack's refinement), u_max = 40.
  integer, parameter :: min_compact_panels = 2**11
  real(dp), parameter :: pole_damping = 2.0_dp
  ! Order of the internal series used for the pole removal (D and M are entire: the terms
  ! at order 40 are ~ 4^40/40! relative, negligible).
  integer, parameter :: long_order = 40
  ! Target of the issue: |H - H_exact| <= 1e-10 max|H|.
  real(dp), parameter :: relative_target = 1.0e-10_dp

  ! FFTW plans kept for the next table of the same transform (aligned_r2r): planning the full
  ! grid's REDFT00 of 2^17 + 1 points costs ~1.6 ms each time (its DST-I as much), a tenth of a
  ! one-film table. An FFTW_ESTIMATE plan depends only on the length, the kind and the arrays'
  ! alignment (always FFTW's own), so a kept plan is the plan a new planning would make: no
  ! digit changes. Read and written under the planner lock; executed (fftw_execute_r2r on new
  ! arrays) without it, which FFTW allows from any number of threads. Lengths above
  ! max_kept_length (stacks refined 4x and more) are planned each time, their plans' memory
  ! not kept for the process's life.
  integer, parameter :: max_kept_plans = 16
  integer, parameter :: max_kept_length = 2**18 + 1
  integer :: kept_plans = 0
  integer :: kept_length(max_kept_plans) = 0
  integer(C_FFTW_R2R_KIND) :: kept_kind(max_kept_plans) = 0
  type(c_ptr) :: kept_plan(max_kept_plans) = c_null_ptr

  type, public :: kernel_table
    real(dp) :: du = 0.0_dp
    real(dp) :: u_max = 0.0_dp            ! tabulated range [0, u_max]; asymptotics beyond
    real(dp) :: c_zero = 1.0_dp
    real(dp) :: half_integral = 0.0_dp    ! int_0^inf H = (pi/2) f_0
    real(dp) :: abs_accuracy = 0.0_dp     ! estimated max |H - H_exact| (also bounds H1's)
    real(dp) :: max_abs_h = 0.0_dp
    real(dp) :: decay_rate = 0.0_dp       ! b of s(q) (diagnostic)
    real(dp) :: taylor(0:max_taylor_order) = 0.0_dp   ! of f - p (= f without a pole)
    real(dp) :: pole_q0 = 1.0_dp          ! pole of f at q = -pole_q0 (removed when residue /= 0)
    real(dp) :: pole_residue = 0.0_dp
    integer :: n_nodes = 0
    integer :: grid_variant = 0
    integer :: stencil = 12                ! Lagrange points of the interpolation
    integer :: stencil_left = 5            ! the stencil of [i, i+1] is i-left .. i-left+stencil-1
    real(dp) :: lagrange_weight(0:max_stencil - 1) = 0.0_dp   ! 1 / prod_{l /= j} (j - l)
    real(dp), allocatable :: h(:)         ! H(k du),  k = 0 .. n_nodes-1
    real(dp), allocatable :: h1(:)        ! H1(k du) (not on compact tables)
    logical :: has_h1 = .true.
  end type kernel_table

  ! What a table is built from: one film (material_pair, THEORY.md section 3) or a stack
  ! (section 12). For a stack the grid is refined `refine` times (refine >= T/h_top, a power of
  ! 2): C - 1 decays like exp(-2 q h_top/T), so q_max = refine * 80 reaches ~ 80 T/h_top and
  ! H is analytic only in |Im u| < 2 h_top/T, so du and the interpolation strip shrink by
  ! `refine` (the same du/strip as one film: the same interpolation error).
  type :: kernel_source
    logical :: is_stack = .false.
    type(material_pair) :: pair
    type(layer_stack) :: stack
    integer :: refine = 1
  end type kernel_source

  ! Finest stack refinement: 2^22 panels on variant 0 (top layer >= T/32); thinner top
  ! layers report CC_ERR_ACCURACY rather than a table that cannot meet its target.
  integer, parameter, public :: max_stack_refine = 32

  public :: build_kernel_table_variant, build_stack_kernel_table_variant, evaluate_kernel_table, &
            evaluate_kernel_h, evaluate_kernel_h_many

contains

  ! Grid of a table variant: N trapezoid panels, tabulated range [0, u_max] (asymptotic
  ! series beyond), period P = 2 pi / dq (du = P / (2N), q_max = N dq = pi / du), and the
  ! Lagrange stencil. Every variant keeps q_max >= 70 (f - p - s below 1e-25 there), the
  ! nearest alias >= 2.3 u_max away and u_max >= 2000 (a/t = 1000 needs u <= 2000). Variants
  ! 1 to 3 interpolate with 13-14 points: their estimated accuracy is ~10x better than
  ! variant 0's, so that a difference from them measures variant 0's error.
  pure subroutine grid_parameters(variant, n, u_max, period, stencil, stencil_left)
    integer, intent(in) :: variant
    integer, intent(out) :: n, stencil, stencil_left
    real(dp), intent(out) :: u_max, period
    select case (variant)
    case (1)      ! du = 0.04028, q_max = 78.0; 14 points shifted right (i-5 .. i+8)
      n = 3 * 2**15
      u_max = 2400.0_dp
      period = 3.3_dp * u_max
      stencil = 14
      stencil_left = 5
    case (2)      ! du = 0.03571, q_max = 88.0; 14 points, shifted left (i-7 .. i+6)
      n = 5 * 2**15
      u_max = 2600.0_dp
      period = 4.5_dp * u_max
      stencil = 14
      stencil_left = 7
    case (3)      ! du = 0.02886, q_max = 108.9; 13 points (i-6 .. i+6)
      n = 9 * 2**14
      u_max = 2300.0_dp
      period = 3.7_dp * u_max
      stencil = 13
      stencil_left = 6
    case default  ! 0: du = 0.0390625, q_max = 80.4; 12 points centred (i-5 .. i+6)
      n = 2**17
      u_max = 2560.0_dp
      period = 4.0_dp * u_max
      stencil = 12
      stencil_left = 5
    end select
  end subroutine grid_parameters

  ! Coefficients c0, c1, c3, c5 of s(q) for decay rate b: match s_k = f_k for k = 0, 1, 3, 5
  ! (s_k = sum_j c_j (-b)^(k-j)/(k-j)!, a triangular system).
  pure function subtraction_coefficients(f, b) result(c)
    real(dp), intent(in) :: f(0:), b
    real(dp) :: c(0:5)
    c = 0.0_dp
    c(0) = f(0)
    c(1) = f(1) + b * c(0)
    c(3) = f(3) + b**3 * c(0) / 6.0_dp - b**2 * c(1) / 2.0_dp
    c(5) = f(5) + b**5 * c(0) / 120.0_dp - b**4 * c(1) / 24.0_dp - b**2 * c(3) / 2.0_dp
  end function subtraction_coefficients

  ! Taylor coefficient k of s(q).
  pure real(dp) function subtraction_taylor(c, b, k) result(sk)
    real(dp), intent(in) :: c(0:5), b
    integer, intent(in) :: k
    integer :: j
    sk = 0.0_dp
    do j = 0, min(k, 5)
      if (j == 2 .or. j == 4) cycle
      sk = sk + c(j) * (-b)**(k - j) / gamma(real(k - j + 1, dp))
    end do
  end function subtraction_taylor

  elemental real(dp) function subtraction_value(c0, c1, c3, c5, b, q) result(s)
    real(dp), intent(in) :: c0, c1, c3, c5, b, q
    real(dp) :: q2
    q2 = q * q
    s = exp(-b * q) * (c0 + q * (c1 + q2 * (c3 + q2 * c5)))
  end function subtraction_value

  ! Taylor coefficients of s for decay rate b, and the estimated table error it leads to:
  ! aliasing of the unmatched odd terms k >= 7 plus rounding in r = f - p - s.
  pure real(dp) function subtraction_error(r_taylor, b, s_max, distance) result(err)
    real(dp), intent(in) :: r_taylor(0:), b, s_max, distance   ! distance: P - u_max
    real(dp) :: c(0:5)
    integer :: k
    c = subtraction_coefficients(r_taylor, b)
    err = 16.0_dp * epsilon(1.0_dp) * s_max
    do k = 7, max_taylor_order, 2
      err = err + 4.0_dp * gamma(real(k + 1, dp)) &
            * abs(r_taylor(k) - subtraction_taylor(c, b, k)) / distance**(k + 1)
    end do
  end function subtraction_error

  ! Decay rate b of s among 1, sqrt(2), 2, ..., 512: the one with the smallest estimated
  ! error (a small b makes s wide and, for a Taylor radius << 1, huge; a large b enlarges
  ! the unmatched r_7).
  subroutine choose_decay_rate(src, table, r_taylor, distance, b)
    type(kernel_source), intent(in) :: src
    type(kernel_table), intent(in) :: table
    real(dp), intent(in) :: r_taylor(0:), distance
    real(dp), intent(out) :: b
    integer, parameter :: n_probe = 240
    real(dp) :: q(n_probe), fq(n_probe), c(0:5), s_max, best, trial, err
    integer :: i, j, status

    do i = 1, n_probe
      q(i) = 1.0e-5_dp * (6.0e6_dp * real(src%refine, dp))**(real(i - 1, dp) &
             / real(n_probe - 1, dp))
    end do
    call source_minus_one(src, q, fq, status)
    fq = fq - pole_value(table, q)
    best = huge(1.0_dp)
    b = 1.0_dp
    do j = 0, 18
      trial = 2.0_dp**(0.5_dp * real(j, dp))
      c = subtraction_coefficients(r_taylor, trial)
      s_max = max(maxval(abs(subtraction_value(c(0), c(1), c(3), c(5), trial, q))), &
                  maxval(abs(fq)))
      err = subtraction_error(r_taylor, trial, s_max, distance)
      if (err < best) then
        best = err
        b = trial
      end if
    end do
  end subroutine choose_decay_rate

  elemental real(dp) function pole_value(table, q) result(p)
    type(kernel_table), intent(in) :: table
    real(dp), intent(in) :: q
    p = 0.0_dp
    if (table%pole_residue /= 0.0_dp) &
      p = table%pole_residue * exp(-pole_damping * q) / (q + table%pole_q0)
  end function pole_value

  ! Analytic transforms of p (zero when no pole is removed).
  elemental subroutine pole_transforms(table, u, h, h1)
    type(kernel_table), intent(in) :: table
    real(dp), intent(in) :: u
    real(dp), intent(out) :: h, h1
    complex(dp) :: j
    h = 0.0_dp
    h1 = 0.0_dp
    if (table%pole_residue == 0.0_dp) return
    j = scaled_e1(cmplx(pole_damping, -u, dp) * table%pole_q0)
    h = table%pole_residue * real(j, dp)
    h1 = table%pole_residue / table%pole_q0 * (atan(u / pole_damping) - aimag(j))
  end subroutine pole_transforms

  ! Looks for a real zero -q0 of D with 0 < q0 < pole_threshold (Newton on the series of D
  ! from -D(0)/D'(0)); if found, stores q0 and the residue R = M(-q0)/D'(-q0) of f and
  ! returns the Taylor coefficients of f - p; else those of f.
  subroutine remove_near_pole(src, table, r_taylor, threshold)
    type(kernel_source), intent(in) :: src
    type(kernel_table), intent(inout) :: table
    real(dp), intent(out) :: r_taylor(0:max_taylor_order)
    real(dp), intent(in) :: threshold
    real(dp), dimension(0:long_order) :: mser, dser, dred, nred, quotient
    real(dp) :: q, step, residue
    integer :: it, status
    logical :: converged

    call source_taylor(src, r_taylor, status)
    table%pole_residue = 0.0_dp
    call source_series(src, mser, dser)
    if (dser(1) <= 0.0_dp .or. dser(0) <= 0.0_dp) return
    q = -dser(0) / dser(1)
    if (q < -threshold) return
    converged = .false.
    do it = 1, 60
      step = series_value(dser, q) / series_slope(dser, q)
      q = q - step
      if (abs(step) <= 4.0_dp * epsilon(1.0_dp) * abs(q)) then
        converged = .true.
        exit
      end if
    end do
    if (.not. converged .or. q >= 0.0_dp .or. q < -threshold) return
    table%pole_q0 = -q
    dred = series_deflate(dser, table%pole_q0)                 ! D / (q + q0)
    ! residue of f at -q0 is M(-q0)/D'(-q0) = M(-q0)/Dtilde(-q0); p's is R exp(2 q0)
    residue = series_value(mser, q) / series_value(dred, q) * exp(pole_damping * q)
    table%pole_residue = residue
    ! f - p = [M - R exp(-2q) D/(q+q0)] / D = Ntilde / Dtilde with both deflated by (q + q0)
    nred = series_deflate(mser - residue * series_product(exp_series(-pole_damping, long_order), &
                                                        dred), table%pole_q0)
    quotient = series_quotient(nred, dred)
    r_taylor = quotient(0:max_taylor_order)
  end subroutine remove_near_pole

  ! Builds the table on the grid of `variant` (0 .. n_grid_variants - 1, see grid_parameters)
  ! for a validated pair. FFTW planning is serialized by cc_planner_lock.c, so any number of
  ! threads may build tables; evaluation is read-only. u_range: a compact grid (build_table);
  ! h_only: no H1 (build_table).
  subroutine build_kernel_table_variant(pair, variant, table, status, u_range, h_only)
    type(material_pair), intent(in) :: pair
    integer, intent(in) :: variant
    type(kernel_table), intent(out) :: table
    integer, intent(out) :: status
    real(dp), intent(in), optional :: u_range
    logical, intent(in), optional :: h_only
    type(kernel_source) :: src
    src%pair = pair
    call build_table(src, variant, table, status, u_range, h_only)
  end subroutine build_kernel_table_variant

  ! The same table for a validated stack of more than one layer or with a slip flag (one
  ! bonded layer: build_kernel_table_variant, so that its table is unchanged bit for bit).
  subroutine build_stack_kernel_table_variant(stack, variant, table, status, u_range, h_only)
    type(layer_stack), intent(in) :: stack
    integer, intent(in) :: variant
    type(kernel_table), intent(out) :: table
    integer, intent(out) :: status
    real(dp), intent(in), optional :: u_range
    logical, intent(in), optional :: h_only
    type(kernel_source) :: src
    src%is_stack = .true.
    src%stack = stack
    src%refine = 1
    do while (real(src%refine, dp) * stack%frac(1) < 1.0_dp)
      src%refine = 2 * src%refine
    end do
    status = CC_ERR_ACCURACY
    if (src%refine > max_stack_refine) return
    call build_table(src, variant, table, status, u_range, h_only)
  end subroutine build_stack_kernel_table_variant

  subroutine source_minus_one(src, q, f, status)
    type(kernel_source), intent(in) :: src
    real(dp), intent(in) :: q(:)
    real(dp), intent(out) :: f(size(q))
    integer, intent(out) :: status
    if (src%is_stack) then
      call stack_compliance_minus_one(src%stack, q, f, status)
    else
      call compliance_minus_one(src%pair, q, f, status)
    end if
  end subroutine source_minus_one

  subroutine source_series(src, mser, dser)
    type(kernel_source), intent(in) :: src
    real(dp), intent(out) :: mser(0:long_order), dser(0:long_order)
    if (src%is_stack) then
      call stack_series(src%stack, long_order, mser, dser)
    else
      call compliance_series(src%pair, long_order, mser, dser)
    end if
  end subroutine source_series

  ! Taylor coefficients of f = C - 1 at q = 0, orders 0 .. max_taylor_order.
  subroutine source_taylor(src, f, status)
    type(kernel_source), intent(in) :: src
    real(dp), intent(out) :: f(0:max_taylor_order)
    integer, intent(out) :: status
    real(dp), dimension(0:long_order) :: mser, dser, quotient
    if (src%is_stack) then
      call stack_series(src%stack, long_order, mser, dser)
      quotient = series_quotient(mser, dser)
      f = quotient(0:max_taylor_order)
      f(0) = src%stack%c_zero - 1.0_dp          ! exact
      status = CC_OK
    else
      call compliance_taylor(src%pair, max_taylor_order, f, status)
    end if
  end subroutine source_taylor

  ! Builds the table of `src` on the grid of `variant`.
  ! u_range (variant 0 only): a compact grid, same du, stencil and q_max, whose period and
  ! range halve while the range still covers u_range (>= 40): a solver that never needs H
  ! beyond u_range skips most of the FFT work; the asymptotic series is used beyond, as usual.
  ! Such a table has no H1 (not computed: half the FFT work; evaluate_kernel_h only).
  ! h_only: any grid without H1 (its DST-I and the planning of it skipped); H, its accuracy
  ! estimate and every other field are those of the table with H1, bit for bit.
  ! One r2r transform of length n on FFTW-allocated (SIMD-aligned) copies of x and y:
  ! FFTW_ESTIMATE picks its codelets by the arrays' alignment, so transforming Fortran-allocated
  ! arrays made a table (and every printed digit after it) depend on the heap state, e.g. on
  ! which thread built the table.
  subroutine aligned_r2r(n, kind, x, y, status)
    integer, intent(in) :: n
    integer(C_FFTW_R2R_KIND), intent(in) :: kind
    real(c_double), intent(in) :: x(0:)
    real(c_double), intent(inout) :: y(0:)
    integer, intent(out) :: status
    type(c_ptr) :: p_in, p_out, plan
    real(c_double), pointer :: a_in(:), a_out(:)
    logical :: kept
    status = CC_ERR_ALLOCATION
    p_in = fftw_alloc_real(int(n, c_size_t))
    p_out = fftw_alloc_real(int(n, c_size_t))
    if (c_associated(p_in) .and. c_associated(p_out)) then
      call c_f_pointer(p_in, a_in, [n])
      call c_f_pointer(p_out, a_out, [n])
      call cc_planner_lock()
      call kept_or_new_plan(n, kind, p_in, p_out, plan, kept)
      call cc_planner_unlock()
      status = CC_ERR_FFT
      if (c_associated(plan)) then
        a_in = x(0:n - 1)
        call fftw_execute_r2r(plan, a_in, a_out)
        y(0:n - 1) = a_out
        if (.not. kept) then
          call cc_planner_lock()
          call fftw_destroy_plan(plan)
          call cc_planner_unlock()
        end if
        status = CC_OK
      end if
    end if
    if (c_associated(p_in)) call fftw_free(p_in)
    if (c_associated(p_out)) call fftw_free(p_out)
  end subroutine aligned_r2r

  ! The kept plan of (n, kind), else a new one, kept while there is room (kept = .true.: not
  ! to be destroyed). Caller holds the planner lock.
  subroutine kept_or_new_plan(n, kind, p_in, p_out, plan, kept)
    integer, intent(in) :: n
    integer(C_FFTW_R2R_KIND), intent(in) :: kind
    type(c_ptr), intent(in) :: p_in, p_out     ! FFTW-allocated, n values each
    type(c_ptr), intent(out) :: plan
    logical, intent(out) :: kept
    real(c_double), pointer :: a_in(:), a_out(:)
    integer :: k
    do k = 1, kept_plans
      if (kept_length(k) == n .and. kept_kind(k) == kind) then
        plan = kept_plan(k)
        kept = .true.
        return
      end if
    end do
    call c_f_pointer(p_in, a_in, [n])
    call c_f_pointer(p_out, a_out, [n])
    plan = fftw_plan_r2r_1d(int(n, c_int), a_in, a_out, kind, FFTW_ESTIMATE)
    kept = c_associated(plan) .and. n <= max_kept_length .and. kept_plans < max_kept_plans
    if (kept) then
      kept_plans = kept_plans + 1
      kept_length(kept_plans) = n
      kept_kind(kept_plans) = kind
      kept_plan(kept_plans) = plan
    end if
  end subroutine kept_or_new_plan

  subroutine build_table(src, variant, table, status, u_range, h_only)
    type(kernel_source), intent(in) :: src
    integer, intent(in) :: variant
    type(kernel_table), intent(out) :: table
    integer, intent(out) :: status
    real(dp), intent(in), optional :: u_range
    logical, intent(in), optional :: h_only

    real(c_double), allocatable :: work_in(:), work_out(:)
    real(dp), allocatable :: q(:), r(:), fq(:)
    real(dp) :: f(0:max_taylor_order), rt(0:max_taylor_order), c(0:5), b, dq, du
    real(dp) :: alias_h, alias_h1, rounding_h, rounding_h1, interp_h, interp_h1, tail, strip
    real(dp) :: cauchy_bound, lebesgue, distance, rk, hs, h1s, hp, h1p, u
    complex(dp) :: z, zk
    real(dp) :: u_table, period, t_probe, product
    integer :: n, k, j, ierr, stencil, stencil_left, i_probe
    logical :: compact

    status = CC_OK
    call grid_parameters(variant, n, u_table, period, stencil, stencil_left)
    n = n * src%refine
    compact = present(u_range) .and. variant == 0
    if (compact) then
      do while (n > min_compact_panels * src%refine .and. 0.5_dp * u_table >= u_range)
        n = n / 2
        u_table = 0.5_dp * u_table
        period = 0.5_dp * period
      end do
    end if
    table%has_h1 = .not. compact
    if (present(h_only)) then
      if (h_only) table%has_h1 = .false.
    end if
    table%grid_variant = variant
    table%stencil = stencil
    table%stencil_left = stencil_left
    do j = 0, stencil - 1      ! barycentric weights (-1)^(s-1-j) / (j! (s-1-j)!)
      table%lagrange_weight(j) = (-1.0_dp)**(stencil - 1 - j) &
          / (gamma(real(j + 1, dp)) * gamma(real(stencil - j, dp)))
    end do
    dq = 2.0_dp * pi / period
    du = pi / (real(n, dp) * dq)
    table%du = du
    table%u_max = u_table
    table%n_nodes = nint(u_table / du) + stencil + 1
    call source_taylor(src, f, status)
    if (status /= CC_OK) return
    table%c_zero = 1.0_dp + f(0)
    table%half_integral = 0.5_dp * pi * f(0)

    if (table%has_h1) then
      allocate(table%h(0:table%n_nodes - 1), table%h1(0:table%n_nodes - 1), stat=ierr)
    else
      allocate(table%h(0:table%n_nodes - 1), stat=ierr)
    end if
    if (ierr /= 0) then
      status = CC_ERR_ALLOCATION
      return
    end if
    table%h = 0.0_dp
    if (table%has_h1) table%h1 = 0.0_dp
    if (.not. src%is_stack) then
      if (src%pair%model == MODEL_HOMOGENEOUS) return      ! f = 0 exactly: H = H1 = 0
    end if

    if (compact) then
      call remove_near_pole(src, table, rt, compact_pole_threshold)
    else
      call remove_near_pole(src, table, rt, pole_threshold)
    end if
    table%taylor = rt
    call choose_decay_rate(src, table, rt, period - u_table, b)
    table%decay_rate = b
    c = subtraction_coefficients(rt, b)

    if (compact) then
      allocate(q(0:n), r(0:n), fq(0:n), work_in(0:2 * n - 1), work_out(0:2 * n - 1), stat=ierr)
    else
      allocate(q(0:n), r(0:n), fq(0:n), work_in(0:n), work_out(0:n), stat=ierr)
    end if
    if (ierr /= 0) then
      status = CC_ERR_ALLOCATION
      return
    end if
    q = [(real(j, dp) * dq, j = 0, n)]
    call source_minus_one(src, q, fq, status)
    if (status /= CC_OK) return
    r = fq - pole_value(table, q) - subtraction_value(c(0), c(1), c(3), c(5), b, q)
    r(0) = 0.0_dp                                     ! exact by construction

    ! H_r(k du) = (dq/2) DCT-I(r)_k  (trapezoid rule, endpoints halved by REDFT00)
    if (compact) then
      ! The DCT-I as the real DFT (R2HC, real parts first) of the even extension of r with
      ! period 2N: the same sums, and planning a power-of-2 R2HC costs a fraction of planning
      ! a REDFT00 (~0.5 against ~1.5 ms, most of a one-radius call once the grid is compact).
      work_in(0:n) = r
      work_in(n + 1:2 * n - 1) = r(n - 1:1:-1)
      call aligned_r2r(2 * n, FFTW_R2HC, work_in, work_out, status)
    else
      work_in = r
      call aligned_r2r(n + 1, FFTW_REDFT00, work_in, work_out, status)
    end if
    if (status /= CC_OK) return
    table%h = 0.5_dp * dq * work_out(0:table%n_nodes - 1)

    if (table%has_h1) then
    ! H1_r(k du) = (dq/2) DST-I(r/q)_(k-1): samples at q_1 .. q_(N-1) (r/q -> 0 at both ends)
    work_in(0:n - 2) = r(1:n - 1) / q(1:n - 1)
    call aligned_r2r(n - 1, FFTW_RODFT00, work_in, work_out, status)
    if (status /= CC_OK) return
    table%h1(0) = 0.0_dp
    table%h1(1:table%n_nodes - 1) = 0.5_dp * dq * work_out(0:table%n_nodes - 2)
    end if

    ! Add the analytic transforms of s and p.
    do k = 0, table%n_nodes - 1
      u = real(k, dp) * du
      z = 1.0_dp / cmplx(b, -u, dp)                 ! 1/(b - iu)
      zk = z
      hs = c(0) * real(zk, dp)
      h1s = c(0) * atan(u / b) + c(1) * aimag(zk)
      zk = zk * z
      hs = hs + c(1) * real(zk, dp)
      zk = zk * z
      h1s = h1s + 2.0_dp * c(3) * aimag(zk)
      zk = zk * z
      hs = hs + 6.0_dp * c(3) * real(zk, dp)
      zk = zk * z
      h1s = h1s + 24.0_dp * c(5) * aimag(zk)
      zk = zk * z
      hs = hs + 120.0_dp * c(5) * real(zk, dp)
      call pole_transforms(table, u, hp, h1p)
      table%h(k) = table%h(k) + hs + hp
      if (table%has_h1) table%h1(k) = table%h1(k) + h1s + h1p
    end do
    table%max_abs_h = maxval(abs(table%h))

    ! ---- accuracy estimate --------------------------------------------------------------
    ! Aliasing: the first unmatched odd Taylor terms r_k of r (k = 7, 9, ...) give
    ! |H_r(v)| ~ k! |r_k| / v^(k+1) and |H1_r(v)| ~ (k-1)! |r_k| / v^k; the nearest alias of
    ! u <= u_max is at distance >= P - u_max.
    distance = period - u_table
    alias_h = 0.0_dp
    alias_h1 = 0.0_dp
    do k = 7, max_taylor_order, 2
      rk = abs(rt(k) - subtraction_taylor(c, b, k))
      alias_h = alias_h + 4.0_dp * gamma(real(k + 1, dp)) * rk / distance**(k + 1)
      alias_h1 = alias_h1 + 4.0_dp * gamma(real(k, dp)) * rk / distance**k
    end do
    ! Rounding in the samples (f - p - s) and the transforms.
    rounding_h = 16.0_dp * epsilon(1.0_dp) * (dq * sum(abs(fq)) + maxval(abs(table%h)))
    rounding_h1 = 0.0_dp
    if (table%has_h1) rounding_h1 = 16.0_dp * epsilon(1.0_dp) &
                                     * (dq * sum(abs(r(1:n - 1) / q(1:n - 1))) + maxval(abs(table%h1)))
    ! Interpolation: |H(u + iy)| <= int |f| cosh(qy) dq =: M for |y| <= strip < 2, hence
    ! |H^(m)|/m! <= M / strip^m and the error is <= M (du/strip)^m max_t prod |t - k|.
    strip = 1.5_dp / real(src%refine, dp)
    cauchy_bound = dq * sum(abs(fq) * cosh(strip * q))
    ! max over t in [0, 1] of prod |t - k| (t = 1/2 for a centred stencil)
    lebesgue = 0.0_dp
    do i_probe = 0, 64
      t_probe = real(i_probe, dp) / 64.0_dp
      product = 1.0_dp
      do k = -stencil_left, stencil - 1 - stencil_left
        product = product * abs(t_probe - real(k, dp))
      end do
      lebesgue = max(lebesgue, product)
    end do
    interp_h = cauchy_bound * lebesgue * (du / strip)**stencil
    interp_h1 = interp_h * strip / real(stencil, dp)
    ! Asymptotic series beyond u_max: size of its last term.
    tail = gamma(real(max_taylor_order + 1, dp)) * abs(rt(max_taylor_order)) &
           / u_table**(max_taylor_order + 1)
    table%abs_accuracy = alias_h + rounding_h + interp_h + tail
    ! Compact grids: the tail and alias estimates above are the last terms of series in
    ! 1/u_max^2; they are trusted only where those series still fall fast (ratio of the last
    ! two terms <= 0.1; else a near singularity of f makes them understate: a longer grid).
    if (compact) then
      if (gamma(real(max_taylor_order + 1, dp)) * abs(rt(max_taylor_order)) > 0.1_dp &
          * gamma(real(max_taylor_order - 1, dp)) * abs(rt(max_taylor_order - 2)) * u_table**2) &
        status = CC_ERR_ACCURACY
    end if
    if (table%abs_accuracy > relative_target * table%max_abs_h) status = CC_ERR_ACCURACY
    if (table%has_h1) then
      if (alias_h1 + rounding_h1 + interp_h1 + tail > relative_target * maxval(abs(table%h1))) &
        status = CC_ERR_ACCURACY
    end if
  end subroutine build_table

  ! Table value at integer node index j (any sign): H even, H1 odd.
  pure real(dp) function node_value(values, j, odd) result(v)
    real(dp), intent(in) :: values(0:)
    integer, intent(in) :: j
    logical, intent(in) :: odd
    if (j >= 0) then
      v = values(j)
    else if (odd) then
      v = -values(-j)
    else
      v = values(-j)
    end if
  end function node_value

  ! Lagrange basis l_j(t) = w_j prod_{m /= j} (t - k_m) on the nodes k_j = j - left,
  ! j = 0 .. stencil-1, by prefix and suffix products: no divisions (each costs several
  ! multiplications), and valid at a node too, where the other l_j vanish.
  pure subroutine lagrange_basis(weight, stencil, left, t, ell)
    real(dp), intent(in) :: weight(0:max_stencil - 1)
    integer, intent(in) :: stencil, left
    real(dp), intent(in) :: t
    real(dp), intent(out) :: ell(0:max_stencil - 1)
    real(dp) :: d(0:max_stencil - 1), suffix(0:max_stencil - 1), prefix
    integer :: j

    do j = 0, stencil - 1
      d(j) = t - real(j - left, dp)
    end do
    suffix(stencil - 1) = 1.0_dp
    do j = stencil - 2, 0, -1
      suffix(j) = suffix(j + 1) * d(j + 1)
    end do
    prefix = 1.0_dp
    do j = 0, stencil - 1
      ell(j) = (weight(j) * prefix) * suffix(j)
      prefix = prefix * d(j)
    end do
  end subroutine lagrange_basis

  ! The default stencil (12 nodes, k = -5 .. 6) with constant bounds and short dependency
  ! chains, so that it unrolls into registers and consecutive evaluations overlap: the
  ! nodes 5-m and 6+m pair up (their product q_m), and l_j = w_j (t - k_partner) times the
  ! product of the other five q, taken as a balanced tree.
  pure subroutine lagrange_basis_12(weight, t, ell)
    real(dp), intent(in) :: weight(0:max_stencil - 1)
    real(dp), intent(in) :: t
    real(dp), intent(out) :: ell(0:max_stencil - 1)
    real(dp) :: d(0:11), q(0:5), r01, r23, r45, others(0:5)
    integer :: j, m

    do j = 0, 11
      d(j) = t - real(j - 5, dp)
    end do
    do m = 0, 5
      q(m) = d(5 - m) * d(6 + m)
    end do
    r01 = q(0) * q(1)
    r23 = q(2) * q(3)
    r45 = q(4) * q(5)
    others(0) = q(1) * (r23 * r45)
    others(1) = q(0) * (r23 * r45)
    others(2) = q(3) * (r01 * r45)
    others(3) = q(2) * (r01 * r45)
    others(4) = q(5) * (r01 * r23)
    others(5) = q(4) * (r01 * r23)
    do m = 0, 5
      ell(5 - m) = (weight(5 - m) * d(6 + m)) * others(m)
      ell(6 + m) = (weight(6 + m) * d(5 - m)) * others(m)
    end do
  end subroutine lagrange_basis_12

  ! sum_j l_j x_j over 12 nodes as a balanced tree (short chain, fixed order).
  pure real(dp) function stencil_sum_12(ell, x) result(s)
    real(dp), intent(in) :: ell(0:max_stencil - 1)
    real(dp), intent(in) :: x(0:11)
    real(dp) :: y(0:5)
    integer :: m

    do m = 0, 5
      y(m) = ell(5 - m) * x(5 - m) + ell(6 + m) * x(6 + m)
    end do
    s = ((y(0) + y(1)) + (y(2) + y(3))) + (y(4) + y(5))
  end function stencil_sum_12

  ! The nodes i - left .. i - left + stencil - 1 of a table: direct indexing away from u = 0;
  ! near it the stencil reaches negative nodes, given by the symmetry of H (even) or H1 (odd).
  pure subroutine stencil_nodes(values, stencil, left, i, odd, x)
    real(dp), intent(in), contiguous :: values(0:)
    integer, intent(in) :: stencil, left, i
    logical, intent(in) :: odd
    real(dp), intent(out) :: x(0:max_stencil - 1)
    integer :: j

    if (i >= left) then
      x(0:stencil - 1) = values(i - left:i - left + stencil - 1)
    else
      do j = 0, stencil - 1
        x(j) = node_value(values, i - left + j, odd)
      end do
    end if
  end subroutine stencil_nodes

  ! Interpolated H, and H1 if with_h1, at u = (i + t) du, t in (0, 1): one routine for both
  ! evaluations so that they give the same H, with the basis kept in registers.
  pure subroutine interpolate(table, i, t, with_h1, h, h1)
    type(kernel_table), intent(in) :: table
    integer, intent(in) :: i
    real(dp), intent(in) :: t
    logical, intent(in) :: with_h1
    real(dp), intent(out) :: h, h1
    real(dp) :: ell(0:max_stencil - 1), x(0:max_stencil - 1)
    integer :: j

    h1 = 0.0_dp
    if (table%stencil == 12 .and. table%stencil_left == 5) then
      call lagrange_basis_12(table%lagrange_weight, t, ell)
      if (i >= 5) then
        h = stencil_sum_12(ell, table%h(i - 5:i + 6))
        if (with_h1) h1 = stencil_sum_12(ell, table%h1(i - 5:i + 6))
      else
        call stencil_nodes(table%h, 12, 5, i, .false., x)
        h = stencil_sum_12(ell, x)
        if (with_h1) then
          call stencil_nodes(table%h1, 12, 5, i, .true., x)
          h1 = stencil_sum_12(ell, x)
        end if
      end if
    else
      call lagrange_basis(table%lagrange_weight, table%stencil, table%stencil_left, t, ell)
      call stencil_nodes(table%h, table%stencil, table%stencil_left, i, .false., x)
      h = 0.0_dp
      do j = 0, table%stencil - 1
        h = h + ell(j) * x(j)
      end do
      if (with_h1) then
        call stencil_nodes(table%h1, table%stencil, table%stencil_left, i, .true., x)
        do j = 0, table%stencil - 1
          h1 = h1 + ell(j) * x(j)
        end do
      end if
    end if
  end subroutine interpolate

  ! H(u) and H1(u) for any real u (thread-safe: reads the table only).
  elemental subroutine evaluate_kernel_table(table, u, h, h1)
    type(kernel_table), intent(in) :: table
    real(dp), intent(in) :: u
    real(dp), intent(out) :: h, h1
    call look_up(table, abs(u), .true., h, h1)
    if (u < 0.0_dp) h1 = -h1
  end subroutine evaluate_kernel_table

  ! H(u) alone (the solver's case; the only evaluation of a table without H1): the same
  ! values as evaluate_kernel_table, half the work.
  elemental real(dp) function evaluate_kernel_h(table, u) result(h)
    type(kernel_table), intent(in) :: table
    real(dp), intent(in) :: u
    real(dp) :: h1
    call look_up(table, abs(u), .false., h, h1)
  end function evaluate_kernel_h

  ! H at many points (the solver's batches): evaluate_kernel_h's values to the last bit. For the
  ! default 12-point stencil the Lagrange basis (lagrange_basis_12's operations in its order) is
  ! computed for a chunk of tabulated points in one loop vectorized across points
  ! (cc_lagrange_basis.c: SSE2 or AVX2, chosen at load time, no FMA), then each sum (stencil_sum_12's order; near u = 0 the nodes at
  ! |k|, H being even, as node_value; a node itself, t = 0, read). Far-field points (v > u_max)
  ! are left out of the chunks and summed point by point, as look_up does. A chunk's basis is
  ! computed for its points only: the solver's small batches (a table node's ~150 node-to-node
  ! values) no longer pay for a whole chunk of padding.
  subroutine evaluate_kernel_h_many(table, u, h)
    type(kernel_table), intent(in) :: table
    real(dp), intent(in) :: u(:)
    real(dp), intent(out) :: h(:)
    integer, parameter :: chunk = 64
    real(dp) :: weights(0:11), y0, y1, y2, y3, y4, y5, v, h1, u_max, du
    real(dp) :: ell(chunk, 0:11), offset(chunk), uu(chunk)
    integer(c_int) :: i(chunk)
    integer :: at(chunk), k, first, count
    interface
      ! cc_lagrange_basis.c: the basis loop, built for SSE2 and AVX2 (no FMA), the same bits;
      ! ell's first extent (chunk = 64) is a constant there.
      subroutine cc_lagrange_basis_12(count, uu, du, w, index, offset, ell) bind(C, name="cc_lagrange_basis_12")
        import :: c_int, c_double
        integer(c_int), value :: count
        real(c_double), intent(in) :: uu(*), w(*)
        real(c_double), value :: du
        integer(c_int), intent(out) :: index(*)
        real(c_double), intent(out) :: offset(*), ell(*)
      end subroutine cc_lagrange_basis_12
    end interface

    if (table%stencil /= 12 .or. table%stencil_left /= 5) then
      h = evaluate_kernel_h(table, u)
      return
    end if
    u_max = table%u_max
    du = table%du
    weights = table%lagrange_weight(0:11)
    first = 1
    do while (first <= size(u))
      ! The next chunk of points in the table (uu, at their indices `at`); the far field, past
      ! u_max, directly.
      count = 0
      do while (first <= size(u) .and. count < chunk)
        v = abs(u(first))
        if (v <= u_max) then
          count = count + 1
          uu(count) = v
          at(count) = first
        else
          call far_field(table, v, .false., h(first), h1)
        end if
        first = first + 1
      end do
      call cc_lagrange_basis_12(count, uu, du, weights, i, offset, ell)
      do k = 1, count
        if (offset(k) == 0.0_dp) then
          h(at(k)) = table%h(i(k))
          cycle
        end if
        y0 = ell(k, 5) * table%h(i(k)) + ell(k, 6) * table%h(i(k) + 1)
        y1 = ell(k, 4) * table%h(abs(i(k) - 1)) + ell(k, 7) * table%h(i(k) + 2)
        y2 = ell(k, 3) * table%h(abs(i(k) - 2)) + ell(k, 8) * table%h(i(k) + 3)
        y3 = ell(k, 2) * table%h(abs(i(k) - 3)) + ell(k, 9) * table%h(i(k) + 4)
        y4 = ell(k, 1) * table%h(abs(i(k) - 4)) + ell(k, 10) * table%h(i(k) + 5)
        y5 = ell(k, 0) * table%h(abs(i(k) - 5)) + ell(k, 11) * table%h(i(k) + 6)
        h(at(k)) = ((y0 + y1) + (y2 + y3)) + (y4 + y5)
      end do
    end do
  end subroutine evaluate_kernel_h_many

  ! H(v) and (with_h1) H1(v) at v >= 0: a node's values, the Lagrange form on the nodes
  ! i + k, k = -left .. stencil-1-left, or beyond the table the far field.
  elemental subroutine look_up(table, v, with_h1, h, h1)
    type(kernel_table), intent(in) :: table
    real(dp), intent(in) :: v
    logical, intent(in) :: with_h1
    real(dp), intent(out) :: h, h1
    real(dp) :: t
    integer :: i

    if (v <= table%u_max) then
      t = v / table%du
      i = int(t)
      t = t - real(i, dp)
      if (t == 0.0_dp) then
        h = table%h(i)
        if (with_h1) h1 = table%h1(i)
      else
        call interpolate(table, i, t, with_h1, h, h1)
      end if
    else
      call far_field(table, v, with_h1, h, h1)
    end if
  end subroutine look_up

  ! H and (with_h1) H1 beyond the table, v > u_max: the pole terms plus the asymptotic series
  ! of the smooth remainder (its Taylor coefficients at q = 0); without with_h1, H1 is
  ! only the pole terms' part (not needed).
  pure subroutine far_field(table, v, with_h1, h, h1)
    type(kernel_table), intent(in) :: table
    real(dp), intent(in) :: v
    logical, intent(in) :: with_h1
    real(dp), intent(out) :: h, h1
    real(dp) :: inv, inv2, term, fact
    integer :: k

    call pole_transforms(table, v, h, h1)
    inv = 1.0_dp / v
    inv2 = inv * inv
    if (with_h1) h1 = h1 + 0.5_dp * pi * table%taylor(0)
    term = inv                                     ! 1/v^(2k+1)
    fact = 1.0_dp                                  ! (2k)!
    do k = 0, (max_taylor_order - 1) / 2
      if (with_h1) h1 = h1 + (-1.0_dp)**k * fact * table%taylor(2 * k + 1) * term
      h = h - (-1.0_dp)**k * fact * real(2 * k + 1, dp) * table%taylor(2 * k + 1) * term * inv
      term = term * inv2
      fact = fact * real((2 * k + 1) * (2 * k + 2), dp)
    end do
  end subroutine far_field

end module cc_kernel_tables
