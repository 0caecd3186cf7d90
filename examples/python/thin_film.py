#!/usr/bin/env python3
"""A film's modulus from nanoindentation: the exact coated solution against the empirical models.

A synthetic CSM test (1 % noise on the stiffness) of a 70 GPa film (nu 0.17), 500 nm thick, on
a stiff substrate (400 GPa, nu 0.25), pressed by a diamond Berkovich (perfect area function,
constant hardness 8 GPa), made with the library's exact flat-punch stiffness of the stack
(THEORY.md section 16). Then coatcontact.indent.film with every model: the exact inversion
returns 70 GPa at every depth, each empirical model departs as the substrate comes in.

usage: thin_film.py [--output DIR]   writes DIR/thin_film_python.png and prints the fitted moduli
"""
import argparse
import os

import numpy as np
import matplotlib
matplotlib.use("Agg")  # headless: tests and CI have no display
import matplotlib.pyplot as plt
import coatcontact as cc

DIAMOND = (1141e9, 0.07)
FILM, THICKNESS, SUBSTRATE = (70e9, 0.17), 500e-9, (400e9, 0.25)


class SyntheticTest:
    """depth, load, stiffness and metadata, as coatcontact.indent.read returns them."""

    def __init__(self, hc, hardness=8e9, noise=0.01, seed=38):
        area = 24.5 * hc ** 2                      # perfect Berkovich, SI
        a = np.sqrt(area / np.pi)
        stack = cc.Stack(FILM, substrate=SUBSTRATE, indenter=DIAMOND)
        e_eq = cc.reduced(stack, a_over_t=a / THICKNESS)["E_eq"]
        s = 2 * a * stack.reference_modulus * e_eq  # S = 2 beta a E_ref E_eq(a/t), beta = 1
        self.load = hardness * area
        self.depth = hc + 0.75 * self.load / s
        self.stiffness = s * (1 + noise * np.random.default_rng(seed).standard_normal(len(hc)))
        self.hardness = None
        self.metadata = {"area coefficients": [24.5], "poisson": FILM[1], "range": None}


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--output", default=".", help="folder of thin_film_python.png")
    args = parser.parse_args()

    test = SyntheticTest(np.linspace(8e-9, 400e-9, 60))
    fig, ax = plt.subplots(figsize=(10, 7.2), dpi=100)
    exact = None
    for model in cc.indent.MODELS:
        f = cc.indent.film(test, thickness=THICKNESS, film_poisson=FILM[1], substrate=SUBSTRATE, model=model,
                           depth_range=(0, 150e-9))
        if exact is None:
            exact = f
            ax.plot(f["depth"] * 1e9, f["E_apparent"] / 1e9, "k--", lw=1.5, label="Oliver-Pharr (composite)")
        ok = f["delivered"]
        style = dict(color="k", lw=2.5, marker="o", ms=3) if model == "exact" else dict(lw=1.2, marker=".", ms=4)
        ax.plot(f["depth"][ok] * 1e9, f["E_film"][ok] / 1e9, label=model, **style)
        alpha = "" if f["alpha"] is None else ", alpha %.3g" % f["alpha"]
        print("%-19s E_film = %6.2f +- %.2f GPa (fit to 150 nm%s)" % (model, f["E_film_mean"] / 1e9,
                                                                       f["E_film_mean_error"] / 1e9, alpha))
    ax.axhline(FILM[0] / 1e9, color="0.6", lw=0.8)
    ax.set_xlabel("depth h (nm)")
    ax.set_ylabel("film modulus (GPa)")
    ax.set_ylim(0, 160)
    top = ax.secondary_xaxis("top", functions=(lambda h: np.interp(h, exact["depth"] * 1e9, exact["a_over_t"]),
                                               lambda x: np.interp(x, exact["a_over_t"], exact["depth"] * 1e9)))
    top.set_xlabel("a/t")
    ax.set_title("70 GPa film, 500 nm, on 400 GPa: film modulus per depth by each model (1 % noise on S)")
    ax.legend(fontsize=8, ncol=2, loc="upper left")
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(os.path.join(args.output, "thin_film_python.png"))


if __name__ == "__main__":
    main()
