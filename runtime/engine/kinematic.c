/* kinematic.c — kinematic joints: an element's frame imposed from another
 * rod's, and penalty loads exchanged, with no couple fed back.
 *
 * Design.  Zhang et al. 2019 (Suppl. Note 5.3) tie the wing's feathers this
 * way: the rachis' first element moves with the bone's element it grows
 * from, each barb's first element with the rachis' element it grows from,
 * and only forces travel back.  Their fast rotational modes (a 1 mm rachis
 * on a bone, ~1e-10 s explicit step) are thereby removed from the scene.
 * Here, after every kick (sw_kinematic_follow) the follower element's
 * angular velocity (material frame) is set to its leader's,
 *   w_f = R w_l,  R = Q_f(0) Q_l(0)^T,
 * so that the drift turns both nearly alike (to O((h w)^2): each element
 * turns by its own stretch and splits its turn about its own d3,
 * integrate.c), and before every load evaluation (sw_kinematic_impose) the
 * frame is set again,
 *   Q_f = R Q_l   (with w_f = R w_l),
 * which undoes that and the round-off, and holds for a rigid leader, whose
 * turn rigid.c updates in the drift.  Then
 * (sw_kinematic_loads) its node is tied to the leader's point p by
 *   F = k (p - x_f) + c (v_p - v_f),  p = x_e + xi (x_{e+1} - x_e),
 * F on the follower node, -F on the leader's two nodes ((1 - xi) and xi),
 * or -w F on a third node (swKinematicDesc.reaction_*: the reference lumps
 * each barb's reaction, weighted by w decaying linearly from the rachis'
 * base to its tip, onto the bone at the rachis' base).
 *
 * Energy.  Imposing a frame is not a force: it changes the follower
 * element's turning kinetic energy w.(J/e)w/2, its shear energy
 * l^ (s - s0).S^(s - s0)/2 and the bending energy of its two domains
 * D^ (k - k0).B^(k - k0)/2 at once.  That change is added to d->work, as
 * the work the imposed motion did (the elastic part of a drift-sized
 * correction to first order, from the couple the rod pass computes after
 * it: sw_kinematic_book), and every load here goes into
 * d->ext_force too (its work booked by the kick like any external load's),
 * so kinetic + elastic - work stays constant up to the integrator's error
 * (tests/runtime/test_kinematic.c).  The joint's spring has no energy of
 * its own for the same reason: its work is booked.
 *
 * Threads: every thread of the team enters each pass.  The impositions
 * and the follows run level by level (order_levels), each level's joints
 * split between the threads, a barrier after each; the ties' forces are
 * split likewise, and each thread adds them to the nodes it owns.  Each
 * joint's work goes to d->kinematic_work and the leader books the sum in
 * level order, so the bits do not depend on the team.  No allocation.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "sinew.h"
#include "vec.h"
#include "internal.h"
#include "model.h"

void sw_kinematic_desc_init(swKinematicDesc *k) {
  memset(k, 0, sizeof *k);
  k->name = "kinematic";
  k->reaction_rod = k->reaction_node = -1;
  k->reaction_weight = 1.0;
}

int sw_spec_add_kinematic(swSpec *s, const swKinematicDesc *k) {
  if (s->nkin == s->capkin) {
    int nc = s->capkin ? 2 * s->capkin : 8;
    swKinematicDesc *p = realloc(s->kin, (size_t)nc * sizeof *p);
    if (!p) return -1;
    s->kin = p;
    char **q = realloc(s->kin_name, (size_t)nc * sizeof *q);
    if (!q) return -1;
    s->kin_name = q;
    s->capkin = nc;
  }
  char *name = strdup(k->name ? k->name : "kinematic");
  if (!name) return -1;
  const int id = s->nkin++;
  s->kin[id] = *k;
  s->kin[id].name = s->kin_name[id] = name;
  return id;
}

void sw_kinematic_spec_free(swSpec *s) {
  for (int k = 0; k < s->nkin; k++) free(s->kin_name[k]);
  free(s->kin);
  free(s->kin_name);
}

/* node or element -1: the rod's last */
static int last_if(int i, int last) { return i < 0 ? last : i; }

