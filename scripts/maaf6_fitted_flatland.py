#!/usr/bin/python3
"""The maaf6 filter's pair weights in flatland: N = 1, MAAF Eq. 10 and the fitted weights (issue 15).

One 2D (x, y) subspace as the maaf6 filter realises it: pixels 1 apart, y drawn from a uniform light
on [-1, 1] with Omega_y^max = 2 (the toolkit's 2 / sigma, sigma = half the side), the pixel band
2 / pixel; components of MAAF Eq. 6-8 (N = 3), x kernels as aaf::maaf6_x_kernel (k = 1, each pair's
cos part less its DC), the light as the y envelope, the window 3 central stds (at most 12 px). The
signal is a step edge sheared by s (v(x, y) = [x - x0 + s y > 0]) at 5 slopes across [s_min, s_max]
and 33 positions x0; the filter is applied to the converged light integral of every channel (Gauss-
Legendre, 200 nodes), so its error is the bias alone. "noise" is the output variance per unit
variance of one sample (sum over taps of E_y[K^2] / (sum K)^2). The fitted weights solve the least
squares of aaf::maaf_fit_pair_weights in the Fourier domain (slopes uniform in 1 / s, 1 / W^2).

Usage: maaf6_fitted_flatland.py   (prints a table; a few seconds)
"""
import numpy as np

Y, YW = np.polynomial.legendre.leggauss(200)
YW = YW / YW.sum()
OMEGA_Y = 2.0
PIXEL_BAND = 2.0


def gauss(t, s):
    return np.exp(-t * t / (2 * s * s))


def components(s_min, s_max, pairs):
    omega = min(OMEGA_Y, s_min * PIXEL_BAND)
    e_min, e_max = min(OMEGA_Y / s_min, PIXEL_BAND), omega / s_max
    seg = 2 * pairs - 1
    out = []
    for p in range(pairs):
        inner, outer = (2 * p - 1) / seg, (2 * p + 1) / seg
        out.append(dict(cx=0.5 * (p > 0) * (e_max * inner + e_min * outer), cy=omega * 2 * p / seg,  # Eq. 6-7
                        sx=e_min / seg if p == 0 else 0.5 * (e_min * outer - e_max * inner),          # Eq. 8
                        mu=gauss(0.5 * (p > 0) * (e_max * inner + e_min * outer), e_min) * gauss(omega * 2 * p / seg, omega)))
    return out


def kernel(comps, mus, radius, k=1.0):
    dx, y = np.arange(-radius, radius + 1)[:, None], Y[None, :]
    out = gauss(dx, k / comps[0]["sx"]) * np.ones_like(y)
    for c, mu in zip(comps[1:], mus[1:]):
        dc = np.exp(-0.5 * (k * c["cx"] / c["sx"]) ** 2)
        out = out + 2 * mu * ((np.cos(c["cx"] * dx) - dc) * np.cos(c["cy"] * y)
                              - np.sin(c["cx"] * dx) * np.sin(c["cy"] * y)) * gauss(dx, k / c["sx"])
    return out


def bias_and_noise(s_min, s_max, pairs, mus=None):
    comps = components(s_min, s_max, pairs)
    mus = [c["mu"] for c in comps] if mus is None else mus
    radius = int(min(12, np.ceil(3 / comps[0]["sx"])))
    k = kernel(comps, mus, radius)
    dx = np.arange(-radius, radius + 1)[:, None]
    den = (k * YW).sum()
    errors = []
    for s in np.linspace(s_min, s_max, 5):
        for x0 in np.linspace(-4, 4, 33):
            v = ((dx - x0) + s * Y[None, :] > 0).astype(float)
            errors.append((k * v * YW).sum() / den - ((-x0 + s * Y) > 0).astype(float) @ YW)
    return float(np.sqrt(np.mean(np.square(errors)))), float((k * k * YW).sum() / den ** 2)


def fitted(t, pairs, k=1.0, slopes=9, freqs=400):
    comps = components(1.0, 1.0 / t, pairs)  # s_min = 1 (x scales with it), no pixel-band clip
    phi = lambda w: np.sinc(w / np.pi)       # the uniform light's spectrum
    a = [k / c["sx"] for c in comps]
    g = lambda w, ap: ap * np.exp(-0.5 * (w * ap) ** 2)
    w = np.linspace(1e-3, 4 * OMEGA_Y, freqs)[None, :]
    s = 1.0 / np.linspace(1.0, t, slopes)[:, None]
    target = phi(w * s)
    residual = (g(w, a[0]) * target / a[0] - target) / w
    basis = []
    for c, ap in zip(comps[1:], a[1:]):
        dc = np.exp(-0.5 * (k * c["cx"] / c["sx"]) ** 2)
        lo, hi = phi(w * s - c["cy"]), phi(w * s + c["cy"])
        basis.append(((g(w - c["cx"], ap) * lo + g(w + c["cx"], ap) * hi - dc * g(w, ap) * (lo + hi)) / a[0] / w).ravel())
    mu, *_ = np.linalg.lstsq(np.stack(basis, 1), -residual.ravel(), rcond=None)
    return [1.0] + list(mu)


def main():
    print("s_min  s_max   N = 1 bias / noise   Eq. 10 bias / noise   fitted bias / noise   fitted mu_1, mu_2")
    for s_min, s_max in ((1.05, 1.1), (1.1, 1.5), (1.4, 1.6), (1.2, 2.4), (1.5, 3.0), (1.2, 6.0)):
        mus = fitted(s_min / s_max, 3)
        rows = [bias_and_noise(s_min, s_max, 1), bias_and_noise(s_min, s_max, 3), bias_and_noise(s_min, s_max, 3, mus)]
        print(f"{s_min:5.2f} {s_max:5.2f}   " + "   ".join(f"{b:.4f} / {n:.3f}     " for b, n in rows)
              + f"{mus[1]:.2f}, {mus[2]:.2f}")


if __name__ == "__main__":
    main()
