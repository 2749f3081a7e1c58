/* sinew_model.h — part of sinew.h (include that): the compiled model, the
 * state and the kernels.
 *
 * Design.  swModel is immutable once sw_compile() returns it; swData is the
 * mutable state of one simulation of it; every kernel has the shape
 * f(const swModel *m, swData *d) and nothing allocates inside a step.  The
 * planar layout of the arrays is described at the top of sinew.h.
 * Implemented in runtime/engine/. */
#ifndef SINEW_MODEL_H
#define SINEW_MODEL_H

#include <stdio.h>
#include "sinew_spec.h"

/* ---- the compiled model (immutable) ---- */
typedef struct {
  /* sizes: nnode, nelem and nvor count real nodes, elements and domains;
   * arrays are sized by stride (see Layout at the top) */
  int nrod, nnode, nelem, nvor, nload, nbc, njoint;
  int nslot;                 /* slots of all rods (= nnode)                  */
  int nslot_elastic;         /* slots [0, nslot_elastic) are elastic rods'   */
  int stride;                /* doubles per plane: nslot + 2 rounded up to a
                                multiple of 8 (64-byte rows; a kernel at the
                                last slot reads two past it)               */
  int chunk;                 /* slots per chunk of the threaded kernels: a
                                multiple of 8 fixed by the model alone, so
                                that any thread count splits every loop and
                                every sum the same way (docs/performance.md) */
  /* options */
  double dt;                 /* time step, s                                 */
  swIntegrator integrator;
  double gravity[3];         /* m/s^2, times gravity_signal(t)               */
  swSignal gravity_signal;   /* dimensionless; constant 1 unless set          */
  /* per rod (nrod) */
  char **rod_name;
  swRodInfo *rod_info;       /* kind, material, where (io/output_attrs.c)     */
  int *rod_nelem;            /* n of each rod                                */
  int *node_adr;             /* first node                                   */
  int *elem_adr;             /* first element                                */
  int *vor_adr;              /* first Voronoi domain                         */
  double *rod_wave_dt;       /* stable dt estimate of each rod, s            */
  swDampingKind *rod_damping;
  /* per node slot; (3) marks three planes of stride */
  double *mass;              /* lumped node mass, kg                         */
  double *weight;            /* the mass gravity acts on: mass, 0 on the
                                nodes of weightless rods; NULL when no rod
                                is weightless (gravity acts on mass)        */
  double *inv_mass;          /* (0 in ghost-free padding)                    */
  double *node_gamma;        /* gamma * Voronoi rest length, kg/s            */
  double *node_decay;        /* analytic damping decay factor                */
  double *node_kick;         /* analytic damping kick length, s              */
  double *x0;                /* (3) initial positions                        */
  /* per element slot (ghost elements: rest lengths 1, stiffness 0) */
  double *rest_len;          /* l^, m                                        */
  double *inv_rest_len;      /* 1 / l^                                       */
  double *radius;            /* m                                            */
  double *shear_stiff;       /* (3) S^ = diag(4GA/3, 4GA/3, EA), N           */
  double *inertia;           /* (3) J^ = rho l^ diag(I1, I2, I3)             */
  double *inv_inertia;       /* (3)                                          */
  double *rest_sigma;        /* (3) rest shear/stretch strain                */
  double *elem_gamma;        /* (3) rotational dissipation, kg m^2/s         */
  double *elem_decay;        /* (3) analytic damping decay factor            */
  double *elem_kick;         /* (3) analytic damping kick length, s          */
  double *Q0;                /* (9) initial directors                        */
  double *clamp_bend;        /* (3) B^ of the element, for clamps            */
  double *elem_ghost;        /* 1 at ghost element slots and padding, else 0  */
  double *elem_variational;  /* 1 on the element and Voronoi slots of rods of
                                SW_LAW_VARIATIONAL, else 0                   */
  double *damp_linear;       /* 1 on the slots of rods with linear damping
                                (loads.c)                                  */
  double *kick_exact;        /* 1 where the kick integrates analytic damping
                                exactly (Verlet, SW_DAMP_ANALYTIC), else 0   */
  /* per Voronoi slot (ghost domains: rest length 1, stiffness 0) */
  double *rest_vor_len;      /* D^, m                                        */
  double *inv_rest_vor_len;  /* 1 / D^                                       */
  double *bend_stiff;        /* (3) B^ = diag(EI1, EI2, GJ), N m^2           */
  double *rest_kappa;        /* (3) 1/m                                      */
  /* loads and boundary conditions */
  swLoadDesc *load;          /* (nload)                                      */
  swBCDesc *bc;              /* (nbc)                                        */
  int bc_slot_order;         /* 1: the conditions' end nodes are in slot order */
  swJointDesc *joint;        /* (njoint), names owned by the model, nodes,
                                stiffness and damping resolved (joint.c)    */
  char **joint_name;         /* (njoint)                                     */
  int *joint_node_a;         /* (njoint)   global node on rod a              */
  int *joint_node_b;         /* (njoint)   global node on rod b, -1 anchored */
  int *joint_elem_a;         /* (njoint)   element of rod a taking couples   */
  int *joint_elem_b;         /* (njoint)   element of rod b, -1 anchored     */
  double *joint_axis_a;      /* (njoint*3) hinge axis, material frame of elem a */
  double *joint_arm_a;       /* (njoint*3) side a's arm, material frame of elem a */
  double *joint_axis_b;      /* (njoint*3) of elem b; lab frame when anchored */
  double *joint_rest_rot;    /* (njoint*9) Q_b Q_a^T at t = 0 (two rods)      */
  double *joint_angle0;      /* (njoint)   hinge angle at t = 0, rad         */
  double *joint_limit_ref;   /* (njoint*9) the limits' reference directions
                                           (joint.c, "Limits")               */
  double *joint_wave_dt;     /* (njoint)   stable dt estimate of each joint  */
  /* kinematic joints (kinematic.c) */
  int nkinematic;
  swKinematicDesc *kinematic; /* (nkinematic), nodes and elements resolved   */
  char **kinematic_name;
  double *kinematic_rot;     /* (nkinematic*9) Q_f Q_l^T at t = 0            */
  double *kinematic_dt;      /* (nkinematic) stable dt of each tie (stability.c) */
  int *kinematic_order;      /* (nkinematic) the joints level by level: a
                                joint after those whose followers it reads
                                (its leader, or a neighbouring follower of
                                its rod); in spec order within a level     */
  int *kinematic_level;      /* (nkinematic_level+1) each level's first entry
                                of kinematic_order, and the end            */
  int nkinematic_level;
  int *joint_implicit;       /* (njoint)   1: linearly implicit (SW_IMEX,
                                           rigid_joint.c): a rigid body on one
                                           side, a body, space or a free
                                           elastic node on the other         */
  int *joint_block;          /* (njoint*2) the block of each side of an
                                           implicit joint, -1 when it holds
                                           still                             */
  int *rigid_block;          /* (nrigid)   the body's block in that system, -1;
                                           numbered group by group           */
  int nrigid_block;          /* members in it: bodies and attachments        */
  int nrigid_attach;         /* attachments: elastic nodes joined to bodies  */
  int nrigid_group;          /* its independent groups: the connected
                                components of the bodies under those joints,
                                one diagonal block of the system each       */
  int *rigid_group_adr;      /* (nrigid_group+1) first block of each group    */
  int *rigid_block_body;     /* (nrigid_block) the body of each block, -1 for
                                           an attachment                     */
  int *rigid_block_node;     /* (nrigid_block) an attachment's node, -1      */
  int *rigid_block_elem;     /* (nrigid_block) an attachment's element, -1   */
  int *rigid_block_rot;      /* (nrigid_block) 1: a joint couples the
                                           attachment's element rotation     */
  int *rigid_block_off;      /* (nrigid_block) its first unknown in its group */
  int *rigid_block_dof;      /* (nrigid_block) its unknowns: 6 (a body, or an
                                           attachment a joint turns), 3 (an
                                           attachment's node alone)          */
  int *rigid_block_env;      /* (nrigid_block) the earliest block joined to
                                           each, or itself: the envelope     */
  int *rigid_block_reach;    /* (nrigid_block) the last block whose envelope
                                           reaches each, or itself           */
  int *rigid_block_rod;      /* (nrigid_block) an implicit rod taking part
                                           through its ports (joint_ports.c), -1 */
  int *rigid_block_port_adr; /* (nrigid_block+1) a rod member's first port   */
  int *rigid_block_leaf;     /* (nrigid_block) an attachment joined only to
                                           one port: that port (eliminated
                                           first, joint_ports.c), else -1     */
  int *rigid_block_partner;  /* (nrigid_block) the leaf eliminated with this
                                           one (a filament's other end), -1   */
  int *rigid_block_fil;      /* (nrigid_block) a leaf's filament when that
                                           filament is in the system, -1      */
  int *rigid_leaf_unit;      /* (nrigid_block*11) a leaf's unit, as
                                           rigid_joint.c's Unit: owner, ro, co,
                                           du, dQ, np, qoff[2], qdof[2], and
                                           its workspace's first double among
                                           its group's leaves' (internal.h)   */
  int nrigid_port;           /* ports: nodes of implicit rods in the system  */
  int *rigid_port_node;      /* (nrigid_port) the node                       */
  int *rigid_port_elem;      /* (nrigid_port) its element                    */
  int *rigid_port_rot;       /* (nrigid_port) 1: a joint turns the element   */
  int *rigid_port_off;       /* (nrigid_port) first unknown in its member    */
  int *joint_port;           /* (njoint*2) the port of a side on an implicit
                                           rod, -1                            */
  int *rod_block;            /* (nrod)     an implicit rod's member, -1      */
  int *fil_system;           /* (nfil or 1) 1: the filament's implicit Hill
                                           damping is solved within that
                                           system, its ends being leaves or
                                           dense members                      */
  int *fil_block;            /* (2*nfil or 2) such a filament whose ends are
                                           dense members: the block of its start
                                           and of its end, -1 when clamped; -1, -1
                                           for the others (joint_groups.c)    */
  int *rigid_group_joint_adr; /* (nrigid_group+1) first entry of each group
                                           in rigid_group_joint              */
  int *rigid_group_joint;    /* (implicit joints) each group's joints, in
                                           joint order                       */
  int *rigid_group_lanes;    /* (nrigid_group or 1) groups of one shape solved
                                           together from this one (at most
                                           SW_GROUP_LANES), 0 inside such a
                                           batch (joint_lanes.c)             */
  int *rigid_group_band;     /* (nrigid_group or 1) 1: the group is one
                                           implicit rod and leaves alone on its
                                           ports, solved in the rod's band with
                                           the leaves eliminated into it
                                           (joint_ports.c, the band path: no
                                           dense block of the ports); 0: its
                                           dense block (joint_groups.c); 2: its
                                           rod members keep only their ports
                                           joined to anything but lone leaves,
                                           the others' leaves eliminated into
                                           the rods' bands (the band path of a
                                           member, joint_ports.c)             */
  int *rigid_block_moff;     /* (nrigid_block) under rigid_group_band 2: its
                                           first unknown in its group (a
                                           leaf's: as rigid_block_off)        */
  int *rigid_block_mdof;     /* (nrigid_block) under 2: its unknowns (a rod
                                           member's: its kept ports')         */
  int *rigid_port_moff;      /* (nrigid_port) under 2: a kept port's first
                                           unknown in its group, or -1 - t for
                                           the group's band port t            */
  int *rigid_port_alias;     /* (nrigid_port) -1, or the earlier kept port
                                           of the same rod member whose
                                           element this port's rotation is
                                           too (joint_alias.c)                */
  /* rods whose geometry changes in time (swell.c): their radius, stiffness,
   * inertia, mass and rest curvature follow signals; what the step reads of
   * these is swData's *_now arrays, which are these model arrays themselves
   * when nswell = 0 */
#define SW_SWELL_TWIST_RADIUS 1   /* w(t) = r(0) / r(t)                      */
#define SW_SWELL_MASS_GROWS 2     /* density fixed: mass ~ g^2               */
  int nswell;
  int *swell_rod;            /* (nswell)   the rods, in rod order            */
  swSignal *swell_sig;       /* (nswell*3) r(t) (m), c(t), w(t) of each      */
  int *swell_flags;          /* (nswell)   SW_SWELL_* bits                   */
  double *swell_range;       /* (nswell*2) least and greatest g = r(t)/r(0)
                                           the stable-dt estimate covers    */
  /* rods whose elasticity is linearly implicit (SW_IMEX, rod_implicit.c) */
  int nimplicit;
  int *rod_implicit;         /* (nrod)     1: the rod asks for it (elastic);
                                           it is kicked so when nimplicit > 0 */
  int *implicit_rod;         /* (nimplicit) the rods, in rod order           */
  size_t *implicit_adr;      /* (nimplicit+1) each one's first double in
                                           swData.implicit_sys              */
  double *implicit_wave_dt;  /* (nimplicit) the rod's explicit elastic bound
                                           (stability.c), s: how long its
                                           factorisation may be kept       */
  /* rigid rods (rigid.c).  A rod with swRodDesc.rigid keeps its nodes and
   * elements in the arrays above and moves as one rigid body b: node
   * x_i = X + R p_i, element frame Q_e = B_e R^T, with R the rotation from the
   * body frame (the principal axes of the inertia tensor) to the lab frame.
   * Body b owns rows [rigid_node_adr[b], +nelem+1) of rigid_p and
   * [rigid_elem_adr[b], +nelem) of rigid_B. */
  int nvariational;          /* rods of SW_LAW_VARIATIONAL (0: rod.c's passes
                                are Gazzola's alone)                        */
  swLaw *rod_law;            /* (nrod)                                       */
  int nrigid;
  int *rod_rigid;            /* (nrod)      rigid body of each rod, -1 elastic */
  int *rigid_rod;            /* (nrigid)    rod of each rigid body            */
  int *rigid_fixed;          /* (nrigid)    1: clamped, never moves           */
  int *rigid_node_adr;       /* (nrigid)    first row in rigid_p              */
  int *rigid_elem_adr;       /* (nrigid)    first row in rigid_B              */
  double *rigid_mass;        /* (nrigid)    M = sum of the node masses, kg    */
  double *rigid_inertia;     /* (nrigid*3)  principal moments about X, kg m^2 */
  double *rigid_X0;          /* (nrigid*3)  initial centre of mass, m         */
  double *rigid_R0;          /* (nrigid*9)  initial R (columns: principal axes) */
  double *rigid_p;           /* (rigid nodes*3)    node in the body frame, m  */
  double *rigid_B;           /* (rigid elements*9) Q_e R, constant            */
  /* muscles (muscle.c) */
  int nmuscle, nfil;
  char **muscle_name;        /* (nmuscle)                                    */
  int *muscle_fil_adr;       /* (nmuscle+1) first filament of each muscle    */
  swSignal *muscle_activation; /* (nmuscle)                                  */
  swSignal *muscle_force;    /* (nmuscle)  prescribed force, N (kind CONST 0 and
                                           muscle_prescribed 0: Hill's law) */
  int *muscle_prescribed;    /* (nmuscle)  1: pulls with muscle_force        */
  const void *muscle_ops;    /* muscle.c's functions (NULL: no muscles)      */
  const void *env_ops;       /* environment.c's (NULL: no environment)       */
  int *fil_rod;              /* (nfil)     rod of each filament              */
  int *fil_passive;          /* (nfil)     1: never contracts                */
  double *fil_area;          /* (nfil)     rest cross-section A_k, m^2       */
  double *fil_fmax;          /* (nfil)     peak isometric force, N           */
  double *fil_l0;            /* (nfil)     rest length, m                    */
  double *fil_tau;           /* (nfil)     activation time constant, s       */
  double *fil_recruit;       /* (nfil*2)   C_{k-1}, C_k: recruitment window  */
  double *fil_hill_a;        /* (nfil)     Hill a / F_qs                     */
  double *fil_v_max;         /* (nfil)     v0 / l0, 1/s                      */
  double *fil_fibres;        /* (nfil)     muscle fibres in the filament     */
  double *fil_elem;          /* (1 plane)  1 at the element slots of filaments */
  int fil_slot_lo, fil_slot_hi; /* the slots [lo, hi) the filaments' nodes span:
                                   the pull's slot loops run over these only */
  int *fil_implicit;         /* (nfil)     SW_FIL_* bits: Hill damping linearly
                                           implicit (SW_IMEX), end nodes held */
  int muscle_implicit;       /* some filament is implicit                    */
  /* via rings (muscle_via.c): one per via point per filament, filament by
   * filament, each filament's in path order */
  int nring;
  int *fil_ring_adr;         /* (nfil+1)   first ring of each filament        */
  int *ring_elem;            /* (nring)    element slot carrying the point, -1: space */
  double *ring_point;        /* (nring*3)  offset from that element's centre in
                                           its material frame; the lab point
                                           when fixed in space, m             */
  double *ring_stiffness;    /* (nring)    N/m                                */
  double *ring_damping;      /* (nring)    N s/m                              */
  double *muscle_via;        /* (nmuscle*SW_MUSCLE_MAX_VIA*3) via points at t = 0 */
  int *muscle_nvia;          /* (nmuscle)                                     */
  /* environments (environment.c): resolved copies of the descriptions, in
   * the order added; rod lists owned by the model (every rod listed when the
   * description said 0) */
  int nground, nfluid, ncontact, nwave, nprobe;
  swGroundDesc *ground;      /* (nground)                                    */
  swFluidDesc *fluid;        /* (nfluid)                                     */
  swContactDesc *contact;    /* (ncontact)                                   */
  swWaveDesc *wave;          /* (nwave)                                      */
  swProbeDesc *probe;        /* (nprobe)                                     */
  int nexpect;
  swExpectDesc *expect;      /* (nexpect) copies, strings owned (expect.c)   */
  /* fluid.c: fluid k's coefficients per element slot, plane k of each
   * (stride entries; 0 off its rods), and the slots [lo, hi) its rods span */
  double *fluid_on;          /* (nfluid planes) times its rod list holds the
                                element (0: not in the fluid)               */
  double *fluid_stokes;      /* (nfluid planes) 4 pi mu / ln(L/r), Pa s (Stokes) */
  double *fluid_cap;         /* (nfluid planes) exposed end-cap silhouette, m^2:
                                pi r^2 / 2 per rod end on it (quadratic)     */
  double *fluid_displaced;   /* (nfluid planes) rho_f pi r^2 l^, kg (buoyancy) */
  int *fluid_span;           /* (2 nfluid) first slot and one past the last  */
  double fluid_dt;           /* step limit of the Stokes drag, s (INFINITY: none) */
  /* wave.c: wave w owns rows [wave_node_adr[w], wave_node_adr[w+1]), one
   * per node of its rod, in the rod's node order */
  int *wave_node_adr;        /* (nwave+1)  first row of each wave             */
  double *wave_s;            /* (rows)     s of the node (from the start, or
                                from the end with `reverse`), m              */
  double *wave_beta;         /* (rows)     beta(s), N m; 0 at the two end nodes */
  double *wave_amp;          /* (rows*2)   beta cos(theta), beta sin(theta),
                                theta = 2 pi s / lambda - phi               */
  /* contact.c: the rows of contact c are [contact_row_adr[c],
   * contact_row_adr[c+1]), its elements rod by rod (each rod once) */
  int *contact_row_adr;      /* (ncontact+1) first row of each contact       */
  int *contact_elem;         /* (rows)     global element                    */
  int *contact_rod;          /* (rows)     its rod                           */
  double *contact_arc;       /* (rows)     rest arc length from the rod's start
                                           to the element's start, m         */
  int contact_maxrows;       /* rows of the largest contact                  */
  int contact_maxanchor;     /* friction anchors the state keeps (0: no
                                contact has friction)                        */
  int contact_nbucket;       /* hash grid buckets, a power of two            */
  /* obstacle.c: rigid obstacles.  A fixed one's centre and axes are in the
   * lab; a carried one's in the material frame of its carrier element, its
   * centre from the carrier node (a joint's arm).  Rods are cut into chunks
   * of SW_OBSTACLE_CHUNK elements for the broad phase: chunk c of rod r is
   * obstacle_chunk_adr[r] + c. */
  int nobstacle;
  swObstacleDesc *obstacle;  /* (nobstacle)                                  */
  int *obstacle_node;        /* (nobstacle) carrier's node slot (-1: fixed)  */
  int *obstacle_elem;        /* (nobstacle) carrier's element slot (-1)      */
  double *obstacle_arm;      /* (nobstacle*3) centre, m (see above)          */
  double *obstacle_axes;     /* (nobstacle*9) rows: the shape's three axes   */
  double *obstacle_extent;   /* (nobstacle*3) half sizes of the shape's box
                                in its own frame (INFINITY along a cylinder) */
  int *obstacle_chunk_adr;   /* (nrod+1) first chunk of each rod             */
  int obstacle_nchunk;       /* chunks of all rods                           */
  int obstacle_maxcontact;   /* contact records the state keeps              */
  int has_gravity;
  int has_damping;
  int has_exact_kick;        /* some rod's kick integrates its damping exactly */
} swModel;

