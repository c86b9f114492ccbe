/* The deformed centre line of contact anywhere's search (nearest.c, nearest_scan.c): the station data of one search,
 * each station's values computed on first use. */
#ifndef FLEXBEAM_NEAREST_LINE_H
#define FLEXBEAM_NEAREST_LINE_H

#include "flexbeam.h"

static inline double line_dot(const double *a, const double *b, int n) {
    double acc = 0.0;
    for (int i = 0; i < n; i++) acc += a[i] * b[i];
    return acc;
}

/* The centre line of a deformed beam, station data computed once per search. */
typedef struct {
    const fb_model *m;
    const double *q; /* [q, p]: n bending modes, then the axial ones */
    int n, M;
    double rh, dx;
    double *w, *w1, *w2, *u; /* per station: Psi q, Psi' q, Psi'' q, u_x (computed on first use) */
    double *s, *s1;          /* per station: Phi_a p, Phi_a' p (computed on first use; NULL without axial modes) */
    unsigned long long *known; /* LINE_KNOWN bit planes of LINE_WORDS(M) words: which stations' values are in */
} line_t;

enum { KNOWN_W, KNOWN_SLOPES, KNOWN_U, KNOWN_S, LINE_KNOWN }; /* w; w1 and w2; u; s and s1 */
#define LINE_WORDS(M) (((M) + 63) / 64)

/* Whether station j's values of bit plane ``plane`` are in; marks them as in (the caller computes them if not). */
static inline int line_known(line_t *ln, int plane, int j) {
    unsigned long long *word = ln->known + (size_t)plane * LINE_WORDS(ln->M) + (j >> 6), bit = 1ULL << (j & 63);
    if (*word & bit) return 1;
    *word |= bit;
    return 0;
}

/* Psi q at station j, computed on first use (a sphere's scan visits only the stations near it). */
static inline double station_w(line_t *ln, int j) {
    if (!line_known(ln, KNOWN_W, j)) ln->w[j] = line_dot(ln->m->st_phi + (size_t)j * ln->n, ln->q, ln->n);
    return ln->w[j];
}

/* The axial stretch Phi_a p at station j and its slope Phi_a' p in *s1 (0 without axial modes). */
static inline double station_s(line_t *ln, int j, double *s1) {
    if (!ln->s) {
        *s1 = 0.0;
        return 0.0;
    }
    if (!line_known(ln, KNOWN_S, j)) {
        int na = ln->m->na;
        const double *p = ln->q + ln->n;
        ln->s[j] = line_dot(ln->m->st_aphi + (size_t)j * na, p, na);
        ln->s1[j] = line_dot(ln->m->st_daphi + (size_t)j * na, p, na);
    }
    *s1 = ln->s1[j];
    return ln->s[j];
}

/* The station whose centre-line point is nearest a sphere's centre c (squared distance) or lowest along a plane's
 * outward normal c, in the body frame (nearest_scan.c); obstacle: the obstacle's index in the model. */
int fb_nearest_station(line_t *ln, int sphere, const double c[2], int obstacle);

#endif
