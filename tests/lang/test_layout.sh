#!/bin/sh
# test_layout.sh — the tree keeps the architecture docs/runtime.md maps:
#   - every runtime file lives in a room: include/ (the public header and its
#     parts), engine/, io/, study/, sim/; none is left at the top of runtime/,
#     and no two share a name (the archive's members are named by it);
#   - the arrows between rooms run one way, sim -> study -> io -> engine,
#     both in what a file includes (another room's header by its path,
#     "engine/internal.h") and in what its object file links to (every sw_*
#     symbol an object leaves undefined is defined in its own room or one
#     below it; nm on build/rt/ROOM/*.o, which make check builds);
#   - the engine and the simulator's command line touch no file format:
#     hdf5.h is included in io/ and in study/study_file.c (a study's file)
#     only, mpi.h in study/study_mpi.c only;
#   - no source file of runtime/, compiler/ or lang/ is over 800 lines;
#   - docs/runtime.md's map names every file of every room, and nothing in the
#     repository cites a document that is not in it (SPEC.md).
. "$(dirname "$0")/tap.sh"
cd "$ROOT" || exit 1
scratch layout

# ---- files in rooms
stray=$(find runtime -maxdepth 1 -type f | sort)
[ -z "$stray" ]; ok $? "no file at the top of runtime/ (each is in a room)"
[ -n "$stray" ] && echo "$stray" | diag
unknown=$(find runtime -mindepth 1 -maxdepth 1 -type d | sed 's|runtime/||' |
          grep -vx -e include -e engine -e io -e study -e sim)
[ -z "$unknown" ]; ok $? "runtime/ holds the rooms include, engine, io, study, sim and no other"
[ -n "$unknown" ] && echo "$unknown" | diag

# the library is one archive, whose members are named by file name alone
dup=$(ls runtime/*/*.c | xargs -n1 basename | sort | uniq -d)
[ -z "$dup" ]; ok $? "no two runtime files share a name (libsinewrt.a's members would clash)"
[ -n "$dup" ] && echo "$dup" | diag

# ---- the arrows, in the includes and in the objects
/usr/bin/python3 - "$TMP" <<'EOF'
import glob, os, re, subprocess, sys
tmp = sys.argv[1]
level = {'engine': 0, 'io': 1, 'study': 2, 'sim': 3}
bad_inc, bad_hdr = [], []
for path in sorted(glob.glob('runtime/*/*.[ch]')):
    room = path.split('/')[1]
    if room == 'include':
        continue
    for n, line in enumerate(open(path), 1):
        m = re.match(r'\s*#\s*include\s*"([^"]+)"', line)
        if m:
            inc = m.group(1)
            other = inc.split('/')[0] if '/' in inc else room
            if other in level and level[other] > level[room]:
                bad_inc.append(f'{path}:{n}: {room}/ includes "{inc}" of {other}/, a room above it')
        m = re.match(r'\s*#\s*include\s*<(hdf5|mpi)\.h>', line)
        if m:
            lib = m.group(1)
            if (lib == 'hdf5' and room != 'io' and path != 'runtime/study/study_file.c') or (lib == 'mpi' and path != 'runtime/study/study_mpi.c'):
                bad_hdr.append(f'{path}:{n}: includes <{lib}.h>')
open(f'{tmp}/inc', 'w').write('\n'.join(bad_inc))
open(f'{tmp}/hdr', 'w').write('\n'.join(bad_hdr))

objs = {}
for room in level:
    for o in sorted(glob.glob(f'build/rt/{room}/*.o')):
        objs[o] = room
if os.path.exists('build/sinewrt_mpi.o'):
    objs['build/sinewrt_mpi.o'] = 'study'
def nm(o, flag):
    out = subprocess.run(['nm', flag, o], capture_output=True, text=True, check=True).stdout
    return [l.split()[-1] for l in out.splitlines() if l.split() and l.split()[-1].startswith('sw_')]
defined = {}
for o, room in objs.items():
    for s in nm(o, '--defined-only'):
        defined.setdefault(s, room)
bad_sym = []
for o, room in objs.items():
    for s in sorted(set(nm(o, '--undefined-only'))):
        other = defined.get(s)
        if other and level[other] > level[room]:
            bad_sym.append(f'{o} ({room}/) uses {s} of {other}/, a room above it')
with open(f'{tmp}/sym', 'w') as f:
    f.write(f'{len(objs)}\n' + '\n'.join(bad_sym))
EOF
[ -s "$TMP/inc" ]; [ $? -ne 0 ]; ok $? "includes run one way: sim -> study -> io -> engine"
diag <"$TMP/inc"
[ -s "$TMP/hdr" ]; [ $? -ne 0 ]; ok $? "hdf5.h only in io/ and study/study_file.c, mpi.h only in study/study_mpi.c"
diag <"$TMP/hdr"
nobj=$(head -1 "$TMP/sym")
[ "$nobj" -gt 30 ]; ok $? "the rooms' objects are built (build/rt/ROOM/*.o: $nobj)"
tail -n +2 "$TMP/sym" >"$TMP/sym.bad"
[ -s "$TMP/sym.bad" ]; [ $? -ne 0 ]; ok $? "links run one way: no object uses a symbol of a room above its own"
diag <"$TMP/sym.bad"

# ---- file size
long=$(wc -l runtime/*/*.[ch] compiler/*.[ch] lang/*.[ly] | awk '$2 != "total" && $1 > 800 { print $2 ": " $1 " lines" }')
[ -z "$long" ]; ok $? "no source file of runtime/, compiler/, lang/ is over 800 lines"
[ -n "$long" ] && echo "$long" | diag
echo "longest: $(wc -l runtime/*/*.[ch] compiler/*.[ch] lang/*.[ly] | grep -v ' total$' | sort -n | tail -1)" | diag

# ---- the map and the citations
missing=""
for f in runtime/*/*.[ch]; do
  grep -qF "\`$(basename "$f")\`" docs/runtime.md || missing="$missing $f"
done
[ -z "$missing" ]; ok $? "docs/runtime.md names every file of every room"
[ -n "$missing" ] && echo "not named:$missing" | diag
cites=$(git grep -n 'SPEC\.md' -- . ':!tests/lang/test_layout.sh' 2>/dev/null)
[ -z "$cites" ]; ok $? "nothing in the repository cites SPEC.md, which is not in it"
[ -n "$cites" ] && echo "$cites" | diag
done_testing
