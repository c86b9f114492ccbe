/* Contact anywhere's scan of the stations (nearest.c): the station nearest the obstacle, around which Newton's
 * method then finds the nearest point.
 *
 * A sphere: outwards from the station abreast of its centre, stopping where the axial distance alone reaches the best
 * squared distance (a few stations).  A half-plane: the station lowest along the plane's outward normal c (body
 * frame), v_j = c . rho_j = c_x (r_h + x_j + s_j) + c_y w_j (s_j = Phi_a,j p, w_j = Psi_j q), over all M stations:
 * M dot products, most of the search's cost when it runs at every node and sample of a step.
 *
 * The plane's warm scan gives the full scan's station, bit for bit, from fewer of them.  The WARM_KEEP + 1 least of
 * the full scan's values v_j^r at a reference (q_r, p_r, c_r) are kept (per thread, per model unpacking and
 * obstacle).  At (q, p, c)
 *     |v_j - v_j^r| <= D = |c_x - c_x^r| X + |c_x^r| dS + |c_y - c_y^r| W + |c_y^r| dW
 * for every j, with |r_h + x_j + s_j| <= X = |r_h| + max|x_j| + sum_k max_j|Phi_a,jk| |p_k| (the larger of now and
 * the reference), |w_j| <= W = sum_k max_j|Psi_jk| |q_k| (likewise), |s_j - s_j^r| <= dS = sum_k max|Phi_a,k|
 * |p_k - p_r,k| and |w_j - w_j^r| <= dW = sum_k max|Psi_k| |q_k - q_r,k| (the maxima over the stations' table values,
 * taken once per model unpacking: exact).  The computed values carry at most (n + n_a + 5) u (|c_x| X + |c_y| W) of rounding each
 * (the dot products' gamma_n bound, Higham 2002 Sec. 3.1, and five more roundings); taken 8 (n + n_a + 4) u, and
 * the sum doubled against the rounding of the bound itself: B = 2 (D + 2 E).  A station with v_j^r > min_k v_k^r +
 * 2 B then has v_j > v_k0 (k0 the reference's minimiser) now: it can be neither the minimiser nor tied with it.  The
 * warm scan evaluates the other stations (the candidates, k0 among them, all among the kept least: a station not
 * kept has v_j^r >= the largest kept, which must exceed min + 2 B) exactly as the full scan does, and takes the first
 * least of them: the full scan's station, its values' very bits.  Where more than WARM_KEEP are candidates (the beam
 * has turned or bent too far since the reference, or lies flat along the plane) the full scan runs and becomes the
 * new reference.
 */
#include <float.h>

#include "nearest_line.h"

#define WARM_KEEP 16 /* a warm scan evaluates at most this many stations, else the full scan runs */

/* The full scan's least values at a reference state of a plane obstacle: the WARM_KEEP + 1 least, ascending. */
typedef struct {
    unsigned long long uid; /* the model unpacking's (fb_model.uid; 0: none held) */
    const double *st_phi;
    int M, n, na;
    double c[2];  /* the plane's outward normal in the body frame */
    double q[64]; /* [q, p] */
    int kept;     /* stations kept: min(M, WARM_KEEP + 1) */
    int sj[WARM_KEEP + 1];
    double sv[WARM_KEEP + 1]; /* their values, ascending: every station not kept has v_j^r >= sv[WARM_KEEP] */
    unsigned long long max_uid; /* the unpacking whose station maxima amax holds (0: none) */
    double amax[64];            /* max_j |Psi_jk| per bending mode, then max_j |Phi_a,jk| per axial one */
} plane_ref;

static FB_THREAD_LOCAL plane_ref refs[FB_MAX_OBSTACLES];
static FB_THREAD_LOCAL int cold;           /* fb_nearest_warm(0): every scan full, no reference kept */
static FB_THREAD_LOCAL long full_scans; /* the plane's full scans so far in this thread */

void fb_nearest_warm(int on) { cold = !on; }

long fb_nearest_full_scans(void) { return full_scans; }

static int sphere_station(line_t *ln, const double c[2]) {
    const fb_model *m = ln->m;
    int M = ln->M, best = 0;
    double best_val = INFINITY;
    /* outwards from the station abreast of the centre: a station whose axial distance alone reaches the best
     * squared distance so far cannot be nearer, nor can any beyond it (r_h + x_j + s_j is monotonic in j: the
     * axial strain is far above -1) */
    int j0 = (int)lround((c[0] - ln->rh) / ln->dx);
    j0 = j0 < 0 ? 0 : (j0 > M - 1 ? M - 1 : j0);
    int lo_open = 1, hi_open = 1;
    for (int k = 0; lo_open || hi_open; k++) {
        for (int side = 0; side < 2; side++) {
            int j = side ? j0 + k : j0 - k;
            if ((side ? !hi_open : !lo_open) || (k == 0 && side == 1)) continue;
            if (j < 0 || j > M - 1) {
                if (side) hi_open = 0;
                else lo_open = 0;
                continue;
            }
            double slope, ex = ln->rh + m->st_x[j] + station_s(ln, j, &slope) - c[0];
            if (ex * ex >= best_val) {
                if (side) hi_open = 0;
                else lo_open = 0;
                continue;
            }
            double ey = station_w(ln, j) - c[1], val = ex * ex + ey * ey;
            if (val < best_val || (val == best_val && j < best)) best_val = val, best = j;
        }
    }
    return best;
}

