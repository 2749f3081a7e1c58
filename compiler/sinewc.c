/* sinewc.c — the compiler's command line.
 *
 *   sinewc MODEL.sinew -o SIM           compile to a standalone simulator
 *   sinewc MODEL.sinew --emit-c -o F.c  write the generated C only
 *   sinewc --check MODEL.sinew          parse and check; diagnostics only
 *   sinewc ... --let NAME=VALUE         a top-level let of the model takes
 *                                       VALUE (a number with its unit, or
 *                                       true or false) instead of its own
 *   sinewc --eval-height MODEL.sinew    the compiler's own height and gradient of
 *                                       each terrain at "x y" lines of stdin
 *   sinewc --eval-signal MODEL.sinew    the compiler's own value of each of the
 *                                       model's signals at "t" lines of stdin
 *
 * Design.  Read the model, check it (every error of every file reported),
 * let the runtime validate the scene and estimate its stable step, then
 * print the C and, for -o, hand it to the system C compiler with the
 * runtime's header and library.  The C compiler is run with posix_spawn and
 * an argument vector, never through a shell, so no file name can become a
 * command.  The runtime is looked up next to the sinewc executable: the
 * source tree (bin/../runtime/include, bin/../build) or an installation
 * (bin/../include/sinew, bin/../lib); SINEW_RUNTIME overrides both with
 * one directory holding the public header (sinew.h and the parts it
 * includes, runtime_header below) and libsinewrt.a.  Exit codes
 * as docs/compiler.md states them:
 * 0 ok, 1 model error, 2 usage error, 4 I/O error.
 */
#include <ctype.h>
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <spawn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "diag.h"
#include "gen.h"
#include "sema.h"

#ifndef SW_RT_CFLAGS
#define SW_RT_CFLAGS ""
#endif
#ifndef SW_RT_LIBS
#define SW_RT_LIBS "-lhdf5 -lgsl -lgslcblas -lm"
#endif
/* mpicc's libraries when sinew was built with MPI ("" without) */
#ifndef SW_RT_MPI_LIBS
#define SW_RT_MPI_LIBS ""
#endif

/* the linker flag, "-fuse-ld=gold" where the compiler had it when sinew
 * was built (scripts/sim_linker.sh: twice as fast as GNU ld here), and
 * that compiler: another $CC gets no flag it may not take */
#ifndef SW_RT_LDFLAGS
#define SW_RT_LDFLAGS ""
#endif
#ifndef SW_RT_CC
#define SW_RT_CC "cc"
#endif

extern char **environ;

static const char *progname = "sinewc";

static void usage(FILE *out) {
  fprintf(out,
          "usage: sinewc MODEL.sinew -o SIM           compile a model to a simulator\n"
          "       sinewc MODEL.sinew --emit-c -o F.c  write the generated C only\n"
          "       sinewc --check MODEL.sinew          parse and check only\n"
          "options:\n"
          "  -o FILE      output file (the simulator, or the C file with --emit-c)\n"
          "  --emit-c     write C instead of compiling it\n"
          "  --check      report diagnostics and write nothing\n"
          "  --portable   build a simulator for any x86-64 machine (-O3, the baseline\n"
          "               instruction set, libsinewrt-portable.a); without it the\n"
          "               simulator is built at -O3 for this machine's CPU\n"
          "  --no-mpi     leave MPI out of the simulator: it sweeps and optimises on\n"
          "               one machine only (by default MPI is linked in when sinew\n"
          "               was built where mpicc exists, for mpirun -np N SIM ...)\n"
          "  -Werror      treat warnings as errors\n"
          "  --let NAME=VALUE  give the top-level let NAME of the model this value\n"
          "               instead of its own, when compiling (repeatable): a number\n"
          "               with its unit in the let's dimension (--let n=10,\n"
          "               --let x=3cm), or true or false for a let that holds one;\n"
          "               recorded in the generated C and in model_source\n"
          "  --eval-height  check, then print each terrain's height and gradient at\n"
          "               the points \"x y\" (m) read from stdin: \"k x y h dh/dx dh/dy\"\n"
          "               (the compiler's evaluator; tests compare it with the C)\n"
          "  --eval-signal  check, then print each signal NAME(t) of the model at the\n"
          "               times t (s) read from stdin: \"k name t value\" (SI units)\n"
          "  --version    print the version\n"
          "  --help       this text\n"
          "environment: SINEW_PATH (import search path), CC (C compiler, default cc),\n"
          "             SINEW_RUNTIME: one directory holding the runtime, instead of\n"
          "               the one found next to sinewc: its header sinew.h and the\n"
          "               parts sinew.h includes (sinew_spec.h, sinew_model.h,\n"
          "               sinew_io.h, sinew_program.h), and its library libsinewrt.a\n"
          "               (libsinewrt-portable.a for --portable; sinewrt_mpi.o, if\n"
          "               there, is linked for MPI studies unless --no-mpi)\n");
}

