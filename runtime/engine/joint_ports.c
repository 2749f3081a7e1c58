/* joint_ports.c — implicit rods and leaf attachments in the joints' system.
 *
 * Design.  rigid_joint.c integrates the stiff joints on rigid bodies with
 * the trapezoidal rule, one dense symmetric block per group of members.
 * An implicit rod (rod_implicit.c) is kicked with the trapezoidal rule in
 * its own elasticity, so a stiff joint on one of its nodes (the arm's
 * tendons on the bones, the bones on each other, the muscle filaments on
 * the tendons: 5e5 N/m on nodes of a few grams) would be the only stiff
 * term left explicit.  Here such a rod joins the system as one member
 * whose unknowns are its ports, the velocities of the nodes (and, when a
 * joint turns it, of the elements) that implicit joints touch.
 *
 * Substructuring (static condensation; Przemieniecki, Theory of Matrix
 * Structural Analysis, 1968, ch. 9).  Write the rod's trapezoidal system
 * A du = h F (rod_implicit.c, banded) and E the map from its unknowns to
 * its ports' lab velocities, p = E^T du (a node's three components as they
 * are; an element's material angular velocity turned to the lab,
 * w_lab = Q^T w, so E holds Q there).  The joints add J^T W J to the whole
 * system and act on the rod only through its ports: A du + E g = h F with
 * g the joints' part on the ports.  So
 *   du = du0 - Z g,  du0 = A^-1 h F,  Z = A^-1 E,
 *   p = p0 - C g,    p0 = E^T du0,    C = E^T Z,
 * and g = S (p0 - p) with S = C^-1, the rod's stiffness as its ports see
 * it within one kick.  In the group's system the rod is therefore a member
 * with "mass" S and right-hand side S p0, exactly as a body has M and
 * h F = M du0: the group is assembled, factored and solved as before, and
 * then du = du0 - Z g gives every unknown of the rod, whose loads become
 * those of that velocity change (sw_implicit_apply).  The exact solution
 * of the one linear system, rods and joints together (Z and C are exact
 * up to round-off); the banded factorisation is done once and solved for
 * 1 + ports right-hand sides at once (rod_implicit.c, as vector operations
 * across them): about 2 N (2 BAND + 1)(p + 1) flops for N unknowns and p
 * port unknowns, 3.2e4 for a bone of 20 elements with 12.
 *
 * Leaves.  A muscle's filaments hang on a tendon's end by a joint each:
 * members of three unknowns whose only neighbour is one port.  In the
 * group's dense block they would widen its envelope to all of them (18
 * per head on the arm).  Such a leaf a is eliminated before the group's
 * factorisation (block Gaussian elimination of a vertex of degree one,
 * which causes no fill: George and Liu 1981, ch. 5): with its block A_aa,
 * its coupling C_a = A_aq to the port and its right-hand side b_a,
 *   A_qq -= C_a^T A_aa^-1 C_a,  b_q -= C_a^T A_aa^-1 b_a,
 * and after the solve u_a = A_aa^-1 (b_a - C_a u_q).  rigid_joint.c
 * assembles the leaves' blocks; the algebra is here.
 *
 * Filaments.  A muscle filament's implicit Hill damping (muscle.c) is a
 * dashpot c b b^T across its nodes.  Solved per filament with free end
 * masses, it takes up the joints' forces on its ends and hands them on
 * explicitly, which held the arm to 46 us with every joint implicit.  When
 * both ends of a filament are leaves (or one is clamped), muscle.c
 * eliminates the interior nodes and leaves the system the dashpot between
 * the ends, h c' b_e b_e^T: the two leaves are eliminated together as one
 * unit of six unknowns joined to two ports (the same algebra with C = A_uQ
 * over both ports, which couples them), and the tension then follows from
 * the ends' velocity changes (system_tension in muscle.c).
 *
 * The band path (issue 32).  A group of one implicit rod and leaves alone
 * (a feather's rachis and its barbs: no body, no other dense member, no
 * leaf pair, which would join two ports; joint_groups.c decides it at
 * setup, m->rigid_group_band) would make S a dense block of all the ports,
 * p^3 / 3 flops to factor and 1 + p band solves to form (150 barbs on
 * fixed joints: p = 900, 1e8 flops a kick).  There the rod's system is not
 * condensed: rigid_joint.c assembles each port's block (its joints' J^T W
 * J on the port, less C_a^T A_aa^-1 C_a of each leaf on it) and right-hand
 * side (less C_a^T A_aa^-1 b_a), lab frame, and sw_band_group_solve adds
 * them to the rod's band as E (.) E^T and E (.): as they are on the node's
 * rows, turned by Q on the element's (w = Q w_lab), rows 6 i - 3 .. 6 i + 2
 * or 6 i .. 6 i + 5, within the half-bandwidth.  (A + sum E K_q E^T) du =
 * h F + sum E b_q is the linear system the dense path solves, factored and
 * solved once; E^T du gives each port's lab velocity, from which each leaf
 * is recovered.  Cost: the rod's own kick plus a few hundred flops per
 * leaf, linear in the leaves (test_joint_band: 64 barbs on 128 elements,
 * 120 us a kick against 27 ms).  The band is factored afresh every kick:
 * the ports' blocks change with the state.
 *
 * A member's band path (issue 32, m->rigid_group_band 2).  A rachis tied
 * at its root to a bone is a member of the bone's group, with every barb's
 * port in S (150 barbs: some 470 unknowns).  Its ports split at setup
 * (joint_groups.c, member_bands): a band port is reached by lone leaves
 * and still sides only; the member keeps the others (rigid_port_moff
 * numbers them in the group's block, -1 - t the band ports).  Then
 * rigid_joint.c assembles the band ports' blocks P and right-hand sides R
 * as the band path does (joints, leaves eliminated), and only after them
 * sw_port_member_assemble adds them to the rod's band through E, and
 * condenses that band to the kept ports exactly as above: du0 = A'^-1 b',
 * Z = A'^-1 E_k, S = (E_k^T Z)^-1, added to the group's block (which holds
 * the kept ports' joints and leaves already).  The group sees the rod as
 * its kept ports alone (6 unknowns for a fixed root); after its solve
 * du = du0 - Z g, each band port's E^T du goes to R, and each leaf is
 * recovered from it (test_joint_member_band: 64 barbs on 128 elements and
 * a rigid bone, 91 us a kick against 12.8 ms; a block of 12 unknowns
 * against 396).  The band is kept across kicks while it holds
 * (rod_implicit.c, sw_implicit_band_kept; ports_hold below), and Z with it,
 * turned by the ports' frames (kept_turns): such a kick solves for du0
 * alone.
 */
