#!/usr/bin/python3
"""Tabulate the patched reference code's wing diagnostics beside sinew's.

usage: oracle_table.py ORACLE_OUT.txt [SINEW_FIRST_MS.txt]

ORACLE_OUT.txt is the standard output of the reference's wing patched as in
PATCHES.md ("diag" lines every 0.1 ms, each followed by its five fastest
elements); SINEW_FIRST_MS.txt is sinew_first_ms.py's output for sinew's
wing over the same time.  Prints, every 0.1 ms: the code's kinetic energy,
its translational part, its muscles' share, its fastest element and |w|;
and sinew's kinetic energy, muscles' share and fastest |w|.
"""
import re
import sys


def oracle(path):
    rows = {}
    cur = None
    for line in open(path):
        m = re.match(r'diag t (\S+) ms step (\d+) KE (\S+) J \(trans (\S+) rot '
                     r'(\S+)\) bones (\S+) rachises (\S+) barbs (\S+) '
                     r'muscles (\S+)', line)
        if m:
            t = round(float(m.group(1)), 4)
            cur = rows.setdefault(t, {'ke': float(m.group(3)),
                                      'trans': float(m.group(4)),
                                      'muscles': float(m.group(9)),
                                      'bones': float(m.group(6)),
                                      'top': []})
            continue
        m = re.match(r'\s+top\d rod\s+(\d+) \((.*)\) elem (\d+)/\d+ \|w\| (\S+)',
                     line)
        if m and cur is not None:
            cur['top'].append((m.group(2), int(m.group(3)), float(m.group(4))))
    return rows


def sinew(path):
    rows = {}
    cur = None
    for line in open(path):
        m = re.match(r't (\S+) ms KE\(diag\) (\S+) J .* bones (\S+) .* muscles '
                     r'(\S+)', line)
        if m:
            cur = rows.setdefault(round(float(m.group(1)), 4),
                                  {'ke': float(m.group(2)),
                                   'bones': float(m.group(3)),
                                   'muscles': float(m.group(4)), 'w': None})
            continue
        m = re.match(r'\s+top1 (\S+) elem (\d+)/\d+ \|w\| (\S+)', line)
        if m and cur is not None:
            cur['w'] = (m.group(1), int(m.group(2)), float(m.group(3)))
    return rows


def main():
    o = oracle(sys.argv[1])
    s = sinew(sys.argv[2]) if len(sys.argv) > 2 else {}
    print('| t (ms) | code: KE (J) | its translational part | its muscles | its bones '
          '| its fastest element | \\|w\\| (rad/s) | sinew: KE (J) | its muscles '
          '| its bones | its largest \\|w\\| (rad/s) |')
    print('|' + '---|' * 11)
    for t in sorted(o):
        if t < 0.1 - 1e-9 or abs(t * 10 - round(t * 10)) > 1e-6:
            continue
        r = o[t]
        name, el, w = r['top'][0]
        q = s.get(round(t, 4))
        tail = (f"{q['ke']:.3g} | {q['muscles']:.3g} | {q['bones']:.3g} | "
                f"{q['w'][2]:.3g}") if q else ' | | | '
        print(f"| {t:.1f} | {r['ke']:.3g} | {r['trans']:.3g} | "
              f"{r['muscles']:.3g} | {r['bones']:.3g} | {name}, element {el} | "
              f"{w:.3g} | {tail} |")


if __name__ == '__main__':
    main()
