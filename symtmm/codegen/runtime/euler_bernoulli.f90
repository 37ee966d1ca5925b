  ! symtmm codegen runtime, Euler-Bernoulli segments (after core.f90): the transfer
  ! matrix from the entire functions c_j(x) = sum_k x^k / (4k+j)!, x = -lam^2 m l^4/EI,
  ! with no branch to choose and no 0/0 at lam = 0.

  ! c_0..c_3 of x: series below |x| = 1, closed forms in x^(1/4) above
  subroutine symtmm_cfun(x, c)
    complex(dp), intent(in) :: x
    complex(dp), intent(out) :: c(0:3)
    ! 1/(4k+j)!, exact to double; 16 terms: the last is below 1e-80
    real(dp), parameter :: coef(0:15, 0:3) = reshape([ &
      1.0_dp, 0.041666666666666664_dp, 2.48015873015873e-05_dp, 2.08767569878681e-09_dp, &
      4.779477332387385e-14_dp, 4.110317623312165e-19_dp, 1.6117375710961184e-24_dp, &
      3.279889237069838e-30_dp, 3.8003907548547434e-36_dp, 2.6882202662866363e-42_dp, &
      1.2256174391283858e-48_dp, 3.7618428812322616e-55_dp, 8.055476070751236e-62_dp, &
      1.2397999308571486e-68_dp, 1.4064725544496498e-75_dp, 1.2017804936493226e-82_dp, &
      1.0_dp, 0.008333333333333333_dp, 2.7557319223985893e-06_dp, 1.6059043836821613e-10_dp, &
      2.8114572543455206e-15_dp, 1.9572941063391263e-20_dp, 6.446950284384474e-26_dp, &
      1.1309962886447716e-31_dp, 1.151633562077195e-37_dp, 7.265460179153071e-44_dp, &
      2.9893108271424046e-50_dp, 8.359650847182804e-57_dp, 1.643974708316579e-63_dp, &
      2.3392451525606576e-70_dp, 2.4674957095607893e-77_dp, 1.9701319568021682e-84_dp, &
      0.5_dp, 0.001388888888888889_dp, 2.755731922398589e-07_dp, 1.1470745597729725e-11_dp, &
      1.5619206968586225e-16_dp, 8.896791392450574e-22_dp, 2.4795962632247976e-27_dp, &
      3.7699876288159054e-33_dp, 3.387157535521162e-39_dp, 1.911963205040282e-45_dp, &
      7.117406731291439e-52_dp, 1.817315401561479e-58_dp, 3.287949416633158e-65_dp, &
      4.331935467704922e-72_dp, 4.254302947518602e-79_dp, 3.1776321883905942e-86_dp, &
      0.16666666666666666_dp, 0.0001984126984126984_dp, 2.505210838544172e-08_dp, &
      7.647163731819816e-13_dp, 8.22063524662433e-18_dp, 3.868170170630684e-23_dp, &
      9.183689863795546e-29_dp, 1.216125041553518e-34_dp, 9.67759295863189e-41_dp, &
      4.902469756513544e-47_dp, 1.6552108677421951e-53_dp, 3.866628513960594e-60_dp, &
      6.446959640457172e-67_dp, 7.876246304918039e-74_dp, 7.2106829618959365e-81_dp, &
      5.043860616493007e-88_dp], [16, 4])
    complex(dp) :: nu, ch, co, sh, si
    integer :: j, k
    if (abs(x) < 1.0_dp) then
      do j = 0, 3
        c(j) = (0.0_dp, 0.0_dp)
        do k = 15, 0, -1
          c(j) = c(j) * x + coef(k, j)
        end do
      end do
    else
      nu = x**0.25_dp
      ch = cosh(nu); co = cos(nu); sh = sinh(nu); si = sin(nu)
      c(0) = (ch + co) / 2.0_dp
      c(1) = (sh + si) / (2.0_dp * nu)
      c(2) = (ch - co) / (2.0_dp * nu * nu)
      c(3) = (sh - si) / (2.0_dp * nu * nu * nu)
    end if
  end subroutine symtmm_cfun

  ! transfer matrix of one of n equal steps of an Euler-Bernoulli segment of length l,
  ! a = m l^4 / EI (lam2 shifted by kw/m on a foundation); I for l = 0
  subroutine symtmm_segment(lam2, a, l, ei, n, u)
    complex(dp), intent(in) :: lam2
    real(dp), intent(in) :: a, l, ei
    integer, intent(in) :: n
    complex(dp), intent(out) :: u(4, 4)
    complex(dp) :: x, c(0:3)
    real(dp) :: h, h2, h3
    integer :: i
    if (l == 0.0_dp) then
      u = (0.0_dp, 0.0_dp)
      do i = 1, 4
        u(i, i) = (1.0_dp, 0.0_dp)
      end do
      return
    end if
    x = -lam2 * (a / real(n, dp)**4)
    call symtmm_cfun(x, c)
    h = l / n
    h2 = h * h
    h3 = h * h * h
    u(1, 1) = c(0);           u(1, 2) = h * c(1)
    u(1, 3) = h2 * c(2) / ei; u(1, 4) = h3 * c(3) / ei
    u(2, 1) = x * c(3) / h;   u(2, 2) = c(0)
    u(2, 3) = h * c(1) / ei;  u(2, 4) = h2 * c(2) / ei
    u(3, 1) = ei * x * c(2) / h2; u(3, 2) = ei * x * c(3) / h
    u(3, 3) = c(0);           u(3, 4) = h * c(1)
    u(4, 1) = ei * x * c(1) / h3; u(4, 2) = ei * x * c(2) / h2
    u(4, 3) = x * c(3) / h;   u(4, 4) = c(0)
  end subroutine symtmm_segment
