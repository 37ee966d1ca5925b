  ! symtmm codegen runtime, beam theories other than the plain Euler-Bernoulli one
  ! (after core.f90): axial force N, rotary inertia rhoI, shear stiffness kGA, a
  ! foundation kw, as symtmm.elements.theories computes them. A theory is
  ! th = [EI, a, b, cN, rhoI, m, kw]: c = cN + rhoI lam2, mu = m lam2 + kw.

  ! c, mu and t, d, the trace and determinant of G = B C, of the theory th at lam2
  subroutine symtmm_invariants(lam2, th, c, mu, t, d)
    complex(dp), intent(in) :: lam2
    real(dp), intent(in) :: th(7)
    complex(dp), intent(out) :: c, mu, t, d
    c = th(4) + th(5) * lam2
    mu = th(6) * lam2 + th(7)
    t = c / th(1) - th(3) * mu
    d = mu * (th(2) * th(2) - th(3) * c) / th(1)
  end subroutine symtmm_invariants

  ! a bound on the largest wave number |s| of the theory th at lam2 (1/length)
  real(dp) function symtmm_wave(lam2, th)
    complex(dp), intent(in) :: lam2
    real(dp), intent(in) :: th(7)
    complex(dp) :: c, mu, t, d
    call symtmm_invariants(lam2, th, c, mu, t, d)
    symtmm_wave = sqrt(abs(t) / 2.0_dp + sqrt(abs(t)**2 / 4.0_dp + abs(d)))
  end function symtmm_wave

  ! transfer matrix exp(A h) of one of n equal steps h = l/n of a segment of the
  ! theory th, [Y, Theta, M, Q]: alpha, beta of F0 = cosh(s h), F1 = sinh(s h)/s from
  ! their series in (t, d) on a piece h/2^j with max|r| (h/2^j)^2 <= 1, then doubled
  ! j times; U = [[F0(G), B F1(G')], [C F1(G), F0(G')]], G = B C on (Y, M), G' = C B
  ! on (Theta, Q), B = [[a, b], [c, a]], C = [[0, 1/EI], [-mu, 0]]
  subroutine symtmm_segment_gen(lam2, th, l, n, u)
    complex(dp), intent(in) :: lam2
    real(dp), intent(in) :: th(7), l
    integer, intent(in) :: n
    complex(dp), intent(out) :: u(4, 4)
    complex(dp) :: c, mu, t, d, ts, ds, qp, q, qn, s0a, s0b, s1a, s1b
    complex(dp) :: a0, b0, a1, b1, na0, nb0, na1, nb1
    complex(dp) :: g00, g01, g10, g11, p00, p01, p10, p11, h00, h01, h10, h11
    complex(dp) :: k00, k01, k10, k11
    real(dp) :: ei, a, b, w, h
    integer :: i, j, k
    ei = th(1)
    a = th(2)
    b = th(3)
    call symtmm_invariants(lam2, th, c, mu, t, d)
    w = symtmm_wave(lam2, th)
    h = l / n
    j = 0
    do while (w * h > 1.0_dp)
      h = h / 2.0_dp
      j = j + 1
    end do
    ts = t * h * h
    ds = d * (h * h) * (h * h)
    qp = (0.0_dp, 0.0_dp)
    q = (1.0_dp, 0.0_dp)
    s0a = qp; s0b = qp; s1a = qp; s1b = qp
    do k = 1, 13   ! k/(2k)! < 1e-18 beyond: the error for w h <= 1
      s0b = s0b + q * symtmm_ifact(2 * k)
      s0a = s0a + qp * symtmm_ifact(2 * k)
      s1b = s1b + q * symtmm_ifact(2 * k + 1)
      s1a = s1a + qp * symtmm_ifact(2 * k + 1)
      qn = ts * q - ds * qp
      qp = q
      q = qn
    end do
    a0 = 1.0_dp - ds * s0a
    b0 = h * h * s0b
    a1 = h * (1.0_dp - ds * s1a)
    b1 = h * h * h * s1b
    do i = 1, j   ! F0(2h) = 2 F0^2 - I, F1(2h) = 2 F0 F1
      na0 = 2.0_dp * (a0 * a0 - d * b0 * b0) - 1.0_dp
      nb0 = 2.0_dp * (2.0_dp * a0 * b0 + t * b0 * b0)
      na1 = 2.0_dp * (a0 * a1 - d * b0 * b1)
      nb1 = 2.0_dp * (a0 * b1 + a1 * b0 + t * b0 * b1)
      a0 = na0
      b0 = nb0
      a1 = na1
      b1 = nb1
    end do
    g00 = -b * mu; g01 = a / ei; g10 = -a * mu; g11 = c / ei   ! G
    p00 = c / ei; p01 = a / ei; p10 = -mu * a; p11 = -mu * b   ! G'
    u(1, 1) = a0 + b0 * g00
    u(1, 3) = b0 * g01
    u(3, 1) = b0 * g10
    u(3, 3) = a0 + b0 * g11
    u(2, 2) = a0 + b0 * p00
    u(2, 4) = b0 * p01
    u(4, 2) = b0 * p10
    u(4, 4) = a0 + b0 * p11
    h00 = a1 + b1 * p00; h01 = b1 * p01; h10 = b1 * p10; h11 = a1 + b1 * p11
    u(1, 2) = a * h00 + b * h10
    u(1, 4) = a * h01 + b * h11
    u(3, 2) = c * h00 + a * h10
    u(3, 4) = c * h01 + a * h11
    k00 = a1 + b1 * g00; k01 = b1 * g01; k10 = b1 * g10; k11 = a1 + b1 * g11
    u(2, 1) = k10 / ei
    u(2, 3) = k11 / ei
    u(4, 1) = -mu * k00
    u(4, 3) = -mu * k01
  end subroutine symtmm_segment_gen
