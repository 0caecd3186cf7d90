! A built kernel table as one array of doubles (its image) and the same table made again from
! an image (C interface: include/coatcontact/cc_kernel_image.h): the solve cache stores tables
! this way (cpp/solver/table_cache.cpp) so that a process that finds one skips the build (the
! stack compliance and the FFTs). Every field of kernel_table is in the image, so a table made
! from it evaluates bit for bit as the one it was taken from.
!
! Layout: a header of integers stored as doubles (format, size of taylor, size of
! lagrange_weight, n_nodes, has_h1, grid_variant, stencil, stencil_left), the nine real
! scalars, taylor, lagrange_weight, h, then h1 when the table has it.
! (Module cc_table_images: no module is named like a binding label, see cc_kernel_capi.f90.)
module cc_table_images
  use, intrinsic :: iso_c_binding
  use cc_elastic_constants, only: dp, CC_OK, CC_ERR_ARGUMENT, CC_ERR_ALLOCATION
  use cc_kernel_tables, only: kernel_table
  implicit none
  private

  integer, parameter :: image_format = 1
  integer, parameter :: header_integers = 8, real_scalars = 9

contains

  ! Number of doubles in the image of `t`.
  integer function image_length(t) result(n)
    type(kernel_table), intent(in) :: t
    n = header_integers + real_scalars + size(t%taylor) + size(t%lagrange_weight) + t%n_nodes
    if (t%has_h1) n = n + t%n_nodes
  end function image_length

  integer(c_int) function capi_kernel_table_image_size(table, n_doubles) result(status) &
      bind(C, name="cc_kernel_table_image_size")
    type(c_ptr), value, intent(in) :: table
    integer(c_int), intent(out) :: n_doubles
    type(kernel_table), pointer :: t
    n_doubles = 0
    status = CC_ERR_ARGUMENT
    if (.not. c_associated(table)) return
    call c_f_pointer(table, t)
    if (.not. allocated(t%h)) return
    n_doubles = int(image_length(t), c_int)
    status = CC_OK
  end function capi_kernel_table_image_size

  integer(c_int) function capi_kernel_table_image(table, n_doubles, image) result(status) &
      bind(C, name="cc_kernel_table_image")
    type(c_ptr), value, intent(in) :: table
    integer(c_int), value, intent(in) :: n_doubles
    real(c_double), intent(out) :: image(max(n_doubles, 0))
    type(kernel_table), pointer :: t
    integer :: at
    status = CC_ERR_ARGUMENT
    if (.not. c_associated(table)) return
    call c_f_pointer(table, t)
    if (.not. allocated(t%h)) return
    if (n_doubles /= image_length(t)) return
    image(1:header_integers) = real([image_format, size(t%taylor), size(t%lagrange_weight), &
                                     t%n_nodes, merge(1, 0, t%has_h1), t%grid_variant, t%stencil, &
                                     t%stencil_left], dp)
    at = header_integers
    image(at + 1:at + real_scalars) = [t%du, t%u_max, t%c_zero, t%half_integral, t%abs_accuracy, &
                                       t%max_abs_h, t%decay_rate, t%pole_q0, t%pole_residue]
    at = at + real_scalars
    call put(t%taylor)
    call put(t%lagrange_weight)
    call put(t%h)
    if (t%has_h1) call put(t%h1)
    status = CC_OK
  contains
    subroutine put(values)
      real(dp), intent(in) :: values(:)
      image(at + 1:at + size(values)) = values
      at = at + size(values)
    end subroutine put
  end function capi_kernel_table_image

  ! A new table from an image: CC_ERR_ARGUMENT (and *table NULL) unless the image is one of
  ! this format and build (sizes, integers and length consistent, every value finite).
  integer(c_int) function capi_kernel_table_from_image(n_doubles, image, table) result(status) &
      bind(C, name="cc_kernel_table_from_image")
    integer(c_int), value, intent(in) :: n_doubles
    real(c_double), intent(in) :: image(max(n_doubles, 0))
    type(c_ptr), value, intent(in) :: table       ! cc_kernel_table **
    type(c_ptr), pointer :: handle
    type(kernel_table), pointer :: t
    integer :: head(header_integers), at, ierr
    status = CC_ERR_ARGUMENT
    if (.not. c_associated(table)) return
    call c_f_pointer(table, handle)
    handle = c_null_ptr
    if (n_doubles < header_integers + real_scalars) return
    if (any(image /= image) .or. any(abs(image) > huge(1.0_dp))) return    ! NaN or infinite
    if (any(abs(image(1:header_integers)) > real(huge(1), dp))) return
    head = nint(image(1:header_integers))
    if (any(real(head, dp) /= image(1:header_integers))) return
    allocate(t, stat=ierr)
    if (ierr /= 0) then
      status = CC_ERR_ALLOCATION
      return
    end if
    if (.not. valid_header(t, head, n_doubles)) then
      deallocate(t)
      return
    end if
    t%n_nodes = head(4)
    t%has_h1 = head(5) == 1
    t%grid_variant = head(6)
    t%stencil = head(7)
    t%stencil_left = head(8)
    at = header_integers
    t%du = image(at + 1)
    t%u_max = image(at + 2)
    t%c_zero = image(at + 3)
    t%half_integral = image(at + 4)
    t%abs_accuracy = image(at + 5)
    t%max_abs_h = image(at + 6)
    t%decay_rate = image(at + 7)
    t%pole_q0 = image(at + 8)
    t%pole_residue = image(at + 9)
    at = at + real_scalars
    t%taylor = take(size(t%taylor))
    t%lagrange_weight = take(size(t%lagrange_weight))
    if (t%has_h1) then
      allocate(t%h(0:t%n_nodes - 1), t%h1(0:t%n_nodes - 1), stat=ierr)
    else
      allocate(t%h(0:t%n_nodes - 1), stat=ierr)
    end if
    if (ierr /= 0) then
      deallocate(t)
      status = CC_ERR_ALLOCATION
      return
    end if
    t%h = take(t%n_nodes)
    if (t%has_h1) t%h1 = take(t%n_nodes)
    handle = c_loc(t)
    status = CC_OK
  contains
    function take(n) result(values)
      integer, intent(in) :: n
      real(dp) :: values(n)
      values = image(at + 1:at + n)
      at = at + n
    end function take
  end function capi_kernel_table_from_image

  ! The header read from an image fits this build's table and the image's length.
  logical function valid_header(t, head, n_doubles) result(valid)
    type(kernel_table), intent(in) :: t
    integer, intent(in) :: head(header_integers)
    integer(c_int), intent(in) :: n_doubles
    integer :: n_nodes, copies
    valid = .false.
    if (head(1) /= image_format .or. head(2) /= size(t%taylor) .or. head(3) /= size(t%lagrange_weight)) return
    n_nodes = head(4)
    if (n_nodes < 1 .or. head(5) < 0 .or. head(5) > 1 .or. head(6) < 0) return
    if (head(7) < 1 .or. head(7) > size(t%lagrange_weight) .or. head(8) < 0 .or. head(8) >= head(7)) return
    copies = 1 + head(5)
    if (n_nodes > (huge(1) - header_integers - real_scalars - head(2) - head(3)) / copies) return
    valid = n_doubles == header_integers + real_scalars + head(2) + head(3) + copies * n_nodes
  end function valid_header

end module cc_table_images
