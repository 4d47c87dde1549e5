#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""C and S maps per layer for every mixing case in lab.h5 (like thesis Figures 3.18/3.19).

Usage: /usr/bin/python3 scripts/plot_lab_grids.py LAB_H5 OUT_DIR
Writes OUT_DIR/mixing_case_<n>.png for every /block_cut/case_<n>: a row of three layer panels for C and one
for S, each block coloured and labelled with its value (layer 1 = top). Called once by `pastemix lab reduce`
for all cases: importing matplotlib and building the figure cost most of the time, so the figure is built
once and only its values change per case. Exit code 3 if matplotlib, h5py or numpy is missing, so the caller
can say so.
"""
import sys
import textwrap

try:
    import h5py
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.colors import Normalize
    import numpy as np
except ImportError as e:  # the caller turns this into a warning and writes everything else
    print(f"plot_lab_grids: {e}", file=sys.stderr)
    sys.exit(3)

from grid_labels import s_label  # noqa: E402 (after the exit-3 check)

# Block edges in cm: i (4 blocks of 5 cm) along the 20 cm side = x, j (3 blocks of 5.5 cm) along 16.5 cm = y.
X_EDGES = np.arange(5) * 5.0
Y_EDGES = np.arange(4) * 5.5
LAYERS = ["layer 1 (top, 0-3 cm)", "layer 2 (3-6 cm)", "layer 3 (bottom, 6-9 cm)"]
NORM = Normalize(0, 100)
CMAPS = ["YlOrBr", "Blues"]  # C row, S row


class GridFigure:
    """Two rows (C, S) of three layer panels of 4 x 3 blocks; artists are made once and updated per case."""

    def __init__(self):
        self.fig, axes = plt.subplots(2, 3, figsize=(13.5, 8.2))
        self.fig.subplots_adjust(left=0.05, right=0.9, bottom=0.1, top=0.83, wspace=0.22, hspace=0.38)
        self.meshes, self.values, self.ids = {}, {}, {}
        for row, field in enumerate(["C", "S"]):
            for k in range(3):
                ax = axes[row, k]
                mesh = ax.pcolormesh(X_EDGES, Y_EDGES, np.zeros((3, 4)), cmap=CMAPS[row], norm=NORM,
                                     edgecolors="k", linewidth=0.8)
                self.meshes[row, k] = mesh
                for i in range(4):
                    for j in range(3):
                        x, y = (X_EDGES[i] + X_EDGES[i + 1]) / 2, (Y_EDGES[j] + Y_EDGES[j + 1]) / 2
                        self.values[row, k, i, j] = ax.text(x, y + 0.6, "", ha="center", va="center", fontsize=10,
                                                            fontweight="bold", linespacing=1.0)
                        self.ids[row, k, i, j] = ax.text(x, y - 1.9, f"M_{i + 1}{j + 1}{k + 1}", ha="center",
                                                         va="center", fontsize=6.5)
                ax.set_xlim(0, 20)
                ax.set_ylim(0, 16.5)
                ax.set_aspect("equal")
                # No tick labels: block ids carry i and j, and ticks would cost a third of the drawing time.
                ax.set_xticks([])
                ax.set_yticks([])
                ax.set_xlabel("i = 1..4 (5 cm blocks along the 20 cm side) \u2192", fontsize=8)
                ax.set_ylabel("j = 1..3 (5.5 cm blocks) \u2192", fontsize=8)
                ax.set_title(f"{field} (%), {LAYERS[k]}", fontsize=9.5)
        self.fig.colorbar(self.meshes[0, 0], cax=self.fig.add_axes([0.925, 0.52, 0.012, 0.31]),
                          label="C = M_wr / (M_wr + M_paste)  (%)")
        self.fig.colorbar(self.meshes[1, 0], cax=self.fig.add_axes([0.925, 0.1, 0.012, 0.31]),
                          label="S = V_paste / V_voids  (%)")
        self.title = self.fig.suptitle("", fontsize=13, y=0.975)
        self.note = self.fig.text(0.5, 0.915, "", ha="center", va="center", fontsize=9)
        self.fig.text(0.5, 0.02, "Blocks seen from above: i = 1..4 along the 20 cm side, j = 1..3 along the 16.5 cm "
                      "side; block id M_ijk, k = layer (1 = top).", ha="center", fontsize=8.5, color="0.3")

    def set_row(self, row, values, labels):
        """values: [i][j][k] in %, NaN = blank; labels: [i][j][k] strings."""
        cmap = plt.get_cmap(CMAPS[row])
        for k in range(3):
            self.meshes[row, k].set_array(np.ma.masked_invalid(values[:, :, k].T).ravel())
            for i in range(4):
                for j in range(3):
                    v = values[i, j, k]
                    dark = bool(np.isfinite(v) and sum(cmap(NORM(v))[:3]) < 1.5)
                    self.values[row, k, i, j].set_text(labels[i][j][k])
                    self.values[row, k, i, j].set_color("white" if dark else "black")
                    self.ids[row, k, i, j].set_color("white" if dark else "0.35")

    def save(self, path, title, note):
        self.title.set_text(title)
        self.note.set_text("\n".join(textwrap.wrap(note, 150)))
        # Light compression: encoding at the default level costs ~15 % of the run for ~30 % smaller files.
        self.fig.savefig(path, dpi=100, format="png", pil_kwargs={"compress_level": 2})


def case_title(f, n):
    parts = [f"Mixing case {n}"]
    psd = f.get(f"/psd/mixing_case_{n}")
    if psd is not None:
        parts.append(f"rock {psd['d_min'][0] * 1e3:g}-{psd['d_max'][-1] * 1e3:g} mm")
    for key, fmt in (("falling_height", "fall {:g} cm"), ("paste_solids_fraction", "paste {:g} % solids")):
        g = f.get(f"/parameters/mixing.case_{n}.{key}")
        if g is not None:
            parts.append(fmt.format(round(g.attrs["value"] * 100, 2)))
    return ", ".join(parts)


def plot_case(fig, f, n, path):
    g = f[f"/block_cut/case_{n}"]
    C, S, flag = g["C"][()], g["S"][()], g["flag"][()]
    K = g.attrs["K"]
    c_labels = [[[f"{C[i, j, k] * 100:.1f}" for k in range(3)] for j in range(3)] for i in range(4)]
    s_labels = [[[s_label(S[i, j, k], flag[i, j, k]) for k in range(3)] for j in range(3)] for i in range(4)]
    corr = f.get(f"/block_cut/case_{n}/corrected")
    if corr is not None and np.isfinite(K):
        applied, s_corr = corr["applied"][()], corr["S_raw"][()]
        for i, j, k in zip(*np.nonzero(applied)):
            s_labels[i][j][k] += f"\ncorr. {s_corr[i, j, k] * 100:.0f}"
    fig.set_row(0, C * 100, c_labels)
    fig.set_row(1, S * 100, s_labels)
    if np.isfinite(K):
        note = (f"S from eq. 3.8 with K = rho_wr/n_wr = {K:g} kg/m3 ({g.attrs['K_source']}). "
                "100* = capped (eq. 3.8 gives more than 100 %); no rock = S undefined (M_wr = 0). "
                "Table 3.2 masses; 'corr.' = S after the Table 3.3 interface correction (uncapped).")
    else:
        note = ("S not computed: K = rho_wr/n_wr is unknown for this case (the thesis states none and prints no "
                "finite S to back-calculate it).")
    fig.save(path, case_title(f, n), note)


def main():
    if len(sys.argv) != 3:
        print(__doc__, file=sys.stderr)
        return 2
    fig = GridFigure()
    with h5py.File(sys.argv[1], "r") as f:
        cases = sorted(int(name.split("_")[1]) for name in f["/block_cut"].keys() if name.startswith("case_"))
        for n in cases:
            plot_case(fig, f, n, f"{sys.argv[2]}/mixing_case_{n}.png")
    return 0


if __name__ == "__main__":
    sys.exit(main())
