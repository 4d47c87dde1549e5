#!/usr/bin/env python3
"""Issue 22: what carries a flow run's pile, measured on its final state (run with /usr/bin/python3: scipy, h5py).

Contacts are the overlapping sphere pairs (distance < r_i + r_j). The floor's normal force is Hertz's on each
sphere below its radius, F = 4/3 E* sqrt(r) delta^1.5, with E* of the particle's material against the box wall's
(both read from the scene text stored in the result). The rock's weight is buoyant (the file's fluid density)
below --surface and whole above it. Prints the contact count, how much of the pile (rock above --pile) is in a
contact cluster touching the floor, the floor's share of the weight, and the weight the floor does not carry spread
over the pile's footprint (the 1 cm cells holding pile rock), to compare with the paste's bearing capacity
(Skempton: 5-9 tau_y). The side walls' friction is not counted.

    /usr/bin/python3 scripts/pile_support.py RESULT.h5 [RESULT.h5 ...] [--pile 0.08] [--surface 0.085]
"""
import argparse
import tomllib

import h5py
import numpy as np
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components
from scipy.spatial import cKDTree

G = 9.81  # m/s2


def last_snapshot(h):
    s = h['snapshots']
    return s[sorted(x for x in s.keys() if x.isdigit())[-1]]


def materials(h):
    """Name -> (density kg/m3, E Pa, nu) from the scene text, and the wall material of the box."""
    text = h.attrs['scene_text']
    scene = tomllib.loads(text.decode() if isinstance(text, bytes) else text)
    mats = {m['name']: (m['density'], m['youngs_modulus'], m['poisson_ratio']) for m in scene['material']}
    box = next(w for w in scene['wall'] if w['type'] == 'box')
    return mats, mats[box['material']]


def floor_force(r, z, particle, wall):
    """Hertz normal force (N) of each sphere on the floor z = 0; particle, wall: (E, nu) arrays / pair."""
    (E1, nu1), (E2, nu2) = particle, wall
    e_star = 1.0 / ((1 - nu1**2) / E1 + (1 - nu2**2) / E2)
    delta = np.clip(r - z, 0.0, None)
    return 4.0 / 3.0 * e_star * np.sqrt(r) * delta**1.5


def floor_cluster(x, r):
    """Contacts (overlapping pairs) and a mask of the spheres in a contact cluster touching the floor."""
    pairs = cKDTree(x).query_pairs(2 * r.max(), output_type='ndarray')
    d = np.linalg.norm(x[pairs[:, 0]] - x[pairs[:, 1]], axis=1)
    touch = pairs[d < r[pairs[:, 0]] + r[pairs[:, 1]]]
    n = len(x)
    graph = coo_matrix((np.ones(len(touch)), (touch[:, 0], touch[:, 1])), shape=(n, n))
    _, label = connected_components(graph, directed=False)
    on_floor = (x[:, 2] - r) < 1e-6
    return touch, on_floor, np.isin(label, np.unique(label[on_floor]))


def report(path, pile_z, surface_z):
    with h5py.File(path, 'r') as h:
        g = last_snapshot(h)
        x, r = g['position'][:], g['radius'][:]
        names = [n.decode() if isinstance(n, bytes) else n for n in h['materials'][:]]
        mats, wall = materials(h)
        mat = g['material'][:]
        rho = np.array([mats[names[k]][0] for k in mat])
        elastic = np.array([mats[names[k]][1:] for k in mat])
        rho_f = float(h.attrs['fluid_density'])
        t = g.attrs['time_s']
    m = 4.0 / 3.0 * np.pi * r**3 * rho
    touch, on_floor, cluster = floor_cluster(x, r)
    pile = x[:, 2] > pile_z
    print(f"{path} t {t:.2f}: contacts {len(touch)} ({2 * len(touch) / len(x):.2f} per rock), rocks on the floor "
          f"{on_floor.sum()}, pile {1000 * m[pile].sum():.0f} g of which {1000 * m[pile & cluster].sum():.0f} g in a "
          "contact cluster touching the floor")
    force = floor_force(r, x[:, 2], (elastic[:, 0], elastic[:, 1]), wall[1:]).sum()
    weight = m * G * np.where(x[:, 2] < surface_z, 1.0 - rho_f / rho, 1.0)  # buoyant below the surface
    print(f"   floor normal force {force:.3f} N; buoyant weight: all rock {weight.sum():.3f} N, pile "
          f"{weight[pile].sum():.3f} N, floor cluster {weight[cluster].sum():.3f} N, rocks on the floor "
          f"{weight[on_floor].sum():.3f} N")
    cells = set(zip(np.floor(x[pile, 0] / 0.01).astype(int), np.floor(x[pile, 1] / 0.01).astype(int)))
    area = 1e-4 * len(cells)
    carried = weight.sum() - force
    print(f"   pile footprint {1e4 * area:.0f} cm2 (1 cm cells holding pile rock); weight not on the floor "
          f"{carried:.2f} N = {carried / area:.0f} Pa over it")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('results', nargs='+')
    ap.add_argument('--pile', type=float, default=0.08, help='z (m) above which rock is the pile')
    ap.add_argument('--surface', type=float, default=0.085,
                    help='z (m) below which rock is buoyant (the centre column paste surface is at 8-9 cm)')
    a = ap.parse_args()
    for path in a.results:
        report(path, a.pile, a.surface)


if __name__ == '__main__':
    main()
