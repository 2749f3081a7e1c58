#!/usr/bin/python3
"""demo_elbow.py — `make demo`: a fast run of examples/elbow_flexion.sinew
beside the stored curves of its 50 ns reference.

  demo_elbow.py compare RUN.h5 REF.csv [-o OUT.png] [--wall S] [--within PCT]
  demo_elbow.py reference RUN.h5 -o REF.csv --command TEXT [--wall S] [--cpu S] [--revision R]

compare  reads the elbow angle (/joints/arm.elbow/angle) and the long head's
         force (/muscles/arm.biceps_long/force) of RUN.h5, interpolates the
         reference linearly onto the run's frame times (the same times when
         the run's dt divides 1 ms, as the demo's does), and prints the
         largest difference of each over the run, in its unit and as a
         percentage of the reference's range of motion (largest - smallest
         value over the 0.5 s; the measure of docs/tradeoff.md).  With -o it
         draws both runs in two panels, angle and force, each with the
         difference on a second axis.  Its last line is the demo's summary.
         --within PCT (e.g. 1): exit 5 when either difference is larger.
reference  writes the two curves of a reference run as REF.csv: '#' lines
         of provenance (command, git revision, date, model, dt, integrator,
         CPU, wall and processor time), then the header time_s,angle_rad,force_N and one
         line per frame.

Runs under Debian's /usr/bin/python3 (python3-h5py, python3-matplotlib,
installed by scripts/deps.sh).  Every problem is one line naming the file,
never a traceback.  Exit codes as sinew's tools: 0 ok, 1 h5py or matplotlib
missing, 2 usage, 4 input or output error (a run that did not complete is
one), 5 a difference beyond --within.
"""
import argparse
import datetime
import os
import platform
import subprocess
import sys

PROG = "demo_elbow"
EXIT_DEPS, EXIT_USAGE, EXIT_IO, EXIT_BEYOND = 1, 2, 4, 5
ANGLE = "/joints/arm.elbow/angle"
FORCE = "/muscles/arm.biceps_long/force"
COLUMNS = ["time_s", "angle_rad", "force_N"]

np = h5py = plt = None


class DemoError(Exception):
    def __init__(self, code, message):
        super().__init__(message)
        self.code = code


def load_modules(plot):
    global np, h5py, plt
    try:
        import numpy as np
        import h5py
        if plot:
            import matplotlib
            matplotlib.use("Agg")
            import matplotlib.pyplot as plt
    except ImportError as e:
        raise DemoError(EXIT_DEPS, f"{e.name or e} is missing: install python3-h5py and "
                        "python3-matplotlib (Debian; `make deps` does it)") from None


def text_attr(f, name):
    v = f.attrs.get(name)
    if isinstance(v, bytes):
        return v.decode("utf-8", "replace")
    return None if v is None else str(v) if not hasattr(v, "item") else v.item()


def read_run(path):
    """time, angle (rad), force (N) and the attributes of a run's output."""
    if not os.path.exists(path):
        raise DemoError(EXIT_IO, f"{path}: no such file")
    try:
        f = h5py.File(path, "r")
    except OSError as e:
        raise DemoError(EXIT_IO, f"{path}: cannot read as HDF5 ({e})") from None
    with f:
        status = text_attr(f, "status")
        if status is not None and not str(status).startswith("complete"):
            raise DemoError(EXIT_IO, f"{path}: the run did not complete (status: {status})")
        cols = []
        for d in ("/time", ANGLE, FORCE):
            obj = f.get(d)
            if obj is None or not hasattr(obj, "shape") or len(obj.shape) != 1:
                raise DemoError(EXIT_IO, f"{path}: no dataset {d} [F] (is it a run of "
                                "examples/elbow_flexion.sinew?)")
            cols.append(np.asarray(obj[()], dtype=float))
        attrs = {k: text_attr(f, k) for k in ("dt", "integrator", "model_sha256")}
    n = min(len(c) for c in cols)
    if n < 2:
        raise DemoError(EXIT_IO, f"{path}: fewer than two frames")
    return cols[0][:n], cols[1][:n], cols[2][:n], attrs


