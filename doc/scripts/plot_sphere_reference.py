#!/usr/bin/env python3
"""Plot the published wall corrections for a rigid sphere on the axis of a
tube against the body-fitted solution (doc/validation.md, Section 2).

    /usr/bin/python3 doc/scripts/plot_sphere_reference.py SPHERE_IN_TUBE_REFERENCE PICTURE.png

Runs the program SPHERE_IN_TUBE_REFERENCE (build/sphere-in-tube-reference)
at λ = 0.2, 0.25, ..., 0.8 on its mesh of 4 refinements (converged to 5e-4
or better, 20 seconds in all) and plots (a) the towed drag factor K and the
free sphere's U/U_c, and (b) how far Bohlin's (1960) K and Haberman &
Sayre's (1958) K and U/U_c lie from it. Prints the table it plots and adds
it to doc/results/sphere_wall_corrections.csv (rbc_ifem_run.add_results).
Needs python3-matplotlib.
"""
import subprocess
import sys

import plot_style
from rbc_ifem_run import add_results, parse_table

plt = plot_style.pyplot()

REFINEMENTS = 4


def bohlin_drag_factor(l):
    return 1 / (1 - 2.10444 * l + 2.08877 * l**3 - 0.94813 * l**5 - 1.372 * l**6
                + 3.87 * l**8 - 4.19 * l**10)


def haberman_sayre_velocity_ratio(l):
    return (1 - 2 / 3 * l**2 - 0.20217 * l**5) / (1 - 0.75857 * l**5)


def haberman_sayre_drag_factor(l):
    return (1 - 0.75857 * l**5) / (1 - 2.1050 * l + 2.0865 * l**3 - 1.7068 * l**5
                                   + 0.72603 * l**6)


def body_fitted(program, l):
    """K and U/U_c on the finest mesh of one run of the program."""
    text = subprocess.run([program, str(l), str(REFINEMENTS)], check=True,
                          capture_output=True, text=True).stdout
    last = parse_table(text)[-1]
    return last["towed_drag_factor"], last["velocity_ratio"]


def main(program, picture):
    lambdas = [round(0.2 + 0.05 * i, 2) for i in range(13)]
    rows = [(l, *body_fitted(program, l)) for l in lambdas]
    header = ["λ", "K", "U/U_c", "Bohlin K", "Haberman-Sayre K", "Haberman-Sayre U/U_c"]
    table = [[l, f"{k:.5f}", f"{u:.5f}", f"{bohlin_drag_factor(l):.5f}",
              f"{haberman_sayre_drag_factor(l):.5f}", f"{haberman_sayre_velocity_ratio(l):.5f}"]
             for l, k, u in rows]
    print(",".join(header))
    for row in table:
        print(",".join(str(v) for v in row))
    print("added to", add_results("sphere_wall_corrections", header, table))

    figure, (left, right) = plt.subplots(1, 2, figsize=(10, 4), layout="constrained")
    l = [r[0] for r in rows]
    left.semilogy(l, [r[1] for r in rows], "k-o", ms=3, label="K, body-fitted")
    left.semilogy(l, [r[2] for r in rows], "b-s", ms=3, label="U/U$_c$, body-fitted")
    left.set_xlabel("λ = a/R")
    left.set_ylabel("K = F/(6πμaU) and U/U$_c$")
    plot_style.plain_log_ticks(left.yaxis)
    left.set_title("(a) towed drag factor K and free sphere's U/U$_c$")
    left.legend()
    left.grid(True, which="both", alpha=0.3)

    def percent(published, index, largest=1.):
        kept = [r for r in rows if r[0] <= largest]
        return [r[0] for r in kept], [100 * (published(r[0]) / r[index] - 1) for r in kept]

    # Bohlin's truncated series has a pole near λ = 0.7.
    right.plot(*percent(bohlin_drag_factor, 1, 0.65), "k--", label="Bohlin (1960) K, λ ≤ 0.65")
    right.plot(*percent(haberman_sayre_drag_factor, 1), "k:", label="Haberman & Sayre (1958) K")
    right.plot(*percent(haberman_sayre_velocity_ratio, 2), "b-", label="Haberman & Sayre U/U$_c$")
    right.axhline(0, color="grey", lw=0.5)
    right.set_ylim(-10, 10)
    right.set_xlabel("λ = a/R")
    right.set_ylabel("published / body-fitted − 1 [%]")
    right.set_title("(b) the published formulas against it")
    right.legend()
    plot_style.save(figure, picture)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
