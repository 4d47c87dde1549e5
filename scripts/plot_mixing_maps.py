#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""PNGs for the analysis layer, drawn in the style of scripts/plot_lab_grids.py.

Usage:
  /usr/bin/python3 scripts/plot_mixing_maps.py maps MAPS_H5 OUT_DIR
      -> OUT_DIR/maps.png: C (top row) and S (bottom row), one panel per layer (layer 1 = top).
  /usr/bin/python3 scripts/plot_mixing_maps.py score SCORE_CSV N TITLE OUT_DIR
      -> OUT_DIR/score_layer_<k>.png per layer: lab C, model C (ensemble mean, +- sd), difference
         (model - lab, pp) and, with more than one realization, the ensemble spread (sd of C).
Called once per command by `pastemix maps` / `pastemix score`. Exit code 3 if matplotlib, h5py or numpy is
missing, so the caller can say so.
"""
import csv
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
    print(f"plot_mixing_maps: {e}", file=sys.stderr)
    sys.exit(3)

from grid_labels import s_label  # noqa: E402 (after the exit-3 check)



def text_colour(cmap, norm, v):
    return "white" if np.isfinite(v) and sum(cmap(norm(v))[:3]) < 1.5 else "black"


def draw_panel(ax, xe, ye, values, labels, cmap, norm, title, ids):
    """values [ni][nj] (NaN = blank), labels [ni][nj] strings; xe, ye block edges in cm."""
    ni, nj = values.shape
    cm = plt.get_cmap(cmap)
    mesh = ax.pcolormesh(xe, ye, np.ma.masked_invalid(values.T), cmap=cm, norm=norm, edgecolors="k", linewidth=0.8)
    fs = 10 if ni * nj <= 16 else 7
    for i in range(ni):
        for j in range(nj):
            x, y = (xe[i] + xe[i + 1]) / 2, (ye[j] + ye[j + 1]) / 2
            h = ye[j + 1] - ye[j]
            ax.text(x, y + 0.1 * h, labels[i][j], ha="center", va="center", fontsize=fs, fontweight="bold",
                    color=text_colour(cm, norm, values[i, j]), linespacing=1.0)
            ax.text(x, y - 0.33 * h, ids[i][j], ha="center", va="center", fontsize=6.5,
                    color="white" if text_colour(cm, norm, values[i, j]) == "white" else "0.35")
    ax.set_xlim(xe[0], xe[-1])
    ax.set_ylim(ye[0], ye[-1])
    ax.set_aspect("equal")
    ax.set_xticks([])
    ax.set_yticks([])
    ax.set_xlabel("i (along x) \u2192", fontsize=8)
    ax.set_ylabel("j (along y) \u2192", fontsize=8)
    ax.set_title(title, fontsize=9.5)
    return mesh


def block_id(i, j, k):
    return f"M_{i + 1}{j + 1}{k + 1}" if max(i, j, k) < 9 else f"M_{i + 1}_{j + 1}_{k + 1}"


def plot_maps(h5_path, out_dir):
    with h5py.File(h5_path, "r") as f:
        g = f["/grid"].attrs
        ni, nj, nk = int(g["count_i"]), int(g["count_j"]), int(g["layers"])
        xe = (g["origin_x_m"] + np.arange(ni + 1) * g["size_x_m"]) * 100
        ye = (g["origin_y_m"] + np.arange(nj + 1) * g["size_y_m"]) * 100
        t = g["layer_thickness_m"] * 100
        C, S, flag = f["/blocks/C"][()], f["/blocks/S"][()], f["/blocks/flag"][()]
        a, acc = f.attrs, f["/accounting"].attrs
        title = f"Model mixing map: {a['result_file']} (seed {a['seed']}, snapshot {a['snapshot']})"
        if "at_rest" in a and not int(a["at_rest"]):
            title += f" - NOT AT REST: {a['moving_mass_kg'] * 1e3:.1f} g moving (--allow-moving)"
        note = (f"Surface z = {a['surface_z_m']:.4g} m ({a['surface_z_source']}); paste {a['paste_density_kg_m3']:g} "
                f"kg/m3, solids {a['solids_fraction']:g}; K = {a['K_kg_m3']:g} kg/m3 ({a['K_source']}). "
                f"Rock: poured {acc['poured_kg'] * 1e3:.1f} g, unmixed (above the surface"
                f"{', counted in layer 1' if int(g.get('top_open', 0)) else ', in no block'}) "
                f"{acc['above_surface_kg'] * 1e3:.1f} g, in blocks {acc['in_blocks_kg'] * 1e3:.1f} g, outside the blocks "
                f"{(acc['below_grid_kg'] + acc['beside_grid_kg'] + acc.get('above_uncounted_kg', 0.0)) * 1e3:.1f} g.")
    norm = Normalize(0, 100)
    fig, axes = plt.subplots(2, nk, figsize=(4.5 * nk, 8.2), squeeze=False)
    fig.subplots_adjust(left=0.05, right=0.9, bottom=0.1, top=0.83, wspace=0.22, hspace=0.38)
    for k in range(nk):
        depth = f"{k * t:g}-{(k + 1) * t:g} cm below the surface"
        ids = [[block_id(i, j, k) for j in range(nj)] for i in range(ni)]
        c_lab = [[f"{C[i, j, k] * 100:.1f}" for j in range(nj)] for i in range(ni)]
        s_lab = [[s_label(S[i, j, k], flag[i, j, k]) for j in range(nj)] for i in range(ni)]
        mc = draw_panel(axes[0, k], xe, ye, C[:, :, k] * 100, c_lab, "YlOrBr", norm,
                        f"C (%), layer {k + 1}{' (top)' if k == 0 else ''}, {depth}", ids)
        ms = draw_panel(axes[1, k], xe, ye, S[:, :, k] * 100, s_lab, "Blues", norm, f"S (%), layer {k + 1}", ids)
    fig.colorbar(mc, cax=fig.add_axes([0.925, 0.52, 0.012, 0.31]), label="C = M_wr / (M_wr + M_paste)  (%)")
    fig.colorbar(ms, cax=fig.add_axes([0.925, 0.1, 0.012, 0.31]), label="S = V_paste / V_voids  (%)")
    fig.suptitle(title, fontsize=12, y=0.975)
    fig.text(0.5, 0.905, "\n".join(textwrap.wrap(note, 160)), ha="center", va="center", fontsize=8.5)
    fig.text(0.5, 0.02, "Blocks seen from above (x, y in cm); block id M_ijk, k = layer (1 = top). 100* = capped, "
             "no rock = S undefined, - = K unknown.", ha="center", fontsize=8.5, color="0.3")
    fig.savefig(f"{out_dir}/maps.png", dpi=100, format="png", pil_kwargs={"compress_level": 2})


def plot_score(csv_path, n_realizations, title, out_dir):
    with open(csv_path, newline="") as fh:
        rows = list(csv.DictReader(fh))
    ni = max(int(r["i"]) for r in rows)
    nj = max(int(r["j"]) for r in rows)
    nk = max(int(r["k"]) for r in rows)
    lab, mean, sd, err = (np.full((ni, nj, nk), np.nan) for _ in range(4))
    cls_lab, cls_model = {}, {}
    for r in rows:
        i, j, k = int(r["i"]) - 1, int(r["j"]) - 1, int(r["k"]) - 1
        lab[i, j, k], mean[i, j, k] = float(r["lab_C_percent"]), float(r["model_C_mean_percent"])
        sd[i, j, k], err[i, j, k] = float(r["model_C_sd_percent"]), float(r["C_error_pp"])
        cls_lab[i, j, k], cls_model[i, j, k] = r["lab_S_class"], r["S_class_agrees"]
    ensemble = n_realizations > 1
    xe, ye = np.arange(ni + 1) * 5.0, np.arange(nj + 1) * 5.5  # the lab grid, cm (display only)
    ncol = 4 if ensemble else 3
    norm_c, norm_d = Normalize(0, 100), Normalize(-50, 50)
    mae = np.nanmean(np.abs(err))
    for k in range(nk):
        fig, axes = plt.subplots(1, ncol, figsize=(4.3 * ncol, 4.6))
        fig.subplots_adjust(left=0.03, right=0.97, bottom=0.2, top=0.8, wspace=0.25)
        ids = [[block_id(i, j, k) for j in range(nj)] for i in range(ni)]
        lab_l = [[f"{lab[i, j, k]:.1f}" for j in range(nj)] for i in range(ni)]
        if ensemble:
            mod_l = [[f"{mean[i, j, k]:.1f}\n\u00b1{sd[i, j, k]:.1f}" for j in range(nj)] for i in range(ni)]
        else:
            mod_l = [[f"{mean[i, j, k]:.1f}" for j in range(nj)] for i in range(ni)]
        dif_l = [[f"{err[i, j, k]:+.1f}" + ("" if cls_model[i, j, k] != "no" else "\nS \u2260")
                  for j in range(nj)] for i in range(ni)]
        m0 = draw_panel(axes[0], xe, ye, lab[:, :, k], lab_l, "YlOrBr", norm_c, "lab C (%)", ids)
        draw_panel(axes[1], xe, ye, mean[:, :, k], mod_l, "YlOrBr", norm_c,
                   "model C (%), ensemble mean \u00b1 sd" if ensemble else "model C (%)", ids)
        m2 = draw_panel(axes[2], xe, ye, err[:, :, k], dif_l, "RdBu_r", norm_d, "model \u2212 lab (pp)", ids)
        fig.colorbar(m0, ax=axes[:2], orientation="horizontal", fraction=0.05, pad=0.08, label="C (%)")
        fig.colorbar(m2, ax=axes[2], orientation="horizontal", fraction=0.05, pad=0.08, label="C error (pp)")
        if ensemble:
            m3 = draw_panel(axes[3], xe, ye, sd[:, :, k], [[f"{sd[i, j, k]:.1f}" for j in range(nj)] for i in range(ni)],
                            "Greys", Normalize(0, max(5.0, float(np.nanmax(sd)))), "ensemble spread: sd of C (pp)", ids)
            fig.colorbar(m3, ax=axes[3], orientation="horizontal", fraction=0.05, pad=0.08, label="sd (pp)")
        layer_mae = np.nanmean(np.abs(err[:, :, k]))
        fig.suptitle(f"{title}: layer {k + 1}{' (top)' if k == 0 else ''}", fontsize=12, y=0.97)
        fig.text(0.5, 0.875, f"mean |C error| this layer {layer_mae:.1f} pp, all 36 blocks {mae:.1f} pp. "
                 "S \u2260: the S class (no rock / < 100 % / capped) differs from the lab's. "
                 "Blocks seen from above: i = 1..4 along x (20 cm side), j = 1..3 along y (16.5 cm side).",
                 ha="center", fontsize=8.5, color="0.3")
        fig.savefig(f"{out_dir}/score_layer_{k + 1}.png", dpi=100, format="png", pil_kwargs={"compress_level": 2})
        plt.close(fig)


def main():
    if len(sys.argv) == 4 and sys.argv[1] == "maps":
        plot_maps(sys.argv[2], sys.argv[3])
        return 0
    if len(sys.argv) == 6 and sys.argv[1] == "score":
        plot_score(sys.argv[2], int(sys.argv[3]), sys.argv[4], sys.argv[5])
        return 0
    print(__doc__, file=sys.stderr)
    return 2


if __name__ == "__main__":
    sys.exit(main())
