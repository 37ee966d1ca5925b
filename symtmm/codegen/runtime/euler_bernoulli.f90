  ! symtmm codegen runtime, Euler-Bernoulli segments (after core.f90): the transfer
  ! matrix from the entire functions c_j(x) = sum_k x^k / (4k+j)!, x = -lam^2 m l^4/EI,
  ! with no branch to choose and no 0/0 at lam = 0.

  ! c_0..c_3 of x: series below |x| = 1, closed forms in x^(1/4) above
  subroutine symtmm_cfun(x, c)
    complex(dp), intent(in) :: x
    complex(dp), intent(out) :: c(0:3)
    complex(dp) :: nu, ch, co, sh, si
    integer :: j, k
    if (abs(x) < 1.0_dp) then   ! 16 terms: 1/(4k+j)! < 1e-80 beyond
      do j = 0, 3
        c(j) = (0.0_dp, 0.0_dp)
        do k = 15, 0, -1
          c(j) = c(j) * x + symtmm_ifact(4 * k + j)
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
