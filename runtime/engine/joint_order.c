/* joint_order.c — the order of a group's members in the joints' system.
 *
 * Design.  rigid_joint.c factors each group's block by Cholesky within its
 * envelope: row i of member s holds entries from the first unknown of the
 * earliest member joined to s, and the factor has no entries outside that
 * envelope (George and Liu, Computer Solution of Large Sparse Positive
 * Definite Systems, 1981, ch. 4).  Its right-looking factorisation takes
 * L(i, j) L(k, j) off A(i, k) for every j < k <= i inside the envelope, so
 * its work is
 *   W = sum_j sum_{i > j, first(i) <= j} (i - j)          (multiply-adds),
 * and depends on the members' order.  The order the joints first meet the
 * members (how setup numbers them) suits a chain, whose joints are met in
 * turn, but not a ring: the muscular snake's pair group (issue 31), a rib,
 * two tendons, two filaments' ends and the other rib and its tendons, closed
 * by the filaments' Hill damping, with the two backbone nodes hanging from
 * the ribs, costs 9773 multiply-adds in that order and 3455 in the one
 * chosen here.  The member graph's vertices are the members, its edges the
 * couplings the envelope takes (rigid_joint.c: implicit joints, a dense
 * filament's damper, a leaf pair's two ports).  Its candidates are the
 * order setup met, and the Cuthill-McKee order (breadth first, each
 * member's unvisited neighbours by increasing degree: Cuthill and McKee,
 * Proc. 24th ACM National Conference, 1969) from each member, and each of
 * those reversed (George and Liu, sec. 4.3); W is counted for each and the
 * cheapest kept, the met order on a tie, so a chain keeps its numbering and
 * its bits.  Groups of more than MANY_STARTS members start only from the two
 * ends of a longest breadth-first path (a pseudo-peripheral pair, George
 * and Liu, sec. 4.3.2).  All of it runs once, at setup.
 */
#include <stdlib.h>
#include <string.h>
#include "sinew.h"
#include "internal.h"

#define MANY_STARTS 48

/* W of the members mem[0 .. cnt) in that order (the header).  Scratch: pos
 * (nb ints, -1 on entry and on return), offs (cnt + 1 ints) and first (a
 * group's unknowns). */
static double envelope_work(int cnt, const int *mem, const int *dof, const int *adr, const int *adj,
                            int *pos, int *offs, int *first) {
  offs[0] = 0;
  for (int t = 0; t < cnt; t++) pos[mem[t]] = t, offs[t + 1] = offs[t] + dof[mem[t]];
  for (int t = 0; t < cnt; t++) { /* each row's first column: member e's first unknown */
    const int s = mem[t];
    int e = t; /* the earliest member joined to s */
    for (int q = adr[s]; q < adr[s + 1]; q++)
      if (pos[adj[q]] >= 0 && pos[adj[q]] < e) e = pos[adj[q]];
    for (int i = offs[t]; i < offs[t + 1]; i++) first[i] = offs[e];
  }
  double w = 0;
  for (int i = 0; i < offs[cnt]; i++) {
    const double reach = (double)(i - first[i]);
    w += 0.5 * reach * (reach + 1);
  }
  for (int t = 0; t < cnt; t++) pos[mem[t]] = -1;
  return w;
}

/* The Cuthill-McKee order of the group's members from `start` into out[]
 * (cnt members; a member not reached continues from the earliest unvisited
 * one in met order).  seen: nb ints, -1 on entry and on return. */
static void cuthill_mckee(int cnt, const int *mem, int start, const int *adr, const int *adj,
                          const int *in_group, int *seen, int *out) {
  int head = 0, tail = 0, next_unvisited = 0;
  out[tail++] = start, seen[start] = 1;
  while (tail < cnt) {
    if (head == tail) { /* another component of the group's dense members */
      while (seen[mem[next_unvisited]] >= 0) next_unvisited++;
      out[tail++] = mem[next_unvisited], seen[mem[next_unvisited]] = 1;
    }
    const int s = out[head++], from = tail;
    for (int q = adr[s]; q < adr[s + 1]; q++) {
      const int t = adj[q];
      if (!in_group[t] || seen[t] >= 0) continue;
      seen[t] = 1, out[tail++] = t;
    }
    for (int a = from + 1; a < tail; a++) { /* by degree, then by met order */
      const int t = out[a], dt = adr[t + 1] - adr[t];
      int b = a;
      while (b > from && (adr[out[b - 1] + 1] - adr[out[b - 1]] > dt ||
                          (adr[out[b - 1] + 1] - adr[out[b - 1]] == dt && out[b - 1] > t)))
        out[b] = out[b - 1], b--;
      out[b] = t;
    }
  }
  for (int t = 0; t < cnt; t++) seen[out[t]] = -1;
}