#include <math.h>
#include <string.h>
#include "sinew.h"
#include "vec.h"
#include "internal.h"

/* A rod member's unknowns in its group: its ports' (3 per node, 3 more
 * when a joint turns the element), or under a member's band path (band)
 * its kept ports'. */
static int member_ports(const swModel *m, int k, int band) {
  return band ? m->rigid_block_mdof[k] : m->rigid_block_dof[k];
}

/* Port q's first unknown in its member k, or < 0 for a band port. */
static int port_col(const swModel *m, int k, int q, int band) {
  if (!band) return m->rigid_port_off[q];
  return m->rigid_port_moff[q] < 0 ? -1 : m->rigid_port_moff[q] - m->rigid_block_moff[k];
}

/* The row length of a rod member's right-hand sides: 1 + its ports'
 * unknowns, rounded up to whole blocks of the solve (rod_implicit.c). */
static int rhs_row(const swModel *m, int k, int band) {
  const int B = SW_SOLVE_BLOCK;
  return (member_ports(m, k, band) + 1 + B - 1) / B * B;
}

/* Member k's band ports under a member's band path. */
static int band_ports_of(const swModel *m, int k) {
  int nbp = 0;
  for (int q = m->rigid_block_port_adr[k]; q < m->rigid_block_port_adr[k + 1]; q++)
    nbp += m->rigid_port_moff[q] < 0;
  return nbp;
}

/* The workspace: X (N rows of rhs_row with SW_IMPLICIT_BAND rows of zeros
 * before and after), S (p x p), p0 and g (p each), and under a member's
 * band path C^-1 (p x p) before it is added to the group's block, then the
 * band ports' blocks its kept band was factored with, then the kept Z's
 * turns (kept_turns). */
size_t sw_port_member_scratch(const swModel *m, int k, int band) {
  const size_t N = sw_implicit_unknowns(m, m->rigid_block_rod[k]), p = (size_t)member_ports(m, k, band);
  const size_t kept = band ? (size_t)band_ports_of(m, k) * SW_BAND_PORT : 0;
  const size_t X = (N + 2 * SW_IMPLICIT_BAND) * (size_t)rhs_row(m, k, band);
  const size_t nq = (size_t)(m->rigid_block_port_adr[k + 1] - m->rigid_block_port_adr[k]);
  const size_t turns = band ? 1 + 9 * nq : 0;
  return X + p * p * (band ? 2 : 1) + 2 * p + kept + turns;
}

/* Under a member's band path, Z = A^-1 E is kept with the band.  E holds
 * the turned ports' frames Q (w = Q w_lab), so with the frame Q_k of the
 * kick that made Z, E's block is Q = Q_k T, T = Q_k^T Q, and Z's columns of
 * that port are Z_k T: exact for the kept band, and no solve for them.
 * The workspace's last part says whether Z is the kept band's (its first
 * double, 1 once the band path has made it) and holds each port's T (9
 * doubles from port q's place, q from the member's first): what the finish
 * turns g by (du = du0 - Z_k (T g)). */
static double *kept_turns(const swModel *m, int k, double *ws) {
  return ws + sw_port_member_scratch(m, k, 1) -
         9 * (size_t)(m->rigid_block_port_adr[k + 1] - m->rigid_block_port_adr[k]);
}

/* X's columns 1 .. p, E (zeros but for the kept ports' rows), and its
 * column 0 and band rows of zeros before and after. */