def read_reference(path):
    """The stored curves and their '# key: value' provenance lines."""
    try:
        with open(path, encoding="utf-8") as fh:
            lines = fh.read().splitlines()
    except (OSError, UnicodeDecodeError) as e:
        raise DemoError(EXIT_IO, f"{path}: cannot read ({e})") from None
    meta, rows, header = {}, [], None
    for no, line in enumerate(lines, 1):
        if line.startswith("#"):
            key, sep, value = line[1:].partition(":")
            if sep and header is None:
                meta[key.strip()] = value.strip()
            continue
        if not line.strip():
            continue
        fields = [x.strip() for x in line.split(",")]
        if header is None:
            if fields != COLUMNS:
                raise DemoError(EXIT_IO, f"{path}:{no}: expected the header "
                                f"'{','.join(COLUMNS)}', got '{line.strip()}'")
            header = fields
            continue
        try:
            row = [float(x) for x in fields]
        except ValueError:
            row = []
        if len(row) != 3 or not all(np.isfinite(row)):
            raise DemoError(EXIT_IO, f"{path}:{no}: expected three numbers, got '{line.strip()}'")
        rows.append(row)
    if len(rows) < 2:
        raise DemoError(EXIT_IO, f"{path}: fewer than two rows of data")
    data = np.array(rows)
    if np.any(np.diff(data[:, 0]) <= 0):
        raise DemoError(EXIT_IO, f"{path}: the times do not increase")
    for key in ("dt", "integrator"):
        if key not in meta:
            raise DemoError(EXIT_IO, f"{path}: no '# {key}: ...' line")
    try:
        meta["dt_s"] = float(meta["dt"].split()[0])
    except ValueError:
        raise DemoError(EXIT_IO, f"{path}: '# dt: {meta['dt']}' is not a number in s") from None
    return data[:, 0], data[:, 1], data[:, 2], meta


def fmt_time(s):
    for unit, scale in (("s", 1.0), ("ms", 1e-3), ("us", 1e-6), ("ns", 1e-9)):
        if abs(s) >= scale:
            return f"{s / scale:.4g} {unit}"
    return f"{s:g} s"


def pct(x):
    return f"{x:.2g}"


def compare(args):
    t, a, fo, attrs = read_run(args.run)
    rt, ra, rf, meta = read_reference(args.reference)
    tol = 1e-9 * max(1.0, rt[-1])
    keep = (t >= rt[0] - tol) & (t <= rt[-1] + tol)
    if not keep.any():
        raise DemoError(EXIT_IO, f"{args.run}: no frame inside the reference's span "
                        f"{rt[0]:g} to {rt[-1]:g} s")
    ia = np.interp(t[keep], rt, ra)
    iff = np.interp(t[keep], rt, rf)
    da, df = a[keep] - ia, fo[keep] - iff
    span_a, span_f = np.ptp(ra), np.ptp(rf)
    ea, ef = np.max(np.abs(da)), np.max(np.abs(df))
    pa, pf = 100 * ea / span_a, 100 * ef / span_f
    tk = t[keep]
    print(f"{PROG}: largest difference from the reference over {fmt_time(tk[0])} to "
          f"{fmt_time(tk[-1])}: angle {np.degrees(ea):.3g} deg ({pct(pa)} % of its "
          f"{np.degrees(span_a):.3g} deg range), force {ef:.3g} N ({pct(pf)} % of its "
          f"{span_f:.3g} N range)")
    dt = attrs.get("dt")
    ref_dt = meta["dt_s"]
    ref_name = f"{fmt_time(ref_dt)} reference"
    if args.output:
        plot(args, (t, a, fo, da, df, tk), (rt, ra, rf), attrs, meta, (pa, pf))
        print(f"{PROG}: wrote {args.output}")
    wall = f" in {args.wall:.3g} s wall" if args.wall is not None else ""
    step = (f", at dt = {fmt_time(dt)} ({dt / ref_dt:.3g} x the reference's step, "
            f"{attrs.get('integrator')})") if dt else ""
    print(f"simulated {t[-1] - t[0]:.3g} s{wall}, within {pct(pa)}% (angle) and "
          f"{pct(pf)}% (force) of the {ref_name}{step}")
    if args.within is not None and max(pa, pf) > args.within:
        raise DemoError(EXIT_BEYOND, f"the run is NOT within {args.within:g}% of the "
                        f"reference (angle {pct(pa)}%, force {pct(pf)}%)")
    return 0


