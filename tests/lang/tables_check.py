#!/usr/bin/python3
"""tables_check.py — compare the scenes' compiled numbers with the reference's
tables (tests/reference/tables.tsv), for tests/lang/test_tables.sh.

    tables_check.py TABLES.tsv INFO_DIR ROOT [SCENE...]

INFO_DIR holds SCENE.info, each the `--info` output of one compiled scene;
with SCENEs, only their rows are checked (test_wing.sh checks the wing's,
whose compilation takes seconds, from the simulator it builds anyway).
Every row of the data file is one number of Zhang et al. 2019's
Supplementary Tables 1-10 (or of the text right by them) that a scene
uses, or one number that is sinew's own:

  check      the scene's value (read from --info) must equal the table's to
             the digits the table prints: |scene - table| <= half a unit of
             the table's last digit (and of --info's, which prints 4 to 6
             digits); a range "15-20" must hold the scene's value;
  deviation  the scene differs from the table on purpose; the row records
             the scene's value and the reason; the scene must still hold
             that value (else the record is stale), and the line is printed;
  own        a number that is not the reference's: the row records the
             scene's value, and the file named in `table` ("sinew:FILE")
             must say so in its header comment (the `note` column is the
             text to find there).

Each row prints one TAP line, "ok - ..." or "not ok - ...", with the table
entry named; deviations and own numbers are listed as "# ..." lines too.

Design.  --info prints the compiled model (runtime/sim/cli_info.c): rods
(count, elements, length, radius), materials (E, G, density), joints
(stiffness), muscles (area, F_max, l0), environments, dt and duration,
params.  parse_info() turns it into dictionaries in SI; a row's `reading`
is a Python expression over small accessors (rod("arm.humerus",
"length"), material("bone_tissue", "E"), ...), so that a derived number
(EI = E pi r^4 / 4, a sum of element counts) is written where it is used.
"""
import math
import os
import re
import sys

# ---- units: a table's unit to SI ----
UNITS = {
    "": 1.0, "1": 1.0, "Pa": 1.0, "kPa": 1e3, "MPa": 1e6, "GPa": 1e9,
    "g/cm^3": 1e3, "g/mm^3": 1e6, "kg/m^3": 1.0,
    "m": 1.0, "cm": 1e-2, "mm": 1e-3, "um": 1e-6,
    "mm^2": 1e-6, "cm^2": 1e-4, "m^2": 1.0,
    "s": 1.0, "ms": 1e-3, "us": 1e-6, "ns": 1e-9,
    "N": 1.0, "mN": 1e-3, "uN": 1e-6, "kg/s^2": 1.0, "N/m": 1.0, "kg/s": 1.0,
    "N mm^2": 1e-6, "N m^2": 1.0, "deg": math.pi / 180,
}
TIME = {"s": 1.0, "ms": 1e-3, "us": 1e-6, "ns": 1e-9}


def half_ulp(text):
    """Half a unit of the last digit of a number as printed: '0.0105' ->
    5e-5, '5e5' -> 5e4, '319.4' -> 0.05, '10' -> 0.5."""
    t = text.strip().lower()
    mant, _, exp = t.partition("e")
    exp = int(exp) if exp else 0
    decimals = len(mant.split(".")[1]) if "." in mant else 0
    return 0.5 * 10.0 ** (exp - decimals)


def num(s):
    return float(s)