/* The runtime's public header: sinew.h and the parts it includes
 * (runtime/include/, installed in PREFIX/include/sinew), all of which must
 * sit in the one directory the generated C is compiled against. */
static const char *const runtime_header[] = {"sinew.h", "sinew_spec.h", "sinew_model.h",
                                             "sinew_io.h", "sinew_program.h"};
enum { NHEADER = sizeof runtime_header / sizeof runtime_header[0] };

static int exists(const char *path) {
  struct stat st;
  return stat(path, &st) == 0;
}

/* Directory of the runtime's header and of its library. */
static int find_runtime(char *inc, char *lib, size_t len) {
  const char *env = getenv("SINEW_RUNTIME");
  if (env && *env) {
    snprintf(inc, len, "%s", env);
    snprintf(lib, len, "%s", env);
    return 1;
  }
  char exe[PATH_MAX];
  ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
  if (n <= 0) return 0;
  exe[n] = 0;
  char *slash = strrchr(exe, '/');
  if (!slash) return 0;
  *slash = 0;   /* exe is now the bin directory */
  static const char *layouts[][2] = {
    {"/../runtime/include", "/../build"}, /* source tree: bin/sinewc */
    {"/../../runtime/include", "/.."},    /* source tree: build/asan/sinewc */
    {"/../include/sinew", "/../lib"},     /* make install */
  };
  for (size_t i = 0; i < sizeof layouts / sizeof layouts[0]; i++) {
    char h[PATH_MAX + 32], l[PATH_MAX + 32];
    snprintf(h, sizeof h, "%s%s/sinew.h", exe, layouts[i][0]);
    snprintf(l, sizeof l, "%s%s/libsinewrt.a", exe, layouts[i][1]);
    if (exists(h) && exists(l)) {
      snprintf(inc, len, "%s%s", exe, layouts[i][0]);
      snprintf(lib, len, "%s%s", exe, layouts[i][1]);
      return 1;
    }
  }
  return 0;
}

/* Split a flags string on blanks into argv (the flags are ours, from pkg-config). */
static int split_flags(char *s, char **argv, int max) {
  int n = 0;
  for (char *tok = strtok(s, " \t\n"); tok && n < max; tok = strtok(NULL, " \t\n")) argv[n++] = tok;
  return n;
}

/* Builds the simulator: for this machine's CPU (-O3 -march=native, with the
 * runtime library `make` built the same way), or, with `portable`, for any
 * x86-64 machine (-O3, the compiler's baseline instruction set, and
 * libsinewrt-portable.a).  docs/benchmarks.md has what each costs. */
