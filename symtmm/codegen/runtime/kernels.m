% symtmm codegen runtime: the fixed kernels of a generated Octave/MATLAB evaluator,
% included verbatim after it as subfunctions of the file symtmm_delta.m.

function D = symtmm_units(b, EI, L)
  % units of one beam's state: 1, 1/b, 1/(EI b^2), 1/(EI b^3), b >= 1/L the wave number
  b = max(b, 1 / L);
  D = [1; 1 / b; 1 / (EI * b^2); 1 / (EI * b^3)];
end

function f = symtmm_ifact()
  % 1/n!, n = 0 .. 63 (f(n + 1)), exact to double: the series of both segment kinds
  f = [...
       1.0, 1.0, 0.5, 0.16666666666666666, ...
       0.041666666666666664, 0.008333333333333333, 0.001388888888888889, 0.0001984126984126984, ...
       2.48015873015873e-05, 2.7557319223985893e-06, 2.755731922398589e-07, 2.505210838544172e-08, ...
       2.08767569878681e-09, 1.6059043836821613e-10, 1.1470745597729725e-11, 7.647163731819816e-13, ...
       4.779477332387385e-14, 2.8114572543455206e-15, 1.5619206968586225e-16, 8.22063524662433e-18, ...
       4.110317623312165e-19, 1.9572941063391263e-20, 8.896791392450574e-22, 3.868170170630684e-23, ...
       1.6117375710961184e-24, 6.446950284384474e-26, 2.4795962632247976e-27, 9.183689863795546e-29, ...
       3.279889237069838e-30, 1.1309962886447716e-31, 3.7699876288159054e-33, 1.216125041553518e-34, ...
       3.8003907548547434e-36, 1.151633562077195e-37, 3.387157535521162e-39, 9.67759295863189e-41, ...
       2.6882202662866363e-42, 7.265460179153071e-44, 1.911963205040282e-45, 4.902469756513544e-47, ...
       1.2256174391283858e-48, 2.9893108271424046e-50, 7.117406731291439e-52, 1.6552108677421951e-53, ...
       3.7618428812322616e-55, 8.359650847182804e-57, 1.817315401561479e-58, 3.866628513960594e-60, ...
       8.055476070751236e-62, 1.643974708316579e-63, 3.287949416633158e-65, 6.446959640457172e-67, ...
       1.2397999308571486e-68, 2.3392451525606576e-70, 4.331935467704922e-72, 7.876246304918039e-74, ...
       1.4064725544496498e-75, 2.4674957095607893e-77, 4.254302947518602e-79, 7.2106829618959365e-81, ...
       1.2017804936493226e-82, 1.9701319568021682e-84, 3.1776321883905942e-86, 5.043860616493007e-88];
end

function [E, logscale] = symtmm_orthonormalise(E, logscale)
  % E := Q of E = Q F (Householder), and logscale := logscale + log det F
  [E, F] = qr(E, 0);
  logscale = logscale + sum(log(diag(F)));
end

% Euler-Bernoulli segments: the transfer matrix from the entire functions
% c_j(x) = sum_k x^k / (4k+j)!, x = -lam^2 m l^4/EI, with no branch to choose and
% no 0/0 at lam = 0.

function c = symtmm_cfun(x)
  % c_0..c_3 of x: series below |x| = 1, closed forms in x^(1/4) above
  ifact = symtmm_ifact();
  c = zeros(1, 4);
  if abs(x) < 1   % 16 terms: 1/(4k+j)! < 1e-80 beyond
    for j = 1:4
      acc = 0;
      for k = 16:-1:1
        acc = acc * x + ifact(4 * (k - 1) + j);
      end
      c(j) = acc;
    end
  else
    nu = x^0.25;
    c(1) = (cosh(nu) + cos(nu)) / 2;
    c(2) = (sinh(nu) + sin(nu)) / (2 * nu);
    c(3) = (cosh(nu) - cos(nu)) / (2 * nu^2);
    c(4) = (sinh(nu) - sin(nu)) / (2 * nu^3);
  end
