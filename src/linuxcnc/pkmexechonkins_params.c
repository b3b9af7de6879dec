/* The parameter file of pkmexechonkins (written by pkm: io::linuxcncExechonParameters) and the
 * checks of the parameters: a bad file fails at load with a message naming the line or field. */
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "pkmexechonkins_internal.h"

#define PKX_DEG (3.14159265358979323846264338327950288 / 180.0)
#define PKX_MAX_LINE 512

/* One parameter-file entry: its name, its field's offset in pkm_exechon_params, how many numbers,
 * and their kind. */
typedef enum { PKX_LENGTH, PKX_INT, PKX_DEGREES } pkx_kind;
typedef struct {
  const char* name;
  size_t offset;
  int count;
  pkx_kind kind;
} pkx_entry;

/* The file's entries, in the order pkm writes them. */
static const pkx_entry pkx_entries[] = {
    {"dA", offsetof(pkm_exechon_params, dA), 1, PKX_LENGTH},
    {"dB", offsetof(pkm_exechon_params, dB), 1, PKX_LENGTH},
    {"dC", offsetof(pkm_exechon_params, dC), 1, PKX_LENGTH},
    {"l12A", offsetof(pkm_exechon_params, l12A), 1, PKX_LENGTH},
    {"l12C", offsetof(pkm_exechon_params, l12C), 1, PKX_LENGTH},
    {"l12B", offsetof(pkm_exechon_params, l12B), 1, PKX_LENGTH},
    {"l23B", offsetof(pkm_exechon_params, l23B), 1, PKX_LENGTH},
    {"pA", offsetof(pkm_exechon_params, pA), 1, PKX_LENGTH},
    {"pB", offsetof(pkm_exechon_params, pB), 1, PKX_LENGTH},
    {"pC", offsetof(pkm_exechon_params, pC), 1, PKX_LENGTH},
    {"hA", offsetof(pkm_exechon_params, hA), 1, PKX_LENGTH},
    {"hC", offsetof(pkm_exechon_params, hC), 1, PKX_LENGTH},
    {"hx", offsetof(pkm_exechon_params, hx), 1, PKX_LENGTH},
    {"hz", offsetof(pkm_exechon_params, hz), 1, PKX_LENGTH},
    {"delta1B", offsetof(pkm_exechon_params, delta1B), 1, PKX_INT},
    {"delta2B", offsetof(pkm_exechon_params, delta2B), 1, PKX_INT},
    {"deltaA", offsetof(pkm_exechon_params, deltaA), 1, PKX_INT},
    {"deltaC", offsetof(pkm_exechon_params, deltaC), 1, PKX_INT},
    {"length_offset", offsetof(pkm_exechon_params, length_offset), 3, PKX_LENGTH},
    {"stroke_min", offsetof(pkm_exechon_params, stroke_min), 3, PKX_LENGTH},
    {"stroke_max", offsetof(pkm_exechon_params, stroke_max), 3, PKX_LENGTH},
    {"alpha_range_deg", offsetof(pkm_exechon_params, alpha_range), 2, PKX_DEGREES},
    {"beta_range_deg", offsetof(pkm_exechon_params, beta_range), 2, PKX_DEGREES},
    {"c_range_deg", offsetof(pkm_exechon_params, c_range), 2, PKX_DEGREES},
    {"a_range_deg", offsetof(pkm_exechon_params, a_range), 2, PKX_DEGREES},
    {"c_axis", offsetof(pkm_exechon_params, c_axis), 3, PKX_LENGTH},
    {"a_axis", offsetof(pkm_exechon_params, a_axis), 3, PKX_LENGTH},
    {"c0_deg", offsetof(pkm_exechon_params, c0), 1, PKX_DEGREES},
    {"a0_deg", offsetof(pkm_exechon_params, a0), 1, PKX_DEGREES},
    {"c_sign", offsetof(pkm_exechon_params, c_sign), 1, PKX_INT},
    {"a_sign", offsetof(pkm_exechon_params, a_sign), 1, PKX_INT},
    {"tool_length", offsetof(pkm_exechon_params, tool_length), 1, PKX_LENGTH},
    {"world_R_zoppi", offsetof(pkm_exechon_params, world_R_zoppi), 9, PKX_LENGTH},
    {"world_p_zoppi", offsetof(pkm_exechon_params, world_p_zoppi), 3, PKX_LENGTH},
    {"home_alpha_deg", offsetof(pkm_exechon_params, home_e[0]), 1, PKX_DEGREES},
    {"home_beta_deg", offsetof(pkm_exechon_params, home_e[1]), 1, PKX_DEGREES},
    {"home_h", offsetof(pkm_exechon_params, home_e[2]), 1, PKX_LENGTH},
    {"home_c_deg", offsetof(pkm_exechon_params, home_c), 1, PKX_DEGREES},
    {"home_a_deg", offsetof(pkm_exechon_params, home_a), 1, PKX_DEGREES},
    {"max_condition", offsetof(pkm_exechon_params, max_condition), 1, PKX_LENGTH},
    {"fk_tolerance", offsetof(pkm_exechon_params, fk_tolerance), 1, PKX_LENGTH},
    {"fk_max_iterations", offsetof(pkm_exechon_params, fk_max_iterations), 1, PKX_INT},
    {"fk_max_backtracks", offsetof(pkm_exechon_params, fk_max_backtracks), 1, PKX_INT},
    {"fk_singular_pivot_ratio",
     offsetof(pkm_exechon_params, fk_singular_pivot_ratio),
     1,
     PKX_LENGTH},
};
#define PKX_ENTRIES ((int)(sizeof pkx_entries / sizeof pkx_entries[0]))