static int run_cc(const char *csrc, const char *out, int portable, int no_mpi) {
  char inc[PATH_MAX], lib[PATH_MAX];
  if (!find_runtime(inc, lib, sizeof inc)) {
    fprintf(stderr, "%s: cannot find the runtime (sinew.h with its parts, and libsinewrt.a) "
            "next to this executable; set SINEW_RUNTIME to their directory (sinewc --help)\n",
            progname);
    return 4;
  }
  /* a missing part would otherwise surface as the C compiler failing on
   * the generated code, which reads as a bug in sinewc */
  for (int i = 0; i < NHEADER; i++) {
    char part[PATH_MAX + 32];
    snprintf(part, sizeof part, "%s/%s", inc, runtime_header[i]);
    if (exists(part)) continue;
    fprintf(stderr, "%s: cannot find the runtime's header '%s' (sinew.h and its parts ", progname,
            part);
    for (int j = 1; j < NHEADER; j++)
      fprintf(stderr, "%s%s", runtime_header[j], j + 1 < NHEADER ? ", " : "");
    fprintf(stderr, " belong in one directory)\n");
    return 4;
  }
  const char *cc = getenv("CC");
  if (!cc || !*cc) cc = "cc";
  char incflag[PATH_MAX + 4], libpath[PATH_MAX + 32];
  snprintf(incflag, sizeof incflag, "-I%s", inc);
  snprintf(libpath, sizeof libpath, "%s/%s", lib, portable ? "libsinewrt-portable.a" : "libsinewrt.a");
  if (!exists(libpath)) {
    fprintf(stderr, "%s: cannot find the runtime library '%s'%s\n", progname, libpath,
            portable ? " (built by `make` beside libsinewrt.a)" : "");
    return 4;
  }
  char cflags[1024], libs[1024], mpilibs[1024], mpiobj[PATH_MAX + 32];
  snprintf(cflags, sizeof cflags, "%s", SW_RT_CFLAGS);
  snprintf(libs, sizeof libs, "%s", SW_RT_LIBS);
  snprintf(mpilibs, sizeof mpilibs, "%s", SW_RT_MPI_LIBS);
  /* the study's MPI transport, built by `make` beside the library where
   * mpicc exists (runtime/study/study_mpi.c) */
  snprintf(mpiobj, sizeof mpiobj, "%s/sinewrt_mpi.o", lib);
  int mpi = !no_mpi && mpilibs[0] && exists(mpiobj);
  char *argv[128];
  int n = 0;
  argv[n++] = (char *)cc;
  argv[n++] = "-std=c11";
  argv[n++] = "-O3";
  if (!portable) argv[n++] = "-march=native";
  argv[n++] = "-fno-math-errno";
  argv[n++] = "-fopenmp"; /* the runtime's threads (libgomp) */
  if (SW_RT_LDFLAGS[0] && !strcmp(cc, SW_RT_CC)) argv[n++] = SW_RT_LDFLAGS;
  argv[n++] = incflag;
  n += split_flags(cflags, argv + n, 32);
  argv[n++] = "-x";
  argv[n++] = "c";
  argv[n++] = (char *)csrc;
  argv[n++] = "-x";
  argv[n++] = "none";
  if (mpi) argv[n++] = mpiobj;
  argv[n++] = libpath;
  n += split_flags(libs, argv + n, 32);
  if (mpi) n += split_flags(mpilibs, argv + n, 24);
  argv[n++] = "-o";
  argv[n++] = (char *)out;
  argv[n] = NULL;
  pid_t pid;
  int rc = posix_spawnp(&pid, cc, NULL, NULL, argv, environ);
  if (rc != 0) {
    fprintf(stderr, "%s: cannot run the C compiler '%s': %s\n", progname, cc, strerror(rc));
    return 4;
  }
  int status;
  while (waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) {
      fprintf(stderr, "%s: lost the C compiler: %s\n", progname, strerror(errno));
      return 4;
    }
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    fprintf(stderr, "%s: the C compiler '%s' failed on the generated code (a bug in sinewc: "
            "please report it with the model)\n", progname, cc);
    return 4;
  }
  return 0;
}

/* --eval-height: "k x y h dh/dx dh/dy" for every terrain k (its index among
 * the grounds) at every "x y" line of stdin, with params at their defaults. */
static void print_heights(const swScene *sc) {
  double x, y;
  while (scanf("%lf %lf", &x, &y) == 2)
    for (int k = 0; k < sc->nground; k++) {
      if (!sc->ground[k].height) continue;
      double grad[2];
      double h = sema_height_eval(x, y, grad, sc->ground[k].height);
      printf("%d %.17g %.17g %.17g %.17g %.17g\n", k, x, y, h, grad[0], grad[1]);
    }
}