/* The joints' followers as (rod, element) keys sorted with their joint's
 * index (sw_kinematic_check), so that the joint turning a given element is
 * found by bisection: the check was quadratic in the joints (6 to 10 ms of
 * the wing's 3163, a hundred times that at ten times as many). */
typedef struct { int rod, elem, joint; } followerKey;

static int key_cmp(const void *pa, const void *pb) {
  const followerKey *a = pa, *b = pb;
  if (a->rod != b->rod) return a->rod < b->rod ? -1 : 1;
  if (a->elem != b->elem) return a->elem < b->elem ? -1 : 1;
  return (a->joint > b->joint) - (a->joint < b->joint);
}

/* The first (lowest) joint turning element `elem` of rod `rod`, or -1. */
static int joint_turning(const followerKey *keys, int n, int rod, int elem) {
  int lo = 0, hi = n; /* the first key not below (rod, elem) */
  while (lo < hi) {
    const int mid = lo + (hi - lo) / 2;
    if (keys[mid].rod < rod || (keys[mid].rod == rod && keys[mid].elem < elem)) lo = mid + 1;
    else hi = mid;
  }
  return lo < n && keys[lo].rod == rod && keys[lo].elem == elem ? keys[lo].joint : -1;
}

/* The joint whose follower element is joint j's leader element, or -1. */
static int leading_joint(const swSpec *s, const followerKey *keys, int j) {
  const swKinematicDesc *k = &s->kin[j];
  return joint_turning(keys, s->nkin, k->leader_rod, last_if(k->leader_elem, s->rod[k->leader_rod].nelem - 1));
}

static int check_joints(const swSpec *s, followerKey *keys, char *err, size_t errlen) {
  for (int j = 0; j < s->nkin; j++) { /* a follower rod that does not exist: a key of its own */
    const swKinematicDesc *k = &s->kin[j];
    const int valid = k->follower_rod >= 0 && k->follower_rod < s->nrod;
    keys[j] = (followerKey){valid ? k->follower_rod : -1,
                            valid ? last_if(k->follower_elem, s->rod[k->follower_rod].nelem - 1) : j, j};
  }
  qsort(keys, (size_t)s->nkin, sizeof *keys, key_cmp);
  for (int j = 0; j < s->nkin; j++) {
    const swKinematicDesc *k = &s->kin[j];
    const char *nm = k->name;
    const int rods[3] = {k->leader_rod, k->follower_rod, k->reaction_rod};
    for (int i = 0; i < 3; i++)
      if (rods[i] >= s->nrod || (i < 2 && rods[i] < 0))
        return sw_fail(err, errlen, "kinematic joint '%s': rod %d does not exist (the scene has "
                       "%d)", nm, rods[i], s->nrod);
    const int nl = s->rod[k->leader_rod].nelem, nf = s->rod[k->follower_rod].nelem;
    const int le = last_if(k->leader_elem, nl - 1), fe = last_if(k->follower_elem, nf - 1);
    const int fn = last_if(k->follower_node, nf);
    if (le < 0 || le >= nl || fe < 0 || fe >= nf || fn < 0 || fn > nf)
      return sw_fail(err, errlen, "kinematic joint '%s': an element or node is off its rod", nm);
    if (k->leader_rod == k->follower_rod)
      return sw_fail(err, errlen, "kinematic joint '%s': a rod cannot lead itself", nm);
    if (!(k->leader_xi >= 0 && k->leader_xi <= 1))
      return sw_fail(err, errlen, "kinematic joint '%s': the point on the leader's element must "
                     "be at 0..1 along it, got %g", nm, k->leader_xi);
    if (!sw_finite_pos(k->stiffness) || !(k->damping >= 0) || !isfinite(k->damping))
      return sw_fail(err, errlen, "kinematic joint '%s': stiffness must be > 0 and damping >= 0",
                     nm);
    if (!isfinite(k->reaction_weight))
      return sw_fail(err, errlen, "kinematic joint '%s': the reaction's weight is not finite", nm);
    if (k->reaction_rod >= 0 &&
        (last_if(k->reaction_node, s->rod[k->reaction_rod].nelem) < 0 ||
         last_if(k->reaction_node, s->rod[k->reaction_rod].nelem) > s->rod[k->reaction_rod].nelem))
      return sw_fail(err, errlen, "kinematic joint '%s': the reaction's node is off its rod", nm);
    if (s->rod[k->follower_rod].rigid || s->rod[k->follower_rod].implicit)
      return sw_fail(err, errlen, "kinematic joint '%s': the follower '%s' must be an elastic, "
                     "explicit rod (its frame is imposed)", nm, s->rod_name[k->follower_rod]);
    const int first = joint_turning(keys, s->nkin, k->follower_rod, fe); /* the lowest to turn it */
    if (first < j)
      return sw_fail(err, errlen, "kinematic joints '%s' and '%s' both turn element %d of '%s'",
                     s->kin[first].name, nm, fe, s->rod_name[k->follower_rod]);
  }
  /* a chain of leaders that comes back to its start has no frame to take */
  for (int j = 0; j < s->nkin; j++) {
    int at = j;
    for (int step = 0; step <= s->nkin; step++) {
      const int up = leading_joint(s, keys, at);
      if (up < 0) break;
      if (up == j)
        return sw_fail(err, errlen, "kinematic joint '%s' leads itself through a chain of kinematic "
                       "joints (a follower's frame must come from outside the chain)", s->kin[j].name);
      at = up;
    }
  }
  return 1;
}