def plot(args, run, ref, attrs, meta, pcts):
    t, a, fo, da, df, tk = run
    rt, ra, rf = ref
    dt = attrs.get("dt")
    fig, axes = plt.subplots(2, 1, figsize=(7.5, 6.5), sharex=True)
    ref_label = f"reference: {meta['integrator']}, dt = {fmt_time(meta['dt_s'])}"
    run_label = (f"this run: {attrs.get('integrator')}, dt = {fmt_time(dt)} "
                 f"({dt / meta['dt_s']:.3g} x)") if dt else "this run"
    panels = ((axes[0], np.degrees(ra), np.degrees(a), np.degrees(da), "elbow angle (deg)",
               "deg", pcts[0]),
              (axes[1], rf, fo, df, "long head's force (N)", "N", pcts[1]))
    for ax, rv, v, d, ylabel, unit, p in panels:
        ax.plot(rt, rv, color="0.75", lw=5, label=ref_label)
        ax.plot(t, v, color="C0", lw=1.2, ls="--", label=run_label)
        ax.set_ylabel(ylabel)
        ax.set_title(f"largest difference {np.max(np.abs(d)):.2g} {unit} ({pct(p)} % of range)",
                     fontsize=10)
        ax.grid(alpha=0.3)
        twin = ax.twinx()
        twin.plot(tk, d, color="C3", lw=0.8, alpha=0.8)
        twin.set_ylabel(f"this run - reference ({unit})", color="C3")
        twin.tick_params(axis="y", colors="C3")
        lim = max(np.max(np.abs(d)), 1e-300) * 1.1
        twin.set_ylim(-lim, lim)
    axes[0].legend(loc="upper right", fontsize=8)
    axes[1].set_xlabel("time (s)")
    fig.suptitle("examples/elbow_flexion.sinew", fontsize=11)
    fig.tight_layout()
    try:
        fig.savefig(args.output, dpi=110)
    except (OSError, ValueError) as e:
        raise DemoError(EXIT_IO, f"{args.output}: cannot write ({e})") from None


def git_revision():
    try:
        r = subprocess.run(["git", "describe", "--always", "--dirty", "--abbrev=12"],
                           capture_output=True, text=True, check=True,
                           cwd=os.path.dirname(os.path.abspath(__file__)))
        return r.stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return "unknown"


def cpu_name():
    try:
        with open("/proc/cpuinfo", encoding="utf-8") as fh:
            for line in fh:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown"


def reference(args):
    t, a, fo, attrs = read_run(args.run)
    now = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
    lines = [
        "# The 50 ns reference of examples/elbow_flexion.sinew: the elbow angle",
        "# (/joints/arm.elbow/angle) and the long head's force",
        "# (/muscles/arm.biceps_long/force), one line per frame (every 1 ms), as",
        "# `make demo` draws them beside its fast run and tests/lang/test_demo_reference.sh",
        "# checks them against short runs.  Written by scripts/demo_elbow.py reference.",
        f"# command: {args.command}",
        f"# revision: {args.revision or git_revision()}",
        f"# date: {now}",
        f"# model_sha256: {attrs.get('model_sha256')}",
        f"# dt: {attrs.get('dt'):.9g} s",
        f"# integrator: {attrs.get('integrator')}",
        f"# machine: {cpu_name()}, {os.cpu_count()} processors",
    ]
    if args.wall is not None:
        lines.append(f"# wall: {args.wall:.0f} s")
    if args.cpu is not None:
        lines.append(f"# processor time: {args.cpu:.0f} s")
    lines.append(",".join(COLUMNS))
    lines += [f"{x:.9g},{y:.12g},{z:.12g}" for x, y, z in zip(t, a, fo)]
    try:
        with open(args.output, "w", encoding="utf-8") as fh:
            fh.write("\n".join(lines) + "\n")
    except OSError as e:
        raise DemoError(EXIT_IO, f"{args.output}: cannot write ({e})") from None
    print(f"{PROG}: wrote {args.output} ({len(t)} frames)")
    return 0


class Parser(argparse.ArgumentParser):
    def error(self, message):
        raise DemoError(EXIT_USAGE, message)


def parse(argv):
    p = Parser(prog=PROG, description="make demo: a run beside the stored 50 ns reference")
    sub = p.add_subparsers(dest="mode", required=True, parser_class=Parser)
    c = sub.add_parser("compare", help="compare a run with the stored reference, plot both")
    c.add_argument("run")
    c.add_argument("reference")
    c.add_argument("-o", "--output", help="PNG of both curves (two panels)")
    c.add_argument("--wall", type=float, help="the run's wall time, s (for the summary)")
    c.add_argument("--within", type=float, help="exit 5 beyond this many % of range")
    r = sub.add_parser("reference", help="store a reference run's curves as CSV")
    r.add_argument("run")
    r.add_argument("-o", "--output", required=True)
    r.add_argument("--command", required=True, help="the command that made the run")
    r.add_argument("--wall", type=float, help="its wall time, s")
    r.add_argument("--cpu", type=float, help="its processor time, s")
    r.add_argument("--revision", help="the git revision the simulator was built from "
                   "(default: git describe of this checkout)")
    return p.parse_args(argv)


def main(argv):
    try:
        args = parse(argv)
        load_modules(args.mode == "compare" and args.output)
        return compare(args) if args.mode == "compare" else reference(args)
    except DemoError as e:
        print(f"{PROG}: {e}", file=sys.stderr)
        return e.code
    except KeyboardInterrupt:
        print(f"{PROG}: interrupted", file=sys.stderr)
        return 130
    except BrokenPipeError:   # e.g. piped into head
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
