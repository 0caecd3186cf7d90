! bind(C) shim: the C interface declared in include/coatcontact/cc_kernel.h. Scalars by value,
! arrays with explicit sizes, `intent` on every argument; validates every argument (moduli,
! Poisson ratios, lengths, null handles, q and u) and returns status codes;
! the physics lives in kernels/ and in cc_kernel_tables.
module cc_kernel_capi
  use, intrinsic :: iso_c_binding
  use cc_elastic_constants, only: dp, material_pair, make_material_pair, CC_OK, CC_ERR_ARGUMENT, &
                                  CC_ERR_ALLOCATION, CC_INPUT_ERROR, CC_NUMERICAL_ERROR, &
                                  CC_INTERNAL_ERROR, CC_ERR_FILM_MODULUS, CC_ERR_FILM_POISSON, &
                                  CC_ERR_SUBSTRATE_MODULUS, CC_ERR_SUBSTRATE_POISSON, &
                                  CC_ERR_ACCURACY, CC_ERR_THICKNESS, CC_INTERRUPTED
  use cc_compliance_models, only: compliance, compliance_minus_one, compliance_taylor, max_taylor_order
  use cc_kernel_tables, only: kernel_table, build_kernel_table_variant, evaluate_kernel_table, &
                              evaluate_kernel_h_many, n_grid_variants, build_stack_kernel_table_variant, &
                              max_stack_refine
  use cc_multilayer_compliance, only: layer_stack, make_layer_stack, stack_compliance, &
                                      stack_compliance_minus_one, max_stack_layers
  use cc_elastic_constants, only: CC_ERR_LAYER_COUNT
  implicit none
  private
  ! The Fortran names carry a capi_ prefix, and no module is named like a binding label:
  ! gfortran 12 silently resolved calls into a module `cc_compliance` to the bind(C) label
  ! "cc_compliance".

  integer, parameter :: message_length = 96
  ! Messages of the detail codes CC_ERR_FILM_MODULUS (101) .. CC_ERR_LAYER_COUNT (110), then of
  ! the classes CC_INPUT_ERROR .. CC_INTERNAL_ERROR, success and an unknown code.
  integer, parameter :: first_detail = CC_ERR_FILM_MODULUS, last_detail = CC_ERR_LAYER_COUNT
  character(kind=c_char, len=message_length), target, save :: detail_messages(first_detail:last_detail) = [ &
    character(kind=c_char, len=message_length) :: &
    "film Young's modulus must be finite and > 0" // c_null_char, &
    "film Poisson ratio must be finite and in (-1, 0.5]" // c_null_char, &
    "substrate Young's modulus must be finite and > 0" // c_null_char, &
    "substrate Poisson ratio must be finite and in (-1, 0.5]" // c_null_char, &
    "bad argument (array length, negative or non-finite q or u, null pointer, order)" // c_null_char, &
    "FFTW could not plan the transform" // c_null_char, &
    "out of memory" // c_null_char, &
    "the kernel table could not reach its accuracy target" // c_null_char, &
    "layer thickness must be finite and > 0" // c_null_char, &
    "number of layers must be between 1 and 1000" // c_null_char]
  character(kind=c_char, len=message_length), target, save :: other_messages(6) = [ &
    character(kind=c_char, len=message_length) :: &
    "success" // c_null_char, &
    "bad input" // c_null_char, &
    "the requested accuracy could not be reached" // c_null_char, &
    "internal error" // c_null_char, &
    "interrupted by the progress hook" // c_null_char, &
    "unknown status code" // c_null_char]

contains

  function capi_status_message(status) result(message) bind(C, name="cc_status_message")
    integer(c_int), value, intent(in) :: status
    type(c_ptr) :: message
    select case (status)
    case (first_detail:last_detail)
      message = c_loc(detail_messages(status))
    case (CC_OK)
      message = c_loc(other_messages(1))
    case (CC_INPUT_ERROR)
      message = c_loc(other_messages(2))
    case (CC_NUMERICAL_ERROR)
      message = c_loc(other_messages(3))
    case (CC_INTERNAL_ERROR)
      message = c_loc(other_messages(4))
    case (CC_INTERRUPTED)
      message = c_loc(other_messages(5))
    case default
      message = c_loc(other_messages(6))
    end select
  end function capi_status_message

  pure integer(c_int) function capi_status_class(status) result(status_class) &
      bind(C, name="cc_status_class")
    integer(c_int), value, intent(in) :: status
    select case (status)
    case (CC_OK, CC_INPUT_ERROR, CC_NUMERICAL_ERROR, CC_INTERNAL_ERROR, CC_INTERRUPTED)
      status_class = status
    case (CC_ERR_FILM_MODULUS, CC_ERR_FILM_POISSON, CC_ERR_SUBSTRATE_MODULUS, &
          CC_ERR_SUBSTRATE_POISSON, CC_ERR_ARGUMENT, CC_ERR_THICKNESS, CC_ERR_LAYER_COUNT)
      status_class = CC_INPUT_ERROR
    case (CC_ERR_ACCURACY)
      status_class = CC_NUMERICAL_ERROR
    case default
      status_class = CC_INTERNAL_ERROR
    end select
  end function capi_status_class

  subroutine pair_from_c(e1, nu1, e0, nu0, substrate_rigid, pair, status)
    real(c_double), intent(in) :: e1, nu1, e0, nu0
    integer(c_int), intent(in) :: substrate_rigid
    type(material_pair), intent(out) :: pair
    integer, intent(out) :: status
    call make_material_pair(real(e1, dp), real(nu1, dp), real(e0, dp), real(nu0, dp), &
                            substrate_rigid /= 0, pair, status)
  end subroutine pair_from_c

  ! A validated stack from the C arrays; the layer count is checked before any array is read.
  subroutine stack_from_c(n_layers, thickness, youngs, poisson, slip_below, base_rigid, e_base, &
      nu_base, stack, status)
    integer(c_int), intent(in) :: n_layers
    real(c_double), intent(in) :: thickness(max(n_layers, 0)), youngs(max(n_layers, 0)), &
                                  poisson(max(n_layers, 0))
    integer(c_int), intent(in) :: slip_below(max(n_layers, 0))
    integer(c_int), intent(in) :: base_rigid
    real(c_double), intent(in) :: e_base, nu_base
    type(layer_stack), intent(out) :: stack
    integer, intent(out) :: status
    status = CC_ERR_LAYER_COUNT
    if (n_layers < 1 .or. n_layers > max_stack_layers) return
    call make_layer_stack(real(thickness, dp), real(youngs, dp), real(poisson, dp), &
                          slip_below /= 0, base_rigid /= 0, real(e_base, dp), real(nu_base, dp), &
                          stack, status)
  end subroutine stack_from_c

  integer(c_int) function capi_compliance(e1, nu1, e0, nu0, substrate_rigid, n, q, c) &
      result(status) bind(C, name="cc_compliance")
    real(c_double), value, intent(in) :: e1, nu1, e0, nu0
    integer(c_int), value, intent(in) :: substrate_rigid, n
    real(c_double), intent(in) :: q(n)
    real(c_double), intent(out) :: c(n)
    status = compliance_at(e1, nu1, e0, nu0, substrate_rigid, n, q, c, .false.)
  end function capi_compliance

  integer(c_int) function capi_compliance_minus_one(e1, nu1, e0, nu0, substrate_rigid, n, q, c) &
      result(status) bind(C, name="cc_compliance_minus_one")
    real(c_double), value, intent(in) :: e1, nu1, e0, nu0
    integer(c_int), value, intent(in) :: substrate_rigid, n
    real(c_double), intent(in) :: q(n)
    real(c_double), intent(out) :: c(n)
    status = compliance_at(e1, nu1, e0, nu0, substrate_rigid, n, q, c, .true.)
  end function capi_compliance_minus_one

  ! C(q) or C(q) - 1 after validating the material pair and the length.
  integer(c_int) function compliance_at(e1, nu1, e0, nu0, substrate_rigid, n, q, c, minus_one) &
      result(status)
    real(c_double), intent(in) :: e1, nu1, e0, nu0
    integer(c_int), intent(in) :: substrate_rigid, n
    real(c_double), intent(in) :: q(n)
    real(c_double), intent(out) :: c(n)
    logical, intent(in) :: minus_one
    type(material_pair) :: pair
    integer :: s
    call pair_from_c(e1, nu1, e0, nu0, substrate_rigid, pair, s)
    status = int(s, c_int)
    if (s /= CC_OK) return
    status = CC_ERR_ARGUMENT
    if (n < 0) return
    if (minus_one) then
      call compliance_minus_one(pair, q, c, s)
    else
      call compliance(pair, q, c, s)
    end if
    status = int(s, c_int)
  end function compliance_at

  ! Stack of n_layers layers (THEORY.md section 12): C(q) with q = k T, T the total thickness.
  integer(c_int) function capi_stack_compliance(n_layers, thickness, youngs, poisson, slip_below, &
      base_rigid, e_base, nu_base, n, q, c) result(status) bind(C, name="cc_stack_compliance")
    integer(c_int), value, intent(in) :: n_layers
    real(c_double), intent(in) :: thickness(max(n_layers, 0)), youngs(max(n_layers, 0)), &
                                  poisson(max(n_layers, 0))
    integer(c_int), intent(in) :: slip_below(max(n_layers, 0))
    integer(c_int), value, intent(in) :: base_rigid
    real(c_double), value, intent(in) :: e_base, nu_base
    integer(c_int), value, intent(in) :: n
    real(c_double), intent(in) :: q(max(n, 0))
    real(c_double), intent(out) :: c(max(n, 0))
    status = stack_at(n_layers, thickness, youngs, poisson, slip_below, base_rigid, e_base, &
                      nu_base, n, q, c, .false.)
  end function capi_stack_compliance

  integer(c_int) function capi_stack_compliance_minus_one(n_layers, thickness, youngs, poisson, &
      slip_below, base_rigid, e_base, nu_base, n, q, c) result(status) &
      bind(C, name="cc_stack_compliance_minus_one")
    integer(c_int), value, intent(in) :: n_layers
    real(c_double), intent(in) :: thickness(max(n_layers, 0)), youngs(max(n_layers, 0)), &
                                  poisson(max(n_layers, 0))
    integer(c_int), intent(in) :: slip_below(max(n_layers, 0))
    integer(c_int), value, intent(in) :: base_rigid
    real(c_double), value, intent(in) :: e_base, nu_base
    integer(c_int), value, intent(in) :: n
    real(c_double), intent(in) :: q(max(n, 0))
    real(c_double), intent(out) :: c(max(n, 0))
    status = stack_at(n_layers, thickness, youngs, poisson, slip_below, base_rigid, e_base, &
                      nu_base, n, q, c, .true.)
  end function capi_stack_compliance_minus_one

  ! C(q) or C(q) - 1 of a stack after validating it (the layer count before any array is read)
  ! and the length.
  integer(c_int) function stack_at(n_layers, thickness, youngs, poisson, slip_below, base_rigid, &
      e_base, nu_base, n, q, c, minus_one) result(status)
    integer(c_int), intent(in) :: n_layers
    real(c_double), intent(in) :: thickness(max(n_layers, 0)), youngs(max(n_layers, 0)), &
                                  poisson(max(n_layers, 0))
    integer(c_int), intent(in) :: slip_below(max(n_layers, 0))
    integer(c_int), intent(in) :: base_rigid
    real(c_double), intent(in) :: e_base, nu_base
    integer(c_int), intent(in) :: n
    real(c_double), intent(in) :: q(max(n, 0))
    real(c_double), intent(out) :: c(max(n, 0))
    logical, intent(in) :: minus_one
    type(layer_stack) :: stack
    integer :: s
    call stack_from_c(n_layers, thickness, youngs, poisson, slip_below, base_rigid, e_base, &
                      nu_base, stack, s)
    status = int(s, c_int)
    if (s /= CC_OK) return
    status = CC_ERR_ARGUMENT
    if (n < 0) return
    if (minus_one) then
      call stack_compliance_minus_one(stack, q, c, s)
    else
      call stack_compliance(stack, q, c, s)
    end if
    status = int(s, c_int)
  end function stack_at

  integer(c_int) function capi_compliance_taylor(e1, nu1, e0, nu0, substrate_rigid, order, &
      coefficients) result(status) bind(C, name="cc_compliance_taylor")
    real(c_double), value, intent(in) :: e1, nu1, e0, nu0
    integer(c_int), value, intent(in) :: substrate_rigid, order
    real(c_double), intent(out) :: coefficients(0:max(order, 0))
    type(material_pair) :: pair
    integer :: s
    call pair_from_c(e1, nu1, e0, nu0, substrate_rigid, pair, s)
    status = int(s, c_int)
    if (s /= CC_OK) return
    status = CC_ERR_ARGUMENT
    if (order < 0 .or. order > max_taylor_order) return
    call compliance_taylor(pair, int(order), coefficients, s)
    status = int(s, c_int)
  end function capi_compliance_taylor

  integer(c_int) function capi_kernel_table_create(e1, nu1, e0, nu0, substrate_rigid, table) &
      result(status) bind(C, name="cc_kernel_table_create")
    real(c_double), value, intent(in) :: e1, nu1, e0, nu0
    integer(c_int), value, intent(in) :: substrate_rigid
    type(c_ptr), value, intent(in) :: table       ! cc_kernel_table **
    status = create_table(e1, nu1, e0, nu0, substrate_rigid, 0, table)
  end function capi_kernel_table_create

  integer(c_int) function capi_kernel_table_create_ex(e1, nu1, e0, nu0, substrate_rigid, &
      grid_variant, table) result(status) bind(C, name="cc_kernel_table_create_ex")
    real(c_double), value, intent(in) :: e1, nu1, e0, nu0
    integer(c_int), value, intent(in) :: substrate_rigid, grid_variant
    type(c_ptr), value, intent(in) :: table       ! cc_kernel_table **
    status = create_table(e1, nu1, e0, nu0, substrate_rigid, int(grid_variant), table)
  end function capi_kernel_table_create_ex

  ! The table of cc_kernel_table_create_ex without H1: see cc_kernel.h.
  integer(c_int) function capi_kernel_table_create_h(e1, nu1, e0, nu0, substrate_rigid, &
      grid_variant, table) result(status) bind(C, name="cc_kernel_table_create_h")
    real(c_double), value, intent(in) :: e1, nu1, e0, nu0
    integer(c_int), value, intent(in) :: substrate_rigid, grid_variant
    type(c_ptr), value, intent(in) :: table       ! cc_kernel_table **
    status = create_table(e1, nu1, e0, nu0, substrate_rigid, int(grid_variant), table, h_only=.true.)
  end function capi_kernel_table_create_h

  ! Variant 0 on a compact grid covering [0, u_range] (series beyond), no H1: see cc_kernel.h.
  integer(c_int) function capi_kernel_table_create_range(e1, nu1, e0, nu0, substrate_rigid, &
      u_range, table) result(status) bind(C, name="cc_kernel_table_create_range")
    real(c_double), value, intent(in) :: e1, nu1, e0, nu0, u_range
    integer(c_int), value, intent(in) :: substrate_rigid
    type(c_ptr), value, intent(in) :: table       ! cc_kernel_table **
    status = CC_ERR_ARGUMENT
    if (.not. valid_range(u_range)) return
    status = create_table(e1, nu1, e0, nu0, substrate_rigid, 0, table, real(u_range, dp))
  end function capi_kernel_table_create_range

  logical function valid_range(u_range)
    real(c_double), intent(in) :: u_range
    valid_range = u_range > 0.0_dp .and. u_range <= huge(1.0_dp)   ! also rejects NaN
  end function valid_range

  integer(c_int) function capi_kernel_grid_variants() result(count) &
      bind(C, name="cc_kernel_grid_variants")
    count = int(n_grid_variants, c_int)
  end function capi_kernel_grid_variants

  integer(c_int) function capi_kernel_stack_max_refinement() result(refinement) &
      bind(C, name="cc_kernel_stack_max_refinement")
    refinement = int(max_stack_refine, c_int)
  end function capi_kernel_stack_max_refinement

  integer(c_int) function create_table(e1, nu1, e0, nu0, substrate_rigid, variant, table, &
      u_range, h_only) result(status)
    real(c_double), intent(in) :: e1, nu1, e0, nu0
    integer(c_int), intent(in) :: substrate_rigid
    integer, intent(in) :: variant
    type(c_ptr), intent(in) :: table
    real(dp), intent(in), optional :: u_range
    logical, intent(in), optional :: h_only
    type(c_ptr), pointer :: handle
    type(material_pair) :: pair
    integer :: s
    status = CC_ERR_ARGUMENT
    if (.not. c_associated(table)) return
    call c_f_pointer(table, handle)
    handle = c_null_ptr
    call pair_from_c(e1, nu1, e0, nu0, substrate_rigid, pair, s)
    status = int(s, c_int)
    if (s /= CC_OK) return
    status = build_into(handle, variant, u_range, h_only, pair=pair)
  end function create_table

  ! A new table of the pair or (present) the stack in handle, on grid variant `variant`;
  ! handle untouched on failure.
  integer(c_int) function build_into(handle, variant, u_range, h_only, pair, stack) result(status)
    type(c_ptr), intent(inout) :: handle
    integer, intent(in) :: variant
    real(dp), intent(in), optional :: u_range
    logical, intent(in), optional :: h_only
    type(material_pair), intent(in), optional :: pair
    type(layer_stack), intent(in), optional :: stack
    type(kernel_table), pointer :: t
    integer :: s, ierr
    status = CC_ERR_ARGUMENT
    if (variant < 0 .or. variant >= n_grid_variants) return
    status = CC_ERR_ALLOCATION
    allocate(t, stat=ierr)
    if (ierr /= 0) return
    if (present(stack)) then
      call build_stack_kernel_table_variant(stack, variant, t, s, u_range, h_only)
    else
      call build_kernel_table_variant(pair, variant, t, s, u_range, h_only)
    end if
    status = int(s, c_int)
    if (s /= CC_OK) then
      deallocate(t)
      return
    end if
    handle = c_loc(t)
  end function build_into

  ! Table of a stack (THEORY.md section 12); one bonded layer goes through create_table, so
  ! its table is cc_kernel_table_create_ex's bit for bit.
  integer(c_int) function capi_kernel_table_create_stack(n_layers, thickness, youngs, poisson, &
      slip_below, base_rigid, e_base, nu_base, grid_variant, table) result(status) &
      bind(C, name="cc_kernel_table_create_stack")
    integer(c_int), value, intent(in) :: n_layers
    real(c_double), intent(in) :: thickness(max(n_layers, 0)), youngs(max(n_layers, 0)), &
                                  poisson(max(n_layers, 0))
    integer(c_int), intent(in) :: slip_below(max(n_layers, 0))
    integer(c_int), value, intent(in) :: base_rigid
    real(c_double), value, intent(in) :: e_base, nu_base
    integer(c_int), value, intent(in) :: grid_variant
    type(c_ptr), value, intent(in) :: table       ! cc_kernel_table **
    status = create_stack_table(n_layers, thickness, youngs, poisson, slip_below, base_rigid, &
                                e_base, nu_base, int(grid_variant), table)
  end function capi_kernel_table_create_stack

  ! The table of cc_kernel_table_create_stack without H1: see cc_kernel.h.
  integer(c_int) function capi_kernel_table_create_stack_h(n_layers, thickness, youngs, poisson, &
      slip_below, base_rigid, e_base, nu_base, grid_variant, table) result(status) &
      bind(C, name="cc_kernel_table_create_stack_h")
    integer(c_int), value, intent(in) :: n_layers
    real(c_double), intent(in) :: thickness(max(n_layers, 0)), youngs(max(n_layers, 0)), &
                                  poisson(max(n_layers, 0))
    integer(c_int), intent(in) :: slip_below(max(n_layers, 0))
    integer(c_int), value, intent(in) :: base_rigid
    real(c_double), value, intent(in) :: e_base, nu_base
    integer(c_int), value, intent(in) :: grid_variant
    type(c_ptr), value, intent(in) :: table       ! cc_kernel_table **
    status = create_stack_table(n_layers, thickness, youngs, poisson, slip_below, base_rigid, &
                                e_base, nu_base, int(grid_variant), table, h_only=.true.)
  end function capi_kernel_table_create_stack_h

  ! Variant 0 of a stack on a compact grid covering [0, u_range], no H1: see cc_kernel.h.
  integer(c_int) function capi_kernel_table_create_stack_range(n_layers, thickness, youngs, &
      poisson, slip_below, base_rigid, e_base, nu_base, u_range, table) result(status) &
      bind(C, name="cc_kernel_table_create_stack_range")
    integer(c_int), value, intent(in) :: n_layers
    real(c_double), intent(in) :: thickness(max(n_layers, 0)), youngs(max(n_layers, 0)), &
                                  poisson(max(n_layers, 0))
    integer(c_int), intent(in) :: slip_below(max(n_layers, 0))
    integer(c_int), value, intent(in) :: base_rigid
    real(c_double), value, intent(in) :: e_base, nu_base, u_range
    type(c_ptr), value, intent(in) :: table       ! cc_kernel_table **
    status = CC_ERR_ARGUMENT
    if (.not. valid_range(u_range)) return
    status = create_stack_table(n_layers, thickness, youngs, poisson, slip_below, base_rigid, &
                                e_base, nu_base, 0, table, real(u_range, dp))
  end function capi_kernel_table_create_stack_range

  integer(c_int) function create_stack_table(n_layers, thickness, youngs, poisson, slip_below, &
      base_rigid, e_base, nu_base, grid_variant, table, u_range, h_only) result(status)
    integer(c_int), intent(in) :: n_layers
    real(c_double), intent(in) :: thickness(max(n_layers, 0)), youngs(max(n_layers, 0)), &
                                  poisson(max(n_layers, 0))
    integer(c_int), intent(in) :: slip_below(max(n_layers, 0))
    integer(c_int), intent(in) :: base_rigid
    real(c_double), intent(in) :: e_base, nu_base
    integer, intent(in) :: grid_variant
    type(c_ptr), intent(in) :: table       ! cc_kernel_table **
    real(dp), intent(in), optional :: u_range
    logical, intent(in), optional :: h_only
    type(c_ptr), pointer :: handle
    type(layer_stack) :: stack
    integer :: s
    status = CC_ERR_ARGUMENT
    if (.not. c_associated(table)) return
    call c_f_pointer(table, handle)
    handle = c_null_ptr
    call stack_from_c(n_layers, thickness, youngs, poisson, slip_below, base_rigid, e_base, &
                      nu_base, stack, s)
    status = int(s, c_int)
    if (s /= CC_OK) return
    if (stack%closed_form) then
      status = create_table(youngs(1), poisson(1), e_base, nu_base, base_rigid, &
                            grid_variant, table, u_range, h_only)
      return
    end if
    status = build_into(handle, grid_variant, u_range, h_only, stack=stack)
  end function create_stack_table

  subroutine capi_kernel_table_destroy(table) bind(C, name="cc_kernel_table_destroy")
    type(c_ptr), value, intent(in) :: table
    type(kernel_table), pointer :: t
    if (.not. c_associated(table)) return
    call c_f_pointer(table, t)
    deallocate(t)
  end subroutine capi_kernel_table_destroy

  integer(c_int) function capi_kernel_table_eval(table, n, u, h, h1) result(status) &
      bind(C, name="cc_kernel_table_eval")
    type(c_ptr), value, intent(in) :: table
    integer(c_int), value, intent(in) :: n
    real(c_double), intent(in) :: u(n)
    real(c_double), intent(out) :: h(n)
    type(c_ptr), value, intent(in) :: h1           ! optional output: NULL or n doubles
    type(kernel_table), pointer :: t
    real(c_double), pointer :: h1s(:)
    status = CC_ERR_ARGUMENT
    if (.not. c_associated(table) .or. n < 0) return
    if (.not. all(abs(u) <= huge(1.0_dp))) return   ! NaN or infinite (one pass: false for NaN)
    call c_f_pointer(table, t)
    if (c_associated(h1)) then
      if (.not. t%has_h1) return                  ! compact tables hold H only
      call c_f_pointer(h1, h1s, [n])
      call evaluate_kernel_table(t, u, h, h1s)
    else
      call evaluate_kernel_h_many(t, u, h)        ! H alone: the same values, half the work
    end if
    status = CC_OK
  end function capi_kernel_table_eval

  integer(c_int) function capi_kernel_table_info(table, u_max, du, c_zero, half_integral, &
      abs_accuracy) result(status) bind(C, name="cc_kernel_table_info")
    type(c_ptr), value, intent(in) :: table, u_max, du, c_zero, half_integral, abs_accuracy
    type(kernel_table), pointer :: t
    status = CC_ERR_ARGUMENT
    if (.not. c_associated(table)) return
    call c_f_pointer(table, t)
    call store(u_max, t%u_max)
    call store(du, t%du)
    call store(c_zero, t%c_zero)
    call store(half_integral, t%half_integral)
    call store(abs_accuracy, t%abs_accuracy)
    status = CC_OK
  end function capi_kernel_table_info

  integer(c_int) function capi_kernel_table_scale(table, max_abs_h, decay_rate) result(status) &
      bind(C, name="cc_kernel_table_scale")
    type(c_ptr), value, intent(in) :: table, max_abs_h, decay_rate
    type(kernel_table), pointer :: t
    status = CC_ERR_ARGUMENT
    if (.not. c_associated(table)) return
    call c_f_pointer(table, t)
    call store(max_abs_h, t%max_abs_h)
    call store(decay_rate, t%decay_rate)
    status = CC_OK
  end function capi_kernel_table_scale

  ! *target = value unless target is NULL.
  subroutine store(target, value)
    type(c_ptr), intent(in) :: target
    real(dp), intent(in) :: value
    real(c_double), pointer :: p
    if (.not. c_associated(target)) return
    call c_f_pointer(target, p)
    p = value
  end subroutine store

end module cc_kernel_capi
