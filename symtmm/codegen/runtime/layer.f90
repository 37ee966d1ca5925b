  ! symtmm codegen runtime, beams joined by continuous layers (after core.f90): one
  ! member of nb beams whose transfer matrix is the single beam's with the scalar x
  ! replaced by the nb x nb matrix X = -(diag(A lam^2 + F) + K + lam C)
  ! (symtmm.elements.layer): blocks c_j(X) above the diagonal and X c_j(X) below,
  ! c_j(X) = sum_k X^k / (4k+j)!, in the state Y_1..Y_nb, Theta_1.., M_1.., Q_1..
  ! The member's constants cp: l, A (nb), F (nb), K (nb x nb), C (nb x nb), l^2/EI
  ! (nb), l^3/EI (nb); A = m l^4/EI, F = kw l^4/EI, K and C the layers' Laplacians
  ! of stiffness and damping times l^4/EI, row by row.

  ! |beta| l of the member: the fourth root of the infinity norm of X, |lam| taken as
  ! sqrt|lam2|
  real(dp) function symtmm_wave_coupled(lam2, cp, nb)
    complex(dp), intent(in) :: lam2
    real(dp), intent(in) :: cp(:)
    integer, intent(in) :: nb
    real(dp) :: la, row
    complex(dp) :: x
    integer :: i, j
    la = sqrt(abs(lam2))
    symtmm_wave_coupled = 0.0_dp
    do i = 1, nb
      row = 0.0_dp
      do j = 1, nb
        x = cp(1 + 2 * nb + (i - 1) * nb + j)
        if (i == j) x = x + cp(1 + i) * lam2 + cp(1 + nb + i)
        row = row + abs(x) + abs(cp(1 + 2 * nb + nb * nb + (i - 1) * nb + j)) * la
      end do
      symtmm_wave_coupled = max(symtmm_wave_coupled, row)
    end do
    symtmm_wave_coupled = symtmm_wave_coupled**0.25_dp
  end function symtmm_wave_coupled

  ! transfer matrix of one of n equal steps of the member (|X| <= nu_step^4 = 256 per
  ! step: 11 terms, the rest below 1e-27); I for l = 0
  subroutine symtmm_segment_coupled(lam, lam2, cp, nb, n, u)
    complex(dp), intent(in) :: lam, lam2
    real(dp), intent(in) :: cp(:)
    integer, intent(in) :: nb, n
    complex(dp), intent(out) :: u(4 * nb, 4 * nb)
    complex(dp) :: x(nb, nb), p(nb, nb), c(nb, nb, 0:3), xc(nb, nb, 1:3), v(nb, nb)
    real(dp) :: steps, h, s(nb, 0:3)
    integer :: i, j, k, q, a, b, kk, ck, cc
    u = (0.0_dp, 0.0_dp)
    if (cp(1) == 0.0_dp) then
      do i = 1, 4 * nb
        u(i, i) = (1.0_dp, 0.0_dp)
      end do
      return
    end if
    steps = real(n, dp)
    kk = 1 + 2 * nb
    ck = kk + nb * nb
    cc = ck + nb * nb
    p = (0.0_dp, 0.0_dp)
    c = (0.0_dp, 0.0_dp)
    do i = 1, nb
      do j = 1, nb
        x(i, j) = cp(kk + (i - 1) * nb + j) + lam * cp(ck + (i - 1) * nb + j)
      end do
      x(i, i) = x(i, i) + cp(1 + i) * lam2 + cp(1 + nb + i)
      p(i, i) = (1.0_dp, 0.0_dp)
      do q = 0, 3
        c(i, i, q) = symtmm_ifact(q)
      end do
    end do
    x = -x / steps**4
    do k = 1, 10
      p = matmul(p, x)
      do q = 0, 3
        c(:, :, q) = c(:, :, q) + symtmm_ifact(4 * k + q) * p
      end do
    end do
    do q = 1, 3
      xc(:, :, q) = matmul(x, c(:, :, q))
    end do
    ! the scaled state (Y, h Theta, h^2 M/EI, h^3 Q/EI) back to (Y, Theta, M, Q)
    h = cp(1) / steps
    do i = 1, nb
      s(i, 0) = 1.0_dp
      s(i, 1) = h
      s(i, 2) = cp(cc + i) / steps**2
      s(i, 3) = cp(cc + nb + i) / steps**3
    end do
    do a = 0, 3
      do b = 0, 3
        if (b >= a) then
          v = c(:, :, b - a)
        else
          v = xc(:, :, 4 + b - a)
        end if
        do i = 1, nb
          do j = 1, nb
            u(a * nb + i, b * nb + j) = v(i, j) * (s(j, b) / s(i, a))
          end do
        end do
      end do
    end do
  end subroutine symtmm_segment_coupled