/* --eval-signal: "k name t value" for every signal k of the model at every
 * "t" line of stdin, with params at their defaults. */
static void print_signals(const swScene *sc) {
  double t;
  while (scanf("%lf", &t) == 1)
    for (int k = 0; k < sc->nsignal; k++)
      printf("%d %s %.17g %.17g\n", k, sc->signal[k]->name, t,
             sema_signal_eval(t, sc->signal[k]));
}

/* --let NAME=VALUE into o: VALUE a number with its unit, read with the
 * runtime's parser of quantities (the one --set uses), or true or false.
 * Returns 0, or 2 after a one-line message. */
static int read_let(const char *arg, const swLetOverride *given, int ngiven, swLetOverride *o) {
  if (!arg) {
    fprintf(stderr, "%s: --let needs NAME=VALUE\n", progname);
    return 2;
  }
  const char *eq = strchr(arg, '=');
  if (!eq || eq == arg) {
    fprintf(stderr, "%s: --let: expected NAME=VALUE, got '%s'\n", progname, arg);
    return 2;
  }
  size_t len = (size_t)(eq - arg);
  int name_ok = arg[0] == '_' || (arg[0] >= 'a' && arg[0] <= 'z') || (arg[0] >= 'A' && arg[0] <= 'Z');
  for (size_t i = 1; i < len; i++)
    name_ok &= arg[i] == '_' || (arg[i] >= 'a' && arg[i] <= 'z') || (arg[i] >= 'A' && arg[i] <= 'Z') ||
               (arg[i] >= '0' && arg[i] <= '9');
  if (!name_ok) {
    fprintf(stderr, "%s: --let: '%.*s' is not a name (letters, digits and _)\n", progname,
            (int)len, arg);
    return 2;
  }
  memset(o, 0, sizeof *o);
  o->name = strndup(arg, len);
  o->text = arg;
  if (!o->name) abort();
  for (int i = 0; i < ngiven; i++)
    if (!strcmp(given[i].name, o->name)) {
      fprintf(stderr, "%s: --let %s is given twice ('%s' and '%s')\n", progname, o->name,
              given[i].text, arg);
      return 2;
    }
  const char *value = eq + 1;
  o->truth = !strcmp(value, "true") ? 1 : !strcmp(value, "false") ? 0 : -1;
  if (o->truth >= 0) return 0;
  char err[256];
  if (sw_parse_quantity(value, &o->value, o->dim.e, err, sizeof err) == 0 && isfinite(o->value))
    return 0;
  if (isalpha((unsigned char)value[0])) {   /* a word, not a number */
    static const char *const truth[] = {"true", "false"};
    const char *near = diag_suggest(value, truth, 2);
    fprintf(stderr, "%s: --let %s: expected a number with its unit, or true or false, got "
            "'%s'%s%s%s\n", progname, o->name, value, near ? " (did you mean '" : "",
            near ? near : "", near ? "'?)" : "");
  } else if (!err[0])
    fprintf(stderr, "%s: --let %s: '%s' is out of range\n", progname, o->name, value);
  else fprintf(stderr, "%s: --let %s: %s\n", progname, o->name, err);
  return 2;
}

/* What the command line asks for. */
typedef struct {
  const char *model, *out;
  int emit_c, check, werror, eval_height, eval_signal, portable, no_mpi;
  swLetOverride *lets;        /* (nlets) --let, in the order given          */
  int nlets;
} swOptions;

/* The command line into o.  Returns -1 to go on, or the exit code: 0 after
 * --help or --version, 2 after a usage error (its message printed). */
