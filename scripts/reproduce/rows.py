"""rows.py — what a study module of `make reproduce` leaves for the page.

Design.  A study module (scripts/reproduce/STUDY.sh) runs its scenes and
then a report script that measures the runs and states, for each claim of
the reference, sinew's figure and a verdict.  This module is the one way
those reach the page: Study(outdir) collects the meta data (title, the
reference's place, models, command lines, plots, notes) and the rows, and
write() leaves OUTDIR/meta.json and OUTDIR/rows.jsonl, which
scripts/reproduce_page.py reads, with OUTDIR/conventions.jsonl: the
defaults of sinew that differ from the reference's code, each with its
effect measured on the study's scenes.  A verdict is "agree" or "differ" for a
number compared with the reference's, "holds" or "fails" for a statement;
every row carries whether its figure is bitwise reproducible run to run.
"""
import json
import os

VERDICTS = ("agree", "differ", "holds", "fails")


class Study:
    def __init__(self, outdir, title, reference, models=(), commands=(), plots=(), notes=""):
        self.outdir = outdir
        self.meta = {"title": title, "reference": reference, "models": list(models),
                     "commands": list(commands), "plots": list(plots), "notes": notes}
        self.rows = []
        self.conventions = []

    def command(self, line):
        self.meta["commands"].append(line)

    def commands_from(self, path):
        """The command lines a module's run helper logged (scripts/reproduce/runs.sh), one a line."""
        with open(path) as f:
            for line in f:
                self.command(line.strip())

    def plot(self, name):
        self.meta["plots"].append(name)

    def save_plot(self, fig, name, dpi=110, **savefig):
        """fig laid out, written as name in the study's folder, and listed."""
        fig.tight_layout()
        fig.savefig(os.path.join(self.outdir, name), dpi=dpi, **savefig)
        self.plot(name)

    def note(self, text):
        self.meta["notes"] = (self.meta["notes"] + "\n\n" + text).strip()

    def row(self, figure, claim, sinew, verdict, why="", bitwise=True):
        if verdict not in VERDICTS:
            raise ValueError("verdict %r is not one of %s" % (verdict, ", ".join(VERDICTS)))
        self.rows.append({"figure": figure, "claim": claim, "sinew": sinew,
                          "verdict": verdict, "why": why, "bitwise": bool(bitwise)})

    def compare(self, figure, claim, value, reference, tolerance, unit="", fmt="%.4g", why_differ="",
                bitwise=True):
        """A number against the reference's: agree within the relative
        tolerance, else differ (why_differ then says why)."""
        rel = abs(value - reference) / abs(reference) if reference else abs(value)
        verdict = "agree" if rel <= tolerance else "differ"
        text = (fmt % value) + (" " + unit if unit else "") + " (%+.1f%%)" % (100 * (value - reference) / reference
                                                                              if reference else 0)
        why = "within %.3g%% of the reference's" % (100 * tolerance) if verdict == "agree" else why_differ
        self.row(figure, claim, text, verdict, why, bitwise)
        return verdict

    def statement(self, figure, claim, holds, figure_text, why="", bitwise=True):
        self.row(figure, claim, figure_text, "holds" if holds else "fails", why, bitwise)

    def convention(self, default, reference_code, scenes, effect):
        """A default of sinew that is not the reference code's, the scenes
        it touches and its effect as measured by this study's runs."""
        self.conventions.append({"default": default, "reference": reference_code,
                                 "scenes": scenes, "effect": effect})

    def write(self):
        os.makedirs(self.outdir, exist_ok=True)
        with open(os.path.join(self.outdir, "meta.json"), "w") as f:
            json.dump(self.meta, f, indent=1)
        with open(os.path.join(self.outdir, "rows.jsonl"), "w") as f:
            for r in self.rows:
                f.write(json.dumps(r) + "\n")
        with open(os.path.join(self.outdir, "conventions.jsonl"), "w") as f:
            for c in self.conventions:
                f.write(json.dumps(c) + "\n")