/* One element touching one obstacle (obstacle.c).  The normal force acts
 * along n at the point s of the element's segment; with friction, the
 * tangential force `friction` acts at the rod's anchored surface point (its
 * centreline point s_anchor plus an arm in the element's frame, with the
 * couple), tied to the obstacle's point `anchor` (in the obstacle's frame). */
typedef struct {
  int obstacle, elem;        /* obstacle index, element slot                 */
  double s;                  /* the point's place on the segment, 0..1      */
  double depth;              /* penetration r - D, m                         */
  double normal[3];          /* out of the obstacle, lab                     */
  double force;              /* normal force on the element, N (>= 0)       */
  double anchor[3];          /* the obstacle's anchor point, its frame, m    */
  double s_anchor;           /* the rod anchor's centreline place, 0..1     */
  double friction[3];        /* tangential force on the element, lab, N      */
  int stuck;                 /* 1 while the anchor holds (0: slipping or no
                                friction)                                    */
} swObstacleContact;
#define SW_OBSTACLE_ANCHOR_ROW 9   /* key, s, rod's arm (3), anchor (3), stuck */
#define SW_CONTACT_ANCHOR_ROW 10   /* key, s, t, arm a (3), arm b (3), stuck (contact.c) */

/* ---- the state (mutable) ---- */
typedef struct {
  double time;
  long step;
  int threads;               /* OpenMP threads of a step (sw_set_threads; 1) */
  void *team;                /* their barrier (integrate.c)                  */
  int team_size;             /* threads of the step running now (1 outside)  */
  double work;               /* work done on the rods by loads, boundaries
                                and dissipation since t = 0, J            */
  /* state, per slot in the layout of the model: x, v (3 planes, node
   * slots), Q (9 planes), omega (3 planes, element slots) */
  double *x, *v, *Q, *omega;
  /* Derived and accumulated per slot.  The dilatation is kept with the
   * state (the drift and the kick use it); the others are scratch of the
   * step: they hold the current state's values after sw_internal_loads()
   * (which sw_energy and sw_data_new call), not after sw_steps(), since a
   * one-thread step may keep only a window of them (integrate.c, the fused
   * sweep). */
  double *dilatation;        /* e = l / l^ (1 at ghosts)                     */
  /* The shortest each element has been: its least dilatation at the
   * stability checks (every 8 steps) since sw_reset, and when; what the
   * report of an unstable run quotes (stability.c).  Per element slot. */
  double *shortest;          /* least e seen (1 at ghosts)                   */
  double *shortest_time;     /* the time of the check that saw it, s         */
  /* The geometry the step reads (swell.c): the model's own arrays when no
   * rod swells (m->nswell = 0), else copies owned here whose slots on the
   * swelling rods follow time (set by sw_swell_update at each kick). */
  const double *radius_now, *shear_now, *bend_now, *kappa0_now; /* as the model's */
  const double *inertia_now, *inv_inertia_now, *mass_now, *inv_mass_now, *weight_now;
  double *swell_own;         /* the copies' storage (NULL: none)             */
  double *swell_g;           /* (nswell) g = r(t)/r(0) at swell_time        */
  double swell_time;         /* when they were last set (NAN: never)        */
  /* derived per element slot */
  double *length;            /* current length l                             */
  double *sigma;             /* (3) shear/stretch strain, material           */
  double *stress;            /* (3) internal force n = S^ (s-s0) / e (Gazzola)
                                or S^ (s-s0) (variational), material        */
  /* derived per Voronoi slot */
  double *vor_dilatation;
  double *kappa;             /* (3) curvature/twist, material frame          */
  double *couple;            /* (3) the bending couple as Delta^h applies it:
                                B^ (k - k0) / eps^3 (Gazzola), or
                                (I + beta [phi]x^2) B^ (k - k0) (variational,
                                rod.c)                                      */
  /* accumulated loads */
  double *force;             /* (3) total force on nodes, lab                */
  double *torque;            /* (3) total couple on elements, material frame */
  double *ext_force;         /* (3) external force, lab                      */
  double *ext_torque;        /* (3) external couple, material frame          */
  /* rod.c's scratch between its two passes: Q^T n of each element (lab) and
   * half the transport couple kappa x c D^ of each domain (3 planes each) */
  double *scratch_f, *scratch_h;
  /* per-slot scratch of integrate.c and rod.c: scratch_flag (1 plane) holds
   * the rod pass's bent-domain flags, then the kick's work per slot;
   * scratch_phi (8 planes) the drift's rotation vectors (the first 3, which
   * muscle.c borrows while the loads are evaluated and the one-thread sweep
   * uses for its bent-domain flags) and, in the other 5, the values its
   * loops pass on within a block (engine/drift.h, drift_frames_block) */
  double *scratch_flag, *scratch_phi;
  /* one partial sum per chunk (the kick's work), added in chunk order, and
   * the work of each boundary condition in a kick (nbc) */
  double *chunk_sum, *bc_work;
  /* 1 once boundary condition k has let its end go (its `until`), else 0
   * (nbc): state, saved by --restart */
  double *bc_free;
  int kick_pending;          /* integrate.c: a kick whose work and rigid part */
  double kick_h;             /* the next drift's leader adds (its h)          */
  int held;                  /* integrate.c: the last step's trailing half
                                drift is held back (sw_steps_held)           */
  int whole;                 /* between sw_whole_begin and sw_whole_end       */
  double *hold;              /* what the half drift of sw_whole_begin moves,
                                kept for sw_whole_end                        */
  /* joint.c: each joint's loads, evaluated in parallel and applied in joint
   * order (SW_JOINT_ROW doubles per joint) */
  double *joint_scratch;
  /* joints, updated with each force evaluation */
  double *joint_force;       /* (njoint*3) force of the joint on rod a, lab, N */
  double *kinematic_force;   /* (nkinematic*3) force on the follower node, lab, N */
  double *kinematic_turn;    /* (nkinematic*3) the follower's w as last set (kinematic.c) */
  double *kinematic_delta;   /* (nkinematic*3) the last imposition's small turn, rad (kinematic.c) */
  double *kinematic_work;    /* (nkinematic) each joint's part of a pass's work,
                                summed in kinematic_order (kinematic.c; scratch) */
  double *joint_angle;       /* (njoint)  hinge angle, rad (0 for others)     */
  double *joint_limit_torque; /* (njoint*3) the limit's couple on rod a's
                                 element, lab, N m (0 inside the limits)     */
  /* rigid bodies (rigid.c), the state the nodes and elements of a rigid rod
   * are set from after every drift and kick */
  double *rigid_X;           /* (nrigid*3) centre of mass, lab, m              */
  double *rigid_V;           /* (nrigid*3) its velocity, m/s                   */
  double *rigid_R;           /* (nrigid*9) rotation body -> lab, row-major     */
  double *rigid_L;           /* (nrigid*3) angular momentum about X, lab, kg m^2/s */
  double *rigid_load;        /* (nrigid*6) a kick's force and torque on each body */
  double *rigid_sys;         /* the implicit joints' system (rigid_joint.c)    */
  double *rigid_lanes;       /* its batches of groups, interleaved (joint_lanes.c) */
  double *implicit_sys;      /* the implicit rods' banded systems (rod_implicit.c) */
  double *rigid_omega;       /* (nrigid*3) angular velocity, lab, rad/s        */
  /* muscles, updated with each force evaluation (activation once a step) */
  double *fil_activation;    /* (nfil)    a_k in [0, 1]                        */
  double *fil_stretch;       /* (nfil)    eta = l / l0                          */
  double *fil_rate;          /* (nfil)    strain rate dl/dt / l0, 1/s           */
  double *fil_tension;       /* (nfil)    T_k, N                                */
  double *fil_sys;           /* (nfil*8)  a filament in the joints' system:
                                           T without its ends' part, c', and
                                           b at its start and end nodes      */
  double *ring_row;          /* (nring*SW_RING_ROW) each ring's contact and
                                           load, last evaluation (muscle_via.c) */
  double *ring_imp;          /* (nring*SW_RING_IMP) an implicit ring's part of
                                           the kick's solve, this evaluation
                                           (via_implicit.c; not saved)       */
  /* environments, updated with each force evaluation */
  /* contact.c: the last evaluation's figures, and the hash grid's scratch */
  int contact_pairs;         /* element pairs in contact                     */
  double contact_max_overlap; /* deepest overlap r_a + r_b - D, m (0: none)  */
  int *contact_cell;         /* (contact_maxrows*3) cell of each row         */
  int *contact_bucket;       /* (contact_maxrows)   its bucket               */
  int *contact_sorted;       /* (contact_maxrows)   rows by bucket           */
  int *contact_start;        /* (contact_nbucket+1) first sorted row of each bucket */
  int *contact_sorted_cell;  /* (contact_maxrows*3) cell of each sorted row  */
  unsigned long long *contact_occupied; /* (contact_nbucket/64+1) bit set: bucket not empty */
  /* the friction's anchors (contact.c): [0] the rows in use, then rows of
   * SW_CONTACT_ANCHOR_ROW: key (the pair's two rows), s and t of the anchor
   * points on the segments of the lower and higher row's elements, the
   * arms from there to the anchored surface points (each in its element's
   * frame), stuck; in the order of the key.
   * State: the checkpoint keeps it; `_old` is scratch. */
  double *contact_anchor;    /* (1 + contact_maxanchor*SW_CONTACT_ANCHOR_ROW) */
  double *contact_anchor_old;
  int contact_stuck;         /* pairs of the last evaluation held still      */
  int contact_slipping;      /* and those slipping                           */
  /* rigidity.c: per rod, its largest stretch or shear strain |sigma -
   * sigma0| and its largest bend beyond rest summed along it (rad) over the
   * frames written (NaN: a rod that cannot be held rigid, not sampled) */
  double *rod_strain_peak;   /* (nrod)                                       */
  double *rod_bend_peak;     /* (nrod)                                       */
  double *muscle_spread_peak; /* (nmuscle) largest spread of its filaments'
                                motion over its length (NaN: one filament,
                                or filaments of unequal element counts)     */
  long rigidity_frames;      /* frames sampled                               */
  long friction_full;        /* touching pairs, over the run's evaluations,
                                left frictionless because the anchor table
                                (contact.c's or obstacle.c's) was full;
                                sw_run warns of them (not saved: a
                                continued run counts its own)            */
  /* obstacle.c: the last evaluation's contacts (the record a friction law
   * will keep its tangential anchor in), figures, and scratch */
  swObstacleContact *obstacle_contact; /* (obstacle_maxcontact)              */
  int obstacle_contacts;     /* contacts of the last evaluation (all, also
                                those beyond the records' room)             */
  double obstacle_max_depth; /* deepest penetration r - D, m (0: none)      */
  long obstacle_tests;       /* element-obstacle pairs the narrow phase saw  */
  /* the friction's anchors (obstacle.c): [0] the rows in use, then rows of
   * SW_OBSTACLE_ANCHOR_ROW: key (obstacle, element), s, the arm from the
   * rod's centreline point there to its anchored surface point (the
   * element's material frame), the obstacle's point (its frame), stuck; in
   * the order of the key.  State: the
   * checkpoint keeps it; `_old` is the previous evaluation's, scratch. */
  double *obstacle_anchor;   /* (1 + obstacle_maxcontact*SW_OBSTACLE_ANCHOR_ROW) */
  double *obstacle_anchor_old;
  int obstacle_stuck;        /* contacts of the last evaluation held still   */
  int obstacle_slipping;     /* and those slipping                           */
  double *obstacle_box;      /* ((obstacle_nchunk+nrod)*6) lo, hi of each
                                chunk's elements with their radii, then of
                                each rod's                                  */
  /* probe.c: the centre-of-mass samples (t, X) that mean-velocity probes
   * difference, a ring of SW_PROBE_RING per probe (probe.c) */
  double *probe_ring;        /* (nprobe*SW_PROBE_RING*4) t, X of each sample  */
  int *probe_head;           /* (nprobe)  slot of the oldest sample           */
  int *probe_count;          /* (nprobe)  samples held                        */
  /* instability report, filled when sw_step returns SW_EUNSTABLE */
  char error[1024];
} swData;

