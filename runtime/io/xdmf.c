/* xdmf.c — the XDMF description beside a run's HDF5 file, so that ParaView
 * (and VisIt, or any XDMF reader) opens the rods as lines over time.
 *
 * Design.  XDMF is light XML that points into heavy HDF5 data (xdmf.org,
 * "XDMF Model and Format").  The description is one temporal collection with
 * one spatial collection per frame of the file, at that frame's time; in it
 * each rod is an unstructured grid of one Polyline cell through its n + 1
 * nodes (connectivity 0 1 ... n), whose geometry is the frame's row of
 * /rods/NAME/position (a HyperSlab: start (f, 0, 0), count (1, n + 1, 3)).
 * Point data: the rest radius at each node, /rods/NAME/node_radius
 * (static), which ParaView's Tube filter uses to vary the tube's radius, and
 * the velocity when the file has it.  What every frame of a rod shares (its
 * topology and its datasets' items) is written once, in the domain, and
 * each frame's grid refers to it by XPath (XDMF's Reference, by position,
 * so no name needs quoting in a path): the description of the arm's 43
 * rods over 501 frames went from 18.8 to 8.7 MB.  Nothing here reads HDF5:
 * output.c says which rods and datasets exist and how many frames are
 * written, and this file only prints XML.
 *
 * The file is rewritten whole (output.c decides when: at open, after the
 * first frame, at most once a second of wall time after that, and at close),
 * to a temporary name in the same directory and renamed over the old one,
 * which POSIX makes atomic: a reader sees the previous description or the
 * new one, and every frame either lists is in the HDF5 file, whose frames
 * are flushed before they are described.  Names from the model are escaped
 * (&amp; &lt; &gt; &quot; &apos;), so a name cannot end an attribute or open
 * an element; the HDF5 file is named by its base name, relative to the
 * description, so the pair can be moved together. */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sinew.h"
#include "xdmf.h"

char *sw_xdmf_path(const char *h5_path) {
  size_t len = strlen(h5_path);
  if (len > 3 && !strcmp(h5_path + len - 3, ".h5")) len -= 3;
  char *path = malloc(len + sizeof ".xdmf");
  if (!path) return NULL;
  memcpy(path, h5_path, len);
  memcpy(path + len, ".xdmf", sizeof ".xdmf");
  return path;
}

int sw_xdmf_name_ok(const char *name) {
  for (const unsigned char *c = (const unsigned char *)name; *c; c++)
    if (*c < 0x20 || *c == 0x7f) return 0;
  return 1;
}

/* s with the five characters XML gives meaning to replaced by their
 * predefined entities (XML 1.0, section 4.6). */
static void put_escaped(FILE *f, const char *s) {
  for (; *s; s++) switch (*s) {
    case '&': fputs("&amp;", f); break;
    case '<': fputs("&lt;", f); break;
    case '>': fputs("&gt;", f); break;
    case '"': fputs("&quot;", f); break;
    case '\'': fputs("&apos;", f); break;
    default: fputc(*s, f);
    }
}

/* FILE.h5:/rods/NAME/DATASET, the form of an HDF data item's text. */
static void put_hdf_ref(FILE *f, const char *h5_base, const char *rod, const char *dataset) {
  put_escaped(f, h5_base);
  fputs(":/rods/", f);
  put_escaped(f, rod);
  fprintf(f, "/%s", dataset);
}

/* What every frame of rod r refers to, in the domain: its topology (the
 * domain's Topology number r + 1) and its heavy items, node_radius,
 * position and, with velocity, velocity (numbered on from first_item, the
 * domain's DataItem count before them; XPath counts from 1). */
