/* Small dense linear algebra with a fixed order of operations: see linalg.h. */
#include "linalg.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

void fb_la_matmul(const double *A, const double *B, double *C, int m, int k, int n) {
    for (int i = 0; i < m; i++)
        for (int j = 0; j < n; j++) {
            double acc = 0.0;
            for (int l = 0; l < k; l++) acc += A[(size_t)i * k + l] * B[(size_t)l * n + j];
            C[(size_t)i * n + j] = acc;
        }
}

void fb_la_gram(const double *A, const double *w, const double *B, double *C, int m, int ka, int kb) {
    for (int a = 0; a < ka; a++)
        for (int b = 0; b < kb; b++) C[(size_t)a * kb + b] = 0.0;
    for (int r = 0; r < m; r++) {
        const double *Ar = A + (size_t)r * ka, *Br = B + (size_t)r * kb;
        for (int a = 0; a < ka; a++) {
            double wa = w[r] * Ar[a];
            double *Ca = C + (size_t)a * kb;
            for (int b = 0; b < kb; b++) Ca[b] += wa * Br[b];
        }
    }
}

int fb_la_solve(double *A, double *B, int n, int nrhs) {
    for (int k = 0; k < n; k++) {
        int piv = k;
        double best = fabs(A[(size_t)k * n + k]);
        for (int i = k + 1; i < n; i++) {
            double v = fabs(A[(size_t)i * n + k]);
            if (v > best) {
                best = v;
                piv = i;
            }
        }
        if (!(best > 0.0)) return -1;
        if (piv != k) {
            for (int j = 0; j < n; j++) {
                double t = A[(size_t)k * n + j];
                A[(size_t)k * n + j] = A[(size_t)piv * n + j];
                A[(size_t)piv * n + j] = t;
            }
            for (int j = 0; j < nrhs; j++) {
                double t = B[(size_t)k * nrhs + j];
                B[(size_t)k * nrhs + j] = B[(size_t)piv * nrhs + j];
                B[(size_t)piv * nrhs + j] = t;
            }
        }
        double pivot = A[(size_t)k * n + k];
        for (int i = k + 1; i < n; i++) {
            double f = A[(size_t)i * n + k] / pivot;
            if (f == 0.0) continue;
            for (int j = k + 1; j < n; j++) A[(size_t)i * n + j] -= f * A[(size_t)k * n + j];
            for (int j = 0; j < nrhs; j++) B[(size_t)i * nrhs + j] -= f * B[(size_t)k * nrhs + j];
        }
    }
    for (int k = n - 1; k >= 0; k--)
        for (int j = 0; j < nrhs; j++) {
            double acc = B[(size_t)k * nrhs + j];
            for (int l = k + 1; l < n; l++) acc -= A[(size_t)k * n + l] * B[(size_t)l * nrhs + j];
            B[(size_t)k * nrhs + j] = acc / A[(size_t)k * n + k];
        }
    return 0;
}

int fb_la_cholesky(double *A, int n) {
    for (int j = 0; j < n; j++) {
        double d = A[(size_t)j * n + j];
        for (int l = 0; l < j; l++) d -= A[(size_t)j * n + l] * A[(size_t)j * n + l];
        if (!(d > 0.0)) return -1;
        double ljj = sqrt(d);
        A[(size_t)j * n + j] = ljj;
        for (int i = j + 1; i < n; i++) {
            double s = A[(size_t)i * n + j];
            for (int l = 0; l < j; l++) s -= A[(size_t)i * n + l] * A[(size_t)j * n + l];
            A[(size_t)i * n + j] = s / ljj;
        }
        for (int i = 0; i < j; i++) A[(size_t)i * n + j] = 0.0;
    }
    return 0;
}

