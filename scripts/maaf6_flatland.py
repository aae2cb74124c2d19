#!/usr/bin/python3
"""MAAF (N = 3) against its central filter alone (N = 1) in an ideal flatland (issue 15).

A stationary, thin y-wedge: f(x, y) = V(x + s y), V a square wave of period 173 px,
y uniform on a light [-L, L] (L = 0.6 m, room's light), pixels of size d = 1 m apart
sampled at their centres with n light samples each, s set so that the wedge's x extent
E = Omega_y^max / s is E d = 0.5 or 1 (room's direct layer: median 0.5, 160x120), slopes
[0.999 s, 1.03 s] (room's median s_max / s_min is 1.03). The filters are the maaf6 filter's
in 1D: the partition of MAAF Eq. 6-10 (as aaf::maaf_components), x kernels as
aaf::maaf6_x_kernel (k = 1, zero-mean pairs), y envelopes the sampling density (the light),
the result divided by the same filter applied to the weights (1, cos, sin), taps 60 px
either side (no window limit). Error: RMSE against the exact light integral, mean of 3
seeds, 2 x 60 px margins left out. Omega_y^max is the toolkit's 2 / L (2 / sigma with
sigma = L for a uniform light) or the paper's 4 / L (MAAF Sec. 3, L = 2 sigma_y); pair
weights MAAF Eq. 10, or Eq. 10 times the uniform light's spectrum sinc(C_y L) at the pair's
y centre. Orientation: the tap-minus-centre sign that the filter uses (the other one is
2-3x worse and not shown).

Usage: maaf6_flatland.py   (prints a table; about a minute)
"""
import numpy as np

LIGHT_HALF_WIDTH_M = 0.6
PERIOD_PX = 173.0
REACH_PX = 60
PIXELS = 3000


def components(s_min, s_max, omega_x_max, omega_y_max, pairs):
    """MAAF Eq. 6-10 with MAAF Sec. 6.2's clip, as aaf::maaf_components (p = 0 .. N-1)."""
    extent = min(omega_y_max / s_min, omega_x_max)
    omega = min(omega_y_max, s_min * omega_x_max)
    extent_max = omega / s_max
    segments = 2 * pairs - 1
    out = []
    for p in range(pairs):
        inner, outer = (2 * p - 1) / segments, (2 * p + 1) / segments
        centre_y = omega * 2 * p / segments                                         # Eq. 6
        centre_x = 0.0 if p == 0 else 0.5 * (extent_max * inner + extent * outer)   # Eq. 7
        sigma_x = extent / segments if p == 0 else 0.5 * (extent * outer - extent_max * inner)  # Eq. 8
        weight = np.exp(-0.5 * (centre_x / extent) ** 2) * np.exp(-0.5 * (centre_y / omega) ** 2)  # Eq. 10
        out.append((centre_x, sigma_x, centre_y, weight))
    return out


def run(pairs, spp, band, extent_px, seed, pair_weights="eq10", k=1.0):
    rng = np.random.default_rng(seed)
    half = LIGHT_HALF_WIDTH_M
    omega_y_max = band / half
    s = omega_y_max / extent_px  # E d = extent_px with d = 1
    x = np.arange(PIXELS, dtype=float)
    edge = lambda t: ((np.floor(t / PERIOD_PX) % 2) == 0).astype(float)
    y = rng.uniform(-half, half, (PIXELS, spp))
    f = edge(x[:, None] + s * y)
    exact = edge(x[:, None] + s * np.linspace(-half, half, 4001)[None, :]).mean(1)
    comps = components(0.999 * s, 1.03 * s, 2.0, omega_y_max, pairs)  # pixel band 2 / d
    sums, weights = [f.mean(1)], [np.ones(PIXELS)]
    for centre_x, sigma_x, centre_y, weight in comps[1:]:
        sums += [(f * np.cos(centre_y * y)).mean(1), (f * np.sin(centre_y * y)).mean(1)]
        weights += [np.cos(centre_y * y).mean(1), np.sin(centre_y * y).mean(1)]
    dx = np.arange(-REACH_PX, REACH_PX + 1, dtype=float)  # tap minus centre
    kernels = [np.exp(-0.5 * (dx * comps[0][1] / k) ** 2)]
    for centre_x, sigma_x, centre_y, weight in comps[1:]:
        if pair_weights == "sinc":
            weight *= np.sinc(centre_y * half / np.pi)  # the uniform light's spectrum at C_y
        envelope = np.exp(-0.5 * (dx * sigma_x / k) ** 2)
        dc = np.exp(-0.5 * (centre_x * k / sigma_x) ** 2)
        kernels += [2 * weight * (np.cos(centre_x * dx) - dc) * envelope,
                    -2 * weight * np.sin(centre_x * dx) * envelope]
    gather = lambda plane, kernel: np.convolve(plane, kernel[::-1], mode="same")
    out = sum(gather(p, q) for p, q in zip(sums, kernels)) / sum(gather(p, q) for p, q in zip(weights, kernels))
    inside = slice(REACH_PX, PIXELS - REACH_PX)
    rmse = lambda image: float(np.sqrt(((image - exact)[inside] ** 2).mean()))
    return rmse(out), rmse(f.mean(1))


def main():
    print("band      E d  spp   input     N = 1     N = 3 Eq. 10   N = 3 sinc weights")
    for band, label in ((2.0, "2 / L"), (4.0, "4 / L")):
        for extent_px in (0.5, 1.0):
            for spp in (4, 16, 64, 1024):
                mean = lambda **a: np.mean([run(spp=spp, band=band, extent_px=extent_px, seed=s, **a)[0]
                                            for s in range(3)])
                unfiltered = np.mean([run(1, spp, band, extent_px, s)[1] for s in range(3)])
                print(f"{label}  {extent_px:4.1f} {spp:4d}   {unfiltered:.4f}    {mean(pairs=1):.4f}    "
                      f"{mean(pairs=3):.4f}         {mean(pairs=3, pair_weights='sinc'):.4f}")


if __name__ == "__main__":
    main()
