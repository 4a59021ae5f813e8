#!/usr/bin/python3
"""HTML report of a `ballista verify` run: one PNG per test, computed vs analytic.

Usage: verify_report.py DIR/verify.json   -> DIR/report.html and DIR/plots/<model>__<test>.png

Figures follow the thesis (seed 000) style: A1 as Fig. 4.2 (unrotated sigma_11 and spatial
sigma_xx, sigma_yy, sigma_xy against t), A2 as Fig. 4.5 (sigma_11 and sigma_22 against eps_11 with
the yield points) next to Fig. 4.6 (meridional profile sigma_11 - sigma_22 against pressure with the
yield surface dashed), A3 as Fig. 4.9 (stresses against t with the published points, meridional
path with the Drucker-Prager line), A4/A5 as Fig. 4.10c-4.12 (I1 against volumetric strain, porosity
against I1 with the crush curve), A5-fluid as Fig. 4.13 (drained vs saturated pressure-volume
curves), A6 as the rotated-vs-unrotated histories and the tangent scatter, A7 as Fig. 4.7 (the
deviator's path in the deviatoric plane with the yield circle, and the principal stresses against t),
A8 as Fig. 4.10a, b (the meridional path against the fixed and the moving surface, and I1 against
the axial strain).
Run with the interpreter CMake found (BALLISTA_PYTHON, /usr/bin/python3); needs numpy, matplotlib.
"""
import base64
import html
import json
import multiprocessing
import os
import re
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (backend first)
import numpy as np  # noqa: E402

MPA = 1e-6


def series(test, name):
    return np.asarray(test["series"].get(name, []), dtype=float)


def scalar(test, name, default=float("nan")):
    v = test["scalars"].get(name, default)
    return default if v is None else v


def stamp(ax, test):
    """Status, error and tolerance in the corner of the first axes."""
    err, tol = test.get("max_rel_error"), test.get("tolerance")
    text = "{}: max rel error {} (tolerance {})".format(
        test["status"].upper(),
        "n/a" if err is None else "{:.2e}".format(err),
        "n/a" if tol is None else "{:.1e}".format(tol))
    ax.text(0.01, 0.99, text, transform=ax.transAxes, va="top", ha="left", fontsize=8,
            color="green" if test["status"] == "pass" else "red",
            bbox=dict(facecolor="white", alpha=0.8, edgecolor="none"))


def plot_a1(test, fig):
    """Thesis Fig. 4.2: sigma_bar_11 and the spatial components against t."""
    ax = fig.add_subplot(1, 1, 1)
    t = series(test, "t")
    ax.plot(t, series(test, "sbar22"), color="0.6", lw=1.0, label=r"$\bar\sigma_{22}$ computed (analytic 0)")
    for key, an, colour, label in [("sbar11", "sbar11_an", "tab:blue", r"$\bar\sigma_{11}$ (unrotated)"),
                                   ("sxx", "sxx_an", "tab:red", r"$\sigma_{xx}$"),
                                   ("syy", "syy_an", "tab:green", r"$\sigma_{yy}$"),
                                   ("sxy", "sxy_an", "tab:orange", r"$\sigma_{xy}$")]:
        ax.plot(t, series(test, key), color=colour, lw=1.5, label=label + " computed")
        ax.plot(t, series(test, an), color="k", lw=0.8, ls="--")
    ax.plot([], [], color="k", lw=0.8, ls="--", label="analytic")
    ax.set_xlabel("t (s)")
    ax.set_ylabel("stress (Pa)")
    ax.set_title("{} {}: frame indifference (thesis Fig. 4.2)".format(test["model"], test["test"]), fontsize=10)
    ax.legend(fontsize=7, loc="lower left")
    ax.grid(alpha=0.3)
    stamp(ax, test)