/* One Jacobi rotation zeroing A[p][q] (Golub & Van Loan, Matrix Computations, 4th ed., Alg. 8.5.1 and 8.5.2). */
static void jacobi_rotate(double *A, double *V, int n, int p, int q) {
    double apq = A[(size_t)p * n + q];
    double tau = (A[(size_t)q * n + q] - A[(size_t)p * n + p]) / (2.0 * apq);
    double t = (tau >= 0.0 ? 1.0 : -1.0) / (fabs(tau) + sqrt(1.0 + tau * tau));
    double c = 1.0 / sqrt(1.0 + t * t), s = t * c;
    for (int k = 0; k < n; k++) { /* A <- A J (columns p, q) */
        double akp = A[(size_t)k * n + p], akq = A[(size_t)k * n + q];
        A[(size_t)k * n + p] = c * akp - s * akq;
        A[(size_t)k * n + q] = s * akp + c * akq;
    }
    for (int k = 0; k < n; k++) { /* A <- J^T A (rows p, q) */
        double apk = A[(size_t)p * n + k], aqk = A[(size_t)q * n + k];
        A[(size_t)p * n + k] = c * apk - s * aqk;
        A[(size_t)q * n + k] = s * apk + c * aqk;
    }
    A[(size_t)p * n + q] = A[(size_t)q * n + p] = 0.0;
    for (int k = 0; k < n; k++) { /* V <- V J */
        double vkp = V[(size_t)k * n + p], vkq = V[(size_t)k * n + q];
        V[(size_t)k * n + p] = c * vkp - s * vkq;
        V[(size_t)k * n + q] = s * vkp + c * vkq;
    }
}

int fb_la_eigh(double *A, int n, double *w, double *V) {
    memset(V, 0, sizeof(double) * (size_t)n * n);
    for (int i = 0; i < n; i++) V[(size_t)i * n + i] = 1.0;
    int sweeps = -1;
    for (int sweep = 0; sweep < 100; sweep++) {
        double off = 0.0, diag = 0.0;
        for (int i = 0; i < n; i++) {
            diag += A[(size_t)i * n + i] * A[(size_t)i * n + i];
            for (int j = i + 1; j < n; j++) off += A[(size_t)i * n + j] * A[(size_t)i * n + j];
        }
        if (off <= 1e-32 * diag || off == 0.0) {
            sweeps = sweep;
            break;
        }
        for (int p = 0; p < n - 1; p++)
            for (int q = p + 1; q < n; q++) {
                double apq = A[(size_t)p * n + q];
                if (apq == 0.0) continue;
                /* negligible against both diagonal entries: set to zero (the classical threshold test) */
                double app = fabs(A[(size_t)p * n + p]), aqq = fabs(A[(size_t)q * n + q]);
                if (sweep > 3 && app + 1e2 * fabs(apq) == app && aqq + 1e2 * fabs(apq) == aqq) {
                    A[(size_t)p * n + q] = A[(size_t)q * n + p] = 0.0;
                    continue;
                }
                jacobi_rotate(A, V, n, p, q);
            }
    }
    /* sort ascending (stable selection sort: n is small), carrying the columns of V */
    for (int i = 0; i < n; i++) w[i] = A[(size_t)i * n + i];
    for (int i = 0; i < n; i++) {
        int best = i;
        for (int j = i + 1; j < n; j++)
            if (w[j] < w[best]) best = j;
        if (best != i) {
            double t = w[i];
            w[i] = w[best];
            w[best] = t;
            for (int k = 0; k < n; k++) {
                double v = V[(size_t)k * n + i];
                V[(size_t)k * n + i] = V[(size_t)k * n + best];
                V[(size_t)k * n + best] = v;
            }
        }
    }
    for (int j = 0; j < n; j++) { /* sign: the largest-magnitude component positive */
        int big = 0;
        for (int k = 1; k < n; k++)
            if (fabs(V[(size_t)k * n + j]) > fabs(V[(size_t)big * n + j])) big = k;
        if (V[(size_t)big * n + j] < 0.0)
            for (int k = 0; k < n; k++) V[(size_t)k * n + j] = -V[(size_t)k * n + j];
    }
    return sweeps;
}
