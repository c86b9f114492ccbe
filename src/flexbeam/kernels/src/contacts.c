/* The contacts buffer of a phase (flexbeam.kernels.layout.pack_contacts): how each pair acts, its law, and its
 * Coulomb friction (friction.c). */
#include "flexbeam.h"

int fb_contacts_unpack(fb_contacts *c, const fb_model *m, const double *buf, size_t nbuf) {
    if (nbuf < 3) return -1;
    c->npairs = (int)buf[0];
    c->alpha = buf[1];
    c->beta = buf[2];
    size_t S = (size_t)c->npairs, width = nbuf == 3 + 10 * S ? 10 : 5;
    if (c->npairs != m->npairs || c->npairs < 0 || nbuf != 3 + width * S) return -1;
    c->friction = 0;
    for (int k = 0; k < c->npairs; k++) {
        const double *r = buf + 3 + width * k;
        c->mode[k] = (int)r[0];
        if (c->mode[k] < FB_MODE_NONE || c->mode[k] > FB_MODE_CONSTRAINT) return -1;
        for (int j = 0; j < 4; j++) c->p[k][j] = r[1 + j];
        c->slip[k] = width == 10 ? r[5] : 0.0;
        c->vrest[k] = width == 10 ? r[8] : 0.0;
        c->sdir[k] = width == 10 ? r[9] : 0.0;
        int held = width == 10 ? (int)r[6] : 0; /* 0 none, 1 stick, 2 + h: stick following pair h, -1 regularised */
        c->stick[k] = held == 1;
        c->follow[k] = held >= 2 ? held - 2 : -1;
        c->mus[k] = width == 10 && held >= 0 ? r[7] : 0.0;
        c->regmu[k] = held == -1 ? c->slip[k] : 0.0; /* [mu_k, -1, v_0] */
        c->regv[k] = held == -1 ? r[7] : 0.0;
        if (held == -1) c->slip[k] = 0.0;
        if (held < -1 || c->follow[k] >= c->npairs || (held == -1 && !(c->regv[k] > 0.0))) return -1;
        if (c->sdir[k] != 0.0 && (held || (c->sdir[k] != 1.0 && c->sdir[k] != -1.0))) return -1;
        /* friction only on a FORCE (CCFM) or CONSTRAINT (CCM) pair */
        if (c->mode[k] == FB_MODE_NONE && (c->slip[k] != 0.0 || c->sdir[k] != 0.0 || held)) return -1;
        c->friction |= c->slip[k] != 0.0 || c->sdir[k] != 0.0 || c->stick[k] || c->regmu[k] != 0.0;
    }
    return 0;
}