def parse_info(text):
    info = {"rod": {}, "group": {}, "material": {}, "joint": {}, "kjoint": {},
            "muscle": {}, "ground": {}, "contact": {}, "fluid": {}, "wave": {},
            "param": {}, "dt": None, "duration": None, "stable": None}
    section = None
    last_fluid = None
    for line in text.splitlines():
        if not line.startswith(" "):
            section = line.split(":")[0]
            m = re.match(r"dt: ([-0-9.e+]+) (\w+) \(.*stable estimate ([-0-9.e+]+) (\w+)\)", line)
            if m:
                info["dt"] = num(m.group(1)) * TIME[m.group(2)]
                info["stable"] = num(m.group(3)) * TIME[m.group(4)]
            m = re.match(r"duration: ([-0-9.e+]+) (\w+),", line)
            if m:
                info["duration"] = num(m.group(1)) * TIME[m.group(2)]
            continue
        body = line.strip()
        if section == "rods":
            m = re.match(r"(\S+): (\d+) rods, (\d+)(?: to (\d+))? elements, length ([-0-9.e+]+) to "
                         r"([-0-9.e+]+) m, radius ([-0-9.e+]+)(?: to ([-0-9.e+]+))? mm", body)
            if m:
                e0 = int(m.group(3))
                info["group"][m.group(1)] = {
                    "rods": int(m.group(2)), "elements_min": e0,
                    "elements_max": int(m.group(4)) if m.group(4) else e0,
                    "length_min": num(m.group(5)), "length_max": num(m.group(6)),
                    "radius_min": num(m.group(7)) * 1e-3,
                    "radius_max": num(m.group(8) or m.group(7)) * 1e-3}
                continue
            m = re.match(r"(\S+): (\d+) elements, length ([-0-9.e+]+) m, radius ([-0-9.e+]+) mm"
                         r"(?: to ([-0-9.e+]+) mm)?.*?, mass ([-0-9.e+]+) kg", body)
            if m:
                r0 = num(m.group(4)) * 1e-3
                info["rod"][m.group(1)] = {
                    "elements": int(m.group(2)), "length": num(m.group(3)), "radius": r0,
                    "radius_end": num(m.group(5)) * 1e-3 if m.group(5) else r0,
                    "mass": num(m.group(6))}
        elif section == "materials":
            m = re.match(r"(\S+): E ([-0-9.e+]+) Pa, G ([-0-9.e+]+) Pa, density ([-0-9.e+]+) kg/m\^3", body)
            if m:
                info["material"].setdefault(m.group(1), []).append(
                    {"E": num(m.group(2)), "G": num(m.group(3)), "density": num(m.group(4))})
        elif section == "joints":
            m = re.match(r"(\S+): (\w+), stiffness ([-0-9.e+]+) N/m", body)
            if m:
                info["joint"][m.group(1)] = {"kind": m.group(2), "stiffness": num(m.group(3))}
        elif section == "kinematic joints":
            m = re.match(r"(\S+): .*spring ([-0-9.e+]+)(?: to ([-0-9.e+]+))? N/m", body)
            if m:
                info["kjoint"][m.group(1)] = {"spring": num(m.group(2)),
                                              "spring_max": num(m.group(3) or m.group(2))}
        elif section == "muscles":
            m = re.match(r"(\S+): (\d+) filaments \(([-0-9.e+]+) to ([-0-9.e+]+) mm\^2, (\d+) fibres\)"
                         r"(?:, area ([-0-9.e+]+) mm\^2)?.*?(?:F_max|at most) ([-0-9.e+]+) N.*?l0 ([-0-9.e+]+) m"
                         r"(?:.*?Hill a ([-0-9.e+]+) F_qs, v_max ([-0-9.e+]+) l0/s)?", body)
            if m:
                info["muscle"][m.group(1)] = {
                    "filaments": int(m.group(2)), "area": num(m.group(6) or "nan") * 1e-6,
                    "F_max": num(m.group(7)), "l0": num(m.group(8)), "fibres": int(m.group(5))}
                if m.group(9):   # a Hill muscle (not a prescribed force)
                    info["muscle"][m.group(1)].update(hill_a=num(m.group(9)), v_max=num(m.group(10)))
        elif section == "environments":
            m = re.match(r"ground (\S+): \w+, stiffness ([-0-9.e+]+) N/m, damping ([-0-9.e+]+) kg/s, "
                         r"kinetic friction ([-0-9.e+]+)/([-0-9.e+]+)/([-0-9.e+]+) \(forward/backward/"
                         r"sideways\), static ([-0-9.e+]+)/([-0-9.e+]+)/([-0-9.e+]+)", body)
            if m:
                g = [num(m.group(i)) for i in range(2, 10)]
                info["ground"][m.group(1)] = dict(zip(
                    ("stiffness", "damping", "mu_k_forward", "mu_k_backward", "mu_k_sideways",
                     "mu_s_forward", "mu_s_backward", "mu_s_sideways"), g))
                continue
            m = re.match(r"contact (\S+): stiffness ([-0-9.e+]+) N/m, damping ([-0-9.e+]+) kg/s", body)
            if m:
                info["contact"][m.group(1)] = {"stiffness": num(m.group(2)), "damping": num(m.group(3))}
                continue
            m = re.match(r"fluid (\S+):", body)
            if m:
                last_fluid = m.group(1)
                info["fluid"][last_fluid] = {}
                continue
            m = re.match(r"area of its rods at rest: planform ([-0-9.e+]+) m\^2", body)
            if m and last_fluid:
                info["fluid"][last_fluid]["planform"] = num(m.group(1))
                continue
            m = re.match(r"torque wave (\S+): rod \S+, (\d+) coefficients \(peak beta ([-0-9.e+]+) N m\), "
                         r"wavelength ([-0-9.e+]+) m, period ([-0-9.e+]+) s", body)
            if m:
                info["wave"][m.group(1)] = {"coefficients": int(m.group(2)), "peak": num(m.group(3)),
                                            "wavelength": num(m.group(4)), "period": num(m.group(5))}
        elif section == "params":
            m = re.match(r"(\S+) = ([-0-9.e+]+)(?: ([^ (][^(]*?))?(?: in \(.*\))?(?: \(--set.*)?$", body)
            if m:
                info["param"][m.group(1)] = {"value": num(m.group(2)), "unit": (m.group(3) or "").strip()}
    return info