static int parse_args(int argc, char **argv, swOptions *o) {
  for (int i = 1; i < argc; i++) {
    const char *a = argv[i];
    if (!strcmp(a, "--let")) {
      int rc = read_let(++i < argc ? argv[i] : NULL, o->lets, o->nlets, &o->lets[o->nlets]);
      if (o->lets[o->nlets].name) o->nlets++;
      if (rc) return rc;
    } else if (!strcmp(a, "-o")) {
      if (++i >= argc) {
        fprintf(stderr, "%s: -o needs a file name\n", progname);
        return 2;
      }
      o->out = argv[i];
    } else if (!strcmp(a, "--emit-c")) o->emit_c = 1;
    else if (!strcmp(a, "--check")) o->check = 1;
    else if (!strcmp(a, "--portable")) o->portable = 1;
    else if (!strcmp(a, "--no-mpi")) o->no_mpi = 1;
    else if (!strcmp(a, "--eval-height")) o->check = o->eval_height = 1;
    else if (!strcmp(a, "--eval-signal")) o->check = o->eval_signal = 1;
    else if (!strcmp(a, "-Werror")) o->werror = 1;
    else if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
      usage(stdout);
      return 0;
    } else if (!strcmp(a, "--version")) {
      printf("sinewc %s\n", SW_VERSION);
      return 0;
    } else if (a[0] == '-' && a[1]) {
      static const char *const opts[] = {"-o", "--emit-c", "--check", "-Werror", "--help",
                                         "--version", "--eval-height", "--eval-signal", "--portable", "--let",
                                         "--no-mpi"};
      const char *near = diag_suggest(a, opts, sizeof opts / sizeof *opts);
      fprintf(stderr, "%s: unknown option '%s'%s%s%s\n", progname, a, near ? "; did you mean '" : "",
              near ? near : "", near ? "'?" : "");
      return 2;
    } else if (o->model) {
      fprintf(stderr, "%s: one model at a time ('%s' and '%s')\n", progname, o->model, a);
      return 2;
    } else o->model = a;
  }
  if (!o->model) {
    usage(stderr);
    return 2;
  }
  if (!o->check && !o->out) {
    fprintf(stderr, "%s: say where to write: -o SIM (or --check to check only)\n", progname);
    return 2;
  }
  if (o->check && (o->out || o->emit_c)) {
    fprintf(stderr, "%s: --check writes nothing; drop -o and --emit-c\n", progname);
    return 2;
  }
  return -1;
}

/* The --let overrides that could not apply, one line each; their count. */
/* sinewc --check on success: what was checked, on one line of stderr. */
static void print_checked(const char *model, const swScene *sc, double stable) {
  int nfil = 0;
  for (int i = 0; i < sc->nmuscle; i++) nfil += sc->muscle[i].filaments;
  int nenv = sc->nground + sc->nfluid + sc->ncontact + sc->nwave + sc->nobstacle;
  const int njoint = sc->njoint + sc->nkin;   /* kinematic joints are joints too */
  char dt[64] = "";
  if (stable > 0) {
    if (stable < 1e-6) snprintf(dt, sizeof dt, "; stable dt %.3g ns", stable * 1e9);
    else if (stable < 1e-3) snprintf(dt, sizeof dt, "; stable dt %.3g us", stable * 1e6);
    else snprintf(dt, sizeof dt, "; stable dt %.3g ms", stable * 1e3);
  }
  /* the objective's reductions are entries of the expectations' list */
  const int nexpect = sc->nexpect - sc->objective.nreduce;
  char objective[64] = "";
  if (sc->objective.sense)
    snprintf(objective, sizeof objective, ", an objective (%d penalt%s)",
             sc->objective.npenalty, sc->objective.npenalty == 1 ? "y" : "ies");
  fprintf(stderr, "%s: %s: ok: %d file%s, %d rod%s (%ld elements), %d muscle%s (%d filaments), "
          "%d joint%s, %d environment%s, %d param%s, %d expectation%s%s, %d warning%s%s\n",
          progname, model, diag_nfiles(), diag_nfiles() == 1 ? "" : "s", sc->nrod,
          sc->nrod == 1 ? "" : "s", sc->nelem, sc->nmuscle, sc->nmuscle == 1 ? "" : "s", nfil,
          njoint, njoint == 1 ? "" : "s", nenv, nenv == 1 ? "" : "s", sc->nparam,
          sc->nparam == 1 ? "" : "s", nexpect, nexpect == 1 ? "" : "s", objective,
          diag_warnings(), diag_warnings() == 1 ? "" : "s", dt);
}