static void load_ports_map(const swModel *m, const swData *d, int k, int band, double *ws,
                           size_t NX, int nc) {
  const int na = m->node_adr[m->rigid_block_rod[k]], ea = m->elem_adr[m->rigid_block_rod[k]];
  double *X = ws + SW_IMPLICIT_BAND * (size_t)nc;
  memset(ws, 0, NX * sizeof(double));
  for (int q = m->rigid_block_port_adr[k]; q < m->rigid_block_port_adr[k + 1]; q++) {
    const size_t i = (size_t)(m->rigid_port_node[q] - na);
    const int o = 1 + port_col(m, k, q, band);
    if (o < 1) continue; /* a band port: its block goes into the band */
    for (int a = 0; a < 3; a++) X[(6 * i + (size_t)a) * (size_t)nc + (size_t)(o + a)] = 1;
    if (!m->rigid_port_rot[q] || m->rigid_port_alias[q] >= 0) continue; /* (joint_alias.c) */
    const size_t e = (size_t)(m->rigid_port_elem[q] - ea);
    double Q[9];
    sw_getQ(m, d->Q, m->rigid_port_elem[q], Q);
    for (int a = 0; a < 3; a++)
      for (int b = 0; b < 3; b++)
        X[(6 * e + 3 + (size_t)a) * (size_t)nc + (size_t)(o + 3 + b)] = Q[3 * a + b];
  }
}

void sw_port_member_forget(const swModel *m, int k, double *ws) { kept_turns(m, k, ws)[-1] = 0; }

/* C's columns of the turned ports times T (C = E^T Z_k T), and each T into
 * the turns (identity when Z is this kick's: kept 0). */
static void turn_ports(const swModel *m, const swData *d, int k, double *C, int p, double *turns,
                       int kept) {
  const int r = m->rigid_block_rod[k], q0 = m->rigid_block_port_adr[k];
  for (int q = q0; q < m->rigid_block_port_adr[k + 1]; q++) {
    double *T = turns + 9 * (size_t)(q - q0), Qk[9], Q[9];
    const int o = port_col(m, k, q, 1);
    for (int c = 0; c < 9; c++) T[c] = c % 4 == 0;
    if (!kept || o < 0 || !m->rigid_port_rot[q] || m->rigid_port_alias[q] >= 0) continue;
    sw_implicit_kept_frame(m, d, r, m->rigid_port_elem[q], Qk);
    sw_getQ(m, d->Q, m->rigid_port_elem[q], Q);
    for (int a = 0; a < 3; a++) /* T = Q_k^T Q */
      for (int b = 0; b < 3; b++)
        T[3 * a + b] = Qk[a] * Q[b] + Qk[3 + a] * Q[3 + b] + Qk[6 + a] * Q[6 + b];
    for (int a = 0; a < p; a++) {
      double *Ca = C + (size_t)a * (size_t)p + o + 3, row[3];
      for (int b = 0; b < 3; b++) row[b] = Ca[0] * T[b] + Ca[1] * T[3 + b] + Ca[2] * T[6 + b];
      memcpy(Ca, row, sizeof row);
    }
  }
}

/* In place: the lower triangle of the n x n SPD matrix C (row-major) turns
 * into its Cholesky factor L, and inv[j] = 1 / L(j, j) (the solves' only
 * use of the diagonal, formed once).  Returns 0 if C is not positive
 * definite. */
static inline __attribute__((always_inline)) int small_cholesky(double *C, int n, double *inv) {
  for (int j = 0; j < n; j++) {
    double djj = C[j * n + j];
    for (int k = 0; k < j; k++) djj -= C[j * n + k] * C[j * n + k];
    if (!(djj > 0)) return 0;
    const double ljj = sqrt(djj);
    C[j * n + j] = ljj;
    for (int i = j + 1; i < n; i++) {
      double s = C[i * n + j];
      for (int k = 0; k < j; k++) s -= C[i * n + k] * C[j * n + k];
      C[i * n + j] = s / ljj;
    }
    inv[j] = 1.0 / ljj;
  }
  return 1;
}

/* L L^T x = b in place, b with nc values per row, rows ld doubles apart,
 * inv the inverse diagonal of small_cholesky. */
static inline __attribute__((always_inline)) void small_solve_ld(const double *restrict L, int n,
                                                                 const double *restrict inv,
                                                                 double *restrict b, int nc, int ld) {
  for (int i = 0; i < n; i++) {
    double *bi = b + (size_t)i * (size_t)ld;
    for (int k = 0; k < i; k++) {
      const double l = L[i * n + k], *bk = b + (size_t)k * (size_t)ld;
      for (int c = 0; c < nc; c++) bi[c] -= l * bk[c];
    }
    for (int c = 0; c < nc; c++) bi[c] *= inv[i];
  }
  for (int i = n - 1; i >= 0; i--) {
    double *bi = b + (size_t)i * (size_t)ld;
    for (int k = i + 1; k < n; k++) {
      const double l = L[k * n + i], *bk = b + (size_t)k * (size_t)ld;
      for (int c = 0; c < nc; c++) bi[c] -= l * bk[c];
    }
    for (int c = 0; c < nc; c++) bi[c] *= inv[i];
  }
}

/* The same for b the identity (zero on entry but for the diagonal, which
 * it sets): C^-1.  Column c of L^-1 is zero above row c, so the forward
 * solve of row i takes off only its columns c <= k from row k; the terms
 * left out are products with those zeros, so the bits are those of
 * small_solve_ld. */