/* ---- access to the planar arrays (see Layout at the top) ---- */
/* Component k of slot i of a per-slot array with planes of m->stride. */
#define SW_AT(m, a, i, k) ((a)[(size_t)(k) * (size_t)(m)->stride + (size_t)(i)])
static inline void sw_get3(const swModel *m, const double *a, int i, double out[3]) {
  out[0] = SW_AT(m, a, i, 0); out[1] = SW_AT(m, a, i, 1); out[2] = SW_AT(m, a, i, 2);
}
static inline void sw_set3(const swModel *m, double *a, int i, const double in[3]) {
  SW_AT(m, a, i, 0) = in[0]; SW_AT(m, a, i, 1) = in[1]; SW_AT(m, a, i, 2) = in[2];
}
static inline void sw_add3(const swModel *m, double *a, int i, const double in[3]) {
  SW_AT(m, a, i, 0) += in[0]; SW_AT(m, a, i, 1) += in[1]; SW_AT(m, a, i, 2) += in[2];
}
/* Frame of slot i as a row-major 3x3 matrix (rows d1, d2, d3). */
static inline void sw_getQ(const swModel *m, const double *Q, int i, double out[9]) {
  for (int k = 0; k < 9; k++) out[k] = SW_AT(m, Q, i, k);
}
static inline void sw_setQ(const swModel *m, double *Q, int i, const double in[9]) {
  for (int k = 0; k < 9; k++) SW_AT(m, Q, i, k) = in[k];
}

