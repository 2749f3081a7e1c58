#!/usr/bin/env python3
"""assisted_report.py (reproduce) — the rows of the assisted elbow's study
for `make reproduce`: the statements of Suppl. Note 6.2 tested by
scripts/assisted_report.py's check() on this run, and the figure it draws.

  scripts/reproduce/assisted_report.py OUTDIR quick|full
"""
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.dirname(HERE))
import assisted_report as ar  # noqa: E402
from rows import Study  # noqa: E402


def main():
    out, budget = sys.argv[1], sys.argv[2]
    runs = ar.runs_of(out)
    tend = min(r["t"][-1] for r in runs.values())
    s = Study(out, "The elbow assisted by an artificial muscle", "Suppl. Note 6.2, Fig. 7",
              models=["examples/elbow_assisted.sinew", "models/human_arm.sinew"],
              commands=["SINEW_PATH=models bin/sinewc examples/elbow_assisted.sinew --let assisted=0 --let injured=0 -o HEALTHY",
                        "SINEW_PATH=models bin/sinewc examples/elbow_assisted.sinew --let assisted=0 -o INJURED",
                        "SINEW_PATH=models bin/sinewc examples/elbow_assisted.sinew -o AM",
                        "AM --set release_rate=0.25/s   # and 0.5/s, 1/s" +
                        ("   (all with --duration 0.45s)" if budget == "quick" else ""),
                        "# all five: scripts/assisted_study.sh (make assisted)"])
    found = []
    ar.check(runs, 0.2, found)
    for text, holds, figure in found:
        s.statement("Fig. 7b-c", text, holds, figure)
    flex = ", ".join("%s %.1f deg" % (n, ar.at(r, "flexion", tend)) for n, r in runs.items())
    s.note("Flexion at %.2f s: %s." % (tend, flex))
    ar.plot(runs, os.path.join(out, "assisted.png"))
    s.plot("assisted.png")
    s.note("Where the scene differs from the reference's: sinew's biceps runs straight from the top of the "
           "humerus, so it has no moment arm on a straight elbow; the arm starts at 45 deg of flexion and "
           "carries 150 N, not 200 N (examples/elbow_assisted.sinew says why). The AM takes the variational law; "
           "the reference's damping couple, whose rate is above any explicit 1/dt, is not applied "
           "(docs/validation.md, 'The elbow assisted by an artificial muscle').")
    g = ar.load(os.path.join(out, "G_am_1.h5"))
    a1 = runs["am_1"]
    s.convention("shear modulus G = E / (2 (1 + nu)) from a material's Poisson ratio",
                 "G = E / (1 + nu) for the AM's fibre (source/Polymer.cpp)", "elbow_assisted (the AM)",
                 "AM at 1/s: flexion at %.2f s %.1f deg with sinew's G, %.1f deg with the reference code's; mean AM "
                 "force from 0.2 s %.0f N against %.0f N" %
                 (tend, ar.at(a1, "flexion", tend), ar.at(g, "flexion", tend),
                  a1["force"][a1["t"] >= 0.2].mean(), g["force"][g["t"] >= 0.2].mean()))
    if budget == "quick":
        s.note("The quick budget runs 0.45 s of the reference's 0.7 s; the statements are tested from 0.2 s, "
               "past the ramps of the load and of the activation.")
    s.write()


if __name__ == "__main__":
    main()
