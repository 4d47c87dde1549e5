# SPDX-License-Identifier: MIT
"""The block-grid cell labels shared by plot_lab_grids.py and plot_mixing_maps.py (imported from the scripts
folder, which Python puts first on the path of a script run from it).

The flags are those of the C++ grids (the flag_legend attribute of lab.h5, lab/lab_h5.cpp): 1 S capped at 1
(eq. 3.8 > 1), 2 no rock in the block (S undefined), 3 K unknown.
"""
FLAG_CAPPED, FLAG_NO_ROCK, FLAG_NO_K = 1, 2, 3


def s_label(s, flag):
    """The text of a block's S (s a fraction): a percentage, or why there is none."""
    if flag == FLAG_NO_ROCK:
        return "no rock"
    if flag == FLAG_NO_K:
        return "-"
    if flag == FLAG_CAPPED:
        return "100*"
    return f"{s * 100:.1f}"