/* The last member of a breadth-first walk from start (a farthest one). */
static int farthest(int cnt, const int *mem, int start, const int *adr, const int *adj,
                    const int *in_group, int *seen, int *out) {
  cuthill_mckee(cnt, mem, start, adr, adj, in_group, seen, out);
  return out[cnt - 1];
}

int sw_order_members(int nb, const int *group, int ngroup, const int *dof, int nedge,
                     const int *edges, int *order) {
  const size_t N = (size_t)(nb > 0 ? nb : 1), E = (size_t)(nedge > 0 ? nedge : 1);
  int *adr = calloc(N + 1, sizeof(int)), *adj = malloc(2 * E * sizeof(int));
  int *pos = malloc(N * sizeof(int)), *seen = malloc(N * sizeof(int));
  int *in_group = calloc(N, sizeof(int)), *cand = malloc(N * sizeof(int));
  int *mem = malloc(N * sizeof(int)), *offs = malloc((N + 1) * sizeof(int));
  int *gadr = calloc((size_t)ngroup + 2, sizeof(int));
  int n_unknowns = 0;
  for (int s = 0; s < nb; s++)
    if (group[s] >= 0) n_unknowns += dof[s];
  int *first = malloc((size_t)(n_unknowns > 0 ? n_unknowns : 1) * sizeof(int));
  int ok = adr && adj && pos && seen && in_group && cand && mem && offs && gadr && first;
  if (ok) {
    for (int q = 0; q < nedge; q++) adr[edges[2 * q] + 1]++, adr[edges[2 * q + 1] + 1]++;
    for (int s = 0; s < nb; s++) adr[s + 1] += adr[s];
    memcpy(pos, adr, N * sizeof(int)); /* a cursor per member */
    for (int q = 0; q < nedge; q++) {
      const int a = edges[2 * q], b = edges[2 * q + 1];
      adj[pos[a]++] = b, adj[pos[b]++] = a;
    }
    for (int s = 0; s < nb; s++) pos[s] = seen[s] = -1;
    for (int s = 0; s < nb; s++) /* the groups' members, each in met order */
      if (group[s] >= 0) gadr[group[s] + 1]++;
    for (int g = 0; g < ngroup; g++) gadr[g + 1] += gadr[g];
    memcpy(cand, gadr, (size_t)ngroup * sizeof(int));
    for (int s = 0; s < nb; s++)
      if (group[s] >= 0) mem[cand[group[s]]++] = s;
    memcpy(order, mem, (size_t)gadr[ngroup] * sizeof(int));
  }
  for (int g = 0; ok && g < ngroup; g++) {
    const int cnt = gadr[g + 1] - gadr[g];
    const int *gm = mem + gadr[g];
    int *best = order + gadr[g];
    if (cnt < 3) continue; /* one or two members: no choice */
    for (int t = 0; t < cnt; t++) in_group[gm[t]] = 1;
    double wbest = envelope_work(cnt, best, dof, adr, adj, pos, offs, first);
    int starts[2] = {-1, -1}, nstart = cnt;
    if (cnt > MANY_STARTS) { /* a pseudo-peripheral pair */
      starts[0] = farthest(cnt, gm, gm[0], adr, adj, in_group, seen, cand);
      starts[1] = farthest(cnt, gm, starts[0], adr, adj, in_group, seen, cand);
      nstart = 2;
    }
    for (int k = 0; k < nstart; k++) {
      const int start = cnt > MANY_STARTS ? starts[k] : gm[k];
      cuthill_mckee(cnt, gm, start, adr, adj, in_group, seen, cand);
      for (int rev = 0; rev < 2; rev++) {
        if (rev) /* the reversed order */
          for (int a = 0, b = cnt - 1; a < b; a++, b--) {
            const int t = cand[a];
            cand[a] = cand[b], cand[b] = t;
          }
        const double w = envelope_work(cnt, cand, dof, adr, adj, pos, offs, first);
        if (w < wbest) wbest = w, memcpy(best, cand, (size_t)cnt * sizeof(int));
      }
    }
    for (int t = 0; t < cnt; t++) in_group[gm[t]] = 0;
  }
  free(adr), free(adj), free(pos), free(seen), free(in_group), free(cand);
  free(mem), free(offs), free(gadr);
  free(first);
  return ok;
}
