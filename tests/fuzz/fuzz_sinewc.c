/* fuzz_sinewc.c — the fuzzing harness: sinewc's whole front end on one input.
 *
 * Design.  One input is one model file.  run_one() does in-process what
 * `sinewc --check` and `sinewc --emit-c` do: register the text as
 * "fuzz.sinew", lex, parse and check it (imports resolve relative to the
 * working directory, which scripts/fuzz.sh makes an empty directory, so they
 * fail cleanly), and when it is error-free and has rods let the runtime
 * validate the scene and estimate its stable step (gen_check), then print the
 * generated C into /dev/null (gen_c).  Then every piece of state is freed and
 * reset, so one process can run many inputs.
 *
 * Three ways to build it:
 *   - afl-clang-fast / afl-clang-lto: AFL++ persistent mode with shared-memory
 *     test cases (__AFL_LOOP, __AFL_FUZZ_TESTCASE_BUF), ~10x faster than a
 *     fork per input;
 *   - clang -fsanitize=fuzzer -DSW_LIBFUZZER: libFuzzer's entry point;
 *   - any C compiler: a replay binary, `fuzz_sinewc FILE...`, which runs each
 *     file once and prints one line per file on what it did ("FILE: N
 *     errors, M warnings, runtime check: yes, C: generated"); make check
 *     builds it under ASan and UBSan (build/asan/fuzz_sinewc) and
 *     tests/lang/test_fuzz_harness.sh replays the seeds and regressions
 *     through it; also the way to reproduce a crash under a debugger.
 * Inputs with NUL bytes are skipped, as sinewc refuses them before parsing.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "diag.h"
#include "gen.h"
#include "sema.h"

/* Cap what one run reads; big inputs only slow the fuzzer down. */
#define FUZZ_MAX_INPUT (64 * 1024)

static FILE *devnull;

/* What the last run_one() did, for the replay binary's report. */
static struct {
  int skipped;               /* too long or has a NUL byte: not run         */
  int errors, warnings;
  int checked;               /* gen_check ran                               */
  int generated;             /* gen_c: -1 not run, 0 written, else failed   */
} last;

static void run_one(const unsigned char *data, size_t len) {
  memset(&last, 0, sizeof last);
  last.generated = -1;
  if (len > FUZZ_MAX_INPUT || memchr(data, 0, len)) {
    last.skipped = 1;
    return;
  }
  if (!devnull) {
    devnull = fopen("/dev/null", "w");
    if (!devnull) abort();
  }
  diag_reset(devnull);
  int file = diag_add_file("fuzz.sinew", (const char *)data, len);
  swArena *arena = ast_arena_new();
  swScene scene;
  sema_check(arena, file, &scene);
  /* as sinewc's compile(): a scene with no rods and no muscles (a library
   * file) is not given to the runtime */
  double stable = 0;
  if (!diag_errors() && scene.nrodid > 0) {
    gen_check(&scene, &stable);
    last.checked = 1;
  }
  diag_flush();
  if (!diag_errors()) {
    swGenOptions opt = {"sinewc fuzz"};
    last.generated = gen_c(devnull, arena, &scene, &opt);
  }
  last.errors = diag_errors();
  last.warnings = diag_warnings();
  sema_scene_free(&scene);
  ast_arena_free(arena);
  diag_reset(devnull);
}

#if defined(SW_LIBFUZZER)

int LLVMFuzzerTestOneInput(const unsigned char *data, size_t len);
int LLVMFuzzerTestOneInput(const unsigned char *data, size_t len) {
  run_one(data, len);
  return 0;
}

#else

static int run_path(const char *path) {
  FILE *f = fopen(path, "rb");
  if (!f) {
    perror(path);
    return 1;
  }
  static unsigned char buf[FUZZ_MAX_INPUT + 1];
  size_t n = fread(buf, 1, sizeof buf, f);
  fclose(f);
  run_one(buf, n);
  if (last.skipped)
    printf("%s: skipped (longer than %d bytes or a NUL byte)\n", path, FUZZ_MAX_INPUT);
  else
    printf("%s: %d error%s, %d warning%s, runtime check: %s, C: %s\n", path, last.errors,
           last.errors == 1 ? "" : "s", last.warnings, last.warnings == 1 ? "" : "s",
           last.checked ? "yes" : "no",
           last.generated < 0 ? "not generated" : last.generated ? "failed" : "generated");
  return 0;
}

#ifdef __AFL_FUZZ_TESTCASE_LEN
__AFL_FUZZ_INIT();
#endif

int main(int argc, char **argv) {
#ifdef __AFL_FUZZ_TESTCASE_LEN
  /* persistent mode: afl-fuzz and afl-tmin hand test cases over shared
   * memory (run them without @@).  Outside AFL the loop body runs once, on
   * the files named, or on standard input. */
  __AFL_INIT();
  unsigned char *buf = __AFL_FUZZ_TESTCASE_BUF;
  int bad = 0;
  while (__AFL_LOOP(10000)) {
    if (argc < 2) run_one(buf, (size_t)__AFL_FUZZ_TESTCASE_LEN);
    for (int i = 1; i < argc; i++) bad |= run_path(argv[i]);
  }
  return bad;
#else
  if (argc < 2) {
    fprintf(stderr, "usage: %s FILE...   (run the front end on each file)\n", argv[0]);
    return 2;
  }
  int bad = 0;
  for (int i = 1; i < argc; i++) bad |= run_path(argv[i]);
  return bad;
#endif
}

#endif