static void small_inverse_ld(const double *restrict L, int n, const double *restrict inv,
                             double *restrict b, int ld) {
  for (int i = 0; i < n; i++) {
    double *bi = b + (size_t)i * (size_t)ld;
    bi[i] = 1;
    for (int k = 0; k < i; k++) {
      const double l = L[i * n + k], *bk = b + (size_t)k * (size_t)ld;
      for (int c = 0; c <= k; c++) bi[c] -= l * bk[c];
    }
    for (int c = 0; c <= i; c++) bi[c] *= inv[i];
  }
  for (int i = n - 1; i >= 0; i--) {
    double *bi = b + (size_t)i * (size_t)ld;
    for (int k = i + 1; k < n; k++) {
      const double l = L[k * n + i], *bk = b + (size_t)k * (size_t)ld;
      for (int c = 0; c < n; c++) bi[c] -= l * bk[c];
    }
    for (int c = 0; c < n; c++) bi[c] *= inv[i];
  }
}

static inline __attribute__((always_inline)) void small_solve(const double *restrict L, int n,
                                                              const double *restrict inv,
                                                              double *restrict b, int nc) {
  small_solve_ld(L, n, inv, b, nc, nc);
}

/* E^T of columns 0 .. p of X (N x nc): the ports' lab velocities, column
 * 0's into p0[a] and column 1 + c's into C[a p + c] (C = E^T Z). */
static void ports_of(const swModel *m, const swData *d, int k, const double *X, int nc, int p,
                     double *p0, double *C, int band) {
  const int r = m->rigid_block_rod[k], na = m->node_adr[r], ea = m->elem_adr[r];
  for (int q = m->rigid_block_port_adr[k]; q < m->rigid_block_port_adr[k + 1]; q++) {
    const size_t i = (size_t)(m->rigid_port_node[q] - na);
    const int o = port_col(m, k, q, band);
    if (o < 0) continue; /* a band port: in the band */
    for (int a = 0; a < 3; a++) {
      const double *Xa = X + (6 * i + (size_t)a) * (size_t)nc;
      p0[o + a] = Xa[0];
      for (int c = 0; c < p; c++) C[(o + a) * p + c] = Xa[1 + c];
    }
    if (!m->rigid_port_rot[q]) continue;
    if (m->rigid_port_alias[q] >= 0) { /* another port's rotation (joint_alias.c): C's identity */
      for (int b = 0; b < 3; b++) {
        p0[o + 3 + b] = 0;
        for (int c = 0; c < p; c++) C[(o + 3 + b) * p + c] = c == o + 3 + b;
      }
      continue;
    }
    const size_t e = (size_t)(m->rigid_port_elem[q] - ea);
    const double *Xw = X + (6 * e + 3) * (size_t)nc; /* the element's three rows */
    double Q[9];
    sw_getQ(m, d->Q, m->rigid_port_elem[q], Q);
    for (int b = 0; b < 3; b++) /* w_lab = Q^T w */
      for (int c = 0; c <= p; c++) {
        double s = 0;
        for (int a = 0; a < 3; a++) s += Q[3 * a + b] * Xw[(size_t)a * (size_t)nc + (size_t)c];
        if (c == 0) p0[o + 3 + b] = s;
        else C[(o + 3 + b) * p + c - 1] = s;
      }
  }
}

static void port_rows(const swModel *m, int r, int q, size_t *pos);
static void add_port_block(const swModel *m, const swData *d, int r, int q, const double *Pq,
                           const double *Rq, double *A, double *b);
static void add_port_rhs(const swModel *m, const swData *d, int r, int q, const double *Rq,
                         double *b);

/* Whether member k's band ports' blocks P (this kick's, its band ports'
 * in their order t) are near those its kept band was factored with (Pk,
 * in the same order): every block's entries within theta (the rod's,
 * sw_implicit_band_kept) of its largest kept entry.  A block is its barbs'
 * joints in series with their inertia (leaf_plain.c), which turns with
 * the barbs' frames; a kept block off by delta of itself is a W-method's
 * matrix off by as much (rod_implicit.c, "keeping a factorisation"). */
static int ports_hold(const swModel *m, int k, const double *P, const double *Pk, double theta) {
  for (int q = m->rigid_block_port_adr[k], c = 0; q < m->rigid_block_port_adr[k + 1]; q++) {
    const int t = -1 - m->rigid_port_moff[q];
    if (t < 0) continue;
    const double *Pt = P + (size_t)SW_BAND_PORT * (size_t)t;
    const double *Pc = Pk + (size_t)SW_BAND_PORT * (size_t)c++;
    double big = 0, moved = 0;
    for (int e = 0; e < SW_BAND_PORT; e++)
      big = sw_max(big, fabs(Pc[e])), moved = sw_max(moved, fabs(Pt[e] - Pc[e])); /* NaN: not */
    if (!(moved <= theta * big)) return 0;
  }
  return 1;
}
static void port_velocity(const swModel *m, const swData *d, int r, int q, const double *du,
                          size_t stride, double *Rq);

