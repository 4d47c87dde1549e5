#!/usr/bin/python3
"""Generate the pour scene's initial particles once, for both codes.

Spheres on a jittered square lattice (pitch 5.5 mm > d_max = 5 mm, so no overlaps) filling the
16.5 x 20 cm box cross-section, all moving down at v0 (as if already fallen from h = v0^2 / 2g).
Diameters are uniform in [d_min, d_max], seeded. Writes:
  <out>.csv   id,diameter,x,y,z,vx,vy,vz   (SI: m, m/s)  -- what pastemix reads
  <out>.data  LIGGGHTS read_data file (atom_style granular: id type diameter density x y z + Velocities)
--scale K makes the box K times wider and longer (K^2 times the spheres, same 12 layers): the scaling series
of bench/run.sh --scaling, where every column of the pile sees the same physics and only N grows.
Usage: make_pour.py OUT_STEM [--seed S] [--scale K]
"""
import argparse
import numpy as np

BOX_X, BOX_Y = 0.165, 0.200   # m, inner box (walls at 0 and BOX_*)
PITCH = 5.5e-3                # m, lattice pitch
D_MIN, D_MAX = 2.5e-3, 5.0e-3 # m
DENSITY = 2760.0              # kg/m3
LAYERS = 12
Z0 = 4.0e-3                   # m, centre height of the lowest layer (d_max/2 + 1.5 mm gap)
V0 = 2.0                      # m/s downward (a 20 cm free fall)


def lattice(seed, scale=1):
    rng = np.random.default_rng(seed)
    box_x, box_y = BOX_X * scale, BOX_Y * scale
    nx = int(BOX_X // PITCH) * scale  # 30 per box width
    ny = int(BOX_Y // PITCH) * scale  # 36
    # Centre the lattice in the box; the margin to each wall is >= (PITCH - d)/2 > 0.
    x0 = (box_x - nx * PITCH) / 2 + PITCH / 2
    y0 = (box_y - ny * PITCH) / 2 + PITCH / 2
    k, j, i = np.meshgrid(np.arange(LAYERS), np.arange(ny), np.arange(nx), indexing="ij")
    x = x0 + i.ravel() * PITCH
    y = y0 + j.ravel() * PITCH
    z = Z0 + k.ravel() * PITCH
    n = x.size
    d = rng.uniform(D_MIN, D_MAX, n)
    # Jitter inside each lattice cell so columns do not stack perfectly (keeps spheres in their cell).
    slack = (PITCH - d) / 2
    x += rng.uniform(-1, 1, n) * slack * 0.9
    y += rng.uniform(-1, 1, n) * slack * 0.9
    v = np.zeros((n, 3))
    v[:, 2] = -V0
    return d, np.column_stack([x, y, z]), v


def write(stem, d, pos, vel, comment, scale=1):
    write_csv(stem + ".csv", d, pos, vel, comment)
    write_data(stem + ".data", d, pos, vel, comment, scale)


def write_csv(path, d, pos, vel, comment):
    with open(path, "w") as f:
        f.write("id,diameter,x,y,z,vx,vy,vz\n")
        for n in range(d.size):
            f.write("%d,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g\n" % (
                n + 1, d[n], *pos[n], *vel[n]))


def write_data(path, d, pos, vel, comment, scale=1):
    top = max(0.30, float(pos[:, 2].max()) + 0.02)
    with open(path, "w") as f:
        f.write("LIGGGHTS data: %s\n\n" % comment)
        f.write("%d atoms\n1 atom types\n\n" % d.size)
        # Domain slightly larger than the walls (walls are fix wall/gran planes at 0 and BOX_*).
        f.write("-0.005 %.4f xlo xhi\n-0.005 %.4f ylo yhi\n-0.005 %.4f zlo zhi\n\n" % (
            BOX_X * scale + 0.005, BOX_Y * scale + 0.005, top))
        f.write("Atoms\n\n")
        for n in range(d.size):
            f.write("%d 1 %.9g %.6g %.9g %.9g %.9g\n" % (n + 1, d[n], DENSITY, *pos[n]))
        f.write("\nVelocities\n\n")
        for n in range(d.size):
            f.write("%d %.9g %.9g %.9g 0 0 0\n" % (n + 1, *vel[n]))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("out_stem")
    ap.add_argument("--seed", type=int, default=20261122)
    ap.add_argument("--scale", type=int, default=1)
    a = ap.parse_args()
    if a.scale < 1:
        raise SystemExit("make_pour: --scale must be >= 1")
    d, pos, vel = lattice(a.seed, a.scale)
    write(a.out_stem, d, pos, vel,
          "pour, %d spheres, d uniform %.1f-%.1f mm, seed %d, box %.3f x %.3f m" % (
              d.size, D_MIN * 1e3, D_MAX * 1e3, a.seed, BOX_X * a.scale, BOX_Y * a.scale), a.scale)
    print("%s: %d spheres, mass %.4f kg, seed %d" % (
        a.out_stem, d.size, (DENSITY * np.pi / 6 * d**3).sum(), a.seed))


if __name__ == "__main__":
    main()