swModel *sw_compile(const swSpec *s, char *err, size_t errlen);
void sw_model_free(swModel *m);
swData *sw_data_new(const swModel *m);
void sw_data_free(swData *d);
void sw_reset(const swModel *m, swData *d);
/* The deepest penetration r - D of obstacle k's rods at t = 0, m (<= 0:
 * none touch it), and where: runtime rod id and element of that rod
 * (obstacle.c; the compiler refuses a rod laid inside an obstacle). */
double sw_obstacle_start_depth(const swModel *m, int k, int *rod, int *elem);

/* Kernels. */
void sw_internal_loads(const swModel *m, swData *d);   /* rod.c: strains and internal loads */
void sw_external_loads(const swModel *m, swData *d);   /* loads.c       */
void sw_apply_bc_velocity(const swModel *m, swData *d, double t); /* boundary.c */
int sw_step(const swModel *m, swData *d);              /* integrate.c   */
int sw_steps(const swModel *m, swData *d, long k);     /* k whole steps  */
/* A run's steps in calls of any length, bitwise those of one call (integrate.c,
 * "Held steps").  sw_steps_held is sw_steps with the last step's trailing
 * half drift held back: d->step counts that step, d->held is 1 and the
 * positions are half a step behind it; the next sw_steps or sw_steps_held
 * fuses the held half drift with its own first one, as one call would.
 * Between sw_whole_begin and sw_whole_end the state is the whole step, for
 * reading (a frame, an expectation's sample); sw_whole_begin runs the step's
 * end (the stability check) and returns its status.  sw_settle makes a held
 * state whole for good.  On a whole state the three do nothing. */