def plot_a2(test, fig):
    """Thesis Fig. 4.5 (stress vs strain, yield points) and Fig. 4.6 (meridional profile)."""
    ax1 = fig.add_subplot(1, 2, 1)
    e = series(test, "e11") * 1e3
    ax1.plot(e, series(test, "s11") * MPA, color="tab:blue", lw=1.5, label=r"$\sigma_{11}$ computed")
    ax1.plot(e, series(test, "s22") * MPA, color="tab:red", lw=1.5, label=r"$\sigma_{22}$ computed")
    ax1.plot(e, series(test, "s11_an") * MPA, color="k", lw=0.8, ls="--", label="analytic")
    ax1.plot(e, series(test, "s22_an") * MPA, color="k", lw=0.8, ls="--")
    ye = series(test, "yield_e11") * 1e3
    ax1.plot(ye, series(test, "yield_s11") * MPA, "o", mfc="none", color="tab:blue", label="yield (analytic)")
    ax1.plot(ye, series(test, "yield_s22") * MPA, "o", mfc="none", color="tab:red")
    ax1.set_xlabel(r"$\varepsilon_{11} = \ln F_{11}$ ($10^{-3}$)")
    ax1.set_ylabel("stress (MPa)")
    ax1.set_title("{} {}: uniaxial strain (Fig. 4.5)".format(test["model"], test["test"]), fontsize=10)
    ax1.legend(fontsize=7, loc="lower right")
    ax1.grid(alpha=0.3)
    stamp(ax1, test)

    ax2 = fig.add_subplot(1, 2, 2)
    p = series(test, "pressure") * MPA
    ax2.plot(p, series(test, "q") * MPA, color="tab:purple", lw=1.5, label="stress path, computed")
    ax2.plot(series(test, "pressure_an") * MPA, series(test, "q_an") * MPA, color="k", lw=0.8, ls="--",
             label="analytic")
    ax2.plot(series(test, "yield_pressure") * MPA, series(test, "yield_q") * MPA, "o", mfc="none", color="k",
             label="yield points")
    sy = scalar(test, "yield_stress") * MPA
    lo, hi = np.min(p) * 1.1 - 10, np.max(p) * 1.1 + 10
    ax2.plot([lo, hi], [sy, sy], color="tab:gray", ls="--", lw=1, label="initial yield surface")
    ax2.plot([lo, hi], [-sy, -sy], color="tab:gray", ls="--", lw=1)
    if scalar(test, "h_iso", 0.0) > 0 or scalar(test, "h_kin", 0.0) > 0:
        beta, r = scalar(test, "reversal_backstress") * MPA, scalar(test, "reversal_radius") * MPA
        ax2.plot([lo, hi], [beta + r, beta + r], color="tab:green", ls="-.", lw=1,
                 label="yield surface at the load reversal")
        ax2.plot([lo, hi], [beta - r, beta - r], color="tab:green", ls="-.", lw=1)
    ax2.set_xlim(lo, hi)
    ax2.set_xlabel("pressure $P = -I_1/3$ (MPa)")
    ax2.set_ylabel(r"$\sigma_{11} - \sigma_{22}$ (MPa)  $(= \pm\sqrt{3 J_2})$")
    ax2.set_title("meridional profile (Fig. 4.6)", fontsize=10)
    ax2.legend(fontsize=7, loc="lower left")
    ax2.grid(alpha=0.3)