static void put_rod_shared(FILE *f, const char *h5_base, const swXdmfRod *r, long frames) {
  fputs("  <Topology Name=\"", f);
  put_escaped(f, r->name);
  fprintf(f, "\" TopologyType=\"Polyline\" NumberOfElements=\"1\" NodesPerElement=\"%d\">\n"
             "   <DataItem Dimensions=\"1 %d\" NumberType=\"Int\" Format=\"XML\">",
          r->nodes, r->nodes);
  for (int i = 0; i < r->nodes; i++) fprintf(f, i ? " %d" : "%d", i);
  fputs("</DataItem>\n  </Topology>\n", f);
  const char *items[] = {"node_radius", "position", "velocity"};
  for (int k = 0; k < (r->velocity ? 3 : 2); k++) {
    fputs("  <DataItem Name=\"", f);
    put_escaped(f, r->name);
    if (k) fprintf(f, " %s\" Dimensions=\"%ld %d 3\"", items[k], frames, r->nodes);
    else fprintf(f, " %s\" Dimensions=\"%d\"", items[k], r->nodes);
    fputs(" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">", f);
    put_hdf_ref(f, h5_base, r->name, items[k]);
    fputs("</DataItem>\n", f);
  }
}

/* Frame k of a shared item [frames, nodes, 3]: one row of nodes x 3 values,
 * by a HyperSlab whose first item is start (k, 0, 0), stride and count.
 * Written in two parts, before and after k: the text of a rod is the same
 * in every frame but for k, so it is made once per description (put_rod)
 * and each frame prints only the pieces and its k. */
static void put_slab_open(FILE *f, const swXdmfRod *r) {
  fprintf(f, "<DataItem ItemType=\"HyperSlab\" Dimensions=\"1 %d 3\" Type=\"HyperSlab\">"
             "<DataItem Dimensions=\"3 3\" NumberType=\"Int\" Format=\"XML\">",
          r->nodes);
}

static void put_slab_close(FILE *f, const swXdmfRod *r, int item) {
  fprintf(f, " 0 0 1 1 1 1 %d 3</DataItem><DataItem Reference=\"/Xdmf/Domain/DataItem[%d]\"/>"
             "</DataItem>",
          r->nodes, item);
}

/* A rod's grid in a frame, as the text before the frame's index in the
 * position slab (piece 0), between it and the index in the velocity slab
 * (1), and after that (2; empty without velocity): rod number `index`,
 * whose shared items start after the domain's first_item DataItems. */
enum { ROD_PIECES = 3 };
typedef struct {
  char *text[ROD_PIECES];
  size_t len[ROD_PIECES];
} swRodText;

static int put_rod(swRodText *t, const swXdmfRod *r, int index, int first_item) {
  FILE *f[ROD_PIECES];
  for (int p = 0; p < ROD_PIECES; p++) {
    t->text[p] = NULL;
    f[p] = open_memstream(&t->text[p], &t->len[p]);
    if (!f[p]) {
      for (int q = 0; q < p; q++) fclose(f[q]);
      return -1;
    }
  }
  fputs("    <Grid Name=\"", f[0]);
  put_escaped(f[0], r->name);
  fprintf(f[0], "\" GridType=\"Uniform\"><Topology Reference=\"/Xdmf/Domain/Topology[%d]\"/>"
                "<Geometry GeometryType=\"XYZ\">",
          index + 1);
  put_slab_open(f[0], r);
  put_slab_close(f[1], r, first_item + 2);
  fprintf(f[1], "</Geometry><Attribute Name=\"radius\" AttributeType=\"Scalar\" "
                "Center=\"Node\"><DataItem Reference=\"/Xdmf/Domain/DataItem[%d]\"/>"
                "</Attribute>",
          first_item + 1);
  FILE *end = f[1];
  if (r->velocity) {
    fputs("<Attribute Name=\"velocity\" AttributeType=\"Vector\" Center=\"Node\">", f[1]);
    put_slab_open(f[1], r);
    put_slab_close(f[2], r, first_item + 3);
    fputs("</Attribute>", f[2]);
    end = f[2];
  }
  fputs("</Grid>\n", end);
  int bad = 0;
  for (int p = 0; p < ROD_PIECES; p++)
    if (fclose(f[p]) != 0) bad = 1;
  return bad ? -1 : 0;
}

static void free_rod_texts(swRodText *t, int n) {
  for (int r = 0; r < n; r++)
    for (int p = 0; p < ROD_PIECES; p++) free(t[r].text[p]);
  free(t);
}

/* Rod r's grid in frame k, from its pieces. */
static void put_rod_frame(FILE *f, const swRodText *t, const swXdmfRod *r, long k) {
  fwrite(t->text[0], 1, t->len[0], f);
  fprintf(f, "%ld", k);
  fwrite(t->text[1], 1, t->len[1], f);
  if (r->velocity) {
    fprintf(f, "%ld", k);
    fwrite(t->text[2], 1, t->len[2], f);
  }
}

int sw_xdmf_write(const char *xdmf_path, const char *h5_path, const swXdmfRod *rods, int nrod,
                  const double *time, long frames, char *err, size_t errlen) {
  const char *slash = strrchr(h5_path, '/');
  const char *h5_base = slash ? slash + 1 : h5_path;
  size_t len = strlen(xdmf_path);
  char *tmp = malloc(len + sizeof ".tmp");
  if (!tmp) {
    snprintf(err, errlen, "%s: out of memory", xdmf_path);
    return SW_EIO;
  }
  memcpy(tmp, xdmf_path, len);
  memcpy(tmp + len, ".tmp", sizeof ".tmp");
  swRodText *text = calloc(nrod > 0 ? (size_t)nrod : 1, sizeof *text);
  int made = 0, items = 0;
  while (text && made < nrod && put_rod(&text[made], &rods[made], made, items) == 0)
    items += rods[made++].velocity ? 3 : 2;
  if (!text || made < nrod) {
    if (text) free_rod_texts(text, made + 1);
    snprintf(err, errlen, "%s: out of memory", xdmf_path);
    free(tmp);
    return SW_EIO;
  }
  FILE *f = fopen(tmp, "w");
  if (!f) {
    snprintf(err, errlen, "cannot create %s: %s", tmp, strerror(errno));
    free_rod_texts(text, nrod);
    free(tmp);
    return SW_EIO;
  }
  fputs("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
        "<!-- The rods of ", f);
  /* "--" may not occur inside a comment: the name is given in a comment
   * only when it has none */
  fputs(strstr(h5_base, "--") ? "this run" : h5_base, f);
  fprintf(f, " over time, %ld frame%s (written by sinew %s; rewritten as the run goes). "
             "In ParaView: open this file, apply Extract Surface, then Tube with "
             "\"Vary Radius\" by the scalar radius. -->\n"
             "<Xdmf Version=\"3.0\">\n"
             " <Domain>\n",
          frames, frames == 1 ? "" : "s", SW_VERSION);
  for (int r = 0; r < nrod; r++) put_rod_shared(f, h5_base, &rods[r], frames);
  fputs("  <Grid Name=\"rods\" GridType=\"Collection\" CollectionType=\"Temporal\">\n", f);
  for (long k = 0; k < frames; k++) {
    fprintf(f, "   <Grid Name=\"frame %ld\" GridType=\"Collection\" "
               "CollectionType=\"Spatial\">\n"
               "    <Time Value=\"%.17g\"/>\n",
            k, time[k]);
    for (int r = 0; r < nrod; r++) put_rod_frame(f, &text[r], &rods[r], k);
    fputs("   </Grid>\n", f);
  }
  fputs("  </Grid>\n </Domain>\n</Xdmf>\n", f);
  free_rod_texts(text, nrod);
  int bad = ferror(f);
  if (fclose(f) != 0) bad = 1;
  if (bad || rename(tmp, xdmf_path) != 0) {
    snprintf(err, errlen, "cannot write %s: %s", bad ? tmp : xdmf_path, strerror(errno));
    remove(tmp);
    free(tmp);
    return SW_EIO;
  }
  free(tmp);
  return SW_OK;
}