int sw_steps_held(const swModel *m, swData *d, long k);
int sw_whole_begin(const swModel *m, swData *d);
void sw_whole_end(const swModel *m, swData *d);
int sw_settle(const swModel *m, swData *d);
/* The time of the steps taken, d->step dt when held, else d->time. */
double sw_time(const swModel *m, const swData *d);
/* Threads a step runs on (OpenMP; 1 by default).  The result does not depend
 * on n: the kernels split their loops into the model's fixed chunks and add
 * partial sums in chunk order.  Returns the count set (n < 1 counts as 1). */
int sw_set_threads(swData *d, int n);                  /* integrate.c   */
int sw_check_finite(const swModel *m, swData *d);      /* stability.c   */
/* Sets the motion of rigid rod `rod` (rigid.c): centre-of-mass velocity V and
 * angular velocity omega, lab frame; node and element velocities follow.
 * Returns SW_OK, or SW_EUSAGE if the rod is not rigid or is clamped. */
int sw_rigid_set_motion(const swModel *m, swData *d, int rod, const double V[3],
                        const double omega[3]);

/* The row of probe p for the current state (probe.c; what /probes/NAME
 * gets).  A mean-velocity probe also records the sample it differences
 * later, so call it once per frame, in time order (sw_reset forgets them). */