int sw_kinematic_check(const swSpec *s, char *err, size_t errlen) {
  followerKey *keys = malloc((size_t)(s->nkin ? s->nkin : 1) * sizeof *keys);
  if (!keys) return sw_fail(err, errlen, "out of memory checking %d kinematic joints", s->nkin);
  const int ok = check_joints(s, keys, err, errlen);
  free(keys);
  return ok;
}

/* The joints level by level (m->kinematic_order).  Imposing joint j's frame
 * reads its leader's frame and turn, which a joint of a lower level may
 * impose, and a correction booked whole (frame_energy) reads the frames of
 * the follower's neighbours in its rod, which a joint earlier in the spec
 * may impose (followers side by side).  So j's level is one more than that
 * of the joint imposing its leader and of an earlier joint imposing a
 * neighbour: every joint reads its leader as imposed in this pass, whatever
 * the order of the declarations, and its neighbours as in spec order; and
 * within a level none reads what another writes, so a level's joints may be
 * split between threads.  The levels are found by relaxation; the chains
 * are acyclic (sw_kinematic_check), so it ends within nkinematic + 1
 * passes.  0: out of memory. */
static int order_levels(swModel *m) {
  const int n = m->nkinematic, S = m->stride;
  int *by_elem = malloc((size_t)S * sizeof *by_elem), *level = calloc((size_t)(n ? n : 1), sizeof *level);
  m->kinematic_order = malloc((size_t)(n ? n : 1) * sizeof *m->kinematic_order);
  if (!by_elem || !level || !m->kinematic_order) {
    free(by_elem), free(level);
    return 0;
  }
  for (int i = 0; i < S; i++) by_elem[i] = -1;
  for (int j = 0; j < n; j++) by_elem[m->kinematic[j].follower_elem] = j;
  int top = 0, changed = 1;
  for (int pass = 0; changed && pass <= n; pass++) {
    changed = 0;
    for (int j = 0; j < n; j++) {
      const int fe = m->kinematic[j].follower_elem, lead = by_elem[m->kinematic[j].leader_elem];
      int L = lead >= 0 ? level[lead] + 1 : 0;
      for (int e = fe - 1; e <= fe + 1; e += 2) { /* past a rod's end lies a ghost, no follower */
        const int i = e >= 0 && e < S ? by_elem[e] : -1;
        if (i >= 0 && i < j && level[i] + 1 > L) L = level[i] + 1;
      }
      if (L != level[j]) level[j] = L, changed = 1;
      if (L > top) top = L;
    }
  }
  m->nkinematic_level = n ? top + 1 : 0;
  m->kinematic_level = calloc((size_t)m->nkinematic_level + 1, sizeof *m->kinematic_level);
  if (!m->kinematic_level) {
    free(by_elem), free(level);
    return 0;
  }
  for (int j = 0; j < n; j++) m->kinematic_level[level[j] + 1]++; /* counting sort, stable */
  for (int L = 0; L < m->nkinematic_level; L++) m->kinematic_level[L + 1] += m->kinematic_level[L];
  int *at = by_elem; /* reused: each level's next entry */
  for (int L = 0; L < m->nkinematic_level; L++) at[L] = m->kinematic_level[L];
  int identity = 1;
  for (int j = 0; j < n; j++) {
    const int t = at[level[j]]++;
    m->kinematic_order[t] = j;
    identity &= t == j;
  }
  if (identity) { /* spec order (every level after the one before: the wing's one level) */
    free(m->kinematic_order);
    m->kinematic_order = NULL;
  }
  free(by_elem), free(level);
  return 1;
}

