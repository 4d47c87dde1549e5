#!/usr/bin/env python3
"""Issue 22: what carries a flow run's pile, measured on its final state (run with /usr/bin/python3: scipy, h5py).
Contacts are the overlapping sphere pairs (distance < r_i + r_j); the floor's normal force is Hertz's on each
sphere below its radius (rock on the rock-material box floor, E 4.68e7 Pa, nu 0.19: F = 4/3 E* sqrt(r) delta^1.5);
the rock's weight is buoyant below z = 8.5 cm (the paste's surface in the centre column is at 8-9 cm) and whole
above. Prints the contact count, how much of the pile (rock above 8 cm) is in a contact cluster touching the
floor, the floor's share of the weight, and the weight the floor does not carry spread over the pile's footprint
(the 1 cm cells holding pile rock), to compare with the paste's bearing capacity (Skempton: 5-9 tau_y). The side
walls' friction is not counted.

    /usr/bin/python3 scripts/pile_support.py RESULT.h5 [RESULT.h5 ...]
"""
import sys, h5py, numpy as np
from scipy.spatial import cKDTree
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components
for f in sys.argv[1:]:
    h = h5py.File(f, 'r'); s = h['snapshots']; k = sorted(x for x in s.keys() if x.isdigit())[-1]; g = s[k]
    x = g['position'][:]; r = g['radius'][:]; m = 4 / 3 * np.pi * r**3 * 2760
    t = cKDTree(x); pairs = t.query_pairs(2 * r.max(), output_type='ndarray')
    d = np.linalg.norm(x[pairs[:, 0]] - x[pairs[:, 1]], axis=1)
    touch = pairs[d < r[pairs[:, 0]] + r[pairs[:, 1]]]
    n = len(x)
    A = coo_matrix((np.ones(len(touch)), (touch[:, 0], touch[:, 1])), shape=(n, n))
    nc, lab = connected_components(A, directed=False)
    floor = (x[:, 2] - r) < 1e-6
    floor_labels = set(lab[floor])
    on_floor_net = np.isin(lab, list(floor_labels))
    pile = x[:, 2] > 0.08
    print(f, 't %.2f' % g.attrs['time_s'], 'contacts', len(touch), 'per rock %.2f' % (2 * len(touch) / n),
          'rocks on floor', floor.sum(),
          'pile mass g %.0f, of it connected to the floor by contacts %.0f g' % (1000 * m[pile].sum(), 1000 * m[pile & on_floor_net].sum()))
    # Floor contact forces (Hertz, rock on the rock-material box floor): F = 4/3 E* sqrt(r) delta^1.5.
    E, nu = 4.68e7, 0.19
    Es = E / (2 * (1 - nu * nu))
    delta = np.clip(r - x[:, 2], 0, None)
    F = 4 / 3 * Es * np.sqrt(r) * delta**1.5
    rho_f = float(h.attrs.get('fluid_density', 1790.0))
    # weight less buoyancy where submerged below ~9 cm (rough: the paste's surface in the centre is 8-9 cm)
    wsub = m * 9.81 * np.where(x[:, 2] < 0.085, 1 - rho_f / 2760, 1.0)
    print('   floor normal force %.3f N; buoyant weight: all rock %.3f N, pile %.3f N, floor-connected cluster %.3f N, rocks on the floor %.3f N'
          % (F.sum(), wsub.sum(), wsub[pile].sum(), wsub[on_floor_net].sum(), wsub[floor].sum()))
    cells = set(zip(np.floor(x[pile, 0] / 0.01).astype(int), np.floor(x[pile, 1] / 0.01).astype(int)))
    area = 1e-4 * len(cells)
    carried = wsub.sum() - F.sum()
    print('   pile footprint %.0f cm2 (1 cm cells holding pile rock); weight not on the floor %.2f N = %.0f Pa over it' % (1e4 * area, carried, carried / area))