def plot_a3(test, fig):
    """Thesis Fig. 4.9: S11, S22 against t with the published points, and the meridional path
    sqrt(J2) against I1 with the Drucker-Prager line."""
    ax1 = fig.add_subplot(1, 2, 1)
    t = series(test, "t")
    ax1.plot(t, series(test, "s11"), color="tab:blue", lw=1.5, label=r"$\sigma_{11}$ computed")
    ax1.plot(t, series(test, "s22"), color="tab:red", lw=1.5, label=r"$\sigma_{22} = \sigma_{33}$ computed")
    ax1.plot(t, series(test, "s11_an"), color="k", lw=0.8, ls="--", label="exact (ln F path)")
    ax1.plot(t, series(test, "s22_an"), color="k", lw=0.8, ls="--")
    tt = series(test, "table_t")
    ax1.plot(tt, series(test, "table_s11"), "o", mfc="none", color="tab:blue", label="published (Brannon & L. 2010)")
    ax1.plot(tt, series(test, "table_s22"), "s", mfc="none", color="tab:red")
    ax1.set_xlabel("t (s)")
    ax1.set_ylabel("stress (Pa)")
    ax1.set_title("{} {}: Drucker-Prager vertex test (Fig. 4.9)".format(test["model"], test["test"]), fontsize=10)
    ax1.legend(fontsize=7, loc="lower right")
    ax1.grid(alpha=0.3)
    stamp(ax1, test)
    ax2 = fig.add_subplot(1, 2, 2)
    i1 = series(test, "i1")
    ax2.plot(i1, series(test, "sqrt_j2"), color="tab:purple", lw=1.5, label="stress path, computed")
    ax2.plot(series(test, "i1_an"), series(test, "sqrt_j2_an"), color="k", lw=0.8, ls="--", label="exact")
    peak, fs = scalar(test, "peak_i1"), scalar(test, "fslope")
    lo = min(np.min(i1), 0.0) * 1.1 if i1.size else -1.0
    ax2.plot([lo, peak], [fs * (peak - lo), 0.0], color="tab:gray", ls="--", lw=1,
             label=r"$\sqrt{J_2} = $ FSLOPE (PEAKI1 $- I_1$)")
    ax2.set_xlabel("$I_1$ (Pa)")
    ax2.set_ylabel(r"$\sqrt{J_2}$ (Pa)")
    ax2.set_title("meridional profile", fontsize=10)
    ax2.legend(fontsize=7, loc="upper right")
    ax2.grid(alpha=0.3)


def _crush_panel(ax, test, prefix=""):
    """Porosity against I1 with the analytic crush curve (thesis eq. 4.5, Fig. 4.11)."""
    ax.plot(series(test, prefix + "i1") * MPA, series(test, prefix + "porosity"), color="tab:red", lw=1.5,
            label="porosity, computed")
    ax.plot(series(test, prefix + "i1_an") * MPA, series(test, prefix + "porosity_an"), color="k", lw=0.8, ls="--",
            label="exact")
    ax.plot(series(test, "curve_i1") * MPA, series(test, "curve_porosity"), color="tab:green", lw=2, ls=":",
            label="crush curve (eq. 4.5)")
    ax.set_xlabel("$I_1$ (MPa)")
    ax.set_ylabel("porosity")
    ax.legend(fontsize=7, loc="upper left")
    ax.grid(alpha=0.3)


def _finish_hydrostat_axis(ax, test, title, legend_loc):
    """Labels, title, legend, grid and pass/fail stamp of an I1-against-volumetric-strain panel."""
    ax.set_xlabel(r"volumetric strain $\varepsilon_v = 3 \ln\lambda$")
    ax.set_ylabel("$I_1$ (MPa)")
    ax.set_title("{} {}: {}".format(test["model"], test["test"], title), fontsize=10)
    ax.legend(fontsize=7, loc=legend_loc)
    ax.grid(alpha=0.3)
    stamp(ax, test)


def plot_a4(test, fig):
    """Thesis Fig. 4.10c (fixed cap dwell) and Fig. 4.11 (porosity on the crush curve)."""
    ax1 = fig.add_subplot(1, 2, 1)
    for prefix, colour, label in [("fixed_", "tab:blue", "fixed cap"), ("", "tab:red", "evolving cap")]:
        ev = series(test, prefix + "ev")
        ax1.plot(ev, series(test, prefix + "i1") * MPA, color=colour, lw=1.5, label=label + ", computed")
        ax1.plot(ev, series(test, prefix + "i1_an") * MPA, color="k", lw=0.8, ls="--")
    ax1.plot([], [], color="k", lw=0.8, ls="--", label="exact")
    ax1.axhline(scalar(test, "p0") * MPA, color="tab:gray", ls=":", lw=1, label="$P_0$")
    _finish_hydrostat_axis(ax1, test, "hydrostatic compression", "lower left")
    ax2 = fig.add_subplot(1, 2, 2)
    _crush_panel(ax2, test)
    ax2.set_title("porosity on the crush curve (Fig. 4.11)", fontsize=10)