int sw_port_member_assemble(const swModel *m, swData *d, double h, int k, double *ws, double *A,
                            int n, int off, double *rhs, const double *P, const double *R) {
  const int band = P != NULL, r = m->rigid_block_rod[k], p = member_ports(m, k, band);
  const int nc = rhs_row(m, k, band);
  const size_t N = sw_implicit_unknowns(m, r), NX = (N + 2 * SW_IMPLICIT_BAND) * (size_t)nc;
  double *X = ws + SW_IMPLICIT_BAND * (size_t)nc, *S = ws + NX, *p0 = S + (size_t)p * (size_t)p;
  double *inv = p0 + p; /* 1 / L(a, a) of C's factor, in g's place (the finish's) */
  /* band ports: without them the rod's own system, kept when it holds */
  const int nbp = band ? band_ports_of(m, k) : 0;
  double *turns = band ? kept_turns(m, k, ws) : NULL;
  int kept = 0;
  if (nbp) { /* the band ports' blocks in the band (sw_band_group_solve), then du0 and Z */
    const int q0 = m->rigid_block_port_adr[k], q1 = m->rigid_block_port_adr[k + 1];
    double *Pk = ws + NX + 2 * (size_t)p * (size_t)p + 2 * (size_t)p; /* the kept band's */
    double theta = 0, *b = sw_implicit_band_kept(m, d, r, h, &theta);
    if (b && ports_hold(m, k, P, Pk, theta)) { /* the kept band; this kick's right-hand side */
      for (int q = q0; q < q1; q++) {
        const int t = -1 - m->rigid_port_moff[q];
        if (t >= 0) add_port_rhs(m, d, r, q, R + 6 * (size_t)t, b);
      }
      kept = turns[-1] == 1; /* and its Z: du0 alone; else Z solved for with this E */
      if (!kept) load_ports_map(m, d, k, band, ws, NX, nc);
      sw_implicit_band_solve_kept(m, d, r, X, nc, !kept);
    } else {
      load_ports_map(m, d, k, band, ws, NX, nc);
      double *Ab = sw_implicit_band_begin(m, d, r, h, &b);
      if (!Ab) return 0;
      for (int q = q0, c = 0; q < q1; q++) {
        const int t = -1 - m->rigid_port_moff[q];
        if (t < 0) continue;
        const double *Pt = P + (size_t)SW_BAND_PORT * (size_t)t;
        add_port_block(m, d, r, q, Pt, R + 6 * (size_t)t, Ab, b);
        memcpy(Pk + (size_t)SW_BAND_PORT * (size_t)c++, Pt, SW_BAND_PORT * sizeof(double));
      }
      turns[-1] = 0; /* Z is this kick's until the band is kept */
      if (!sw_implicit_band_solve_many(m, d, r, X, nc)) return 0;
      sw_implicit_band_keep(m, d, r, h);
      turns[-1] = 1;
    }
  } else {
    load_ports_map(m, d, k, band, ws, NX, nc);
    if (!sw_implicit_solve_many(m, d, r, h, X, nc)) return 0; /* du0, Z */
  }
  ports_of(m, d, k, X, nc, p, p0, S, band); /* p0, and C = E^T Z into S */
  if (band) turn_ports(m, d, k, S, p, turns, kept); /* C = E^T Z_k T */
  for (int a = 0; a < p; a++) /* symmetric up to round-off */
    for (int c = 0; c < a; c++) S[a * p + c] = S[c * p + a] = 0.5 * (S[a * p + c] + S[c * p + a]);
  if (!small_cholesky(S, p, inv)) return 0;
  /* S = C^-1: the identity solved for, all its columns at once, in the
   * member's diagonal block of A (zero here; its row length is n), or
   * under a member's band path in the workspace (A's block holds the
   * joints' and leaves' terms already) and added to A's lower triangle */
  double *T = inv + p;
  if (band) memset(T, 0, (size_t)p * (size_t)p * sizeof(double));
  double *Ainv = band ? T : A + (size_t)off * (size_t)n + off;
  const size_t ld = band ? (size_t)p : (size_t)n;
  small_inverse_ld(S, p, inv, Ainv, (int)ld);
  for (int q = m->rigid_block_port_adr[k]; q < m->rigid_block_port_adr[k + 1]; q++) {
    const int o = port_col(m, k, q, band) + 3; /* an alias' rows of S: C's identity's, taken off */
    if (m->rigid_port_alias[q] >= 0 && o >= 3)
      for (int b = 0; b < 3; b++) Ainv[(size_t)(o + b) * ld + (size_t)(o + b)] = 0;
  }
  for (int a = 0; a < p; a++) { /* S kept for the finish; rhs = S p0 */
    double s = 0;
    for (int c = 0; c < p; c++) {
      S[a * p + c] = Ainv[(size_t)a * ld + c];
      s += S[a * p + c] * p0[c];
    }
    if (!band) {
      rhs[off + a] = s;
      continue;
    }
    rhs[off + a] += s;
    for (int c = 0; c <= a; c++) A[(size_t)(off + a) * (size_t)n + (size_t)(off + c)] += S[a * p + c];
  }
  return 1;
}

