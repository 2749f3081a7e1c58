/* test_joint_order.c — the order of a group's members in the joints'
 * system (joint_order.c): the envelope Cholesky's work W of the order it
 * picks, counted here independently (each row's first column, then
 * sum over rows of (i - first) (i - first + 1) / 2), against the order the
 * members were met in and against the least W over every order of a small
 * group (brute force).
 *
 * Scenes: a chain (its met order is already the best, and is kept, so a
 * chain's bits do not move); a star whose met order puts its hub last; the
 * muscular snake's pair group as setup meets it (the member graph of
 * examples/study/snake_pairs4.sinew read off its model: a ring of a rib,
 * two tendons, two filaments' ends and the other rib's tendons, closed by
 * the filaments' dampers, with the two backbone nodes hanging from the
 * ribs), and two groups side by side, which must be ordered apart. */
#include "testutil.h"
#include "internal.h"

/* W of the members order[0 .. cnt) (the header), edges as pairs. */
static double work(int cnt, const int *order, const int *dof, int ne, const int *edges) {
  int pos[64], off[65];
  for (int t = 0; t < cnt; t++) pos[order[t]] = t;
  off[0] = 0;
  for (int t = 0; t < cnt; t++) off[t + 1] = off[t] + dof[order[t]];
  double w = 0;
  for (int t = 0; t < cnt; t++) {
    int e = t;
    for (int q = 0; q < ne; q++) {
      const int a = edges[2 * q], b = edges[2 * q + 1];
      if (a == order[t] && pos[b] < e) e = pos[b];
      if (b == order[t] && pos[a] < e) e = pos[a];
    }
    for (int i = off[t]; i < off[t + 1]; i++) w += 0.5 * (i - off[e]) * (i - off[e] + 1.0);
  }
  return w;
}

/* The least W over every order of members 0 .. cnt - 1 (Heap's algorithm). */
static double least_work(int cnt, const int *dof, int ne, const int *edges) {
  int a[16], c[16] = {0};
  for (int i = 0; i < cnt; i++) a[i] = i;
  double best = work(cnt, a, dof, ne, edges);
  for (int i = 1; i < cnt;) {
    if (c[i] < i) {
      const int k = i % 2 ? c[i] : 0, t = a[k];
      a[k] = a[i], a[i] = t;
      const double w = work(cnt, a, dof, ne, edges);
      if (w < best) best = w;
      c[i]++, i = 1;
    } else {
      c[i++] = 0;
    }
  }
  return best;
}

/* Orders one group of cnt members; checks the result is a permutation. */
static double ordered(int cnt, const int *dof, int ne, const int *edges, int *order) {
  int group[64] = {0};
  for (int s = 0; s < cnt; s++) group[s] = 0;
  assert_int_equal(sw_order_members(cnt, group, 1, dof, ne, edges, order), 1);
  int seen[64] = {0};
  for (int t = 0; t < cnt; t++) {
    assert_true(order[t] >= 0 && order[t] < cnt);
    assert_int_equal(seen[order[t]]++, 0);
  }
  return work(cnt, order, dof, ne, edges);
}

static void test_chain_kept(void **state) {
  (void)state;
  const int dof[6] = {6, 6, 6, 6, 6, 6}, edges[10] = {0, 1, 1, 2, 2, 3, 3, 4, 4, 5};
  int order[6], met[6] = {0, 1, 2, 3, 4, 5};
  const double w = ordered(6, dof, 5, edges, order);
  fprintf(stderr, "# %s: W = %.0f, met %.0f, least %.0f\n", __func__, w,
          work(6, met, dof, 5, edges), least_work(6, dof, 5, edges));
  for (int t = 0; t < 6; t++) assert_int_equal(order[t], t); /* a tie keeps the met order */
  assert_true(w == least_work(6, dof, 5, edges));
}