def plot_a5(test, fig):
    """Thesis Fig. 4.12: I1 against volumetric strain through the load-unload-reload cycle, and
    porosity against I1 with the crush curve."""
    ax1 = fig.add_subplot(1, 2, 1)
    ev = series(test, "ev")
    ax1.plot(ev, series(test, "i1") * MPA, color="tab:blue", lw=1.5, label="computed")
    ax1.plot(ev, series(test, "i1_an") * MPA, color="k", lw=0.8, ls="--", label="exact")
    ax1.axhline(scalar(test, "peak_i1") * MPA, color="tab:gray", ls=":", lw=1, label="PEAKI1")
    _finish_hydrostat_axis(ax1, test, "hydrostatic load-unload (Fig. 4.12)", "lower right")
    ax2 = fig.add_subplot(1, 2, 2)
    _crush_panel(ax2, test)
    ax2.axhline(scalar(test, "phi0"), color="tab:gray", ls=":", lw=1)
    ax2.set_title("porosity against $I_1$", fontsize=10)


def plot_a5_fluid(test, fig):
    """Thesis Fig. 4.13: pressure against volumetric strain drained and saturated, and porosity."""
    ax1 = fig.add_subplot(1, 2, 1)
    for prefix, colour, label in [("dry_", "tab:blue", "drained"), ("wet_", "tab:red", "water-saturated")]:
        ax1.plot(-series(test, prefix + "ev"), -series(test, prefix + "i1") / 3 * MPA, color=colour, lw=1.5,
                 label=label + ", computed")
    ax1.plot(-series(test, "dry_ev"), -series(test, "dry_i1_an") / 3 * MPA, color="k", lw=0.8, ls="--",
             label="drained, exact")
    ev = -series(test, "wet_ev")
    pf = series(test, "wet_pore_pressure")
    if pf.size == ev.size:
        ax1.plot(ev, pf * MPA, color="tab:cyan", lw=1.2, ls="-.", label="pore pressure (saturated)")
    ax1.set_xlabel(r"compressive volumetric strain $-\varepsilon_v$")
    ax1.set_ylabel("pressure $-I_1/3$ (MPa)")
    ax1.set_title("{} {}: fluid-filled pores (Fig. 4.13)".format(test["model"], test["test"]), fontsize=10)
    ax1.legend(fontsize=7, loc="upper left", bbox_to_anchor=(0.0, 0.93))
    ax1.grid(alpha=0.3)
    stamp(ax1, test)
    ax2 = fig.add_subplot(1, 2, 2)
    for prefix, colour, label in [("dry_", "tab:blue", "drained"), ("wet_", "tab:red", "water-saturated")]:
        ax2.plot(-series(test, prefix + "ev"), series(test, prefix + "porosity"), color=colour, lw=1.5, label=label)
    ax2.set_xlabel(r"compressive volumetric strain $-\varepsilon_v$")
    ax2.set_ylabel("porosity")
    ax2.legend(fontsize=7)
    ax2.grid(alpha=0.3)