void sw_port_member_finish(const swModel *m, swData *d, double h, int k, double *ws,
                           const double *pu, double *R) {
  const int band = R != NULL, r = m->rigid_block_rod[k], p = member_ports(m, k, band);
  const int nc = rhs_row(m, k, band);
  const size_t N = sw_implicit_unknowns(m, r), NX = (N + 2 * SW_IMPLICIT_BAND) * (size_t)nc;
  double *X = ws + SW_IMPLICIT_BAND * (size_t)nc, *S = ws + NX, *p0 = S + (size_t)p * (size_t)p;
  double *g = p0 + p;
  for (int a = 0; a < p; a++) { /* g = S (p0 - p) */
    double s = 0;
    for (int c = 0; c < p; c++) s += S[a * p + c] * (p0[c] - pu[c]);
    g[a] = s;
  }
  if (band) { /* Z_k's columns: g turned by each port's T (kept_turns) */
    const double *turns = kept_turns(m, k, ws);
    for (int q = m->rigid_block_port_adr[k]; q < m->rigid_block_port_adr[k + 1]; q++) {
      const double *T = turns + 9 * (size_t)(q - m->rigid_block_port_adr[k]);
      const int o = port_col(m, k, q, 1) + 3;
      if (o < 3 || !m->rigid_port_rot[q] || m->rigid_port_alias[q] >= 0) continue;
      double t[3];
      for (int a = 0; a < 3; a++)
        t[a] = T[3 * a] * g[o] + T[3 * a + 1] * g[o + 1] + T[3 * a + 2] * g[o + 2];
      memcpy(g + o, t, sizeof t);
    }
  }
  for (size_t i = 0; i < N; i++) { /* du = du0 - Z g, into column 0 */
    double *Xi = X + i * (size_t)nc, s = Xi[0];
    for (int c = 0; c < p; c++) s -= Xi[1 + c] * g[c];
    Xi[0] = s;
  }
  for (int q = m->rigid_block_port_adr[k]; band && q < m->rigid_block_port_adr[k + 1]; q++) {
    const int t = -1 - m->rigid_port_moff[q]; /* a band port's lab velocity change, E^T du */
    if (t >= 0) port_velocity(m, d, r, q, X, (size_t)nc, R + 6 * (size_t)t);
  }
  sw_implicit_apply(m, d, r, X, (size_t)nc, h);
}

/* A unit's workspace (sw_unit_size doubles): A_uu (du x du), its coupling
 * C (du x dQ) to its np ports (the ports' columns one after another,
 * qdof[p] each), X = A_uu^-1 C and b, one after another; qoff[p] is port
 * p's first unknown in the group's dense block A (n x n). */
static inline __attribute__((always_inline)) int
condense(double *ws, int du, int dQ, int np, const int *qoff, const int *qdof, double *A, int n,
         double *rhs) {
  double *Auu = ws, *C = sw_unit_C(ws, du), *X = sw_unit_X(ws, du, dQ), *b = sw_unit_b(ws, du, dQ);
  double inv[12];
  if (!small_cholesky(Auu, du, inv)) return 0;
  memcpy(X, C, (size_t)(du * dQ) * sizeof(double));
  small_solve(Auu, du, inv, X, dQ);
  small_solve(Auu, du, inv, b, 1);
  /* A_QQ -= C^T X on A's lower triangle, the only part the envelope Cholesky
   * reads (rigid_joint.c): row qoff[p1] + i, the columns up to it */
  for (int p1 = 0, c1 = 0; p1 < np; c1 += qdof[p1++])
    for (int i = 0; i < qdof[p1]; i++) {
      const int row = qoff[p1] + i;
      double *Ai = A + (size_t)row * (size_t)n;
      for (int p2 = 0, c2 = 0; p2 < np; c2 += qdof[p2++])
        for (int c = 0; c < qdof[p2] && qoff[p2] + c <= row; c++) {
          double s = 0;
          for (int a = 0; a < du; a++) s += C[a * dQ + c1 + i] * X[a * dQ + c2 + c];
          Ai[qoff[p2] + c] -= s;
        }
      double s = 0;
      for (int a = 0; a < du; a++) s += C[a * dQ + c1 + i] * b[a];
      rhs[qoff[p1] + i] -= s;
    }
  return 1;
}

/* LANES units of one shape eliminated together (the arm's 36 filaments are
 * all units of two 3-unknown ends on two 3-unknown ports): each lane does
 * condense's operations on its own unit in the same order, so the bits are
 * condense's, but the lanes' operations are one vector operation, and the
 * chain of square roots and divisions of the small factorisations is paid
 * once per LANES units.  The units' factor, X and b go back to their
 * workspaces (sw_leaf_recover reads X and b); their updates of A and rhs,
 * the only sums over units, are made unit after unit, as condense makes
 * them.  nu <= LANES units; the lanes past nu repeat the last unit and are
 * not written back. */
#define LANES 4
/* Row i of the lanes' right-hand sides (X's dQ columns and b) less l times
 * row k, and scaled by inv: the two steps of small_solve_ld, lane by lane. */
