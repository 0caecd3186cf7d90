#!/usr/bin/env python3
"""Fit the work of adhesion w and the film thickness t to measured (a, F) data from Python,
as `coatcontact fit DATA --columns a,F --free w,t` does, and plot data, fit and residuals.

usage: fit_data.py [DATA] [--output DIR]   DATA: two columns a, F ('#' comments), in m and N
unless a '# units: um mN' line says otherwise (read by coatcontact.read_curve, as the CLI
reads it); default data/example_a_F.tsv (1 MPa elastomer film on glass, 5 mm sphere, in um
and mN). Writes DIR/fit_python.png.
"""
import argparse
import os

import matplotlib
matplotlib.use("Agg")  # headless: tests and CI have no display
import matplotlib.pyplot as plt
import coatcontact as cc

HERE = os.path.dirname(os.path.abspath(__file__))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("data", nargs="?", default=os.path.join(HERE, "..", "..", "data", "example_a_F.tsv"))
    parser.add_argument("--output", default=".", help="folder of fit_python.png")
    args = parser.parse_args()

    data = cc.read_curve(args.data, "a,F")  # the CLI's reader and unit table: a [m], F [N]
    a, F = data["a"], data["F"]
    r = cc.fit(a, F, kind="a", radius=5e-3, film=(1e6, 0.49), substrate=(70e9, 0.22),
               thickness=40e-6, free=("w", "t"))
    est, err = r["estimates"], r["errors"]
    print("w = %.6g J/m2 +- %.2g, t = %.6g m +- %.2g, R^2 = %.6f, correlation w, t %.3f"
          % (est["w"], err["w"], est["t"], err["t"], r["r_squared"], r["correlation"][0, 1]))

    fig, (top, bottom) = plt.subplots(2, 1, figsize=(8, 7), dpi=100, sharex=True,
                                      gridspec_kw={"height_ratios": [3, 1]})
    top.plot(a * 1e6, F * 1e3, "o", ms=3, label="data")
    top.plot(r["curve"]["a"] * 1e6, r["curve"]["F"] * 1e3, "-",
             label="fit: w = %.4g mJ/m², t = %.4g µm" % (est["w"] * 1e3, est["t"] * 1e6))
    top.set_ylabel("F [mN]")
    top.set_xlim(0, 1.05e6 * a.max())
    top.set_ylim(1.2e3 * F.min(), 1.2e3 * F.max())
    top.legend()
    bottom.plot(a * 1e6, r["residual"] * 1e6, "o", ms=3)
    bottom.axhline(0, color="0.5")
    bottom.set_xlabel("a [µm]")
    bottom.set_ylabel("F_model - F [µN]")
    path = os.path.join(args.output, "fit_python.png")
    fig.savefig(path)
    print("wrote", path)


if __name__ == "__main__":
    main()