/* The sum of the joints' parts of a pass's work (d->kinematic_work), in
 * level order: the same bits for any team. */
static double work_sum(const swModel *m, const swData *d) {
  double sum = 0;
  for (int t = 0; t < m->nkinematic; t++) sum += d->kinematic_work[m->kinematic_order ? m->kinematic_order[t] : t];
  return sum;
}

int sw_kinematic_setup(swModel *m, const swSpec *s) {
  const size_t K = (size_t)(s->nkin ? s->nkin : 1);
  m->kinematic = calloc(K, sizeof *m->kinematic);
  m->kinematic_name = calloc(K, sizeof *m->kinematic_name);
  m->kinematic_rot = sw_dalloc(9 * K);
  m->kinematic_dt = sw_dalloc(K);
  if (!m->kinematic || !m->kinematic_name || !m->kinematic_rot || !m->kinematic_dt) return 0;
  for (int j = 0; j < s->nkin; j++) {
    swKinematicDesc k = s->kin[j];
    if (!(m->kinematic_name[j] = strdup(k.name))) return 0;
    m->nkinematic = j + 1;
    k.name = m->kinematic_name[j];
    /* slots: elements and nodes of the rods */
    const int nl = m->rod_nelem[k.leader_rod], nf = m->rod_nelem[k.follower_rod];
    k.leader_elem = m->elem_adr[k.leader_rod] + last_if(k.leader_elem, nl - 1);
    k.follower_elem = m->elem_adr[k.follower_rod] + last_if(k.follower_elem, nf - 1);
    k.follower_node = m->node_adr[k.follower_rod] + last_if(k.follower_node, nf);
    if (k.reaction_rod >= 0)
      k.reaction_node = m->node_adr[k.reaction_rod] +
                        last_if(k.reaction_node, m->rod_nelem[k.reaction_rod]);
    m->kinematic[j] = k;
    double Ql[9], Qf[9], R[9];
    sw_getQ(m, m->Q0, k.leader_elem, Ql);
    sw_getQ(m, m->Q0, k.follower_elem, Qf);
    for (int a = 0; a < 3; a++) /* R = Qf Ql^T: R_ab = d^f_a . d^l_b */
      for (int b = 0; b < 3; b++) R[3 * a + b] = sw_v3_dot(Qf + 3 * a, Ql + 3 * b);
    memcpy(m->kinematic_rot + 9 * j, R, sizeof R);
  }
  for (int j = 0; j < m->nkinematic; j++) m->kinematic_dt[j] = sw_stable_dt_kinematic(m, j);
  return order_levels(m);
}

void sw_kinematic_free(swModel *m) {
  if (m->kinematic_name)
    for (int j = 0; j < m->nkinematic; j++) free(m->kinematic_name[j]);
  free(m->kinematic); free(m->kinematic_name); free(m->kinematic_rot); free(m->kinematic_dt);
  free(m->kinematic_order); free(m->kinematic_level);
}

/* The energy that depends on element e's frame (e of rod r): its turning
 * kinetic energy, its shear energy and the bending energy of the domains on
 * either side of it in its rod (energy.c's sums, term by term). */
