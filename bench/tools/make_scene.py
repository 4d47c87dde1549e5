#!/usr/bin/python3
"""Write a runnable pastemix scene: a template from bench/scenes plus the shared initial particles.

The template's time_step, end_time, [neighbor] skin, [output] intervals and [contact] rolling are set
from the arguments; every sphere of STATE.csv (id,diameter,x,y,z,vx,vy,vz in SI) becomes a [[particle]]
of material "rock", in id order (so pastemix's dense index k is LIGGGHTS atom id k+1).
--box X Y moves the box's far side walls (and the domain) to x = X, y = Y (m): the scaling series' wider pours.
Usage: make_scene.py TEMPLATE.toml STATE.csv OUT.toml --dt S --steps N --skin M --rolling cdt|epsd2|off
                     [--box X Y]
"""
import argparse
import re

import numpy as np

ROLLING = {"cdt": "constant_torque", "epsd2": "elastic_plastic", "off": "none"}


def set_key(text, key, value, count=1):
    new, n = re.subn(r"(?m)^%s = [^#\n]*?(\s*#|$)" % re.escape(key), "%s = %s\\1" % (key, value), text)
    if n != count:
        raise SystemExit("make_scene: expected %d '%s = ' line(s) in the template, found %d" % (count, key, n))
    return new


def replace_once(text, pattern, repl):
    new, n = re.subn(pattern, repl, text)
    if n != 1:
        raise SystemExit("make_scene: expected one line matching %s in the template, found %d" % (pattern, n))
    return new


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("template")
    ap.add_argument("state")
    ap.add_argument("out")
    ap.add_argument("--dt", type=float, required=True)
    ap.add_argument("--steps", type=int, required=True)
    ap.add_argument("--skin", type=float, required=True)
    ap.add_argument("--rolling", choices=sorted(ROLLING), required=True)
    ap.add_argument("--box", type=float, nargs=2, metavar=("X", "Y"))
    a = ap.parse_args()
    text = open(a.template).read()
    end = a.dt * a.steps
    text = set_key(text, "time_step", "%.9g" % a.dt)
    text = set_key(text, "end_time", "%.9g" % end)
    text = set_key(text, "skin", "%.9g" % a.skin)
    text = set_key(text, "interval", "%.9g" % end)
    text = set_key(text, "energy_interval", "%.9g" % end)
    text = set_key(text, "rolling", '"%s"' % ROLLING[a.rolling])
    if a.rolling == "epsd2":
        # LIGGGHTS epsd2 has no rolling dashpot ("the viscous damping torque M_rd is disabled").
        text = text.replace('rolling = "elastic_plastic"', 'rolling = "elastic_plastic"\nrolling_damping = 0.0')
    if a.rolling == "off":
        # No rolling resistance (LIGGGHTS "rolling_friction off"); pastemix refuses a coefficient without a law.
        text = set_key(text, "rolling_friction", "0.0", count=text.count("\nrolling_friction = "))
    if a.box:
        # [domain] max = the walls + 5 mm (as the template), [[wall]] max = the walls; z unchanged.
        text = replace_once(text, r"(?m)^max = \[0\.17, 0\.205, (0\.3)\]",
                            "max = [%.9g, %.9g, \\1]" % (a.box[0] + 0.005, a.box[1] + 0.005))
        text = replace_once(text, r"(?m)^max = \[0\.165, 0\.2, (0\.25)\]",
                            "max = [%.9g, %.9g, \\1]" % (a.box[0], a.box[1]))
    s = np.loadtxt(a.state, delimiter=",", skiprows=1, ndmin=2)
    out = [text, "\n# %d spheres from %s\n" % (len(s), a.state)]
    for row in s[np.argsort(s[:, 0])]:
        _, d, x, y, z, vx, vy, vz = row
        out.append('[[particle]]\nmaterial = "rock"\nradius = %.9g\nposition = [%.9g, %.9g, %.9g]\n'
                   "velocity = [%.9g, %.9g, %.9g]\n" % (d / 2, x, y, z, vx, vy, vz))
    with open(a.out, "w") as f:
        f.write("".join(out))


if __name__ == "__main__":
    main()