/* v_j = c . rho_j of station j (without u_x), the full and warm scans' one expression. */
static double plane_value(line_t *ln, const double c[2], int j) {
    double slope;
    return c[0] * (ln->rh + ln->m->st_x[j] + station_s(ln, j, &slope)) + c[1] * station_w(ln, j);
}

/* Station j of value val into r's least values (ascending; the largest dropped when WARM_KEEP + 1 are kept). */
static void keep_least(plane_ref *r, double val, int j) {
    int k = r->kept;
    if (k == WARM_KEEP + 1) {
        if (!(val < r->sv[WARM_KEEP])) return;
        k = WARM_KEEP;
    } else {
        r->kept++;
    }
    for (; k > 0 && val < r->sv[k - 1]; k--) r->sv[k] = r->sv[k - 1], r->sj[k] = r->sj[k - 1];
    r->sv[k] = val, r->sj[k] = j;
}

/* The first station of least v_j over all of them; with r, their least values kept there as the new reference. */
static int plane_full(line_t *ln, const double c[2], plane_ref *r) {
    int best = 0, finite = 1;
    double best_val = INFINITY;
    full_scans++;
    if (r) r->uid = 0, r->kept = 0;
    for (int j = 0; j < ln->M; j++) {
        double val = plane_value(ln, c, j);
        if (val < best_val) best_val = val, best = j;
        if (r) keep_least(r, val, j), finite &= isfinite(val) != 0;
    }
    if (r && finite) {
        const fb_model *m = ln->m;
        r->uid = m->uid, r->st_phi = m->st_phi, r->M = ln->M, r->n = ln->n, r->na = m->na;
        r->c[0] = c[0], r->c[1] = c[1];
        for (int k = 0; k < ln->n + m->na; k++) r->q[k] = ln->q[k];
    }
    return best;
}

/* The largest |Psi_jk| and |Phi_a,jk| over the stations j, per mode k, into r->amax (once per model unpacking). */
static void station_maxima(const line_t *ln, plane_ref *r) {
    const fb_model *m = ln->m;
    int n = ln->n, na = m->na;
    for (int k = 0; k < n + na; k++) r->amax[k] = 0.0;
    for (int j = 0; j < ln->M; j++) {
        for (int k = 0; k < n; k++) r->amax[k] = fmax(r->amax[k], fabs(m->st_phi[(size_t)j * n + k]));
        for (int k = 0; k < na; k++) r->amax[n + k] = fmax(r->amax[n + k], fabs(m->st_aphi[(size_t)j * na + k]));
    }
    r->max_uid = r->uid;
}

/* B (the header's) for the state of ln and the normal c against the reference r. */
static double plane_drift(const line_t *ln, const double c[2], const plane_ref *r) {
    const fb_model *m = ln->m;
    int n = ln->n, na = m->na;
    double W = 0.0, Wr = 0.0, dW = 0.0, S = 0.0, Sr = 0.0, dS = 0.0;
    for (int k = 0; k < n; k++) {
        double a = r->amax[k];
        W += a * fabs(ln->q[k]), Wr += a * fabs(r->q[k]), dW += a * fabs(ln->q[k] - r->q[k]);
    }
    for (int k = n; k < n + na; k++) {
        double a = r->amax[k];
        S += a * fabs(ln->q[k]), Sr += a * fabs(r->q[k]), dS += a * fabs(ln->q[k] - r->q[k]);
    }
    double X = fabs(ln->rh) + fmax(fabs(m->st_x[0]), fabs(m->st_x[ln->M - 1])) + fmax(S, Sr), Wm = fmax(W, Wr);
    double D = fabs(c[0] - r->c[0]) * X + fabs(r->c[0]) * dS + fabs(c[1] - r->c[1]) * Wm + fabs(r->c[1]) * dW;
    double cx = fmax(fabs(c[0]), fabs(r->c[0])), cy = fmax(fabs(c[1]), fabs(r->c[1]));
    double E = 8.0 * (n + na + 4) * (0.5 * DBL_EPSILON) * (cx * X + cy * Wm);
    return 2.0 * (D + 2.0 * E);
}

/* The full scan's station from the candidates of the reference r (the header's), or -1 where more than WARM_KEEP
 * are candidates or the bound is not finite. */
static int plane_warm(line_t *ln, const double c[2], plane_ref *r) {
    if (r->max_uid != r->uid) station_maxima(ln, r);
    double B = plane_drift(ln, c, r), top = r->sv[0] + 2.0 * B, best_val = INFINITY;
    if (!(top < INFINITY) || (r->kept == WARM_KEEP + 1 && r->sv[WARM_KEEP] <= top)) return -1;
    int best = -1;
    for (int i = 0; i < r->kept && r->sv[i] <= top; i++) {
        int j = r->sj[i];
        double val = plane_value(ln, c, j);
        if (val < best_val || (val == best_val && j < best)) best_val = val, best = j;
    }
    return best;
}

int fb_nearest_station(line_t *ln, int sphere, const double c[2], int obstacle) {
    if (sphere) return sphere_station(ln, c);
    const fb_model *m = ln->m;
    plane_ref *r = NULL;
    if (!cold && m->uid && obstacle >= 0 && obstacle < FB_MAX_OBSTACLES && ln->n + m->na <= 64)
        r = &refs[obstacle];
    if (r && r->uid == m->uid && r->st_phi == m->st_phi && r->M == ln->M && r->n == ln->n && r->na == m->na) {
        int best = plane_warm(ln, c, r);
        if (best >= 0) return best;
    }
    return plane_full(ln, c, r);
}