static double frame_energy(const swModel *m, const swData *d, int r, int e) {
  const int first = m->elem_adr[r], last = first + m->rod_nelem[r] - 1;
  double Q[9], x0[3], x1[3], dx[3], s[3];
  sw_getQ(m, d->Q, e, Q);
  sw_get3(m, d->x, e, x0);
  sw_get3(m, d->x, e + 1, x1);
  sw_v3_sub(dx, x1, x0);
  sw_mat_vec(s, Q, dx); /* sigma = Q dx / l^ - d3 */
  const double dil = sw_inertia_dilatation(m, d, e);
  double E = 0;
  for (int k = 0; k < 3; k++) {
    const double w = SW_AT(m, d->omega, e, k);
    const double ds = s[k] / m->rest_len[e] - (k == 2) - SW_AT(m, m->rest_sigma, e, k);
    E += 0.5 * SW_AT(m, m->inertia, e, k) / dil * w * w;
    E += 0.5 * m->rest_len[e] * SW_AT(m, m->shear_stiff, e, k) * ds * ds;
  }
  for (int j = e - 1; j <= e; j++) { /* domain j lies between elements j and j + 1 */
    if (j < first || j + 1 > last) continue;
    double Qa[9], Qb[9], phi[3];
    sw_getQ(m, d->Q, j, Qa);
    sw_getQ(m, d->Q, j + 1, Qb);
    sw_frame_log(phi, Qa, Qb);
    for (int k = 0; k < 3; k++) {
      const double dk = phi[k] / m->rest_vor_len[j] - SW_AT(m, m->rest_kappa, j, k);
      E += 0.5 * m->rest_vor_len[j] * SW_AT(m, m->bend_stiff, j, k) * dk * dk;
    }
  }
  return E;
}

/* w_f = R w_l: in material frames, w_f = Q_f w = R Q_l w = R w_l */
static inline __attribute__((always_inline)) void follow_turn(const swModel *m, swData *d, int j) {
  const swKinematicDesc *k = &m->kinematic[j];
  double wl[3], wf[3];
  for (int c = 0; c < 3; c++) wl[c] = SW_AT(m, d->omega, k->leader_elem, c);
  sw_mat_vec(wf, m->kinematic_rot + 9 * j, wl);
  for (int c = 0; c < 3; c++) SW_AT(m, d->omega, k->follower_elem, c) = wf[c];
}

/* The rotation that takes frame Qb to Qa, Qa = exp(-[delta]x) Qb, to first
 * order: [delta]x = (Qb Qa^T - Qa Qb^T) / 2 (material components, the
 * drift's convention: integrate.c). */
static inline __attribute__((always_inline)) void small_turn(const double Qa[9], const double Qb[9],
                                                            double delta[3]) {
  /* entries (2,1), (0,2), (1,0) of Qb Qa^T - Qa Qb^T, an antisymmetric matrix
   * whose (i,j) entry is d^b_i . d^a_j - d^a_i . d^b_j */
  delta[0] = 0.5 * (sw_v3_dot(Qb + 6, Qa + 3) - sw_v3_dot(Qa + 6, Qb + 3));
  delta[1] = 0.5 * (sw_v3_dot(Qb + 0, Qa + 6) - sw_v3_dot(Qa + 0, Qb + 6));
  delta[2] = 0.5 * (sw_v3_dot(Qb + 3, Qa + 0) - sw_v3_dot(Qa + 3, Qb + 0));
}

/* Below this turn (rad) a correction's change of the elastic energy is
 * booked to first order, from the couple the rod pass computes right after
 * it (sw_kinematic_book): dE = -tau . delta, whose neglected second-order
 * term is below 1e-12 of the element's stiffness times a radian squared.
 * The corrections are the drift's: a follower and its leader turn alike
 * only to O((h w)^2) (integrate.c turns each element by its own stretch
 * and splits the turn about its own d3), 1e-12 to 2e-8 rad a step late in
 * the wing's stroke, where evaluating the energy before and after each of
 * them (frame_energy, four logarithms of frames) was a fifth of the step.
 * Larger corrections (a layout that does not start on its leader's frame)
 * are booked exactly. */
#define SW_KIN_FIRST_ORDER 1e-6