class Missing(Exception):
    pass


def accessors(info):
    def get(kind, name, field):
        try:
            v = info[kind][name]
        except KeyError:
            raise Missing("no %s '%s' in --info" % (kind, name))
        if isinstance(v, list):   # a material name may stand for several constants
            vals = {x[field] for x in v}
            if len(vals) != 1:
                raise Missing("material '%s' has %d different %s" % (name, len(vals), field))
            return vals.pop()
        if field not in v:
            raise Missing("%s '%s' has no %s in --info" % (kind, name, field))
        return v[field]

    def over(kind, pattern, field, f):
        """f (sum, min, max) of field over the entries whose name matches the regex"""
        found = [v[field] for k, v in info[kind].items() if re.fullmatch(pattern, k)]
        if not found:
            raise Missing("no %s matching '%s' in --info" % (kind, pattern))
        return f(found)

    def param(name):
        get("param", name, "value")   # raises when there is none
        q = info["param"][name]
        if q["unit"] not in UNITS:
            raise Missing("param '%s' is in '%s', a unit tables_check.py does not know" % (name, q["unit"]))
        return q["value"] * UNITS[q["unit"]]

    def scalar(key):
        if info[key] is None:
            raise Missing("no %s line in --info" % key)
        return info[key]

    return {
        "rod": lambda n, f: get("rod", n, f),
        "group": lambda n, f: get("group", n, f),
        "material": lambda n, f: get("material", n, f),
        "joint": lambda n, f="stiffness": get("joint", n, f),
        "kjoint": lambda n, f="spring": get("kjoint", n, f),
        "muscle": lambda n, f: get("muscle", n, f),
        "ground": lambda n, f: get("ground", n, f),
        "contact": lambda n, f: get("contact", n, f),
        "fluid": lambda n, f: get("fluid", n, f),
        "wave": lambda n, f: get("wave", n, f),
        "param": param,
        "total": lambda k, p, f: over(k, p, f, sum),
        "smallest": lambda k, p, f: over(k, p, f, min),
        "largest": lambda k, p, f: over(k, p, f, max),
        "dt": lambda: scalar("dt"),
        "duration": lambda: scalar("duration"),
        "pi": math.pi, "sqrt": math.sqrt, "sin": math.sin,
    }


def fmt(x, unit):
    return "%.6g %s" % (x / UNITS[unit], unit) if unit not in ("", "1") else "%.6g" % x


def header_comment(path):
    """The leading comment block of a .sinew file (its header)."""
    lines = []
    with open(path) as f:
        for line in f:
            if line.startswith("#") or not line.strip():
                lines.append(line.lstrip("#").strip())
            else:
                break
    return " ".join(" ".join(lines).split())


