# bench_base.sh — sourced by the benchmarks that run a tree of an earlier
# commit beside this one (bench_speedup.sh, bench_rigid_groups.sh,
# bench_snake_eval.sh, bench_wing_resolved.sh, bench_wing_threads.sh), and bench_wing_floor.sh for bench_steps.
# bench_base DIR REV: DIR holds a git worktree of REV with its bin/sinewc and
# runtime built by its own Makefile (once: kept while DIR/bin/sinewc exists).
bench_base() {
  if [ ! -x "$1/bin/sinewc" ]; then
    rm -rf "$1"
    git worktree prune
    git worktree add --detach "$1" "$2" >/dev/null 2>&1
    make -C "$1" --no-print-directory bin/sinewc build/libsinewrt.a >/dev/null
  fi
}

# bench_old_tree REV (after cd to $root, the repository's root): $tree, a
# worktree of REV built as bench_base builds it, and $tmp, a scratch
# directory removed when the script exits.
bench_old_tree() {
  tmp=$(mktemp -d)
  trap 'rm -rf "$tmp"' EXIT
  tree=$root/build/bench/base-$1
  bench_base "$tree" "$1"
}

# bench_steps BIN DURATION: the steps of DURATION (e.g. 5ms) at BIN's step
# (its --info "dt:" line).
bench_steps() {
  "$1" --info 2>/dev/null | awk -v d="$2" '
    function sec(v, u) { return v * (u == "ns" ? 1e-9 : u == "us" ? 1e-6 : u == "ms" ? 1e-3 : 1) }
    /^dt:/ { dt = sec($2, $3) }
    END { u = d; sub(/^[0-9.]+/, "", u); printf "%d", sec(d + 0, u) / dt + 0.5 }'
}