/* Joint j's imposition (sw_kinematic_impose); returns the work it books. */
static inline __attribute__((always_inline)) double impose(const swModel *m, swData *d, int j) {
  const swKinematicDesc *k = &m->kinematic[j];
  const int fe = k->follower_elem;
  double Ql[9], Qf[9], Qnow[9], *delta = d->kinematic_delta + 3 * j, work = 0;
  sw_getQ(m, d->Q, k->leader_elem, Ql);
  sw_mat_mul(Qf, m->kinematic_rot + 9 * j, Ql);
  sw_getQ(m, d->Q, fe, Qnow);
  small_turn(Qf, Qnow, delta);
  /* a small correction changes the turning kinetic energy here and the
   * elastic energy in sw_kinematic_book; a large one is booked whole */
  const int small = sw_v3_dot(delta, delta) < SW_KIN_FIRST_ORDER * SW_KIN_FIRST_ORDER;
  double w0[3], before = 0;
  for (int c = 0; c < 3; c++) w0[c] = SW_AT(m, d->omega, fe, c);
  if (!small) before = frame_energy(m, d, k->follower_rod, fe);
  sw_setQ(m, d->Q, fe, Qf);
  follow_turn(m, d, j);
  if (!small) {
    work = frame_energy(m, d, k->follower_rod, fe) - before;
    delta[0] = delta[1] = delta[2] = 0;
  } else {
    const double half_inv_dil = 0.5 / sw_inertia_dilatation(m, d, fe); /* one division, not three */
    for (int c = 0; c < 3; c++) {
      const double w = SW_AT(m, d->omega, fe, c);
      work += SW_AT(m, m->inertia, fe, c) * half_inv_dil * (w * w - w0[c] * w0[c]);
    }
  }
  for (int c = 0; c < 3; c++) d->kinematic_turn[3 * j + c] = SW_AT(m, d->omega, fe, c);
  return work;
}

/* Runs pass(m, d, j) for every joint, level by level, each level's joints
 * split between the team's threads (a barrier after each), and books the
 * work the passes return on the leader, summed in level order. */
static inline __attribute__((always_inline)) void by_levels(const swModel *m, swData *d,
                                                           double (*pass)(const swModel *, swData *, int)) {
  const int *restrict order = m->kinematic_order; /* NULL: spec order */
  if (d->team_size <= 1) { /* a running sum, in the order work_sum adds: the same bits */
    double work = 0;
    if (order)
      for (int t = 0; t < m->nkinematic; t++) work += pass(m, d, order[t]);
    else
      for (int j = 0; j < m->nkinematic; j++) work += pass(m, d, j);
    d->work += work;
    return;
  }
  for (int L = 0; L < m->nkinematic_level; L++) {
    const int first = m->kinematic_level[L], n = m->kinematic_level[L + 1] - first;
    for (int t = first + sw_share_lo(d, n); t < first + sw_share_hi(d, n); t++) {
      const int j = order ? order[t] : t;
      d->kinematic_work[j] = pass(m, d, j);
    }
    sw_team_barrier(d);
  }
  if (sw_team_leader(d)) d->work += work_sum(m, d);
}

void sw_kinematic_impose(const swModel *m, swData *d) { by_levels(m, d, impose); }

/* After the rod pass that follows sw_kinematic_impose, while d->torque
 * holds the internal couples only: the elastic energy the small
 * corrections changed, dE = -tau . delta (tau the element's elastic couple,
 * material frame, whose power is tau . w), to first order, with the couple
 * at the corrected frame.  On the variational law tau is the energy's
 * gradient; on Gazzola's it is the couple the scheme integrates, which
 * differs from the gradient of energy.c's energy as that law's own balance
 * does (docs/physics.md). */
static inline __attribute__((always_inline)) double book(const swModel *m, swData *d, int j) {
  const int fe = m->kinematic[j].follower_elem;
  const double *delta = d->kinematic_delta + 3 * j;
  double dE = 0;
  for (int c = 0; c < 3; c++) dE -= SW_AT(m, d->torque, fe, c) * delta[c];
  return dE;
}

/* (by_levels' barriers: the couples are read before any thread adds loads
 * to them) */
void sw_kinematic_book(const swModel *m, swData *d) { by_levels(m, d, book); }

/* After a kick: the follower turns at its leader's rate, so that the drift
 * nearly keeps Q_f = R Q_l (exp(-h [R w_l]x) R Q_l = R exp(-h [w_l]x) Q_l,
 * to the drift's own stretch and split turn: the header); the change of
 * its turning kinetic energy is booked. */