static inline __attribute__((always_inline)) void
lanes_take_row(double (*X)[LANES], double (*b)[LANES], int dQ, int i, int k, const double *l) {
  for (int u = 0; u < LANES; u++) {
    for (int c = 0; c < dQ; c++) X[i * dQ + c][u] -= l[u] * X[k * dQ + c][u];
    b[i][u] -= l[u] * b[k][u];
  }
}
static inline __attribute__((always_inline)) void
lanes_scale_row(double (*X)[LANES], double (*b)[LANES], int dQ, int i, const double *inv) {
  for (int u = 0; u < LANES; u++) {
    for (int c = 0; c < dQ; c++) X[i * dQ + c][u] *= inv[u];
    b[i][u] *= inv[u];
  }
}
static inline __attribute__((always_inline)) int
condense_lanes(double *const *ws, const int *const *qoff, int nu, int du, int dQ, int np,
               const int *qdof, double *A, int n, double *rhs) {
  double L[12 * 12][LANES], C[12 * 12][LANES], X[12 * 12][LANES], b[12][LANES], inv[12][LANES];
  double G[12 * 12][LANES], gb[12][LANES]; /* C^T X and C^T b */
  for (int u = 0; u < LANES; u++) { /* the units' A_uu, C and b, lane by lane */
    const double *w = ws[u < nu ? u : nu - 1];
    for (int e = 0; e < du * du; e++) L[e][u] = w[e];
    for (int e = 0; e < du * dQ; e++) C[e][u] = X[e][u] = w[du * du + e];
    for (int e = 0; e < du; e++) b[e][u] = w[du * du + 2 * du * dQ + e];
  }
  int ok = 1;
  for (int j = 0; j < du; j++) { /* small_cholesky */
    double ljj[LANES];
    for (int u = 0; u < LANES; u++) {
      double djj = L[j * du + j][u];
      for (int k = 0; k < j; k++) djj -= L[j * du + k][u] * L[j * du + k][u];
      ok &= djj > 0;
      ljj[u] = sqrt(djj);
      L[j * du + j][u] = ljj[u];
    }
    for (int i = j + 1; i < du; i++)
      for (int u = 0; u < LANES; u++) {
        double s = L[i * du + j][u];
        for (int k = 0; k < j; k++) s -= L[i * du + k][u] * L[j * du + k][u];
        L[i * du + j][u] = s / ljj[u];
      }
    for (int u = 0; u < LANES; u++) inv[j][u] = 1.0 / ljj[u];
  }
  if (!ok) return 0;
  for (int i = 0; i < du; i++) { /* small_solve of X = A_uu^-1 C and of b: L y = x */
    for (int k = 0; k < i; k++) lanes_take_row(X, b, dQ, i, k, L[i * du + k]);
    lanes_scale_row(X, b, dQ, i, inv[i]);
  }
  for (int i = du - 1; i >= 0; i--) { /* L^T x = y */
    for (int k = i + 1; k < du; k++) lanes_take_row(X, b, dQ, i, k, L[k * du + i]);
    lanes_scale_row(X, b, dQ, i, inv[i]);
  }
  for (int r = 0; r < dQ; r++) { /* C^T X and C^T b, every place (each unit's own part of them below) */
    for (int c = 0; c < dQ; c++)
      for (int u = 0; u < LANES; u++) {
        double s = 0;
        for (int a = 0; a < du; a++) s += C[a * dQ + r][u] * X[a * dQ + c][u];
        G[r * dQ + c][u] = s;
      }
    for (int u = 0; u < LANES; u++) {
      double s = 0;
      for (int a = 0; a < du; a++) s += C[a * dQ + r][u] * b[a][u];
      gb[r][u] = s;
    }
  }
  for (int u = 0; u < nu; u++) { /* back to the workspace; A_QQ -= C^T X on A's lower triangle */
    double *w = ws[u];
    for (int i = 0; i < du; i++)
      for (int j = 0; j <= i; j++) w[i * du + j] = L[i * du + j][u];
    for (int e = 0; e < du * dQ; e++) w[du * du + du * dQ + e] = X[e][u];
    for (int e = 0; e < du; e++) w[du * du + 2 * du * dQ + e] = b[e][u];
    for (int p1 = 0, c1 = 0; p1 < np; c1 += qdof[p1++])
      for (int i = 0; i < qdof[p1]; i++) {
        const int row = qoff[u][p1] + i;
        double *Ai = A + (size_t)row * (size_t)n;
        for (int p2 = 0, c2 = 0; p2 < np; c2 += qdof[p2++])
          for (int c = 0; c < qdof[p2] && qoff[u][p2] + c <= row; c++)
            Ai[qoff[u][p2] + c] -= G[(c1 + i) * dQ + c2 + c][u];
        rhs[row] -= gb[c1 + i][u];
      }
  }
  return 1;
}

/* The common units at sizes the compiler knows, so their small loops are
 * unrolled: a filament's two ends on two spherical ports (6 and 6), one end
 * (3 and 3), by LANES; any other one by one, by the general loops. */
int sw_leaf_condense(double *const *ws, const int *const *qoff, int nu, int du, int dQ, int np,
                     const int *qdof, double *A, int n, double *rhs) {
  static const int three[2] = {3, 3};
  for (int u0 = 0; u0 < nu; u0 += LANES) {
    const int m = nu - u0 < LANES ? nu - u0 : LANES;
    if (du == 6 && dQ == 6 && np == 2 && qdof[0] == 3) {
      if (!condense_lanes(ws + u0, qoff + u0, m, 6, 6, 2, three, A, n, rhs)) return 0;
    } else if (du == 3 && dQ == 3 && np == 1) {
      if (!condense_lanes(ws + u0, qoff + u0, m, 3, 3, 1, three, A, n, rhs)) return 0;
    } else {
      for (int u = u0; u < u0 + m; u++)
        if (!condense(ws[u], du, dQ, np, qoff[u], qdof, A, n, rhs)) return 0;
    }
  }
  return 1;
}

void sw_leaf_recover(double *ws, int du, int dQ, int np, const int *qoff, const int *qdof,
                     const double *u) {
  const double *X = sw_unit_X(ws, du, dQ); /* u_a = A_uu^-1 b_a - X u_Q, into b */
  double *b = sw_unit_b(ws, du, dQ);
  for (int a = 0; a < du; a++) {
    double s = b[a];
    for (int p = 0, c0 = 0; p < np; c0 += qdof[p++])
      for (int c = 0; c < qdof[p]; c++) s -= X[a * dQ + c0 + c] * u[qoff[p] + c];
    b[a] = s;
  }
}