def plot_a6_objectivity(test, fig):
    ax1 = fig.add_subplot(1, 2, 1)
    n = series(test, "step")
    every = max(1, len(n) // 40)
    for comp, colour in [("11", "tab:blue"), ("22", "tab:red"), ("12", "tab:green")]:
        ax1.plot(n, series(test, "ref" + comp), color=colour, lw=1.2, label=r"$\bar\sigma_{%s}$ unrotated" % comp)
        ax1.plot(n[::every], series(test, "const" + comp)[::every], "o", mfc="none", ms=4, color=colour)
        ax1.plot(n[::every], series(test, "rot" + comp)[::every], "x", ms=4, color=colour)
    ax1.plot([], [], "o", mfc="none", color="k", label="constant rotation")
    ax1.plot([], [], "x", color="k", label="rotating copy")
    ax1.set_xlabel("step")
    ax1.set_ylabel("unrotated stress (Pa)")
    ax1.set_title("{} {}: path 0".format(test["model"], test["test"]), fontsize=10)
    ax1.legend(fontsize=7)
    ax1.grid(alpha=0.3)
    stamp(ax1, test)
    ax2 = fig.add_subplot(1, 2, 2)
    d = np.maximum(series(test, "rel_diff"), 1e-17)
    ax2.semilogy(n, d, color="tab:purple", label="max relative difference, all paths and copies")
    ax2.axhline(test["tolerance"], color="tab:red", ls="--", label="tolerance")
    ax2.set_xlabel("step")
    ax2.set_ylabel("relative difference")
    ax2.set_ylim(1e-17, 1e-8)
    ax2.legend(fontsize=7)
    ax2.grid(alpha=0.3, which="both")


def plot_a6_tangent(test, fig):
    ax1 = fig.add_subplot(1, 2, 1)
    fd, model = series(test, "fd"), series(test, "model")
    scale = np.max(np.abs(fd)) if fd.size else 1.0
    ax1.plot(fd / scale, model / scale, ".", ms=3)
    ax1.plot([-1, 1], [-1, 1], "k--", lw=0.8, label="model = finite difference")
    ax1.set_xlabel("finite-difference tangent entry / max")
    ax1.set_ylabel("model tangent entry / max")
    ax1.set_title("{} {}".format(test["model"], test["test"]), fontsize=10)
    ax1.legend(fontsize=7, loc="lower right")
    ax1.grid(alpha=0.3)
    stamp(ax1, test)
    ax2 = fig.add_subplot(1, 2, 2)
    err = np.maximum(series(test, "sample_error"), 1e-17)
    smooth = series(test, "sample_smoothness")
    ax2.semilogy(err, "o", label="|T - T_fd| / |T_fd| per sample")
    ax2.semilogy(np.maximum(smooth, 1e-17), "x", label="|T_fd(h) - T_fd(2h)| / |T_fd| (skipped if above)")
    ax2.axhline(scalar(test, "smooth_limit"), color="tab:orange", ls=":", label="skip limit (near a kink)")
    ax2.axhline(test["tolerance"], color="tab:red", ls="--", label="tolerance")
    ax2.set_xlabel("sample")
    ax2.legend(fontsize=7)
    ax2.grid(alpha=0.3, which="both")


def plot_a7(test, fig):
    """Thesis Fig. 4.7: the deviator in the plane of diagonal deviators (fixed eigenvectors) with the
    yield circle, and the principal stresses against t; computed against exact."""
    ax1 = fig.add_subplot(1, 2, 1)
    r = scalar(test, "radius") * MPA
    phi = np.linspace(0.0, 2.0 * np.pi, 200)
    ax1.plot(r * np.cos(phi), r * np.sin(phi), color="tab:gray", ls="--", lw=1, label="yield circle")
    ax1.plot(series(test, "s1") * MPA, series(test, "s2") * MPA, color="tab:blue", lw=1.5, label="computed")
    ax1.plot(series(test, "s1_an") * MPA, series(test, "s2_an") * MPA, color="k", lw=0.8, ls="--",
             label="exact (Krieg & Krieg 1977)")
    ax1.set_aspect("equal")
    ax1.set_xlabel(r"$s \cdot E_1$ (MPa), $E_1 = $ diag(2, -1, -1)$/\sqrt{6}$")
    ax1.set_ylabel(r"$s \cdot E_2$ (MPa), $E_2 = $ diag(0, 1, -1)$/\sqrt{2}$")
    ax1.set_title("{} {}: deviatoric plane".format(test["model"], test["test"]), fontsize=10)
    ax1.legend(fontsize=7, loc="lower left")
    ax1.grid(alpha=0.3)
    stamp(ax1, test)
    ax2 = fig.add_subplot(1, 2, 2)
    t = series(test, "t")
    for key, colour in [("s11", "tab:blue"), ("s22", "tab:red"), ("s33", "tab:green")]:
        ax2.plot(t, series(test, key) * MPA, color=colour, lw=1.5, label=r"$\sigma_{%s}$" % key[1:])
        ax2.plot(t, series(test, key + "_an") * MPA, color="k", lw=0.8, ls="--")
    ax2.plot([], [], color="k", lw=0.8, ls="--", label="exact")
    ax2.set_xlabel("t (legs 0-1, 1-2, 2-3)")
    ax2.set_ylabel("principal stress (MPa)")
    ax2.set_title("constant eigenvectors, transient eigenvalues (Fig. 4.7)", fontsize=10)
    ax2.legend(fontsize=7)
    ax2.grid(alpha=0.3)


def plot_a8(test, fig):
    """Thesis Fig. 4.10a, b: the meridional path of uniaxial strain against the cone and the cap,
    fixed and moving, and I1 against the axial strain; computed against the reference."""
    ax1 = fig.add_subplot(1, 2, 1)
    peak, fs, cr = scalar(test, "peak_i1"), scalar(test, "fslope"), scalar(test, "cap_ratio")

    def surface(X):
        kappa = (X + cr * fs * peak) / (1.0 + cr * fs)
        i1 = np.linspace(X, peak, 400)
        u = np.clip((kappa - i1) / (kappa - X), 0.0, 1.0)
        return i1, fs * (peak - i1) * np.sqrt(np.where(i1 < kappa, 1.0 - u * u, 1.0))

    for prefix, colour, label in [("fixed_", "tab:blue", "(a) fixed cap"), ("", "tab:red", "(b) moving cap")]:
        ax1.plot(series(test, prefix + "i1") * MPA, series(test, prefix + "sqrt_j2") * MPA, color=colour, lw=1.5,
                 label=label + ", computed")
        ax1.plot(series(test, prefix + "i1_ref") * MPA, series(test, prefix + "sqrt_j2_ref") * MPA, color="k",
                 lw=0.8, ls="--")
        cap = series(test, prefix + "cap")
        if len(cap):
            i1, q = surface(cap[-1])
            ax1.plot(i1 * MPA, q * MPA, color=colour, lw=0.8, ls=":", label=label + ": final surface")
    i1, q = surface(scalar(test, "p0"))
    ax1.plot(i1 * MPA, q * MPA, color="tab:gray", lw=1, ls="--", label="initial surface")
    ax1.plot([], [], color="k", lw=0.8, ls="--", label="reference (consistency ODE)")
    ax1.axvline(scalar(test, "stationary_i1") * MPA, color="tab:blue", lw=0.6, ls="-.",
                label=r"$d\sqrt{J_2}/dI_1 = 1/(2\sqrt{3})$ on the fixed cap")
    ax1.set_xlabel("$I_1$ (MPa)")
    ax1.set_ylabel(r"$\sqrt{J_2}$ (MPa)")
    ax1.set_xlim(1.1 * min(series(test, "i1").min(), series(test, "cap").min()) * MPA, 1.2 * peak * MPA)
    ax1.set_ylim(0.0, None)
    ax1.set_title("{} {}: meridional profile (Fig. 4.10a, b)".format(test["model"], test["test"]), fontsize=10)
    ax1.legend(fontsize=6, loc="upper right")
    ax1.grid(alpha=0.3)
    stamp(ax1, test)
    ax2 = fig.add_subplot(1, 2, 2)
    for prefix, colour, label in [("fixed_", "tab:blue", "fixed cap"), ("", "tab:red", "moving cap")]:
        e = series(test, prefix + "e")
        ax2.plot(e, series(test, prefix + "i1") * MPA, color=colour, lw=1.5, label="$I_1$, " + label)
        ax2.plot(e, series(test, prefix + "i1_ref") * MPA, color="k", lw=0.8, ls="--")
        ax2.plot(e, series(test, prefix + "cap") * MPA, color=colour, lw=1, ls=":", label="cap $X$, " + label)
    ax2.plot([], [], color="k", lw=0.8, ls="--", label="reference")
    ax2.set_xlabel(r"compressive axial strain $-\ln F_{11}$")
    ax2.set_ylabel("MPa")
    ax2.set_title("uniaxial strain", fontsize=10)
    ax2.legend(fontsize=7)
    ax2.grid(alpha=0.3)


# Plot kind -> (function, figure size in inches, left/right margins). Fixed margins instead of
# tight_layout, which took half the report's time.
PLOTS = {"a1": (plot_a1, (7, 4.5), (0.11, 0.97)), "a2": (plot_a2, (12, 4.8), (0.07, 0.98)),
         "a3": (plot_a3, (12, 4.8), (0.07, 0.98)), "a4": (plot_a4, (12, 4.8), (0.07, 0.98)),
         "a5": (plot_a5, (12, 4.8), (0.07, 0.98)), "a5_fluid": (plot_a5_fluid, (12, 4.8), (0.07, 0.98)),
         "a6_objectivity": (plot_a6_objectivity, (12, 4.5), (0.07, 0.98)),
         "a6_tangent": (plot_a6_tangent, (11, 4.5), (0.07, 0.98)),
         "a7": (plot_a7, (12, 5.2), (0.07, 0.98)), "a8": (plot_a8, (12, 4.8), (0.07, 0.98))}


def render(job):
    """Draws one test's PNG (runs in a worker process)."""
    test, out_dir = job
    fn, size, (left, right) = PLOTS[test["plot"]]
    fig = plt.figure(figsize=size)
    fn(test, fig)
    fig.subplots_adjust(left=left, right=right, bottom=0.12, top=0.92, wspace=0.28)
    name = png_name(test)
    fig.savefig(os.path.join(out_dir, name), dpi=90)
    plt.close(fig)
    return name


def png_name(test):
    return "plots/{}__{}.png".format(re.sub(r"[^A-Za-z0-9_.-]", "_", test["model"]),
                                     re.sub(r"[^A-Za-z0-9_.-]", "_", test["test"]))


def embedded_png(out_dir, name):
    """The PNG as a data: URI, so that report.html is one self-contained file (it can be mailed or
    moved without its plots/ folder, which is still written beside it)."""
    with open(os.path.join(out_dir, name), "rb") as f:
        return "data:image/png;base64," + base64.b64encode(f.read()).decode("ascii")


def fmt(x, spec="{:.3g}"):
    return "–" if x is None else spec.format(x)


def write_html(doc, out_dir, images):
    s = doc["summary"]
    rows, sections = [], []
    for k, t in enumerate(doc["tests"]):
        status = t["status"]
        cls = {"pass": "pass", "fail": "fail"}.get(status, "na")
        anchor = "t{}".format(k)
        rows.append("<tr class='{}'><td>{}</td><td><a href='#{}'>{}</a></td><td>{}</td><td>{}</td><td>{}</td>"
                    "<td>{}</td></tr>".format(cls, html.escape(t["model"]), anchor, html.escape(t["test"]),
                                              status, fmt(t["max_rel_error"], "{:.2e}"),
                                              fmt(t["tolerance"], "{:.1e}"), html.escape(t["reason"])))
        checks = "".join("<tr class='{}'><td>{}</td><td>{}</td><td>{} {}</td></tr>".format(
            "pass" if c["pass"] else "fail", html.escape(c["name"]), fmt(c["value"], "{:.4g}"),
            html.escape(c["kind"]), fmt(c["limit"], "{:.4g}")) for c in t["checks"])
        body = "<h2 id='{}'>{} — {} <span class='{}'>{}</span></h2><p>{}</p>".format(
            anchor, html.escape(t["model"]), html.escape(t["test"]), cls, status, html.escape(t["title"]))
        if t["reason"]:
            body += "<p><b>Note:</b> {}</p>".format(html.escape(t["reason"]))
        if t["error_measure"]:
            body += "<p><b>Error measure:</b> {}<br><b>Tolerance:</b> {} — {}</p>".format(
                html.escape(t["error_measure"]), fmt(t["tolerance"], "{:.2e}"),
                html.escape(t["tolerance_justification"]))
        if checks:
            body += "<table><tr><th>check</th><th>value</th><th>limit</th></tr>{}</table>".format(checks)
        if k in images:
            body += "<p><img src='{}' alt='{} {}'></p>".format(embedded_png(out_dir, images[k]),
                                                               html.escape(t["model"]), html.escape(t["test"]))
        sections.append(body)
    page = """<!DOCTYPE html>
<html><head><meta charset="utf-8"><title>Ballista single-element verification</title>
<style>
body {{ font-family: sans-serif; max-width: 1300px; margin: 1em auto; }}
table {{ border-collapse: collapse; margin: 0.5em 0; font-size: 90%; }}
td, th {{ border: 1px solid #ccc; padding: 2px 6px; text-align: left; }}
.pass {{ color: #060; }} .fail {{ color: #b00; font-weight: bold; }} .na {{ color: #777; }}
img {{ max-width: 100%; }}
</style></head><body>
<h1>Ballista single-element verification (CATALOGUE §A)</h1>
<p>Ballista {version}; {npass} passed, {nfail} failed, {nna} not applicable; tests ran in {secs:.1f} s on {threads}
thread(s). Data: <a href="verify.json">verify.json</a>. How each test works and why its tolerance is what it is:
docs/validation.md, "Single-element verification (ballista verify)".</p>
<table><tr><th>model</th><th>test</th><th>status</th><th>max rel error</th><th>tolerance</th><th>note</th></tr>
{rows}
</table>
{sections}
</body></html>
""".format(version=html.escape(doc["ballista_version"]), npass=s["pass"], nfail=s["fail"], nna=s["not_applicable"],
           secs=doc["wall_seconds"], threads=doc["threads"], rows="\n".join(rows), sections="\n".join(sections))
    tmp = os.path.join(out_dir, "report.html.tmp")
    with open(tmp, "w", encoding="utf-8") as f:
        f.write(page)
    os.replace(tmp, os.path.join(out_dir, "report.html"))


def main(argv):
    if len(argv) != 2:
        sys.stderr.write("usage: verify_report.py DIR/verify.json\n")
        return 2
    path = argv[1]
    out_dir = os.path.dirname(os.path.abspath(path))
    with open(path, encoding="utf-8") as f:
        doc = json.load(f)
    os.makedirs(os.path.join(out_dir, "plots"), exist_ok=True)
    jobs = []
    for k, t in enumerate(doc["tests"]):
        kind = t.get("plot")
        if not kind:
            continue
        if kind not in PLOTS:
            sys.stderr.write("verify_report: unknown plot kind '{}' ({} {})\n".format(kind, t["model"], t["test"]))
            return 1
        jobs.append((k, t))
    # The figures are independent: draw them in up to two worker processes (the machines this runs
    # on have two cores; matplotlib is single-threaded).
    workers = min(2, len(jobs), os.cpu_count() or 1)
    if workers > 1:
        with multiprocessing.get_context("fork").Pool(workers) as pool:
            names = pool.map(render, [(t, out_dir) for _, t in jobs])
    else:
        names = [render((t, out_dir)) for _, t in jobs]
    images = {k: name for (k, _), name in zip(jobs, names)}
    write_html(doc, out_dir, images)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