end

function U = symtmm_segment(lam2, a, l, EI, n)
  % transfer matrix of one of n equal steps of an Euler-Bernoulli segment of length l,
  % a = m l^4 / EI (lam2 shifted by kw/m on a foundation); I for l = 0
  if l == 0
    U = eye(4);
    return
  end
  x = -lam2 * (a / n^4);
  c = symtmm_cfun(x);
  h = l / n;
  U = [c(1), h*c(2), h^2*c(3)/EI, h^3*c(4)/EI;
       x*c(4)/h, c(1), h*c(2)/EI, h^2*c(3)/EI;
       EI*x*c(3)/h^2, EI*x*c(4)/h, c(1), h*c(2);
       EI*x*c(2)/h^3, EI*x*c(3)/h^2, x*c(4)/h, c(1)];
end

% Beam theories other than the plain Euler-Bernoulli one: axial force N, rotary
% inertia rhoI, shear stiffness kGA, a foundation kw, as symtmm.elements.theories
% computes them. A theory is th = [EI, a, b, cN, rhoI, m, kw]: c = cN + rhoI lam2,
% mu = m lam2 + kw.

function [c, mu, t, d] = symtmm_invariants(lam2, th)
  % c, mu and t, d, the trace and determinant of G = B C, of the theory th at lam2
  c = th(4) + th(5) * lam2;
  mu = th(6) * lam2 + th(7);
  t = c / th(1) - th(3) * mu;
  d = mu * (th(2) * th(2) - th(3) * c) / th(1);
end

function w = symtmm_wave(lam2, th)
  % a bound on the largest wave number |s| of the theory th at lam2 (1/length)
  [~, ~, t, d] = symtmm_invariants(lam2, th);
  w = sqrt(abs(t) / 2 + sqrt(abs(t)^2 / 4 + abs(d)));
end

function U = symtmm_segment_gen(lam2, th, l, n)
  % transfer matrix exp(A h) of one of n equal steps h = l/n of a segment of the
  % theory th, [Y, Theta, M, Q]: alpha, beta of F0 = cosh(s h), F1 = sinh(s h)/s from
  % their series in (t, d) on a piece h/2^j with max|r| (h/2^j)^2 <= 1, then doubled
  % j times; U = [[F0(G), B F1(G')], [C F1(G), F0(G')]], G = B C on (Y, M), G' = C B
  % on (Theta, Q), B = [[a, b], [c, a]], C = [[0, 1/EI], [-mu, 0]]
  ifact = symtmm_ifact();
  EI = th(1); a = th(2); b = th(3);
  [c, mu, t, d] = symtmm_invariants(lam2, th);
  w = symtmm_wave(lam2, th);
  h = l / n;
  nd = 0;
  while w * h > 1
    h = h / 2;
    nd = nd + 1;
  end
  T = t * h * h;
  DD = d * (h * h) * (h * h);
  qp = 0; q = 1; s0a = 0; s0b = 0; s1a = 0; s1b = 0;
  for k = 1:13   % k/(2k)! < 1e-18 beyond: the error for w h <= 1
    s0b = s0b + q * ifact(2 * k + 1);
    s0a = s0a + qp * ifact(2 * k + 1);
    s1b = s1b + q * ifact(2 * k + 2);
    s1a = s1a + qp * ifact(2 * k + 2);
    qn = T * q - DD * qp;
    qp = q;
    q = qn;
  end
  a0 = 1 - DD * s0a; b0 = h * h * s0b;
  a1 = h * (1 - DD * s1a); b1 = h * h * h * s1b;
  for it = 1:nd   % F0(2h) = 2 F0^2 - I, F1(2h) = 2 F0 F1
    na0 = 2 * (a0 * a0 - d * b0 * b0) - 1;
    nb0 = 2 * (2 * a0 * b0 + t * b0 * b0);
    na1 = 2 * (a0 * a1 - d * b0 * b1);
    nb1 = 2 * (a0 * b1 + a1 * b0 + t * b0 * b1);
    a0 = na0; b0 = nb0; a1 = na1; b1 = nb1;
  end
  G = [-b * mu, a / EI; -a * mu, c / EI];     % B C, on (Y, M)
  P = [c / EI, a / EI; -mu * a, -mu * b];     % C B, on (Theta, Q)
  F1P = a1 * eye(2) + b1 * P;
  F1G = a1 * eye(2) + b1 * G;
  U = zeros(4, 4);
  U([1 3], [1 3]) = a0 * eye(2) + b0 * G;
  U([2 4], [2 4]) = a0 * eye(2) + b0 * P;
  U([1 3], [2 4]) = [a, b; c, a] * F1P;
  U([2 4], [1 3]) = [0, 1 / EI; -mu, 0] * F1G;