static int report_lets(const swOptions *o) {
  int n = 0;
  for (int i = 0; i < o->nlets; i++)
    if (o->lets[i].error) {
      fprintf(stderr, "%s: %s\n", progname, o->lets[i].error);
      n++;
    }
  return n;
}

/* Check the model, then write the C or build the simulator; the exit code. */
static int compile(const swOptions *o) {
  const char *model = o->model, *out = o->out;
  diag_reset(stderr);
  diag_set_werror(o->werror);
  size_t len;
  const char *why;
  int not_text;
  char *text = sema_read_file(model, &len, &why, &not_text);
  if (!text) {
    fprintf(stderr, "%s: cannot read '%s': %s\n", progname, model, why);
    return not_text ? 1 : 4;
  }
  int file = diag_add_file(model, text, len);
  const char *base = strrchr(model, '/');
  diag_set_name(file, base && base[1] ? base + 1 : model);
  free(text);
  swArena *arena = ast_arena_new();
  swScene scene;
  sema_check_lets(arena, file, o->lets, o->nlets, &scene);
  /* a --let that cannot apply is a usage error: said first, in one line */
  int bad_lets = report_lets(o);
  /* a library file (materials, components, no rods) has nothing to run */
  double stable = 0;
  if (!diag_errors() && !bad_lets && scene.nrodid > 0) gen_check(&scene, &stable);
  if (!diag_errors() && !bad_lets && scene.nrodid == 0 && !o->check)
    fprintf(stderr, "%s: warning: '%s' defines no rods; the simulator will have nothing to "
            "simulate\n", progname, model);
  int rc = 0;
  diag_flush();
  if (diag_errors()) {
    fprintf(stderr, "%s: %d error%s, %d warning%s\n", progname, diag_errors(),
            diag_errors() == 1 ? "" : "s", diag_warnings(), diag_warnings() == 1 ? "" : "s");
    rc = 1;
  }
  if (bad_lets) rc = 2;
  if (rc) goto done;
  if (o->eval_height) {
    print_heights(&scene);
  } else if (o->eval_signal) {
    print_signals(&scene);
  } else if (o->check) {
    print_checked(model, &scene, stable);
  } else {
    char tmp[PATH_MAX];
    const char *cpath = out;
    if (!o->emit_c) {
      const char *dir = getenv("TMPDIR");
      snprintf(tmp, sizeof tmp, "%s/sinewc-XXXXXX.c", dir && *dir ? dir : "/tmp");
      int fd = mkstemps(tmp, 2);
      if (fd < 0) {
        fprintf(stderr, "%s: cannot create a temporary file: %s\n", progname, strerror(errno));
        rc = 4;
        goto done;
      }
      close(fd);
      cpath = tmp;
    }
    FILE *f = fopen(cpath, "w");
    if (!f) {
      fprintf(stderr, "%s: cannot write '%s': %s\n", progname, cpath, strerror(errno));
      rc = 4;
      goto done;
    }
    char version[64];
    snprintf(version, sizeof version, "sinewc %s", SW_VERSION);
    swGenOptions opt = {version};
    int bad = gen_c(f, arena, &scene, &opt);
    if (fclose(f) != 0 || bad) {
      fprintf(stderr, "%s: cannot write '%s'\n", progname, cpath);
      rc = 4;
    } else if (!o->emit_c) rc = run_cc(cpath, out, o->portable, o->no_mpi);
    if (!o->emit_c) unlink(cpath);
  }
done:
  sema_scene_free(&scene);
  ast_arena_free(arena);
  diag_reset(NULL);
  return rc;
}

int main(int argc, char **argv) {
  swOptions o;
  memset(&o, 0, sizeof o);
  o.lets = calloc((size_t)argc, sizeof *o.lets);
  if (!o.lets) abort();
  int rc = parse_args(argc, argv, &o);
  if (rc < 0) rc = compile(&o);
  for (int i = 0; i < argc; i++) free((char *)o.lets[i].name);
  free(o.lets);
  return rc;
}
