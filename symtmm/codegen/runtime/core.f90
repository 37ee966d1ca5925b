  ! symtmm codegen runtime, core: units of a beam's state, re-orthonormalisation of
  ! the unknown columns and the determinant of chosen rows. Module procedures,
  ! included verbatim after "contains" in every generated Fortran evaluator, before
  ! euler_bernoulli.f90 and theory.f90; the module defines the kind dp.

  ! 1/n!, n = 0 .. 63, exact to double: the series of both segment kinds
  pure real(dp) function symtmm_ifact(n)
    integer, intent(in) :: n
    real(dp), parameter :: table(0:63) = [ &
      1.0_dp, 1.0_dp, 0.5_dp, &
      0.16666666666666666_dp, 0.041666666666666664_dp, 0.008333333333333333_dp, &
      0.001388888888888889_dp, 0.0001984126984126984_dp, 2.48015873015873e-05_dp, &
      2.7557319223985893e-06_dp, 2.755731922398589e-07_dp, 2.505210838544172e-08_dp, &
      2.08767569878681e-09_dp, 1.6059043836821613e-10_dp, 1.1470745597729725e-11_dp, &
      7.647163731819816e-13_dp, 4.779477332387385e-14_dp, 2.8114572543455206e-15_dp, &
      1.5619206968586225e-16_dp, 8.22063524662433e-18_dp, 4.110317623312165e-19_dp, &
      1.9572941063391263e-20_dp, 8.896791392450574e-22_dp, 3.868170170630684e-23_dp, &
      1.6117375710961184e-24_dp, 6.446950284384474e-26_dp, 2.4795962632247976e-27_dp, &
      9.183689863795546e-29_dp, 3.279889237069838e-30_dp, 1.1309962886447716e-31_dp, &
      3.7699876288159054e-33_dp, 1.216125041553518e-34_dp, 3.8003907548547434e-36_dp, &
      1.151633562077195e-37_dp, 3.387157535521162e-39_dp, 9.67759295863189e-41_dp, &
      2.6882202662866363e-42_dp, 7.265460179153071e-44_dp, 1.911963205040282e-45_dp, &
      4.902469756513544e-47_dp, 1.2256174391283858e-48_dp, 2.9893108271424046e-50_dp, &
      7.117406731291439e-52_dp, 1.6552108677421951e-53_dp, 3.7618428812322616e-55_dp, &
      8.359650847182804e-57_dp, 1.817315401561479e-58_dp, 3.866628513960594e-60_dp, &
      8.055476070751236e-62_dp, 1.643974708316579e-63_dp, 3.287949416633158e-65_dp, &
      6.446959640457172e-67_dp, 1.2397999308571486e-68_dp, 2.3392451525606576e-70_dp, &
      4.331935467704922e-72_dp, 7.876246304918039e-74_dp, 1.4064725544496498e-75_dp, &
      2.4674957095607893e-77_dp, 4.254302947518602e-79_dp, 7.2106829618959365e-81_dp, &
      1.2017804936493226e-82_dp, 1.9701319568021682e-84_dp, 3.1776321883905942e-86_dp, &
      5.043860616493007e-88_dp]
    symtmm_ifact = table(n)
  end function symtmm_ifact

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