static void test_star(void **state) {
  (void)state;
  /* four bodies on a hub met last, and a node on the first */
  const int dof[6] = {6, 6, 6, 6, 6, 3}, edges[10] = {0, 4, 1, 4, 2, 4, 3, 4, 0, 5};
  int order[6], met[6] = {0, 1, 2, 3, 4, 5};
  const double w = ordered(6, dof, 5, edges, order), w0 = work(6, met, dof, 5, edges);
  const double least = least_work(6, dof, 5, edges);
  fprintf(stderr, "# %s: W = %.0f, met order %.0f, least over all 720 orders %.0f\n", __func__, w,
          w0, least);
  assert_true(w < w0);
  assert_true(w == least);
}

/* The muscular snake's pair group, members as setup met them (dof: a
 * filament's end node 3, a tendon or rib 6, a backbone node and its
 * element 6): ends 0-2 and 4-6 of the two filaments (their dampers), the
 * tendons 1, 3, 5, 7 on them, ribs 8 and 10 on the tendons, backbone
 * nodes 9 and 11 on the ribs. */
static const int pair_dof[12] = {3, 6, 3, 6, 3, 6, 3, 6, 6, 6, 6, 6};
static const int pair_edges[24] = {0, 2, 0, 1, 2, 3, 4, 6, 4, 5, 6, 7,
                                   8, 1, 8, 5, 10, 3, 10, 7, 9, 8, 11, 10};

static void test_snake_pair(void **state) {
  (void)state;
  int order[12], met[12];
  for (int t = 0; t < 12; t++) met[t] = t;
  const double w = ordered(12, pair_dof, 12, pair_edges, order);
  const double w0 = work(12, met, pair_dof, 12, pair_edges);
  fprintf(stderr, "# %s: W = %.0f multiply-adds against %.0f in the met order (%.2f x); order", __func__,
          w, w0, w0 / w);
  for (int t = 0; t < 12; t++) fprintf(stderr, " %d", order[t]);
  fprintf(stderr, "\n");
  assert_true(w0 == 9773); /* the figure in joint_order.c's header */
  assert_true(w == 3455);
  /* no rotation of the ring nor a mirror does better: each starting
   * member, both directions, as the ring's own orders */
  static const int ring[10] = {8, 1, 0, 2, 3, 10, 7, 6, 4, 5};
  double ring_best = 1e300;
  for (int s = 0; s < 10; s++)
    for (int dir = -1; dir <= 1; dir += 2) {
      int o[12], n = 0; /* around the ring, each rib's backbone node after it */
      for (int k = 0; k < 10; k++) {
        const int mem = ring[((s + dir * k) % 10 + 10) % 10];
        o[n++] = mem;
        if (mem == 8) o[n++] = 9;
        if (mem == 10) o[n++] = 11;
      }
      const double wr = work(12, o, pair_dof, 12, pair_edges);
      if (wr < ring_best) ring_best = wr;
    }
  fprintf(stderr, "# %s: the best order walking around the ring: W = %.0f\n", __func__, ring_best);
  assert_true(w < ring_best);
}

/* Two groups: each ordered within itself, the groups in their order. */
static void test_two_groups(void **state) {
  (void)state;
  int dof[24], group[24], edges[48], order[24];
  for (int s = 0; s < 24; s++) dof[s] = pair_dof[s % 12], group[s] = s < 12 ? 1 : 0;
  for (int q = 0; q < 24; q++) edges[q] = pair_edges[q], edges[24 + q] = pair_edges[q] + 12;
  assert_int_equal(sw_order_members(24, group, 2, dof, 24, edges, order), 1);
  int first[12], second[12];
  for (int t = 0; t < 12; t++) first[t] = order[t] - 12, second[t] = order[12 + t];
  const double w0 = work(12, first, pair_dof, 12, pair_edges), w1 = work(12, second, pair_dof, 12, pair_edges);
  fprintf(stderr, "# %s: group 0 (members 12-23) W = %.0f, group 1 (0-11) W = %.0f\n", __func__, w0, w1);
  for (int t = 0; t < 12; t++) assert_true(order[t] >= 12 && order[12 + t] < 12);
  assert_true(w0 == 3455 && w1 == 3455);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_chain_kept),
      cmocka_unit_test(test_star),
      cmocka_unit_test(test_snake_pair),
      cmocka_unit_test(test_two_groups),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