end

% Beams joined by continuous layers: one member of nb beams whose transfer matrix is
% the single beam's with the scalar x replaced by the nb x nb matrix
% X = -(diag(A lam^2 + F) + K + lam C) (symtmm.elements.layer): blocks c_j(X) above
% the diagonal and X c_j(X) below, in the state Y_1..Y_nb, Theta_1.., M_1.., Q_1..
% The member's constants cp: l, A (nb), F (nb), K (nb x nb), C (nb x nb), l^2/EI (nb),
% l^3/EI (nb); K and C are the layers' Laplacians times l^4/EI, row by row.

function [l, A, F, K, C, sM, sQ] = symtmm_coupled_parts(cp, nb)
  l = cp(1);
  A = cp(2:1 + nb);
  F = cp(2 + nb:1 + 2 * nb);
  K = reshape(cp(2 + 2 * nb:1 + 2 * nb + nb^2), nb, nb).';
  C = reshape(cp(2 + 2 * nb + nb^2:1 + 2 * nb + 2 * nb^2), nb, nb).';
  sM = cp(2 + 2 * nb + 2 * nb^2:1 + 3 * nb + 2 * nb^2);
  sQ = cp(2 + 3 * nb + 2 * nb^2:1 + 4 * nb + 2 * nb^2);
end

function w = symtmm_wave_coupled(lam2, cp, nb)
  % |beta| l of the member: the fourth root of the infinity norm of X (|lam| as sqrt|lam2|)
  [~, A, F, K, C] = symtmm_coupled_parts(cp, nb);
  M = abs(K + diag(A * lam2 + F)) + abs(C) * sqrt(abs(lam2));
  w = max(sum(M, 2))^0.25;
end

function U = symtmm_segment_coupled(lm, lam2, cp, nb, n)
  % transfer matrix of one of n equal steps of the member (|X| <= nu_step^4 = 256 per
  % step: 11 terms, the rest below 1e-27); I for l = 0
  [l, A, F, K, C, sM, sQ] = symtmm_coupled_parts(cp, nb);
  if l == 0
    U = eye(4 * nb);
    return
  end
  f = symtmm_ifact();
  X = -(K + lm * C + diag(A * lam2 + F)) / n^4;
  c = cell(1, 4);
  for q = 1:4
    c{q} = f(q) * eye(nb);
  end
  P = eye(nb);
  for k = 1:10
    P = P * X;
    for q = 1:4
      c{q} = c{q} + f(4 * k + q) * P;
    end
  end
  % the scaled state (Y, h Theta, h^2 M/EI, h^3 Q/EI) back to (Y, Theta, M, Q)
  h = l / n;
  s = [ones(1, nb); h * ones(1, nb); sM / n^2; sQ / n^3];
  U = zeros(4 * nb);
  for a = 0:3
    for b = 0:3
      if b >= a
        V = c{b - a + 1};
      else
        V = X * c{4 + b - a + 1};
      end
      U(a * nb + (1:nb), b * nb + (1:nb)) = V .* (s(b + 1, :) ./ s(a + 1, :).');
    end
  end
end