def main():
    tsv, info_dir, root = sys.argv[1:4]
    only = set(sys.argv[4:])
    infos = {}
    counts = {}
    failed = 0
    with open(tsv) as f:
        rows = [l.rstrip("\n").split("\t") for l in f if l.strip() and not l.startswith("#")]
    head, rows = rows[0], rows[1:]
    for n, cols in enumerate(rows, 2):
        if len(cols) != len(head):
            print("not ok - tables.tsv row %d has %d columns, not %d" % (n, len(cols), len(head)))
            failed += 1
            continue
        r = dict(zip(head, cols))
        scene, status, unit = r["scene"], r["status"], r["unit"]
        if only and scene not in only:
            continue
        if scene not in infos:
            path = os.path.join(info_dir, scene + ".info")
            infos[scene] = accessors(parse_info(open(path).read())) if os.path.exists(path) else None
        name = "%s, %s" % (r["table"], r["entry"])
        if infos[scene] is None:
            print("not ok - %s: scene %s did not compile" % (name, scene))
            failed += 1
            continue
        try:
            got = eval(r["reading"], {"__builtins__": {}}, infos[scene])
        except Missing as e:
            print("not ok - %s: %s (%s)" % (name, e, scene))
            failed += 1
            continue
        if unit not in UNITS:
            print("not ok - %s: unknown unit '%s' in tables.tsv" % (name, unit))
            failed += 1
            continue
        scale = UNITS[unit]

        def matches(value_text):
            if re.fullmatch(r"[0-9.]+-[0-9.]+", value_text):
                lo, hi = (float(x) * scale for x in value_text.split("-"))
                return lo <= got <= hi
            want = float(value_text) * scale
            tol = half_ulp(value_text) * scale if r["tolerance"] == "digits" \
                else float(r["tolerance"]) * scale
            # --info's own rounding: 6 digits, 4 for radii and a loop's rods
            four = "radius" in r["reading"] or '"group"' in r["reading"] or "group(" in r["reading"]
            tol += (5e-4 if four else 5e-7) * abs(want)
            return abs(got - want) <= tol

        shown = fmt(got, unit)
        if status == "check":
            counts[r["table"]] = counts.get(r["table"], 0) + 1
            if matches(r["table_value"]):
                print("ok - %s (%s): scene %s, table %s %s" % (name, scene, shown, r["table_value"], unit))
            else:
                print("not ok - %s: scene %s, table %s %s (%s; %s)" %
                      (name, shown, r["table_value"], unit, scene, r["reading"]))
                failed += 1
        elif status == "deviation":
            counts[r["table"] + " (deviations)"] = counts.get(r["table"] + " (deviations)", 0) + 1
            # '-': the scene's value is not recorded (a step the simulator
            # estimates); the deviation holds while it differs from the table
            good = not matches(r["table_value"]) if r["scene_value"] == "-" \
                else matches(r["scene_value"])
            print("%s - %s (%s): documented deviation: scene %s, table %s %s" %
                  ("ok" if good else "not ok", name, scene, shown, r["table_value"], unit))
            print("# deviation, %s: %s" % (name, r["note"]))
            if not good:
                print("# the record says the scene holds %s %s: update tables.tsv or the scene"
                      % (r["scene_value"] if r["scene_value"] != "-" else "a value unlike the table's",
                         unit))
                failed += 1
        elif status == "own":
            counts["sinew's own"] = counts.get("sinew's own", 0) + 1
            where = r["table"].split(":", 1)[1]
            marked = r["note"] in header_comment(os.path.join(root, where))
            good = matches(r["scene_value"])
            print("%s - sinew's own, %s (%s): %s, marked in %s's header" %
                  ("ok" if good and marked else "not ok", r["entry"], scene, shown, where))
            if not marked:
                print("# %s's header comment does not say '%s'" % (where, r["note"]))
            if not good:
                print("# the record says %s %s" % (r["scene_value"], unit))
            failed += not (good and marked)
        else:
            print("not ok - %s: unknown status '%s'" % (name, status))
            failed += 1
    print("# coverage: " + "; ".join("%s %d" % kv for kv in sorted(counts.items())))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
