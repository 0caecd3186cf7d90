#!/usr/bin/env python3
"""Figure 5 of Barthel & Perriot (2007) from Python: normalized force P = F/(pi w R) versus
contact radius a_bar = a/(pi w R^2/E1*)^(1/3) for several eta = t/(pi w R^2/E1*)^(1/3), soft
film E1/E0 = 0.1, nu = 0.25 (THEORY.md section 5), with the homogeneous JKR curve and the
pull-off points.   usage: fig5.py [--output DIR]  (writes DIR/fig5_python.png)
"""
import argparse
import os

import matplotlib
matplotlib.use("Agg")  # headless: tests and CI have no display
import matplotlib.pyplot as plt
import numpy as np

import coatcontact as cc

ETA = [0.1, 0.3, 1, 3, 10]  # as data/figures.conf


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--output", default=".", help="folder of fig5_python.png")
    args = parser.parse_args()

    model = cc.AdhesiveModel(cc.Stack(film=(0.1, 0.25), substrate=(1, 0.25)))
    a_bar = np.geomspace(0.002, 3, 481)
    pull = model.pulloff(ETA)  # one C++ call for every eta

    fig, ax = plt.subplots(figsize=(10, 7.2), dpi=100)
    for eta in ETA:
        curve = model.curve(eta, a_bar)
        ax.plot(curve["a_bar"], curve["P"], label="η = %g" % eta)
    # JKR of a homogeneous film material (section 5): P = (4/3) a^3 - 2 sqrt(2) a^(3/2).
    ax.plot(a_bar, 4 / 3 * a_bar**3 - 2 * np.sqrt(2) * a_bar**1.5, "k--", label="JKR, homogeneous (E1*)")
    ax.plot(pull["a_bar_load"], pull["P_load"], "ko", label="pull-off, load control (min P)")
    ax.plot(pull["a_bar_disp"], pull["P_disp"], "ks", mfc="none", label="pull-off, displacement control (min D)")
    ax.axhline(0, color="0.6", lw=0.8)
    ax.set_xlim(0, 3)
    ax.set_ylim(-2.1, 3)
    ax.set_xlabel("ā = a / (π w R²/E1*)^(1/3)")
    ax.set_ylabel("P = F / (π w R)")
    ax.set_title("Fig. 5 — adhesive sphere on a soft film, E1/E0 = 0.1, ν = 0.25")
    ax.legend(loc="upper left")
    path = os.path.join(args.output, "fig5_python.png")
    fig.savefig(path)
    print("wrote", path)


if __name__ == "__main__":
    main()
