/* The parameter file of pkmhexkins (written by pkm: io::linuxcncHexapodParameters; format in
 * docs/linuxcnc.md, "The pkmhexkins parameter file") and the checks of its values: a bad file
 * fails the module's load with a message naming the line or the missing name. */
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "pkmhexkins_core.h"

#define N PKM_HEX_STRUTS
#define MAX_LINE 512
#define MAX_FILE 65536

typedef enum { KIND_REAL, KIND_INT } value_kind;

/* One entry of the file: its name, how many numbers, where they go (double or int array). */
typedef struct {
  char name[24];
  int count;
  value_kind kind;
  void* target;
} entry;

#define ENTRIES (3 * N + 11)

static void set_entry(entry* e, const char* name, int count, value_kind kind, void* target) {
  snprintf(e->name, sizeof e->name, "%s", name);
  e->count = count;
  e->kind = kind;
  e->target = target;
}

/* The file's entries in the order pkm writes them, pointing into *p. */
static int make_entries(pkm_hex_params* p, entry e[ENTRIES]) {
  int n = 0;
  char name[24];
  for (int i = 0; i < N; ++i) {
    snprintf(name, sizeof name, "base.%d", i);
    set_entry(&e[n++], name, 3, KIND_REAL, p->geometry.base[i]);
    snprintf(name, sizeof name, "platform.%d", i);
    set_entry(&e[n++], name, 3, KIND_REAL, p->geometry.platform[i]);
    snprintf(name, sizeof name, "length-offset.%d", i);
    set_entry(&e[n++], name, 1, KIND_REAL, &p->geometry.length_offset[i]);
  }
  pkm_hex_fk_options* o = &p->options;
  set_entry(&e[n++], "tool", 3, KIND_REAL, p->geometry.tool);
  set_entry(&e[n++], "spindle-offset", 1, KIND_REAL, &p->geometry.spindle_offset);
  set_entry(&e[n++], "home", 6, KIND_REAL, p->home);
  set_entry(&e[n++], "convergence-criterion", 1, KIND_REAL, &o->tolerance);
  set_entry(&e[n++], "limit-iterations", 1, KIND_INT, &o->max_iterations);
  set_entry(&e[n++], "max-error", 1, KIND_REAL, &o->max_error);
  set_entry(&e[n++], "max-backtracks", 1, KIND_INT, &o->max_backtracks);
  set_entry(&e[n++], "singular-pivot-ratio", 1, KIND_REAL, &o->singular_pivot_ratio);
  set_entry(&e[n++], "max-step-translation", 1, KIND_REAL, &o->max_step_translation);
  set_entry(&e[n++], "max-step-rotation", 1, KIND_REAL, &o->max_step_rotation);
  set_entry(&e[n++], "continuation-step", 1, KIND_REAL, &o->continuation_step);
  return n;
}

/* Reads e's numbers from text (after the name); −1 on a missing or bad number or extra text. */
static int read_values(const entry* e, const char* text) {
  for (int k = 0; k < e->count; ++k) {
    char* end = NULL;
    const double x = strtod(text, &end);
    if (end == text || (*end != '\0' && strchr(" \t\r", *end) == NULL)) return -1;
    text = end;
    if (e->kind == KIND_INT) {
      if (!(x == floor(x) && fabs(x) <= 1e9)) return -1;
      ((int*)e->target)[k] = (int)x;
    } else {
      ((double*)e->target)[k] = x;
    }
  }
  text += strspn(text, " \t\r");
  return *text == '\0' ? 0 : -1;
}

/* One line (without its newline); −1 with the reason in why. */
static int parse_line(
    char* line, entry* entries, int count, int* seen, int number, char* why, size_t size) {
  char* hash = strchr(line, '#');
  if (hash != NULL) *hash = '\0';
  const char* name = line + strspn(line, " \t\r");
  if (*name == '\0') return 0;
  const size_t len = strcspn(name, " \t\r");
  for (int i = 0; i < count; ++i) {
    const entry* e = &entries[i];
    if (strlen(e->name) != len || strncmp(e->name, name, len) != 0) continue;
    if (seen[i]) {
      snprintf(why, size, "line %d: %s given twice", number, e->name);
      return -1;
    }
    seen[i] = 1;
    if (read_values(e, name + len) == 0) return 0;
    snprintf(why,
             size,
             "line %d: %s needs %d %s",
             number,
             e->name,
             e->count,
             e->kind == KIND_INT ? "whole number" : (e->count == 1 ? "number" : "numbers"));
    return -1;
  }
  snprintf(why, size, "line %d: unknown parameter '%.*s'", number, (int)len, name);
  return -1;
}