void sw_probe_measure(const swModel *m, swData *d, int p, double out[3]);

/* Energies (J): kinetic (translational + rotational), elastic
 * (bend/twist + shear/stretch), and the work done on the system. */
void sw_energy(const swModel *m, swData *d, double out[3]);

/* Stable time step estimates, s (stability.c). */
double sw_stable_dt(const swModel *m);
double sw_stable_dt_rod(const swModel *m, int rod);
double sw_stable_dt_joint(const swModel *m, int joint);
/* The implicit rods' kicks since sw_reset, summed over the rods: those that
 * assembled and factored the rod's system afresh and those that kept an
 * earlier factorisation (rod_implicit.c, "Keeping a factorisation"). */
void sw_implicit_counts(const swModel *m, const swData *d, double *fresh, double *kept);

/* The record of one run's expectations (created before the run, sampled by
 * sw_run through swRunOptions.expect, reported after it). */
typedef struct swExpectRun swExpectRun;
swExpectRun *sw_expect_run_new(const swModel *m);
void sw_expect_run_free(swExpectRun *r);
/* Writes the report to f (quiet: the failures only); returns how many
 * expectations failed (those the run did not reach are listed, not counted). */
int sw_expect_report(const swModel *m, const swExpectRun *r, FILE *f, const char *prog,
                     int quiet);

#endif