/* pos[a]: the band row of port q's unknown a, the node's three at 6 i and,
 * when the port turns its element e, the element's three at 6 e + 3: rows
 * 6 i - 3 .. 6 i + 2 (e = i - 1) or 6 i .. 6 i + 5 (e = i), within the
 * half-bandwidth (joint_groups.c checks e at setup). */
static void port_rows(const swModel *m, int r, int q, size_t *pos) {
  const size_t i = (size_t)(m->rigid_port_node[q] - m->node_adr[r]);
  for (size_t a = 0; a < 3; a++) pos[a] = 6 * i + a;
  if (!m->rigid_port_rot[q]) return;
  const size_t e = (size_t)(m->rigid_port_elem[q] - m->elem_adr[r]);
  for (size_t a = 0; a < 3; a++) pos[3 + a] = 6 * e + 3 + a;
}

/* Port q's block Pq (lower triangle, rows 6 apart) and right-hand side Rq
 * (lab frame) added to rod r's band A and rhs b through E: as they are on
 * the node's rows, turned by Q on the element's (w = Q w_lab). */
static void add_port_block(const swModel *m, const swData *d, int r, int q, const double *Pq,
                           const double *Rq, double *A, double *b) {
  const int dof = sw_port_dof(m, q);
  double G[36], g[6], Q[9];
  for (int a = 0; a < dof; a++) { /* the lower triangle, both ways */
    for (int c = 0; c <= a; c++) G[6 * a + c] = G[6 * c + a] = Pq[6 * a + c];
    g[a] = Rq[a];
  }
  if (dof == 6) { /* E G E^T and E g, E = diag(I, Q): w = Q w_lab on the element's rows */
    sw_getQ(m, d->Q, m->rigid_port_elem[q], Q);
    for (int a = 0; a < 6; a++) { /* G E^T: columns 3-5 */
      double s[3];
      for (int c = 0; c < 3; c++) {
        s[c] = 0;
        for (int x = 0; x < 3; x++) s[c] += G[6 * a + 3 + x] * Q[3 * c + x];
      }
      for (int c = 0; c < 3; c++) G[6 * a + 3 + c] = s[c];
    }
    for (int c = 0; c < 6; c++) { /* then E on the left: rows 3-5 */
      double s[3];
      for (int a = 0; a < 3; a++) {
        s[a] = 0;
        for (int x = 0; x < 3; x++) s[a] += Q[3 * a + x] * G[6 * (3 + x) + c];
      }
      for (int a = 0; a < 3; a++) G[6 * (3 + a) + c] = s[a];
    }
    double w[3];
    sw_mat_vec(w, Q, g + 3);
    for (int a = 0; a < 3; a++) g[3 + a] = w[a];
  }
  size_t pos[6];
  port_rows(m, r, q, pos);
  for (int a = 0; a < dof; a++) { /* the band's lower triangle */
    b[pos[a]] += g[a];
    for (int c = 0; c < dof; c++)
      if (pos[c] <= pos[a]) *sw_band_at(A, pos[a], pos[c]) += G[6 * a + c];
  }
}

/* Port q's right-hand side Rq (lab frame) added to rod r's b through E,
 * as add_port_block adds it. */
static void add_port_rhs(const swModel *m, const swData *d, int r, int q, const double *Rq,
                         double *b) {
  double g[6];
  memcpy(g, Rq, 6 * sizeof(double));
  if (sw_port_dof(m, q) == 6) {
    double Q[9];
    sw_getQ(m, d->Q, m->rigid_port_elem[q], Q);
    sw_mat_vec(g + 3, Q, Rq + 3);
  }
  size_t pos[6];
  port_rows(m, r, q, pos);
  for (int a = 0; a < sw_port_dof(m, q); a++) b[pos[a]] += g[a];
}

/* Port q's lab velocity change E^T du into Rq (du's rows stride apart). */
static void port_velocity(const swModel *m, const swData *d, int r, int q, const double *du,
                          size_t stride, double *Rq) {
  size_t pos[6];
  port_rows(m, r, q, pos);
  for (int a = 0; a < 3; a++) Rq[a] = du[pos[a] * stride];
  if (!m->rigid_port_rot[q]) return;
  double Q[9];
  const double w[3] = {du[pos[3] * stride], du[pos[4] * stride], du[pos[5] * stride]};
  sw_getQ(m, d->Q, m->rigid_port_elem[q], Q);
  sw_matT_vec(Rq + 3, Q, w); /* w_lab = Q^T w */
}

int sw_band_group_solve(const swModel *m, swData *d, double h, int k, const double *P, double *R) {
  const int r = m->rigid_block_rod[k], q0 = m->rigid_block_port_adr[k];
  double *b, *A = sw_implicit_band_begin(m, d, r, h, &b);
  if (!A) return 0;
  for (int q = q0; q < m->rigid_block_port_adr[k + 1]; q++)
    add_port_block(m, d, r, q, P + (size_t)SW_BAND_PORT * (size_t)(q - q0), R + 6 * (size_t)(q - q0), A, b);
  if (!sw_implicit_band_solve(m, d, r)) return 0;
  for (int q = q0; q < m->rigid_block_port_adr[k + 1]; q++) /* p = E^T du */
    port_velocity(m, d, r, q, b, 1, R + 6 * (size_t)(q - q0));
  sw_implicit_apply(m, d, r, b, 1, h);
  return 1;
}