/* Parses the values after the name into e's target; -1 on a bad or missing number or extra text. */
static int pkx_read_values(const pkx_entry* e, pkm_exechon_params* p, const char* text) {
  char* target = (char*)p + e->offset;
  for (int k = 0; k < e->count; ++k) {
    char* end = NULL;
    const double x = strtod(text, &end);
    if (end == text) return -1;
    text = end;
    if (e->kind == PKX_INT) {
      if (x != floor(x) || fabs(x) > 1e9) return -1;
      ((int*)(void*)target)[k] = (int)x;
    } else {
      ((double*)(void*)target)[k] = e->kind == PKX_DEGREES ? x * PKX_DEG : x;
    }
  }
  while (*text == ' ' || *text == '\t' || *text == '\r') ++text;
  return *text == '\0' ? 0 : -1;
}

/* Handles one line (comment and blanks removed); -1 with the reason in why. */
static int pkx_parse_line(
    char* line, pkm_exechon_params* p, int* seen, int number, char* why, int why_size) {
  char* hash = strchr(line, '#');
  if (hash != NULL) *hash = '\0';
  char* name = line + strspn(line, " \t\r");
  if (*name == '\0') return 0;
  const size_t len = strcspn(name, " \t\r");
  for (int i = 0; i < PKX_ENTRIES; ++i) {
    const pkx_entry* entry = &pkx_entries[i];
    if (strlen(entry->name) != len || strncmp(entry->name, name, len) != 0) continue;
    if (seen[i]) {
      snprintf(why, (size_t)why_size, "line %d: %s given twice", number, entry->name);
      return -1;
    }
    seen[i] = 1;
    if (pkx_read_values(entry, p, name + len) == 0) return 0;
    snprintf(
        why, (size_t)why_size, "line %d: %s needs %d number(s)", number, entry->name, entry->count);
    return -1;
  }
  snprintf(why, (size_t)why_size, "line %d: unknown parameter '%.*s'", number, (int)len, name);
  return -1;
}

int pkm_exechon_parse_params(const char* text,
                             pkm_exechon_params* params,
                             char* why,
                             int why_size) {
  pkm_exechon_params p;
  int seen[PKX_ENTRIES] = {0};
  memset(&p, 0, sizeof p);
  char line[PKX_MAX_LINE];
  for (int number = 1; *text != '\0'; ++number) {
    const size_t len = strcspn(text, "\n");
    if (len >= sizeof line) {
      snprintf(why, (size_t)why_size, "line %d: longer than %d characters", number, PKX_MAX_LINE);
      return -1;
    }
    memcpy(line, text, len);
    line[len] = '\0';
    text += len + (text[len] == '\n' ? 1 : 0);
    if (pkx_parse_line(line, &p, seen, number, why, why_size) != 0) return -1;
  }
  for (int i = 0; i < PKX_ENTRIES; ++i)
    if (!seen[i]) {
      snprintf(why, (size_t)why_size, "missing %s", pkx_entries[i].name);
      return -1;
    }
  if (pkm_exechon_prepare(&p, why, why_size) != 0) return -1;
  *params = p;
  return 0;
}