static inline __attribute__((always_inline)) double follow(const swModel *m, swData *d, int j) {
  const int fe = m->kinematic[j].follower_elem;
  double kicked[3], work = 0;
  for (int c = 0; c < 3; c++) kicked[c] = SW_AT(m, d->omega, fe, c);
  follow_turn(m, d, j);
  const double half_inv_dil = 0.5 / sw_inertia_dilatation(m, d, fe); /* one division, not three */
  /* the couple that turned w from `kicked` to w_f over the kick,
   * C = (J / e)(w_f - kicked) / h, times the kick's mean rate
   * (w_before + w_f) / 2: the midpoint rule the kick books every external
   * load's work by (integrate.c) */
  double *before = d->kinematic_turn + 3 * j;
  for (int c = 0; c < 3; c++) {
    const double w = SW_AT(m, d->omega, fe, c);
    work += SW_AT(m, m->inertia, fe, c) * half_inv_dil * (w - kicked[c]) * (before[c] + w);
    before[c] = w;
  }
  return work;
}

void sw_kinematic_follow(const swModel *m, swData *d) { by_levels(m, d, follow); }

/* w f on node i, into the total and the external loads: with `all`, any
 * node (one thread), else only a node in [lo, hi), this thread's */
static inline __attribute__((always_inline)) void push(const swModel *m, swData *d, int i, const double f[3],
                                                      double w, int lo, int hi, const int all) {
  if (!all && (i < lo || i >= hi)) return;
  for (int c = 0; c < 3; c++) {
    SW_AT(m, d->force, i, c) += w * f[c];
    SW_AT(m, d->ext_force, i, c) += w * f[c];
  }
}

/* Joint j's tie force F = k (p - x_f) + c (v_p - v_f), into F and
 * d->kinematic_force. */
static inline __attribute__((always_inline)) void tie_force(const swModel *m, swData *d, int j, double F[3]) {
  const swKinematicDesc *k = &m->kinematic[j];
  const int a = k->leader_elem, b = a + 1, f = k->follower_node;
  const double xi = k->leader_xi;
  double xa[3], xb[3], va[3], vb[3], xf[3], vf[3];
  sw_get3(m, d->x, a, xa);
  sw_get3(m, d->x, b, xb);
  sw_get3(m, d->v, a, va);
  sw_get3(m, d->v, b, vb);
  sw_get3(m, d->x, f, xf);
  sw_get3(m, d->v, f, vf);
  for (int c = 0; c < 3; c++) {
    const double p = (1 - xi) * xa[c] + xi * xb[c], vp = (1 - xi) * va[c] + xi * vb[c];
    F[c] = k->stiffness * (p - xf[c]) + k->damping * (vp - vf[c]);
    d->kinematic_force[3 * j + c] = F[c];
  }
}

/* Joint j's tie force F onto its nodes (push): F on the follower node, -F
 * on the leader's two nodes ((1 - xi) and xi) or -w F on the reaction node. */
static inline __attribute__((always_inline)) void tie_push(const swModel *m, swData *d, int j, const double F[3],
                                                          int lo, int hi, const int all) {
  const swKinematicDesc *k = &m->kinematic[j];
  const double xi = k->leader_xi;
  push(m, d, k->follower_node, F, 1.0, lo, hi, all);
  if (k->reaction_rod >= 0) {
    push(m, d, k->reaction_node, F, -k->reaction_weight, lo, hi, all);
  } else {
    push(m, d, k->leader_elem, F, -(1 - xi), lo, hi, all);
    push(m, d, k->leader_elem + 1, F, -xi, lo, hi, all);
  }
}

/* The ties' forces, each thread a share of the joints; then each thread
 * adds them to the nodes it owns (internal.h, sw_owned_slots), in joint
 * order, so every node gets its loads in the order of one thread. */
void sw_kinematic_loads(const swModel *m, swData *d) {
  const int n = m->nkinematic;
  double F[3];
  if (d->team_size <= 1) { /* one pass: each tie's loads while its force is at hand */
    for (int j = 0; j < n; j++) tie_force(m, d, j, F), tie_push(m, d, j, F, 0, 0, 1);
    return;
  }
  for (int j = sw_share_lo(d, n); j < sw_share_hi(d, n); j++) tie_force(m, d, j, F);
  sw_team_barrier(d);
  int lo, hi;
  sw_owned_slots(m, d, &lo, &hi);
  for (int j = 0; j < n; j++) tie_push(m, d, j, d->kinematic_force + 3 * j, lo, hi, 0);
}