int pkm_hex_check_params(const pkm_hex_params* p, char* why, size_t size) {
  const pkm_hex_fk_options* o = &p->options;
  const char* bad = NULL;
  if (!(o->tolerance > 0.0 && isfinite(o->tolerance)))
    bad = "convergence-criterion must be > 0";
  else if (o->max_iterations < 1)
    bad = "limit-iterations must be >= 1";
  else if (!(o->max_error >= 0.0))
    bad = "max-error must be >= 0 (0: no limit)";
  else if (o->max_backtracks < 0)
    bad = "max-backtracks must be >= 0";
  else if (!(o->singular_pivot_ratio > 0.0 && o->singular_pivot_ratio < 1.0))
    bad = "singular-pivot-ratio must be in (0, 1)";
  else if (!(o->max_step_translation > 0.0 && isfinite(o->max_step_translation)))
    bad = "max-step-translation must be > 0";
  else if (!(o->max_step_rotation > 0.0 && isfinite(o->max_step_rotation)))
    bad = "max-step-rotation must be > 0";
  else if (!(o->continuation_step > 0.0 && isfinite(o->continuation_step)))
    bad = "continuation-step must be > 0";
  if (bad != NULL) {
    if (why != NULL) snprintf(why, size, "%s", bad);
    return -1;
  }
  const double deg = 3.14159265358979323846 / 180.0;
  const double rpy[3] = {p->home[3] * deg, p->home[4] * deg, p->home[5] * deg};
  return pkm_hex_check_home(&p->geometry, p->home, rpy, o->singular_pivot_ratio, why, size);
}

int pkm_hex_parse_params(const char* text, pkm_hex_params* params, char* why, size_t size) {
  char ignored[8];
  if (why == NULL) {
    why = ignored;
    size = sizeof ignored;
  }
  pkm_hex_params p;
  memset(&p, 0, sizeof p);
  entry entries[ENTRIES];
  const int count = make_entries(&p, entries);
  int seen[ENTRIES] = {0};
  char line[MAX_LINE];
  for (int number = 1; *text != '\0'; ++number) {
    const size_t len = strcspn(text, "\n");
    if (len >= sizeof line) {
      snprintf(why, size, "line %d: longer than %d characters", number, MAX_LINE - 1);
      return -1;
    }
    memcpy(line, text, len);
    line[len] = '\0';
    text += len + (text[len] == '\n' ? 1 : 0);
    if (parse_line(line, entries, count, seen, number, why, size) != 0) return -1;
  }
  for (int i = 0; i < count; ++i)
    if (!seen[i]) {
      snprintf(why, size, "missing %s", entries[i].name);
      return -1;
    }
  if (p.options.max_error == 0.0) p.options.max_error = INFINITY;
  if (pkm_hex_check_params(&p, why, size) != 0) return -1;
  *params = p;
  return 0;
}

int pkm_hex_load_params(const char* path, pkm_hex_params* params, char* why, size_t size) {
  FILE* f = fopen(path, "rb");
  if (f == NULL) {
    if (why != NULL) snprintf(why, size, "cannot read %s", path);
    return -1;
  }
  char* text = malloc(MAX_FILE + 1);
  size_t n = 0;
  if (text != NULL) n = fread(text, 1, MAX_FILE + 1, f);
  const int failed = text == NULL || ferror(f);
  fclose(f);
  if (failed || n > MAX_FILE) {
    if (why != NULL)
      snprintf(why, size, failed ? "cannot read %s" : "%s is larger than 64 KiB", path);
    free(text);
    return -1;
  }
  text[n] = '\0';
  const int rc = memchr(text, '\0', n) != NULL ? -1 : pkm_hex_parse_params(text, params, why, size);
  if (rc != 0 && memchr(text, '\0', n) != NULL && why != NULL)
    snprintf(why, size, "%s is not a text file", path);
  free(text);
  return rc;
}
