  ! symtmm codegen runtime, core: units of a beam's state, re-orthonormalisation of
  ! the unknown columns and the determinant of chosen rows. Module procedures,
  ! included verbatim after "contains" in every generated Fortran evaluator, before
  ! euler_bernoulli.f90 and theory.f90; the module defines the kind dp.

  ! units of one beam's state: 1, 1/b, 1/(EI b^2), 1/(EI b^3), b >= 1/L the wave number
  subroutine symtmm_units(b_in, ei, bl, dd)
    real(dp), intent(in) :: b_in, ei, bl
    real(dp), intent(out) :: dd(4)
    real(dp) :: b
    b = max(b_in, 1.0_dp / bl)
    dd = [1.0_dp, 1.0_dp / b, 1.0_dp / (ei * b * b), 1.0_dp / (ei * b * b * b)]
  end subroutine symtmm_units

  ! modified Gram-Schmidt, twice: e := q of e = q f, and logscale := logscale + log det f
  subroutine symtmm_orthonormalise(e, logscale)
    complex(dp), intent(inout) :: e(:, :)
    real(dp), intent(inout) :: logscale
    complex(dp) :: r
    real(dp) :: nrm
    integer :: j, k, pass
    do j = 1, size(e, 2)
      do pass = 1, 2
        do k = 1, j - 1
          r = sum(conjg(e(:, k)) * e(:, j))
          e(:, j) = e(:, j) - r * e(:, k)
        end do
      end do
      nrm = sqrt(sum(real(e(:, j) * conjg(e(:, j)), kind=dp)))
      e(:, j) = e(:, j) / nrm
      logscale = logscale + log(nrm)
    end do
  end subroutine symtmm_orthonormalise

  ! determinant by Gaussian elimination with partial pivoting
  function symtmm_det(a_in) result(d)
    complex(dp), intent(in) :: a_in(:, :)
    complex(dp) :: a(size(a_in, 1), size(a_in, 2)), d, f, row(size(a_in, 2))
    integer :: i, k, p, n
    a = a_in
    n = size(a, 1)
    d = (1.0_dp, 0.0_dp)
    do k = 1, n
      p = k
      do i = k + 1, n
        if (abs(a(i, k)) > abs(a(p, k))) p = i
      end do
      if (a(p, k) == (0.0_dp, 0.0_dp)) then
        d = (0.0_dp, 0.0_dp)
        return
      end if
      if (p /= k) then
        row = a(k, :); a(k, :) = a(p, :); a(p, :) = row
        d = -d
      end if
      d = d * a(k, k)
      do i = k + 1, n
        f = a(i, k) / a(k, k)
        a(i, k + 1:n) = a(i, k + 1:n) - f * a(k, k + 1:n)
      end do
    end do
  end function symtmm_det
